"""What is drawn: meshes with materials and transforms, lights, ambient and background.

Plain data (numpy arrays), no GL handles: the renderer keeps the GPU copies.
"""

from __future__ import annotations

from dataclasses import replace

import dataclasses
import warnings

from typing import Any

from dataclasses import dataclass, field

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..errors import GeometryError, SceneError, plain
from ..modes import LightingModel, Tessellation, choose
from ..geometry.analytic import affine_matrix
from ..geometry.mesh import Mesh
from ..geometry.lines import Polyline
from ..geometry.points import PointCloud
from ..geometry.transforms import MAX_DRAWABLE_COORDINATE, box_corners, compose_transform
from ..solids.tree import Solid
from .lights import MAX_LIGHTS, DirectionalLight, PointLight, SpotLight, lights_for
from .describe import material_from_description
from .material import Material, color3
from .pbr import PBRMaterial

__all__ = ["Model", "InstanceGroup", "SolidModel", "PatchModel", "CloudModel", "LineModel",
           "Scene",
           "MAX_DRAWABLE_COORDINATE",
           "MAX_GPU_LEVEL", "MAX_GPU_PATCH_POINTS"]

#: GPU tessellation: the largest level (GL 4.0's guaranteed GL_MAX_TESS_GEN_LEVEL) and
#: control points a patch (GL_MAX_PATCH_VERTICES' guaranteed 32)
MAX_GPU_LEVEL, MAX_GPU_PATCH_POINTS = 64, 32


@dataclass(eq=False)
class Model:
    """One mesh placed in a scene.

    Parameters
    ----------
    mesh : Mesh
        Its polygons (model coordinates).
    material : Material
        How it is shaded.
    transform : ndarray
        ``(4, 4)`` model-to-world matrix, column vectors.
    name : str or None
        Its name.
    visible : bool
        Whether draws show it.
    vertex_colors : ndarray or None
        ``(V, 3)`` float32 linear RGB a vertex, shown by the ``radiosity`` mode.
    label : str or None
        Its class, for ground truth (:attr:`Scene.labels`).
    instance_id : int
        Which object it is (1, 2, ... in the order added; 0: not added by Scene.add).
    group : InstanceGroup or None
        The instances it is one of (``Scene.add(..., instances=)``), drawn together.
    """

    mesh: Mesh
    material: Material | PBRMaterial = field(default_factory=Material)
    transform: NDArray[np.float64] = field(default_factory=lambda: np.eye(4))
    name: str | None = None
    visible: bool = True
    #: (V, 3) linear RGB per mesh vertex, shown by the ``radiosity`` mode (read-only)
    vertex_colors: NDArray[np.float32] | None = None
    #: what the model is, for ground truth: its class's name, and which object it is (1,
    #: 2, ... in the order added; the parts of one multi-material mesh share theirs)
    label: str | None = None
    instance_id: int = 0
    group: InstanceGroup | None = field(default=None, repr=False)
    _constant: tuple | None = field(default=None, repr=False)

    @property
    def transparent(self) -> bool:
        """Whether it is drawn as a transparent surface: its material's opacity (or opacity
        map), or its mesh's colours with an alpha below 1 where the material takes them."""
        return self.material.transparent or (self.material.vertex_colors
                                             and self.mesh.translucent)

    @property
    def corners(self) -> NDArray[np.float64]:
        """The mesh's bounding-box corners ``(8, 3)`` placed in the world (kept while the
        mesh and the transform are the ones they were made from: a draw asks every frame)."""
        key = (id(self.mesh), id(self.transform), self.transform.tobytes())
        found = self.__dict__.get("_corners")
        if found is None or found[0] != key:
            c = box_corners(self.mesh.bounds) @ self.transform[:3, :3].T + self.transform[:3, 3]
            found = self.__dict__["_corners"] = (key, c)
        return found[1]

    def display_colors(self, ambient) -> np.ndarray:
        """What the ``radiosity`` mode shows at each vertex: ``vertex_colors``, or without
        them the surface's own emission plus its ambient term (no light transport).

        Parameters
        ----------
        ambient : array_like
            ``(3,)`` the scene's ambient intensity.
        """
        if self.vertex_colors is not None:
            return self.vertex_colors
        key = (self.mesh.n_vertices, self.material, tuple(ambient))
        if self._constant is None or self._constant[0] != key:  # (the same array each frame)
            m = self.material
            c = np.add(m.emission, np.multiply(ambient, m.ambient_rgb))
            self._constant = (key, np.broadcast_to(np.asarray(c, np.float32),
                                                   (self.mesh.n_vertices, 3)))
        return self._constant[1]


