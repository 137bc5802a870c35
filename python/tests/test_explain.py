"""Scene.explain: the ray tree of a pixel as plain data, equal to the render's
pixel and to the command line's --json output."""

import json
import os
import re
import shlex
import subprocess

import numpy as np
import pytest

import lamplight


def _cli():
    return os.environ.get("LAMPLIGHT_CLI")


# spp None: Whitted's default adaptive anti-aliasing (16 samples where neighbours differ).
@pytest.mark.parametrize("integrator,spp", [("whitted", None), ("whitted", 1), ("whitted", 4), ("path", 4)])
def test_contributions_add_up_to_the_rendered_pixel(integrator, spp):
    scene = lamplight.Scene("luxo")
    settings = dict(width=48, height=27, spp=spp, integrator=integrator)
    image = np.asarray(lamplight.render(scene, **settings))
    for x, y in [(20, 14), (21, 18), (30, 10), (0, 0)]:
        tree = scene.explain(x, y, **settings)
        assert tree["value"] == [float(v) for v in image[y, x]]
        assert len(tree["samples"]) == tree["spp"]
        for sample in tree["samples"]:
            # Summed in the integrator's order, the contributions are the sample's radiance exactly.
            total = [0.0, 0.0, 0.0]
            for c in sample["contributions"]:
                total = [t + v for t, v in zip(total, c)]
            assert total == sample["radiance"]
        json.dumps(tree)


def test_the_noise_threshold_is_explained_as_rendered():
    scene = lamplight.Scene("cornell-box")
    settings = dict(width=24, height=24, spp=32, noise_threshold=0.1, min_spp=4)
    image = np.asarray(lamplight.render(scene, **settings))
    for x, y in [(3, 3), (12, 12), (12, 20), (20, 5)]:
        tree = scene.explain(x, y, **settings)
        assert tree["value"] == [float(v) for v in image[y, x]]
        assert 4 <= tree["spp"] <= 32 and len(tree["samples"]) == tree["spp"]
        assert tree["sampling"]["noise_threshold"]["threshold"] == 0.1


def test_a_glass_pixel_shows_both_rays():
    tree = lamplight.Scene("luxo").explain(28, 24, width=64)
    root = tree["samples"][0]["ray"]
    assert root["kind"] == "camera" and root["hit"]["object_kind"] == "Quadric"
    assert 0 < root["reflection"]["F"] < 1
    assert root["refraction"]["one_minus_F"] == 1 - root["reflection"]["F"]
    assert [c["kind"] for c in root["children"]] == ["reflected", "refracted"]
    assert root["children"][1]["inside"]


def test_one_sample_and_bad_input():
    scene = lamplight.Scene("cornell-box")
    one = scene.explain(16, 16, sample=2, width=32, spp=4)
    assert [s["index"] for s in one["samples"]] == [2]
    assert "path" in one["samples"][0]
    with pytest.raises(ValueError, match=r"^pixel \(32, 0\) is outside the 32x32 image \(x from 0 to 31, y from 0 to 31\)$"):
        scene.explain(32, 0, width=32)
    with pytest.raises(ValueError, match=r"^sample 4 does not exist: the render takes 4 samples at pixel \(0, 0\), numbered 0 to 3$"):
        scene.explain(0, 0, sample=4, width=32, spp=4)
    with pytest.raises(TypeError, match="x must be an int"):
        scene.explain(1.5, 0)


@pytest.mark.skipif(not _cli(), reason="LAMPLIGHT_CLI names no lamplight binary")
def test_the_same_tree_as_the_command_line():
    args = ["--width", "48", "--spp", "2", "--pixel", "21,18", "--json"]
    out = subprocess.run([_cli(), "explain", "luxo", *args], check=True, capture_output=True, text=True).stdout
    assert json.loads(out) == lamplight.Scene("luxo").explain(21, 18, width=48, spp=2)


def test_the_docs_examples_are_what_the_program_prints(monkeypatch):
    """docs/explain.md quotes real output: each `$ lamplight explain ...` block
    is what the command prints now, and its Python example runs."""
    from conftest import ROOT

    text = (ROOT / "docs" / "explain.md").read_text()
    for block in re.findall(r"```python\n(.*?)```", text, flags=re.S):
        exec(compile(block, "docs/explain.md", "exec"), {})
    if not _cli():
        pytest.skip("LAMPLIGHT_CLI names no lamplight binary")
    quoted = re.findall(r"^\$ lamplight (explain [^\n]*)\n(.*?)(?=^\$ |^```)", text, flags=re.S | re.M)
    assert len(quoted) >= 5
    for command, output in quoted:
        run = subprocess.run([_cli(), *shlex.split(command)], capture_output=True, text=True)
        assert run.stdout + run.stderr == output, command
