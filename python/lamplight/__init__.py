"""lamplight: a ray tracer with numpy arrays out and Dask across a cluster.

>>> import lamplight
>>> image = lamplight.render("spheres", width=320, height=180, spp=4)
>>> image.shape, image.dtype
((180, 320, 3), dtype('float32'))
>>> image.save("spheres.png")

A scene is a built-in name (``lamplight.builtin_names()``), a scene file
(``.toml``, see ``docs/scene-format.md``), a mesh file (``.obj``, ``.ply``,
``.gltf``, ``.glb``), a dict with the structure of a scene file, or a
:class:`Scene`. ``lamplight.dask.render`` renders the same image across a Dask
cluster. The tutorial is ``docs/python.md``.
"""

from __future__ import annotations

from . import dask, frames, objects
from ._lamplight import Scene, SceneError, __version__, builtin_names, kinds
from ._render import as_scene, load, render
from .frames import make_video
from .image import Image, denoise, read_exr, save
from .objects import (
    box,
    camera,
    directional_light,
    disk,
    group,
    instance,
    material,
    mesh,
    node,
    plane,
    point_light,
    rectangle,
    scene,
    sphere,
    triangle,
)

__all__ = [
    "Image",
    "Scene",
    "SceneError",
    "__version__",
    "as_scene",
    "box",
    "builtin_names",
    "kinds",
    "camera",
    "dask",
    "denoise",
    "directional_light",
    "disk",
    "frames",
    "group",
    "instance",
    "load",
    "make_video",
    "material",
    "mesh",
    "node",
    "objects",
    "plane",
    "point_light",
    "read_exr",
    "rectangle",
    "render",
    "save",
    "scene",
    "sphere",
    "triangle",
]
