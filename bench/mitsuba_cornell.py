#!/usr/bin/env python3
"""Cross-check lamplight's path tracer against Mitsuba 3 on the Cornell box.

Both render `mitsuba.cornell_box()` (lamplight's built-in `cornell-box` is the
same scene) with a box pixel filter and paths of at most 8 segments. Reports:

* accuracy: relative RMSE (RMSE over the mean of the reference) between the two
  renderers at high spp, and per-channel ratio of image means;
* speed: samples per second at 512x512 for lamplight and for Mitsuba's fastest
  CPU variant (llvm_ad_rgb if LLVM loads, else scalar_rgb), in the same run;
* time to quality: seconds each needs to reach a fixed RMSE against the
  high-spp reference (interpolated in log-log between measured spp).

The accuracy renders may use another Mitsuba sampler (`--mitsuba-sampler
stratified`): the sampler changes only the noise, not the expected image, and
cornell_box()'s `independent` sampler leaves binomial noise of the light's full
radiance in the pixels on the light's edges, which dominates the difference.
The accuracy report splits the squared difference into the light, its edge
pixels and the rest, each with the share two renders per renderer attribute to
noise.

Usage: python bench/mitsuba_cornell.py [--size 128] [--ref-spp 4096] [--speed-size 512]
       [--mitsuba-sampler stratified] [--skip-speed] [--ladder ""]
Needs `pip install mitsuba numpy`; for the LLVM variant set DRJIT_LIBLLVM_PATH
(e.g. /usr/lib/x86_64-linux-gnu/libLLVM.so.19.1; LLVM 15 crashed in code generation). Run from the repository root
after `cargo build --release`.
"""
import argparse
import os
import subprocess
import tempfile
import time

import numpy as np
import mitsuba as mi

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
LAMPLIGHT = os.environ.get("LAMPLIGHT", os.path.join(ROOT, "target", "release", "lamplight"))


def set_variant(variants=("llvm_ad_rgb", "scalar_rgb")):
    """Sets the first of `variants` that loads and returns its name."""
    for v in variants:
        try:
            mi.set_variant(v)
            return v
        except Exception:  # LLVM not found: fall back
            continue
    raise SystemExit("no usable Mitsuba variant")


SAMPLER = "independent"


def mitsuba_scene(size, spp, sampler=None):
    d = mi.cornell_box()
    d["integrator"] = {"type": "path", "max_depth": 8}
    d["sensor"]["film"]["width"] = size
    d["sensor"]["film"]["height"] = size
    d["sensor"]["film"]["rfilter"] = {"type": "box"}
    d["sensor"]["sampler"] = {"type": sampler or SAMPLER, "sample_count": spp}
    return mi.load_dict(d)


def render_mitsuba(size, spp, seed=0, sampler=None):
    scene = mitsuba_scene(size, spp, sampler)
    # Warm-up at 1 spp so that JIT compilation is not timed (llvm variant).
    mi.render(mitsuba_scene(size, 1, sampler), spp=1)
    t0 = time.perf_counter()
    img = mi.render(scene, spp=spp, seed=seed)
    arr = np.array(img, dtype=np.float64)  # forces evaluation
    return arr, time.perf_counter() - t0


def render_lamplight(size, spp, seed=0):
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "cb.exr")
        cmd = [LAMPLIGHT, "render", "cornell-box", "--integrator", "path", "--max-depth", "8", "--filter", "box",
               "--width", str(size), "--height", str(size), "--spp", str(spp), "--seed", str(seed), "--quiet", "-o", out]
        t0 = time.perf_counter()
        subprocess.run(cmd, check=True)
        elapsed = time.perf_counter() - t0
        arr = np.array(mi.Bitmap(out), dtype=np.float64)[:, :, :3]
    return arr, elapsed


def rmse(a, b):
    return float(np.sqrt(np.mean((a - b) ** 2)))


def time_to_rmse(points, target):
    """Seconds to reach `target` RMSE, interpolating log(time) against log(rmse),
    and whether the value is extrapolated (from the last two points) because the
    ladder did not reach the target."""
    pts = sorted(points, key=lambda p: p[0])
    for (t0, e0), (t1, e1) in zip(pts, pts[1:]):
        if e0 >= target >= e1:
            f = (np.log(target) - np.log(e0)) / (np.log(e1) - np.log(e0))
            return float(np.exp(np.log(t0) + f * (np.log(t1) - np.log(t0)))), False
    if len(pts) >= 2 and pts[-1][1] > target and pts[-2][1] > pts[-1][1]:
        (t0, e0), (t1, e1) = pts[-2], pts[-1]
        f = (np.log(target) - np.log(e0)) / (np.log(e1) - np.log(e0))
        return float(np.exp(np.log(t0) + f * (np.log(t1) - np.log(t0)))), True
    return float("nan"), False


