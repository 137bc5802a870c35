#!/usr/bin/env python3
"""Textured scenes against Mitsuba 3: image textures with each wrap mode and
filter on a diffuse quad, a normal-mapped rough conductor, an alpha cut-out,
stochastic transparency (alpha_mode = "blend", against Mitsuba's `mask`), and
lamplight's textured `pbr` (glTF metallic-roughness) material against Mitsuba's
`principled` BSDF, as a metal and as a dielectric, per-pixel z-tested.

Every scene is a 2 x 2 quad read from the same OBJ file by both renderers, its
texture coordinates running from -0.5 to 1.5 so that the wrap mode shows,
seen at an angle by a perspective camera with a box pixel filter and lit by a
uniform sky (the conductors by a point light). The textures are PNGs
this script writes: a 16 x 16 image of random sRGB colours, a tangent-space
normal map of a sinusoidal height field, a binary 8 x 8 coverage pattern and a
coverage ramp from 0.1 to 0.9.

Both renderers render each scene K times with different seeds. Per pixel and
channel, the means of the K renders are compared with

    z = (mean_l - mean_m) / sqrt(var_l / K + var_m / K + floor^2),

`var` being each renderer's sample variance over its K renders and `floor` a
0.2 % allowance of the pixel value for what is not noise: 32-bit storage and
the renderers' different float arithmetic, which matter where a pixel's noise
is near zero (under a uniform sky a diffuse pixel is its texture's mean over
the pixel, whatever the path). A pixel passes when all three channels' |z|
stay below the two-sided Sidak-corrected 1 % threshold over all pixels; a
scene passes when at least 99.75 % of pixels do.

Usage: python bench/mitsuba_textures.py [--size 64] [--spp 16] [--renders 32] [--keep DIR] [--only TEXT]
Needs Mitsuba 3 and numpy (scalar_rgb variant); LAMPLIGHT names the binary
(default target/release/lamplight).
"""
import argparse
import math
import os
import subprocess
import tempfile
import time

import numpy as np
import mitsuba as mi

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
LAMPLIGHT = os.environ.get("LAMPLIGHT", os.path.join(ROOT, "target", "release", "lamplight"))

EYE, TARGET, VFOV = [0.0, -2.2, 2.4], [0.0, 0.0, 0.0], 45.0
# Gold-like complex index, per channel.
ETA, K = [0.2, 0.45, 1.4], [3.5, 2.4, 1.8]
ALPHA = 0.3
LIGHT = [1.0, -1.0, 2.0]
INTENSITY = 4.0
SKY = 0.5
UP = [0, 0, 1]

QUAD_OBJ = """v -1 -1 0
v 1 -1 0
v 1 1 0
v -1 1 0
vt -0.5 -0.5
vt 1.5 -0.5
vt 1.5 1.5
vt -0.5 1.5
vn 0 0 1
f 1/1/1 2/2/1 3/3/1
f 1/1/1 3/3/1 4/4/1
"""


def write_inputs(d):
    import zlib, struct

    def png(path, rgb):
        h, w, _ = rgb.shape
        raw = b"".join(b"\x00" + rgb[y].astype(np.uint8).tobytes() for y in range(h))
        chunk = lambda t, b: struct.pack(">I", len(b)) + t + b + struct.pack(">I", zlib.crc32(t + b) & 0xFFFFFFFF)
        data = b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 2, 0, 0, 0))
        data += chunk(b"IDAT", zlib.compress(raw)) + chunk(b"IEND", b"")
        with open(path, "wb") as f:
            f.write(data)

    rng = np.random.default_rng(14)
    png(os.path.join(d, "colours.png"), rng.integers(0, 256, size=(16, 16, 3)))
    # Normal map of h = 0.03 sin(2 pi 2 s) sin(2 pi 2 t) over the image (s right, t up).
    n = 64
    s = (np.arange(n) + 0.5) / n
    t = 1.0 - (np.arange(n) + 0.5) / n  # row 0 is the top of the image
    S, T = np.meshgrid(s, t)
    a, f = 0.03, 2 * math.pi * 2
    dhds = a * f * np.cos(f * S) * np.sin(f * T)
    dhdt = a * f * np.sin(f * S) * np.cos(f * T)
    nrm = np.stack([-dhds, -dhdt, np.ones_like(S)], axis=-1)
    nrm /= np.linalg.norm(nrm, axis=-1, keepdims=True)
    png(os.path.join(d, "normals.png"), np.round((nrm * 0.5 + 0.5) * 255))
    # Coverage: a binary 8 x 8 pattern (cut-outs), and a smooth ramp (blending).
    cut = (rng.random((8, 8)) < 0.5) * 255
    png(os.path.join(d, "cutout.png"), np.repeat(cut[:, :, None], 3, axis=2))
    ramp = np.round(np.linspace(0.1, 0.9, 32)[None, :].repeat(32, 0) * 255)
    png(os.path.join(d, "coverage.png"), np.repeat(ramp[:, :, None], 3, axis=2))
    # Grey levels 0.15 to 0.85 in a 4 x 4 pattern, for a textured scalar (roughness).
    grey = np.round((0.15 + 0.7 * rng.random((4, 4))) * 255)
    png(os.path.join(d, "grey.png"), np.repeat(grey[:, :, None], 3, axis=2))
    with open(os.path.join(d, "quad.obj"), "w") as f:
        f.write(QUAD_OBJ)


