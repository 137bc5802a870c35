#!/usr/bin/env python3
"""Judge lamplight's Mitsuba XML reader against Mitsuba 3 itself.

For every plugin the reader maps, a small scene (bench/mitsuba_xml/cases.py)
is rendered from the same XML file by Mitsuba (`scalar_rgb`) and by lamplight
(`lamplight render case.xml -D spp=N`). Mitsuba renders K independent seeds of
N / K samples each: their mean is its image and their sample variance over K
its variance of the mean; lamplight writes the variance of each pixel's mean (--variance-output).
Each pixel's channels are z-tested, `z = (a - b) / sqrt(var_a + var_b)`,
two-sided, at the Sidak-corrected level `1 - (1 - 0.01)^(1 / n)` for the n
values of the image; a case passes when at least 99.75 % of the pixels pass
(the rule of Mitsuba's own render tests, src/render/tests/test_renders.py).
Values equal to float32 rounding (1e-5 relative) pass whatever the variances (a
sky seen directly has none).

Usage: /work/mi-venv/bin/python bench/mitsuba_xml_compare.py [--spp 256] [--seeds 8]
       [--only NAME,...] [--keep DIR]
Run from the repository root after `cargo build -p lamplight-cli` (or set LAMPLIGHT).
Prints one row per case for BENCHMARKS.md.
"""
import argparse
import math
import os
import subprocess
import sys
import tempfile
import time

import numpy as np

# The llvm variants (the cases of the differentiable integrators) abort with
# this machine's LLVM 15; LLVM 19 comes from `apt-get install libllvm19`.
LLVM19 = "/usr/lib/x86_64-linux-gnu/libLLVM.so.19.1"
if os.path.exists(LLVM19):
    os.environ.setdefault("DRJIT_LIBLLVM_PATH", LLVM19)

try:
    import mitsuba as mi
except ImportError:
    sys.exit("mitsuba is not installed (pip install mitsuba): nothing to compare against")

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from mitsuba_xml import cases as cases_mod  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
LAMPLIGHT = os.environ.get("LAMPLIGHT", os.path.join(ROOT, "target", "debug", "lamplight"))


def normal_sf2(z):
    """Two-sided p-value of a standard normal z (array)."""
    return np.vectorize(lambda v: math.erfc(abs(v) / math.sqrt(2.0)))(z)


def render_mitsuba(path, spp, seeds):
    """The mean of `seeds` renders of spp / seeds samples each, and its variance."""
    per = max(1, spp // seeds)
    scene = mi.load_file(path, spp=str(per))
    imgs = [np.array(mi.render(scene, seed=s, spp=per), dtype=np.float64)[:, :, :3] for s in range(seeds)]
    stack = np.stack(imgs)
    return stack.mean(axis=0), stack.var(axis=0, ddof=1) / seeds


def render_lamplight(path, spp, tmp):
    out = os.path.join(tmp, "ll.exr")
    var = os.path.join(tmp, "ll_var.exr")
    cmd = [LAMPLIGHT, "render", path, "-D", f"spp={spp}", "--quiet", "-o", out, "--variance-output", var]
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode != 0:
        raise RuntimeError(r.stderr.strip().splitlines()[-1] if r.stderr.strip() else f"exit {r.returncode}")
    img = np.array(mi.Bitmap(out), dtype=np.float64)[:, :, :3]
    v = np.array(mi.Bitmap(var), dtype=np.float64)[:, :, :3]
    return img, v, r.stderr.strip()


def z_test(a, va, b, vb, alpha=0.01):
    n = a.size
    level = 1.0 - (1.0 - alpha) ** (1.0 / n)
    var = va + vb
    with np.errstate(divide="ignore", invalid="ignore"):
        z = np.where(var > 0, (a - b) / np.sqrt(np.maximum(var, 1e-300)), 0.0)
    p = normal_sf2(z)
    # Equal to float32 rounding (Mitsuba's precision): a pass whatever the variances say.
    exact = np.abs(a - b) <= 1e-5 * np.maximum(np.abs(a), np.abs(b)) + 1e-7
    ok = exact | ((var > 0) & (p > level))
    pixel_ok = ok.all(axis=2)
    return float(pixel_ok.mean()), float(np.abs(z).max()) if var.max() > 0 else 0.0


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--spp", type=int, default=1024, help="samples per pixel of each renderer (Mitsuba: over all seeds)")
    ap.add_argument("--seeds", type=int, default=16)
    ap.add_argument("--only", default="")
    ap.add_argument("--keep", metavar="DIR", help="write the XML files and images here")
    args = ap.parse_args()
    mi.set_variant("scalar_rgb")
    print(f"Mitsuba {mi.__version__} scalar_rgb, {os.cpu_count()} CPUs, lamplight {LAMPLIGHT}")
    only = [s for s in args.only.split(",") if s]
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        work = args.keep or tmp
        os.makedirs(work, exist_ok=True)
        cases_mod.write_assets(work)
        for case in cases_mod.CASES:
            if only and case.name not in only:
                continue
            path = os.path.join(work, case.name + ".xml")
            with open(path, "w") as f:
                f.write(case.xml)
            t0 = time.perf_counter()
            try:
                mi.set_variant(case.variant)
                mref, mvar = render_mitsuba(path, args.spp, args.seeds)
            except Exception as e:  # noqa: BLE001
                rows.append((case, "mitsuba error", str(e).splitlines()[0][:120], ""))
                continue
            try:
                limg, lvar, warn = render_lamplight(path, args.spp, tmp)
            except RuntimeError as e:
                rows.append((case, "lamplight error", str(e)[:160], ""))
                continue
            if limg.shape != mref.shape:
                rows.append((case, "FAIL", f"image sizes differ: {limg.shape} vs {mref.shape}", ""))
                continue
            frac, zmax = z_test(limg, lvar, mref, mvar)
            ratio = limg.mean(axis=(0, 1)) / np.maximum(mref.mean(axis=(0, 1)), 1e-12)
            verdict = "pass" if frac >= 0.9975 else "FAIL"
            detail = f"{100 * frac:.2f} % pixels pass, max |z| {zmax:.1f}, mean ratio {ratio[0]:.3f} {ratio[1]:.3f} {ratio[2]:.3f}"
            rows.append((case, verdict, detail, f"{time.perf_counter() - t0:.1f} s"))
            if args.keep:
                np.save(os.path.join(work, case.name + "_ll.npy"), limg)
                np.save(os.path.join(work, case.name + "_mi.npy"), mref)
            print(f"{case.name}: {verdict} ({detail})", flush=True)
    print()
    print("| case | plugins | result | detail |")
    print("|---|---|---|---|")
    for case, verdict, detail, _ in rows:
        print(f"| `{case.name}` | {case.plugins} | {verdict} | {detail} |")


if __name__ == "__main__":
    main()