def references(size, spp):
    """Two independent renders per renderer (seeds 7 and 8): (m1, m2, l1, l2)."""
    m1, _ = render_mitsuba(size, spp, seed=7)
    m2, _ = render_mitsuba(size, spp, seed=8)
    l1, _ = render_lamplight(size, spp, seed=7)
    l2, _ = render_lamplight(size, spp, seed=8)
    return m1, m2, l1, l2


def speed(size, spp, runs=1):
    """Render times (s) at size x size and spp, lamplight and Mitsuba alternating:
    (lamplight times, Mitsuba times)."""
    t_l, t_m = [], []
    for _ in range(runs):
        t_l.append(render_lamplight(size, spp)[1])
        t_m.append(render_mitsuba(size, spp)[1])
    return t_l, t_m


def ladder_points(size, ladder, ref_l, ref_m, runs=1):
    """For each spp of `ladder`: (spp, lamplight median s, lamplight RMSE, Mitsuba
    median s, Mitsuba RMSE), each RMSE against that renderer's own reference. Seed 1
    throughout, so the images (and RMSEs) are the same in every run."""
    rows = []
    for spp in ladder:
        t_l, t_m = [], []
        for _ in range(runs):
            il, t = render_lamplight(size, spp, seed=1)
            t_l.append(t)
            im, t = render_mitsuba(size, spp, seed=1)
            t_m.append(t)
        rows.append((spp, float(np.median(t_l)), rmse(il, ref_l), float(np.median(t_m)), rmse(im, ref_m)))
    return rows


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--size", type=int, default=128)
    ap.add_argument("--ref-spp", type=int, default=4096)
    ap.add_argument("--speed-size", type=int, default=512)
    ap.add_argument("--speed-spp", type=int, default=16)
    ap.add_argument("--ladder", default="4,16,64,256", help="spp list for time to quality; empty: skip")
    ap.add_argument("--mitsuba-sampler", default="independent",
                    help="Mitsuba sampler for the accuracy renders (independent, stratified, multijitter, ldsampler); "
                         "speed and time to quality use --speed-sampler")
    ap.add_argument("--speed-sampler", default="independent",
                    help="Mitsuba sampler for the speed and time-to-quality renders (default: cornell_box()'s independent)")
    ap.add_argument("--skip-speed", action="store_true")
    ap.add_argument("--save", metavar="DIR", help="save the four accuracy renders as .npy files in DIR")
    args = ap.parse_args()
    global SAMPLER
    variant = set_variant()
    print(f"Mitsuba {mi.__version__}, variant {variant}, {os.cpu_count()} CPUs")
    SAMPLER = args.mitsuba_sampler

    # Two independent renders per renderer: their difference measures each one's
    # noise, which is subtracted from the squared difference between renderers to
    # leave the systematic part (E|a - b|^2 = bias^2 + var_a + var_b).
    t0 = time.perf_counter()
    m1, m2, l1, l2 = references(args.size, args.ref_spp)
    ref_m, ref_l = 0.5 * (m1 + m2), 0.5 * (l1 + l2)
    if args.save:
        for name, arr in (("m1", m1), ("m2", m2), ("l1", l1), ("l2", l2)):
            np.save(os.path.join(args.save, f"{name}.npy"), arr)
    mean = ref_m.mean()
    var_m = np.mean((m1 - m2) ** 2) / 4.0  # variance of the mean of two renders
    var_l = np.mean((l1 - l2) ** 2) / 4.0
    mse = np.mean((ref_l - ref_m) ** 2)
    print(f"\n## Accuracy: {args.size}x{args.size}, 2 x {args.ref_spp} spp each")
    print(f"relative RMSE (RMSE / mean of Mitsuba) = {np.sqrt(mse) / mean * 100:.3f} %")
    print(f"  of which noise: Mitsuba {np.sqrt(var_m) / mean * 100:.3f} %, lamplight {np.sqrt(var_l) / mean * 100:.3f} %")
    print(f"  noise removed: {np.sqrt(max(0.0, mse - var_m - var_l)) / mean * 100:.3f} %")
    blocks = lambda a: a.reshape(a.shape[0] // 4, 4, a.shape[1] // 4, 4, 3).mean(axis=(1, 3))
    print(f"  on 4x4 pixel blocks: {rmse(blocks(ref_l), blocks(ref_m)) / mean * 100:.3f} %")
    # The few pixels that see the light (radiance ~18) dominate every squared error:
    # with an independent sampler their partial coverage is binomial noise of the
    # light's radiance. Without them:
    off = (ref_m.max(axis=2) < 1.0) & (ref_l.max(axis=2) < 1.0)
    mse_off = np.mean((ref_l - ref_m)[off] ** 2)
    vm_off = np.mean((m1 - m2)[off] ** 2) / 4.0
    vl_off = np.mean((l1 - l2)[off] ** 2) / 4.0
    print(f"  without the {np.sum(~off)} pixels that see the light: {np.sqrt(mse_off) / mean * 100:.3f} %, "
          f"noise removed {np.sqrt(max(0.0, mse_off - vm_off - vl_off)) / mean * 100:.3f} %")
    print("mean per channel lamplight / Mitsuba = " + ", ".join(f"{r:.4f}" for r in ref_l.mean(axis=(0, 1)) / ref_m.mean(axis=(0, 1))))
    print(f"(the four reference renders took {time.perf_counter() - t0:.1f} s, Mitsuba sampler {SAMPLER})")
    # Where the disagreement sits: the light itself, its edge pixels, the rest.
    light = ref_m.max(axis=2) > 5.0
    edge = (~light) & (~off)
    for name, mask in (("light interior", light), ("light edge", edge), ("rest", off)):
        d2 = np.sum((ref_l - ref_m)[mask] ** 2) / ref_m.size
        n2 = (np.sum((m1 - m2)[mask] ** 2) + np.sum((l1 - l2)[mask] ** 2)) / 4.0 / ref_m.size
        print(f"  {name}: {np.sum(mask)} pixels, share of squared difference {d2 / mse * 100:.1f} %, "
              f"of which noise {n2 / max(d2, 1e-30) * 100:.0f} %")
    SAMPLER = args.speed_sampler

    if not args.skip_speed:
        n = args.speed_size * args.speed_size * args.speed_spp
        (t_l,), (t_m,) = speed(args.speed_size, args.speed_spp)
        print(f"\n## Speed: {args.speed_size}x{args.speed_size}, {args.speed_spp} spp")
        print(f"lamplight: {t_l:.2f} s, {n / t_l / 1e6:.3f} M samples/s")
        print(f"Mitsuba {variant} ({SAMPLER} sampler): {t_m:.2f} s, {n / t_m / 1e6:.3f} M samples/s")
    if not args.ladder:
        return

    # Time to quality: each renderer against its own high-spp reference (other seeds),
    # so that the residual difference between the renderers does not set a floor.
    ladder = [int(s) for s in args.ladder.split(",")]
    print(f"\n## Time to quality: {args.size}x{args.size}, RMSE against each renderer's own 2 x {args.ref_spp}-spp render")
    print("spp | lamplight s | lamplight RMSE | Mitsuba s | Mitsuba RMSE")
    rows = ladder_points(args.size, ladder, ref_l, ref_m)
    for spp, t_l, e_l, t_m, e_m in rows:
        print(f"{spp} | {t_l:.3f} | {e_l:.5f} | {t_m:.3f} | {e_m:.5f}")
    pts_l = [(r[1], r[2]) for r in rows]
    pts_m = [(r[3], r[4]) for r in rows]
    target = 0.02 * mean
    (t_l, x_l), (t_m, x_m) = time_to_rmse(pts_l, target), time_to_rmse(pts_m, target)
    mark = lambda x: " (extrapolated)" if x else ""
    print(f"time to RMSE {target:.4f} (2 % of the mean): lamplight {t_l:.3f} s{mark(x_l)}, "
          f"Mitsuba {t_m:.3f} s{mark(x_m)}; Mitsuba / lamplight = {t_m / t_l:.2f}")
    # A second reading from the rungs up to 1024 spp only (extrapolated where they
    # stop short): above that Mitsuba's stratified sampler is slower per sample
    # (2116 spp took 2.7 times as long as 1024), which would flatter lamplight.
    low = lambda pts: [p for p, spp in zip(pts, ladder) if spp <= 1024]
    (e_l, xe_l), (e_m, xe_m) = time_to_rmse(low(pts_l), target), time_to_rmse(low(pts_m), target)
    print(f"  from the rungs up to 1024 spp only: lamplight {e_l:.3f} s{mark(xe_l)}, Mitsuba {e_m:.3f} s{mark(xe_m)}; "
          f"Mitsuba / lamplight = {e_m / e_l:.2f}")


if __name__ == "__main__":
    main()
