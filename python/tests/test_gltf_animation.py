"""A glTF file's animation from Python (issue 29): ``frame=`` poses Khronos'
BoxAnimated (the scene crate's test data, CC BY 4.0) as the command line's
``--frames N`` does, to the byte; ``animation=`` chooses which animation
plays, as ``--animation`` does."""

import copy
import json
import pickle
import re
import subprocess

import numpy as np
import pytest

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


def two_clips(tmp_path):
    """BoxAnimated with its animation named "Whole" and a second one, "Turn",
    of its rotation channel alone (keys 1.25 to 2.5 s: frames 0 to 60)."""
    data = json.loads(BOX.read_text())
    data["animations"][0]["name"] = "Whole"
    turn = copy.deepcopy(data["animations"][0])
    turn["name"] = "Turn"
    turn["channels"] = turn["channels"][:1]
    data["animations"].append(turn)
    path = tmp_path / "clips.gltf"
    path.write_text(json.dumps(data))
    return path


def test_animation_chooses_the_animation_by_name_or_index(cli, tmp_path):
    path = two_clips(tmp_path)
    out = tmp_path / "turn45.exr"
    subprocess.run([cli, "render", str(path), "--animation", "Turn", "--frames", "45", "--width", "24", "--height", "16",
                    "--spp", "1", "-o", str(out), "--quiet"], check=True)
    expected = lamplight.read_exr(out)
    by_name = lamplight.render(str(path), animation="Turn", frame=45, progress=False, **SMALL)
    assert by_name.tobytes() == expected.tobytes(), f"max difference {np.abs(by_name - expected).max()}"
    assert lamplight.render(str(path), animation=1, frame=45, progress=False, **SMALL).tobytes() == expected.tobytes()
    with pytest.warns(UserWarning, match=r"glTF file has 2 animations: the first plays unless --animation \(Python animation=\) chooses another"):
        assert lamplight.render(str(path), frame=45, progress=False, **SMALL).tobytes() != expected.tobytes()
    # The scene's frames follow the animation it plays.
    assert lamplight.load(path).animation == {"frames": (0, 89), "fps": 24.0}
    turn = lamplight.load(path, animation="Turn")
    assert turn.animation == {"frames": (0, 60), "fps": 24.0}
    assert pickle.loads(pickle.dumps(turn)).animation == {"frames": (0, 60), "fps": 24.0}
    assert lamplight.render(turn, frame=45, progress=False, **SMALL).tobytes() == expected.tobytes()
    has = 'it has animations 0 "Whole", 1 "Turn"'
    with pytest.raises(ValueError, match=re.escape(f'{path}: animation "Jog" names no animation of the file: {has}')):
        lamplight.render(str(path), animation="Jog", progress=False, **SMALL)
    with pytest.raises(ValueError, match=re.escape(f"{path}: animation 2 is out of range: {has}")):
        lamplight.load(path, animation=2)
    with pytest.raises(TypeError, match=r"^animation must be an animation's name \(str\) or index \(int\), got bool$"):
        lamplight.render(str(path), animation=True, progress=False, **SMALL)
    with pytest.raises(ValueError, match=r"^animation applies to a glTF file rendered directly \(\.gltf, \.glb\); 'spheres' is a built-in scene$"):
        lamplight.render("spheres", animation="Walk", progress=False, **SMALL)


def test_render_frames_follows_the_chosen_animation(client, tmp_path):
    import lamplight.dask

    path = two_clips(tmp_path)
    done = lamplight.dask.render_frames(str(path), client, out=str(tmp_path / "f_####.png"), animation="Turn",
                                        width=8, height=6, spp=1, progress=False)
    assert done.written == list(range(61)), "Turn's frames, 0 to 60"
