"""lamplight.dask on a LocalCluster: the same bytes as a local render, frames,
shipped meshes, and a worker killed in the middle of a render."""

import os
import signal

import numpy as np
import pytest

import lamplight
from conftest import EXAMPLES

distributed = pytest.importorskip("distributed")
import lamplight.dask  # noqa: E402  (after the skip: it needs distributed at call time only)


def local(scene, **kw):
    return lamplight.render(scene, progress=False, **kw)


@pytest.mark.parametrize(
    "scene, args",
    [
        ("spheres", dict(width=96, height=54, spp=2, tiles=7)),
        ("cornell-box", dict(width=32, height=32, spp=4, integrator="path", tiles=(3, 2))),
        ("luxo", dict(width=64, height=36, tiles=64)),
        # Settings come from the one table: clamp and the noise threshold reach the tasks too.
        ("cornell-box", dict(width=24, height=24, spp=16, integrator="path", clamp=0.5, noise_threshold=0.2, min_spp=4, tiles=5)),
    ],
)
def test_dask_render_equals_the_local_render(client, scene, args):
    tiles = args.pop("tiles")
    remote = lamplight.dask.render(scene, client, tiles=tiles, **args)
    assert remote.shape == (args["height"], args["width"], 3) and remote.dtype == np.float32
    assert remote.tobytes() == local(scene, **args).tobytes()


def test_a_denoised_cluster_render_equals_the_denoised_local_render(client, oidn):
    args = dict(width=32, height=32, spp=8, integrator="path")
    remote = lamplight.dask.render("cornell-box", client, tiles=(2, 2), denoise=True, **args)
    assert remote.tobytes() == local("cornell-box", denoise=True, **args).tobytes()
    # Tile by tile the edges would show: each tile denoised alone differs from the whole.
    noisy = local("cornell-box", exr_layers=["albedo", "normal"], **args)
    quarter = lamplight.denoise(noisy[:16, :16], noisy.layers["albedo"][:16, :16], noisy.layers["normal"][:16, :16])
    assert np.abs(quarter - remote[:16, :16]).max() > 1e-3


def test_workers_keep_the_build_between_renders(client):
    scene = lamplight.Scene.from_file(EXAMPLES / "spheres.toml")
    digest = lamplight.dask._digest(scene)

    def builds():
        import lamplight.dask as d

        return d._WORKER_SCENES.get(digest) is not None and id(d._WORKER_SCENES[digest])

    first = lamplight.dask.render(scene, client, width=32, height=18, tiles=8)
    kept = {w: b for w, b in client.run(builds).items() if b}
    assert kept, "the workers built the scene"
    second = lamplight.dask.render(scene, client, width=32, height=18, tiles=8)
    after = client.run(builds)
    assert all(after[w] == b for w, b in kept.items()), "the second render used the same built scenes"
    assert first.tobytes() == second.tobytes()


def test_tile_windows_cover_the_image_once():
    for w, h, tiles in [(96, 54, 7), (5, 3, 100), (640, 360, 64), (10, 10, (3, 4))]:
        cover = np.zeros((h, w), dtype=int)
        for x0, y0, tw, th in lamplight.dask.tile_windows(w, h, tiles):
            assert tw > 0 and th > 0
            cover[y0 : y0 + th, x0 : x0 + tw] += 1
        assert (cover == 1).all()
    with pytest.raises(ValueError):
        lamplight.dask.tile_windows(10, 10, 0)


def test_frames_from_a_camera_path_and_from_a_list(client):
    cameras = [{"eye": [10 * np.sin(a), 5, 10 * np.cos(a)], "look_at": [0, 0, 0], "vfov": 40} for a in np.linspace(0, 1, 3)]
    frames = lamplight.dask.render_frames("spheres", client, cameras=cameras, width=48, height=27)
    assert len(frames) == 3
    for camera, frame in zip(cameras, frames):
        assert frame.tobytes() == local(lamplight.Scene("spheres").with_camera(camera), width=48, height=27).tobytes()
    assert frames[0].tobytes() != frames[2].tobytes()
    listed = lamplight.dask.render_frames(["business-card", "spheres"], client, width=20, height=20)
    assert [f.tobytes() for f in listed] == [local(s, width=20, height=20).tobytes() for s in ["business-card", "spheres"]]


