"""Adaptive sampling against fixed supersampling (issue 13), by error at the
samples spent: the program's own sample counts, not seconds.

- Whitted, POV-Ray's +A (the default render): spheres and luxo at 640x360,
  error of the display image (sRGB bytes) against 256 stratified samples.
- Path tracer, Cycles' noise threshold: spheres at 160x90 and cornell-box at
  128x128, error of the display image against 4096 samples, at the threshold's
  mean sample count and at a fixed count equal to it.

    cargo build --release -p lamplight-cli
    .venv/bin/python bench/adaptive.py [path/to/lamplight]
"""

import pathlib
import re
import subprocess
import sys
import tempfile

import numpy as np

import lamplight

CLI = sys.argv[1] if len(sys.argv) > 1 else str(pathlib.Path(__file__).resolve().parents[1] / "target/release/lamplight")


def render(scene, *flags):
    """The linear image of one CLI render and its mean samples per pixel (from the summary line)."""
    with tempfile.TemporaryDirectory() as d:
        out = pathlib.Path(d) / "out.exr"
        run = subprocess.run([CLI, "render", scene, "-o", str(out), *flags], check=True, capture_output=True, text=True)
        image = np.asarray(lamplight.read_exr(out), dtype=np.float64)
    spp = re.search(r", ([0-9.]+) spp", run.stderr)
    return image, float(spp.group(1))


def srgb(x):
    x = np.clip(x, 0, 1)
    return np.round(255 * np.where(x <= 0.0031308, 12.92 * x, 1.055 * x ** (1 / 2.4) - 0.055))


def whitted(scene):
    size = ["--width", "640", "--height", "360"]
    ref, _ = render(scene, *size, "--spp", "256")
    rows = []
    for label, flags, spp in [
        ("--spp 1", ["--spp", "1"], 1.0),
        ("default (+A 0.3)", [], None),
        ("--antialias 0.1", ["--antialias", "0.1"], None),
        ("--spp 4", ["--spp", "4"], 4.0),
        ("--spp 16", ["--spp", "16"], 16.0),
    ]:
        image, mean_spp = render(scene, *size, *flags)
        err = np.sqrt(np.mean((srgb(image) - srgb(ref)) ** 2))
        edge = np.abs(srgb(image) - srgb(ref)).max(axis=2) > 16
        rows.append((label, mean_spp, err, edge.mean()))
    print(f"{scene} 640x360, Whitted, against --spp 256 (sRGB bytes):")
    for label, mean_spp, err, edge in rows:
        print(f"  {label:18s} {mean_spp:6.2f} spp   RMSE {err:6.3f}   pixels off by > 16 levels {100 * edge:5.2f} %")


def path(scene, width, height):
    size = ["--width", str(width), "--height", str(height), "--integrator", "path"]
    ref, _ = render(scene, *size, "--spp", "4096")
    display = lambda a: np.sqrt(np.mean((srgb(a) - srgb(ref)) ** 2))
    p99 = lambda a: np.percentile(np.abs(srgb(a) - srgb(ref)), 99)
    print(f"{scene} {width}x{height}, path, error of the sRGB bytes against --spp 4096, at equal mean samples:")
    for threshold in ["0.05", "0.02", "0.01"]:
        image, mean_spp = render(scene, *size, "--spp", "1024", "--noise-threshold", threshold)
        fixed, _ = render(scene, *size, "--spp", str(max(1, round(mean_spp))))
        print(
            f"  --noise-threshold {threshold:4s}: {mean_spp:6.1f} spp   RMSE {display(image):.3f}, 99th pct {p99(image):5.2f}"
            f"   fixed --spp {round(mean_spp)}: RMSE {display(fixed):.3f}, 99th pct {p99(fixed):5.2f}"
        )


for scene in ["spheres", "luxo"]:
    whitted(scene)
path("spheres", 160, 90)
path("cornell-box", 128, 128)
