"""What is drawn and from where: cameras, key-frame paths, materials, lights and scenes.
Plain data; no GL."""

from .camera import Camera, View, default_camera
from .keyframes import CameraPath, Keyframe
from .lights import MAX_LIGHTS, DirectionalLight, PointLight, SpotLight, lights_for
from .material import Material
from .pbr import PBRMaterial
from .scene import Model, Scene
from .texture import Texture

__all__ = ["Camera", "View", "default_camera", "CameraPath", "Keyframe", "Material",
           "PBRMaterial", "PointLight", "DirectionalLight", "SpotLight", "lights_for",
           "MAX_LIGHTS", "Model", "Scene", "Texture"]
