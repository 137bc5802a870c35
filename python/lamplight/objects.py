"""Constructors for the common parts of a scene dict.

Each function returns a plain dict with the keys of ``docs/scene-format.md``
(``None`` arguments are left out, so the format's defaults apply), and
:func:`scene` puts them together. The result is an ordinary scene dict: print
it, change it, pickle it, or pass it to :func:`lamplight.render`.

>>> import lamplight as ll
>>> s = ll.scene(
...     camera=ll.camera(eye=[0, 1, 5], look_at=[0, 0, 0], vfov=40),
...     materials={"red": ll.material(color=[0.9, 0.1, 0.1], ks=0.3, shininess=40)},
...     objects=[ll.sphere([0, 0, 0], 1, material="red"), ll.point_light([5, 5, 5], 60)],
...     ambient=0.1,
... )
>>> s["objects"][0]
{'type': 'sphere', 'center': [0, 0, 0], 'radius': 1, 'material': 'red'}
"""

from __future__ import annotations

from typing import Any, Dict, List, Optional, Sequence, Union

Vec = Sequence[float]
Colour = Union[float, Sequence[float]]


def _clean(d: Dict[str, Any]) -> Dict[str, Any]:
    return {k: (list(v) if isinstance(v, tuple) else v) for k, v in d.items() if v is not None}


def _node(kind: str, **keys: Any) -> Dict[str, Any]:
    return _clean({"type": kind, **keys})


def scene(
    camera: Dict[str, Any],
    objects: Sequence[Dict[str, Any]] = (),
    materials: Optional[Dict[str, Dict[str, Any]]] = None,
    meshes: Optional[Dict[str, Dict[str, Any]]] = None,
    definitions: Optional[Dict[str, Dict[str, Any]]] = None,
    ambient: Optional[Colour] = None,
    background: Optional[Colour] = None,
    render: Optional[Dict[str, Any]] = None,
) -> Dict[str, Any]:
    """A whole scene dict (the top level of a scene file)."""
    return _clean(
        {
            "ambient": ambient,
            "background": background,
            "render": render,
            "camera": camera,
            "materials": materials,
            "meshes": meshes,
            "definitions": definitions,
            "objects": list(objects),
        }
    )


def camera(
    eye: Vec,
    look_at: Vec,
    vfov: Optional[float] = None,
    hfov: Optional[float] = None,
    up: Optional[Vec] = None,
    pixel_offset: Optional[float] = None,
    fov: Optional[float] = None,
) -> Dict[str, Any]:
    """A look-at camera; ``vfov`` (default 40 when none is given), ``hfov`` or
    ``fov`` (across the image's shorter side, pbrt's) in degrees."""
    if vfov is None and hfov is None and fov is None:
        vfov = 40.0
    return _clean(
        {"eye": eye, "look_at": look_at, "vfov": vfov, "hfov": hfov, "fov": fov, "up": up, "pixel_offset": pixel_offset}
    )


def material(
    color: Optional[Colour] = None,
    ka: Optional[Colour] = None,
    kd: Optional[Colour] = None,
    ks: Optional[Colour] = None,
    shininess: Optional[float] = None,
    emission: Optional[Colour] = None,
    reflection: Optional[Dict[str, Any]] = None,
    refraction: Optional[Dict[str, Any]] = None,
    shadow_transmittance: Optional[Colour] = None,
    checker: Optional[Dict[str, Any]] = None,
) -> Dict[str, Any]:
    """A material table (the lecture's Phong-Blinn terms, mirror, refraction)."""
    return _clean(
        {
            "color": color,
            "checker": checker,
            "ka": ka,
            "kd": kd,
            "ks": ks,
            "shininess": shininess,
            "emission": emission,
            "reflection": reflection,
            "refraction": refraction,
            "shadow_transmittance": shadow_transmittance,
        }
    )


def sphere(center: Vec, radius: float, material: Optional[str] = None, name: Optional[str] = None) -> Dict[str, Any]:
    """A sphere node."""
    return _node("sphere", center=center, radius=radius, material=material, name=name)


def plane(point: Vec, normal: Vec, material: Optional[str] = None, name: Optional[str] = None) -> Dict[str, Any]:
    """An infinite plane node; ``normal`` is the outward side."""
    return _node("plane", point=point, normal=normal, material=material, name=name)


def rectangle(corner: Vec, edge_u: Vec, edge_v: Vec, material: Optional[str] = None, name: Optional[str] = None) -> Dict[str, Any]:
    """A parallelogram node with outward normal ``edge_u x edge_v``."""
    return _node("rectangle", corner=corner, edge_u=edge_u, edge_v=edge_v, material=material, name=name)


