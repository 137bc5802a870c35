#!/usr/bin/env python3
"""Do lamplight and Mitsuba 3 see the Cornell box light cover the same part of each
edge pixel? Renders only the directly visible light (max depth 1) at 64x64 with a
box filter in Mitsuba (stratified and independent samplers, 65536 spp) and prints
the light's coverage (R / 18.387) of the edge pixels beside the analytic coverage
(dense ray sampling of the pixel against the rectangle at y = 0.99, |x| <= 0.23,
-0.18 <= z <= 0.2, seen from (0, 0, 3.9) with a 39.3077 degree field of view).
lamplight gives the analytic values within 0.001 at 4096 spp:
`lamplight render cornell-box --integrator path --max-depth 1 --filter box --width 64 --height 64 --spp 4096 -o d1.exr`.

Run: DRJIT_LIBLLVM_PATH=/usr/lib/x86_64-linux-gnu/libLLVM.so.19.1 python bench/mitsuba_light_edges.py
"""
import numpy as np, mitsuba as mi, time, sys
mi.set_variant('llvm_ad_rgb')
size=64
for sampler, spp in (('stratified', 65536), ('independent', 65536)):
    d = mi.cornell_box()
    d['integrator'] = {'type': 'path', 'max_depth': 1}
    d['sensor']['film']['width'] = size; d['sensor']['film']['height'] = size
    d['sensor']['film']['rfilter'] = {'type': 'box'}
    d['sensor']['sampler'] = {'type': sampler, 'sample_count': spp}
    t=time.time()
    m = np.array(mi.render(mi.load_dict(d), spp=spp, seed=11), dtype=np.float64)[:, :, 0] / 18.387
    print(sampler, spp, f'{time.time()-t:.0f}s', 'coverage (26,8) %.4f (27..36,8) %.4f (26,9) %.4f (37,9) %.4f (27..36,10) %.4f (26,10) %.4f (37,10) %.4f' % (
        m[8,26], m[8,27:37].mean(), m[9,26], m[9,37], m[10,27:37].mean(), m[10,26], m[10,37]))
print('analytic   (26,8) 0.4447 (27,8) 0.9740 (26,9) 0.2273 (37,9) 0.2273 (30,10) 0.2590 (26,10) 0.0210')
