#!/usr/bin/env python3
"""Frames on Dask: 2 single-threaded workers against 1 on a turntable (issue 29).

    python bench/dask_frames.py [--scene examples/turntable.toml] [--frames 1-24] [--width 480] [--height 270] [--runs 5]

Needs the Python package (`pip install .` or `maturin develop`) and
dask[distributed]. Starts a LocalCluster of 1 and one of 2 worker processes,
one thread each, warms both up (imports, the scene sent and built), then times
`runs` rounds; each round times, in turn, the frames rendered here one after
the other on 1 thread and saved (what one worker does, without Dask), and
`lamplight.dask.render_frames(..., out=...)` on each cluster (client side,
from the call until every frame is on disk), each into a fresh folder. Every
frame the clusters write is checked equal, byte for byte, to the local one.

The per-frame overhead is (Dask with 1 worker - local) / frames: scheduling,
sending the task, building the frame's scene on the worker, writing the file
and telling the client. Dask's own part of it is (1 worker's wall time - the
seconds its tasks took, as the workers timed them) / frames, which the load
of a shared machine disturbs less than a difference of two wall times. Prints the machine, the load average, every time and
the medians' ratios.
"""

import argparse
import os
import shutil
import statistics
import sys
import tempfile
import time

import distributed

import lamplight
import lamplight.dask
from machine import cpu_model  # bench/machine.py, beside this script

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--scene", default=os.path.join(ROOT, "examples", "turntable.toml"))
    p.add_argument("--frames", default="1-24")
    p.add_argument("--width", type=int, default=480)
    p.add_argument("--height", type=int, default=270)
    p.add_argument("--runs", type=int, default=5)
    a = p.parse_args()
    size = dict(width=a.width, height=a.height)
    frames = lamplight.frames.frame_list(a.frames)
    print(f"nproc {os.cpu_count()}, CPU {cpu_model()}, Python {sys.version.split()[0]}, distributed {distributed.__version__}")
    print(f"load average at start {os.getloadavg()}")
    scratch = tempfile.mkdtemp(prefix="lamplight-bench-frames-")
    scene = lamplight.Scene(a.scene)
    reference = os.path.join(scratch, "reference", "f_####.png")
    os.makedirs(os.path.dirname(reference))
    for f, path in zip(frames, lamplight.frames.frame_paths(reference, frames)):
        lamplight.render(scene, frame=f, threads=1, progress=False, **size).save(path)
    clusters = {n: distributed.LocalCluster(n_workers=n, threads_per_worker=1, processes=True, dashboard_address=":0") for n in (1, 2)}
    clients = {n: distributed.Client(c) for n, c in clusters.items()}
    for n, client in clients.items():
        client.wait_for_workers(n)
        lamplight.dask.render_frames(a.scene, client, frames=frames[:2], progress=False, **size)  # warm-up

    count = [0]

    def fresh() -> str:
        count[0] += 1
        os.makedirs(os.path.join(scratch, f"run{count[0]}"))
        return os.path.join(scratch, f"run{count[0]}", "f_####.png")

    def local(_):
        for f, path in zip(frames, lamplight.frames.frame_paths(fresh(), frames)):
            lamplight.render(scene, frame=f, threads=1, progress=False, **size).save(path)

    task_seconds = {1: [], 2: []}

    def dask(workers):
        out = fresh()
        done = lamplight.dask.render_frames(a.scene, clients[workers], frames=frames, out=out, progress=False, **size)
        assert done.written == frames
        for mine, ref in zip(lamplight.frames.frame_paths(out, frames), lamplight.frames.frame_paths(reference, frames)):
            with open(mine, "rb") as x, open(ref, "rb") as y:
                assert x.read() == y.read(), f"{mine} differs from the local frame"
        task_seconds[workers].append(sum(done.seconds.values()))

    cases = {"local, 1 thread, frame after frame": (local, 0), "dask, 1 worker x 1 thread": (dask, 1), "dask, 2 workers x 1 thread": (dask, 2)}
    times = {name: [] for name in cases}
    for _ in range(a.runs):
        for name, (run, n) in cases.items():
            start = time.perf_counter()
            run(n)
            times[name].append(time.perf_counter() - start)
    print(f"load average at end {os.getloadavg()}")
    medians = {name: statistics.median(t) for name, t in times.items()}
    for name, t in times.items():
        print(f"{name:36s} median {medians[name]:6.2f} s   runs {', '.join(f'{x:.2f}' for x in t)}")
    local_s, one, two = medians.values()
    n = len(frames)
    print(f"speed-up, 2 workers over 1: {one / two:.2f}x")
    print(f"1 worker against local: {one / local_s:.2f}x; per-frame overhead {(one - local_s) / n * 1000:.0f} ms of {local_s / n * 1000:.0f} ms a frame")
    tasks = statistics.median(task_seconds[1])
    print(f"task seconds summed (1 worker, median): {tasks:.2f} s; Dask's own per-frame cost (wall - tasks) / frames: {(one - tasks) / n * 1000:.0f} ms")
    for c in clients.values():
        c.close()
    for c in clusters.values():
        c.close()
    shutil.rmtree(scratch, ignore_errors=True)


if __name__ == "__main__":
    main()
