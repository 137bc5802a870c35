"""The scenes of bench/mitsuba_xml_compare.py: one small Mitsuba XML scene per
plugin (or per mapped parameter), and the files they read (written by
write_assets: an environment map, meshes, images)."""
import os
import struct
import zlib
from collections import namedtuple

import numpy as np

# `variant`: Mitsuba's variant that renders the case (the differentiable
# integrators run only in the JIT ones).
Case = namedtuple("Case", "name plugins xml variant", defaults=("scalar_rgb",))

PATH = '<integrator type="path"><integer name="max_depth" value="6"/></integrator>'


def scene(body, *, size=(48, 48), fov=40, fov_axis="x", integrator=PATH, sensor="perspective", sensor_props="",
          to_world='<lookat origin="0, 1.2, 4" target="0, 0.4, 0" up="0, 1, 0"/>', rfilter='<rfilter type="box"/>'):
    fovs = f'<float name="fov" value="{fov}"/><string name="fov_axis" value="{fov_axis}"/>' if sensor != "orthographic" else ""
    return f"""<scene version="3.0.0">
    <default name="spp" value="16"/>
    {integrator}
    <sensor type="{sensor}">
        {fovs}{sensor_props}
        <transform name="to_world">{to_world}</transform>
        <sampler type="independent"><integer name="sample_count" value="$spp"/></sampler>
        <film type="hdrfilm">
            <integer name="width" value="{size[0]}"/><integer name="height" value="{size[1]}"/>
            {rfilter}
        </film>
    </sensor>
{body}
</scene>
"""


FLOOR = """    <shape type="rectangle">
        <transform name="to_world"><rotate x="1" angle="-90"/><scale value="3"/></transform>
        <bsdf type="diffuse"><rgb name="reflectance" value="0.6, 0.6, 0.55"/></bsdf>
    </shape>
"""
LIGHT = """    <shape type="rectangle">
        <transform name="to_world"><scale value="0.6"/><rotate x="1" angle="90"/><translate y="2.5"/></transform>
        <emitter type="area"><rgb name="radiance" value="12, 11, 10"/></emitter>
    </shape>
"""
SKY = '    <emitter type="constant"><rgb name="radiance" value="0.25, 0.3, 0.4"/></emitter>\n'


def sphere(bsdf, center="0, 0.6, 0", radius=0.6):
    return f"""    <shape type="sphere">
        <point name="center" value="{center}"/><float name="radius" value="{radius}"/>
        {bsdf}
    </shape>
"""


DIFFUSE_RED = '<bsdf type="diffuse"><rgb name="reflectance" value="0.7, 0.2, 0.15"/></bsdf>'
QUAD_OBJ = """v -1 0 -1
v 1 0 -1
v 1 0 1
v -1 0 1
vt 0 1
vt 1 1
vt 1 0
vt 0 0
vn 0 1 0
f 4/4/1 3/3/1 2/2/1
f 4/4/1 2/2/1 1/1/1
"""


def lit(body):
    return FLOOR + LIGHT + body


