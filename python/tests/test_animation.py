"""Animated scenes from Python (issue 29): ``frame=`` renders one frame, the
same numbers as the command line's ``--frames N``; a dict takes the same
``[animation]`` and ``animate`` keys as a file, with the same errors."""

import subprocess

import numpy as np
import pytest

import lamplight

TOML = """
[animation]
frames = [1, 5]
[render]
width = 24
height = 16
spp = 1
[camera]
eye = [0, 0, 5]
look_at = [0, 0, 0]
vfov = 40
[[objects]]
type = "point_light"
position = [2, 4, 5]
animate.intensity = { frames = [1, 5], values = [40, 10] }
[[objects]]
type = "sphere"
center = [0, 0, 0]
radius = 0.6
animate.translate = { frames = [1, 5], values = [[-1.5, 0, 0], [1.5, 0, 0]] }
"""

DICT = {
    "animation": {"frames": [1, 5]},
    "render": {"width": 24, "height": 16, "spp": 1},
    "camera": {"eye": [0, 0, 5], "look_at": [0, 0, 0], "vfov": 40},
    "objects": [
        {"type": "point_light", "position": [2, 4, 5], "animate": {"intensity": {"frames": [1, 5], "values": [40, 10]}}},
        {
            "type": "sphere",
            "center": [0, 0, 0],
            "radius": 0.6,
            "animate": {"translate": {"frames": [1, 5], "values": [[-1.5, 0, 0], [1.5, 0, 0]]}},
        },
    ],
}


def test_a_frame_equals_the_command_lines_frame(cli, tmp_path):
    path = tmp_path / "moving.toml"
    path.write_text(TOML)
    subprocess.run([cli, "render", str(path), "--frames", "4", "-o", str(tmp_path / "f4.exr"), "--quiet"], check=True)
    expected = lamplight.read_exr(tmp_path / "f4.exr")
    image = lamplight.render(str(path), frame=4, progress=False)
    assert image.tobytes() == expected.tobytes(), f"max difference {np.abs(image - expected).max()}"
    # The dict form is the same scene.
    assert lamplight.render(DICT, frame=4, progress=False).tobytes() == expected.tobytes()
    # One Scene renders any frame; without frame=, the first.
    scene = lamplight.Scene(str(path))
    first = lamplight.render(scene, progress=False)
    assert first.tobytes() == lamplight.render(scene, frame=1, progress=False).tobytes()
    assert first.tobytes() != lamplight.render(scene, frame=4, progress=False).tobytes()
    assert lamplight.render(scene, frame=4, progress=False).tobytes() == expected.tobytes()


def test_dict_errors_name_the_key_path():
    bad = dict(DICT, animation={"frames": [5, 1]})
    with pytest.raises(lamplight.SceneError, match=r"animation\.frames: animation: frames: \[5, 1\] must have 0 <= start <= end <= 1048574"):
        lamplight.Scene(bad)
    with pytest.raises(ValueError, match="frame must be a frame number from 0 to 1048574, got -1"):
        lamplight.render(DICT, frame=-1, progress=False)


def test_a_dict_takes_the_shutter_as_a_file_does(cli, tmp_path):
    """Motion blur from a dict: `"shutter"` in `"animation"` blurs the moving
    sphere as the file's key does (the same numbers as the command line), a
    closed shutter is the frame without blur, and a bad one gives the file's error."""
    import copy

    blurred = copy.deepcopy(DICT)
    blurred["animation"]["shutter"] = [-0.5, 0.5]
    blurred["render"]["spp"] = 16
    path = tmp_path / "blurred.toml"
    path.write_text(TOML.replace("frames = [1, 5]\n[render]", "frames = [1, 5]\nshutter = [-0.5, 0.5]\n[render]").replace("spp = 1", "spp = 16"))
    subprocess.run([cli, "render", str(path), "--frames", "3", "-o", str(tmp_path / "b3.exr"), "--quiet"], check=True)
    expected = lamplight.read_exr(tmp_path / "b3.exr")
    image = lamplight.render(blurred, frame=3, progress=False)
    assert image.tobytes() == expected.tobytes(), f"max difference {np.abs(image - expected).max()}"
    sharp = copy.deepcopy(DICT)
    sharp["render"]["spp"] = 16
    closed = copy.deepcopy(sharp)
    closed["animation"]["shutter"] = [0, 0]
    assert lamplight.render(closed, frame=3, progress=False).tobytes() == lamplight.render(sharp, frame=3, progress=False).tobytes()
    assert image.tobytes() != lamplight.render(sharp, frame=3, progress=False).tobytes()
    bad = copy.deepcopy(DICT)
    bad["animation"]["shutter"] = [1, 0]
    with pytest.raises(lamplight.SceneError, match=r"animation: shutter: \[1, 0\] must have open <= close, both within ±1000 frames"):
        lamplight.render(bad, frame=3, progress=False)
