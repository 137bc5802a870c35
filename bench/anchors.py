#!/usr/bin/env python3
"""lamplight's speed table against its peers, every peer measured in the same run (issue 24).

    python3 bench/anchors.py                       # every row, a few minutes on 2 cores
    python3 bench/anchors.py --quick               # fewer repeats: a smoke test
    python3 bench/anchors.py --only whitted,raycast
    LAMPLIGHT=/path/to/lamplight python3 bench/anchors.py

Rows (lamplight and the peer alternate; each figure is a median; the Whitted
rows' check also gives the median of the per-round ratios and the ratio of
the minimums, which the machine's load moves less):
  whitted  `spheres` and `luxo`, 1280x720, 1 spp, 2 threads: lamplight's whole
           process against POV-Ray 3.7's own trace time (bench/povray_compare.py);
           the images must agree to within 1 level per channel.
  path     Cornell box 512x512, 16 spp, depth 8, box filter: samples/s against
           Mitsuba 3 `llvm_ad_rgb` (its `independent` sampler, the cheaper); time
           to 2 % RMSE (128x128, --quick 64x64; ladder 4,16,64,256,1024 spp, each
           renderer against its own 2 x 4096-spp render, Mitsuba's `stratified`
           sampler, which reaches the goal soonest; interpolated in log-log
           between rungs, never extrapolated: a renderer that does not reach it
           by 1024 spp gives a bound, "> r") and the ratio of image means
           (bench/mitsuba_cornell.py).
  raycast  `lamplight raycast`, 1 thread, incoherent and primary rays on the bunny
           and Igea-1M, against native Embree 3 (best of its APIs), Mrays/s;
           hit/miss mismatches and structure bytes per triangle
           (bench/raycast_compare.py, bench/embree/harness.c).

Needs: povray (apt-get install povray); for path, Mitsuba 3.9.1 and numpy in a
venv (python3 -m venv /work/bench-venv && /work/bench-venv/bin/pip install numpy
mitsuba==3.9.1) and LLVM 19 (apt-get install libllvm19; DRJIT_LIBLLVM_PATH is set
to /usr/lib/x86_64-linux-gnu/libLLVM.so.19.1 when it exists: the machine's LLVM 15
aborts); for raycast, numpy and libembree-dev (apt-get install libembree-dev).
When numpy or mitsuba is missing from this Python and $BENCH_VENV (default
/work/bench-venv) has them, the script reruns itself with that venv's Python. A
row whose peer is missing is skipped with what to install; the others still run.
Ray sets go to $ANCHOR_RAYS (default /tmp/anchor-rays, generated when missing),
the Embree harness to $EMBREE_HARNESS (default /tmp/lamplight-embree/harness, built
when missing). Progress goes to stderr; stdout is the machine and a Markdown table.
"""
import argparse
import concurrent.futures
import datetime
import importlib.util
import multiprocessing
import os
import platform
import shutil
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
sys.path.insert(0, str(HERE))
LAMPLIGHT = os.environ.get("LAMPLIGHT", str(ROOT / "target/release/lamplight"))
BENCH_VENV = Path(os.environ.get("BENCH_VENV", "/work/bench-venv"))
LLVM19 = "/usr/lib/x86_64-linux-gnu/libLLVM.so.19.1"
SECTIONS = ("whitted", "path", "raycast")

# Settings of each row (the issue's), and the repeats of a full and a --quick run.
WHITTED = {"width": 1280, "height": 720, "threads": 2, "target": 5.0}
PATH = {"size": 512, "spp": 16, "target": 1.5, "ref_spp": 4096,
        "ladder": [4, 16, 64, 256, 1024], "ttq_target": 2.5, "mean_tol": 0.002}
RAYCAST = {"meshes": ["bunny", "igea-1m"], "sets": ["incoherent", "primary"], "target": 0.9,
           "bytes_per_tri": {"igea-1m": 54.6}}  # BENCHMARKS.md's Igea-1M figure, issue 11
# Time to quality at 128x128: there Mitsuba's stratified sampler reaches 2 % by 1024
# spp (0.00292 against a goal of 0.00294, 2 Dec 2026); at 64x64 it does not (0.0034,
# BENCHMARKS.md), and only a bound is known. --quick uses 64x64 for its 4x lower cost.
REPEATS = {False: {"whitted": 7, "speed": 5, "ladder": 3, "ray_rounds": 3, "ray_runs": 5, "ttq_size": 128},
           True: {"whitted": 3, "speed": 2, "ladder": 1, "ray_rounds": 1, "ray_runs": 2, "ttq_size": 64}}