# name -> (lamplight material lines, Mitsuba BSDF dict, point light?, sky radiance).
# The conductors are lit by the point light alone: under the sky, Mitsuba's
# normalmap loses light that the analytic value keeps (see `sky_check`).
def scenes(d):
    def bitmap(name, wrap, filt, raw=False):
        return {"type": "bitmap", "filename": os.path.join(d, name), "wrap_mode": wrap, "filter_type": filt, "raw": raw}

    def diffuse(wrap, filt):
        ll = f'kd = 1\nka = 0\ncolor = {{ type = "image", file = "colours.png", wrap = "{wrap}", filter = "{filt}" }}'
        return ll, {"type": "diffuse", "reflectance": bitmap("colours.png", wrap, filt)}, False, SKY

    out = {f"diffuse bitmap, {w}, {f}": diffuse(w, f) for w, f in
           (("repeat", "bilinear"), ("mirror", "bilinear"), ("clamp", "bilinear"), ("repeat", "nearest"))}
    grey = 'kd = 1\nka = 0\ncolor = 0.2\n'
    white = {"type": "diffuse", "reflectance": {"type": "rgb", "value": 0.2}}
    ll = grey + 'alpha = { type = "image", file = "cutout.png", color_space = "linear", channel = "r", filter = "nearest" }'
    out["alpha cut-out (nearest)"] = (ll, {"type": "mask", "opacity": bitmap("cutout.png", "repeat", "nearest", raw=True),
                                            "bsdf": white}, False, SKY)
    ll = grey + ('alpha = { type = "image", file = "coverage.png", color_space = "linear", channel = "r" }\n'
                 'alpha_mode = "blend"')
    out["alpha blend (stochastic, vs Mitsuba's mask)"] = (
        ll, {"type": "mask", "opacity": bitmap("coverage.png", "repeat", "bilinear", raw=True), "bsdf": white}, False, SKY)
    conductor = {"type": "roughconductor", "distribution": "ggx", "alpha": ALPHA,
                 "eta": {"type": "rgb", "value": ETA}, "k": {"type": "rgb", "value": K}}
    ll = f'kd = 0\nka = 0\nroughness = {ALPHA}\nreflection = {{ type = "conductor", eta = {ETA}, k = {K} }}\n'
    out["rough conductor"] = (ll, conductor, True, 0.0)
    ll += 'normal_map = { type = "image", file = "normals.png", color_space = "linear" }'
    out["normal-mapped rough conductor"] = (
        ll, {"type": "normalmap", "normalmap": bitmap("normals.png", "repeat", "bilinear", raw=True), "bsdf": conductor}, True, 0.0)
    # glTF's metallic-roughness model against Mitsuba's principled BSDF (Disney's),
    # the base colour from the bitmap. As a metal both are GGX of alpha = r^2
    # with Schlick's Fresnel from the base colour; as a dielectric glTF has a
    # Lambert base under (1 - F) with f0 = 0.04 (principled: specular = 0.5),
    # principled has Disney's retro-reflective diffuse.
    for metallic, rough, light, sky in ((1.0, 0.5, True, 0.0), (0.0, 0.2, False, SKY), (0.0, 0.5, False, SKY), (0.0, 0.8, False, SKY)):
        ll = (f'type = "pbr"\nbase_color = {{ type = "image", file = "colours.png" }}\n'
              f'metallic = {metallic}\nroughness = {rough}')
        principled = {"type": "principled", "base_color": bitmap("colours.png", "repeat", "bilinear"),
                      "metallic": metallic, "roughness": rough, "specular": 0.5}
        kind = "metal" if metallic == 1.0 else "dielectric"
        out[f"textured pbr {kind}, roughness {rough}, vs principled"] = (ll, principled, light, sky)
        # lamplight's `principled` kind is Mitsuba's principled BSDF itself, so
        # the same textured material, read by the same texture code, must agree.
        ll = (f'type = "principled"\nbase_color = {{ type = "image", file = "colours.png" }}\n'
              f'metallic = {metallic}\nroughness = {rough}\nspecular = 0.5')
        out[f"textured principled {kind}, roughness {rough}"] = (ll, principled, light, sky)
    # A texture on a scalar weight (grey, so that the first channel is the luminance).
    ll = ('type = "principled"\nbase_color = [0.7, 0.4, 0.2]\n'
          'roughness = { type = "image", file = "grey.png", color_space = "linear" }\nclearcoat = 0.5')
    principled = {"type": "principled", "base_color": {"type": "rgb", "value": [0.7, 0.4, 0.2]},
                  "roughness": bitmap("grey.png", "repeat", "bilinear", raw=True), "clearcoat": 0.5}
    out["textured principled roughness, clearcoat"] = (ll, principled, False, SKY)
    return out


