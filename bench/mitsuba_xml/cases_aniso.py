"""Cases of bench/mitsuba_xml_compare.py for anisotropic microfacets (issue 26):
`roughconductor` and `roughdielectric` with `alpha_u` != `alpha_v`, and the
principled BSDFs' `anisotropic`. The roughness is measured along the shading
frame's first tangent, the surface's dp/du, so each case puts the lobe on a
shape whose dp/du differs: a sphere (azimuthal, about its local z, here turned
by to_world), a rectangle (its to_world x axis), a disk (radial), an OBJ
mesh (from its texture coordinates) and a cube (per face, as Mitsuba's cube
mesh). Rendered in `llvm_ad_rgb` (the JIT
variant; set DRJIT_LIBLLVM_PATH to LLVM 19 as the comparator does). Imported
by cases.py, which appends them to its CASES."""
from .cases import LIGHT, SKY, Case, lit, scene, sphere
from .cases_bsdfs2 import PANE

V = "llvm_ad_rgb"
DIFFUSE = '<bsdf type="diffuse"><rgb name="reflectance" value="0.7, 0.2, 0.15"/></bsdf>'


def rough_conductor(au, av, distribution="ggx", material="Cu"):
    return (f'<bsdf type="roughconductor"><string name="material" value="{material}"/>'
            f'<string name="distribution" value="{distribution}"/>'
            f'<float name="alpha_u" value="{au}"/><float name="alpha_v" value="{av}"/></bsdf>')


def turned_sphere(bsdf):
    """A unit sphere scaled to 0.6 whose pole (local z) is turned towards the
    upper right, so that its dp/du rings are seen obliquely."""
    return f"""    <shape type="sphere">
        <transform name="to_world"><scale value="0.6"/><rotate x="1" angle="-60"/><rotate z="1" angle="35"/><translate y="0.6"/></transform>
        {bsdf}
    </shape>
"""


def floor(shape, bsdf, transform):
    return f"""    <shape type="{shape}">
        <transform name="to_world">{transform}</transform>
        {bsdf}
    </shape>
"""


MESH_FLOOR = """    <shape type="obj"><string name="filename" value="quad.obj"/>
        <transform name="to_world"><rotate y="1" angle="25"/><scale value="2"/></transform>
        {bsdf}
    </shape>
"""

CASES = [
    Case("roughconductor_aniso_ggx", "roughconductor (ggx, alpha_u 0.05, alpha_v 0.4; sphere)", scene(lit(SKY + sphere(
        rough_conductor(0.05, 0.4)))), V),
    Case("roughconductor_aniso_beckmann_turned", "roughconductor (beckmann, alpha_u 0.4, alpha_v 0.08; turned sphere)",
         scene(lit(SKY + turned_sphere(rough_conductor(0.4, 0.08, "beckmann", "Al")))), V),
    Case("roughconductor_aniso_rectangle", "roughconductor (anisotropic; rectangle turned about y)", scene(
        SKY + LIGHT + floor("rectangle", rough_conductor(0.03, 0.35, "ggx", "Ag"),
                            '<rotate x="1" angle="-90"/><rotate y="1" angle="30"/><scale value="3"/>')
        + sphere(DIFFUSE, center="0.5, 0.4, 0", radius=0.4)), V),
    Case("roughconductor_aniso_disk", "roughconductor (anisotropic; disk: dp/du radial)", scene(
        SKY + LIGHT + floor("disk", rough_conductor(0.35, 0.03, "ggx", "Au"),
                            '<rotate x="1" angle="-90"/><scale value="2"/>')
        + sphere(DIFFUSE, center="0.5, 0.4, 0", radius=0.4)), V),
    Case("roughconductor_aniso_mesh", "roughconductor (anisotropic; OBJ quad, dp/du from its uv)", scene(
        SKY + LIGHT + MESH_FLOOR.format(bsdf=rough_conductor(0.04, 0.3, "beckmann", "Cu"))
        + sphere(DIFFUSE, center="-0.5, 0.4, 0", radius=0.4)), V),
    Case("roughconductor_aniso_cube", "roughconductor (anisotropic; cube, turned)", scene(lit(SKY + floor(
        "cube", rough_conductor(0.04, 0.4, "ggx", "Cu"),
        '<scale value="0.4"/><rotate y="1" angle="30"/><rotate x="1" angle="20"/><translate y="0.6"/>'))), V),
    Case("roughdielectric_aniso", "roughdielectric (ggx, alpha_u 0.02, alpha_v 0.4; turned sphere)", scene(lit(SKY + turned_sphere(
        '<bsdf type="roughdielectric"><float name="int_ior" value="1.5"/><string name="distribution" value="ggx"/>'
        '<float name="alpha_u" value="0.02"/><float name="alpha_v" value="0.4"/></bsdf>'))), V),
    Case("principled_aniso", "principled (anisotropic 0.8, metallic 0.7)", scene(lit(SKY + turned_sphere(
        '<bsdf type="principled"><rgb name="base_color" value="0.9, 0.6, 0.3"/><float name="metallic" value="0.7"/>'
        '<float name="roughness" value="0.4"/><float name="anisotropic" value="0.8"/></bsdf>'))), V),
    Case("principled_aniso_spec_trans", "principled (anisotropic 1, spec_trans 0.9; turned sphere)", scene(lit(SKY + turned_sphere(
        '<bsdf type="principled"><rgb name="base_color" value="0.95, 0.9, 0.8"/><float name="spec_trans" value="0.9"/>'
        '<float name="roughness" value="0.35"/><float name="anisotropic" value="1"/></bsdf>'))), V),
    Case("principledthin_aniso", "principledthin (anisotropic 1, spec_trans 0.9; a pane before a sphere)", scene(lit(SKY + sphere(DIFFUSE)
        + PANE.format(bsdf='<bsdf type="principledthin"><rgb name="base_color" value="0.3, 0.6, 0.8"/>'
                      '<float name="spec_trans" value="0.9"/><float name="roughness" value="0.35"/>'
                      '<float name="anisotropic" value="1"/></bsdf>'))), V),
]
