"""lamplight.render: arrays, the command line's EXR numbers, progress, Ctrl-C, bad arguments."""

import _thread
import subprocess
import signal
import threading
import time

import numpy as np
import pytest

import lamplight
from conftest import EXAMPLES


@pytest.mark.parametrize(
    "scene, args",
    [
        ("spheres", dict(width=64, height=36, spp=2)),
        ("luxo", dict(width=48, height=27, spp=1, seed=3)),
        ("cornell-box", dict(width=24, height=24, spp=4, integrator="path")),
        (str(EXAMPLES / "business-card.toml"), dict(width=40, height=40, spp=1)),
        # Adaptive sampling: Whitted's default anti-aliasing, a threshold, and
        # the path tracer's noise threshold.
        ("spheres", dict(width=48, height=27)),
        ("luxo", dict(width=48, height=27, antialias=0.1)),
        ("cornell-box", dict(width=16, height=16, spp=64, noise_threshold=0.2, min_spp=4)),
    ],
)
def test_render_equals_the_command_lines_exr(cli, tmp_path, scene, args):
    out = tmp_path / "out.exr"
    flags = [f"--{k.replace('_', '-')}={v}" for k, v in args.items()]
    subprocess.run([cli, "render", scene, "-o", str(out), "--quiet", *flags], check=True)
    expected = lamplight.read_exr(out)
    image = lamplight.render(scene, progress=False, **args)
    assert isinstance(image, lamplight.Image) and isinstance(image, np.ndarray)
    assert image.shape == (args["height"], args["width"], 3) and image.dtype == np.float32
    assert image.flags.c_contiguous
    assert image.tobytes() == expected.tobytes(), f"max difference {np.abs(image - expected).max()}"
    assert image.max() > 0


def test_defaults_come_from_the_scene():
    image = lamplight.render("business-card", progress=False)
    assert image.shape == (32, 32, 3)
    half = lamplight.render("spheres", width=64, progress=False)
    assert half.shape == (36, 64, 3), "one side keeps the scene's aspect"


def test_threads_and_windows_do_not_change_pixels():
    full = lamplight.render("spheres", width=50, height=30, spp=2, threads=2, progress=False)
    one = lamplight.render("spheres", width=50, height=30, spp=2, threads=1, progress=False)
    part = lamplight.render("spheres", width=50, height=30, spp=2, window=(7, 5, 20, 11), progress=False)
    assert full.tobytes() == one.tobytes()
    assert part.shape == (11, 20, 3)
    assert part.tobytes() == np.ascontiguousarray(full[5:16, 7:27]).tobytes()


def test_progress_callback_sees_every_tile():
    calls = []
    lamplight.render("spheres", width=160, height=90, spp=16, progress=lambda done, total: calls.append((done, total)))
    assert calls, "the callback was called"
    assert calls[-1][0] == calls[-1][1] == 60, "160x90 is 10x6 tiles of 16"
    assert [d for d, _ in calls] == sorted(d for d, _ in calls)


def test_a_raising_callback_stops_the_render():
    def stop(done, total):
        raise RuntimeError("enough")

    with pytest.raises(RuntimeError, match="enough"):
        lamplight.render("spheres", width=640, height=360, spp=64, progress=stop)


def test_ctrl_c_interrupts_a_long_render():
    # A suite started in the background by a shell without job control inherits
    # SIGINT ignored, and interrupt_main then does nothing: the render ran its
    # full 1-2 minutes and the test failed. Python's own handler is put back
    # for the length of the test, as an interactive session has it.
    previous = signal.signal(signal.SIGINT, signal.default_int_handler)
    timer = threading.Timer(0.5, _thread.interrupt_main)
    start = time.monotonic()
    timer.start()
    try:
        with pytest.raises(KeyboardInterrupt):
            lamplight.render("spheres", width=1280, height=720, spp=256, progress=False)
    finally:
        timer.cancel()
        signal.signal(signal.SIGINT, previous)
    assert time.monotonic() - start < 20, "the render stopped soon after Ctrl-C"
    # The module still works afterwards.
    assert lamplight.render("business-card", width=8, height=8, progress=False).shape == (8, 8, 3)


