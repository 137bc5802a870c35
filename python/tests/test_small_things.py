"""Small things people reach for: importer warnings in Python, images from
arithmetic without stale stats, progress=True without tqdm says why."""

import builtins
import warnings

import numpy as np
import pytest

import lamplight
from lamplight import _render

# A quad with a line and a point element: two importer warnings.
WARNED_OBJ = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\nl 1 3\np 2\n"
EXPECTED = [
    "OBJ line elements ignored",
    "OBJ point elements ignored",
]


def test_importer_warnings_are_a_list_and_python_warnings(tmp_path):
    path = tmp_path / "quad.obj"
    path.write_text(WARNED_OBJ)
    scene = lamplight.Scene(str(path))
    with pytest.warns(UserWarning) as caught:
        scene.build()
    expected = [f"{path}: {w}" for w in EXPECTED]
    assert [str(w.message) for w in caught] == expected
    assert scene.warnings == expected
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # given once: the kept build warns no more
        assert scene.warnings == expected
        lamplight.render(scene, width=8, height=8)


def test_a_scene_file_gives_its_mesh_files_warnings(tmp_path):
    (tmp_path / "quad.obj").write_text(WARNED_OBJ)
    text = (
        '[camera]\neye = [0, 0, 5]\nlook_at = [0, 0, 0]\nvfov = 40\n[meshes.quad]\nfile = "quad.obj"\n'
        '[[objects]]\ntype = "mesh"\nmesh = "quad"\n'
        '[[objects]]\ntype = "point_light"\nposition = [0, 0, 5]\nintensity = 1\n'
    )
    (tmp_path / "s.toml").write_text(text)
    with pytest.warns(UserWarning) as caught:
        image = lamplight.render(str(tmp_path / "s.toml"), width=8, height=8)
    assert [str(w.message) for w in caught] == [f"{tmp_path / 'quad.obj'}: {w}" for w in EXPECTED]
    assert image.shape == (8, 8, 3)
    assert lamplight.Scene("spheres").warnings == []


def test_arithmetic_drops_the_stats_and_layers_of_its_operands():
    image = lamplight.render("spheres", width=16, height=9, exr_layers=["samples"])
    assert image.stats and "samples" in image.layers
    for result in [image * 2, image + image, image - 1.0, np.sqrt(image), 0.5 * image]:
        assert isinstance(result, lamplight.Image)
        assert result.stats == {} and result.layers == {}
    # A view or slice is the same data: it keeps them.
    crop = image[2:5, 3:9]
    assert crop.stats == image.stats and "samples" in crop.layers


def test_progress_true_without_tqdm_says_why_once(monkeypatch):
    real_import = builtins.__import__

    def no_tqdm(name, *args, **kwargs):
        if name.startswith("tqdm"):
            raise ImportError("No module named 'tqdm'")
        return real_import(name, *args, **kwargs)

    monkeypatch.setattr(builtins, "__import__", no_tqdm)
    monkeypatch.setattr(_render, "_warned_no_tqdm", False)
    with pytest.warns(UserWarning, match=r"progress=True shows a bar only with tqdm installed \(pip install tqdm\)"):
        lamplight.render("spheres", width=8, height=8, progress=True)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        lamplight.render("spheres", width=8, height=8, progress=True)  # once
        lamplight.render("spheres", width=8, height=8, progress=None)  # not asked for: silent
