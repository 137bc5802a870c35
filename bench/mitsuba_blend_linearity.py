#!/usr/bin/env python3
"""Which renderer's blendbsdf is off in the `blendbsdf_mirror` case of
bench/mitsuba_xml_compare.py (a diffuse and a perfect mirror, weight 0.5)?

With the `direct` integrator (emitted light plus one bounce) an image is
linear in the sphere's BSDF, so the blend's image must be the mean of the two
components' images. Each renderer renders the blend and both components from
the same XML; the script prints, per renderer, the blend's image mean and the
mean of its own component images, and lamplight's over Mitsuba's.

Usage: /work/mi-venv/bin/python bench/mitsuba_blend_linearity.py (after
`cargo build --release -p lamplight-cli`, or set LAMPLIGHT).
"""
import os
import subprocess
import sys
import tempfile

import numpy as np

try:
    import mitsuba as mi
except ImportError:
    sys.exit("mitsuba is not installed (pip install mitsuba): nothing to compare against")

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from mitsuba_xml.cases import SKY, lit, scene, sphere, write_assets  # noqa: E402
from mitsuba_xml.cases_blend import DIFFUSE, MIRROR, blend  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
LAMPLIGHT = os.environ.get("LAMPLIGHT", os.path.join(ROOT, "target", "release", "lamplight"))


def main():
    mi.set_variant("scalar_rgb")
    bsdfs = {"diffuse": DIFFUSE, "mirror": MIRROR, "blend": blend('<float name="weight" value="0.5"/>', DIFFUSE, MIRROR)}
    means = {}
    with tempfile.TemporaryDirectory() as tmp:
        write_assets(tmp)
        for name, bsdf in bsdfs.items():
            path = os.path.join(tmp, name + ".xml")
            with open(path, "w") as f:
                f.write(scene(lit(SKY + sphere(bsdf)), integrator='<integrator type="direct"/>'))
            loaded = mi.load_file(path, spp="256")
            means[("mitsuba", name)] = np.mean([np.array(mi.render(loaded, seed=s, spp=256))[:, :, :3] for s in range(8)], axis=(0, 1, 2))
            out = os.path.join(tmp, name + ".exr")
            subprocess.run([LAMPLIGHT, "render", path, "-D", "spp=2048", "--quiet", "-o", out], check=True)
            means[("lamplight", name)] = np.array(mi.Bitmap(out), dtype=np.float64)[:, :, :3].mean(axis=(0, 1))
    for who in ["mitsuba", "lamplight"]:
        mix = 0.5 * (means[(who, "diffuse")] + means[(who, "mirror")])
        print(f"{who}: blend mean {np.round(means[(who, 'blend')], 4)}, mean of its components {np.round(mix, 4)}, "
              f"ratio {np.round(means[(who, 'blend')] / mix, 4)}")
    for name in bsdfs:
        print(f"lamplight / mitsuba, {name}: {np.round(means[('lamplight', name)] / means[('mitsuba', name)], 4)}")


if __name__ == "__main__":
    main()
