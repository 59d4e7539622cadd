"""Progressive path tracing: samples added pass by pass until a sample count or a relative
error is reached, with a per-pixel variance estimate from the sums of the samples and of
their squares; a Ctrl-C keeps the image made so far."""

from __future__ import annotations

import time
from dataclasses import dataclass, field

import numpy as np

from ..errors import OptionError
from ..modes import Sampler
from ..options import COHERENT_TILE, TraceOptions
from .scene import TraceScene

__all__ = ["PathTraced", "PathTracer", "trace", "relative_error"]


def relative_error(image: np.ndarray, se: np.ndarray) -> float:
    """The stop rule's figure: the pixels' root-mean-square standard error over the
    image's mean, both averaged over channels (``inf`` for a black image).

    Parameters
    ----------
    image : ndarray
        ``(H, W, 3)`` the picture.
    se : ndarray
        ``(H, W, 3)`` each pixel's standard error.
    """
    mean = float(image.mean())
    return float(np.sqrt((se ** 2).mean())) / mean if mean > 0 else float("inf")


@dataclass
class PathTraced:
    """A path-traced picture, its per-pixel errors and how it was made.

    Parameters
    ----------
    image : ndarray
        ``(H, W, 3)`` float64 in radiosity units (pi x radiance).
    se : ndarray
        ``(H, W, 3)`` each pixel's standard error, figured as ``se_from`` says.
    samples : int
        Samples a pixel (their mean, rounded, where adaptive sampling made them differ).
    emitting : ndarray
        ``(H, W)`` the fraction of a pixel's first hits on an emitter.
    seconds : float
        Time spent tracing (a pilot's included).
    interrupted : bool
        Whether a Ctrl-C ended it early.
    method : str
        How it was made, in words.
    history : list
        ``(seconds, samples, relative error)`` after each step of the run.
    coverage : ndarray or None
        ``(H, W)`` the fraction of a pixel's camera rays that hit the scene.
    near_limit : int
        Bounces that came near the driver's loop limit (0: none could have been cut short).
    counts : ndarray or None
        ``(H, W)`` the samples each pixel drew.
    se_from : str
        How ``se`` was figured. ``"spread"``: the samples' spread over sqrt(n), right for
        independent samples (``sampler="pcg"``) but far too high for Sobol points, whose
        error falls faster (the Cornell box + sphere at 256 samples: 13.8% where the error
        against a long render is 3.1%). ``"halves"`` (Sobol points): the difference
        between the mean of the pixel's first samples -- up to a mark near half its count
        (a power of two, or a step of adaptive sampling) -- and of the rest, each a
        well-stratified set: 3.5% there, a little high (1.1-1.3x at 64 to 1,024 samples),
        one degree of freedom a pixel (noisy pixel by pixel, right over the picture).
        Sobol points fall back to the spread where no mark serves (one sample a pixel, or
        counts given to :meth:`PathTracer.add` in one step).
    """

    image: np.ndarray
    se: np.ndarray
    samples: int
    emitting: np.ndarray
    seconds: float
    interrupted: bool = False
    method: str = "GPU path tracing"
    history: list = field(default_factory=list)
    coverage: np.ndarray | None = field(default=None, repr=False)
    near_limit: int = 0
    counts: np.ndarray | None = field(default=None, repr=False)
    se_from: str = "spread"

    @property
    def adaptive(self) -> bool:
        """Whether pixels drew different numbers of samples (``counts``; ``samples`` is
        then their mean, rounded)."""
        return self.counts is not None and bool((self.counts != self.counts.flat[0]).any())

    @property
    def relative_error(self) -> float:
        return relative_error(self.image, self.se)

    def __repr__(self) -> str:
        h, w = self.image.shape[:2]
        c = self.counts
        spread = (f" (adaptive, {int(c.min()):,} to {int(c.max()):,})"
                  if c is not None and self.adaptive else "")
        return (f"<PathTraced {w}x{h}, {self.samples:,} samples a pixel{spread}, relative error "
                f"{self.relative_error:.2%}, {self.seconds:.1f} s>")

    def auto_exposure(self) -> float:
        """1 / the brightest lit surface (the 99.5th percentile of the pixels that see no
        emitter), as radiosity's display does."""
        lit = self.image[self.emitting < 0.5]
        peak = float(np.percentile(lit.max(-1), 99.5)) if lit.size else float(self.image.max())
        return 1.0 / peak if peak > 0 else 1.0

    def rgba8(self, exposure: float | None = None, srgb: bool = False) -> np.ndarray:
        """(H, W, 4) uint8 for display: the image times ``exposure`` (default
        :meth:`auto_exposure`), clipped, sRGB-encoded if asked.

        Parameters
        ----------
        exposure : float or None
            The factor on the image (None: :meth:`auto_exposure`).
        srgb : bool
            Encode as sRGB (else linear).
        """
        k = self.auto_exposure() if exposure is None else exposure
        linear = np.clip(self.image * k, 0, 1)
        if srgb:
            from ..cpu.lighting import encode_srgb

            linear = encode_srgb(linear)
        rgb = np.clip(linear * 255 + 0.5, 0, 255).astype(np.uint8)
        return np.dstack([rgb, np.full(rgb.shape[:2], 255, np.uint8)])

    def _repr_html_(self) -> str:
        from ..display import facts_html, picture

        return facts_html(repr(self), [f"{self.method}", f"exposure {self.auto_exposure():.4g}"],
                          picture(self.rgba8()))