@dataclass(eq=False)
class InstanceGroup:
    """Copies of one mesh, each its own model in ``Scene.models`` -- its own transform,
    colour and ``instance_id``, so that every reader of a scene (the tracer, radiosity, the
    ground truth) sees K objects -- that the renderer draws with one instanced call (the
    same picture, to the byte, as K models added one by one).

    Parameters
    ----------
    models : tuple of Model
        The instances' models, in order (consecutive in ``Scene.models``).
    colors : ndarray or None
        ``(K, 3)`` each instance's linear RGB colour (None: the material's).
    materials : tuple of Material
        Each instance's material as added: a model given another one since is drawn on
        its own (the group's draw knows only these).
    """

    models: tuple
    colors: NDArray[np.float64] | None = None
    materials: tuple = ()

    def __len__(self) -> int:
        return len(self.models)

    @property
    def transforms(self) -> NDArray[np.float64]:
        """``(K, 4, 4)`` each instance's model-to-world matrix, as its model holds it now."""
        return np.stack([m.transform for m in self.models])


@dataclass(eq=False)
class SolidModel:
    """One CSG solid in a scene (placed: its transform is part of the tree).

    Parameters
    ----------
    solid : Solid
        The CSG tree, placed (its transform is a node of the tree).
    material : Material
        How it is shaded.
    name : str or None
        Its name.
    visible : bool
        Whether draws show it.
    label : str or None
        Its class, for ground truth.
    instance_id : int
        Which object it is.
    """

    solid: Solid
    material: Material = field(default_factory=Material)
    name: str | None = None
    visible: bool = True
    label: str | None = None
    instance_id: int = 0

    @property
    def n_polygons(self) -> int:
        """The polygon ids the solid takes: one a leaf."""
        return len(self.solid.leaves())


@dataclass(eq=False)
class PatchModel:
    """Patches tessellated on the GPU at draw time (GL 4.0 tessellation shaders), ``level``
    segments a patch side; placed by ``transform`` (4x4).

    Parameters
    ----------
    patches : PatchSet or PatchSurface
        The patches (model coordinates).
    material : Material
        How they are shaded.
    transform : ndarray
        ``(4, 4)`` model-to-world matrix, column vectors.
    level : int
        Segments a patch side, 1 to 64.
    name : str or None
        Its name.
    visible : bool
        Whether draws show it.
    label : str or None
        Its class, for ground truth.
    instance_id : int
        Which object it is.
    """

    patches: Any
    material: Material = field(default_factory=Material)
    transform: NDArray[np.float64] = field(default_factory=lambda: np.eye(4))
    level: int = 16
    name: str | None = None
    visible: bool = True
    label: str | None = None
    instance_id: int = 0

    @property
    def corners(self) -> NDArray[np.float64]:
        """The control points' box corners ``(8, 3)`` placed in the world (the surface
        lies inside its control points' hull)."""
        b = self.patches.bounds()
        box = np.stack([b[:, 0].min(0), b[:, 1].max(0)])
        return box_corners(box) @ self.transform[:3, :3].T + self.transform[:3, 3]


class _Placed:
    """What a cloud's and a polyline's model share: a similarity placement
    (``transform``) of a ``shape`` with ``bounds``."""

    transform: NDArray[np.float64]

    @property
    def shape(self) -> Any:
        raise NotImplementedError

    @property
    def scale(self) -> float:
        """The placement's uniform scale (a radius or a world width in the world is this
        times the shape's own)."""
        return float(np.cbrt(abs(np.linalg.det(self.transform[:3, :3]))))

    @property
    def corners(self) -> NDArray[np.float64]:
        """The shape's box corners ``(8, 3)`` placed in the world."""
        return box_corners(self.shape.bounds) @ self.transform[:3, :3].T + \
            self.transform[:3, 3]


@dataclass(eq=False)
class CloudModel(_Placed):
    """A point cloud placed in a scene (:class:`~glshade.geometry.points.PointCloud`): its
    points are ids of ``Frame.face_id`` after every polygon and solid leaf.

    Parameters
    ----------
    cloud : PointCloud
        The points (model coordinates).
    material : Material
        How they are shaded (the cloud's ``colors`` replace its colour).
    transform : ndarray
        ``(4, 4)`` model-to-world matrix, column vectors: a similarity (a sphere stays a
        sphere), its scale multiplying the radii.
    name : str or None
        Its name.
    visible : bool
        Whether draws show it.
    label : str or None
        Its class, for ground truth.
    instance_id : int
        Which object it is.
    """

    cloud: PointCloud
    material: Material = field(default_factory=Material)
    transform: NDArray[np.float64] = field(default_factory=lambda: np.eye(4))
    name: str | None = None
    visible: bool = True
    label: str | None = None
    instance_id: int = 0

    @property
    def shape(self) -> PointCloud:
        """What is placed: the cloud."""
        return self.cloud

    @property
    def n_polygons(self) -> int:
        """The ids the cloud takes: one a point."""
        return self.cloud.n_points


