"""Cases of bench/mitsuba_xml_compare.py for blendbsdf (lamplight's `blend`):
a constant weight of a diffuse and a rough conductor on a sphere, a
checkerboard weight (0.15 and 0.85) of the same two on an OBJ quad (a mesh,
whose texture coordinates agree with Mitsuba's; the built-in sphere's do not),
and a constant weight of a diffuse and a perfect mirror. Imported by cases.py,
which appends them to its CASES."""
from .cases import LIGHT, SKY, Case, lit, scene, sphere

DIFFUSE = '<bsdf type="diffuse"><rgb name="reflectance" value="0.7, 0.2, 0.15"/></bsdf>'
ROUGH_GOLD = '<bsdf type="roughconductor"><string name="material" value="Au"/><float name="alpha" value="0.25"/></bsdf>'
MIRROR = '<bsdf type="conductor"/>'
WEIGHT_CHECKER = ('<texture type="checkerboard" name="weight"><float name="color0" value="0.15"/>'
                  '<float name="color1" value="0.85"/><transform name="to_uv"><scale x="3" y="3"/></transform></texture>')


def blend(weight, a, b):
    return '<bsdf type="blendbsdf">' + weight + a + b + '</bsdf>'


CASES = [
    Case("blendbsdf", "blendbsdf (weight 0.35, diffuse and roughconductor)", scene(lit(SKY + sphere(
        blend('<float name="weight" value="0.35"/>', DIFFUSE, ROUGH_GOLD))))),
    Case("blendbsdf_textured", "blendbsdf (checkerboard weight, diffuse and roughconductor), obj", scene(LIGHT + SKY + """
    <shape type="obj"><string name="filename" value="quad.obj"/>
        <transform name="to_world"><scale value="2"/></transform>
        """ + blend(WEIGHT_CHECKER, DIFFUSE, ROUGH_GOLD) + """
    </shape>
""", to_world='<lookat origin="0, 3, 2" target="0, 0, 0" up="0, 1, 0"/>')),
    Case("blendbsdf_mirror", "blendbsdf (weight 0.5, diffuse and conductor)", scene(lit(SKY + sphere(
        blend('<float name="weight" value="0.5"/>', DIFFUSE, MIRROR))))),
]
