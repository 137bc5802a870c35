#!/usr/bin/env python3
"""The instruction-count guard's runner (scripts/bench-guard.sh calls it; see
BENCHMARKS.md, "Instruction-count guard (issue 24)").

Runs every case of CASES under `valgrind --tool=cachegrind --cache-sim=no`
(instructions executed, every thread of the process, nothing simulated), twice
by default to check that the count repeats, compares with bench/guard/baseline.toml
and prints case, baseline, now, change %. Exit status: 0 when no case grew by
more than the tolerance, 1 when one did, 2 for a broken setup (a render fails,
counts do not repeat).

    guard.py --bin target/release/lamplight --inputs DIR [--bunny OBJ]
             [--only a,b] [--once] [--jobs N] [--accept REASON]
"""
import argparse
import concurrent.futures
import datetime
import os
import re
import subprocess
import sys
import tempfile
from pathlib import Path

try:
    import tomllib
except ImportError:  # Python before 3.11
    sys.exit("error: bench/guard/guard.py needs Python 3.11 or newer (tomllib); set PYTHON=python3.11 or newer")

ROOT = Path(__file__).resolve().parents[2]
BASELINE = ROOT / "bench/guard/baseline.toml"
# Two runs of one case may differ by this much (per cent) and still count as repeating.
# Idle rayon workers spin and a mutex is contended a scheduler-dependent number of
# times: 5-25 thousand instructions a run, up to 0.011 % of the smallest case
# (measured); 0.05 % stays 60 times below the 3 % the guard fails on.
REPEAT_TOLERANCE = 0.05

# name -> (what it measures, argument list; {inputs}, {out}, {bunny} are filled in).
# Every case is single-threaded with a fixed seed, so its instruction count is a
# property of the code and the compiler alone.
COMMON = ["--threads", "1", "--seed", "7", "-q"]  # -q: no progress bar, whose work depends on the clock
CASES = {
    "spheres": ("Whitted, built-in `spheres`, 160x90, adaptive AA",
                ["render", "spheres", "--width", "160", "--height", "90", *COMMON, "-o", "{out}/spheres.png"]),
    "luxo": ("Whitted, built-in `luxo`, 160x90, adaptive AA",
             ["render", "luxo", "--width", "160", "--height", "90", *COMMON, "-o", "{out}/luxo.png"]),
    "cornell-path": ("path tracer, built-in `cornell-box`, 128x128, 4 spp",
                     ["render", "cornell-box", "--integrator", "path", "--width", "128", "--height", "128", "--spp", "4",
                      *COMMON, "-o", "{out}/cornell.png"]),
    "gltf-textured": ("Whitted, generated textured glTF (make_inputs.py), 160x90, adaptive AA",
                      ["render", "{inputs}/textured.gltf", "--width", "160", "--height", "90", *COMMON,
                       "-o", "{out}/gltf.png"]),
    "mitsuba-xml": ("Mitsuba 3 XML, bench/guard/mitsuba.xml, path tracer, 128x96, 4 spp",
                    ["render", str(ROOT / "bench/guard/mitsuba.xml"), *COMMON, "-o", "{out}/mitsuba.png"]),
    "raycast-bunny": ("`lamplight raycast`, Stanford bunny (69,451 triangles): build + 4096 primary + 4096 incoherent rays",
                      ["raycast", "--mesh", "{bunny}", "--origins", "{inputs}/bunny_origins.npy",
                       "--directions", "{inputs}/bunny_directions.npy", "-o", "{out}/t.npy", "--prims", "{out}/p.npy",
                       "--threads", "1"]),
}


def count(binary: str, args: list, workdir: Path) -> int:
    """Instructions executed by one run of `binary args` under cachegrind."""
    out_file = workdir / "cachegrind.out"
    cmd = ["valgrind", "--tool=cachegrind", "--cache-sim=no", f"--cachegrind-out-file={out_file}", binary, *args]
    # A fixed, small environment: the count includes the start-up code that reads it.
    env = {"PATH": os.environ.get("PATH", "/usr/bin:/bin"), "LC_ALL": "C", "HOME": str(workdir)}
    run = subprocess.run(cmd, cwd=workdir, env=env, capture_output=True, text=True)
    if run.returncode != 0:
        raise RuntimeError(f"`{' '.join(cmd)}` exited with {run.returncode}:\n{run.stdout}{run.stderr}")
    m = re.search(r"^==\d+== I\s+refs:\s+([\d,]+)", run.stderr, re.M)
    if not m:
        raise RuntimeError(f"no `I refs` line in valgrind's output of `{' '.join(cmd)}`:\n{run.stderr}")
    return int(m.group(1).replace(",", ""))