@dataclass(eq=False)
class LineModel(_Placed):
    """Polylines placed in a scene (:class:`~glshade.geometry.lines.Polyline`): their
    segments are ids of ``Frame.face_id`` after every polygon, solid leaf and point.

    Parameters
    ----------
    lines : Polyline
        The polylines (model coordinates).
    material : Material
        Their colour (``color``, unless the polyline has its own colours).
    transform : ndarray
        ``(4, 4)`` model-to-world matrix, column vectors: a similarity, its scale
        multiplying a width in world units.
    name : str or None
        Its name.
    visible : bool
        Whether draws show it.
    label : str or None
        Its class, for ground truth.
    instance_id : int
        Which object it is.
    """

    lines: Polyline
    material: Material = field(default_factory=Material)
    transform: NDArray[np.float64] = field(default_factory=lambda: np.eye(4))
    name: str | None = None
    visible: bool = True
    label: str | None = None
    instance_id: int = 0

    @property
    def shape(self) -> Polyline:
        """What is placed: the polylines."""
        return self.lines

    @property
    def n_polygons(self) -> int:
        """The ids the lines take: one a segment."""
        return self.lines.n_segments



def _notes_only(material, what: str) -> None:
    """Refuse a material of another lighting model for what only the notes' model lights
    (clouds, lines, ray-cast solids, GPU patches), naming both."""
    if material is not None and material.lighting is not LightingModel.NOTES:
        raise SceneError(f"{what} is lit by the notes' model: give it a glshade.Material, "
                         f"not a {type(material).__name__} (meshes take either)")

