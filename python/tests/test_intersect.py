"""Scene.intersect against a brute force in numpy, against `lamplight raycast`
(the same batch API: the same numbers), and its argument checks."""

import subprocess

import numpy as np
import pytest

import lamplight

SPHERES = [([0.0, 0.0, 0.0], 1.0), ([2.5, 0.5, -1.0], 0.75), ([-2.0, -0.5, 1.0], 0.5)]
TRIANGLE = np.array([[-3.0, -2.0, -3.0], [3.0, -2.0, -3.0], [0.0, 3.0, -3.5]])


def scene():
    return lamplight.Scene.from_dict(
        lamplight.scene(
            camera=lamplight.camera(eye=[0, 0, 8], look_at=[0, 0, 0]),
            meshes={"tri": lamplight.objects.mesh_data(TRIANGLE, [[0, 1, 2]])},
            objects=[lamplight.sphere(c, r) for c, r in SPHERES] + [lamplight.mesh("tri")],
        )
    )


def brute_force(origins, directions):
    """Nearest t > 0 along unit directions, object id and outward normal."""
    d = directions / np.linalg.norm(directions, axis=1, keepdims=True)
    n = len(origins)
    best_t = np.full(n, np.inf)
    best_id = np.full(n, -1)
    best_normal = np.zeros((n, 3))
    for i, (c, r) in enumerate(SPHERES):
        oc = origins - np.array(c)
        b = np.sum(oc * d, axis=1)
        disc = b * b - (np.sum(oc * oc, axis=1) - r * r)
        sq = np.sqrt(np.maximum(disc, 0))
        for t in (-b - sq, -b + sq):
            hit = (disc >= 0) & (t > 1e-9) & (t < best_t)
            best_t[hit], best_id[hit] = t[hit], i
            best_normal[hit] = (origins[hit] + t[hit, None] * d[hit] - np.array(c)) / r
    # Moller-Trumbore for the triangle.
    a, b_, c_ = TRIANGLE
    e1, e2 = b_ - a, c_ - a
    p = np.cross(d, e2)
    det = p @ e1
    inv = 1.0 / np.where(det == 0, np.nan, det)
    s = origins - a
    u = np.sum(s * p, axis=1) * inv
    q = np.cross(s, e1)
    v = np.sum(d * q, axis=1) * inv
    t = (q @ e2) * inv
    hit = (u >= 0) & (v >= 0) & (u + v <= 1) & (t > 1e-9) & (t < best_t)
    normal = np.cross(e1, e2)
    best_t[hit], best_id[hit] = t[hit], len(SPHERES)
    best_normal[hit] = normal / np.linalg.norm(normal)
    return best_t, best_id, best_normal


def rays(n, dtype, seed=1):
    rng = np.random.default_rng(seed)
    origins = rng.uniform(-1, 1, (n, 3)) + np.array([0.0, 0.0, 6.0])
    targets = rng.uniform([-3.5, -2.5, -3.0], [3.5, 2.5, 1.0], (n, 3))
    return origins.astype(dtype), (targets - origins).astype(dtype)


@pytest.mark.parametrize("dtype", [np.float64, np.float32])
def test_intersect_matches_brute_force(dtype):
    origins, directions = rays(20_000, dtype)
    t, ids, prims, normals = scene().intersect(origins, directions)
    assert t.dtype == dtype and normals.dtype == dtype and ids.dtype == np.int64 and prims.dtype == np.int64
    assert t.shape == (20_000,) and ids.shape == (20_000,) and prims.shape == (20_000,) and normals.shape == (20_000, 3)
    et, eid, enormal = brute_force(origins.astype(np.float64), directions.astype(np.float64))
    # Rays grazing an edge may go either way within rounding; they are very few.
    agree = ids == eid
    assert agree.mean() > 0.999, f"{(~agree).sum()} rays disagree"
    hit = agree & (eid >= 0)
    assert hit.sum() > 5_000 and (eid == -1).sum() > 1_000, "both hits and misses are tested"
    assert set(np.unique(eid[hit])) == {0, 1, 2, 3}
    tol = 1e-9 if dtype == np.float64 else 1e-4
    np.testing.assert_allclose(t[hit], et[hit], rtol=tol * 10, atol=tol)
    np.testing.assert_allclose(normals[hit], enormal[hit], atol=tol * 100)
    miss = agree & (eid == -1)
    assert np.all(np.isinf(t[miss])) and np.all(normals[miss] == 0)
    # Spheres are not meshes; the triangle is face 0 of the mesh object 3.
    assert np.all(prims[ids == 3] == 0) and np.all(prims[ids != 3] == -1)


def test_threads_do_not_change_answers_and_inputs_need_not_be_contiguous():
    origins, directions = rays(3_000, np.float64, seed=2)
    s = scene()
    a = s.intersect(origins, directions, threads=1)
    b = s.intersect(origins, directions, threads=2)
    wide_o = np.zeros((3_000, 6))
    wide_o[:, ::2] = origins
    c = s.intersect(wide_o[:, ::2], np.asfortranarray(directions))
    for x, y, z in zip(a, b, c):
        assert x.tobytes() == y.tobytes() == z.tobytes()


def test_degenerate_rays_miss():
    origins = np.array([[0, 0, 5], [np.nan, 0, 5], [0, 0, 5]], dtype=np.float64)
    directions = np.array([[0, 0, 0], [0, 0, -1], [0, 0, -1]], dtype=np.float64)
    t, ids, prims, _ = scene().intersect(origins, directions)
    assert list(ids) == [-1, -1, 0] and list(prims) == [-1, -1, -1]
    assert t[2] == pytest.approx(4.0)


