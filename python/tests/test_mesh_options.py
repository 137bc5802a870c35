"""How a mesh file rendered directly is built, from Python as from the command
line (issue 27): ``smooth=`` is ``--smooth`` and ``keep_auto_lights=`` is
``--keep-auto-lights``, both rows of the one settings table
(``crates/lamplight-py/src/settings.rs``), taken by ``render`` and ``load``."""

import math
import subprocess

import numpy as np
import pytest

import lamplight
from lamplight._render import BUILD_KEYWORDS, RENDER_KEYWORDS


def write_ball(path):
    """An octahedron subdivided twice and pushed onto the unit sphere, with no
    normals: flat, its 128 faces show; smooth, it shades as a ball."""
    vertices = [(1, 0, 0), (-1, 0, 0), (0, 1, 0), (0, -1, 0), (0, 0, 1), (0, 0, -1)]
    faces = [(0, 2, 4), (2, 1, 4), (1, 3, 4), (3, 0, 4), (2, 0, 5), (1, 2, 5), (3, 1, 5), (0, 3, 5)]
    for _ in range(2):
        middle = {}

        def mid(a, b):
            key = (min(a, b), max(a, b))
            if key not in middle:
                p = [(x + y) / 2 for x, y in zip(vertices[a], vertices[b])]
                n = math.sqrt(sum(c * c for c in p))
                vertices.append(tuple(c / n for c in p))
                middle[key] = len(vertices) - 1
            return middle[key]

        faces = [
            f
            for a, b, c in faces
            for f in ((a, mid(a, b), mid(c, a)), (b, mid(b, c), mid(a, b)), (c, mid(c, a), mid(b, c)), (mid(a, b), mid(b, c), mid(c, a)))
        ]
    lines = [f"v {x:.9f} {y:.9f} {z:.9f}" for x, y, z in vertices] + [f"f {a + 1} {b + 1} {c + 1}" for a, b, c in faces]
    path.write_text("\n".join(lines) + "\n")
    return path


def test_smooth_and_keep_auto_lights_are_rows_of_the_settings_table():
    names = [name for name, _, _ in RENDER_KEYWORDS]
    assert "smooth" in names and "keep_auto_lights" in names
    assert BUILD_KEYWORDS == ("smooth", "keep_auto_lights", "animation")
    import inspect

    assert list(inspect.signature(lamplight.load).parameters) == ["path", "smooth", "keep_auto_lights", "animation"]


def test_smooth_renders_what_the_command_line_s_smooth_renders(cli, tmp_path):
    ball = write_ball(tmp_path / "ball.obj")
    size = dict(width=96, height=72, antialias=False)
    out = tmp_path / "smooth.exr"
    subprocess.run([cli, "render", str(ball), "--smooth", "--width", "96", "--height", "72", "--antialias", "off", "-o", str(out), "-q"], check=True)
    smooth = lamplight.render(str(ball), smooth=True, **size)
    assert np.asarray(smooth).tobytes() == lamplight.read_exr(out).tobytes()
    flat = lamplight.render(str(ball), **size)
    assert np.asarray(flat).tobytes() == lamplight.render(str(ball), smooth=False, **size).tobytes()
    # Flat shading shows the faces: under directional lights each face is one
    # colour, so many neighbouring pixels on the ball are equal; smooth, few are.
    def equal_neighbours(image):
        a = np.asarray(image)
        ball = (np.abs(a - 0.2).max(axis=2) > 1e-6)[:, 1:] & (np.abs(a - 0.2).max(axis=2) > 1e-6)[:, :-1]
        same = (a[:, 1:] == a[:, :-1]).all(axis=2)
        return float((same & ball).sum() / ball.sum())

    assert equal_neighbours(flat) > 0.3 and equal_neighbours(smooth) < 0.05, (equal_neighbours(flat), equal_neighbours(smooth))
    # `load` takes it as the scene's own; a render's keyword overrides it.
    loaded = lamplight.load(ball, smooth=True)
    assert np.asarray(lamplight.render(loaded, **size)).tobytes() == np.asarray(smooth).tobytes()
    assert np.asarray(lamplight.render(loaded, smooth=False, **size)).tobytes() == np.asarray(flat).tobytes()
    # It survives pickling (Dask ships scenes so).
    import pickle

    assert np.asarray(lamplight.render(pickle.loads(pickle.dumps(loaded)), **size)).tobytes() == np.asarray(smooth).tobytes()


