#!/usr/bin/env python3
"""Side by side: `lamplight raycast` against native Embree 3 (bench/embree/harness.c)
on the anchor ray sets, in the same run, and a check that lamplight agrees with
Embree's answers (lamplight's `t` is the distance to the hit, Embree's the
parameter along the direction as given: equal for unit directions, and compared
as distances here).

    python3 bench/gen_rays.py                       # once: rays into $ANCHOR_RAYS
    bench/embree/build.sh                           # once: the Embree harness
    cargo build --release -p lamplight-cli        # or LAMPLIGHT=/path/to/another/build
    ANCHOR_RAYS=/tmp/anchor-rays python3 bench/raycast_compare.py [--meshes bunny,igea,igea-1m] [--runs 5]

For each mesh and set (`incoherent`, `primary` camera rays, and any-hit
`occlusion` on the incoherent rays) it runs every Embree API (rtcIntersect1, 8/16
packets, 1M streams; camera rays in 2x2/4x2/4x4 pixel tiles) on 1 and 2 threads,
keeps the best, and runs lamplight on 1 and 2 threads. Each figure is the median of
`--runs` casts after a warm-up. Besides wall-clock Mrays/s it prints Mrays per
CPU-second (process CPU time), which is what stays comparable when other programs
load the machine. Prints a Markdown table; needs only numpy.
"""
import argparse
import json
import os
import re
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
RAYS = Path(os.environ.get("ANCHOR_RAYS", "/tmp/anchor-rays"))
HARNESS = Path(os.environ.get("EMBREE_HARNESS", "/tmp/lamplight-embree/harness"))
LAMPLIGHT = Path(os.environ.get("LAMPLIGHT", ROOT / "target/release/lamplight"))  # or another build, for before/after
MODES = {"incoherent": ["1", "8", "16", "stream"], "primary": ["1", "4", "8", "16", "stream"], "occlusion": ["o1", "o8", "o16", "ostream"]}


def files(mesh, rays):
    return [RAYS / f"{mesh}_vertices.npy", RAYS / f"{mesh}_indices.npy", RAYS / f"{mesh}_{rays}_origins.npy", RAYS / f"{mesh}_{rays}_directions.npy"]


def embree(mesh, rays, mode, threads, runs, tile, extra=()):
    cmd = [str(HARNESS), *map(str, files(mesh, rays)), "--mode", mode, "--threads", str(threads), "--runs", str(runs), *extra]
    if tile and mode.lstrip("o") not in ("1", "stream"):
        cmd += ["--tile", str(tile)]
    return json.loads(subprocess.run(cmd, check=True, capture_output=True, text=True).stdout)


def lamplight(mesh, rays, threads, runs, out, any_hit=False):
    v, i, o, d = files(mesh, rays)
    cmd = [str(LAMPLIGHT), "raycast", "--vertices", str(v), "--indices", str(i), "--origins", str(o), "--directions", str(d),
           "-o", str(out / "t.npy"), "--threads", str(threads), "--repeat", str(runs)]
    cmd += ["--any-hit"] if any_hit else ["--prims", str(out / "p.npy")]
    text = subprocess.run(cmd, check=True, capture_output=True, text=True).stdout
    num = lambda pat: float(re.search(pat, text).group(1))
    return {"build_ms": num(r"build: ([\d.]+) ms"), "bytes_per_tri": num(r"structure ([\d.]+) bytes/triangle"),
            "with_mesh": num(r"with the mesh arrays ([\d.]+) bytes"), "mrays_wall": num(r"([\d.]+) Mrays/s"),
            "mrays_per_cpu_s": num(r"([\d.]+) Mrays per CPU-second")}


def agreement(out, ref_t, ref_p, any_hit, directions):
    """lamplight's `t` is the distance `s |d|`; Embree's is the parameter `s`
    along the direction as given. The anchor directions are unit to float32
    rounding, so the two differ by about 1e-7; Embree's is scaled by |d| (in
    float64) so that both are distances and only the casting differs."""
    t = np.load(out / "t.npy")
    ref_t = ref_t * np.linalg.norm(directions.astype(np.float64), axis=1)
    hit, ref_hit = np.isfinite(t), np.isfinite(ref_t)
    res = {"hit_mismatch": int((hit != ref_hit).sum())}
    if not any_hit:
        both = hit & ref_hit
        rel = np.abs(t[both].astype(np.float64) - ref_t[both]) / np.maximum(ref_t[both], 1e-30)
        p = np.load(out / "p.npy")
        res.update(t_rel_max=float(rel.max(initial=0)), t_rel_over_1e5=int((rel > 1e-5).sum()), prim_differs=int((p[both] != ref_p[both]).sum()))
    return res


