"""The render settings are stated once (``crates/lamplight-py/src/settings.rs``):
every front end takes exactly the table's keywords, and the type stub lists
them as generated from it. A setting added to the table reaches ``render``,
``Scene.explain``, ``resolve_settings`` and the Dask wrappers with no other
edit, or one of these tests names what is missing.

``LAMPLIGHT_BLESS=1 pytest python/tests/test_keywords.py`` rewrites the stub's
generated blocks after a deliberate change to the table."""

import inspect
import os
import re
from pathlib import Path

import numpy as np
import pytest

import lamplight
from lamplight import _lamplight
from lamplight import dask as ldask
from lamplight._render import RENDER_KEYWORDS

STUB = Path(lamplight.__file__).parent / "_lamplight.pyi"
BLOCK = re.compile(r"^(?P<indent> *)# BEGIN settings(?P<explain> explain)? generated[^\n]*\n(?P<body>.*?)^(?P=indent)# END settings$", re.M | re.S)

# One value per setting that a small render accepts (with `WITH`, what it needs
# beside it). A setting added to the
# table without one here fails `test_every_setting_has_a_sample_value`.
SAMPLES = {
    "width": 8,
    "height": 6,
    "spp": 2,
    "integrator": "path",
    "threads": 1,
    "seed": 7,
    "max_depth": 3,
    "window": (0, 0, 4, 3),
    "time_limit": 60.0,
    "filter": "tent",
    "environment": None,  # a file: given by `environment_file` below
    "exr_layers": ["samples"],
    "denoise": False,  # True needs the library (test_denoise.py)
    "clamp": 10.0,
    "antialias": False,
    "noise_threshold": 0.5,
    "min_spp": 4,
    "memory_budget": "1G",
    "frame": 3,
    # The mesh file settings' defaults (cornell-box is no mesh file: other values
    # are refused there; test_mesh_options.py renders them on one).
    "smooth": False,
    "keep_auto_lights": "auto",
    "animation": None,  # a glTF file's: test_gltf_animation.py
}


WITH = {"noise_threshold": {"spp": 8}, "min_spp": {"spp": 8, "noise_threshold": 0.5}}


def generated(indent: str, explain: bool) -> str:
    return "".join(f"{indent}{name}: {annotation} = None,\n" for name, annotation, both in RENDER_KEYWORDS if both or not explain)


def test_the_stub_lists_the_table():
    text = STUB.read_text()
    blocks = list(BLOCK.finditer(text))
    assert len(blocks) == 3, "render_array, resolve_settings and Scene.explain each hold one generated block"
    updated = BLOCK.sub(lambda m: m.group(0)[: m.start("body") - m.start()] + generated(m.group("indent"), bool(m.group("explain"))) + m.group(0)[m.end("body") - m.start() :], text)
    if updated != text:
        if os.environ.get("LAMPLIGHT_BLESS"):
            STUB.write_text(updated)
            return
        pytest.fail(f"{STUB} lists other settings than crates/lamplight-py/src/settings.rs (rerun with LAMPLIGHT_BLESS=1 to rewrite it)")


def test_the_wrappers_take_the_table_in_order():
    names = [name for name, _, _ in RENDER_KEYWORDS]
    assert names[:7] == ["width", "height", "spp", "integrator", "threads", "seed", "max_depth"], "the old positional order"
    render = list(inspect.signature(lamplight.render).parameters)
    assert render == ["scene", *names, "progress", "base_dir"]
    split = [n for n in names if n not in ("window", "time_limit", "exr_layers")]
    assert list(inspect.signature(ldask.render).parameters) == ["scene", "client", *split, "tiles", "ship_meshes", "progress", "retries", "base_dir"]
    frames = list(inspect.signature(ldask.render_frames).parameters)
    # frames= (which frames) takes the place of the one-frame setting frame=.
    each = [n for n in split if n != "frame"]
    assert frames == ["scenes", "client", "cameras", *each, "frames", "out", "overwrite", "video", "tiles", "ship_meshes", "progress", "retries", "base_dir"]
    assert inspect.signature(ldask.render).parameters["threads"].default == 1


def test_every_setting_has_a_sample_value():
    assert sorted(SAMPLES) == sorted(name for name, _, _ in RENDER_KEYWORDS)


@pytest.fixture
def environment_file(tmp_path):
    path = tmp_path / "sky.exr"
    lamplight.save(path, np.full((4, 8, 3), 0.5, dtype=np.float32))
    return path


@pytest.mark.parametrize("name", [name for name, _, _ in RENDER_KEYWORDS])
def test_every_setting_reaches_render_and_explain(name, environment_file):
    value = environment_file if name == "environment" else SAMPLES[name]
    if value is None:
        pytest.skip(f"{name} is tested where its conditions are set up")
    base = {"width": 8, "height": 6, "spp": 2, "integrator": "path", "progress": False}
    args = dict(base, **WITH.get(name, {}), **{name: value})
    image = lamplight.render("cornell-box", **args)
    expected = (3, 4, 3) if name == "window" else (args["height"], args["width"], 3)
    assert np.asarray(image).shape == expected
    explainable = {n: e for n, _, e in RENDER_KEYWORDS}[name]
    scene = lamplight.Scene("cornell-box")
    settings = {k: v for k, v in args.items() if k != "progress"}
    if explainable:
        assert [s["index"] for s in scene.explain(1, 1, 0, **settings)["samples"]] == [0]
    else:
        with pytest.raises(TypeError, match=rf"^explain\(\) got an unexpected keyword argument '{name}'$"):
            scene.explain(1, 1, 0, **settings)
    assert _lamplight.resolve_settings(scene, **settings)[:2] == (args["width"], args["height"])


def test_a_misspelt_setting_names_the_nearest():
    with pytest.raises(TypeError, match=r"^render\(\) got an unexpected keyword argument 'max_dept' \(did you mean 'max_depth'\?\)$"):
        lamplight.render("spheres", width=4, height=4, max_dept=2)
    with pytest.raises(TypeError, match=r"^render_array\(\) got an unexpected keyword argument 'sp' \(did you mean 'spp'\?\)$"):
        _lamplight.render_array(lamplight.Scene("spheres"), sp=2)
    with pytest.raises(TypeError, match=r"^explain\(\) got an unexpected keyword argument 'intgrator' \(did you mean 'integrator'\?\)$"):
        lamplight.Scene("spheres").explain(0, 0, intgrator="path")
    with pytest.raises(TypeError, match=r"^render\(\) got an unexpected keyword argument 'window'$"):
        ldask.render("spheres", None, window=(0, 0, 1, 1))


def test_the_old_positional_order_still_works():
    a = lamplight.render("spheres", 8, 6, 1, "whitted", 1, 3, progress=False)
    b = lamplight.render("spheres", width=8, height=6, spp=1, integrator="whitted", threads=1, seed=3, progress=False)
    assert (np.asarray(a) == np.asarray(b)).all()
