#!/usr/bin/env python3
"""Mitsuba 3 reference for lamplight's rough-glass furnace test
(crates/lamplight-core/tests/path.rs, `rough_glass_furnace_loses_only_the_microfacet_shadowing`).

A GGX `roughdielectric` sphere (ior 1.5, radius 1) in a constant white sky, seen
from (0, 0, 4) with a 30 degree vertical field of view, 8x8 pixels, box filter,
8192 spp, no Russian roulette before depth 100 (the furnace needs no cut-off: at
65 segments the remaining throughput is negligible). Prints the pixel values, the
centre 4x4 mean and the image mean for alpha 0.02, 0.1 and 0.4.

Run: DRJIT_LIBLLVM_PATH=/usr/lib/x86_64-linux-gnu/libLLVM.so.19.1 python bench/mitsuba_furnace.py
(Mitsuba 3.9.1 from PyPI, `pip install mitsuba numpy`.)
"""
import numpy as np
import mitsuba as mi

mi.set_variant('llvm_ad_rgb')
for alpha in [0.02, 0.1, 0.4]:
    scene = mi.load_dict({
        'type': 'scene',
        'integrator': {'type': 'path', 'max_depth': 65, 'rr_depth': 100},
        'sensor': {'type': 'perspective', 'fov': 30, 'fov_axis': 'y',
                   'to_world': mi.ScalarTransform4f().look_at(origin=[0,0,4], target=[0,0,0], up=[0,1,0]),
                   'film': {'type': 'hdrfilm', 'width': 8, 'height': 8, 'rfilter': {'type': 'box'}},
                   'sampler': {'type': 'independent', 'sample_count': 8192}},
        'env': {'type': 'constant', 'radiance': {'type': 'rgb', 'value': 1.0}},
        'ball': {'type': 'sphere', 'center': [0,0,0], 'radius': 1.0,
                 'bsdf': {'type': 'roughdielectric', 'distribution': 'ggx', 'alpha': alpha, 'int_ior': 1.5, 'ext_ior': 1.0}},
    })
    img = np.array(mi.render(scene, spp=8192))[:, :, 0]
    c = img[2:6, 2:6]
    print(f"mitsuba alpha {alpha}: pixels in [{img.min():.4f}, {img.max():.4f}], centre 4x4 from {c.min():.4f}, centre mean {c.mean():.4f}, image mean {img.mean():.4f}")
    np.set_printoptions(precision=3, linewidth=150)
    print(img)