#: what the pilot's seed differs from the picture's by (any other seed: independent numbers)
PILOT_SEED = 0x9E3779B9


def _moments(total: np.ndarray, square: np.ndarray):
    n = np.maximum(total[..., 3:4], 1)
    mean = total[..., :3] / n
    var = np.maximum(square[..., :3] / n - mean ** 2, 0) * n / np.maximum(n - 1, 1)
    return mean, np.sqrt(var / n)


def _by_halves(total: np.ndarray, marks: list) -> np.ndarray | None:
    """Each pixel's standard error from its first n1 samples' mean against the rest's
    (``marks``: sums read as pixels passed powers of two, their counts in A; each pixel
    takes the one nearest half its count), or None where some pixel has no mark within a
    quarter to three quarters of its count, or fewer than two samples. For independent
    halves the figure's square is the mean's variance exactly (``(m1 - m2)^2 n1 n2 /
    N^2``); Sobol points' halves are each stratified and slightly anti-correlated, so it
    errs a little high."""
    n = total[..., 3:4]
    if not marks or (n < 2).any():
        return None
    stack = np.stack(marks)  # (K, H, W, 4)
    pick = np.abs(2 * stack[..., 3:4] - n).argmin(0)  # (H, W, 1)
    first = np.take_along_axis(stack, pick[None], 0)[0]
    n1 = first[..., 3:4]
    if ((4 * n1 < n) | (4 * n1 > 3 * n)).any():
        return None
    m1, m2 = first[..., :3] / n1, (total[..., :3] - first[..., :3]) / (n - n1)
    return np.abs(m1 - m2) * np.sqrt(n1 * (n - n1)) / n


