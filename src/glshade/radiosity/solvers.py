"""The radiosity equation in its discrete form, ``B_i = E_i + rho_i sum_j F_ij B_j``,
solved two ways:

* progressive refinement (Cohen, Chen, Wallace and Greenberg 1988): the patch with the
  most unshot energy ``dB_i A_i`` shoots it to every patch through one row of form
  factors (``dB_j += rho_j dB_i F_ij A_i / A_j``, by reciprocity), until the unshot
  fraction of the emitted energy is below ``until``. Only rows of shooters are computed;
  an *ambient* term estimates what is still unshot for display;
* Gauss-Seidel gathering over the full matrix, for small scenes.

Both return a :class:`Solution` with the radiosity per patch and the energy history.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field

import numpy as np

from ..errors import InputError
from .formfactors import FormFactors
from .patches import DISPLAY_CREASE
from .problem import PatchScene

__all__ = ["Solution", "progressive", "gauss_seidel"]


def _energy(values: np.ndarray, areas: np.ndarray) -> float:
    """Power of per-patch RGB radiosities: sum over patches and channels of B A."""
    return float((values.sum(axis=1) * areas).sum())


@dataclass
class Solution:
    """Radiosity ``B`` (P, 3) per patch; ``unshot`` (P, 3) what progressive refinement did
    not yet shoot (zeros for gathering); ``history`` rows of (seconds, step, unshot
    fraction) -- a step is a shot or a sweep.

    Parameters
    ----------
    problem : PatchScene
        The patches solved.
    radiosity : ndarray
        ``(P, 3)`` radiosity B of each patch.
    unshot : ndarray
        ``(P, 3)`` what progressive refinement did not yet shoot (zeros for gathering).
    method : str
        How it was solved.
    history : list
        Rows of (seconds, step, unshot fraction); a step is a shot or a sweep.
    hemicubes : int
        Hemicubes drawn.
    se : ndarray or None
        ``(P, 3)`` each patch's standard error (Monte Carlo), or None.
    converged : bool
        Whether it reached its stop rule (else it stopped at its cap).
    """

    problem: PatchScene
    radiosity: np.ndarray
    unshot: np.ndarray
    method: str
    history: list = field(default_factory=list)
    hemicubes: int = 0
    #: (P, 3) each patch's standard error, for a Monte Carlo solution (None otherwise)
    se: np.ndarray | None = field(default=None, repr=False)
    #: whether the solver met its goal (False: it stopped at a cap; see ``history``)
    converged: bool = True

    def __repr__(self) -> str:
        steps = self.history[-1][1] if self.history else 0
        return (f"<Solution {self.method}: {self.problem.n_patches:,} patches, {steps:,} "
                f"steps, unshot {self.unshot_fraction:.2%}>")

    def _repr_html_(self) -> str:
        """In a notebook: the solution drawn in the radiosity mode, and its figures."""
        from ..display import facts_html, picture

        facts = [f"{self.hemicubes:,} hemicubes",
                 f"radiosity {float(self.radiosity.min()):.4g} .. "
                 f"{float(self.radiosity.max()):.4g}"]
        # (a room is closed: from the view that shows most, inside it where need be -- the
        # emitters and the walls they light, judged by the models each patch came from)
        p = self.problem
        emits = np.zeros(len(p.names), bool)
        emits[p.model[p.emission.sum(1) > 0]] = True
        polygons = (p.model[p.patches.triangle_patch], emits)
        return facts_html(repr(self), facts, picture(self.scene(), mode="radiosity",
                                                     choose=True, polygons=polygons))

    @property
    def unshot_fraction(self) -> float:
        p = self.problem
        return _energy(self.unshot, p.patches.areas) / _energy(p.emission, p.patches.areas)

    @property
    def ambient(self) -> np.ndarray:
        """The ambient term (RGB): the unshot energy spread evenly over the scene, with the
        scene's mean reflectance's infinite interreflection ``1 / (1 - rho_avg)``."""
        p = self.problem
        a = p.patches.areas
        rho_avg = (p.rho * a[:, None]).sum(0) / a.sum()
        return (self.unshot * a[:, None]).sum(0) / a.sum() / np.maximum(1 - rho_avg, 1e-9)

    def displayed(self, ambient: bool = True) -> np.ndarray:
        """Per-patch radiosity to show: plus ``rho * ambient`` where energy is unshot.

        Parameters
        ----------
        ambient : bool
            Add ``rho x`` the unshot energy's ambient estimate.
        """
        if not ambient:
            return self.radiosity
        return self.radiosity + self.problem.rho * self.ambient

    def vertex_colors(self, exposure: float = 1.0, ambient: bool = True,
                      crease: float = DISPLAY_CREASE) -> np.ndarray:
        """(V, 3) radiosities at the display mesh's vertices, times ``exposure``.

        Parameters
        ----------
        exposure : float
            The factor on the radiosity.
        ambient : bool
            Add the ambient estimate of the unshot energy.
        crease : float
            Degrees past which the display mesh keeps an edge sharp.
        """
        return self.problem.patches.vertex_values(self.displayed(ambient), crease) * exposure

    def scene(self, exposure: float | None = None, ambient: bool = True, background=(0, 0, 0),
              crease: float = DISPLAY_CREASE):
        """A Scene showing the solution in the ``radiosity`` mode: one mesh of patches with
        its vertex radiosities, averaged only across bends gentler than ``crease`` degrees
        (so a box stays a box). ``exposure`` scales them for display (default: the
        brightest non-emitting patch maps to 1).

        Parameters
        ----------
        exposure : float or None
            The factor on the radiosity (None: :meth:`auto_exposure`).
        ambient : bool
            Add the ambient estimate of the unshot energy.
        background : tuple
            The scene's background colour.
        crease : float
            Degrees past which the display mesh keeps an edge sharp.
        """
        from ..scene import Scene

        from ..errors import SceneError
        from ..scene.material import MAX_SHADING_VALUE

        if exposure is None:
            exposure = self.auto_exposure(ambient)
        colors = self.vertex_colors(exposure, ambient, crease)
        peak = float(np.max(colors, initial=0.0))
        if not np.isfinite(peak) or peak > MAX_SHADING_VALUE:
            # (said of the exposure, the value given: the colours are made from it)
            brightest = float(np.max(self.displayed(ambient), initial=0.0))
            raise SceneError(f"exposure {exposure:g} makes the brightest patch {peak:g}; a "
                             f"colour may be at most {MAX_SHADING_VALUE:g} (shading runs in "
                             f"32-bit floats): give an exposure up to "
                             f"{MAX_SHADING_VALUE / max(brightest, 1e-300):.3g}")
        s = Scene(background=background)
        s.add(self.problem.patches.mesh(crease), vertex_colors=colors, name="radiosity")
        return s

    def surface_means(self) -> tuple[tuple, np.ndarray]:
        """The models' names and each one's area-mean radiosity ``(M, 3)``: the per-surface
        numbers a path tracer's :func:`~glshade.pathtrace.surfaces.surface_radiosity`
        estimates too."""
        p = self.problem
        a = p.patches.areas
        models = len(p.names)
        area = np.bincount(p.model, weights=a, minlength=models)
        means = np.stack([np.bincount(p.model, weights=self.radiosity[:, c] * a,
                                      minlength=models) for c in range(3)], 1)
        return tuple(p.names), means / np.maximum(area, 1e-300)[:, None]

    def auto_exposure(self, ambient: bool = True) -> float:
        """The exposure that shows the brightest lit (non-emitting) patch as white.

        Parameters
        ----------
        ambient : bool
            Count the ambient estimate of the unshot energy.
        """
        b = self.displayed(ambient)
        lit = self.problem.emission.sum(1) == 0
        peak = float(b[lit].max()) if lit.any() else float(b.max())
        return 1.0 / peak if peak > 0 else 1.0


def progressive(ff: FormFactors, until: float = 0.01, max_shots: int | None = None,
                progress=None, on_shot=None) -> Solution:
    """Shoot until the unshot fraction of the emitted energy is below ``until`` (or
    ``max_shots``). ``on_shot(solution, shot)`` is called after each shot (animation).

    Parameters
    ----------
    ff : FormFactors
        The form factors (rows drawn as shooters need them).
    until : float
        Stop when the unshot fraction of the emitted energy is below this.
    max_shots : int or None
        The most shots (None: as many as ``until`` takes).
    progress : bool, tqdm-like or None
        The progress bar.
    on_shot : callable or None
        ``on_shot(solution, shots)`` after each shot: the solution so far (an animation's
        frames).
    """
    if not 0 <= until < 1:
        raise InputError(f"until must be an unshot fraction in [0, 1), got {until!r}")
    p = ff.problem
    areas = p.patches.areas
    emitted = _energy(p.emission, areas)
    b = p.emission.copy()
    db = p.emission.copy()
    sol = Solution(p, b, db, "progressive refinement")
    start = time.perf_counter()
    sol.history.append((0.0, 0, 1.0))
    power = db.sum(axis=1) * areas
    shots = 0
    while power.sum() / emitted > until and (max_shots is None or shots < max_shots):
        i = int(np.argmax(power))
        row = ff.row(i)  # F[i, j]
        gain = p.rho * (row * (areas[i] / areas))[:, None] * db[i]  # (P, 3)
        b += gain
        db += gain
        db[i] = 0.0
        power = db.sum(axis=1) * areas
        shots += 1
        sol.history.append((time.perf_counter() - start, shots, float(power.sum() / emitted)))
        if progress:
            progress.update(1, f"unshot {sol.history[-1][2]:.2%} (goal {until:.2%})")
        if on_shot:
            on_shot(sol, shots)
    sol.hemicubes = ff.hemicubes_drawn
    sol.converged = power.sum() / emitted <= until
    return sol


def gauss_seidel(ff: FormFactors, iterations: int | None = None, tol: float = 1e-4,
                 progress=None) -> Solution:
    """Gather with the full matrix: sweep ``B_i = E_i + rho_i sum_j F_ij B_j`` in place
    (each row uses the values already updated) until no radiosity changes by more than
    ``tol`` of the largest, or for ``iterations`` sweeps.

    Parameters
    ----------
    ff : FormFactors
        The form factors (the whole matrix is drawn).
    iterations : int or None
        Sweeps (None: until the change is below ``tol``).
    tol : float
        The relative change a sweep must fall below to stop.
    progress : bool, tqdm-like or None
        The progress bar.
    """
    p = ff.problem
    start = time.perf_counter()
    areas = p.patches.areas
    # what patch i receives is what each patch j sends it, by j's own row (the rows are the
    # shooters': their energy leaves from their uncovered points), so i gathers through
    # F_ji A_j / A_i -- equal to F_ij where reciprocity holds, right where it cannot (a patch
    # partly under a block sends from its open part, but its whole area counts)
    f = ff.matrix(progress).T * areas[None, :] / areas[:, None]
    e, rho = p.emission, p.rho
    b = e.copy()
    sol = Solution(p, b, np.zeros_like(b), "Gauss-Seidel gathering")
    emitted = _energy(e, areas)
    sweeps = 0
    while iterations is None or sweeps < iterations:
        change = 0.0
        for i in range(len(b)):  # (sequential by nature: row i uses rows < i of this sweep)
            new = e[i] + rho[i] * (f[i] @ b)
            change = max(change, float(np.abs(new - b[i]).max()))
            b[i] = new
        sweeps += 1
        # the energy still to arrive, estimated from the last change
        residual = change * areas.sum() * 3 / max(emitted, 1e-300)
        sol.history.append((time.perf_counter() - start, sweeps, residual))
        if iterations is None and change <= tol * max(float(b.max()), 1e-300):
            break
        if iterations is None and sweeps >= MAX_SWEEPS:
            sol.converged = False  # (said by the caller: never success at a cap)
            break
    sol.hemicubes = ff.hemicubes_drawn
    return sol


#: Gauss-Seidel's cap on sweeps when no count is given (a solution that has not settled
#: by then is reported as not converged)
MAX_SWEEPS = 10_000


def check_converges(problem) -> None:
    """Refuse, before any work, a closed room that loses no light: every patch reflecting
    all of one colour channel (reflectance 1) in a closed surface makes the spectral
    radius of rho F one, so shooting or gathering never settles."""
    rho = np.asarray(problem.rho)
    lossless = [bool((rho[:, c] >= 1.0 - 1e-12).all()) for c in range(3)]
    if not any(lossless):
        return
    if not problem.closed:
        return
    names = ", ".join(c for c, ok in zip(("red", "green", "blue"), lossless) if ok)
    raise InputError(f"every surface reflects all {names} light (reflectance 1) and the "
                     "scene is closed: the light never dies out (the spectral radius of "
                     "rho F is 1), so no solver can converge; give some surface a "
                     "reflectance below 1")
