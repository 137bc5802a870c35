#!/usr/bin/env python3
"""How many samples lamplight with `--denoise` needs to reach the error of
Mitsuba 3 at 256 spp on the Cornell box, and the time it takes against
Mitsuba's, side by side (issue 28).

Each renderer is measured against its own reference (the mean of two
`--ref-spp` renders, seeds 7 and 8), as bench/mitsuba_cornell.py does; both
render at `--size`, box filter, paths of at most 8 segments, Mitsuba
`llvm_ad_rgb` with its `stratified` sampler. The error is the RMSE of the
displayed values (radiance clamped to [0, 1]) and, second, of linear radiance.
lamplight's time is its whole process (render, feature pass, OIDN, EXR write);
Mitsuba's its render call after a JIT warm-up; medians of `--runs`.

Usage: DRJIT_LIBLLVM_PATH=/usr/lib/x86_64-linux-gnu/libLLVM.so.19.1 \\
       python bench/denoise_vs_mitsuba.py [--size 64] [--ref-spp 4096] [--ladder 1,2,4,8,16,32,64] [--runs 3]
Needs what bench/mitsuba_cornell.py needs, and OIDN (LAMPLIGHT_OIDN or pyoidn).
"""
import argparse
import os
import subprocess
import sys
import tempfile
import time

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import mitsuba_cornell as mc  # noqa: E402  (its renderers and helpers)


def lamplight_denoised(size, spp, seed=1):
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "cb.exr")
        cmd = [mc.LAMPLIGHT, "render", "cornell-box", "--integrator", "path", "--max-depth", "8", "--filter", "box", "--denoise",
               "--width", str(size), "--height", str(size), "--spp", str(spp), "--seed", str(seed), "--quiet", "-o", out]
        t0 = time.perf_counter()
        subprocess.run(cmd, check=True)
        elapsed = time.perf_counter() - t0
        arr = np.array(mc.mi.Bitmap(out), dtype=np.float64)[:, :, :3]
    return arr, elapsed


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--size", type=int, default=64)
    ap.add_argument("--ref-spp", type=int, default=4096)
    ap.add_argument("--mitsuba-spp", type=int, default=256)
    ap.add_argument("--ladder", default="1,2,4,8,16,32,64")
    ap.add_argument("--runs", type=int, default=3)
    args = ap.parse_args()
    variant = mc.set_variant()
    mc.SAMPLER = "stratified"
    shown = lambda a: np.clip(a, 0.0, 1.0)
    print(f"Mitsuba {mc.mi.__version__}, {variant}, sampler stratified, {os.cpu_count()} CPUs, load {os.getloadavg()[0]:.2f}")
    m1, m2, l1, l2 = mc.references(args.size, args.ref_spp)
    ref_m, ref_l = 0.5 * (m1 + m2), 0.5 * (l1 + l2)
    times = []
    for _ in range(args.runs):
        im, t = mc.render_mitsuba(args.size, args.mitsuba_spp, seed=1)
        times.append(t)
    t_m = float(np.median(times))
    e_m, e_m_lin = mc.rmse(shown(im), shown(ref_m)), mc.rmse(im, ref_m)
    print(f"\nMitsuba {args.mitsuba_spp} spp, {args.size}x{args.size}: RMSE shown {e_m:.5f}, linear {e_m_lin:.5f}, {t_m:.3f} s (median of {args.runs})")
    print("\n| lamplight spp | denoised, shown | linear | noisy, shown | s (denoised, median) | s (noisy) |")
    print("|---:|---:|---:|---:|---:|---:|")
    reached = None
    for spp in [int(s) for s in args.ladder.split(",")]:
        runs = [lamplight_denoised(args.size, spp) for _ in range(args.runs)]
        den, t_d = runs[0][0], float(np.median([t for _, t in runs]))
        noisy_runs = [mc.render_lamplight(args.size, spp, seed=1) for _ in range(args.runs)]
        noisy, t_n = noisy_runs[0][0], float(np.median([t for _, t in noisy_runs]))
        e_d = mc.rmse(shown(den), shown(ref_l))
        print(f"| {spp} | {e_d:.5f} | {mc.rmse(den, ref_l):.5f} | {mc.rmse(shown(noisy), shown(ref_l)):.5f} | {t_d:.3f} | {t_n:.3f} |")
        if reached is None and e_d <= e_m:
            reached = (spp, t_d)
    if reached:
        print(f"\nlamplight --denoise reaches Mitsuba's {args.mitsuba_spp}-spp error (shown) at {reached[0]} spp in {reached[1]:.3f} s "
              f"against Mitsuba's {t_m:.3f} s: {t_m / reached[1]:.2f}x")
    else:
        print("\nthe ladder did not reach Mitsuba's error")


if __name__ == "__main__":
    main()
