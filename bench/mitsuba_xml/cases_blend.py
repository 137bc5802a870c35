"""Cases of bench/mitsuba_xml_compare.py for blendbsdf (lamplight's `blend`):
a constant weight of a diffuse and a rough conductor, and a checkerboard
weight (0.15 and 0.85) of a diffuse and a perfect mirror, both in the lit
scene under a sky. Imported by cases.py, which appends them to its CASES."""
from .cases import SKY, Case, lit, scene, sphere

DIFFUSE = '<bsdf type="diffuse"><rgb name="reflectance" value="0.7, 0.2, 0.15"/></bsdf>'
ROUGH_GOLD = '<bsdf type="roughconductor"><string name="material" value="Au"/><float name="alpha" value="0.25"/></bsdf>'
MIRROR = '<bsdf type="conductor"/>'
WEIGHT_CHECKER = ('<texture type="checkerboard" name="weight"><float name="color0" value="0.15"/>'
                  '<float name="color1" value="0.85"/><transform name="to_uv"><scale x="6" y="3"/></transform></texture>')

CASES = [
    Case("blendbsdf", "blendbsdf (weight 0.35, diffuse and roughconductor)", scene(lit(SKY + sphere(
        '<bsdf type="blendbsdf"><float name="weight" value="0.35"/>' + DIFFUSE + ROUGH_GOLD + '</bsdf>')))),
    Case("blendbsdf_textured", "blendbsdf (checkerboard weight, diffuse and conductor)", scene(lit(SKY + sphere(
        '<bsdf type="blendbsdf">' + WEIGHT_CHECKER + DIFFUSE + MIRROR + '</bsdf>')))),
]
