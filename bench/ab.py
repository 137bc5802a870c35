#!/usr/bin/env python3
"""Two builds of lamplight side by side: same bytes, and which is faster.

    python3 bench/ab.py OLD NEW [--rounds 30] [--cases spheres,luxo,cornell] [--threads 1]

Cases: spheres, luxo, cornell (path-traced, 8 spp), cornell16 (16 spp, the
peer table's), card, bunny (the Stanford bunny path-traced: a mesh's own walk;
needs ../shared/data or LAMPLIGHT_BUNNY).

OLD and NEW are `lamplight` binaries (copy the build before a change somewhere
first, e.g. `cp target/release/lamplight /tmp/lamplight-old`). For each case it
first renders once with both and compares the output files byte for byte (a
speed change must not change an image: `--no-cmp` skips this). Then it runs the
cases in rounds, OLD and NEW back to back in each round, in alternating order,
and reports for each case:

- the median and the minimum of the process's CPU time (user + system, from
  `wait4`), for each build, and NEW / OLD;
- in how many rounds NEW took less CPU time than OLD in the same round.

Why this shape: the project's 2-core VMs share their host, and one run of the
same binary varies by 10-20 % (BENCHMARKS.md, issue 24). Back-to-back pairs see
the same load, so the count of rounds NEW wins is robust to slow drift; the
medians and minimums over many rounds say by how much. A change of a few percent
needs 30 rounds or more; count instructions with scripts/bench-guard.sh too.
Needs only the standard library.
"""
import argparse
import filecmp
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from machine import cpu_model  # noqa: E402

# The Stanford bunny of the shared data, for the `bunny` case.
BUNNY = Path(os.environ.get("LAMPLIGHT_BUNNY", Path(__file__).resolve().parents[2] / "shared/data/meshes/stanford-bunny.obj"))

# Each case: lamplight arguments, `{out}` the output file. Small enough that a
# round of all of them takes about a second on one thread.
CASES = {
    "spheres": ["render", "spheres", "--width", "640", "--height", "360", "--spp", "1", "-o", "{out}/spheres.png"],
    "luxo": ["render", "luxo", "--width", "640", "--height", "360", "--spp", "1", "-o", "{out}/luxo.png"],
    "cornell": ["render", "cornell-box", "--integrator", "path", "--max-depth", "8", "--filter", "box",
                "--width", "256", "--height", "256", "--spp", "8", "-o", "{out}/cornell.exr"],
    # The peer table's spp (16: passes of 1, 1, 2, 4 and 8 samples), at a quarter of its pixels.
    "cornell16": ["render", "cornell-box", "--integrator", "path", "--max-depth", "8", "--filter", "box",
                  "--width", "256", "--height", "256", "--spp", "16", "-o", "{out}/cornell16.exr"],
    "card": ["render", "business-card", "--width", "320", "--height", "240", "-o", "{out}/card.png"],
    # A mesh's own walk (69,451 triangles), path-traced; needs ../shared/data.
    "bunny": ["render", str(BUNNY), "--integrator", "path", "--width", "200", "--height", "200", "--spp", "8",
              "-o", "{out}/bunny.exr"],
}


def command(binary, case, out, threads):
    args = [a.replace("{out}", str(out)) for a in CASES[case]]
    return [str(binary), *args, "--threads", str(threads), "--quiet"]


def cpu_ms(cmd):
    """Runs `cmd`; returns (CPU ms of the child, wall ms). Exits on failure."""
    start = time.perf_counter()
    proc = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    _, status, usage = os.wait4(proc.pid, 0)
    wall = (time.perf_counter() - start) * 1e3
    err = proc.stderr.read().decode(errors="replace")
    proc.stderr.close()
    if os.waitstatus_to_exitcode(status) != 0:
        sys.exit(f"error: {' '.join(cmd)} failed:\n{err}")
    return (usage.ru_utime + usage.ru_stime) * 1e3, wall


def same_bytes(old, new, cases, threads):
    """Renders every case with both builds; returns the cases whose outputs differ."""
    differ = []
    with tempfile.TemporaryDirectory() as a, tempfile.TemporaryDirectory() as b:
        for case in cases:
            cpu_ms(command(old, case, a, threads))
            cpu_ms(command(new, case, b, threads))
            name = Path(CASES[case][-1]).name
            if not filecmp.cmp(Path(a) / name, Path(b) / name, shallow=False):
                differ.append(case)
    return differ


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("old", type=Path)
    ap.add_argument("new", type=Path)
    ap.add_argument("--rounds", type=int, default=30)
    ap.add_argument("--cases", default="spheres,luxo,cornell")
    ap.add_argument("--threads", type=int, default=1)
    ap.add_argument("--no-cmp", action="store_true", help="skip the byte comparison of the outputs")
    args = ap.parse_args()
    cases = [c for c in args.cases.split(",") if c]
    unknown = [c for c in cases if c not in CASES]
    if unknown:
        sys.exit(f"error: unknown case {', '.join(unknown)}; known: {', '.join(CASES)}")
    if "bunny" in cases and not BUNNY.is_file():
        sys.exit(f"error: the bunny case needs {BUNNY} (../shared/data, or set LAMPLIGHT_BUNNY)")
    for b in (args.old, args.new):
        if not os.access(b, os.X_OK):
            sys.exit(f"error: {b} is not an executable lamplight binary")
    if not 1 <= args.rounds <= 1000 or not 1 <= args.threads <= 256:
        sys.exit("error: --rounds must be 1..1000 and --threads 1..256")

    print(f"machine: {cpu_model()}, nproc {len(os.sched_getaffinity(0))}, load {os.getloadavg()[0]:.2f} at start")
    if not args.no_cmp:
        differ = same_bytes(args.old, args.new, cases, args.threads)
        print("outputs: " + ("the same bytes" if not differ else "DIFFERENT for " + ", ".join(differ)))

    times = {(case, which): [] for case in cases for which in ("old", "new")}
    with tempfile.TemporaryDirectory() as out:
        for r in range(args.rounds):
            for case in cases:
                order = [("old", args.old), ("new", args.new)]
                for which, binary in order if r % 2 == 0 else order[::-1]:
                    times[(case, which)].append(cpu_ms(command(binary, case, out, args.threads))[0])

    print(f"\n{args.rounds} rounds, {args.threads} thread(s), load {os.getloadavg()[0]:.2f} at end; CPU time per run:\n")
    print("| case | old median | new median | new / old | old min | new min | new / old | new faster in |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|")
    for case in cases:
        old, new = times[(case, "old")], times[(case, "new")]
        wins = sum(n < o for o, n in zip(old, new))
        mo, mn = statistics.median(old), statistics.median(new)
        print(f"| {case} | {mo:.1f} ms | {mn:.1f} ms | {mn / mo:.3f} | {min(old):.1f} ms | {min(new):.1f} ms | "
              f"{min(new) / min(old):.3f} | {wins} of {len(old)} rounds |")


if __name__ == "__main__":
    main()
