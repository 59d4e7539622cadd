"""The tessellation's tolerance at the edge of what float64 and the sample cap hold."""

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

pytestmark = pytest.mark.filterwarnings("error")  # (numpy's words are a fault here too)


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


@settings(max_examples=10, deadline=None)
@given(exponent=st.integers(16, 323))
def test_a_patch_too_small_for_float64s_products_is_named(exponent):
    """A patch net 1e-320 across printed numpy's 'invalid value' warnings and ended as
    'every patch collapses to a point' (its points do not coincide): a span under 1e-15 is
    refused naming the patch and its span; one of 1e-14 tessellates."""
    import numpy as np

    from glshade.errors import GeometryError
    from glshade.patches import PatchSet, PatchSurface, tessellate

    grid = np.stack(np.meshgrid(np.arange(4.0), np.arange(4.0), indexing="ij"), -1)
    net = np.concatenate([grid, np.zeros((4, 4, 1))], -1)[None]
    with pytest.raises(GeometryError, match=r"patch 0: its control points span .* under the "
                                            r"least extent of 1e-15"):
        PatchSet(net * 10.0 ** -exponent)
    mesh = tessellate(PatchSurface(PatchSet(net * 1e-14), "small"), level=2).mesh
    assert mesh.n_faces > 0 and np.isfinite(mesh.vertices).all()
