"""Files in and out: meshes (OBJ, OFF, PLY, STL; one module each), scene files (TOML),
images (PNG and the labels, grids and heat maps pictures are made of), atomic writes.
No GL."""

from .images import save_image
from .meshes import FORMATS, load_mesh, save_mesh
from .scenefile import RenderSettings, SceneFile, load_scene

__all__ = ["load_mesh", "save_mesh", "FORMATS", "save_image", "load_scene", "SceneFile",
           "RenderSettings"]