def test_meshes_are_read_on_workers_or_shipped(client, tmp_path):
    folder = tmp_path / "scene"
    (folder / "meshes").mkdir(parents=True)
    (folder / "meshes" / "quad.obj").write_text("mtllib quad.mtl\nv -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nusemtl m\nf 1 2 3 4\n")
    (folder / "meshes" / "quad.mtl").write_text("newmtl m\nKd 0.8 0.3 0.1\n")
    d = lamplight.scene(
        camera=lamplight.camera(eye=[0, 0, 4], look_at=[0, 0, 0]),
        meshes={"quad": lamplight.objects.mesh_file("meshes/quad.obj")},
        objects=[lamplight.mesh("quad"), lamplight.point_light([0, 1, 4], 30)],
        ambient=0.2,
    )
    expected = local(lamplight.Scene.from_dict(d, base_dir=folder), width=32, height=24)
    assert expected.max() > 0
    shared = lamplight.dask.render(d, client, width=32, height=24, tiles=4, base_dir=folder)
    assert shared.tobytes() == expected.tobytes()
    payload = lamplight.dask.shipped(lamplight.Scene.from_dict(d, base_dir=folder))
    assert sorted(payload.state[2]) == [os.path.join("meshes", "quad.mtl"), os.path.join("meshes", "quad.obj")]
    shipped = lamplight.dask.render(d, client, width=32, height=24, tiles=4, ship_meshes=True, base_dir=folder)
    assert shipped.tobytes() == expected.tobytes()
    # Shipped, the workers need nothing from the client's folder: render from a
    # payload whose folder is then removed, on workers that never saw it.
    for f in (folder / "meshes").iterdir():
        f.unlink()
    (folder / "meshes").rmdir()
    [remote] = client.scatter([payload], broadcast=True, hash=False)
    options = dict(width=32, height=24, spp=None, integrator="whitted", seed=0, max_depth=None, threads=1, filter="box")
    tile = client.submit(lamplight.dask._render_tile, remote, "shipped-test", options, (0, 0, 32, 24)).result()
    assert tile.tobytes() == expected.tobytes()


def test_a_killed_worker_does_not_change_the_image():
    args = dict(width=320, height=180, spp=8)
    expected = local("spheres", **args)
    cluster = distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=":0")
    try:
        with distributed.Client(cluster) as client:
            client.wait_for_workers(2)
            pids = client.run(os.getpid)
            assert len(set(pids.values())) == 2 and os.getpid() not in pids.values()
            killed = []

            def kill_one(done, total):
                # After a few tiles: both workers are busy and hold finished tiles.
                if done == 4 and not killed:
                    victim = sorted(pids.values())[0]
                    os.kill(victim, signal.SIGKILL)
                    killed.append(victim)

            image = lamplight.dask.render("spheres", client, tiles=48, progress=kill_one, **args)
            assert killed, "a worker was killed during the render"
            assert killed[0] not in client.run(os.getpid).values(), "the killed worker is gone"
            assert image.tobytes() == expected.tobytes()
    finally:
        cluster.close()


def test_a_cropped_scene_is_refused_not_split_wrongly(client, tmp_path):
    path = tmp_path / "cropped.toml"
    path.write_text(
        '[render]\nwidth = 40\nheight = 30\ncrop = [7, 5, 22, 17]\nintegrator = "path"\nspp = 4\nfilter = "gaussian"\n\n'
        "[camera]\neye = [0, 1, 5]\nlook_at = [0, 0.5, 0]\nvfov = 40\n\n"
        '[[objects]]\ntype = "sphere"\ncenter = [0, 0.5, 0]\nradius = 0.6\n\n'
        '[[objects]]\ntype = "point_light"\nposition = [2, 3, 3]\nintensity = 20\n'
    )
    scene = lamplight.Scene.from_file(path)
    assert scene.defaults()["crop"] == (7, 5, 22, 17)
    expected = local(scene)
    assert expected.shape == (17, 22, 3) and expected.max() > 0
    with pytest.raises(ValueError, match="does not split a scene with \\[render\\] crop yet"):
        lamplight.dask.render(scene, client, tiles=(3, 2))
