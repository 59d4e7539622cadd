"""The radiosity control variate at Russian roulette (glshade.radiosity.control): unbiased
against the furnace's closed form at every albedo, with far less spread between pixels
where roulette's noise is most of it (albedo near 1), and its values of the right size
(the furnace's indirect irradiance, rho E / (1 - rho), in closed form)."""

import numpy as np
import pytest

from glshade.errors import OptionError
from glshade.pathtrace import TraceScene, trace
from glshade.radiosity.control import radiosity_control

from .test_sweeps import INSIDE, closed_form, furnace

pytestmark = [pytest.mark.gl]


@pytest.mark.parametrize("rho, sampler", [(0.5, "pcg"), (0.8, "sobol"), (0.95, "pcg"),
                                          (0.99, "sobol")])
def test_the_control_is_unbiased_and_quiets_roulette(gl_context, rho, sampler):
    """The same furnace with and without the control: both meet E / (1 - rho) within their
    error bars, and with it the pixels spread less (measured 3x less at 0.8, 10x at 0.95:
    a killed path no longer loses all it would have brought)."""
    want = closed_form(rho, None)
    scene = furnace(rho)
    values = radiosity_control(scene, context=gl_context)
    spread = {}
    for control in (False, True):
        r = trace(scene, INSIDE, (32, 32), spp=16, seed=3, context=gl_context,
                  progress=False, sampler=sampler, control=values if control else None)
        pixels = r.image.mean(-1).ravel()
        bar = pixels.std(ddof=1) / np.sqrt(pixels.size)
        assert abs(pixels.mean() - want) <= 5 * bar + 4e-7 * want, (control, pixels.mean())
        spread[control] = pixels.std()
    if rho >= 0.8:
        assert spread[True] < 0.5 * spread[False], spread


def test_the_control_values_are_under_the_indirect_irradiance(gl_context):
    """In a furnace of emission 1 every surface's direct irradiance is 1 and its total
    1 / (1 - rho): the indirect rho / (1 - rho). The two solves find it from under (the
    progressive solver's first shots, one a patch, carry some light that has bounced:
    measured 67% of it at rho = 0.5, 85% at 0.8) -- never over, which would make roulette
    noisier than without."""
    for rho, least in ((0.5, 0.6), (0.8, 0.8)):
        c = radiosity_control(furnace(rho), context=gl_context)
        assert c.shape == (1, 3)
        assert least * rho / (1 - rho) <= c.min() <= c.max() <= 1.01 * rho / (1 - rho), c


def test_bad_control_values_are_named(gl_context):
    scene = furnace(0.5)
    for bad in (np.ones((2, 3)), -np.ones((1, 3)), np.ones(3), [[np.nan, 0, 0]]):
        with pytest.raises(OptionError, match="control must be finite values >= 0"):
            trace(scene, INSIDE, (8, 8), spp=1, context=gl_context, progress=False,
                  control=bad)
    with pytest.raises(OptionError, match="control must be finite values >= 0"):
        trace(TraceScene.from_scene(scene), INSIDE, (8, 8), spp=1, context=gl_context,
              progress=False, control=np.zeros((1, 2)))
