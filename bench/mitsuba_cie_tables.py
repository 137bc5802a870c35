#!/usr/bin/env python3
"""Writes crates/lamplight-scene/src/formats/mitsuba/cie_tables.rs: the CIE 1931
2-degree colour matching functions and the D65 illuminant at whole nanometres
from 360 to 830 nm, as Mitsuba 3 tabulates them (mi.cie1931_xyz, mi.cie_d65),
so that a `<spectrum>` of wavelength:value pairs becomes the RGB colour
`scalar_rgb` computes. Usage: /work/mi-venv/bin/python bench/mitsuba_cie_tables.py
"""
import os

import mitsuba as mi

mi.set_variant("scalar_rgb")
ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
OUT = os.path.join(ROOT, "crates/lamplight-scene/src/formats/mitsuba/cie_tables.rs")
lines = [
    "//! CIE 1931 2-degree colour matching functions and the D65 illuminant, at",
    "//! whole nanometres from 360 to 830, as Mitsuba 3 tabulates them. Generated",
    "//! by `bench/mitsuba_cie_tables.py` from Mitsuba " + mi.__version__ + "; do not edit by hand.",
    "",
    "/// Mitsuba's `MI_CIE_Y_NORMALIZATION`: one over the integral of `y`.",
    f"pub const CIE_Y_NORMALIZATION: f64 = {mi.MI_CIE_Y_NORMALIZATION!r};",
    "",
    "/// `[x, y, z, d65]` at `360 + i` nm.",
    "#[rustfmt::skip]",
    "pub const TABLE: [[f64; 4]; 471] = [",
]
for nm in range(360, 831):
    x, y, z = mi.cie1931_xyz(float(nm))
    d = mi.cie_d65(float(nm))
    lines.append(f"    [{float(x)!r}, {float(y)!r}, {float(z)!r}, {float(d)!r}],")
lines.append("];")
open(OUT, "w").write("\n".join(lines) + "\n")
print("wrote", OUT)