def measure(name: str, binary: str, inputs: Path, bunny: str, runs: int) -> list:
    counts = []
    for _ in range(runs):
        # The same path length every run: a fresh directory of a fixed name pattern.
        with tempfile.TemporaryDirectory(prefix="lamplight-guard-") as tmp:
            out = Path(tmp)
            args = [a.format(inputs=inputs, out=out, bunny=bunny) for a in CASES[name][1]]
            counts.append(count(binary, args, out))
    return counts


def toolchain() -> dict:
    rustc = subprocess.run(["rustc", "--version"], capture_output=True, text=True).stdout.strip()
    valgrind = subprocess.run(["valgrind", "--version"], capture_output=True, text=True).stdout.strip()
    return {"rustc": rustc, "valgrind": valgrind}


def git(*args) -> str:
    r = subprocess.run(["git", *args], cwd=ROOT, capture_output=True, text=True)
    return r.stdout.strip() if r.returncode == 0 else "unknown"


def load_baseline() -> dict:
    if not BASELINE.exists():
        return {"tolerance_percent": 3.0, "toolchain": {}, "counts": {}, "history": []}
    with BASELINE.open("rb") as f:
        data = tomllib.load(f)
    data.setdefault("tolerance_percent", 3.0)
    data.setdefault("toolchain", {})
    data.setdefault("counts", {})
    data.setdefault("history", [])
    return data


def toml_str(s: str) -> str:
    return '"' + s.replace("\\", "\\\\").replace('"', '\\"').replace("\n", " ") + '"'


def write_baseline(data: dict):
    lines = [
        "# Instruction counts of scripts/bench-guard.sh (valgrind --tool=cachegrind --cache-sim=no,",
        "# one thread, fixed seeds). Written by `scripts/bench-guard.sh --accept REASON`; edit the",
        "# reasons if you like, never the counts by hand. The guard fails when a case runs more than",
        "# tolerance_percent more instructions than its count here.",
        "",
        f"tolerance_percent = {data['tolerance_percent']}",
        "",
        "[toolchain]  # counts depend on the compiler; the guard warns when these differ",
        f"rustc = {toml_str(data['toolchain'].get('rustc', ''))}",
        f"valgrind = {toml_str(data['toolchain'].get('valgrind', ''))}",
        "",
        "[counts]  # instructions executed per case",
    ]
    lines += [f"{name} = {n:_}" for name, n in data["counts"].items()]
    lines += ["", "# Every accepted change, oldest first: why the counts moved."]
    for h in data["history"]:
        lines += ["", "[[history]]"]
        lines += [f"{k} = {toml_str(str(h[k]))}" for k in ("date", "commit", "reason", "changes") if k in h]
    BASELINE.write_text("\n".join(lines) + "\n")


def pct(now: int, base: int) -> float:
    return 100.0 * (now - base) / base


