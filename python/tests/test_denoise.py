"""Denoising from Python (issue 28): ``exr_layers=["albedo", "normal"]``,
``render(..., denoise=True)`` and ``lamplight.denoise``, each the same numbers
as the command line's; the error without the library."""

import os
import subprocess
import sys

import numpy as np
import pytest

import lamplight

ARGS = dict(width=24, height=24, spp=8, integrator="path", threads=2)


def flags(args):
    return [f"--{k.replace('_', '-')}={v}" for k, v in args.items()]


def test_feature_layers_equal_the_command_line(cli, tmp_path):
    out = tmp_path / "cli.exr"
    subprocess.run([cli, "render", "cornell-box", "-o", str(out), "--quiet", "--exr-layers", "albedo,normal", *flags(ARGS)], check=True)
    image = lamplight.render("cornell-box", progress=False, exr_layers=["albedo", "normal"], **ARGS)
    assert set(image.layers) == {"albedo", "normal"}
    albedo, normal = image.layers["albedo"], image.layers["normal"]
    assert albedo.shape == normal.shape == (24, 24, 3)
    assert 0 <= albedo.min() and albedo.max() <= 1 and -1 <= normal.min() and normal.max() <= 1
    # The left wall is red, and faces +x.
    np.testing.assert_array_equal(albedo[12, 1], np.float32([0.570068, 0.0430135, 0.0443706]))
    assert normal[12, 1, 0] > 0.99
    image.save(tmp_path / "py.exr")
    assert (tmp_path / "py.exr").read_bytes() == out.read_bytes()


def test_denoised_render_equals_the_command_line_and_lamplight_denoise(cli, tmp_path, oidn):
    out = tmp_path / "cli.exr"
    subprocess.run([cli, "render", "cornell-box", "-o", str(out), "--quiet", "--denoise", *flags(ARGS)], check=True)
    denoised = lamplight.render("cornell-box", progress=False, denoise=True, **ARGS)
    assert denoised.tobytes() == lamplight.read_exr(out).tobytes()
    assert denoised.stats["denoise_seconds"] > 0
    noisy = lamplight.render("cornell-box", progress=False, exr_layers=["albedo", "normal", "emitted"], **ARGS)
    assert noisy.tobytes() != denoised.tobytes()
    # The image's own layers guide lamplight.denoise by default; the light seen
    # directly (its `emitted` layer) is added back, not filtered.
    assert lamplight.denoise(noisy, threads=2).tobytes() == denoised.tobytes()
    emitted = noisy.layers["emitted"]
    assert emitted.max() > 1 and (denoised >= emitted).all()
    with pytest.raises(ValueError, match=r"^albedo is 2x2, the image 24x24$"):
        lamplight.denoise(noisy, albedo=np.zeros((2, 2, 3), dtype=np.float32))


def test_the_kept_denoiser_gives_the_same_bytes_call_after_call(oidn):
    # The device and filter are kept between calls (the filter per image size):
    # a call after another of another size, or after many, changes nothing.
    noisy = lamplight.render("cornell-box", progress=False, exr_layers=["albedo", "normal", "emitted"], **ARGS)
    first = lamplight.denoise(noisy, threads=2).tobytes()
    corner = [np.ascontiguousarray(a[:8, :12]) for a in (noisy, *(noisy.layers[k] for k in ("albedo", "normal", "emitted")))]
    small = lamplight.denoise(*corner[:3], threads=2, emitted=corner[3])
    assert small.shape == (8, 12, 3)
    assert [lamplight.denoise(noisy, threads=2).tobytes() for _ in range(3)] == [first] * 3
    assert lamplight.denoise(*corner[:3], threads=2, emitted=corner[3]).tobytes() == small.tobytes()


def test_a_missing_library_is_a_value_error_that_says_where_to_look(tmp_path):
    (tmp_path / "notlib.so").write_text("not a library")
    code = "import lamplight\ntry:\n    lamplight.render('cornell-box', width=4, height=4, spp=1, denoise=True, progress=False)\nexcept ValueError as e:\n    print(e)\n"
    env = dict(os.environ, LAMPLIGHT_OIDN=str(tmp_path / "notlib.so"))
    out = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True, check=True).stdout
    assert out.startswith(f"LAMPLIGHT_OIDN={tmp_path / 'notlib.so'}: cannot load Open Image Denoise: "), out
    with pytest.raises(TypeError, match="^denoise must be True or False, got str$"):
        lamplight.render("cornell-box", width=4, height=4, denoise="yes", progress=False)
    with pytest.raises(ValueError, match="^the noisy layer is the image before denoising: it needs denoise$"):
        lamplight.render("cornell-box", width=4, height=4, exr_layers=["noisy"], progress=False)