CASES = [
    Case("diffuse_area", "diffuse, area, rectangle, sphere, path", scene(lit(sphere(DIFFUSE_RED)))),
    Case("spectrum_pairs", "spectrum (wavelength:value), area", scene(FLOOR + sphere(
        '<bsdf type="diffuse"><spectrum name="reflectance" value="400:0.1, 500:0.7, 600:0.3, 700:0.6"/></bsdf>') + """
    <shape type="rectangle">
        <transform name="to_world"><scale value="0.6"/><rotate x="1" angle="90"/><translate y="2.5"/></transform>
        <emitter type="area"><spectrum name="radiance" value="10"/></emitter>
    </shape>
""")),
    Case("point", "point", scene(FLOOR + sphere(DIFFUSE_RED) + """
    <emitter type="point"><point name="position" value="1, 2.5, 1"/><rgb name="intensity" value="20, 18, 16"/></emitter>
""")),
    Case("spot", "spot", scene(FLOOR + sphere(DIFFUSE_RED, center="0.8, 0.3, 0", radius=0.3) + """
    <emitter type="spot">
        <transform name="to_world"><lookat origin="0, 2.5, 0.5" target="0, 0, 0" up="0, 0, 1"/></transform>
        <rgb name="intensity" value="30, 30, 30"/><float name="cutoff_angle" value="35"/><float name="beam_width" value="15"/>
    </emitter>
""")),
    Case("directional", "directional", scene(FLOOR + sphere(DIFFUSE_RED) + """
    <emitter type="directional"><vector name="direction" value="-0.4, -1, -0.3"/><rgb name="irradiance" value="3, 3, 3"/></emitter>
""")),
    Case("constant", "constant", scene(FLOOR + SKY + sphere(DIFFUSE_RED))),
    Case("envmap", "envmap (scale)", scene(FLOOR + sphere('<bsdf type="diffuse"/>') + """
    <emitter type="envmap"><string name="filename" value="sky.exr"/><float name="scale" value="1.5"/></emitter>
""", fov=70)),
    Case("envmap_rotated", "envmap (to_world turn about y)", scene(FLOOR + sphere('<bsdf type="conductor"/>') + """
    <emitter type="envmap"><string name="filename" value="sky.exr"/>
        <transform name="to_world"><rotate y="1" angle="70"/></transform></emitter>
""", fov=70)),
    Case("conductor_named", "conductor (material Au)", scene(lit(SKY + sphere('<bsdf type="conductor"><string name="material" value="Au"/></bsdf>')))),
    Case("conductor_eta_k", "conductor (eta, k)", scene(lit(SKY + sphere(
        '<bsdf type="conductor"><rgb name="eta" value="0.2, 0.9, 1.1"/><rgb name="k" value="3.9, 2.4, 2.1"/></bsdf>')))),
    Case("roughconductor_ggx", "roughconductor (ggx)", scene(lit(SKY + sphere(
        '<bsdf type="roughconductor"><string name="material" value="Cu"/><string name="distribution" value="ggx"/>'
        '<float name="alpha" value="0.25"/></bsdf>')))),
    Case("roughconductor_beckmann", "roughconductor (beckmann)", scene(lit(SKY + sphere(
        '<bsdf type="roughconductor"><string name="material" value="Al"/><float name="alpha" value="0.25"/></bsdf>')))),
    Case("dielectric", "dielectric (named IORs)", scene(lit(SKY + sphere(
        '<bsdf type="dielectric"><string name="int_ior" value="bk7"/><string name="ext_ior" value="air"/></bsdf>')))),
    Case("roughdielectric_ggx", "roughdielectric (ggx)", scene(lit(SKY + sphere(
        '<bsdf type="roughdielectric"><float name="int_ior" value="1.5"/><string name="distribution" value="ggx"/>'
        '<float name="alpha" value="0.2"/></bsdf>')))),
    Case("twosided", "twosided", scene(lit(sphere('<bsdf type="twosided">' + DIFFUSE_RED + '</bsdf>')))),
    Case("null", "null", scene(lit(sphere(DIFFUSE_RED) + """
    <shape type="rectangle"><transform name="to_world"><translate z="1.5" y="0.5"/></transform><bsdf type="null"/></shape>
"""))),
    Case("mask_bitmap", "mask (bitmap opacity), bitmap", scene(lit(sphere(DIFFUSE_RED, center="0, 0.6, -0.8") + """
    <shape type="obj"><string name="filename" value="quad.obj"/>
        <transform name="to_world"><rotate x="1" angle="90"/><scale value="0.7"/><translate y="0.8" z="0.6"/></transform>
        <bsdf type="mask"><texture type="bitmap" name="opacity"><string name="filename" value="mask.png"/>
            <boolean name="raw" value="true"/><string name="filter_type" value="nearest"/></texture>
            <bsdf type="diffuse"><rgb name="reflectance" value="0.2, 0.5, 0.8"/></bsdf></bsdf>
    </shape>
"""))),
    Case("mask_bitmap_twosided", "mask (bitmap opacity) of twosided", scene(lit(sphere(DIFFUSE_RED, center="0, 0.6, -0.8") + """
    <shape type="obj"><string name="filename" value="quad.obj"/>
        <transform name="to_world"><rotate x="1" angle="90"/><scale value="0.7"/><translate y="0.8" z="0.6"/></transform>
        <bsdf type="mask"><texture type="bitmap" name="opacity"><string name="filename" value="mask.png"/>
            <boolean name="raw" value="true"/><string name="filter_type" value="nearest"/></texture>
            <bsdf type="twosided"><bsdf type="diffuse"><rgb name="reflectance" value="0.2, 0.5, 0.8"/></bsdf></bsdf></bsdf>
    </shape>
"""))),
    Case("bitmap_obj", "bitmap (filter_type, wrap_mode), obj", scene(LIGHT + """
    <shape type="obj"><string name="filename" value="quad.obj"/>
        <transform name="to_world"><scale value="2"/></transform>
        <bsdf type="diffuse"><texture type="bitmap" name="reflectance"><string name="filename" value="tex.png"/>
            <string name="filter_type" value="nearest"/><string name="wrap_mode" value="repeat"/>
            <transform name="to_uv"><scale x="2" y="2"/></transform></texture></bsdf>
    </shape>
""", to_world='<lookat origin="0, 3, 2" target="0, 0, 0" up="0, 1, 0"/>')),
    Case("checkerboard_obj", "checkerboard, obj", scene(LIGHT + """
    <shape type="obj"><string name="filename" value="quad.obj"/>
        <transform name="to_world"><scale value="2"/></transform>
        <bsdf type="diffuse"><texture type="checkerboard" name="reflectance">
            <rgb name="color0" value="0.8, 0.3, 0.1"/><rgb name="color1" value="0.1, 0.3, 0.8"/>
            <transform name="to_uv"><scale x="3" y="3"/></transform></texture></bsdf>
    </shape>
""", to_world='<lookat origin="0, 3, 2" target="0, 0, 0" up="0, 1, 0"/>')),
    Case("normalmap", "normalmap", scene(LIGHT + """
    <shape type="obj"><string name="filename" value="quad.obj"/>
        <transform name="to_world"><scale value="2"/></transform>
        <bsdf type="normalmap"><texture type="bitmap" name="normalmap"><string name="filename" value="normal.png"/>
            <boolean name="raw" value="true"/></texture>
            <bsdf type="diffuse"/></bsdf>
    </shape>
""", to_world='<lookat origin="0, 3, 2" target="0, 0, 0" up="0, 1, 0"/>')),
    Case("ply", "ply", scene(lit("""
    <shape type="ply"><string name="filename" value="tetra.ply"/><boolean name="face_normals" value="true"/>
        <transform name="to_world"><translate y="0.01"/></transform>""" + DIFFUSE_RED + """</shape>
"""))),
    Case("serialized", "serialized", scene(lit("""
    <shape type="serialized"><string name="filename" value="tetra.serialized"/><boolean name="face_normals" value="true"/>
        <transform name="to_world"><translate y="0.01"/></transform>""" + DIFFUSE_RED + """</shape>
"""))),
    Case("cube", "cube", scene(lit("""
    <shape type="cube"><transform name="to_world"><scale value="0.5"/><rotate y="1" angle="30"/><translate y="0.5"/></transform>
    """ + DIFFUSE_RED + "</shape>\n"))),
    Case("disk", "disk", scene(lit("""
    <shape type="disk"><transform name="to_world"><scale value="0.8"/><rotate x="1" angle="-60"/><translate y="0.7"/></transform>
    """ + DIFFUSE_RED + "</shape>\n"))),
    Case("disk_twosided", "disk in twosided", scene(lit("""
    <shape type="disk"><transform name="to_world"><scale value="0.8"/><rotate x="1" angle="-60"/><translate y="0.7"/></transform>
    <bsdf type="twosided">""" + DIFFUSE_RED + "</bsdf></shape>\n"))),
    Case("cylinder", "cylinder", scene(lit("""
    <shape type="cylinder"><point name="p0" value="-0.8, 0.4, 0"/><point name="p1" value="0.8, 0.4, 0"/>
        <float name="radius" value="0.4"/>""" + DIFFUSE_RED + "</shape>\n"))),
    Case("shapegroup_instance", "shapegroup, instance", scene(lit("""
    <shape type="shapegroup" id="pair">
        <shape type="sphere"><float name="radius" value="0.3"/>""" + DIFFUSE_RED + """</shape>
        <shape type="sphere"><point name="center" value="0.7, 0, 0"/><float name="radius" value="0.2"/><bsdf type="diffuse"/></shape>
    </shape>
    <shape type="instance"><ref id="pair"/><transform name="to_world"><translate x="-0.8" y="0.3"/></transform></shape>
    <shape type="instance"><ref id="pair"/><transform name="to_world"><rotate y="1" angle="90"/><translate x="0.6" y="0.3"/></transform></shape>
"""))),
    Case("fov_axis_y", "perspective (fov_axis y)", scene(lit(sphere(DIFFUSE_RED)), size=(64, 40), fov=35, fov_axis="y")),
    Case("fov_axis_diagonal", "perspective (fov_axis diagonal)", scene(lit(sphere(DIFFUSE_RED)), size=(64, 40), fov=50, fov_axis="diagonal")),
    Case("fov_axis_smaller", "perspective (fov_axis smaller)", scene(lit(sphere(DIFFUSE_RED)), size=(40, 64), fov=40, fov_axis="smaller")),
    Case("mirrored_camera", "perspective (mirroring to_world)", scene(lit(sphere(DIFFUSE_RED, center="0.5, 0.6, 0")),
         to_world='<scale x="-1"/><lookat origin="0, 1.2, 4" target="0, 0.4, 0" up="0, 1, 0"/>')),
    Case("orthographic", "orthographic", scene(lit(sphere(DIFFUSE_RED)), sensor="orthographic",
         to_world='<scale x="1.5" y="1.5"/><lookat origin="0, 1.2, 4" target="0, 0.4, 0" up="0, 1, 0"/>')),
    Case("thinlens", "thinlens", scene(lit(sphere(DIFFUSE_RED) + sphere(DIFFUSE_RED, center="-1, 0.3, -1.5", radius=0.3)),
         sensor="thinlens", sensor_props='<float name="aperture_radius" value="0.1"/><float name="focus_distance" value="4"/>')),
    Case("gaussian_filter", "rfilter gaussian", scene(lit(sphere(DIFFUSE_RED)), rfilter='<rfilter type="gaussian"/>')),
    Case("tent_filter", "rfilter tent", scene(lit(sphere(DIFFUSE_RED)), rfilter='<rfilter type="tent"/>')),
    Case("direct", "direct", scene(lit(sphere(DIFFUSE_RED)), integrator='<integrator type="direct"/>')),
    Case("max_depth_2", "path (max_depth 2)", scene(lit(sphere(DIFFUSE_RED)), integrator='<integrator type="path"><integer name="max_depth" value="2"/></integrator>')),
    Case("ptracer", "ptracer", scene(lit(sphere(DIFFUSE_RED)), integrator='<integrator type="ptracer"><integer name="max_depth" value="6"/></integrator>')),
    Case("volpath", "volpath (no media)", scene(lit(sphere(DIFFUSE_RED)), integrator='<integrator type="volpath"><integer name="max_depth" value="6"/></integrator>')),
    Case("principled", "principled", scene(lit(SKY + sphere(
        '<bsdf type="principled"><rgb name="base_color" value="0.7, 0.3, 0.2"/><float name="metallic" value="0.3"/>'
        '<float name="roughness" value="0.4"/></bsdf>')))),
    Case("plastic", "plastic", scene(lit(sphere('<bsdf type="plastic"><rgb name="diffuse_reflectance" value="0.7, 0.2, 0.15"/></bsdf>')))),
    Case("include_default_ref", "include, default, ref", scene(lit('    <include filename="included.xml"/>\n' + sphere('<ref id="inc_red"/>')))),
]


