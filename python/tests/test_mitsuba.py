"""Mitsuba 3 XML scenes from Python: the same reader as `lamplight render
scene.xml`. The comparison with Mitsuba itself runs only where Mitsuba is
installed (it is slow and not in CI: bench/mitsuba_xml_compare.py does it for
every plugin)."""
import numpy as np
import pytest

import lamplight

SCENE = """<scene version="3.0.0">
    <integrator type="path"><integer name="max_depth" value="4"/></integrator>
    <sensor type="perspective">
        <float name="fov" value="45"/>
        <transform name="to_world"><lookat origin="0, 1, 5" target="0, 0.5, 0" up="0, 1, 0"/></transform>
        <sampler type="independent"><integer name="sample_count" value="16"/></sampler>
        <film type="hdrfilm"><integer name="width" value="24"/><integer name="height" value="16"/><rfilter type="box"/></film>
    </sensor>
    <emitter type="constant"><rgb name="radiance" value="0.5"/></emitter>
    <shape type="sphere"><point name="center" value="0, 0.5, 0"/><float name="radius" value="0.5"/>
        <bsdf type="diffuse"><rgb name="reflectance" value="0.8, 0.2, 0.1"/></bsdf></shape>
</scene>
"""


def test_xml_scene_renders_with_its_own_settings(tmp_path):
    path = tmp_path / "s.xml"
    path.write_text(SCENE)
    image = lamplight.render(str(path))
    assert image.shape == (16, 24, 3), "the film's size"
    # The sky is seen at the corners: exactly the constant emitter's radiance.
    assert np.allclose(image[0, 0], 0.5)
    assert image[8, 12, 0] > image[8, 12, 2], "the red sphere in the middle"


def test_xml_errors_name_line_and_column(tmp_path):
    path = tmp_path / "s.xml"
    path.write_text(SCENE.replace('type="diffuse"', 'type="velvet"'))
    with pytest.raises(lamplight.SceneError) as e:
        lamplight.Scene(str(path))
    assert str(e.value) == f'{path}:11:21: bsdf "velvet": unknown BSDF'


def test_xml_matches_mitsuba_where_installed(tmp_path):
    mi = pytest.importorskip("mitsuba", reason="Mitsuba 3 is not installed: the comparison with it is skipped")
    mi.set_variant("scalar_rgb")
    path = tmp_path / "s.xml"
    path.write_text(SCENE)
    ours = lamplight.render(str(path), spp=256)
    theirs = np.array(mi.render(mi.load_file(str(path)), spp=256), dtype=np.float64)[:, :, :3]
    assert abs(ours.mean() / theirs.mean() - 1) < 0.02