def main() -> int:
    ap = argparse.ArgumentParser(description="instruction-count guard (see scripts/bench-guard.sh)")
    ap.add_argument("--bin", required=True, help="the lamplight binary to measure")
    ap.add_argument("--inputs", required=True, type=Path, help="make_inputs.py's output directory")
    ap.add_argument("--bunny", default="", help="the Stanford bunny .obj (the raycast case skips without it)")
    ap.add_argument("--only", default="", help="comma-separated cases to run (default: all)")
    ap.add_argument("--once", action="store_true", help="one run per case (skips the repeat check)")
    ap.add_argument("--jobs", type=int, default=os.cpu_count() or 1, help="cases measured at once")
    ap.add_argument("--accept", metavar="REASON", help="write the measured counts into the baseline, with REASON")
    args = ap.parse_args()

    names = [n for n in args.only.split(",") if n] or list(CASES)
    unknown = [n for n in names if n not in CASES]
    if unknown:
        print(f"error: unknown case {', '.join(unknown)}; the cases are {', '.join(CASES)}", file=sys.stderr)
        return 2
    skipped = {}
    if "raycast-bunny" in names and not (args.bunny and Path(args.bunny).is_file()):
        skipped["raycast-bunny"] = (f"skipped: no Stanford bunny at {args.bunny or '(none given)'} (expected "
                                    "../shared/data/meshes/stanford-bunny.obj beside the clone, or LAMPLIGHT_BUNNY)")
        names.remove("raycast-bunny")

    base = load_baseline()
    tools = toolchain()
    for k in ("rustc", "valgrind"):
        if base["toolchain"].get(k) and base["toolchain"][k] != tools[k]:
            print(f"warning: the baseline was counted with `{base['toolchain'][k]}`, this is `{tools[k]}`: "
                  "counts may move with the compiler alone; re-baseline with --accept \"new toolchain\" if they do",
                  file=sys.stderr)

    runs = 1 if args.once else 2
    results, failures = {}, {}
    with concurrent.futures.ThreadPoolExecutor(max_workers=max(1, args.jobs)) as pool:
        futures = {pool.submit(measure, n, args.bin, args.inputs.resolve(), args.bunny, runs): n for n in names}
        for f in concurrent.futures.as_completed(futures):
            try:
                results[futures[f]] = f.result()
            except RuntimeError as e:
                failures[futures[f]] = str(e)
    for name, err in failures.items():
        print(f"error: case {name}: {err}", file=sys.stderr)
    if failures:
        return 2

    tol = float(base["tolerance_percent"])
    rows, grew, shrank, unstable = [], [], [], []
    for name in CASES:
        if name in skipped:
            rows.append((name, base["counts"].get(name), None, skipped[name]))
            continue
        if name not in results:
            continue
        counts = results[name]
        now = counts[0]
        if runs == 2:
            drift = abs(pct(counts[1], counts[0]))
            repeat = "repeats exactly" if drift == 0 else f"runs differ by {drift:.4f} %"
            if drift > REPEAT_TOLERANCE:
                unstable.append(name)
        else:
            repeat = "one run"
        b = base["counts"].get(name)
        if b is None:
            note = "new case, no baseline"
        else:
            change = pct(now, b)
            note = f"{change:+.2f} %"
            if change > tol:
                grew.append(name)
                note += f"  SLOWER (> {tol:g} %)"
            elif change < -tol:
                shrank.append(name)
                note += "  faster"
        rows.append((name, b, now, f"{note}; {repeat}"))

    w = max(len(r[0]) for r in rows)
    print(f"{'case':<{w}}  {'baseline':>15}  {'now':>15}  change")
    for name, b, now, note in rows:
        fb = f"{b:,}" if b is not None else "-"
        fn = f"{now:,}" if now is not None else "-"
        print(f"{name:<{w}}  {fb:>15}  {fn:>15}  {note}")

    if unstable:
        print(f"error: {', '.join(unstable)}: two runs gave counts more than {REPEAT_TOLERANCE} % apart, so the "
              "count is not deterministic; find what varies (threads, seeds, time) before trusting the guard",
              file=sys.stderr)
        return 2

    if args.accept is not None:
        if not args.accept.strip():
            print("error: --accept needs a reason, e.g. --accept \"BVH: SAH with 16 bins\"", file=sys.stderr)
            return 2
        changes = []
        for name in (n for n in CASES if n in results):
            old = base["counts"].get(name)
            new = results[name][0]
            changes.append(f"{name} {old:,} -> {new:,} ({pct(new, old):+.2f} %)" if old else f"{name} {new:,} (new)")
            base["counts"][name] = new
        base["counts"] = {n: base["counts"][n] for n in CASES if n in base["counts"]}
        base["toolchain"] = tools
        commit = git("rev-parse", "--short", "HEAD")
        if git("status", "--porcelain", "--untracked-files=no", "--", "crates", "Cargo.lock", "Cargo.toml"):
            commit += " + uncommitted changes"
        base["history"].append({"date": datetime.date.today().isoformat(), "commit": commit,
                                "reason": args.accept.strip(), "changes": "; ".join(changes)})
        write_baseline(base)
        print(f"accepted: {BASELINE.relative_to(ROOT)} now holds these counts, with the reason; commit it "
              "with the change")
        return 0

    if grew:
        print(f"FAIL: {', '.join(grew)} ran more than {tol:g} % more instructions than the baseline. Make it fast "
              "again, or, if the cost is wanted, record why: scripts/bench-guard.sh --accept \"REASON\" and commit "
              "bench/guard/baseline.toml with the change", file=sys.stderr)
        return 1
    missing = [n for n in results if n not in base["counts"]]
    if missing:
        print(f"note: {', '.join(missing)} have no baseline yet: scripts/bench-guard.sh --accept \"REASON\" adds them")
    if shrank:
        print(f"note: {', '.join(shrank)} got faster by more than {tol:g} %: tighten the baseline with "
              "scripts/bench-guard.sh --accept \"REASON\"")
    print("ok: no case grew by more than " f"{tol:g} %")
    return 0


if __name__ == "__main__":
    sys.exit(main())
