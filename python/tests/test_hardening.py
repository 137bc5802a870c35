"""Issue 12 ("Hardening") from Python: every bad value raises one error naming
the parameter or the key path and its bound, and no NaN reaches an answer."""

import decimal
import re

import numpy as np
import pytest

import lamplight

CAMERA = {"eye": [0, 0, 5], "look_at": [0, 0, 0], "vfov": 40}
SPHERE = {"type": "sphere", "center": [0, 0, 0], "radius": 1}


def scene_with(**parts):
    return {"camera": dict(CAMERA), "objects": [dict(SPHERE)], **parts}


@pytest.mark.parametrize(
    "kwargs, message",
    [
        (dict(width=2**32), "width must be at most 4294967295, got 4294967296"),
        (dict(height=-5), "height must be at least 1, got -5"),
        (dict(spp=2**40), "spp must be between 1 and 1048576, got 1099511627776"),
        (dict(threads=-1), "threads must be at least 0 (0 uses all cores), got -1"),
        (dict(threads=2**70), "threads must be at most 1024 (0 uses all cores), got 1180591620717411303424"),
        (dict(seed=-1), "seed must be at least 0, got -1"),
        (dict(seed=2**64), "seed must be at most 18446744073709551615, got 18446744073709551616"),
        (dict(max_depth=2**33), "max_depth must be between 1 and 64 (work grows as 2^depth), got 8589934592"),
        (dict(window=(0, 0, -1, 2)), "window width must be at least 0, got -1"),
    ],
)
def test_out_of_range_integers_name_the_parameter_and_its_bound(kwargs, message):
    with pytest.raises(ValueError, match="^" + re.escape(message) + "$"):
        lamplight.render(scene_with(), progress=False, **kwargs)


def test_intersect_threads_are_checked_by_name():
    with pytest.raises(ValueError, match="^" + re.escape("threads must be at least 0 (0 uses all cores), got -1") + "$"):
        lamplight.Scene(scene_with()).intersect(np.zeros((1, 3)), np.ones((1, 3)), threads=-1)


@pytest.mark.parametrize("z", [1e17, 1e30, 1e308])
def test_far_hits_keep_finite_normals(z):
    t, ids, _, normals = lamplight.Scene(scene_with()).intersect(np.array([[0.0, 0.0, z]]), np.array([[0.0, 0.0, -1.0]]))
    assert list(ids) == [0] and t[0] == z
    assert normals.tolist() == [[0.0, 0.0, 1.0]]


def exact_sphere_distance(origin, direction, center, radius):
    """The nearest root of |o + s d - c| = r, to 50 digits, as a distance."""
    with decimal.localcontext() as ctx:
        ctx.prec = 50
        o, d, c = ([decimal.Decimal(float(x)) for x in v] for v in (origin, direction, center))
        oc = [a - b for a, b in zip(o, c)]
        length = sum(x * x for x in d).sqrt()
        u = [x / length for x in d]
        b = sum(x * y for x, y in zip(u, oc))
        disc = b * b - (sum(x * x for x in oc) - decimal.Decimal(radius) ** 2)
        root = disc.sqrt()
        near, far = -b - root, -b + root
        return near if near > 0 else far


@pytest.mark.parametrize("dtype, farthest", [(np.float64, 1e13), (np.float32, 1e4)])
def test_distance_error_bounds_hold_and_say_where_precision_is_lost(dtype, farthest):
    rng = np.random.default_rng(7)
    center, radius = np.array([0.3, -0.2, 0.1]), 1.0
    scene = lamplight.Scene(scene_with(objects=[dict(SPHERE, center=center.tolist(), radius=radius)]))
    # Origins at every scale the dtype can still aim from, at random points of
    # the sphere's inner half-radius ball (no ray grazes it); then rays down the
    # z axis, aimed exactly from any height.
    scale = 10.0 ** rng.uniform(0, np.log10(farthest), 200)
    origins = rng.normal(size=(200, 3)) * scale[:, None]
    targets = center + rng.uniform(-0.28, 0.28, (200, 3))
    heights = 10.0 ** np.arange(1, 21)
    origins = np.vstack([origins, np.column_stack([np.full(20, 0.3), np.full(20, -0.2), heights])]).astype(dtype)
    directions = np.vstack([targets - origins[:200], np.tile([0.0, 0.0, -1.0], (20, 1))]).astype(dtype)
    t, ids, _, normals, t_error = scene.intersect(origins, directions, errors=True)
    assert t_error.dtype == dtype and (ids == 0).all() and np.isfinite(normals).all()
    for i in range(len(t)):
        exact = exact_sphere_distance(origins[i], directions[i], center, radius)
        off = abs(decimal.Decimal(float(t[i])) - exact)
        assert off <= decimal.Decimal(float(t_error[i])), f"ray {i}: t {t[i]} is {off} off, bound {t_error[i]}"
    # A few ulps of the magnitudes: far below the radius for near rays, above it
    # for those so far that the distance cannot resolve the sphere.
    eps = np.finfo(dtype).eps
    magnitude = np.abs(origins).max(axis=1).astype(np.float64) + t
    assert (t_error <= 64 * eps * (magnitude + 2)).all()
    axis_error = t_error[200:]
    assert (axis_error[heights * eps < 1e-4] < 0.01 * radius).all()
    assert (axis_error[heights * eps > 2] > radius).all()
    t, _, _, _, t_error = scene.intersect([[0.0, 0.0, 5.0]], [[0.0, 1.0, 0.0]], errors=True)
    assert (t[0], t_error[0]) == (np.inf, np.inf), "a miss"
    assert len(scene.intersect(origins, directions)) == 4, "without errors=True the answers are the four of before"


