"""Scene dicts: same schema and builder as scene files, errors that name the key."""

import pickle
import tomllib

import numpy as np
import pytest

import lamplight
from conftest import EXAMPLES


def small(scene, **kw):
    return lamplight.render(scene, width=kw.pop("width", 48), height=kw.pop("height", 27), progress=False, **kw)


@pytest.mark.parametrize("name", ["spheres", "luxo", "business-card"])
def test_dict_from_toml_renders_the_same_bytes_as_the_file(name):
    path = EXAMPLES / f"{name}.toml"
    with open(path, "rb") as f:
        as_dict = tomllib.load(f)
    from_file = small(lamplight.Scene.from_file(path), spp=2)
    from_dict = small(lamplight.Scene.from_dict(as_dict, base_dir=EXAMPLES), spp=2)
    assert from_file.tobytes() == from_dict.tobytes()
    assert from_file.max() > 0


def test_builtin_file_and_dict_agree():
    with open(EXAMPLES / "spheres.toml", "rb") as f:
        as_dict = tomllib.load(f)
    a = small("spheres")
    b = small(as_dict)
    c = small(str(EXAMPLES / "spheres.toml"))
    assert a.tobytes() == b.tobytes() == c.tobytes()


def test_constructors_build_a_scene():
    s = lamplight.scene(
        camera=lamplight.camera(eye=[0, 1, 5], look_at=[0, 0, 0], vfov=40),
        materials={"red": lamplight.material(color=[0.9, 0.1, 0.1], ks=0.3, shininess=40)},
        objects=[
            lamplight.sphere([0, 0, 0], 1, material="red"),
            lamplight.plane([0, -1, 0], [0, 1, 0]),
            lamplight.group([lamplight.box([-0.2, -0.2, -0.2], [0.2, 0.2, 0.2])], translate=(1.5, 0, 0)),
            lamplight.point_light([5, 5, 5], 60),
        ],
        ambient=0.1,
    )
    image = small(s)
    assert image.shape == (27, 48, 3)
    centre = image[13, 24]
    assert centre[0] > centre[1], "the sphere is red"


def test_numpy_arrays_and_tuples_are_accepted():
    s = lamplight.scene(
        camera=lamplight.camera(eye=np.array([0.0, 0.0, 4.0]), look_at=(0, 0, 0)),
        meshes={"tri": lamplight.objects.mesh_data(np.array([[-1, -1, 0], [1, -1, 0], [0, 1, 0]], dtype=np.float32), np.array([[0, 1, 2]]))},
        objects=[lamplight.mesh("tri"), lamplight.point_light(np.float64(3) * np.ones(3), 30)],
        ambient=np.float32(0.2),
    )
    image = small(s)
    assert image[13, 24].sum() > 0, "the triangle is in the middle"