def write_assets(d):
    """The files the cases read, into folder d."""
    import mitsuba as mi
    # Smooth, so that Mitsuba's bilinear lookup and lamplight's nearest-pixel one
    # agree; the bright red blob shows the orientation.
    h, w = 128, 256
    yy, xx = np.mgrid[0:h, 0:w].astype(np.float32)
    blob = np.exp(-((xx - 50) ** 2 + (yy - 30) ** 2) / (2 * 12.0 ** 2))
    sky = np.stack([0.2 + 0.8 * xx / w + 6 * blob, 0.3 + 0.5 * (1 - yy / h) + 1.5 * blob, 0.4 + 0 * xx + blob], axis=2)
    sky = sky.astype(np.float32)
    mi.Bitmap(sky).write(os.path.join(d, "sky.exr"))
    with open(os.path.join(d, "quad.obj"), "w") as f:
        f.write(QUAD_OBJ)
    tex = np.zeros((8, 8, 3), dtype=np.uint8)
    for y in range(8):
        for x in range(8):
            tex[y, x] = [40 + 25 * x, 40 + 25 * y, 200 if (x + y) % 2 else 60]
    mi.Bitmap(tex, mi.Bitmap.PixelFormat.RGB).write(os.path.join(d, "tex.png"))
    mask = np.zeros((4, 4, 1), dtype=np.uint8)
    mask[::2, ::2] = 255
    mask[1::2, 1::2] = 255
    mi.Bitmap(mask, mi.Bitmap.PixelFormat.Y).write(os.path.join(d, "mask.png"))
    nrm = np.zeros((16, 16, 3), dtype=np.uint8)
    for y in range(16):
        for x in range(16):
            n = np.array([0.5 * np.sin(x / 16 * 2 * np.pi), 0.0, 1.0])
            n /= np.linalg.norm(n)
            nrm[y, x] = ((n * 0.5 + 0.5) * 255).round().astype(np.uint8)
    mi.Bitmap(nrm, mi.Bitmap.PixelFormat.RGB).write(os.path.join(d, "normal.png"))
    verts = [(-0.6, 0, -0.5), (0.6, 0, -0.5), (0, 0, 0.6), (0, 1.0, 0)]
    faces = [(0, 1, 2), (0, 3, 1), (1, 3, 2), (2, 3, 0)]  # counter-clockwise seen from outside
    with open(os.path.join(d, "tetra.ply"), "w") as f:
        f.write("ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
                "element face 4\nproperty list uchar int vertex_indices\nend_header\n")
        for v in verts:
            f.write("%g %g %g\n" % v)
        for t in faces:
            f.write("3 %d %d %d\n" % t)
    body = struct.pack("<I", 0) + b"tetra\0" + struct.pack("<QQ", len(verts), len(faces))
    body += b"".join(struct.pack("<fff", *v) for v in verts) + b"".join(struct.pack("<III", *t) for t in faces)
    with open(os.path.join(d, "tetra.serialized"), "wb") as f:
        f.write(struct.pack("<HH", 0x041C, 4) + zlib.compress(body) + struct.pack("<QI", 0, 1))
    _scene2.write_assets(d)
    _lights2.write_assets(d)
    _surfaces.write_assets(d)
    _sdf.write_assets(d)
    _textures3.write_assets(d)
    _rough.write_assets(d)
    with open(os.path.join(d, "included.xml"), "w") as f:
        f.write('<scene version="3.0.0">\n    <default name="inc_r" value="0.7"/>\n'
                '    <bsdf type="diffuse" id="inc_red"><rgb name="reflectance" value="$inc_r, 0.2, 0.15"/></bsdf>\n</scene>\n')