class Scene:
    """Meshes, lights, ambient intensity ``Ia`` and background colour.

    A scene with no lights is drawn with a default headlight: a white point light at the
    camera (so what faces the viewer is lit), documented here and in the README.

    Parameters
    ----------
    ambient : array_like
        ``(3,)`` the ambient intensity Ia (linear RGB).
    background : array_like
        ``(4,)`` linear RGBA of the empty pixels.
    environment : Environment or None
        Light from every direction at infinity (:class:`~glshade.Environment`): the path
        tracer's sky, sampled by importance and seen where camera rays miss; also settable
        as ``scene.environment``.
    """

    def __init__(self, ambient: ArrayLike = (1.0, 1.0, 1.0),
                 background: ArrayLike = (0.0, 0.0, 0.0, 1.0), environment=None):
        self.ambient = color3(ambient, "ambient")
        bg = np.asarray(background, dtype=np.float64)
        if bg.shape == (3,):
            bg = np.append(bg, 1.0)
        if bg.shape != (4,) or not np.isfinite(bg).all():
            raise SceneError(f"background must be (r, g, b) or (r, g, b, a), got "
                                f"{background!r}")
        self.background = tuple(float(x) for x in bg)
        self.models: list[Model] = []
        self.solids: list[SolidModel] = []
        self.patch_models: list[PatchModel] = []
        self.clouds: list[CloudModel] = []
        self.lines: list[LineModel] = []
        self.lights: list = []
        self.environment = environment
        self._next_instance = 0

    @property
    def environment(self):
        """The scene's :class:`~glshade.Environment` (None: black beyond the scene)."""
        return self._environment

    @environment.setter
    def environment(self, value) -> None:
        from .environment import Environment

        if value is not None and not isinstance(value, Environment):
            raise SceneError(f"environment must be a glshade.Environment or None, got "
                             f"{type(value).__name__}")
        self._environment = value

    def __repr__(self) -> str:
        polygons = sum(m.mesh.n_faces for m in self.models)
        leaves = sum(s.solid.n_leaves for s in self.solids)
        gpu = (f", {len(self.patch_models)} patch models (GPU tessellation)"
               if self.patch_models else "")
        if self.clouds:
            gpu += (f", {len(self.clouds)} point clouds "
                    f"({sum(c.cloud.n_points for c in self.clouds):,} points)")
        if self.lines:
            gpu += (f", {len(self.lines)} polylines "
                    f"({sum(m.lines.n_segments for m in self.lines):,} segments)")
        return (f"<Scene: {len(self.models)} models ({polygons:,} polygons), "
                f"{len(self.solids)} solids ({leaves:,} leaves){gpu}, "
                f"{len(self.lights)} lights>")

    def _repr_html_(self) -> str:
        """In a notebook: a thumbnail from the iso view and the counts."""
        from ..display import bounds_fact, facts_html, picture

        return facts_html(repr(self), [bounds_fact(self.bounds)], picture(self))

    def add(self, mesh: Mesh | Solid, material: Material | PBRMaterial | None = None,
            transform: ArrayLike | None = None,
            *, rotation: ArrayLike | None = None, translation: ArrayLike = (0, 0, 0),
            scale: ArrayLike = 1.0, name: str | None = None,
            crease: float | None = None, vertex_colors: ArrayLike | None = None,
            tessellation: Tessellation | str = "cpu", level: int | None = None,
            label: str | None = None, instances: ArrayLike | None = None,
            colors: ArrayLike | None = None):
        """Add a mesh (or a CSG solid, :mod:`glshade.solids`, ray cast on the GPU; or patches,
        :mod:`glshade.patches`, tessellated to a thousandth of their size with their exact
        normals -- :func:`~glshade.patches.tessellate` for another tolerance). Place
        it with a 4x4 ``transform`` (column vectors), or with a
        quaternion ``rotation``, ``translation`` and ``scale`` (T R S). ``crease`` (degrees)
        keeps edges sharper than that sharp under smooth shading (CAD parts): the mesh is
        added with its vertices split there (:meth:`Mesh.split_creases`). ``vertex_colors``
        (V, 3) are what the ``radiosity`` mode shows (a radiosity solution's display).
        Patches are tessellated here, ``level`` segments a side if given (else to the
        tolerance above); with ``tessellation="gpu"`` they are kept as patches and
        tessellated by the GPU at every draw, ``level`` segments a side (1..64, default 16):
        a :class:`PatchModel`. The same level gives the same triangles either way.

        Parameters
        ----------
        mesh : Mesh, Solid, patches, PointCloud or Polyline
            What to add (a :class:`~glshade.geometry.points.PointCloud` becomes a
            :class:`CloudModel`, a :class:`~glshade.geometry.lines.Polyline` a
            :class:`LineModel`, placed by a similarity).
        material : Material, PBRMaterial or None
            Its material (None: the default Material, or the file's own); a PBRMaterial
            for meshes only.
        transform : array_like or None
            ``(4, 4)`` model-to-world matrix for column vectors (instead of the next three).
        rotation : array_like or None
            ``(4,)`` a unit quaternion ``(x, y, z, w)``.
        translation : array_like
            ``(3,)`` scene units.
        scale : float or array_like
            Uniform, or ``(3,)`` per axis, > 0.
        name : str or None
            The model's name (None: the mesh's).
        crease : float or None
            Degrees: edges sharper than this stay sharp under smooth shading.
        vertex_colors : array_like or None
            ``(V, 3)`` linear RGB, >= 0, one a vertex.
        tessellation : glshade.modes.Tessellation or str
            Patches: ``"cpu"`` or ``"gpu"``.
        level : int or None
            Patches: segments a side (None: to a thousandth of their size).
        label : str or None
            The model's class, for ground truth (:attr:`labels`; None: its name). Every
            model also gets the next ``instance_id`` (1, 2, ... in the order added).
        instances : array_like or None
            ``(K, 4, 4)`` model-to-world matrices: K copies of one mesh of one material,
            the k-th placed at ``instances[k] @ placement`` (the placement from
            ``transform`` or ``rotation``/``translation``/``scale``). Each copy is a model
            of its own (its own ``instance_id``); the renderer draws them with one call.
            Returns their :class:`InstanceGroup`.
        colors : array_like or None
            ``(K, 3)`` linear RGB, each instance's colour (its material's ``color``);
            only with ``instances``.
        """
        if label is not None and not (isinstance(label, str) and label.strip()):
            raise SceneError(f"label must be a non-empty string (the object's class), got "
                             f"{label!r}")
        if colors is not None and instances is None:
            raise SceneError("colors are the instances' colours: give instances= too")
        copies = None if instances is None else _instance_matrices(instances)
        kinds: tuple[list, ...] = (self.models, self.patch_models, self.solids, self.clouds,
                                   self.lines)
        before = [len(k) for k in kinds]  # (what this add appends: a mesh's parts too)
        model = self._add(mesh, material, transform, rotation, translation, scale, name,
                          crease, vertex_colors, tessellation, level)
        added = [m for k, n in zip(kinds, before) for m in k[n:]]
        if copies is not None:
            if added != [model] or not isinstance(model, Model):
                del self.models[before[0]:], self.patch_models[before[1]:]
                del self.solids[before[2]:], self.clouds[before[3]:], self.lines[before[4]:]
                raise SceneError("instances= copies one mesh of one material; this add "
                                 f"made {len(added)} models (a solid, GPU patches, a point "
                                 "cloud or a mesh whose faces name materials): add those "
                                 "one by one")
            model = self._instances(model, copies, colors)
            added = list(model.models)
        for each in added:
            if copies is not None or each is added[0]:
                self._next_instance += 1
            each.instance_id = self._next_instance
            each.label = label if label is not None else (
                name or getattr(mesh, "name", None) or type(mesh).__name__)
        return model

    def _instances(self, model: Model, copies: np.ndarray, colors) -> InstanceGroup:
        """``model`` (the last of ``models``) as the first of ``len(copies)`` instances."""
        k = len(copies)
        transforms = copies @ model.transform
        try:
            _check_reach(model.mesh, transforms, "the instances reach")
        except SceneError:
            del self.models[-1]
            raise
        table = None
        materials = [model.material] * k
        if colors is not None:
            table = _instance_colors(colors, k)
            # (an instance's colour is its material's: the notes' C, or glTF's base colour)
            base = model.material
            materials = [dataclasses.replace(base, base_color=tuple(map(float, c)))
                         if isinstance(base, PBRMaterial) else
                         dataclasses.replace(base, color=tuple(map(float, c))) for c in table]
        models = tuple(Model(model.mesh, materials[i], transforms[i], model.name,
                             vertex_colors=model.vertex_colors) for i in range(k))
        group = InstanceGroup(models, table, tuple(materials))
        for each in models:
            each.group = group
        self.models[-1:] = models
        return group

    @property
    def every_model(self) -> list:
        """Every model in the order its polygon ids run: meshes, patches, solids, clouds,
        lines."""
        return [*self.models, *self.patch_models, *self.solids, *self.clouds, *self.lines]

    @property
    def labels(self) -> dict[str, int]:
        """Each label to its class id: 1, 2, ... in the order of first appearance (by
        instance); 0 is the background's."""
        out: dict[str, int] = {}
        for model in sorted(self.every_model, key=lambda m: m.instance_id):
            if model.label is not None and model.label not in out:
                out[model.label] = len(out) + 1
        return out

    def id_tables(self) -> tuple[NDArray[np.int32], NDArray[np.int32]]:
        """``(instances, classes)``: for each polygon id ``k`` (as :class:`Frame` numbers
        them: the meshes' polygons in order, then the patches', then a leaf a solid, then a
        point a cloud, then a segment a polyline), its
        model's ``instance_id`` at ``[k + 1]`` and its label's class id likewise; ``[0]`` is
        the background's 0 -- so ``instances[face_id + 1]`` is a frame's instance mask.
        """
        labels = self.labels
        counts = [m.mesh.n_faces for m in self.models] + \
            [len(m.patches) for m in self.patch_models] + \
            [m.n_polygons for m in self.solids] + [m.n_polygons for m in self.clouds] + \
            [m.n_polygons for m in self.lines]
        every = self.every_model
        instances = np.repeat(np.array([m.instance_id for m in every], np.int32), counts)
        classes = np.repeat(np.array([labels.get(m.label, 0) if m.label is not None else 0
                                      for m in every], np.int32), counts)
        return (np.concatenate([np.zeros(1, np.int32), instances]),
                np.concatenate([np.zeros(1, np.int32), classes]))

    def _add(self, mesh, material, transform, rotation, translation, scale, name, crease,
             vertex_colors, tessellation, level):
        if isinstance(mesh, (PointCloud, Polyline)):
            return self._add_placed(mesh, material, transform, rotation, translation, scale,
                                   name, crease, vertex_colors, tessellation, level)
        if isinstance(mesh, Solid):
            return self._add_solid(mesh, material, transform, rotation, translation, scale,
                                   name)
        from ..patches import PatchSet, PatchSurface

        tessellation = choose(Tessellation, tessellation, "tessellation", SceneError)
        if tessellation is Tessellation.GPU:
            if not isinstance(mesh, (PatchSurface, PatchSet)):
                raise SceneError(f"tessellation='gpu' is for patches (glshade.patches), not "
                                 f"a {type(mesh).__name__}")
            return self._add_patches(mesh, material, transform, rotation, translation, scale,
                                     name, 16 if level is None else level)
        if isinstance(mesh, (PatchSurface, PatchSet)):  # (a tessellation, exact normals)
            mesh = _tessellated(mesh, level)
        elif level is not None:
            raise SceneError(f"level is for patches (glshade.patches), not a "
                             f"{type(mesh).__name__}")
        if not isinstance(mesh, Mesh):
            raise SceneError(f"scene.add needs a Mesh, a Solid, patches, a PointCloud or a "
                             f"Polyline, got "
                                f"{type(mesh).__name__}")
        if crease is not None:
            mesh = mesh.split_creases(crease)
        m = _placement(transform, rotation, translation, scale)
        _check_reach(mesh, m[None], "the mesh reaches")
        colors = None
        if vertex_colors is not None:
            if crease is not None:
                raise SceneError("vertex_colors and crease cannot be combined (crease "
                                    "splits the vertices the colours belong to)")
            colors = _vertex_colors(vertex_colors, mesh.n_vertices)
            colors.flags.writeable = False
        if material is None and mesh.material_groups and colors is None:
            return self._add_material_parts(mesh, m, name or mesh.name)
        if material is not None and material.textures and mesh.uv is None:
            warnings.warn(f"{name or mesh.name or 'the mesh'} has no texture coordinates "
                          f"(uv); its material's {', '.join(material.textures)} is not shown",
                          UserWarning, stacklevel=3)
        model = Model(mesh, material or Material(), m, name or mesh.name,
                      vertex_colors=colors)
        self.models.append(model)
        return model

    def _add_material_parts(self, mesh: Mesh, m: np.ndarray, name: str | None) -> Model:
        """A mesh whose faces name materials (an OBJ's ``usemtl`` parts): a model per part,
        drawn with its material (named ``NAME:MATERIAL``); faces in no part, or whose
        material was not found, get the default Material. Returns the first."""
        parts = list(mesh.material_groups.items())
        covered = np.zeros(mesh.n_faces, bool)
        for _, faces in parts:
            covered[faces] = True
        if not covered.all():
            parts.append(("", np.flatnonzero(~covered)))
        models = []
        for part, faces in parts:
            # (a part's material: made from its file's description where the mesh holds one)
            material = material_from_description(mesh.materials.get(part),
                                                 f"{name or 'mesh'}: {part}")
            sub = mesh.subset(faces)
            models.append(Model(sub, material if isinstance(material, (Material, PBRMaterial))
                                else Material(),
                                m, f"{name}:{part}" if part and name else (part or name)))
        self.models.extend(models)
        return models[0]

    def _add_patches(self, patches, material, transform, rotation, translation, scale, name,
                     level):
        """Patches for the GPU's tessellator (see :class:`PatchModel`)."""
        from ..patches import PatchSurface

        _notes_only(material, "GPU-tessellated patches")

        if isinstance(patches, PatchSurface):
            patches = patches.patches
        if isinstance(level, bool) or not isinstance(level, (int, np.integer)) or \
                not 1 <= level <= MAX_GPU_LEVEL:
            raise SceneError(f"level must be a whole number from 1 to {MAX_GPU_LEVEL} (GL "
                             f"4.0's tessellation limit) for tessellation='gpu', got {level!r}")
        m, n = patches.degree
        if (m + 1) * (n + 1) > MAX_GPU_PATCH_POINTS or max(m, n) > 7:
            raise SceneError(f"patches of degree {m}x{n} have {(m + 1) * (n + 1)} control "
                             f"points; the GPU's tessellator takes at most "
                             f"{MAX_GPU_PATCH_POINTS} (degree 7): use tessellation='cpu'")
        t = _placement(transform, rotation, translation, scale)
        model = PatchModel(patches, material or Material(), t, int(level),
                           name or "patches")
        self.patch_models.append(model)
        return model

    def _add_placed(self, cloud, material, transform, rotation, translation, scale, name,
                   crease, vertex_colors, tessellation, level):
        """A point cloud or polylines (:class:`CloudModel`, :class:`LineModel`); a
        similarity places them."""
        what, kinds = (("a point cloud", "point clouds") if isinstance(cloud, PointCloud)
                       else ("polylines", "polylines"))
        given = [k for k, v in (("crease", crease), ("vertex_colors", vertex_colors),
                                ("level", level)) if v is not None]
        if tessellation not in ("cpu", Tessellation.CPU):
            given.append("tessellation")
        if given:
            raise SceneError(f"{', '.join(given)} {'is' if len(given) == 1 else 'are'} for "
                             f"meshes and patches, not {what}")
        _notes_only(material, what)
        if material is not None and material.opacity < 1:
            raise SceneError(f"{kinds} are drawn opaque; this material's opacity is "
                             f"{plain(material.opacity)}")
        m = _placement(transform, rotation, translation, scale)
        a = m[:3, :3]
        s = np.cbrt(abs(np.linalg.det(a)))
        if not np.allclose(a.T @ a, s * s * np.eye(3), rtol=0, atol=1e-9 * s * s):
            raise SceneError(f"{kinds} are placed by a rotation, a translation and one scale "
                             "(a sphere stays a sphere, a width a width): this transform "
                             "shears or scales its axes unequally")
        corners = box_corners(cloud.bounds) @ a.T + m[:3, 3]
        reach = float(np.abs(corners).max())
        if reach > MAX_DRAWABLE_COORDINATE:
            raise SceneError(f"{what} placed so: a coordinate of {reach:g}, where the GPU "
                             f"draws up to {MAX_DRAWABLE_COORDINATE:g}: scale down")
        if isinstance(cloud, PointCloud):
            model: Any = CloudModel(cloud, material or Material(), m,
                                    name or cloud.name or "points")
            self.clouds.append(model)
        else:
            model = LineModel(cloud, material or Material(), m, name or cloud.name or "lines")
            self.lines.append(model)
        return model

    def _add_solid(self, solid, material, transform, rotation, translation, scale, name):
        """A CSG solid, ray cast on the GPU (its placement becomes a Transformed node)."""
        _notes_only(material, "a CSG solid")
        m = _placement(transform, rotation, translation, scale)
        if not np.allclose(m, np.eye(4)):
            solid = solid.transformed(m)
        if solid.bounds is None:
            raise SceneError("a solid in a scene must be bounded: cut a half-space with a "
                                "bounded solid (e.g. Box(10) & HalfSpace())")
        model = SolidModel(solid, material or Material(), name or type(solid).__name__)
        self.solids.append(model)
        return model

    def set_texture_filter(self, filter: str) -> None:
        """Sample every texture of the scene's models with ``filter`` ("nearest",
        "linear" or "mipmap"; the command line's ``--texture-filter``).

        Parameters
        ----------
        filter : str
            ``"nearest"``, ``"linear"`` or ``"mipmap"``.
        """
        from .texture import FILTERS

        if filter not in FILTERS:
            raise SceneError(f"texture filter must be one of {', '.join(FILTERS)}, got "
                             f"{filter!r}")
        for model in self.models:
            maps = model.material.textures
            if maps:
                model.material = dataclasses.replace(
                    model.material, **{k: t.replace(filter=filter) for k, t in maps.items()})

    def add_light(self, light) -> None:
        """Add a PointLight, SpotLight or DirectionalLight (at most MAX_LIGHTS).

        Parameters
        ----------
        light : PointLight, SpotLight or DirectionalLight
            The light.
        """
        if not isinstance(light, (PointLight, SpotLight, DirectionalLight)):
            raise SceneError(f"expected a PointLight, SpotLight or DirectionalLight, got "
                             f"{light!r}")
        if len(self.lights) >= MAX_LIGHTS:
            raise SceneError(f"at most {MAX_LIGHTS} lights per scene")
        self.lights.append(light)

    def lights_for(self, camera) -> list:
        """The lights a draw with ``camera`` uses (the headlight when there are none and
        no environment lights the scene: under a sky the headlight is dark -- a light of
        intensity 0, so the programs keep their one light -- as the path tracer has none).

        Parameters
        ----------
        camera : Camera
            The camera of the draw (the headlight sits at its eye).
        """
        found = lights_for(self.lights, camera)
        if not self.lights and self.environment is not None:
            return [replace(found[0], intensity=0.0)]
        return found

    @property
    def bounds(self) -> NDArray[np.float64]:
        """World bounding box ``(2, 3)`` of the visible models."""
        pts = []
        for m in self.models:
            if not m.visible or m.mesh.n_vertices == 0:
                continue
            pts.append(m.corners)
        pts += [box_corners(s.solid.bounds) for s in self.solids if s.visible]
        pts += [p.corners for p in self.patch_models if p.visible]
        pts += [c.corners for c in self.clouds if c.visible]
        pts += [m.corners for m in self.lines if m.visible]
        if not pts:
            return np.zeros((2, 3))
        p = np.vstack(pts)
        return np.stack([p.min(0), p.max(0)])