def log(msg):
    """Progress, on stderr so that stdout stays the table."""
    print(msg, file=sys.stderr, flush=True)


def rerun_in_venv():
    """Reruns this script with $BENCH_VENV's Python when this one lacks numpy or
    mitsuba and that one exists (once: ANCHORS_IN_VENV marks the rerun)."""
    missing = [m for m in ("numpy", "mitsuba") if importlib.util.find_spec(m) is None]
    py = BENCH_VENV / "bin" / "python"
    if missing and py.exists() and not os.environ.get("ANCHORS_IN_VENV"):
        log(f"{sys.executable} lacks {', '.join(missing)}: rerunning with {py}")
        os.environ["ANCHORS_IN_VENV"] = "1"
        os.execv(str(py), [str(py), __file__, *sys.argv[1:]])


def loadavg():
    return " ".join(open("/proc/loadavg").read().split()[:3])


def cpu_model():
    """The model name lscpu reports, else /proc/cpuinfo's (bench/machine.py)."""
    try:
        out = subprocess.run(["lscpu"], capture_output=True, text=True, check=True).stdout
        for line in out.splitlines():
            if line.startswith("Model name:"):
                return line.split(":", 1)[1].strip()
    except (OSError, subprocess.CalledProcessError):
        pass
    from machine import cpu_model as from_cpuinfo
    return from_cpuinfo()


def nproc():
    return len(os.sched_getaffinity(0))


def skipped(workload, target, reason):
    return {"workload": workload, "target": target, "skip": reason}


def row(workload, peer, ours, ratio, target, met, check):
    return {"workload": workload, "peer": peer, "lamplight": ours, "ratio": ratio, "target": target, "met": met, "check": check}


# ---------------------------------------------------------------- Whitted vs POV-Ray

def povray_version():
    res = subprocess.run(["povray", "--version"], capture_output=True, text=True)
    first = (res.stdout + res.stderr).strip().splitlines()
    return next((l.split()[1].removesuffix(".unofficial") for l in first if l.startswith("POV-Ray")), "?")


def whitted_rows(quick):
    """The two Whitted rows: median POV-Ray trace time over median lamplight whole
    process; the image check is every pixel within 1 level on every channel."""
    import povray_compare as pc
    runs, w = REPEATS[quick]["whitted"], WHITTED
    target = f">= {w['target']:g}x; images within 1 level"
    rows = []
    for scene in ("spheres", "luxo"):
        name = f"Whitted `{scene}`, {w['width']}x{w['height']}, 1 spp, {w['threads']} threads: lamplight whole process vs POV-Ray trace time"
        log(f"whitted {scene}: {runs} alternating runs each")
        try:
            res = pc.compare(scene, LAMPLIGHT, runs, w["width"], w["height"], w["threads"])
        except (RuntimeError, OSError, subprocess.CalledProcessError) as e:
            rows.append(skipped(name, target, str(e)))
            continue
        ours, peer = statistics.median(res["lamplight"]), statistics.median(res["povray_trace"])
        img = res["image"]
        ratio = peer / ours
        # The ratio stands on the medians. Both renderers' times move with the
        # machine's load (POV-Ray's from 0.47 to 0.95 s on `spheres` within half
        # an hour, BENCHMARKS.md session 29), so the check also gives the median
        # of each round's ratio (the two runs of a round see the same load) and
        # the ratio of the minimums, for reading one table against another.
        paired = statistics.median(p / o for p, o in zip(res["povray_trace"], res["lamplight"]))
        fastest = min(res["povray_trace"]) / min(res["lamplight"])
        rows.append(row(name, f"POV-Ray {povray_version()}: {peer:.3f} s", f"{ours:.3f} s", f"{ratio:.2f}x", target,
                        ratio >= w["target"] and img["over_1"] == 0,
                        f"image: max difference {img['max']} level(s), {img['over_1']} of {img['pixels']} pixels differ by > 1; "
                        f"per-round ratios' median {paired:.2f}x, minimums' ratio {fastest:.2f}x"))
    return rows


# ---------------------------------------------------------------- path tracing vs Mitsuba