@pytest.mark.parametrize(
    "change, message",
    [
        (lambda d: d["objects"].__setitem__(1, {"type": "sphere", "center": [0, 0, 0], "radius": "big"}), "objects[1].radius"),
        (lambda d: d["camera"].__setitem__("colour", 1), "scene dict: camera.colour: camera: unknown parameter 'colour'"),
        (lambda d: d.__setitem__("render", {"spp": -1}), "render.spp"),
        (lambda d: d["objects"].__setitem__(0, {"type": "sphere", "center": [0, 0, 0], "radius": -1}), "invalid radius"),
        (lambda d: d["objects"].__setitem__(0, {"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "gold"}), "unknown material"),
        (lambda d: d.pop("camera"), "camera"),
    ],
)
def test_bad_dicts_raise_scene_errors_naming_the_problem(change, message):
    d = lamplight.scene(
        camera=lamplight.camera(eye=[0, 0, 5], look_at=[0, 0, 0]),
        objects=[lamplight.sphere([0, 0, 0], 1), lamplight.sphere([1, 0, 0], 0.5)],
    )
    change(d)
    with pytest.raises(lamplight.SceneError, match=message.replace("[", r"\[").replace("]", r"\]")):
        lamplight.Scene.from_dict(d).build()
    assert issubclass(lamplight.SceneError, ValueError)


def test_dict_errors_are_the_file_errors_with_the_key_path(tmp_path):
    # The same mistake in a dict and in a TOML file gives the same message;
    # only the place differs (the key path instead of line:column).
    d = lamplight.scene(camera=lamplight.camera(eye=[0, 0, 5], look_at=[0, 0, 0]), objects=[{"type": "sphere", "center": [0, 0, 0], "radious": 1}])
    with pytest.raises(lamplight.SceneError) as from_dict:
        lamplight.Scene.from_dict(d).build()
    text = '[camera]\neye = [0, 0, 5]\nlook_at = [0, 0, 0]\nvfov = 40\n[[objects]]\ntype = "sphere"\ncenter = [0, 0, 0]\nradious = 1\n'
    (tmp_path / "s.toml").write_text(text)
    with pytest.raises(lamplight.SceneError) as from_file:
        lamplight.Scene(str(tmp_path / "s.toml")).build()
    message = "sphere: unknown parameter 'radious' (did you mean 'radius'?)"
    assert str(from_dict.value) == f"scene dict: objects[0].radious: {message}"
    assert str(from_file.value) == f"{tmp_path / 's.toml'}:8:1: {message}"


def test_scene_arguments_of_the_wrong_kind():
    with pytest.raises(TypeError, match="built-in name, a file path, a dict"):
        lamplight.render(42)
    with pytest.raises(ValueError, match='unknown scene "nope"'):
        lamplight.render("nope")
    with pytest.raises(ValueError, match="unknown scene file type"):
        lamplight.Scene("scene.txt")
    with pytest.raises(lamplight.SceneError, match="no such file"):
        lamplight.Scene("missing.toml")
    with pytest.raises(FileNotFoundError):
        lamplight.load("missing.obj")
    with pytest.raises(TypeError, match="keys must be strings"):
        lamplight.Scene.from_dict({1: 2})


def test_mesh_file_paths_resolve_against_base_dir(tmp_path):
    (tmp_path / "meshes").mkdir()
    (tmp_path / "meshes" / "tri.obj").write_text("v -1 -1 0\nv 1 -1 0\nv 0 1 0\nf 1 2 3\n")
    d = lamplight.scene(
        camera=lamplight.camera(eye=[0, 0, 4], look_at=[0, 0, 0]),
        meshes={"tri": lamplight.objects.mesh_file("meshes/tri.obj")},
        objects=[lamplight.mesh("tri"), lamplight.point_light([0, 0, 4], 30)],
        ambient=0.2,
    )
    with pytest.raises(lamplight.SceneError, match="not found"):
        lamplight.Scene.from_dict(d).build()
    scene = lamplight.Scene.from_dict(d, base_dir=tmp_path)
    assert scene.mesh_files() == ["meshes/tri.obj"]
    assert small(scene)[13, 24].sum() > 0
    mesh_scene = lamplight.load(tmp_path / "meshes" / "tri.obj")
    assert mesh_scene.kind == "mesh"
    assert small(mesh_scene).max() > 0


@pytest.mark.parametrize("make", [
    lambda: lamplight.Scene("spheres"),
    lambda: lamplight.Scene.from_file(EXAMPLES / "luxo.toml"),
    lambda: lamplight.Scene.from_dict(tomllib.loads((EXAMPLES / "spheres.toml").read_text())),
    lambda: lamplight.Scene("business-card").with_camera({"eye": [0, 2, 9], "look_at": [0, 0, 0], "vfov": 50}),
])
def test_scenes_pickle_as_their_description(make):
    scene = make()
    scene.build(48, 27)
    data = pickle.dumps(scene)
    assert len(data) < 200_000, "no built data in the pickle"
    again = pickle.loads(data)
    assert again.kind == scene.kind and repr(again) == repr(scene)
    assert small(again).tobytes() == small(scene).tobytes()


def test_with_camera_moves_the_view():
    scene = lamplight.Scene("spheres")
    moved = scene.with_camera({"eye": [0, 20, 0.1], "look_at": [0, 0, 0], "vfov": 60})
    assert small(moved).tobytes() != small(scene).tobytes()
    with pytest.raises(lamplight.SceneError, match="camera"):
        scene.with_camera({"eye": [0, 1, 2], "lookat": [0, 0, 0]})


def test_every_registered_node_kind_has_a_constructor():
    kinds = lamplight.kinds()
    names = {k["name"] for k in kinds if k["role"] in ("shape", "light", "node")}
    assert {"sphere", "spot_light", "group", "implicit"} <= names
    for name in names:
        make = getattr(lamplight.objects, name)
        assert make.__name__ == name
    sphere = next(k for k in kinds if k["name"] == "sphere")
    assert [p["name"] for p in sphere["params"]] == ["center", "radius", "material", "flip_normals"]
    assert sphere["params"][1]["default"] is None, "radius is required"
    spot = lamplight.objects.spot_light(position=[0, 3, 0], look_at=[0, 0, 0], intensity=40, outer_angle=30)
    assert spot == {"type": "spot_light", "position": [0, 3, 0], "look_at": [0, 0, 0], "intensity": 40, "outer_angle": 30}
    s = lamplight.scene(
        camera=lamplight.camera(eye=[0, 3, 0.01], look_at=[0, 0, 0], vfov=60),
        objects=[lamplight.rectangle([-5, 0, -5], [0, 0, 10], [10, 0, 0]), spot],
    )
    image = lamplight.render(s, width=32, height=32, progress=False)
    assert image[16, 16].sum() > 0 and image[0, 0].sum() == 0, "lit inside the cone, dark outside"
    with pytest.raises(AttributeError):
        lamplight.objects.no_such_kind


def test_blend_and_pbr_transmission_in_dicts():
    # The same kinds as scene files: a blend of a named and an inline material,
    # and a pbr material with a textured transmission, in a white furnace.
    camera = {"type": "orthographic", "eye": [0.5, 0.5, 5], "look_at": [0.5, 0.5, 0], "half_width": 0.5, "half_height": 0.5}
    square = {"type": "rectangle", "corner": [0, 0, 0], "edge_u": [1, 0, 0], "edge_v": [0, 1, 0], "material": "m"}
    matte = {"color": 1, "kd": 0.8, "ka": 0, "ks": 0}
    mirror = {"color": 1, "kd": 0, "ka": 0, "ks": 0, "reflection": {"type": "constant", "weight": 1}}
    blend = {"background": 1, "camera": camera, "objects": [square],
             "materials": {"matte": matte, "m": {"type": "blend", "a": "matte", "b": mirror, "weight": 0.5}}}
    image = small(blend, width=8, height=8, spp=64, integrator="path")
    assert abs(image.mean() - 0.9) < 0.02, image.mean()
    pane = {"type": "pbr", "base_color": 1, "metallic": 0, "roughness": 0,
            "transmission": {"type": "uv_checker", "even": 0, "odd": 1, "uv_scale": [2, 1]}}
    clear = {"background": 1, "camera": camera, "objects": [square], "materials": {"m": pane}}
    image = small(clear, width=8, height=8, spp=64, integrator="path")
    assert abs(image.mean() - 1.0) < 0.01, image.mean()
    with pytest.raises(Exception, match=r"materials.m.a: material \"m\": a: the blend contains itself \(m -> m\)"):
        small({**blend, "materials": {"m": {"type": "blend", "a": "m", "b": {}}}}, width=4, height=4, spp=1)