def test_t_is_a_distance_whatever_the_direction_length():
    origins = np.array([[0, 0, 5]] * 3, dtype=np.float64)
    directions = np.array([[0, 0, -1], [0, 0, -0.125], [0, 0, -64]], dtype=np.float64)
    t, ids, _, _ = scene().intersect(origins, directions)
    assert list(t) == [4.0, 4.0, 4.0] and list(ids) == [0, 0, 0]


def height_field(n=20):
    """A bumpy (n x n)-vertex sheet, two triangles per cell."""
    x, y = np.meshgrid(np.linspace(-1, 1, n), np.linspace(-1, 1, n))
    z = 0.2 * np.sin(3 * x) * np.cos(2 * y)
    positions = np.stack([x, y, z], axis=-1).reshape(-1, 3).astype(np.float32)
    k = np.arange(n * n).reshape(n, n)[:-1, :-1].ravel()
    indices = np.concatenate([np.stack([k, k + 1, k + n + 1], 1), np.stack([k, k + n + 1, k + n], 1)]).astype(np.int32)
    return positions, indices


def test_python_and_the_command_line_give_the_same_numbers(cli, tmp_path):
    positions, indices = height_field()
    rng = np.random.default_rng(7)
    n = 4_000
    origins = (rng.uniform(-1.2, 1.2, (n, 3)) + [0, 0, 2]).astype(np.float32)
    targets = rng.uniform([-1.3, -1.3, -0.3], [1.3, 1.3, 0.3], (n, 3))
    # Directions of every length, not only unit ones.
    directions = ((targets - origins) * rng.uniform(0.01, 100, (n, 1))).astype(np.float32)
    for name, array in [("v", positions), ("i", indices), ("o", origins), ("d", directions)]:
        np.save(tmp_path / f"{name}.npy", array)
    out = {k: str(tmp_path / f"{k}.npy") for k in ("t", "p", "obj")}
    subprocess.run(
        [cli, "raycast", "--vertices", str(tmp_path / "v.npy"), "--indices", str(tmp_path / "i.npy"),
         "--origins", str(tmp_path / "o.npy"), "--directions", str(tmp_path / "d.npy"),
         "-o", out["t"], "--prims", out["p"], "--objects", out["obj"], "--threads", "2"],
        check=True, capture_output=True,
    )
    cli_t, cli_p, cli_obj = np.load(out["t"]), np.load(out["p"]), np.load(out["obj"])
    mesh_scene = lamplight.Scene.from_dict(
        lamplight.scene(
            camera=lamplight.camera(eye=[0, 0, 8], look_at=[0, 0, 0]),
            meshes={"sheet": lamplight.objects.mesh_data(positions, indices)},
            objects=[lamplight.mesh("sheet")],
        )
    )
    t, ids, prims, _ = mesh_scene.intersect(origins, directions)
    assert t.dtype == cli_t.dtype == np.float32
    np.testing.assert_array_equal(ids, cli_obj)
    hit = ids >= 0
    assert 1_000 < hit.sum() < n, "both hits and misses"
    assert np.all(np.isinf(cli_t[~hit])) and np.all(cli_p[~hit] == -1)
    # float32 (the command line) against float64 (the scene) geometry: t within
    # float32 rounding, and the same triangle except on shared edges.
    np.testing.assert_allclose(cli_t[hit], t[hit], rtol=2e-6)
    assert (prims[hit] != cli_p[hit]).sum() <= 2


@pytest.mark.parametrize(
    "origins, directions, error, message",
    [
        ("0 0 0", np.zeros((1, 3)), TypeError, "origins must be a numpy array \\(or a list of rows\\) of shape \\(N, 3\\), got str"),
        ([[0, 0, 0], [1, 2]], np.zeros((2, 3)), ValueError, "origins must be rows of three numbers, shape \\(N, 3\\): "),
        ([[0, 0]], np.zeros((1, 3)), ValueError, "origins must have shape \\(N, 3\\), got \\[1, 2\\]"),
        (np.zeros((4, 2)), np.zeros((4, 3)), ValueError, "origins must have shape \\(N, 3\\), got \\[4, 2\\]"),
        (np.zeros(3), np.zeros((1, 3)), ValueError, "origins must have shape \\(N, 3\\)"),
        (np.zeros((4, 3)), np.zeros((5, 3)), ValueError, "same number of rows, got 4 and 5"),
        (np.zeros((4, 3), dtype=np.int64), np.zeros((4, 3)), TypeError, "must both be float32 or both float64 arrays"),
        (np.zeros((4, 3), dtype=np.float32), np.zeros((4, 3)), TypeError, "must both be float32 or both float64 arrays"),
    ],
)
def test_bad_arrays_raise_clear_errors(origins, directions, error, message):
    with pytest.raises(error, match=message):
        scene().intersect(origins, directions)


def test_lists_are_rays_too():
    origins = [[0.0, 0.5, 5.0], [9.0, 9.0, 9.0]]
    directions = ((0, 0, -1), (0, 0, 1))
    expected = scene().intersect(np.array(origins), np.array(directions, dtype=np.float64))
    for o, d in [(origins, directions), (np.array(origins), directions), (origins, np.array(directions, dtype=np.float64))]:
        got = scene().intersect(o, d)
        for a, b in zip(got, expected):
            np.testing.assert_array_equal(a, b)
    # A list beside a float32 array becomes float32: the answers are float32.
    t32 = scene().intersect(np.array(origins, dtype=np.float32), directions)[0]
    assert t32.dtype == np.float32 and np.isfinite(t32[0]) and np.isinf(t32[1])


def test_thread_counts_are_bounded():
    with pytest.raises(ValueError, match="threads must be at most 1024 \\(0 uses all cores\\), got 1025"):
        scene().intersect(np.zeros((1, 3)), np.ones((1, 3)), threads=1025)
