#!/usr/bin/env python3
"""Times `lamplight render SCENE` against POV-Ray 3.7 on the same machine, in one run.

lamplight is timed as a whole process (start to PNG written, as the issue asks;
an extra untimed run writes the PPM that is compared with POV-Ray's); POV-Ray by
its own "Trace Time" (its process also idles ~0.7 s at start and stop, see
shared/anchors/README.md). Runs alternate between the two, and medians are
reported. Both write 8-bit sRGB PPM images, which are then compared.

    python3 bench/povray_compare.py [--scene spheres] [--runs 7] [--width 1280 --height 720]

Needs `povray` (apt-get install povray) and a release build of lamplight
(cargo build --release). Prints a Markdown table for BENCHMARKS.md.
"""
import argparse
import os
from machine import cpu_model  # bench/machine.py, beside this script
import re
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
POV_DIR = os.path.join(ROOT, "..", "shared", "anchors", "povray")  # worktrees sit beside /work/shared


def read_ppm(path):
    """Reads a binary (P6) PPM: header tokens separated by whitespace, `#` comments allowed."""
    with open(path, "rb") as f:
        data = f.read()
    tokens, pos = [], 0
    while len(tokens) < 4:
        while data[pos:pos + 1].isspace():
            pos += 1
        if data[pos:pos + 1] == b"#":
            pos = data.index(b"\n", pos) + 1
            continue
        start = pos
        while not data[pos:pos + 1].isspace():
            pos += 1
        tokens.append(data[start:pos])
    if tokens[0] != b"P6":
        raise ValueError(f"{path}: not a binary PPM")
    width, height, maxval = int(tokens[1]), int(tokens[2]), int(tokens[3])
    pixels = data[pos + 1:]
    if maxval > 255:  # 16-bit big-endian samples: keep the 8-bit value they round to
        pixels = bytes(min(255, round(int.from_bytes(pixels[i:i + 2], "big") * 255 / maxval)) for i in range(0, 2 * width * height * 3, 2))
    return width, height, pixels[: width * height * 3]


def image_diff(a, b):
    """Compares two 8-bit RGB byte strings of equal size: mean absolute difference
    over all samples, the largest difference, and per pixel (worst channel) how many
    differ by more than 1 and by more than 2 levels."""
    diffs = [abs(x - y) for x, y in zip(a, b)]
    per_pixel = [max(diffs[i:i + 3]) for i in range(0, len(diffs), 3)]
    return {"mean_abs": sum(diffs) / len(diffs), "max": max(diffs, default=0),
            "over_1": sum(1 for d in per_pixel if d > 1), "over_2": sum(1 for d in per_pixel if d > 2),
            "pixels": len(per_pixel)}


def compare(scene, lamplight, runs=7, width=1280, height=720, threads=2, pov_dir=None):
    """Renders SCENE with lamplight and POV-Ray, alternating, `runs` times each.
    Returns lamplight's whole-process times, POV-Ray's trace times and whole-process
    times (seconds), and image_diff() of the two PPM images. Raises RuntimeError
    with what to install when a program is missing."""
    if not shutil.which("povray"):
        raise RuntimeError("povray not found: apt-get install povray")
    if not os.path.exists(lamplight):
        raise RuntimeError(f"{lamplight} not found: cargo build --release")
    pov_src = os.path.join(pov_dir or POV_DIR, f"{scene}.pov")
    work = tempfile.mkdtemp(prefix="lamplight-bench-")
    try:
        shutil.copy(pov_src, work)
        ll_out = os.path.join(work, "lamplight.ppm")
        pov_out = os.path.join(work, "povray.ppm")
        ll_base = [lamplight, "render", scene, "--width", str(width), "--height", str(height),
                   "--spp", "1", "--threads", str(threads), "--quiet", "-o"]
        ll_cmd = ll_base + [os.path.join(work, "lamplight.png")]
        pov_cmd = ["povray", "-D", "-A", f"+W{width}", f"+H{height}", f"+WT{threads}", "+FP",
                   f"+O{pov_out}", f"{scene}.pov"]
        ll_times, pov_times, pov_wall = [], [], []
        for _ in range(runs):
            start = time.perf_counter()
            subprocess.run(ll_cmd, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
            ll_times.append(time.perf_counter() - start)
            start = time.perf_counter()
            res = subprocess.run(pov_cmd, cwd=work, check=True, capture_output=True, text=True)
            pov_wall.append(time.perf_counter() - start)
            m = re.search(r"Trace Time:.*\(([\d.]+) seconds\)", res.stderr + res.stdout)
            if not m:
                raise RuntimeError("could not find POV-Ray's Trace Time in its output")
            pov_times.append(float(m.group(1)))
        subprocess.run(ll_base + [ll_out], check=True)
        w1, h1, a = read_ppm(ll_out)
        w2, h2, b = read_ppm(pov_out)
        if (w1, h1) != (w2, h2):
            raise RuntimeError("image sizes differ")
        return {"lamplight": ll_times, "povray_trace": pov_times, "povray_wall": pov_wall, "image": image_diff(a, b)}
    finally:
        shutil.rmtree(work)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--scene", default="spheres", choices=["spheres", "luxo"])
    ap.add_argument("--runs", type=int, default=7)
    ap.add_argument("--width", type=int, default=1280)
    ap.add_argument("--height", type=int, default=720)
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--lamplight", default=os.path.join(ROOT, "target", "release", "lamplight"))
    ap.add_argument("--pov-dir", default=POV_DIR)
    args = ap.parse_args()

    try:
        res = compare(args.scene, args.lamplight, args.runs, args.width, args.height, args.threads, args.pov_dir)
    except RuntimeError as e:
        sys.exit(str(e))
    ll_times, pov_times, pov_wall, img = res["lamplight"], res["povray_trace"], res["povray_wall"], res["image"]
    ll_med, pov_med = statistics.median(ll_times), statistics.median(pov_times)
    print(f"machine: {os.cpu_count()} CPUs, {cpu_model()}; load before: {open('/proc/loadavg').read().split()[0]}")
    print(f"scene {args.scene} {args.width}x{args.height}, 1 spp, {args.threads} threads, {args.runs} runs each (alternating)")
    print()
    print("| measure | median (s) | min | max |")
    print("|---|---:|---:|---:|")
    print(f"| lamplight whole process (to PNG) | {ll_med:.3f} | {min(ll_times):.3f} | {max(ll_times):.3f} |")
    print(f"| POV-Ray trace time | {pov_med:.3f} | {min(pov_times):.3f} | {max(pov_times):.3f} |")
    print(f"| POV-Ray whole process | {statistics.median(pov_wall):.3f} | {min(pov_wall):.3f} | {max(pov_wall):.3f} |")
    print()
    print(f"ratio POV-Ray trace time / lamplight whole process: {pov_med / ll_med:.2f}x")
    print(f"image: mean absolute difference {img['mean_abs']:.5f} (8-bit levels), largest {img['max']}, "
          f"pixels differing by more than 1 level: {img['over_1']}, by more than 2: {img['over_2']} of {img['pixels']}")


if __name__ == "__main__":
    main()
