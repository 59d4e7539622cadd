"""The GL half of glshade: the only package that makes GL objects.

- :mod:`.context`: headless (EGL, then OSMesa) and window contexts, and what they can do.
- :mod:`.renderer`: :class:`~glshade.render.renderer.Renderer`, whose ``draw`` is a frame's
  pipeline -- shadows, meshes, patches, CSG solids, transparency, edges -- over one frozen
  :class:`~glshade.render.state.DrawState` (:mod:`.passes` tells the stages' protocol).
- :mod:`.state`: the draw's facts and every decision the stages act on, made once.
- :mod:`.passes`: the stages and the other GL passes (hemicube, path tracer, labels).
- :mod:`.programs`, :mod:`.shaders`: program variants, their keys and their compilation.
- :mod:`.target`, :mod:`.gpu_mesh`, :mod:`.textures`, :mod:`.data`: framebuffers, meshes,
  textures and data tables on the GPU.

The numpy that feeds each pass lives in its chapter (``solids/encoding.py``,
``pathtrace/pack.py``, ``scene/occluders.py``), beside its reference, and never imports GL.
"""
