#!/usr/bin/env python3
"""Time per call of `lamplight.denoise` (issue 28): the first call of a process
and the calls after it, at the viewer's frame size and a small one; wall time
and the process's CPU time (every thread's; less sensitive to a shared machine).

Since the device and filter are kept between calls (`denoise/oidn.rs`), only
the first call of a size pays for making them; before, every call did.

Usage: python bench/denoise_calls.py [--calls 10] [--sizes 256x256,640x360]
Needs the Python package and OIDN (`pip install pyoidn`, or LAMPLIGHT_OIDN).
"""
import argparse
import statistics
import time

import lamplight


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--calls", type=int, default=10)
    p.add_argument("--sizes", default="256x256,640x360")
    p.add_argument("--threads", type=int, default=0)
    args = p.parse_args()
    for size in args.sizes.split(","):
        w, h = (int(v) for v in size.split("x"))
        noisy = lamplight.render("cornell-box", width=w, height=h, spp=4, integrator="path", exr_layers=["albedo", "normal"], progress=False)
        times, cpus = [], []
        for _ in range(args.calls):
            start, cpu = time.perf_counter(), time.process_time()
            lamplight.denoise(noisy, threads=args.threads)
            times.append(time.perf_counter() - start)
            cpus.append(time.process_time() - cpu)
        rest, cpu_rest = times[1:], cpus[1:]
        print(
            f"{w}x{h}: first call {times[0] * 1e3:.0f} ms ({cpus[0] * 1e3:.0f} ms CPU), then median "
            f"{statistics.median(rest) * 1e3:.0f} ms (min {min(rest) * 1e3:.0f}, max {max(rest) * 1e3:.0f}; "
            f"CPU median {statistics.median(cpu_rest) * 1e3:.0f} ms) over {len(rest)} calls"
        )


if __name__ == "__main__":
    main()