@pytest.mark.parametrize(
    "kwargs, error, message",
    [
        (dict(spp=0), ValueError, "spp must be between 1 and 1048576, got 0"),
        (dict(width=0), ValueError, "width must be at least 1"),
        (dict(width=2.5), TypeError, "width must be an int"),
        (dict(integrator="photon"), ValueError, "integrator must be"),
        (dict(max_depth=0), ValueError, "max_depth must be between 1 and 64"),
        (dict(threads=5000), ValueError, "threads must be at most 1024"),
        (dict(window=(0, 0, 100, 1)), ValueError, "inside the 32x32 image"),
        (dict(time_limit=-1.0), ValueError, "time_limit must be a positive"),
        (dict(clamp=0.0), ValueError, "clamp must be a positive number \\(a radiance\\), got 0"),
        (dict(filter="sinc"), ValueError, "filter must be"),
        (dict(width=1 << 20, height=1 << 20), ValueError, "image 1048576x1048576 is too large \\(at most 268435456 pixels\\)"),
    ],
)
def test_bad_arguments_raise(kwargs, error, message):
    with pytest.raises(error, match=message):
        lamplight.render("business-card", progress=False, **kwargs)


def test_images_save_and_display(tmp_path):
    image = lamplight.render("business-card", progress=False)
    png = image._repr_png_()
    assert png.startswith(b"\x89PNG\r\n\x1a\n")
    image.save(tmp_path / "a.exr")
    assert lamplight.read_exr(tmp_path / "a.exr").tobytes() == image.tobytes()
    image.save(tmp_path / "a.png")
    assert (tmp_path / "a.png").read_bytes() == png
    lamplight.save(tmp_path / "a.ppm", np.asarray(image))
    assert (tmp_path / "a.ppm").read_bytes().startswith(b"P6\n32 32\n255\n")
    with pytest.raises(ValueError, match="unknown image format"):
        image.save(tmp_path / "a.jpg")
    with pytest.raises(ValueError, match=r"\(H, W, 3\)"):
        lamplight.save(tmp_path / "b.png", np.zeros((4, 4)))
    assert image[:, :, 0]._repr_png_() is None, "a slice that is not an image does not display"
    assert image.stats["camera_rays"] == 32 * 32


def test_progress_true_shows_a_tqdm_bar(capsys):
    pytest.importorskip("tqdm")
    lamplight.render("business-card", progress=True)
    err = capsys.readouterr().err
    assert "lamplight" in err and "tile" in err, err
    lamplight.render("business-card", progress=False)
    assert capsys.readouterr().err == ""


def test_environment_and_exr_layers_equal_the_command_line(cli, tmp_path):
    # A sky brighter upwards, as an .exr map both front ends read.
    sky = np.zeros((8, 16, 3), dtype=np.float32)
    sky[:4] = [1.0, 0.9, 0.8]
    sky[4:] = [0.1, 0.1, 0.1]
    lamplight.save(tmp_path / "sky.exr", sky)
    args = dict(width=16, height=16, spp=4, integrator="path")
    out = tmp_path / "cli.exr"
    flags = [f"--{k.replace('_', '-')}={v}" for k, v in args.items()]
    subprocess.run(
        [cli, "render", "cornell-box", "-o", str(out), "--quiet", "--environment", str(tmp_path / "sky.exr"), "--exr-layers", "variance,samples", *flags],
        check=True,
    )
    image = lamplight.render("cornell-box", progress=False, environment=tmp_path / "sky.exr", exr_layers=["variance", "samples"], **args)
    assert image.tobytes() == lamplight.read_exr(out).tobytes()
    plain = lamplight.render("cornell-box", progress=False, **args)
    assert image.tobytes() != plain.tobytes(), "the environment lights the scene"
    assert set(image.layers) == {"variance", "samples"}
    assert image.layers["variance"].shape == (16, 16, 3) and image.layers["variance"].max() > 0
    assert (image.layers["samples"] == 4).all()
    # Saved, the layers are the command line's file's layers.
    image.save(tmp_path / "py.exr")
    assert (tmp_path / "py.exr").read_bytes() == out.read_bytes()
    whitted = lamplight.render("spheres", width=8, height=8, spp=2, exr_layers=["samples"], progress=False)
    assert (whitted.layers["samples"] == 2).all(), "every integrator fills the film the layers come from"
    with pytest.raises(ValueError, match='unknown layer "depth"'):
        lamplight.render("cornell-box", width=8, height=8, integrator="path", exr_layers=["depth"], progress=False)


