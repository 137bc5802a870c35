"""Texture scenes of bench/mitsuba_xml_compare.py (issue 26): the checkerboard's
phase on Mitsuba's rectangle and disk (their `uv`), bitmaps magnified until
their texel borders show (each filter_type and wrap_mode), PLY attributes read
by `mesh_attribute` (per vertex and per face, as Mitsuba's `write_ply` names
them), `rawconstant`, and a textured area emitter. write_assets writes the
image and the meshes."""
import os
import struct

import numpy as np

from mitsuba_xml.cases import Case, scene

# Lit evenly from every side, so that a texture shows as it is.
SKY = '    <emitter type="constant"><rgb name="radiance" value="1, 1, 1"/></emitter>\n'
CHECKER = """<bsdf type="diffuse"><texture type="checkerboard" name="reflectance">
            <rgb name="color0" value="0.8, 0.3, 0.1"/><rgb name="color1" value="0.1, 0.3, 0.8"/>{to_uv}</texture></bsdf>"""
TOP = '<lookat origin="0, 0, 4" target="0, 0, 0" up="0, 1, 0"/>'
ORTHO_TOP = '<scale x="1.2" y="1.2"/>' + TOP
# Seen at a slant and turned, so that a flip in u or v or a turned frame shows.
SLANT = '<lookat origin="0.8, -2.5, 3" target="0, 0, 0" up="0, 0, 1"/>'


def rect(bsdf, to_world='<rotate z="1" angle="20"/>'):
    return f"""    <shape type="rectangle"><transform name="to_world">{to_world}</transform>
        {bsdf}
    </shape>
"""


def disk(bsdf, to_world='<rotate z="1" angle="30"/>'):
    return f"""    <shape type="disk"><transform name="to_world">{to_world}</transform>
        {bsdf}
    </shape>
"""


def bitmap(filter_type, wrap, to_uv='<scale x="2.5" y="1.5"/><translate x="-0.3" y="-0.2"/>'):
    return f"""<bsdf type="diffuse"><texture type="bitmap" name="reflectance"><string name="filename" value="texels.png"/>
            <string name="filter_type" value="{filter_type}"/><string name="wrap_mode" value="{wrap}"/>
            <transform name="to_uv">{to_uv}</transform></texture></bsdf>"""


def ply(filename, texture):
    return f"""    <shape type="ply"><string name="filename" value="{filename}"/>
        <bsdf type="diffuse">{texture}</bsdf>
    </shape>
"""


def attribute(name):
    return f'<texture type="mesh_attribute" name="reflectance"><string name="name" value="{name}"/></texture>'