def measure(mesh, kind, runs, tmp, threads=(1, 2)):
    """One mesh and set (`incoherent`, `primary`, `occlusion`): Embree's answers on
    1 thread with rtcIntersect1 (the reference), then for each thread count every
    Embree API (the best kept: per CPU-second on 1 thread, wall-clock otherwise)
    and lamplight, each the median of `runs` casts; lamplight's agreement with
    Embree on 1 thread. `tmp` is a scratch folder (Path)."""
    rays = "incoherent" if kind == "occlusion" else kind
    any_hit = kind == "occlusion"
    tile = 1024 if rays == "primary" else 0
    ref = embree(mesh, rays, "o1" if any_hit else "1", 1, 1, 0, ["--t-out", str(tmp / "et.npy"), "--prim-out", str(tmp / "ep.npy")])
    ref_t = np.load(tmp / "et.npy")
    ref_p = None if any_hit else np.load(tmp / "ep.npy")
    row = {"mesh": mesh, "set": kind, "triangles": ref["triangles"], "embree_bvh_bytes_per_tri": ref["bvh_bytes"] / ref["triangles"]}
    for n in threads:
        results = [embree(mesh, rays, m, n, runs, tile) for m in MODES[kind]]
        best = max(results, key=lambda r: r["mrays_per_cpu_s"] if n == 1 else r["mrays_wall"])
        ours = lamplight(mesh, rays, n, runs, tmp, any_hit)
        row[f"embree_{n}t"] = best
        row[f"embree_all_{n}t"] = {r["mode"]: (r["mrays_wall"], r["mrays_per_cpu_s"]) for r in results}
        row[f"lamplight_{n}t"] = ours
        if n == 1:
            row["agreement"] = agreement(tmp, ref_t, ref_p, any_hit, np.load(files(mesh, rays)[3]))
    return row


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--meshes", default="bunny,igea,igea-1m")
    ap.add_argument("--sets", default="incoherent,primary,occlusion")
    ap.add_argument("--runs", type=int, default=5)
    ap.add_argument("--json", help="also write all figures here")
    args = ap.parse_args()
    load = open("/proc/loadavg").read().split()[:3]
    cpu = next((l.split(":", 1)[1].strip() for l in open("/proc/cpuinfo") if l.startswith("model name")), "?")
    print(f"# {cpu}, {os.cpu_count()} cores; load average at start {' '.join(load)}", flush=True)
    rows, everything = [], []
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        for mesh in args.meshes.split(","):
            for kind in args.sets.split(","):
                row = measure(mesh, kind, args.runs, tmp)
                rows.append(row)
                e1, l1, e2, l2 = row["embree_1t"], row["lamplight_1t"], row["embree_2t"], row["lamplight_2t"]
                print(f"{mesh} {kind}: embree 1t {e1['mode']} {e1['mrays_wall']:.2f} ({e1['mrays_per_cpu_s']:.2f}/cpu-s), "
                      f"lamplight 1t {l1['mrays_wall']:.2f} ({l1['mrays_per_cpu_s']:.2f}/cpu-s); 2t {e2['mrays_wall']:.2f} vs {l2['mrays_wall']:.2f}; "
                      f"{row['agreement']}", flush=True)
    load_end = open("/proc/loadavg").read().split()[:3]
    print(f"\nload average at end {' '.join(load_end)}\n")
    print("| mesh | rays | Embree best API 1t | Embree 1t Mrays/s (per CPU-s) | lamplight 1t Mrays/s (per CPU-s) | ratio 1t (CPU) "
          "| Embree 2t | lamplight 2t | ratio 2t | build ms 1t/2t Embree | build ms 1t/2t lamplight | hit/miss mismatches, t rel err max |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|")
    for r in rows:
        e1, l1, e2, l2, a = r["embree_1t"], r["lamplight_1t"], r["embree_2t"], r["lamplight_2t"], r["agreement"]
        agree = f"{a['hit_mismatch']}" + (f", {a['t_rel_max']:.1e} ({a['t_rel_over_1e5']} > 1e-5)" if "t_rel_max" in a else "")
        print(f"| {r['mesh']} ({r['triangles']:,} tris) | {r['set']} | {e1['mode']} | {e1['mrays_wall']:.2f} ({e1['mrays_per_cpu_s']:.2f}) "
              f"| {l1['mrays_wall']:.2f} ({l1['mrays_per_cpu_s']:.2f}) | {l1['mrays_wall'] / e1['mrays_wall']:.2f} ({l1['mrays_per_cpu_s'] / e1['mrays_per_cpu_s']:.2f}) "
              f"| {e2['mrays_wall']:.2f} | {l2['mrays_wall']:.2f} | {l2['mrays_wall'] / e2['mrays_wall']:.2f} "
              f"| {e1['build_ms']:.0f} / {e2['build_ms']:.0f} | {l1['build_ms']:.0f} / {l2['build_ms']:.0f} | {agree} |")
    print("\n| mesh | Embree BVH bytes/tri | lamplight structure bytes/tri | lamplight + mesh arrays bytes/tri |\n|---|---|---|---|")
    for r in rows:
        if r["set"] == "incoherent":
            l1 = r["lamplight_1t"]
            print(f"| {r['mesh']} | {r['embree_bvh_bytes_per_tri']:.1f} | {l1['bytes_per_tri']:.1f} | {l1['with_mesh']:.1f} |")
    if args.json:
        Path(args.json).write_text(json.dumps({"load_start": load, "load_end": load_end, "rows": rows}, indent=1))


if __name__ == "__main__":
    sys.exit(main())