#: patches a scene tessellates itself: to this fraction of their size
PATCH_TOLERANCE = 1e-3


def _placement(transform, rotation, translation, scale) -> NDArray[np.float64]:
    """A model's 4x4 matrix: ``transform`` as given, or T R S from the rest."""
    if transform is not None:
        return affine_matrix(transform, "transform")
    return affine_matrix(compose_transform(rotation, translation, scale), "transform")


def _check_reach(mesh: Mesh, placements: np.ndarray, what: str) -> None:
    """Refuse placements ``(K, 4, 4)`` that take the mesh's box beyond the coordinates the
    GPU draws."""
    if not mesh.n_vertices:
        return
    corners = box_corners(mesh.bounds)
    reach = float(np.abs(corners @ np.swapaxes(placements[:, :3, :3], 1, 2)
                         + placements[:, None, :3, 3]).max())
    if reach > MAX_DRAWABLE_COORDINATE:
        raise SceneError(f"{what} a coordinate of {reach:g}; the GPU draws up to "
                         f"{MAX_DRAWABLE_COORDINATE:g} (its 32-bit arithmetic squares "
                         "lengths): scale down")


def _instance_matrices(values) -> NDArray[np.float64]:
    """``(K, 4, 4)`` finite, invertible placements, or a SceneError in plain numbers."""
    try:
        t = np.array(values, dtype=np.float64)
    except (TypeError, ValueError):
        raise SceneError(f"instances must be a (K, 4, 4) array of numbers, got "
                         f"{type(values).__name__}") from None
    if t.ndim != 3 or t.shape[1:] != (4, 4) or len(t) == 0:
        raise SceneError(f"instances must be a (K, 4, 4) array of model-to-world matrices "
                         f"with K >= 1, got shape {t.shape}")
    with np.errstate(all="ignore"):
        bad = ~np.isfinite(t).all((1, 2))
        if not bad.any():
            bad = ~(np.abs(np.linalg.det(t[:, :3, :3])) > 1e-300)
    if bad.any():
        i = int(np.flatnonzero(bad)[0])
        raise SceneError(f"instances[{i}] is not a finite, invertible matrix: "
                         f"{plain(t[i].tolist())} ({int(bad.sum())} of {len(t)} such)")
    if not np.allclose(t[:, 3], [0, 0, 0, 1], rtol=0, atol=0):
        i = int(np.flatnonzero((t[:, 3] != [0, 0, 0, 1]).any(1))[0])
        raise SceneError(f"instances[{i}]'s last row must be (0, 0, 0, 1) (an affine "
                         f"placement), got {plain(t[i, 3].tolist())}")
    return t


