"""More scenes of bench/mitsuba_xml_compare.py (issue 15): a coarse sphere mesh
without normals, smoothed by Mitsuba's default and shaded flat with
face_normals; flip_normals; masks of fractional opacity. write_assets writes
the mesh."""
import math
import os

from mitsuba_xml.cases import DIFFUSE_RED, Case, lit, scene, sphere

BALL = """    <shape type="ply"><string name="filename" value="ball.ply"/>{extra}
        <transform name="to_world"><scale value="0.6"/><translate y="0.6"/></transform>
        <bsdf type="roughconductor"><string name="material" value="Cu"/><float name="alpha" value="0.15"/></bsdf>
    </shape>
"""

CASES = [
    Case("mesh_smooth_default", "ply without normals (Mitsuba's vertex normals)", scene(lit(BALL.format(extra="")))),
    Case("mesh_face_normals", "ply (face_normals)", scene(lit(BALL.format(extra='<boolean name="face_normals" value="true"/>')))),
]


def write_assets(d):
    """ball.ply: a UV sphere of 8 rings and 12 segments, positions only."""
    rings, segments = 8, 12
    verts = [(0.0, 1.0, 0.0)]
    for i in range(1, rings):
        theta = math.pi * i / rings
        for j in range(segments):
            phi = 2 * math.pi * j / segments
            verts.append((math.sin(theta) * math.cos(phi), math.cos(theta), math.sin(theta) * math.sin(phi)))
    verts.append((0.0, -1.0, 0.0))
    ring = lambda i, j: 1 + (i - 1) * segments + j % segments  # noqa: E731
    faces = [(0, ring(1, j + 1), ring(1, j)) for j in range(segments)]
    for i in range(1, rings - 1):
        for j in range(segments):
            a, b, c, e = ring(i, j), ring(i, j + 1), ring(i + 1, j + 1), ring(i + 1, j)
            faces += [(a, b, c), (a, c, e)]
    last = len(verts) - 1
    faces += [(last, ring(rings - 1, j), ring(rings - 1, j + 1)) for j in range(segments)]
    with open(os.path.join(d, "ball.ply"), "w") as f:
        f.write("ply\nformat ascii 1.0\nelement vertex %d\nproperty float x\nproperty float y\nproperty float z\n"
                "element face %d\nproperty list uchar int vertex_indices\nend_header\n" % (len(verts), len(faces)))
        for v in verts:
            f.write("%.9g %.9g %.9g\n" % v)
        for t in faces:
            f.write("3 %d %d %d\n" % t)

# flip_normals: a light whose normal points up, flipped so that it shines down,
# and a one-sided wall turned away from the camera, flipped so that it faces it.
FLIPPED = """    <shape type="rectangle">
        <transform name="to_world"><scale value="0.6"/><rotate x="1" angle="-90"/><translate y="2.5"/></transform>
        <boolean name="flip_normals" value="true"/>
        <emitter type="area"><rgb name="radiance" value="12, 11, 10"/></emitter>
    </shape>
    <shape type="rectangle">
        <transform name="to_world"><scale value="1.5"/><rotate y="1" angle="180"/><translate z="-1"/></transform>
        <boolean name="flip_normals" value="true"/>
        <bsdf type="diffuse"><rgb name="reflectance" value="0.3, 0.6, 0.4"/></bsdf>
    </shape>
    <shape type="ply"><string name="filename" value="ball.ply"/><boolean name="flip_normals" value="true"/>
        <transform name="to_world"><scale value="0.4"/><translate x="0.7" y="0.4"/></transform>
        <bsdf type="diffuse"><rgb name="reflectance" value="0.7, 0.2, 0.15"/></bsdf>
    </shape>
"""
FLOOR_ONLY = """    <shape type="rectangle">
        <transform name="to_world"><rotate x="1" angle="-90"/><scale value="3"/></transform>
        <bsdf type="diffuse"><rgb name="reflectance" value="0.6, 0.6, 0.55"/></bsdf>
    </shape>
"""
CASES.append(Case("flip_normals", "flip_normals (area emitter, one-sided rectangle, ply)", scene(FLOOR_ONLY + FLIPPED)))

# mask with a fractional opacity: Mitsuba keeps the surface with that probability.
MASKED = """    <shape type="sphere"><point name="center" value="-0.2, 0.5, 0.9"/><float name="radius" value="0.45"/>
        <bsdf type="mask"><float name="opacity" value="0.35"/>
            <bsdf type="diffuse"><rgb name="reflectance" value="0.2, 0.5, 0.8"/></bsdf></bsdf>
    </shape>
"""
CASES.append(Case("mask_fractional", "mask (opacity 0.35)", scene(lit(sphere(DIFFUSE_RED, center="0.3, 0.6, -0.5") + MASKED))))
