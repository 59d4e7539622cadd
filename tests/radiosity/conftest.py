"""Form factors made on the suite's GL context, closed after each test."""

import pytest

from glshade.radiosity import FormFactors


@pytest.fixture
def factors(gl_context):
    made = []

    def make(problem, *args, **kwargs):
        made.append(FormFactors(problem, *args, context=gl_context, **kwargs))
        return made[-1]

    yield make
    for ff in made:
        ff.close()
