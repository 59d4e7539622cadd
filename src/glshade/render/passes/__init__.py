"""The GL passes, one per kind of thing drawn or computed: each a :class:`GLResource` made
from a RenderContext, fed by the numpy of its chapter (``solids/encoding.py``,
``pathtrace/pack.py``, ...). The passes of a frame share one signature,
``draw(state, id_base) -> id_base``: the frozen :class:`DrawState` of the draw and the first
polygon id still free (ids run on from one pass to the next); the renderer draws its meshes,
then each pass in turn.

- :mod:`.csg`: CSG solids by ray casting (:class:`CsgPass`).
- :mod:`.edges`: the edge overlay (:class:`EdgePass`).
- :mod:`.patches`: patches tessellated by GL 4.0 shaders (:class:`PatchPass`).
- :mod:`.hemicube`: radiosity's form factors (:class:`Hemicube`).
- :mod:`.pathtrace`: the path tracer's passes (:class:`GpuPathTracer`).
- :mod:`.labels`: the viewer's text bands (:class:`LabelOverlay`).
"""