def disk(center: Vec, normal: Vec, radius: float, material: Optional[str] = None, name: Optional[str] = None) -> Dict[str, Any]:
    """A disk node."""
    return _node("disk", center=center, normal=normal, radius=radius, material=material, name=name)


def box(min: Vec, max: Vec, material: Optional[str] = None, name: Optional[str] = None) -> Dict[str, Any]:  # noqa: A002
    """An axis-aligned box node."""
    return _node("box", min=min, max=max, material=material, name=name)


def triangle(vertices: Sequence[Vec], material: Optional[str] = None, name: Optional[str] = None) -> Dict[str, Any]:
    """A triangle node (outward normal by the right-hand rule)."""
    return _node("triangle", vertices=[list(v) for v in vertices], material=material, name=name)


def mesh(mesh: str, material: Optional[str] = None, name: Optional[str] = None) -> Dict[str, Any]:
    """A node placing the mesh asset ``mesh`` (a key of the scene's ``meshes``)."""
    return _node("mesh", mesh=mesh, material=material, name=name)


def mesh_file(file: str) -> Dict[str, Any]:
    """A mesh asset read from an OBJ, PLY or glTF file (for the scene's ``meshes``)."""
    return {"file": file}


def mesh_data(positions: Any, indices: Any, normals: Any = None) -> Dict[str, Any]:
    """A mesh asset from arrays (numpy arrays are fine): positions ``(V, 3)``,
    triangle indices ``(T, 3)``, optional per-vertex normals ``(V, 3)``."""
    return _clean({"positions": positions, "indices": indices, "normals": normals})


def point_light(
    position: Vec, intensity: Colour, falloff: Optional[str] = None, own_object: Optional[str] = None
) -> Dict[str, Any]:
    """A point light node (``falloff``: ``"inverse_square"``, the default, or ``"none"``)."""
    return _node("point_light", position=position, intensity=intensity, falloff=falloff, own_object=own_object)


def directional_light(direction: Vec, radiance: Colour) -> Dict[str, Any]:
    """A light from infinitely far, travelling along ``direction``."""
    return _node("directional_light", direction=direction, radiance=radiance)


def group(
    children: Sequence[Dict[str, Any]],
    translate: Optional[Vec] = None,
    rotate: Optional[Dict[str, Any]] = None,
    scale: Optional[Colour] = None,
    material: Optional[str] = None,
    name: Optional[str] = None,
) -> Dict[str, Any]:
    """A group node: ``children`` move with its transform."""
    return _node(
        "group", children=list(children), translate=translate, rotate=rotate, scale=scale, material=material, name=name
    )


def node(type: str, **params: Any) -> Dict[str, Any]:  # noqa: A002
    """A node of any registered kind (``lamplight.kinds()``): ``type`` and its
    parameters as keywords, for example
    ``node("spot_light", position=[0, 4, 0], look_at=[0, 0, 0], intensity=50)``."""
    return _node(type, **params)


def _constructor(kind: Dict[str, Any]):
    def make(**params: Any) -> Dict[str, Any]:
        return _node(kind["name"], **params)

    rows = "\n".join(
        f"    {p['name']} ({p['type']}{'' if p['default'] is None else ', default ' + p['default']}): {p['doc']}" for p in kind["params"]
    )
    make.__name__ = make.__qualname__ = kind["name"]
    make.__doc__ = f"A {kind['name']} node: {kind['summary']}.\n\nKeyword parameters:\n{rows}"
    return make


def __getattr__(name: str):
    """Constructors for registered node kinds without a hand-written one here
    (``lamplight.objects.spot_light(position=..., ...)``), made from the registry."""
    from . import _lamplight

    for kind in _lamplight.kinds():
        if kind["name"] == name and kind["role"] in ("shape", "light", "node"):
            return _constructor(kind)
    raise AttributeError(f"module 'lamplight.objects' has no attribute {name!r}")


def instance(
    of: str,
    translate: Optional[Vec] = None,
    rotate: Optional[Dict[str, Any]] = None,
    scale: Optional[Colour] = None,
    material: Optional[str] = None,
) -> Dict[str, Any]:
    """A node placing the definition ``of``."""
    return _node("instance", of=of, translate=translate, rotate=rotate, scale=scale, material=material)


__all__: List[str] = [
    "box",
    "camera",
    "directional_light",
    "disk",
    "group",
    "instance",
    "material",
    "mesh",
    "mesh_data",
    "mesh_file",
    "node",
    "plane",
    "point_light",
    "rectangle",
    "scene",
    "sphere",
    "triangle",
]
