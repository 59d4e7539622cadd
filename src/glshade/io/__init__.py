"""Mesh files: Wavefront OBJ, OFF, PLY (ascii and binary) and STL (ascii and binary)."""

from .meshio import load_mesh, save_mesh, FORMATS

__all__ = ["load_mesh", "save_mesh", "FORMATS"]
