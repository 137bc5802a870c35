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


# The principled BSDF (crates/lamplight-core/src/bsdfs/principled.rs): albedo per
# channel for `wi` at 0, 30, 60, 80 degrees, and eval() (f cos, per channel) and
# pdf() from `wi` at 30 degrees (and from below, -30 degrees, for spec_trans)
# towards five directions, two of them below the surface.
def rgb(v):
    return " ".join(f"{v[k]:.7g}" for k in range(3))


def albedo_rgb(bsdf, wi, n=200):
    si = mi.SurfaceInteraction3f()
    si.wi = wi
    ctx = mi.BSDFContext()
    rs = random.Random(1)
    total = [0.0, 0.0, 0.0]
    for i in range(n):
        for j in range(n):
            _, w = bsdf.sample(ctx, si, rs.random(), mi.Point2f((i + 0.5) / n, (j + 0.5) / n))
            for k in range(3):
                total[k] += w[k]
    return [t / (n * n) for t in total]


PRINCIPLED = {
    "dielectric": {"base_color": {"type": "rgb", "value": [0.7, 0.3, 0.2]}},
    "white": {"base_color": {"type": "rgb", "value": [1, 1, 1]}, "roughness": 0.2},
    "metal": {"base_color": {"type": "rgb", "value": [0.9, 0.6, 0.3]}, "metallic": 1.0, "roughness": 0.3},
    "glass": {"base_color": {"type": "rgb", "value": [0.9, 0.9, 0.7]}, "spec_trans": 0.8, "roughness": 0.2, "eta": 1.5},
    "coated": {"base_color": {"type": "rgb", "value": [0.2, 0.5, 0.7]}, "metallic": 0.3, "spec_tint": 0.4, "sheen": 0.8,
               "sheen_tint": 0.5, "clearcoat": 0.7, "clearcoat_gloss": 0.6, "specular": 0.3, "roughness": 0.4},
}
for name, params in PRINCIPLED.items():
    bsdf = mi.load_dict({"type": "principled", **params})
    for t in (0, 30, 60, 80):
        print(f"principled {name} albedo theta {t}", rgb(albedo_rgb(bsdf, direction(t, 0.4))))
    for theta_i in (30, -30) if "spec_trans" in params else (30,):
        si = mi.SurfaceInteraction3f()
        si.wi = direction(30, 0.4) if theta_i > 0 else -direction(30, 0.4)
        ctx = mi.BSDFContext()
        for wo in (direction(10, 2.0), direction(50, 3.0), direction(70, 0.4 + math.pi), direction(150, 0.4 + math.pi), direction(120, 1.0)):
            print(f"principled {name} from {theta_i}", rgb(bsdf.eval(ctx, si, wo)), f"pdf {bsdf.pdf(ctx, si, wo):.7g}")

# The thin principled sheet (crates/lamplight-core/src/bsdfs/principled_thin.rs) and
# the principled one with flatness: the same numbers, `wi` from outside.
THIN = {
    "thin_leaf": {"base_color": {"type": "rgb", "value": [0.3, 0.6, 0.2]}, "spec_trans": 0.4, "diff_trans": 0.8,
                  "roughness": 0.4, "eta": 1.4, "sheen": 0.5, "sheen_tint": 0.3, "spec_tint": 0.2},
    "thin_flat": {"base_color": {"type": "rgb", "value": [0.8, 0.5, 0.4]}, "diff_trans": 1.5, "flatness": 0.6, "roughness": 0.6},
}
for name, params in list(THIN.items()) + [("flat", {"base_color": {"type": "rgb", "value": [0.8, 0.5, 0.4]}, "flatness": 0.7, "roughness": 0.6})]:
    bsdf = mi.load_dict({"type": "principled" if name == "flat" else "principledthin", **params})
    for t in (0, 30, 60, 80):
        print(f"principled {name} albedo theta {t}", rgb(albedo_rgb(bsdf, direction(t, 0.4))))
    si = mi.SurfaceInteraction3f()
    si.wi = direction(30, 0.4)
    ctx = mi.BSDFContext()
    for wo in (direction(10, 2.0), direction(50, 3.0), direction(70, 0.4 + math.pi), direction(150, 0.4 + math.pi), direction(120, 1.0)):
        print(f"principled {name} from 30", rgb(bsdf.eval(ctx, si, wo)), f"pdf {bsdf.pdf(ctx, si, wo):.7g}")
