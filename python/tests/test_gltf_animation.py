"""A glTF file's animation from Python (issue 29): ``frame=`` poses Khronos'
BoxAnimated (the scene crate's test data, CC BY 4.0) as the command line's
``--frames N`` does, to the byte."""

import subprocess

import numpy as np

import lamplight
from conftest import ROOT

BOX = ROOT / "crates" / "lamplight-scene" / "tests" / "data" / "gltf" / "BoxAnimated" / "BoxAnimated.gltf"
SMALL = {"width": 24, "height": 16, "spp": 1}


def test_a_gltf_frame_equals_the_command_lines_frame(cli, tmp_path):
    out = tmp_path / "f45.exr"
    subprocess.run([cli, "render", str(BOX), "--frames", "45", "--width", "24", "--height", "16", "--spp", "1",
                    "-o", str(out), "--quiet"], check=True)
    expected = lamplight.read_exr(out)
    image = lamplight.render(str(BOX), frame=45, progress=False, **SMALL)
    assert image.tobytes() == expected.tobytes(), f"max difference {np.abs(image - expected).max()}"
    # Without frame=, the first frame; the box has moved by frame 45.
    first = lamplight.render(str(BOX), progress=False, **SMALL)
    assert first.tobytes() == lamplight.render(str(BOX), frame=0, progress=False, **SMALL).tobytes()
    assert first.tobytes() != image.tobytes()
