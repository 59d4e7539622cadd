"""A CSG transform's stretch is held to the sizes a solid may have (1e-15 to 1e15, as its
leaves' sizes and translations are): ``solid:sphere(1).scale(1e150)`` ended in an
OverflowError traceback from ``glshade info`` (its volume cubed the scale). Swept over the
scale's exponent: a scale in range gives the sphere's closed-form volume, one out of range
is refused in one line naming it."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from glshade import solids
from glshade.errors import GeometryError
from tests.conftest import glshade


@settings(max_examples=40, deadline=None)
@given(exponent=st.floats(-40.0, 320.0), axis=st.integers(0, 3))
def test_a_scale_in_range_keeps_the_volume_one_out_of_range_is_refused(exponent, axis):
    factor = np.ones(3)
    factor[:3 if axis == 3 else axis:axis + 1 if axis < 3 else 3] = 10.0 ** min(exponent, 300)
    inside = (factor > 1e-15).all() and (factor < 1e15).all()
    if not inside:
        with pytest.raises(GeometryError):  # (its stretch, or a shape it flattens)
            solids.Sphere(1.0).scaled(factor)
        return
    volume, error = solids.Sphere(1.0).scaled(factor).volume()
    exact = 4 / 3 * np.pi * np.prod(factor)  # (the ellipsoid's closed form)
    assert np.isfinite(volume) and abs(volume - exact) <= 5 * error + 1e-12 * exact


def test_the_command_line_says_it_in_one_line():
    done = glshade("info", "solid:sphere(1).scale(1e150)")
    assert done.returncode == 2 and "Traceback" not in done.stderr
    (line,) = done.stderr.strip().splitlines()
    assert "CSG transform scales by (1e+150, 1e+150, 1e+150)" in line
