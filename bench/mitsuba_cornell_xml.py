#!/usr/bin/env python3
"""Mitsuba's own `mi.cornell_box()` dict written out as Mitsuba XML, rendered by
lamplight from that XML, and compared to noise with lamplight's built-in
`cornell-box` (the same scene written by hand) and with Mitsuba's render of the
dict. The comparison is the per-pixel z-test of bench/mitsuba_xml_compare.py
(Sidak-corrected at 1 %, pass at >= 99.75 % of pixels).

Usage: /work/mi-venv/bin/python bench/mitsuba_cornell_xml.py [--size 64] [--spp 1024] [--xml OUT.xml]
Run from the repository root after `cargo build -p lamplight-cli` (or set LAMPLIGHT).
"""
import argparse
import os
import subprocess
import sys
import tempfile

import numpy as np
import mitsuba as mi

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from mitsuba_xml_compare import LAMPLIGHT, render_mitsuba, z_test  # noqa: E402

TAGS = {"path": "integrator", "perspective": "sensor", "hdrfilm": "film", "independent": "sampler",
        "box": "rfilter", "gaussian": "rfilter", "tent": "rfilter", "diffuse": "bsdf", "rectangle": "shape",
        "cube": "shape", "sphere": "shape", "area": "emitter"}


def value_xml(name, v, indent):
    pad = " " * indent
    if isinstance(v, bool):
        return f'{pad}<boolean name="{name}" value="{str(v).lower()}"/>\n'
    if isinstance(v, int):
        return f'{pad}<integer name="{name}" value="{v}"/>\n'
    if isinstance(v, float):
        return f'{pad}<float name="{name}" value="{v!r}"/>\n'
    if isinstance(v, str):
        return f'{pad}<string name="{name}" value="{v}"/>\n'
    if isinstance(v, mi.ScalarTransform4f):
        m = np.array(v.matrix, dtype=np.float64)
        return f'{pad}<transform name="{name}"><matrix value="{" ".join(repr(float(x)) for x in m.ravel())}"/></transform>\n'
    if isinstance(v, dict) and v.get("type") == "rgb":
        return f'{pad}<rgb name="{name}" value="{", ".join(repr(float(x)) for x in v["value"])}"/>\n'
    if isinstance(v, dict) and v.get("type") == "ref":
        return f'{pad}<ref name="{name}" id="{v["id"]}"/>\n'
    if isinstance(v, dict):
        return object_xml(v, indent, name=name)
    raise TypeError(f"{name}: cannot write {type(v)}")


def object_xml(d, indent, name=None, id=None):
    pad = " " * indent
    tag = TAGS[d["type"]]
    attrs = f' type="{d["type"]}"' + (f' id="{id}"' if id else "") + (f' name="{name}"' if name and tag not in ("film", "sampler", "rfilter", "emitter", "bsdf") else "")
    body = "".join(value_xml(k, v, indent + 4) for k, v in d.items() if k != "type")
    return f"{pad}<{tag}{attrs}>\n{body}{pad}</{tag}>\n"


def scene_xml(d):
    out = '<scene version="3.0.0">\n'
    for key, v in d.items():
        if key == "type":
            continue
        tag = TAGS[v["type"]]
        out += object_xml(v, 4, id=key if tag in ("bsdf", "shape") else None)
    return out + "</scene>\n"


def render_lamplight(args_scene, spp, tmp, extra=()):
    out, var = os.path.join(tmp, "l.exr"), os.path.join(tmp, "l_var.exr")
    cmd = [LAMPLIGHT, "render", args_scene, "--spp", str(spp), "--quiet", "-o", out, "--variance-output", var, *extra]
    subprocess.run(cmd, check=True)
    return np.array(mi.Bitmap(out), dtype=np.float64)[:, :, :3], np.array(mi.Bitmap(var), dtype=np.float64)[:, :, :3]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--size", type=int, default=64)
    ap.add_argument("--spp", type=int, default=1024)
    ap.add_argument("--seeds", type=int, default=16)
    ap.add_argument("--xml", help="also write the XML here")
    args = ap.parse_args()
    mi.set_variant("scalar_rgb")
    d = mi.cornell_box()
    d["sensor"]["film"]["width"] = args.size
    d["sensor"]["film"]["height"] = args.size
    d["sensor"]["film"]["rfilter"] = {"type": "box"}
    d["sensor"]["sampler"]["sample_count"] = 0  # replaced by $spp below
    text = scene_xml(d).replace('<integer name="sample_count" value="0"/>', '<integer name="sample_count" value="$spp"/>')
    text = text.replace('<scene version="3.0.0">\n', f'<scene version="3.0.0">\n    <default name="spp" value="{args.spp}"/>\n', 1)
    if args.xml:
        with open(args.xml, "w") as f:
            f.write(text)
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "cornell_box.xml")
        with open(path, "w") as f:
            f.write(text)
        lx, vx = render_lamplight(path, args.spp, tmp)
        size = ["--width", str(args.size), "--height", str(args.size)]
        lb, vb = render_lamplight("cornell-box", args.spp, tmp,
                                  ["--integrator", "path", "--max-depth", "8", "--filter", "box", "--seed", "1", *size])
        frac, zmax = z_test(lx, vx, lb, vb)
        ratio = lx.mean(axis=(0, 1)) / lb.mean(axis=(0, 1))
        print(f"| `mi.cornell_box()` as XML vs built-in `cornell-box`, both lamplight | {args.size}x{args.size}, {args.spp} spp | "
              f"{'pass' if frac >= 0.9975 else 'FAIL'} | {100 * frac:.2f} % pixels pass, max abs z {zmax:.1f}, "
              f"mean ratio {ratio[0]:.4f} {ratio[1]:.4f} {ratio[2]:.4f} |")
        mref, mvar = render_mitsuba(path, args.spp, args.seeds)
        frac, zmax = z_test(lx, vx, mref, mvar)
        ratio = lx.mean(axis=(0, 1)) / mref.mean(axis=(0, 1))
        print(f"| `mi.cornell_box()` as XML: lamplight vs Mitsuba scalar_rgb ({args.seeds} seeds) | {args.size}x{args.size}, {args.spp} spp | "
              f"{'pass' if frac >= 0.9975 else 'FAIL'} | {100 * frac:.2f} % pixels pass, max abs z {zmax:.1f}, "
              f"mean ratio {ratio[0]:.4f} {ratio[1]:.4f} {ratio[2]:.4f} |")


if __name__ == "__main__":
    main()
