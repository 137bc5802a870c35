"""More scenes of bench/mitsuba_xml_compare.py: scene-level parameters
(hide_emitters, moment) and the textures and wrappers that had no case
(mesh_attribute, bumpmap). write_assets writes the files they read."""
import os

from mitsuba_xml.cases import LIGHT, SKY, DIFFUSE_RED, Case, lit, scene, sphere

HIDE = ('<integrator type="path"><integer name="max_depth" value="6"/>'
        '<boolean name="hide_emitters" value="true"/></integrator>')
GLOW = """    <shape type="sphere"><point name="center" value="0.9, 0.25, 0.7"/><float name="radius" value="0.2"/>
        <emitter type="area"><rgb name="radiance" value="3, 2.5, 2"/></emitter>
    </shape>
"""

MOMENT = ('<integrator type="moment"><integrator type="path"><integer name="max_depth" value="6"/></integrator>'
          '</integrator>')

# merge: a mesh, a sphere and a rectangle joined; Mitsuba merges the meshes.
MERGED = """    <shape type="merge">
        <shape type="obj"><string name="filename" value="quad.obj"/>
            <transform name="to_world"><scale value="0.4"/><rotate x="1" angle="-60"/><translate x="-0.7" y="0.5"/></transform>
            <bsdf type="diffuse"><rgb name="reflectance" value="0.2, 0.7, 0.3"/></bsdf></shape>
        <shape type="sphere"><point name="center" value="0.5, 0.45, 0"/><float name="radius" value="0.45"/>
            <bsdf type="diffuse"><rgb name="reflectance" value="0.8, 0.2, 0.1"/></bsdf></shape>
        <shape type="rectangle"><transform name="to_world"><rotate x="1" angle="-90"/><scale value="3"/></transform>
            <bsdf type="diffuse"><rgb name="reflectance" value="0.6, 0.6, 0.55"/></bsdf></shape>
    </shape>
"""

# Every kind of shape in one scene, as Mitsuba's own test scenes mix them:
# meshes with Mitsuba's vertex normals (no face_normals), an open cylinder seen
# inside, a disk, a sphere, the floor; light bounces between them.
def _diffuse(rgb):
    return f'<bsdf type="diffuse"><rgb name="reflectance" value="{rgb}"/></bsdf>'


VARIOUS = f"""    <shape type="ply"><string name="filename" value="ball.ply"/>
        <transform name="to_world"><scale value="0.35"/><translate x="-0.9" y="0.35" z="0.3"/></transform>{_diffuse("0.7, 0.6, 0.2")}</shape>
    <shape type="serialized"><string name="filename" value="tetra.serialized"/>
        <transform name="to_world"><scale value="0.6"/><translate x="0.9" y="0.01" z="0.4"/></transform>{_diffuse("0.2, 0.5, 0.8")}</shape>
    <shape type="obj"><string name="filename" value="quad.obj"/>
        <transform name="to_world"><scale value="0.4"/><rotate x="1" angle="-70"/><translate x="0.1" y="0.7" z="-0.8"/></transform>
        {_diffuse("0.8, 0.8, 0.8")}</shape>
    <shape type="sphere"><point name="center" value="0.25, 0.3, 0.5"/><float name="radius" value="0.3"/>{_diffuse("0.8, 0.2, 0.1")}</shape>
    <shape type="disk"><transform name="to_world"><scale value="0.35"/><rotate y="1" angle="40"/><translate x="-0.4" y="0.45" z="-0.6"/></transform>
        {_diffuse("0.3, 0.8, 0.3")}</shape>
    <shape type="cylinder"><point name="p0" value="0.6, 0.25, -0.5"/><point name="p1" value="1.2, 0.5, -0.2"/>
        <float name="radius" value="0.25"/>{_diffuse("0.6, 0.3, 0.7")}</shape>
"""

CASES = [
    Case("various_shapes", "ply, serialized, obj (vertex normals), sphere, disk, cylinder, rectangle in one scene",
         scene(lit(VARIOUS), size=(64, 48))),
    Case("merge", "merge (obj, sphere, rectangle)", scene(LIGHT + MERGED)),
    # Mitsuba's default max_depth of the differentiable integrators is 6.
    Case("prb", "prb (default max_depth)", scene(lit(sphere(DIFFUSE_RED)), integrator='<integrator type="prb"/>'),
         "llvm_ad_rgb"),
    Case("prb_projective", "prb_projective, max_depth 3", scene(
        lit(sphere(DIFFUSE_RED)),
        integrator='<integrator type="prb_projective"><integer name="max_depth" value="3"/></integrator>'), "llvm_ad_rgb"),
    Case("moment", "moment (of path)", scene(lit(sphere(DIFFUSE_RED)), integrator=MOMENT)),
    Case("hide_emitters", "path (hide_emitters), area, constant", scene(lit(SKY + GLOW + sphere(DIFFUSE_RED)), integrator=HIDE)),
    Case("mesh_attribute", "mesh_attribute (vertex_color), ply", scene(lit("""
    <shape type="ply"><string name="filename" value="tetra_colors.ply"/><boolean name="face_normals" value="true"/>
        <transform name="to_world"><translate y="0.01"/></transform>
        <bsdf type="diffuse"><texture type="mesh_attribute" name="reflectance"><string name="name" value="vertex_color"/></texture></bsdf>
    </shape>
"""))),
    Case("bumpmap", "bumpmap (bitmap height)", scene(LIGHT + """
    <shape type="obj"><string name="filename" value="quad.obj"/>
        <transform name="to_world"><scale value="2"/></transform>
        <bsdf type="bumpmap"><texture type="bitmap"><string name="filename" value="height.png"/><boolean name="raw" value="true"/></texture>
            <float name="scale" value="0.3"/>
            <bsdf type="diffuse"><rgb name="reflectance" value="0.6, 0.5, 0.4"/></bsdf></bsdf>
    </shape>
""", to_world='<lookat origin="0, 3, 2" target="0, 0, 0" up="0, 1, 0"/>')),
]


def write_assets(d):
    """The files these cases read, into folder d."""
    import mitsuba as mi
    import numpy as np
    # Float colours: Mitsuba reads integer ones unscaled (0 to 255, with a warning).
    verts = [(-0.6, 0, -0.5), (0.6, 0, -0.5), (0, 0, 0.6), (0, 1.0, 0)]
    colors = [(0.9, 0.15, 0.1), (0.1, 0.8, 0.25), (0.15, 0.25, 0.85), (0.95, 0.9, 0.8)]
    faces = [(0, 1, 2), (0, 3, 1), (1, 3, 2), (2, 3, 0)]  # counter-clockwise seen from outside
    with open(os.path.join(d, "tetra_colors.ply"), "w") as f:
        f.write("ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
                "property float red\nproperty float green\nproperty float blue\n"
                "element face 4\nproperty list uchar int vertex_indices\nend_header\n")
        for v, c in zip(verts, colors):
            f.write("%g %g %g %g %g %g\n" % (v + c))
        for t in faces:
            f.write("3 %d %d %d\n" % t)
    # Smooth ridges along u: the bump's slope varies slowly over each pixel.
    h, w = 32, 32
    xx = np.mgrid[0:h, 0:w][1].astype(np.float32)
    height = (0.5 + 0.5 * np.sin(xx / w * 4 * np.pi))[:, :, None]
    mi.Bitmap((height * 255).round().astype(np.uint8), mi.Bitmap.PixelFormat.Y).write(os.path.join(d, "height.png"))