def lamplight_toml(material, light, sky):
    lines = [
        f"environment = {{ color = {sky} }}",
        "[camera]", 'type = "perspective"', f"eye = {EYE}", f"look_at = {TARGET}", f"up = {UP}", f"vfov = {VFOV}",
        "[meshes.quad]", 'file = "quad.obj"',
        "[materials.m]", material,
        "[[objects]]", 'type = "mesh"', 'mesh = "quad"', 'material = "m"',
    ]
    if light:
        # lamplight's intensity is the lecture's: the radiant intensity is pi times it.
        lines += ["[[objects]]", 'type = "point_light"', f"position = {LIGHT}", f"intensity = {INTENSITY / math.pi}"]
    return "\n".join(lines) + "\n"


def render_lamplight(d, material, light, size, spp, seed, sky=SKY):
    path = os.path.join(d, "scene.toml")
    with open(path, "w") as f:
        f.write(lamplight_toml(material, light, sky))
    out = os.path.join(d, f"l{seed}.exr")
    subprocess.run([LAMPLIGHT, "render", path, "--integrator", "path", "--max-depth", "8", "--filter", "box",
                    "--width", str(size), "--height", str(size), "--spp", str(spp), "--seed", str(seed),
                    "--quiet", "-o", out], check=True)
    return np.array(mi.Bitmap(out), dtype=np.float64)[:, :, :3]


def render_mitsuba(d, bsdf, light, size, spp, seed, sky=SKY):
    scene = {
        "type": "scene",
        "integrator": {"type": "path", "max_depth": 8},
        "sensor": {
            "type": "perspective", "fov": VFOV, "fov_axis": "y",
            "to_world": mi.ScalarTransform4f().look_at(origin=EYE, target=TARGET, up=UP),
            "film": {"type": "hdrfilm", "width": size, "height": size, "rfilter": {"type": "box"}},
            "sampler": {"type": "independent", "sample_count": spp},
        },
        "sky": {"type": "constant", "radiance": {"type": "rgb", "value": sky}},
        "quad": {"type": "obj", "filename": os.path.join(d, "quad.obj"), "bsdf": bsdf},
    }
    if light:
        scene["light"] = {"type": "point", "position": LIGHT, "intensity": {"type": "rgb", "value": INTENSITY}}
    return np.array(mi.render(mi.load_dict(scene), spp=spp, seed=seed), dtype=np.float64)[:, :, :3]