def path_rows(quick):
    """Samples/s at 512x512 x 16 spp, and time to 2 % RMSE with the mean ratio,
    against Mitsuba's llvm_ad_rgb (no fallback to scalar_rgb: another peer)."""
    p, rep = PATH, REPEATS[quick]
    speed_name = f"path tracing, Cornell box {p['size']}x{p['size']}, {p['spp']} spp, depth 8, box filter: samples/s"
    ttq_name = (f"time to 2 % RMSE, Cornell box {rep['ttq_size']}x{rep['ttq_size']} (ladder {','.join(map(str, p['ladder']))} spp, "
                f"each against its own 2 x {p['ref_spp']} spp)")
    speed_target, ttq_target = f">= {p['target']:g}x per sample", f">= {p['ttq_target']:g}x sooner; mean ratio within {p['mean_tol'] * 100:g} %"
    fail = lambda why: [skipped(speed_name, speed_target, why), skipped(ttq_name, ttq_target, why)]
    if importlib.util.find_spec("numpy") is None or importlib.util.find_spec("mitsuba") is None:
        return fail(f"Mitsuba not importable by {sys.executable}: python3 -m venv {BENCH_VENV} && "
                    f"{BENCH_VENV}/bin/pip install numpy mitsuba==3.9.1")
    if "DRJIT_LIBLLVM_PATH" not in os.environ:
        if not os.path.exists(LLVM19):
            return fail("Mitsuba's llvm_ad_rgb needs LLVM 19 (the machine's LLVM 15 aborts): apt-get install libllvm19, "
                        "or set DRJIT_LIBLLVM_PATH")
        os.environ["DRJIT_LIBLLVM_PATH"] = LLVM19
    # Mitsuba's JIT aborts the whole process on a bad LLVM: run it in a child.
    with concurrent.futures.ProcessPoolExecutor(1, mp_context=multiprocessing.get_context("fork")) as pool:
        try:
            return pool.submit(_path_rows_child, quick, speed_name, ttq_name, speed_target, ttq_target).result()
        except concurrent.futures.process.BrokenProcessPool:
            return fail(f"the Mitsuba process died (DRJIT_LIBLLVM_PATH={os.environ['DRJIT_LIBLLVM_PATH']}; LLVM 19 is known to work)")


def _path_rows_child(quick, speed_name, ttq_name, speed_target, ttq_target):
    import numpy as np
    import mitsuba_cornell as mc
    p, rep = PATH, REPEATS[quick]
    mc.LAMPLIGHT = LAMPLIGHT
    try:
        variant = mc.set_variant(("llvm_ad_rgb",))
    except SystemExit:
        why = "Mitsuba's llvm_ad_rgb variant did not load (is DRJIT_LIBLLVM_PATH LLVM 19?)"
        return [skipped(speed_name, speed_target, why), skipped(ttq_name, ttq_target, why)]
    mc.SAMPLER = "independent"  # cornell_box()'s own, Mitsuba's fastest: for samples/s
    peer = f"Mitsuba {mc.mi.__version__} `{variant}`"
    log(f"path speed: {rep['speed']} alternating runs each")
    t_l, t_m = mc.speed(p["size"], p["spp"], rep["speed"])
    n = p["size"] ** 2 * p["spp"]
    s_l, s_m = n / statistics.median(t_l), n / statistics.median(t_m)
    rows = [row(speed_name, f"{peer}, independent sampler: {s_m / 1e6:.2f} M/s", f"{s_l / 1e6:.2f} M/s", f"{s_l / s_m:.2f}x", speed_target,
                s_l / s_m >= p["target"], f"lamplight whole process {statistics.median(t_l):.2f} s, Mitsuba render {statistics.median(t_m):.2f} s")]

    mc.SAMPLER = "stratified"  # the fairer peer for quality (BENCHMARKS.md: like lamplight's Sobol points)
    log(f"path references: 2 x {p['ref_spp']} spp each at {rep['ttq_size']}x{rep['ttq_size']}")
    m1, m2, l1, l2 = mc.references(rep["ttq_size"], p["ref_spp"])
    ref_m, ref_l = 0.5 * (m1 + m2), 0.5 * (l1 + l2)
    means = ref_l.mean(axis=(0, 1)) / ref_m.mean(axis=(0, 1))
    log(f"path ladder {p['ladder']}: {rep['ladder']} alternating runs per rung")
    pts = mc.ladder_points(rep["ttq_size"], p["ladder"], ref_l, ref_m, rep["ladder"])
    goal = 0.02 * float(ref_m.mean())
    (tt_l, ok_l), (tt_m, ok_m) = reach(mc, [(r[1], r[2]) for r in pts], goal), reach(mc, [(r[3], r[4]) for r in pts], goal)
    ratio, ratio_ok = ttq_ratio(tt_l, ok_l, tt_m, ok_m, p["ttq_target"])
    means_ok = bool(np.all(np.abs(means - 1) <= p["mean_tol"]))
    shown = lambda t, ok: f"{t:.3f} s" if ok else f"> {t:.3f} s (not reached by {p['ladder'][-1]} spp)"
    check = (f"mean ratio (lamplight / Mitsuba, R G B) {' '.join(f'{m:.4f}' for m in means)}; "
             f"RMSE at {p['ladder'][-1]} spp {pts[-1][2]:.5f} / {pts[-1][4]:.5f} (goal {goal:.5f}, 2 % of the mean)")
    rows.append(row(ttq_name, f"{peer}, stratified sampler: {shown(tt_m, ok_m)}", shown(tt_l, ok_l), ratio, ttq_target,
                    ratio_ok and means_ok, check))
    return rows