def garbage_mesh(tmp_path):
    path = tmp_path / "garbage.obj"
    path.write_bytes(np.random.default_rng(12).integers(0, 256, 4096, dtype=np.uint8).tobytes())
    return path


@pytest.mark.parametrize(
    "make, message",
    [
        (lambda t: scene_with(objects=[{"type": "group", "children": [dict(SPHERE, radius=-1)]}]),
         "scene dict: objects[0].children[0].radius: sphere: invalid radius: must be a positive number, got -1"),
        (lambda t: scene_with(objects=[dict(SPHERE, center=[0, 0, 0, 0])]),
         "scene dict: objects[0].center: sphere: center: expected [x, y, z], got an array of 4"),
        (lambda t: {"camera": dict(CAMERA, eye=[0, 0, 5, 123])}, "scene dict: camera.eye: camera: eye: expected [x, y, z], got an array of 4"),
        (lambda t: {"camera": dict(CAMERA, up=[0, 0, 0])},
         "scene dict: camera.up: camera: invalid up: is the zero vector [0, 0, 0], expected a direction"),
        (lambda t: scene_with(materials={"e": {"emission": 1e39}}),
         "scene dict: materials.e.emission: material \"e\": emission: must be at most 3.4028235e38 in magnitude (f32's largest), got [1e39, 1e39, 1e39]"),
        (lambda t: scene_with(objects=[{"type": "point_light", "position": [0, 0, 3], "intensity": 1e300}]),
         "scene dict: objects[0].intensity: point_light: intensity: must be at most 3.4028235e38 in magnitude (f32's largest), got [1e300, 1e300, 1e300]"),
        (lambda t: scene_with(materials={"m": {"reflection": {"type": "dielectric", "ior": 1.5, "min": 2, "max": -1}}}),
         "scene dict: materials.m.reflection.min: material \"m\": reflection: min: must be between 0 and 1, got 2"),
        (lambda t: scene_with(objects=[{"type": "implicit", "expression": "x*x + y*y + z*z - 1", "min": [1, 1, 1], "max": [-1, -1, -1], "lipschitz": 4}]),
         "scene dict: objects[0].max: implicit: max: min [1, 1, 1] must be below max [-1, -1, -1] on every axis"),
        (lambda t: scene_with(meshes={"m": {"file": ""}}, objects=[{"type": "mesh", "mesh": "m"}]),
         "scene dict: meshes.m.file: mesh \"m\": file: the path is empty, expected a mesh file"),
        (lambda t: scene_with(meshes={"m": {"file": str(garbage_mesh(t))}}, objects=[{"type": "mesh", "mesh": "m"}]),
         "scene dict: meshes.m.file: mesh \"m\": {tmp}/garbage.obj: has no triangles, expected a mesh"),
    ],
)
def test_builder_errors_keep_their_key_path(tmp_path, make, message):
    with pytest.raises(lamplight.SceneError) as info:
        lamplight.render(make(tmp_path), width=4, height=4, progress=False)
    assert str(info.value) == message.replace("{tmp}", str(tmp_path))


def test_a_scene_without_lights_warns_when_rendered():
    dark = lamplight.Scene(scene_with())
    with pytest.warns(UserWarning, match="the scene has no lights"):
        image = lamplight.render(dark, width=8, height=8, progress=False)
    assert image.stats["warnings"] == ["the scene has no lights: add a light, an emitting material, a background or an ambient term"]
    lit = lamplight.Scene(scene_with(objects=[dict(SPHERE), {"type": "point_light", "position": [0, 0, 5], "intensity": 1}]))
    assert lamplight.render(lit, width=8, height=8, progress=False).stats["warnings"] == []


def test_an_implicit_surface_steeper_than_its_bound_warns():
    loose = {
        "type": "implicit",
        "expression": "10 * (sqrt(x*x + y*y + z*z) - 1)",
        "min": [-1.5, -1.5, -1.5],
        "max": [1.5, 1.5, 1.5],
        "lipschitz": 2,
    }
    s = lamplight.Scene({"ambient": 0.2, "camera": dict(CAMERA), "objects": [loose]})
    with pytest.warns(UserWarning, match="implicit surface: f changed by .* above its lipschitz = 2"):
        lamplight.render(s, width=16, height=16, progress=False)