def _instance_colors(values, k: int) -> NDArray[np.float64]:
    """``(K, 3)`` colours from 0 to MAX_SHADING_VALUE, or a SceneError in plain numbers."""
    from .material import MAX_SHADING_VALUE

    rule = f"colors must be ({k:,}, 3) numbers from 0 to {MAX_SHADING_VALUE:g}, one an instance"
    try:
        c = np.array(values, dtype=np.float64)
    except (TypeError, ValueError):
        raise SceneError(f"{rule}; got {type(values).__name__}") from None
    if c.shape != (k, 3):
        raise SceneError(f"{rule}; got shape {c.shape}")
    bad = ~(np.isfinite(c) & (c >= 0) & (c <= MAX_SHADING_VALUE)).all(1)
    if bad.any():
        i = int(np.flatnonzero(bad)[0])
        raise SceneError(f"{rule}; colors[{i}] is {plain(c[i].tolist())}")
    c.flags.writeable = False
    return c


def _tessellated(patches, level: int | None = None) -> Mesh:
    """Patches as a mesh: ``level`` segments a side, or to PATCH_TOLERANCE of their size."""
    from ..patches import PatchSet, PatchSurface, tessellate

    surface = patches if isinstance(patches, PatchSurface) else PatchSurface(patches)
    if level is not None:
        try:
            return tessellate(surface, level=level).mesh
        except GeometryError as exc:
            raise SceneError(str(exc)) from None
    b = surface.patches.bounds()
    size = float(np.ptp(np.concatenate([b[:, 0], b[:, 1]]), 0).max()) or 1.0
    assert isinstance(surface.patches, PatchSet)
    return tessellate(surface, tolerance=PATCH_TOLERANCE * size).mesh


def _vertex_colors(values, n_vertices: int) -> np.ndarray:
    """``(N, 3)`` float32 radiosities a vertex, or a SceneError saying which rule a value
    breaks (the shape, a number that is not finite, below 0 or past float32), in plain
    numbers."""
    rule = f"vertex_colors must be ({n_vertices:,}, 3) non-negative numbers, one per vertex"
    try:
        colors = np.array(values, dtype=np.float64)
    except (TypeError, ValueError):
        raise SceneError(f"{rule}; got something that is not numbers") from None
    if colors.shape != (n_vertices, 3):
        raise SceneError(f"{rule}; got shape {tuple(int(n) for n in colors.shape)}")
    bad = ~np.isfinite(colors) | (colors < 0) | (colors > np.finfo(np.float32).max)
    if bad.any():
        i, j = (int(k) for k in np.argwhere(bad)[0])
        raise SceneError(f"{rule}; vertex {i:,} has {plain(colors[i, j])} in channel {j} "
                         f"({int(bad.any(1).sum()):,} vertices like it)")
    return colors.astype(np.float32)
