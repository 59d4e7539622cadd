"""Find, assemble and compile the GLSL programs.

Sources live in the package as ``glshade/shaders`` (the repository's ``shaders/`` folder,
mapped into the wheel). ``#include "file"`` pulls in ``shaders/include/file`` with ``#line``
directives, so the driver's line numbers can be mapped back to the file they came from.
"""

from __future__ import annotations

from typing import Any

import importlib.resources
import re
from pathlib import Path

from ..errors import ShaderError
from ..interrupt import held
from ..modes import ShadingMode
from .base import GLResource
from .programs import ProgramKey
from .units import glsl_defines

__all__ = ["shader_dir", "ShaderLibrary", "assemble", "compile_compute", "PROGRAMS", "LOOP_CAP",
           "LOOP_BUDGET"]

#: llvmpipe stops one shader invocation after this many loop iterations (every loop of the
#: invocation counted together), silently: what it computed so far stands as its answer
LOOP_CAP = 65_535
#: the loop iterations one invocation's bounded work may take in all (a shadow ray, a
#: transparent list's walk, a path's bounces): under LOOP_CAP with room for the loops
#: around it; every program is compiled with it (``#define LOOP_BUDGET``), and work that
#: reaches it is counted and reported, never silently cut
LOOP_BUDGET = 60_000

#: program of each mode: (vertex shader file, fragment shader file) under shaders/
PROGRAMS = {
    ShadingMode.FLAT: ("flat.vert", "flat.frag"),
    ShadingMode.GOURAUD: ("gouraud.vert", "gouraud.frag"),
    ShadingMode.PHONG: ("smooth.vert", "phong.frag"),
    ShadingMode.NORMALS: ("smooth.vert", "normals.frag"),
    ShadingMode.DEPTH: ("smooth.vert", "depth.frag"),
    ShadingMode.RADIOSITY: ("radiosity.vert", "radiosity.frag"),
}

_INCLUDE = re.compile(r'^\s*#include\s+"([^"]+)"\s*$')
_MAX_DEPTH = 8
#: defines whose programs need a GL extension enabled (an #extension line after #version)
_EXTENSIONS = {"OIT_FETCH": "GL_EXT_shader_framebuffer_fetch"}


def shader_dir() -> Path:
    """The folder holding the GLSL files: package data in an installed wheel, or the
    repository's ``shaders/`` in an editable install."""
    packaged = importlib.resources.files("glshade") / "shaders"
    if packaged.is_dir():
        return Path(str(packaged))
    repo = Path(__file__).resolve().parents[3] / "shaders"
    if repo.is_dir():
        return repo
    raise ShaderError(f"GLSL sources not found: neither {packaged} nor {repo} exists "
                      "(a broken install? reinstall glshade)")


def assemble(name: str, root: Path | None = None,
             defines: tuple[str, ...] = ()) -> tuple[str, list[str]]:
    """Source of ``name`` with includes expanded and ``defines`` injected after
    ``#version``; and the file of each ``#line`` source number (index = source string
    number used in ``#line L N``). The define ``GLSL_430`` raises the file's ``#version``
    to 430 core (storage buffers and image atomics in a program written for 330),
    ``GLSL_410`` to 410 core (sampler arrays indexed in a loop: what a Mac's GL has).

    Parameters
    ----------
    name : str
        The shader file, under ``shaders/`` (or ``root``).
    root : Path or None
        Another folder of shaders (None: the packaged ones).
    defines : tuple of str
        ``#define`` lines to inject after ``#version``.
    """
    root = root or shader_dir()
    files: list[str] = []

    def expand(rel: str, depth: int, base: Path) -> list[str]:
        path = (base / rel) if (base / rel).is_file() else root / "include" / rel
        if depth > _MAX_DEPTH:
            raise ShaderError(f"{rel}: #include nested more than {_MAX_DEPTH} deep (a cycle?)")
        try:
            text = path.read_text(encoding="utf-8")
        except FileNotFoundError:
            raise ShaderError(f"{rel}: shader file not found in {root}") from None
        number = len(files)
        files.append(path.relative_to(root).as_posix() if path.is_relative_to(root) else
                     str(path))
        lines = text.splitlines()
        out: list[str] = []
        for i, line in enumerate(lines, start=1):
            if depth == 0 and i == 1:
                if not line.startswith("#version"):
                    raise ShaderError(f"{files[number]}:1: the first line must be #version, "
                                      f"got {line!r}")
                out.append("#version 430 core" if "GLSL_430" in defines else
                           "#version 410 core" if "GLSL_410" in defines else line)
                out.extend(f"#extension {_EXTENSIONS[d]} : require" for d in defines
                           if d in _EXTENSIONS)
                out.extend(f"#define {d}" for d in defines)
                out.append(f"#define LOOP_BUDGET {LOOP_BUDGET}")
                out.extend(f"#define {d}" for d in glsl_defines())
                out.append(f"#line 2 {number}")
                continue
            m = _INCLUDE.match(line)
            if m:
                out.extend(expand(m.group(1), depth + 1, path.parent))
                out.append(f"#line {i + 1} {number}")
            else:
                out.append(line)
        if depth > 0:
            out.insert(0, f"#line 1 {number}")
        return out

    return "\n".join(expand(name, 0, root)) + "\n", files




