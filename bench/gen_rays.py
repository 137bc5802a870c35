#!/usr/bin/env python3
"""Writes the anchor ray sets (../shared/anchors/embree/raycast_bench.py, --gen-only)
for the bunny, Igea and Igea-1M (../shared/data/meshes/igea-1m.ply, which the anchor
script does not list: it is added here with the same camera convention, so its
`primary` and `incoherent` sets are the same kinds of rays).

    ANCHOR_RAYS=/tmp/anchor-rays python3 bench/gen_rays.py [--meshes bunny,igea,igea-1m]

Embree's answers for every set are then written by the native harness
(bench/embree/run.sh), not by the Python binding. Never write these files into the
repository.
"""
import importlib.util
import sys
from pathlib import Path

ANCHOR = Path(__file__).resolve().parents[2] / "shared/anchors/embree/raycast_bench.py"
if not ANCHOR.exists():  # worktrees live beside /work/shared
    ANCHOR = Path("/work/shared/anchors/embree/raycast_bench.py")
spec = importlib.util.spec_from_file_location("raycast_bench", ANCHOR)
rb = importlib.util.module_from_spec(spec)
spec.loader.exec_module(rb)
rb.ROOT = ANCHOR.parents[3]
rb.MESHES["igea-1m"] = ("shared/data/meshes/igea-1m.ply", (0.0, 0.0, -1.0), (0.0, 1.0, 0.0))

if __name__ == "__main__":
    if "--meshes" not in sys.argv:
        sys.argv += ["--meshes", "bunny,igea,igea-1m"]
    sys.argv.append("--gen-only")
    rb.main()
