"""GPU copies of named float arrays -- a point cloud's, a polyline's -- and the vertex
arrays that bind them to each program; kept per object while the object lives.

Two small pieces two passes share (render/passes/points.py, lines.py): :class:`GpuArrays`
(buffers of the arrays a vertex shader names, an optional index buffer, a vertex array a
program that reads only those it has) and :class:`PerObject` (one copy per live object, held
weakly: a copy is released once its object is gone, and an object made at a dead one's id
gets its own).
"""

from __future__ import annotations

import weakref
from typing import Any, Callable

import numpy as np

__all__ = ["GpuArrays", "PerObject"]


class GpuArrays:
    """Buffers of ``arrays`` (``(name, array)``: float32 ``(N,)`` or ``(N, k)``, named as
    the vertex shader's inputs) and of ``index`` (uint32, or None), with a vertex array per
    program made on first use.

    Parameters
    ----------
    ctx : moderngl.Context
        The context.
    arrays : list of (str, ndarray)
        Each input's name and values.
    index : ndarray or None
        The index buffer's values (uint32), or None for a plain draw.
    chunks : Chunks or None
        Spatial chunks of the index order (a big cloud's, render.gpu_mesh.Chunks), which a
        draw culls by.
    """

    def __init__(self, ctx, arrays: list, index: np.ndarray | None = None, chunks=None):
        self.chunks = chunks
        self.buffers = [(name, f"{a.shape[1] if a.ndim > 1 else 1}f",
                         ctx.buffer(np.ascontiguousarray(a, np.float32)))
                        for name, a in arrays]
        self.index = None if index is None else ctx.buffer(
            np.ascontiguousarray(index, np.uint32))
        #: the bytes its buffers take on the GPU
        self.nbytes = sum(b.size for _, _, b in self.buffers) + (
            0 if self.index is None else self.index.size)
        self._vaos: dict[int, Any] = {}

    def vertex_array(self, ctx, prog):
        """The vertex array binding these buffers to ``prog`` (only the inputs it has: a
        variant may not read every array).

        Parameters
        ----------
        ctx : moderngl.Context
            The context.
        prog : moderngl.Program
            The program.
        """
        vao = self._vaos.get(id(prog))
        if vao is None:
            names = set(prog)
            vao = self._vaos[id(prog)] = ctx.vertex_array(
                prog, [(buf, fmt, name) for name, fmt, buf in self.buffers if name in names],
                index_buffer=self.index, index_element_size=4)
        return vao

    def release(self) -> None:
        for vao in self._vaos.values():
            vao.release()
        for _, _, buf in self.buffers:
            buf.release()
        if self.index is not None:
            self.index.release()
        self._vaos.clear()
        self.buffers = []


class PerObject:
    """One GPU copy per live object: ``make(obj)`` on first use, kept while ``obj`` lives
    (held weakly), released once it is gone or on :meth:`release`.

    Parameters
    ----------
    make : callable
        ``make(obj)``: the copy (with a ``release()``).
    """

    def __init__(self, make: Callable[[Any], Any]):
        self._make = make
        self._found: dict[int, tuple] = {}

    def __call__(self, obj):
        for key in [k for k, v in self._found.items() if v[0]() is None]:
            self._found.pop(key)[1].release()
        found = self._found.get(id(obj))
        if found is None or found[0]() is not obj:
            if found is not None:
                found[1].release()
            found = self._found[id(obj)] = (weakref.ref(obj), self._make(obj))
        return found[1]

    def release(self) -> None:
        for _, copy in self._found.values():
            copy.release()
        self._found.clear()
