"""The tessellation's tolerance at the edge of what float64 and the sample cap hold."""

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st


@settings(max_examples=12, deadline=None)
@given(exponent=st.integers(5, 320))
def test_a_tolerance_too_fine_for_the_samples_allowed_is_named(exponent):
    """A tolerance of 1e-300 asked for 1e150 samples a side -- past int64 -- and was
    refused as "every patch collapses to a point": the tolerance is named, with the most
    samples allowed, whatever its size (a subnormal 1e-320 included)."""
    from glshade import patches
    from glshade.errors import GeometryError
    from glshade.patches import tessellate

    tolerance = 10.0 ** -exponent
    with pytest.raises(GeometryError, match=r"the tolerance .* asks for more samples a patch "
                                            r"side than the 512 allowed"):
        tessellate(patches.named("teapot"), tolerance=tolerance)