class PathTracer:
    """A GPU path tracer for one scene and image size: ``add`` samples seen from a
    camera (a new camera starts over), ``result`` the picture so far. Owns its GL objects
    (and its context when it made one): use it in a ``with`` block or ``close`` it.

    Parameters
    ----------
    scene : Scene or TraceScene
        What to trace (a Scene is converted once, :meth:`TraceScene.from_scene`).
    size : (int, int)
        The picture's width and height in pixels.
    options : TraceOptions or None
        How paths are traced (None: the defaults).
    seed : int
        The random streams' seed: the same seed, the same picture.
    context : GLContext or None
        The context to trace in (None: one of its own, from ``backend``).
    backend : str
        ``"auto"``, ``"egl"`` or ``"osmesa"``, where it makes its own context.
    lights : bool
        Whether a Scene's point and directional lights are traced (emitters always are).
    camera : Camera or None
        The headlight's place for a scene with no lights or emitters.
    smooth : bool
        Shade with the renderer's vertex normals (see :class:`TraceScene`).
    control : ndarray or None
        ``(M, 3)`` a control value for each model in radiosity units, used at Russian
        roulette (:mod:`glshade.radiosity.control`).
    **changes
        TraceOptions' fields, by name, laid over ``options``.
    """

    def __init__(self, scene, size=(256, 256), options: TraceOptions | None = None, *,
                 seed: int = 0, context=None, backend: str = "auto", lights: bool = True,
                 camera=None, smooth: bool = False, control: np.ndarray | None = None,
                 **changes):
        from ..render.context import create_context
        from ..render.passes.pathtrace import GpuPathTracer

        w, h = _size(size)
        #: how paths are traced (checked here, once; the GL pass takes it whole)
        self.options = TraceOptions.of(options, **changes)
        self.trace_scene = scene if isinstance(scene, TraceScene) else \
            TraceScene.from_scene(scene, lights=lights, camera=camera, smooth=smooth)
        self.seed = int(seed)
        self._own = context is None
        self.context = create_context(backend) if context is None else context
        try:
            self.gpu = GpuPathTracer(self.context, self.trace_scene, w, h, self.options,
                                     control=control)
        except BaseException:
            self.close()
            raise
        self.camera = None
        self.seconds = 0.0
        #: Sobol points: ``(H, W, 4)`` sums read as pixels passed powers of two (the
        #: count in A), from which result() figures the error by halves
        self._marks: list[np.ndarray] = []

    @property
    def samples(self) -> int:
        """Samples every pixel has finished."""
        return self.gpu.samples

    def reset(self) -> None:
        """Forget every sample (the next :meth:`add` starts the picture over, as a new
        camera does)."""
        self.gpu.reset()
        self.seconds = 0.0
        self._marks = []

    @property
    def counts(self) -> np.ndarray:
        """``(H, W)`` int64: the samples each pixel has finished."""
        return self.gpu.counts

    def add(self, camera, samples: int = 1, *, counts: np.ndarray | None = None) -> bool:
        """Add exactly ``samples`` paths per pixel seen from ``camera`` -- or make each
        pixel's count ``counts`` ``(H, W)`` (adaptive sampling: none fewer than it has);
        whether that started the picture over (a new camera).

        Parameters
        ----------
        camera : Camera
            From where (another camera than the last call's starts the picture over).
        samples : int
            Paths to add to every pixel.
        counts : ndarray or None
            ``(H, W)`` whole numbers: each pixel's samples in all, instead.
        """
        restarted = self.camera is not None and camera != self.camera
        if restarted:
            self.reset()
        self.camera = camera
        t0 = time.perf_counter()
        if self.options.sampler is Sampler.SOBOL and counts is None:
            self._run_marking(camera, self.gpu.counts + int(samples))
        else:
            self.gpu.run(camera, int(samples), self.seed, counts=counts)
            if self.options.sampler is Sampler.SOBOL:
                # (counts that differ: a mark at the end -- trace's adaptive runs end a
                # step at each pixel's half)
                self._mark(int(self.gpu.counts.min()))
        self.context.ctx.finish()
        self.seconds += time.perf_counter() - t0
        return restarted

    def _run_marking(self, camera, target: np.ndarray) -> None:
        """Run every pixel to its ``target`` ``(H, W)`` samples, stopping where pixels
        pass each power of two to read the sums there (Sobol points' error by halves,
        :meth:`result`; a pixel's samples are the same however a run is split). Marks
        below a quarter of the fewest target never serve again and are dropped."""
        least = int(target.min())
        mark = 1 << (max(least // 4, 1) - 1).bit_length()
        while mark <= int(target.max()):
            have = self.gpu.counts
            if (have < np.minimum(target, mark)).any():  # (someone passes it here)
                self._run_to(camera, np.maximum(have, np.minimum(target, mark)))
                self._mark(least)
            mark *= 2
        self._run_to(camera, target)

    def _run_to(self, camera, counts: np.ndarray) -> None:
        """Every pixel to its ``counts`` -- where they are all one number and the pixels
        alike, as a plain count (no per-pixel table to upload: a viewer adds a sample a
        frame)."""
        n = int(counts.flat[0])
        if not self.gpu.extra.any() and (counts == n).all():
            self.gpu.run(camera, n - self.gpu.samples, self.seed)
        else:
            self.gpu.run(camera, 0, self.seed, counts=counts)

    def _mark(self, least: int) -> None:
        """Read the sums as they stand for :meth:`result`'s halves, dropping the marks that
        can serve no pixel once each has ``least`` samples (under a quarter of it)."""
        self._marks = [m for m in self._marks if 4 * m[..., 3].max() >= least]
        self._marks.append(self.gpu.sums())

    def deviations(self, camera, samples: int) -> np.ndarray:
        """``(H, W)`` each pixel's per-sample standard deviation (RMS over channels) from
        ``samples`` paths drawn from another seed and then forgotten (the tracer left empty):
        adaptive sampling's pilot, independent of the picture's own samples.

        Parameters
        ----------
        camera : Camera
            From where.
        samples : int
            The pilot's paths a pixel.
        """
        self.reset()
        t0 = time.perf_counter()
        self.gpu.run(camera, int(samples), (self.seed + PILOT_SEED) & 0xFFFFFFFF)
        total, square, _ = self.gpu.read()  # (a read waits for the passes)
        _, se = _moments(total, square)
        self.gpu.reset()
        self.camera = camera
        self.seconds += time.perf_counter() - t0  # (the pilot's time is the picture's cost)
        return np.sqrt((se ** 2).mean(-1) * int(samples))

    def allocate(self, sigma: np.ndarray, mean: int) -> np.ndarray:
        """``(H, W)`` each pixel's samples for a mean of ``mean`` by the pilot's
        deviations ``sigma`` (:meth:`deviations`; :func:`glshade.pathtrace.adaptive.
        allocate`, at most 3x the mean).

        Parameters
        ----------
        sigma : ndarray
            ``(H, W)`` the pilot's per-sample standard deviations.
        mean : int
            The mean samples a pixel.
        """
        from .adaptive import allocate

        # (pixels that share random numbers draw one count; pixels that draw their own,
        # one count a 4x2 block too: llvmpipe shades 4x2 fragments in one SIMD step, and a
        # block whose pixels finish together leaves no lane idle -- measured 5% faster on
        # the Cornell box)
        tile = self.options.coherent
        unit = tile if tile != (1, 1) else COHERENT_TILE
        return allocate(sigma, mean, tile=unit, most=min(3 * int(mean), MOST_SAMPLES))

    def result(self, interrupted: bool = False) -> PathTraced:
        """The picture so far, its errors and counts.

        Parameters
        ----------
        interrupted : bool
            Whether a Ctrl-C ended the run (said in the result).
        """
        total, square, hits = self.gpu.read()
        mean, se = _moments(total, square)
        counts = self.gpu.counts
        se_from = "spread"
        halves = _by_halves(total, self._marks)
        if halves is not None:
            se, se_from = halves, "halves"
        n = np.maximum(counts, 1)
        near = int(hits[..., 1].sum())
        if near:
            import warnings

            from ..errors import RenderWarning
            from ..render.shaders import LOOP_CAP

            warnings.warn(f"{near:,} bounces came near the GPU driver's limit of "
                          f"{LOOP_CAP:,} loop iterations a pixel and may have been cut "
                          "short (a scene whose one ray costs that much: simplify it)",
                          RenderWarning, stacklevel=3)
        return PathTraced(mean, se, int(round(float(counts.mean()))), square[..., 3] / n,
                          self.seconds, interrupted, coverage=hits[..., 0] / n,
                          near_limit=near, counts=counts.copy(), se_from=se_from)

    def close(self) -> None:
        gpu = getattr(self, "gpu", None)
        if gpu is not None:
            gpu.release()
        if self._own and getattr(self, "context", None) is not None:
            self.context.release()
            self.context = None

    def __enter__(self) -> PathTracer:
        return self

    def __exit__(self, *exc) -> None:
        self.close()


def _size(size) -> tuple[int, int]:
    """``size`` as (width, height): a number for a square, or a pair (options.check_size)."""
    from ..options import check_size

    pair = (size, size) if np.ndim(size) == 0 else tuple(size)
    if len(pair) != 2:
        raise OptionError(f"size must be a width and height in pixels, got {size!r}")
    return check_size(*pair)


def trace(scene, camera=None, size=(256, 256), *, options: TraceOptions | None = None,
          spp: int | None = None, until: float | None = None, max_samples: int = 65536,
          seed: int = 0, samples_per_pass: int | None = None, backend: str = "auto",
          context=None, lights: bool = True, progress=None,
          control: np.ndarray | None = None, adaptive: bool = False,
          **changes) -> PathTraced:
    """Path-trace ``scene`` from ``camera``: exactly ``spp`` samples a pixel, or until a
    relative error. A Ctrl-C returns the picture so far (``interrupted`` set). Seeded: the
    same call gives the same picture, however its samples are grouped into passes.

    Parameters
    ----------
    scene : Scene or TraceScene
        What to trace.
    camera : Camera or None
        Where from (None: the scene framed).
    size : (int, int)
        The picture's width and height in pixels.
    options : TraceOptions or None
        How paths are traced (None: the defaults). Its fields may be given as keywords
        instead -- ``max_depth``, ``accel``, ``sampler``, ``mis``, ``coherent``,
        ``storage``, ``kernel``, ``streams`` (see :class:`TraceOptions`) -- checked once,
        here, before a context or a scene is made.
    spp : int or None
        Samples a pixel (default 64 when ``until`` is None too).
    until : float or None
        A relative error in (0, 1) (:func:`relative_error`) to stop at, checked after each
        doubling of the samples, at most ``max_samples`` a pixel.
    max_samples : int
        The most samples a pixel draws for ``until``.
    seed : int
        The random streams' seed.
    samples_per_pass : int or None
        Samples between two looks at the progress bar and Ctrl-C (never changing the
        picture: a pixel's k-th sample is the same however they are grouped).
    backend : str
        ``"auto"``, ``"egl"`` or ``"osmesa"``, where no ``context`` is given.
    context : GLContext or None
        A context to trace in (None: one made and closed here).
    lights : bool
        Whether a Scene's point and directional lights are traced.
    progress : bool, tqdm-like or None
        The progress bar (None: one on a terminal; False: none).
    control : ndarray or None
        ``(M, 3)`` a value for each model, a control variate at Russian roulette -- each
        model's indirect irradiance from its radiosity, ``control=radiosity_control(scene)``
        (:mod:`glshade.radiosity.control`: unbiased whatever the values, less error the
        nearer they are to what a path's continuation brings).
    adaptive : bool
        ``spp`` is the mean: a pilot (:func:`glshade.pathtrace.adaptive.pilot_samples` a
        pixel, from another seed, thrown away) measures each pixel's spread, and the pixels
        draw their samples in proportion (:func:`~glshade.pathtrace.adaptive.allocate`;
        unbiased: the picture's samples are independent of the pilot's) -- less RMS error
        for the same paths, most where a few pixels hold most of it (``counts`` says how
        many each drew).
    **changes
        TraceOptions' fields, by name, laid over ``options``.

    Returns
    -------
    PathTraced
        The picture (radiosity units), its standard errors, samples and timings.
    """
    from ..options import check_whole
    from ..parallel.progress import as_progress
    from ..scene.camera import default_camera

    # (every option checked here, before a context or a scene is made)
    options = TraceOptions.of(options, **changes)
    if spp is not None and until is not None:
        raise OptionError("give spp (samples a pixel) or until (a relative error), not both")
    if until is not None and not (0 < float(until) < 1):
        raise OptionError(f"until must be a relative error in (0, 1), got {until!r}")
    if spp is None and until is None:
        spp = 64
    if spp is not None:
        spp = check_whole("spp", spp, 1)
    w, h = _size(size)
    if camera is None:  # (a Scene's bounds, or a TraceScene's)
        camera = default_camera(scene.bounds, w / h)
    per_pass = _per_pass(w * h)
    goal = int(spp) if spp is not None else int(max_samples)
    bar, owned = as_progress(progress, goal, "samples")
    if samples_per_pass is not None:
        per_pass = check_whole("samples_per_pass", samples_per_pass, 1)
    with PathTracer(scene, (w, h), options, seed=seed, context=context, backend=backend,
                    lights=lights, control=control) as tracer:
        history: list = []
        interrupted = False
        try:
            (_adaptive if adaptive else _uniform)(tracer, camera, spp, until, goal, per_pass,
                                                  bar, history)
        except KeyboardInterrupt:
            interrupted = True
        finally:
            if owned and bar is not None:
                bar.close()
        out = tracer.result(interrupted)
        out.history = history
        return out


def _uniform(tracer: PathTracer, camera, spp: int | None, until: float | None, most: int,
             per_pass: int, bar, history: list) -> None:
    """``trace``'s samples, every pixel alike: ``per_pass`` at a time up to ``spp`` -- or,
    for ``until``, doubling until the relative error is reached (at most ``most``)."""
    from ..interrupt import check

    goal = int(spp) if spp is not None else most
    step, shown = per_pass, 0
    while tracer.samples < goal:
        tracer.add(camera, min(step, goal - tracer.samples))
        if bar is not None:
            bar.update(tracer.samples - shown)
            shown = tracer.samples
        check()
        if until is not None:
            result = tracer.result()
            history.append((tracer.seconds, tracer.samples, result.relative_error))
            if result.relative_error <= until:
                return
            step = tracer.samples  # (doubling: a check costs a read-back)


def _adaptive(tracer: PathTracer, camera, spp: int | None, until: float | None, most: int,
              per_pass: int, bar, history: list) -> None:
    """``trace(adaptive=True)``'s samples: a pilot from another seed (thrown away), then
    each pixel's share of a mean of ``spp`` by the pilot's deviations
    (:mod:`glshade.pathtrace.adaptive`) -- or, for ``until``, of a mean doubled until the
    relative error is reached (at most ``most``); in steps of about ``per_pass`` samples a
    pixel's paths (progress, Ctrl-C)."""
    from ..interrupt import check
    from .adaptive import pilot_samples

    pixels = tracer.counts.size
    shown = 0.0

    def advance(counts: np.ndarray) -> None:
        nonlocal shown
        start = tracer.counts
        todo = counts - start
        chunks = max(1, -(-int(todo.sum()) // (per_pass * pixels)))
        if tracer.options.sampler is Sampler.SOBOL:
            # (an even number of steps: one ends at each pixel's half, a mark for Sobol
            # points' error by halves -- PathTracer.result)
            chunks += chunks % 2
        for j in range(1, chunks + 1):
            tracer.add(camera, counts=start + todo * j // chunks)
            if bar is not None:
                mean = float(tracer.counts.mean())
                bar.update(mean - shown)
                shown = mean
            check()

    mean = spp if spp is not None else 64
    # (``until`` goes on to as many samples as it takes: the largest pilot)
    sigma = tracer.deviations(camera, pilot_samples(spp if spp is not None else most))

    def counts(mean: int) -> np.ndarray:
        return np.maximum(tracer.counts, tracer.allocate(sigma, mean))

    advance(counts(mean))
    while until is not None:
        result = tracer.result()
        history.append((tracer.seconds, result.samples, result.relative_error))
        if result.relative_error <= until or mean >= most:
            return
        mean = min(2 * mean, most)
        advance(counts(mean))


#: the most samples one pixel may draw (its count is a float32 on the GPU: exact to 2^24)
MOST_SAMPLES = 1 << 24


def _per_pass(pixels: int) -> int:
    """Samples a pixel between two looks at the progress bar and Ctrl-C: about a million
    paths, at least 1 and at most 16."""
    return int(np.clip(2**20 // max(pixels, 1), 1, 16))

