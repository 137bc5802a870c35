"""Whitted against direct-only path tracing on one scene (issue 13).

bench/whitted_vs_path.toml: a diffuse floor and ball under a point, a
directional, a spot and a square area light, no ambient term, black background,
max_depth 2. Both integrators should give the same image up to noise.

    .venv/bin/python bench/whitted_vs_path.py
"""

import pathlib

import numpy as np

import lamplight

scene = lamplight.Scene(str(pathlib.Path(__file__).with_name("whitted_vs_path.toml")))
whitted = np.asarray(lamplight.render(scene, integrator="whitted", spp=64, progress=False), dtype=np.float64)
path = np.asarray(lamplight.render(scene, integrator="path", spp=1024, progress=False), dtype=np.float64)
h, w, _ = whitted.shape
blocks = lambda a: a.reshape(h // 10, 10, w // 10, 10, 3).mean(axis=(1, 3))
bw, bp = blocks(whitted), blocks(path)
rel = np.abs(bp - bw) / np.maximum(bw, 0.01 * bw.max())
print(f"image mean: whitted {whitted.mean():.6f}, path {path.mean():.6f}, ratio {path.mean() / whitted.mean():.6f}")
print(f"10x10 blocks, relative difference: median {np.median(rel):.4f}, 95th percentile {np.percentile(rel, 95):.4f}, max {rel.max():.4f}")
print(f"per-pixel RMSE over the image mean: {np.sqrt(((path - whitted) ** 2).mean()) / whitted.mean():.4f}")
