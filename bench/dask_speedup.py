#!/usr/bin/env python3
"""Speed-up of a Dask render with 2 single-threaded workers over 1.

    python bench/dask_speedup.py [--scene spheres] [--width 640] [--height 360] [--spp 24] [--tiles 64] [--runs 3]

Needs the Python package (`pip install .` or `maturin develop --release`) and
dask[distributed]. For each worker count it starts a LocalCluster of that many
worker processes with one thread each, renders once to warm up (imports, scene
build), then times `runs` renders of `lamplight.dask.render` (client side, from
the call to the stitched image) and checks every image against a local render.
It also times the same render locally on 1 and 2 threads, the ceiling the
machine allows at that moment. Prints the machine, the load average, the times
and the speed-ups of the medians.
"""

import argparse
import os
import platform
import statistics
import time

import distributed

import lamplight
import lamplight.dask


def cpu_model() -> str:
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or "unknown"


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--scene", default="spheres")
    p.add_argument("--width", type=int, default=640)
    p.add_argument("--height", type=int, default=360)
    p.add_argument("--spp", type=int, default=24)
    p.add_argument("--tiles", type=int, default=64)
    p.add_argument("--runs", type=int, default=3)
    a = p.parse_args()
    args = dict(width=a.width, height=a.height, spp=a.spp)
    print(f"nproc {os.cpu_count()}, CPU {cpu_model()}, load average at start {os.getloadavg()}")
    expected = lamplight.render(a.scene, threads=1, progress=False, **args)
    # The control: the same render in this process on 1 and 2 threads shows what
    # the machine's second core gives at the moment (it is shared).
    local = {}
    for threads in (1, 2):
        times = []
        for _ in range(a.runs):
            start = time.perf_counter()
            lamplight.render(a.scene, threads=threads, progress=False, **args)
            times.append(time.perf_counter() - start)
        local[threads] = statistics.median(times)
        print(f"local, {threads} thread(s): " + ", ".join(f"{t:.2f}" for t in times) + f" s; median {local[threads]:.2f} s")
    medians = {}
    for workers in (1, 2):
        with distributed.LocalCluster(n_workers=workers, threads_per_worker=1, processes=True, dashboard_address=":0") as cluster:
            with distributed.Client(cluster) as client:
                client.wait_for_workers(workers)
                lamplight.dask.render(a.scene, client, tiles=a.tiles, **args)  # warm-up
                times = []
                for _ in range(a.runs):
                    start = time.perf_counter()
                    image = lamplight.dask.render(a.scene, client, tiles=a.tiles, **args)
                    times.append(time.perf_counter() - start)
                    assert image.tobytes() == expected.tobytes(), "the Dask render differs from the local one"
        medians[workers] = statistics.median(times)
        print(f"{workers} worker(s) x 1 thread: " + ", ".join(f"{t:.2f}" for t in times) + f" s; median {medians[workers]:.2f} s")
    print(f"speed-up of 2 workers over 1: {medians[1] / medians[2]:.2f}x")
    print(f"local speed-up of 2 threads over 1 (the ceiling now): {local[1] / local[2]:.2f}x")
    print(f"Dask overhead with 1 worker: {medians[1] / local[1]:.2f}x the local 1-thread time")
    print(f"load average at end {os.getloadavg()}")


if __name__ == "__main__":
    main()
