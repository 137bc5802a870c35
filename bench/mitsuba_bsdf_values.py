"""Mitsuba 3's own numbers for the coated and thin BSDFs, which lamplight's unit
tests hold their lobes to (crates/lamplight-core/src/bsdfs/{plastic,rough_plastic,
thin_dielectric}.rs).

    /work/mi-venv/bin/python bench/mitsuba_bsdf_values.py

Prints, with Mitsuba's scalar_rgb variant: the albedo E[weight] of 200^2
stratified sample() calls (lobe choice from a seeded random stream) for `wi` at
0, 30, 60, 80 degrees (azimuth 0.4), and eval() (f cos) for `wi` at 30 degrees
towards three directions.
"""

import math
import random

import mitsuba as mi

mi.set_variant("scalar_rgb")


def direction(theta_deg, phi):
    t = math.radians(theta_deg)
    return mi.Vector3f(math.sin(t) * math.cos(phi), math.sin(t) * math.sin(phi), math.cos(t))


def albedo(bsdf, wi, n=200):
    si = mi.SurfaceInteraction3f()
    si.wi = wi
    ctx = mi.BSDFContext()
    rs = random.Random(1)
    total = 0.0
    for i in range(n):
        for j in range(n):
            _, w = bsdf.sample(ctx, si, rs.random(), mi.Point2f((i + 0.5) / n, (j + 0.5) / n))
            total += w[0]
    return total / (n * n)


def report(label, bsdf):
    albedos = [albedo(bsdf, direction(t, 0.4)) for t in (0, 30, 60, 80)]
    si = mi.SurfaceInteraction3f()
    si.wi = direction(30, 0.4)
    ctx = mi.BSDFContext()
    evals = [bsdf.eval(ctx, si, wo)[0] for wo in (direction(10, 2.0), direction(50, 3.0), direction(70, 0.4 + math.pi))]
    print(label, "albedo", " ".join(f"{a:.5f}" for a in albedos), "eval", " ".join(f"{e:.7g}" for e in evals))


white = {"type": "rgb", "value": [1, 1, 1]}
for dist in ("ggx", "beckmann"):
    for alpha in (0.05, 0.3, 0.7):
        report(f"roughplastic {dist} {alpha}", mi.load_dict({"type": "roughplastic", "alpha": alpha, "distribution": dist, "diffuse_reflectance": white}))
for nonlinear in (False, True):
    for d in (0.3, 1.0):
        report(
            f"plastic d {d} nonlinear {nonlinear}",
            mi.load_dict({"type": "plastic", "nonlinear": nonlinear, "diffuse_reflectance": {"type": "rgb", "value": [d, d, d]}}),
        )
# The thin sheet: the fraction of samples reflected is R'.
sheet = mi.load_dict({"type": "thindielectric"})
for t in (0, 30, 60, 80):
    si = mi.SurfaceInteraction3f()
    si.wi = direction(t, 0.4)
    n, reflected = 20000, 0
    for i in range(n):
        bs, _ = sheet.sample(mi.BSDFContext(), si, (i + 0.5) / n, mi.Point2f(0.5, 0.5))
        reflected += bs.wo[2] > 0
    print(f"thindielectric theta {t} reflected fraction {reflected / n:.5f}")