ORTHO = dict(sensor="orthographic", to_world=ORTHO_TOP, size=(64, 64))
CASES = [
    Case("checker_rectangle_ortho", "checkerboard on rectangle (uv), orthographic",
         scene(SKY + rect(CHECKER.format(to_uv="")), **ORTHO)),
    Case("checker_rectangle_slant", "checkerboard (to_uv) on rectangle, perspective",
         scene(SKY + rect(CHECKER.format(to_uv='<transform name="to_uv"><scale x="3" y="2"/><translate x="0.25"/></transform>')),
               to_world=SLANT, size=(64, 64))),
    Case("checker_disk_ortho", "checkerboard on disk (uv), orthographic",
         scene(SKY + disk(CHECKER.format(to_uv='<transform name="to_uv"><scale x="3" y="5"/></transform>')), **ORTHO)),
    Case("checker_disk_slant", "checkerboard on a scaled disk, perspective",
         scene(SKY + disk(CHECKER.format(to_uv='<transform name="to_uv"><scale x="2" y="3"/></transform>'),
                          to_world='<scale value="1.3"/><rotate z="1" angle="-50"/>'), to_world=SLANT, size=(64, 64))),
    Case("bitmap_bilinear_repeat", "bitmap (bilinear, repeat) magnified",
         scene(SKY + rect(bitmap("bilinear", "repeat"), to_world=""), **ORTHO)),
    Case("bitmap_nearest_repeat", "bitmap (nearest, repeat) magnified",
         scene(SKY + rect(bitmap("nearest", "repeat"), to_world=""), **ORTHO)),
    Case("bitmap_bilinear_mirror", "bitmap (bilinear, mirror) magnified",
         scene(SKY + rect(bitmap("bilinear", "mirror"), to_world=""), **ORTHO)),
    Case("bitmap_nearest_clamp", "bitmap (nearest, clamp) magnified",
         scene(SKY + rect(bitmap("nearest", "clamp"), to_world=""), **ORTHO)),
    Case("bitmap_bilinear_clamp_slant", "bitmap (bilinear, clamp) at a slant",
         scene(SKY + rect(bitmap("bilinear", "clamp")), to_world=SLANT, size=(64, 64))),
    # Minified, with Mitsuba's default filter_type (bilinear): about 5 x 4 texels
    # a pixel near and many more far off, so that a MIP level or a ray-cone
    # footprint (which Mitsuba does not use) would show as a blur.
    Case("bitmap_default_minified", "bitmap (default filter_type) minified at a slant",
         scene(SKY + rect('<bsdf type="diffuse"><texture type="bitmap" name="reflectance">'
                          '<string name="filename" value="texels.png"/>'
                          '<transform name="to_uv"><scale x="27" y="23"/></transform></texture></bsdf>'),
               to_world=SLANT, size=(64, 64))),
    Case("mesh_attribute_vertex", "mesh_attribute vertex_color (PLY color_0..2)",
         scene(SKY + ply("attributes.ply", attribute("vertex_color")), **ORTHO)),
    Case("mesh_attribute_face", "mesh_attribute face_color (PLY face color_0..2)",
         scene(SKY + ply("attributes.ply", attribute("face_color")), **ORTHO)),
    Case("mesh_attribute_face_weight", "mesh_attribute face_weight (one channel)",
         scene(SKY + ply("attributes.ply", attribute("face_weight")), **ORTHO)),
    Case("rawconstant", "rawconstant",
         scene(SKY + rect('<bsdf type="diffuse"><texture type="rawconstant" name="reflectance">'
                          '<vector name="value" value="0.2, 0.5, 0.7"/></texture></bsdf>'), **ORTHO)),
    Case("area_textured", "area (radiance a checkerboard) on a rectangle",
         scene("""    <shape type="rectangle">
        <transform name="to_world"><rotate z="1" angle="20"/><scale value="0.7"/></transform>
        <emitter type="area"><texture type="checkerboard" name="radiance">
            <rgb name="color0" value="1, 0.6, 0.3"/><rgb name="color1" value="0.2, 0.5, 1"/>
            <transform name="to_uv"><scale x="2" y="3"/></transform></texture></emitter>
    </shape>
    <shape type="rectangle">
        <transform name="to_world"><scale value="3"/><translate z="-0.5"/></transform>
        <bsdf type="diffuse"><rgb name="reflectance" value="0.8, 0.8, 0.8"/></bsdf>
    </shape>
""", to_world=SLANT, size=(64, 64))),
    Case("area_bitmap", "area (radiance a bitmap) on a disk",
         scene("""    <shape type="disk">
        <transform name="to_world"><rotate x="1" angle="30"/><scale value="0.7"/></transform>
        <emitter type="area"><texture type="bitmap" name="radiance"><string name="filename" value="texels.png"/>
            <string name="filter_type" value="nearest"/></texture></emitter>
    </shape>
    <shape type="rectangle">
        <transform name="to_world"><scale value="3"/><translate z="-0.5"/></transform>
        <bsdf type="diffuse"><rgb name="reflectance" value="0.8, 0.8, 0.8"/></bsdf>
    </shape>
""", to_world=SLANT, size=(64, 64))),
]


def write_assets(d):
    """texels.png: 4 x 3 texels of sharp contrast; attributes.ply: a grid of
    quads with per-vertex and per-face colours, as Mitsuba's write_ply names
    them (`color_0..2`, `weight_0`), binary."""
    import mitsuba as mi
    tex = np.zeros((3, 4, 3), dtype=np.uint8)
    for y in range(3):
        for x in range(4):
            tex[y, x] = [230 if (x + y) % 2 else 20, 30 + 60 * x, 40 + 90 * y]
    mi.Bitmap(tex, mi.Bitmap.PixelFormat.RGB).write(os.path.join(d, "texels.png"))
    n = 4  # quads per side over [-1, 1]^2
    rng = np.random.default_rng(7)
    verts = [(-1 + 2 * i / n, -1 + 2 * j / n, 0.0) for j in range(n + 1) for i in range(n + 1)]
    vcol = rng.uniform(0.05, 0.95, size=(len(verts), 3))
    faces = []
    for j in range(n):
        for i in range(n):
            a, b, c, e = j * (n + 1) + i, j * (n + 1) + i + 1, (j + 1) * (n + 1) + i + 1, (j + 1) * (n + 1) + i
            faces += [(a, b, c), (a, c, e)]
    fcol = rng.uniform(0.05, 0.95, size=(len(faces), 3))
    fw = rng.uniform(0.05, 0.95, size=len(faces))
    head = ("ply\nformat binary_little_endian 1.0\nelement vertex %d\nproperty float x\nproperty float y\nproperty float z\n"
            "property float color_0\nproperty float color_1\nproperty float color_2\n"
            "element face %d\nproperty list uchar int vertex_indices\n"
            "property float color_0\nproperty float color_1\nproperty float color_2\nproperty float weight_0\nend_header\n"
            % (len(verts), len(faces)))
    body = b"".join(struct.pack("<6f", *v, *c) for v, c in zip(verts, vcol))
    body += b"".join(struct.pack("<B3i4f", 3, *t, *c, w) for t, c, w in zip(faces, fcol, fw))
    with open(os.path.join(d, "attributes.ply"), "wb") as f:
        f.write(head.encode() + body)
