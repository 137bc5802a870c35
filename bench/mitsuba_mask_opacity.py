#!/usr/bin/env python3
"""How Mitsuba 3's `mask` weights a directly lit surface of fractional opacity:
a diffuse square facing the camera and a point light, rendered with opacity 1
and with `--opacity`; prints the ratio of the two (a coverage blend, as
lamplight's alpha_mode = "blend", pbrt-v4's alpha and glTF's BLEND, gives the
opacity itself). Then how much of an emitter behind a black masked square
the camera sees through it (a coverage blend: 1 - opacity).

    DRJIT_LIBLLVM_PATH=... /work/mi-venv/bin/python bench/mitsuba_mask_opacity.py --opacity 0.35
"""
import argparse

import mitsuba as mi
import numpy as np


def square_mean(opacity, reflectance, spp, **others):
    """The mean of the image's middle 4x4 pixels: a square of `mask` `opacity`
    over a diffuse BSDF of `reflectance`, seen from 4 away, with `others` in the scene."""
    diffuse = {"type": "diffuse", "reflectance": {"type": "rgb", "value": [reflectance] * 3}}
    scene = {
        "type": "scene",
        "integrator": {"type": "path", "max_depth": 8},
        "sensor": {
            "type": "perspective", "fov": 30,
            "to_world": mi.ScalarTransform4f().look_at(origin=[0, 0, 4], target=[0, 0, 0], up=[0, 1, 0]),
            "film": {"type": "hdrfilm", "width": 16, "height": 16, "rfilter": {"type": "box"}},
            "sampler": {"type": "independent", "sample_count": spp},
        },
        "square": {"type": "rectangle", "bsdf": {"type": "mask", "opacity": opacity, "nested": diffuse}},
        **others,
    }
    return np.array(mi.render(mi.load_dict(scene)))[6:10, 6:10].mean()


def render(opacity, spp):
    """The radiance of a grey masked square lit by a point light."""
    return square_mean(opacity, 0.5, spp, light={"type": "point", "position": [0, 0, 3], "intensity": 10})


def transmission(opacity, spp):
    """The radiance seen through a black square of `opacity` in front of an emitter of radiance 1."""
    back = {"type": "rectangle", "to_world": mi.ScalarTransform4f().translate([0, 0, -1]).scale(5),
            "emitter": {"type": "area", "radiance": {"type": "rgb", "value": [1, 1, 1]}}}
    return square_mean(opacity, 0.0, spp, back=back)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--opacity", type=float, default=0.35)
    ap.add_argument("--spp", type=int, default=1024)
    args = ap.parse_args()
    mi.set_variant("scalar_rgb")
    ratio = render(args.opacity, args.spp) / render(1.0, args.spp)
    print(f"Mitsuba {mi.__version__}: opacity {args.opacity}: lit square / opaque square = {ratio:.4f} "
          f"(opacity {args.opacity:.4f}, opacity^2 {args.opacity ** 2:.4f})")
    seen = transmission(args.opacity, args.spp)
    print(f"seen through it: {seen:.4f} of the emitter behind (1 - opacity {1 - args.opacity:.4f}, "
          f"1 - opacity^2 {1 - args.opacity ** 2:.4f})")


if __name__ == "__main__":
    main()