def test_a_scene_that_asks_for_variance_gets_it_from_both_front_ends(cli, tmp_path):
    # `[render] variance = true` (what Mitsuba's `moment` becomes): the command
    # line's .exr holds the layer unasked, and Python's image carries it too.
    scene = tmp_path / "variance.toml"
    scene.write_text(
        (EXAMPLES / "cornell-box.toml").read_text().replace("[render]", "[render]\nvariance = true", 1)
    )
    args = dict(width=12, height=12, spp=4, integrator="path")
    out = tmp_path / "cli.exr"
    subprocess.run([cli, "render", str(scene), "-o", str(out), "--quiet", *[f"--{k}={v}" for k, v in args.items()]], check=True)
    image = lamplight.render(str(scene), progress=False, **args)
    assert set(image.layers) == {"variance"}
    assert image.layers["variance"].shape == (12, 12, 3) and image.layers["variance"].max() > 0
    image.save(tmp_path / "py.exr")
    assert (tmp_path / "py.exr").read_bytes() == out.read_bytes()
    asked = lamplight.render(str(scene), progress=False, exr_layers=["samples"], **args)
    assert list(asked.layers) == ["samples", "variance"], "the scene's layer comes after those asked for"


def test_a_scene_says_how_its_pngs_store_values():
    # Heckbert's card prints display values: its PNGs keep them as they are.
    assert lamplight.Scene("business-card").defaults()["transfer"] == "linear"
    assert lamplight.Scene("luxo").defaults()["transfer"] == "srgb"


def test_sampling_is_adaptive_unless_spp_says_otherwise():
    # Whitted without spp: 16 samples where neighbours differ, one elsewhere.
    aa = lamplight.render("spheres", width=64, height=36, exr_layers=["samples"], progress=False)
    one = lamplight.render("spheres", width=64, height=36, spp=1, progress=False)
    sixteen = lamplight.render("spheres", width=64, height=36, spp=16, progress=False)
    counts = aa.layers["samples"]
    assert set(np.unique(counts)) == {1.0, 16.0}
    refined = counts == 16
    assert np.array_equal(aa[refined], sixteen[refined]) and np.array_equal(aa[~refined], one[~refined])
    assert aa.stats["samples_per_pixel"] == 16
    assert aa.stats["mean_samples_per_pixel"] == pytest.approx(1 + 15 * refined.mean() + refined.mean(), rel=1e-9)
    assert np.array_equal(lamplight.render("spheres", width=64, height=36, antialias=False, progress=False), one)
    # The path tracer's noise threshold: per-pixel counts, fewer than spp in all.
    noisy = lamplight.render(
        "cornell-box", width=16, height=16, integrator="path", spp=128, noise_threshold=0.1, exr_layers=["samples"], progress=False
    )
    counts = noisy.layers["samples"]
    assert counts.min() >= 16 and counts.max() <= 128 and counts.mean() < 128
    # Without spp anywhere, the path tracer samples to the default noise level (0.05).
    default = lamplight.render("spheres", width=16, height=9, integrator="path", exr_layers=["samples"], progress=False)
    assert default.stats["samples_per_pixel"] == 1024 and 16 <= default.layers["samples"].min()
    assert default.stats["mean_samples_per_pixel"] < 1024
    with pytest.raises(ValueError, match=r"^noise_threshold is for the path tracer \(integrator path\); whitted takes its samples in one pass$"):
        lamplight.render("spheres", width=8, height=8, noise_threshold=0.1, progress=False)
    with pytest.raises(ValueError, match=r"^antialias must be True, False or a threshold >= 0 \(POV-Ray's 0.3\), got -1$"):
        lamplight.render("spheres", width=8, height=8, antialias=-1, progress=False)


def test_clamp_bounds_every_sample():
    plain = lamplight.render("cornell-box", width=16, height=16, spp=4, progress=False)
    clamped = lamplight.render("cornell-box", width=16, height=16, spp=4, clamp=0.5, progress=False)
    assert plain.max() > 1.0, "the lamp is brighter than the clamp"
    assert clamped.max() <= 0.5


def test_the_business_cards_png_holds_its_linear_numbers(tmp_path):
    card = lamplight.render("business-card", progress=False)
    assert card.stats["transfer"] == "linear"
    assert card.to_png() != card.to_png(transfer="srgb"), "the sRGB encoding brightens it"
    with pytest.raises(ValueError, match='transfer must be "srgb" or "linear", got "gamma"'):
        card.to_png(transfer="gamma")
    # The saved bytes are round(255 x), the card's own numbers.
    card.save(tmp_path / "card.ppm")
    data = (tmp_path / "card.ppm").read_bytes()
    header = b"P6\n32 32\n255\n"
    assert data.startswith(header)
    expected = np.clip(np.asarray(card, dtype=np.float64), 0, 1) * 255
    saved = np.frombuffer(data[len(header):], dtype=np.uint8).reshape(32, 32, 3)
    assert np.abs(saved - expected).max() <= 0.5 + 1e-4, "each byte is its value rounded"
