#!/usr/bin/env python3
"""Speed-up of a Dask render with 2 single-threaded workers over 1.

    python bench/dask_speedup.py [--scene spheres] [--width 640] [--height 360] [--spp 24] [--tiles 64] [--runs 5]

Needs the Python package (`pip install .` or `maturin develop --release`) and
dask[distributed]. For each worker count it starts a LocalCluster of that many
worker processes with one thread each, renders once to warm up (imports, scene
build), then times `runs` rounds of `lamplight.dask.render` on each (client
side, from the call to the stitched image), checking every image against a
local render. Each round also times the same render locally on 1 and 2
threads: the ceiling the machine allows at that moment. The four measurements
alternate within each round, so a shared machine's drifting load falls on all.
Prints the machine, the load average, the times and the speed-ups of the medians.
"""

import argparse
import os
from machine import cpu_model  # bench/machine.py, beside this script
import statistics
import time

import distributed

import lamplight
import lamplight.dask


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--scene", default="spheres")
    p.add_argument("--width", type=int, default=640)
    p.add_argument("--height", type=int, default=360)
    p.add_argument("--spp", type=int, default=24)
    p.add_argument("--tiles", type=int, default=64)
    p.add_argument("--runs", type=int, default=5)
    a = p.parse_args()
    args = dict(width=a.width, height=a.height, spp=a.spp)
    print(f"nproc {os.cpu_count()}, CPU {cpu_model()}, load average at start {os.getloadavg()}")
    expected = lamplight.render(a.scene, threads=1, progress=False, **args)
    clusters = {n: distributed.LocalCluster(n_workers=n, threads_per_worker=1, processes=True, dashboard_address=":0") for n in (1, 2)}
    clients = {n: distributed.Client(c) for n, c in clusters.items()}
    for n, client in clients.items():
        client.wait_for_workers(n)
        lamplight.dask.render(a.scene, client, tiles=a.tiles, **args)  # warm-up: imports, scene build

    def local(threads):
        lamplight.render(a.scene, threads=threads, progress=False, **args)

    def dask(workers):
        image = lamplight.dask.render(a.scene, clients[workers], tiles=a.tiles, **args)
        assert image.tobytes() == expected.tobytes(), "the Dask render differs from the local one"

    # Rounds alternate the four measurements, so that the load of the shared
    # machine, which drifts, falls on all of them alike.
    cases = {"local, 1 thread": (local, 1), "local, 2 threads": (local, 2), "dask, 1 worker x 1 thread": (dask, 1), "dask, 2 workers x 1 thread": (dask, 2)}
    times = {name: [] for name in cases}
    for _ in range(a.runs):
        for name, (run, n) in cases.items():
            start = time.perf_counter()
            run(n)
            times[name].append(time.perf_counter() - start)
    for client in clients.values():
        client.close()
    for cluster in clusters.values():
        cluster.close()
    med = {name: statistics.median(t) for name, t in times.items()}
    for name, t in times.items():
        print(f"{name}: " + ", ".join(f"{x:.2f}" for x in t) + f" s; median {med[name]:.2f} s")
    medians = {1: med["dask, 1 worker x 1 thread"], 2: med["dask, 2 workers x 1 thread"]}
    local = {1: med["local, 1 thread"], 2: med["local, 2 threads"]}
    print(f"speed-up of 2 workers over 1: {medians[1] / medians[2]:.2f}x")
    print(f"local speed-up of 2 threads over 1 (the ceiling now): {local[1] / local[2]:.2f}x")
    print(f"Dask overhead with 1 worker: {medians[1] / local[1]:.2f}x the local 1-thread time")
    print(f"load average at end {os.getloadavg()}")


if __name__ == "__main__":
    main()