def compile_compute(context, source: str):
    """A compute program of ``source``, compiled with a Ctrl-C held until the driver is
    done (the one way every pass compiles one: an interrupt mid-compile crashed Mesa).

    Parameters
    ----------
    context : RenderContext
        The context.
    source : str
        The assembled GLSL.
    """
    from ..interrupt import held

    with held():
        return context.ctx.compute_shader(source)


# Mesa: "0:12(5): error: ..."; NVIDIA: "0(12) : error C0000: ..."; others "ERROR: 0:12: ..."
_ERROR_LINE = re.compile(r"(?:ERROR:\s*)?(\d+)[:(](\d+)\)?(?:\(\d+\))?\s*:?\s*(.*)")


def explain_compile_error(driver_text: str, sources: dict[str, tuple[str, list[str]]],
                          root: Path | None = None) -> str:
    """Turn a driver's compile log into ``file:line: message`` lines with the source line."""
    out = []
    for raw in driver_text.splitlines():
        m = _ERROR_LINE.search(raw)
        if not m or "error" not in raw.lower():
            continue
        number, line, message = int(m.group(1)), int(m.group(2)), m.group(3).strip()
        for _, (_, files) in sources.items():
            if number < len(files):
                file = files[number]
                try:
                    whole = ((root or shader_dir()) / file).read_text(encoding="utf-8")
                    src = whole.splitlines()[line - 1].strip()
                except (OSError, IndexError):
                    src = ""
                out.append(f"{file}:{line}: {message}" + (f"\n    {src}" if src else ""))
                break
    return "\n".join(out)


class ShaderLibrary(GLResource):
    """Compiled programs of one RenderContext, one per shading mode and output set, built on
    first use and released with the context.

    Parameters
    ----------
    context : RenderContext
        The context its GL objects live in.
    """

    def __init__(self, context):
        super().__init__(context)
        self._programs: dict[ProgramKey, Any] = {}

    @property
    def compiled(self) -> tuple:
        """The :class:`ProgramKey` of every mode program compiled so far."""
        return tuple(self._programs)

    def program(self, mode, aux: bool = True):
        """The program of a :class:`ProgramKey`, compiled on first use; or, given a mode, its
        general variant (one point light, two-sided; ``aux=False``: colour only, no normal,
        polygon id or depth outputs, so no id lookup per pixel).

        Parameters
        ----------
        mode : ProgramKey or ShadingMode
            The variant, or a mode (its general variant).
        aux : bool
            With a mode: whether it writes the auxiliary outputs.
        """
        self._check()
        key = mode if isinstance(mode, ProgramKey) else \
            ProgramKey(ShadingMode.parse(mode), aux=bool(aux))
        program = self._programs.get(key)
        if program is None:
            vert, frag = PROGRAMS[key.mode]
            # (a big mesh's flat draw lights each triangle's polygon in a geometry stage)
            geom = "flat.geom" if key.fetch and key.mode is ShadingMode.FLAT else None
            program = self._programs[key] = self.compile(vert, frag, defines=key.defines(),
                                                         geom=geom)
        return program

    def compile(self, vert: str, frag: str, root: Path | None = None,
                defines: tuple[str, ...] = (), geom: str | None = None,
                tess: tuple[str, str] | None = None):
        """Compile and link one program (``tess``: the tessellation control and evaluation
        shaders' files); a failure raises ShaderError naming file and line.

        Parameters
        ----------
        vert, frag : str
            The vertex and fragment shaders' files.
        root : Path or None
            Another folder of shaders (None: the packaged ones).
        defines : tuple of str
            ``#define`` lines injected into every stage (the vertex stage also gets
            ``GLSHADE_VERTEX_STAGE``: an include serving both stages tells them apart).
        geom : str or None
            A geometry shader's file.
        tess : (str, str) or None
            Tessellation control and evaluation shaders' files.
        """
        stages = {"vertex_shader": assemble(vert, root, (*defines, "GLSHADE_VERTEX_STAGE")),
                  "fragment_shader": assemble(frag, root, defines)}
        if geom:
            stages["geometry_shader"] = assemble(geom, root, defines)
        if tess:
            stages["tess_control_shader"] = assemble(tess[0], root, defines)
            stages["tess_evaluation_shader"] = assemble(tess[1], root, defines)
        try:
            with held():  # (a Ctrl-C waits for the driver's compile and link)
                return self.context.ctx.program(**{k: v[0] for k, v in stages.items()})
        except Exception as exc:  # moderngl raises a bare Error with the driver's log
            text = str(exc)
            found = re.search(r"^(" + "|".join(stages) + r")\s*$", text, re.M)
            which = found.group(1) if found else "fragment_shader"
            detail = explain_compile_error(text, {which: stages[which]}, root)
            head = f"{vert} + {frag}: GLSL {which.replace('_', ' ')} failed to compile"
            raise ShaderError(head + ("\n" + detail if detail else "") +
                              "\n--- driver log ---\n" + text.strip()) from None

    def _release_extra(self) -> None:
        for prog in self._programs.values():
            prog.release()
        self._programs.clear()