def test_mesh_options_are_refused_for_a_scene_that_is_not_a_mesh_file_and_misspelt_or_mistyped():
    with pytest.raises(ValueError, match=r"^smooth applies to a mesh file rendered directly \(\.obj, \.ply, \.gltf, \.glb\); 'spheres' is not one"):
        lamplight.render("spheres", width=8, height=8, smooth=True)
    with pytest.raises(ValueError, match=r"^keep_auto_lights applies to a mesh file rendered directly .*'spheres' is not one: a scene file is lit by the lights it states$"):
        lamplight.render("spheres", width=8, height=8, keep_auto_lights=True)
    with pytest.raises(TypeError, match=r"^smooth must be True or False, got int$"):
        lamplight.render("spheres", width=8, height=8, smooth=1)
    with pytest.raises(ValueError, match=r'^keep_auto_lights must be True, False or "auto", got "sometimes"$'):
        lamplight.render("spheres", width=8, height=8, keep_auto_lights="sometimes")
    with pytest.raises(TypeError, match=r"^load\(\) got an unexpected keyword argument 'smoth' \(did you mean 'smooth'\?\)$"):
        lamplight.load("x.obj", smoth=True)


def write_lantern(folder):
    """A closed box whose only light is an emitting box inside it (a
    jack-o'-lantern without its face), as crates/lamplight-cli/tests/lighting.rs builds it."""
    corners = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1)]
    faces = [[1, 4, 3, 2], [5, 6, 7, 8], [1, 5, 8, 4], [2, 3, 7, 6], [1, 2, 6, 5], [4, 8, 7, 3]]
    text = "mtllib boxes.mtl\n"
    for first, (half, material) in enumerate([(1.0, "skin"), (0.2, "candle")]):
        text += f"usemtl {material}\n" + "".join(f"v {' '.join(str(half if b else -half) for b in c)}\n" for c in corners)
        text += "".join("f " + " ".join(str(i + 8 * first) for i in f) + "\n" for f in faces)
    (folder / "boxes.obj").write_text(text)
    (folder / "boxes.mtl").write_text("newmtl skin\nKd 0.9 0.45 0.1\nnewmtl candle\nKd 0 0 0\nKe 4 3 1\n")
    return folder / "boxes.obj"


def test_keep_auto_lights_renders_what_the_command_line_s_flag_renders(cli, tmp_path):
    lantern = write_lantern(tmp_path)
    size = dict(width=64, height=48)
    for value, flag in [(False, "off"), (True, "on")]:
        out = tmp_path / f"{flag}.exr"
        args = [cli, "render", str(lantern), "--width", "64", "--height", "48", "--keep-auto-lights", flag, "-o", str(out), "-q"]
        subprocess.run(args, check=True, capture_output=True)
        assert np.asarray(lamplight.render(str(lantern), keep_auto_lights=value, **size)).tobytes() == lamplight.read_exr(out).tobytes()
    # The default keeps them here (the candle reaches nothing the camera sees), and says so.
    dark = np.asarray(lamplight.render(str(lantern), keep_auto_lights=False, **size))
    note = r"boxes\.obj: the file's own lights reach 0 % of what the camera sees \(less than 25 %\), so the automatic lights"
    with pytest.warns(UserWarning, match=note):
        kept = np.asarray(lamplight.render(str(lantern), **size))
    assert dark.max() < 0.02 and kept.mean() > 0.2, (dark.max(), kept.mean())
    with pytest.warns(UserWarning, match=note):
        warnings = lamplight.load(lantern).warnings
    assert len(warnings) == 1, warnings
    assert np.asarray(lamplight.render(lamplight.load(lantern, keep_auto_lights="off"), **size)).tobytes() == dark.tobytes()