def z_test(lams, mits, alpha=0.01):
    k = len(lams)
    l, m = np.stack(lams), np.stack(mits)
    ml, mm = l.mean(0), m.mean(0)
    vl, vm = l.var(0, ddof=1), m.var(0, ddof=1)
    floor = 2e-3 * np.maximum(ml, mm)
    z = np.abs(ml - mm) / np.sqrt(vl / k + vm / k + floor ** 2 + 1e-30)
    pixels = z.shape[0] * z.shape[1]
    # Two-sided Sidak threshold for 3 channels x all pixels at family-wise 1 %.
    per_test = 1.0 - (1.0 - alpha) ** (1.0 / (3 * pixels))
    lo, hi = 0.0, 40.0
    for _ in range(100):  # erfc(z / sqrt 2) = per_test, by bisection
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if math.erfc(mid / math.sqrt(2)) > per_test else (lo, mid)
    passed = np.all(z < hi, axis=-1)
    rel = np.sqrt(np.mean((ml - mm) ** 2)) / mm.mean()
    return passed.mean(), hi, rel, ml.mean(axis=(0, 1)) / mm.mean(axis=(0, 1)), z.max()


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--size", type=int, default=64)
    ap.add_argument("--spp", type=int, default=16)
    ap.add_argument("--renders", type=int, default=32)
    ap.add_argument("--keep", metavar="DIR", help="write the inputs and the mean images here")
    ap.add_argument("--only", metavar="TEXT", help="only the scenes whose name contains TEXT")
    args = ap.parse_args()
    mi.set_variant("scalar_rgb")
    print(f"Mitsuba {mi.__version__} scalar_rgb; {args.size}x{args.size}, {args.renders} renders x {args.spp} spp per renderer")
    print("scene | pixels passing | |z| threshold | max |z| | relative RMSE of the means | mean ratio lamplight / Mitsuba (r, g, b) | verdict")
    print("---|---|---|---|---|---|---")
    d = args.keep or tempfile.mkdtemp()
    os.makedirs(d, exist_ok=True)
    write_inputs(d)
    ok = True
    for name, (material, bsdf, light, sky) in scenes(d).items():
        if args.only and args.only not in name:
            continue
        t0 = time.perf_counter()
        lams = [render_lamplight(d, material, light, args.size, args.spp, s, sky) for s in range(args.renders)]
        mits = [render_mitsuba(d, bsdf, light, args.size, args.spp, s, sky) for s in range(args.renders)]
        frac, thr, rel, ratio, zmax = z_test(lams, mits)
        verdict = "pass" if frac >= 0.9975 else "FAIL"
        ok &= verdict == "pass"
        print(f"{name} | {frac * 100:.2f} % | {thr:.2f} | {zmax:.2f} | {rel * 100:.2f} % | "
              + ", ".join(f"{r:.4f}" for r in ratio) + f" | {verdict} ({time.perf_counter() - t0:.0f} s)")
        if args.keep:
            tag = name.replace(",", "").replace(" ", "_")
            np.save(os.path.join(d, f"{tag}_lamplight.npy"), np.mean(lams, 0))
            np.save(os.path.join(d, f"{tag}_mitsuba.npy"), np.mean(mits, 0))
    if not args.only:
        sky_check(d, args.size)
    raise SystemExit(0 if ok else 1)


def sky_check(d, size):
    """A normal-mapped diffuse quad (albedo 0.5) under the uniform sky, seen from
    straight above: where a mapped normal is tilted by theta, the sky above the
    geometric surface lights it with the view factor (1 + cos theta) / 2, so the
    mean over whole periods of the map is 0.25 mean((1 + n.z) / 2)."""
    global EYE, UP
    saved = EYE, UP
    EYE, UP = [0.0, 0.0, 3.0], [0, 1, 0]
    img = np.array(mi.Bitmap(os.path.join(d, "normals.png")), dtype=np.float64) / 255.0
    n = img * 2 - 1
    n /= np.linalg.norm(n, axis=-1, keepdims=True)
    analytic = 0.25 * np.mean((1 + n[..., 2]) / 2)
    ll = 'kd = 1\nka = 0\ncolor = 0.5\nnormal_map = { type = "image", file = "normals.png", color_space = "linear" }'
    bsdf = {"type": "normalmap", "normalmap": {"type": "bitmap", "filename": os.path.join(d, "normals.png"), "raw": True},
            "bsdf": {"type": "diffuse", "reflectance": {"type": "rgb", "value": 0.5}}}
    # The centre half of the image sees one whole period of the map in each direction.
    c = slice(size // 4, 3 * size // 4)
    l = np.mean([render_lamplight(d, ll, False, size, 256, s, 0.5) for s in range(2)], 0)[c, c, 0].mean()
    m = np.mean([render_mitsuba(d, bsdf, False, size, 256, s, 0.5) for s in range(2)], 0)[c, c, 0].mean()
    print(f"\nnormal-mapped diffuse under the sky, centre mean: analytic {analytic:.5f}, "
          f"lamplight {l:.5f} ({(l / analytic - 1) * 100:+.2f} %), Mitsuba {m:.5f} ({(m / analytic - 1) * 100:+.2f} %)")
    EYE, UP = saved


if __name__ == "__main__":
    main()