from .cases_bsdfs2 import CASES as _BSDFS2_CASES  # noqa: E402 (it uses the helpers above)

CASES += _BSDFS2_CASES

from .cases_principled import CASES as _PRINCIPLED_CASES  # noqa: E402 (it uses the helpers above)

CASES += _PRINCIPLED_CASES

from .cases_blend import CASES as _BLEND_CASES  # noqa: E402 (it uses the helpers above)

CASES += _BLEND_CASES

from mitsuba_xml import cases_scene2 as _scene2  # noqa: E402  (scene-level cases, written alongside these)
CASES += _scene2.CASES

from mitsuba_xml import cases_lights2 as _lights2  # noqa: E402  (textured spot and projector)
CASES += _lights2.CASES

from mitsuba_xml import cases_surfaces as _surfaces  # noqa: E402  (mesh normals, flip_normals, blended masks)
CASES += _surfaces.CASES

from mitsuba_xml import cases_sensors3 as _sensors3  # noqa: E402  (film and sensor cases)
CASES += _sensors3.CASES

from mitsuba_xml import cases_sdf as _sdf  # noqa: E402  (the signed-distance grid shape)
CASES += _sdf.CASES
from mitsuba_xml import cases_textures3 as _textures3  # noqa: E402  (checkerboard phase, bitmap texels, mesh attributes)
CASES += _textures3.CASES
from mitsuba_xml import cases_aniso as _aniso  # noqa: E402  (anisotropic microfacets, issue 26)
CASES += _aniso.CASES
from mitsuba_xml import cases_rough as _rough  # noqa: E402  (textured roughness, normal-mapped conductors, textured thin eta)
CASES += _rough.CASES