def reach(mc, pts, goal):
    """(seconds to reach `goal` RMSE, True) interpolated in log-log between two
    rungs, or (the slowest rung's seconds, False) when the ladder never reaches it:
    then it is only known to take longer. Nothing is extrapolated."""
    t, extrapolated = mc.time_to_rmse(pts, goal)
    if t != t or extrapolated:  # nan: not reached
        return max(p[0] for p in pts), False
    return t, True


def ttq_ratio(t_l, ok_l, t_m, ok_m, target):
    """Mitsuba's time to quality over lamplight's, as text ("> r" when only a
    lower bound is known, "< r" an upper one), and whether it meets `target`."""
    r = t_m / t_l
    if ok_l and ok_m:
        return f"{r:.2f}x", r >= target
    if ok_l:
        return f"> {r:.2f}x", r >= target
    if ok_m:
        return f"< {r:.2f}x", False
    return "n/a (neither reached the goal)", False


# ---------------------------------------------------------------- raycast vs Embree

def embree_api(mode):
    """The harness's --mode as the Embree call it makes."""
    return {"1": "rtcIntersect1", "stream": "rtcIntersect1M"}.get(mode, f"rtcIntersect{mode}")


def embree_version():
    try:
        res = subprocess.run(["dpkg-query", "-W", "-f", "${Version}", "libembree3-3"], capture_output=True, text=True)
    except OSError:
        return "3"
    return res.stdout.split("+")[0] if res.returncode == 0 else "3"


def ensure_raycast_inputs(rc):
    """Builds the Embree harness and writes the ray sets when missing; returns
    why they could not be had, or None."""
    if not rc.HARNESS.exists():
        log(f"building the Embree harness into {rc.HARNESS.parent}")
        res = subprocess.run(["sh", str(HERE / "embree/build.sh")], capture_output=True, text=True,
                             env={**os.environ, "OUT_DIR": str(rc.HARNESS.parent)})
        if res.returncode != 0 or not rc.HARNESS.exists():
            return f"the Embree 3 harness did not build: apt-get install libembree-dev ({res.stderr.strip()[-200:]})"
    need = [f for m in RAYCAST["meshes"] for s in RAYCAST["sets"] for f in rc.files(m, s)]
    if not all(f.exists() for f in need):
        log(f"writing the ray sets into {rc.RAYS} (bench/gen_rays.py)")
        res = subprocess.run([sys.executable, str(HERE / "gen_rays.py"), "--meshes", ",".join(RAYCAST["meshes"])],
                             env={**os.environ, "ANCHOR_RAYS": str(rc.RAYS)}, capture_output=True, text=True)
        if res.returncode != 0 or not all(f.exists() for f in need):
            return f"could not write the ray sets (needs /work/shared/data/meshes): {res.stderr.strip()[-300:]}"
    return None


