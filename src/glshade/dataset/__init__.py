"""Data sets for vision code, rendered with exact ground truth: BOP (poses, full and visible
masks, depth) and COCO (instances with run-length masks), from a scene and cameras on a
sphere around it or its key-framed path.

>>> import tempfile
>>> from glshade import Scene, dataset
>>> from glshade.geometry import primitives
>>> scene = Scene()
>>> _ = scene.add(primitives.cube(), label="box")
>>> folder = dataset.write_bop(scene, tempfile.mkdtemp(), views=2, size=(64, 48),
...                            progress=False)
>>> sorted(p.name for p in folder.iterdir() if not p.name.startswith("."))[:3]
['depth', 'mask', 'mask_visib']
"""

from .bop import write_bop
from .cameras import sphere_cameras
from .coco import write_coco

__all__ = ["write_bop", "write_coco", "sphere_cameras"]
