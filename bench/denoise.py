#!/usr/bin/env python3
"""Denoising (issue 28): error against a converged render with and without
Open Image Denoise, the time the filter adds, and the images of docs/denoise.md.

For each scene, renders a reference at `--ref-spp` and, at each of `--spp`,
the noisy image and the denoised one (`--denoise`, the same samples: the noisy
image is the `noisy` layer of the denoised render), and, as it was denoised
before issue 28's fix, the whole image filtered (`lamplight.denoise` of the
same render without its `emitted` layer). Reports the RMSE against the
reference of

* the displayed values (radiance clamped to [0, 1], what a PNG shows),
* linear radiance (dominated by pixels brighter than 1: a light's edge), and
* linear radiance where the reference is below 20 (the Cornell box's light is
  18.6; DamagedHelmet's 4096-spp reference has a few fireflies, up to 149 where
  every noisy render has 4, which otherwise dominate its linear RMSE),

and the filter's time per megapixel (`denoised in X s` of `lamplight render`,
its own clock around the OIDN call, which includes making the device).

Usage: python bench/denoise.py [--size 256] [--ref-spp 4096] [--spp 4,16,64]
       [--images docs/denoise] [--mp-size 1024] [--keep DIR]
(`--keep DIR` keeps the references there and reuses them.)
Needs the release binary (`cargo build --release -p lamplight-cli`, or set
LAMPLIGHT), the Python package (`maturin develop`, for reading EXR) and OIDN
(`pip install pyoidn`, or LAMPLIGHT_OIDN). The glTF case needs
../shared/data/gltf/DamagedHelmet.glb (LAMPLIGHT_HELMET).
"""
import argparse
import os
import re
import subprocess
import tempfile
import time

import numpy as np

import lamplight

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
LAMPLIGHT = os.environ.get("LAMPLIGHT", os.path.join(os.environ.get("CARGO_TARGET_DIR", os.path.join(ROOT, "target")), "release", "lamplight"))
HELMET = os.environ.get("LAMPLIGHT_HELMET", os.path.join(ROOT, "..", "shared", "data", "gltf", "DamagedHelmet.glb"))


def render(scene, out, size, spp, *extra):
    """Runs `lamplight render`; returns (wall seconds, denoise seconds or None)."""
    args = [LAMPLIGHT, "render", scene, "--integrator", "path", "--width", str(size), "--height", str(size), "--spp", str(spp), "-o", out, *extra]
    start = time.perf_counter()
    err = subprocess.run(args, check=True, capture_output=True, text=True).stderr
    wall = time.perf_counter() - start
    m = re.search(r"denoised in ([0-9.]+) s", err)
    return wall, (float(m.group(1)) if m else None)


def rmse(a, b):
    return float(np.sqrt(np.mean((a.astype(np.float64) - b) ** 2)))


def shown(a):
    return np.clip(a, 0.0, 1.0)


def case(name, scene, args, tmp):
    ref_dir = args.keep or tmp
    ref_path = os.path.join(ref_dir, f"{name}-{args.size}-{args.ref_spp}-ref.exr")
    wall = 0.0
    if not os.path.exists(ref_path):
        wall, _ = render(scene, ref_path, args.size, args.ref_spp, "--seed", "99")
    ref = np.asarray(lamplight.read_exr(ref_path), dtype=np.float64)
    under = ref.max(axis=2) < 20
    print(f"\n{name}, {args.size}x{args.size}, reference {args.ref_spp} spp ({wall:.1f} s; {(~under).sum()} pixels at 20 or more)")
    print("| spp | shown: noisy | whole filtered | denoised | gain | linear: noisy | whole filtered | denoised | gain "
          "| linear < 20: noisy | whole filtered | denoised | render s | denoise s |")
    print("|---:|" + "---:|" * 13)
    for spp in args.spp:
        noisy_path = os.path.join(tmp, f"{name}-{spp}-noisy.exr")
        den_path = os.path.join(tmp, f"{name}-{spp}-denoised.exr")
        wall_noisy, _ = render(scene, noisy_path, args.size, spp, "--seed", "1")
        _, dt = render(scene, den_path, args.size, spp, "--seed", "1", "--denoise")
        noisy, den = lamplight.read_exr(noisy_path), lamplight.read_exr(den_path)
        # Before the fix: the whole image filtered, the same samples and features.
        featured = lamplight.render(scene, width=args.size, height=args.size, spp=spp, seed=1, integrator="path",
                                    exr_layers=["albedo", "normal"], progress=False)
        assert featured.tobytes() == noisy.tobytes()
        whole = lamplight.denoise(featured)
        s = [rmse(shown(i), shown(ref)) for i in (noisy, whole, den)]
        lin = [rmse(i, ref) for i in (noisy, whole, den)]
        low = [rmse(np.asarray(i)[under], ref[under]) for i in (noisy, whole, den)]
        print(f"| {spp} | {s[0]:.4f} | {s[1]:.4f} | {s[2]:.4f} | {s[0] / s[2]:.1f}x | {lin[0]:.4f} | {lin[1]:.4f} | {lin[2]:.4f} "
              f"| {lin[0] / lin[2]:.2f}x | {low[0]:.4f} | {low[1]:.4f} | {low[2]:.4f} | {wall_noisy:.2f} | {dt:.3f} |")
        if args.images and spp == 16:
            os.makedirs(args.images, exist_ok=True)
            lamplight.save(os.path.join(args.images, f"{name}-16spp.png"), noisy)
            lamplight.save(os.path.join(args.images, f"{name}-16spp-denoised.png"), den)
            lamplight.save(os.path.join(args.images, f"{name}-reference.png"), ref.astype(np.float32))


def filter_time(args, tmp):
    """Seconds per megapixel the filter adds, at --mp-size squared (three runs)."""
    out = os.path.join(tmp, "mp.exr")
    times = [render("cornell-box", out, args.mp_size, 1, "--denoise", "--seed", str(i))[1] for i in range(3)]
    mp = args.mp_size * args.mp_size / 1e6
    print(f"\nfilter time at {args.mp_size}x{args.mp_size} ({mp:.2f} MP): " + ", ".join(f"{t:.2f} s" for t in times) + f"; {min(times) / mp:.2f} s per megapixel (best)")


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--size", type=int, default=256)
    p.add_argument("--ref-spp", type=int, default=4096)
    p.add_argument("--spp", type=lambda s: [int(x) for x in s.split(",")], default=[4, 16, 64])
    p.add_argument("--images", default="")
    p.add_argument("--mp-size", type=int, default=1024)
    p.add_argument("--keep", default="")
    args = p.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        case("cornell-box", "cornell-box", args, tmp)
        if os.path.exists(HELMET):
            case("damaged-helmet", HELMET, args, tmp)
        else:
            print(f"\n(no {HELMET}: the glTF case is skipped)")
        filter_time(args, tmp)


if __name__ == "__main__":
    main()