def raycast_rows(quick):
    """One row per mesh and ray set: lamplight and the best Embree API on 1 thread,
    `ray_rounds` alternating rounds of `ray_runs` casts each, medians of the rounds."""
    r, rep = RAYCAST, REPEATS[quick]
    names = [(m, s, f"`raycast`, 1 thread, {m}, {'incoherent' if s == 'incoherent' else 'coherent (primary)'} rays: Mrays/s")
             for m in r["meshes"] for s in r["sets"]]
    target = lambda m: f">= {r['target']:g}x, 0 hit/miss mismatches" + (f", bytes/tri <= {r['bytes_per_tri'][m]:g}" if m in r["bytes_per_tri"] else "")
    if importlib.util.find_spec("numpy") is None:
        return [skipped(n, target(m), f"numpy missing from {sys.executable}: pip install numpy (or a venv, see --help)") for m, _, n in names]
    import raycast_compare as rc
    rc.LAMPLIGHT = Path(LAMPLIGHT)
    why = ensure_raycast_inputs(rc)
    if why:
        return [skipped(n, target(m), why) for m, _, n in names]
    rows, peer = [], f"Embree {embree_version()}"
    with tempfile.TemporaryDirectory() as tmp:
        for mesh, kind, name in names:
            log(f"raycast {mesh} {kind}: {rep['ray_rounds']} rounds of {rep['ray_runs']} casts")
            rounds = [rc.measure(mesh, kind, rep["ray_runs"], Path(tmp), threads=(1,)) for _ in range(rep["ray_rounds"])]
            med = lambda key, field: statistics.median(x[key][field] for x in rounds)
            e_w, e_c, l_w, l_c = med("embree_1t", "mrays_wall"), med("embree_1t", "mrays_per_cpu_s"), med("lamplight_1t", "mrays_wall"), med("lamplight_1t", "mrays_per_cpu_s")
            agree, bytes_tri = rounds[0]["agreement"], rounds[0]["lamplight_1t"]["bytes_per_tri"]
            apis = sorted({embree_api(x["embree_1t"]["mode"]) for x in rounds})
            bytes_ok = bytes_tri <= r["bytes_per_tri"].get(mesh, float("inf"))
            check = (f"{agree['hit_mismatch']} hit/miss mismatches, t rel err max {agree['t_rel_max']:.1e}, "
                     f"{agree['prim_differs']} triangle ids differ; bytes/tri {bytes_tri:.1f} (Embree {rounds[0]['embree_bvh_bytes_per_tri']:.1f}); "
                     f"per CPU-s ratio {l_c / e_c:.2f}")
            rows.append(row(name, f"{peer} {'/'.join(apis)}: {e_w:.2f} ({e_c:.2f} per CPU-s)", f"{l_w:.2f} ({l_c:.2f} per CPU-s)",
                            f"{l_w / e_w:.2f}x", target(mesh), l_w / e_w >= r["target"] and agree["hit_mismatch"] == 0 and bytes_ok, check))
    return rows


# ---------------------------------------------------------------- the table

def table(rows):
    """The Markdown table; a skipped row says why in the peer column."""
    out = ["| workload | peer | lamplight | ratio | target | met | check |", "|---|---|---|---:|---|---|---|"]
    for r in rows:
        if "skip" in r:
            out.append(f"| {r['workload']} | skipped: {r['skip']} | | | {r['target']} | | |")
        else:
            out.append(f"| {r['workload']} | {r['peer']} | {r['lamplight']} | {r['ratio']} | {r['target']} "
                       f"| {'yes' if r['met'] else 'no'} | {r['check']} |")
    return "\n".join(out)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--quick", action="store_true", help="fewer repeats (a smoke test; figures are noisier)")
    ap.add_argument("--only", default=",".join(SECTIONS), help=f"comma-separated subset of {','.join(SECTIONS)}")
    args = ap.parse_args()
    only = [s for s in args.only.split(",") if s]
    if bad := [s for s in only if s not in SECTIONS]:
        ap.error(f"--only: unknown {', '.join(bad)}; choose from {','.join(SECTIONS)}")
    rerun_in_venv()
    if not os.path.exists(LAMPLIGHT):
        sys.exit(f"{LAMPLIGHT} not found: cargo build --release -p lamplight-cli, or set LAMPLIGHT=/path/to/lamplight")
    start, load_start = datetime.datetime.now(datetime.timezone.utc), loadavg()
    binary = Path(LAMPLIGHT).resolve()
    mtime = binary.stat().st_mtime
    rows = []
    for section in SECTIONS:
        if section in only:
            rows += {"whitted": whitted_rows, "path": path_rows, "raycast": raycast_rows}[section](args.quick)
    end = datetime.datetime.now(datetime.timezone.utc)
    built = datetime.datetime.fromtimestamp(mtime, datetime.timezone.utc)
    rebuilt = binary.stat().st_mtime != mtime
    print(f"`python3 bench/anchors.py{' --quick' if args.quick else ''}{'' if len(only) == 3 else ' --only ' + ','.join(only)}`, "
          f"{start:%Y-%m-%d %H:%M}-{end:%H:%M} UTC ({(end - start).total_seconds() / 60:.1f} min)")
    print(f"machine: nproc {nproc()}, {cpu_model()}, {platform.system()} {platform.release()}; "
          f"load average at start {load_start}, at end {loadavg()}")
    print(f"lamplight: {binary} (built {built:%Y-%m-%d %H:%M} UTC)"
          + ("; WARNING: it was rebuilt during this run, so rows may measure different builds" if rebuilt else ""))
    print()
    print(table(rows))


if __name__ == "__main__":
    main()
