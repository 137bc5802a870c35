"""Cases of bench/mitsuba_xml_compare.py for Mitsuba's principled BSDF, read as
lamplight's `principled` material (crates/lamplight-core/src/bsdfs/principled.rs):
a dielectric, a metal, rough glass (spec_trans), sheen with clearcoat,
textured base colour and roughness; and `principledthin` (lamplight's
`principled_thin`) as a pane before a sphere and as a sphere. Imported by cases.py, which appends them to
its CASES."""
from .cases import SKY, Case, lit, scene, sphere
from .cases_bsdfs2 import PANE

# Greys for the roughness: Mitsuba reads a scalar through eval_1 (luminance),
# lamplight through the first channel; equal channels make them the same.
# (Mitsuba's checkerboard eval_1 swaps color0 and color1; the reader follows.)
TEXTURED = ('<bsdf type="principled">'
            '<texture type="checkerboard" name="base_color"><rgb name="color0" value="0.8, 0.3, 0.1"/>'
            '<rgb name="color1" value="0.1, 0.3, 0.8"/><transform name="to_uv"><scale x="4" y="4"/></transform></texture>'
            '<texture type="checkerboard" name="roughness"><float name="color0" value="0.15"/>'
            '<float name="color1" value="0.7"/><transform name="to_uv"><scale x="3" y="3"/></transform></texture>'
            '<float name="clearcoat" value="0.5"/></bsdf>')

CASES = [
    Case("principled_dielectric", "principled (dielectric)", scene(lit(SKY + sphere(
        '<bsdf type="principled"><rgb name="base_color" value="0.7, 0.3, 0.2"/><float name="roughness" value="0.4"/></bsdf>')))),
    Case("principled_metal", "principled (metallic)", scene(lit(SKY + sphere(
        '<bsdf type="principled"><rgb name="base_color" value="0.9, 0.6, 0.3"/><float name="metallic" value="1"/>'
        '<float name="roughness" value="0.3"/></bsdf>')))),
    Case("principled_spec_trans", "principled (spec_trans, eta)", scene(lit(SKY + sphere(
        '<bsdf type="principled"><rgb name="base_color" value="0.95, 0.9, 0.8"/><float name="spec_trans" value="0.9"/>'
        '<float name="eta" value="1.5"/><float name="roughness" value="0.2"/></bsdf>')))),
    Case("principled_sheen_clearcoat", "principled (sheen, clearcoat, spec_tint, specular)", scene(lit(SKY + sphere(
        '<bsdf type="principled"><rgb name="base_color" value="0.2, 0.5, 0.7"/><float name="metallic" value="0.2"/>'
        '<float name="sheen" value="0.8"/><float name="sheen_tint" value="0.5"/><float name="clearcoat" value="0.8"/>'
        '<float name="clearcoat_gloss" value="0.7"/><float name="spec_tint" value="0.3"/>'
        '<float name="specular" value="0.3"/><float name="roughness" value="0.5"/></bsdf>')))),
    Case("principled_textured", "principled (textured base_color and roughness)", scene(lit(SKY + sphere(TEXTURED)))),
    Case("principledthin_pane", "principledthin (spec_trans, diff_trans, eta, spec_tint)", scene(lit(SKY + sphere(
        '<bsdf type="diffuse"><rgb name="reflectance" value="0.7, 0.2, 0.15"/></bsdf>')
        + PANE.format(bsdf='<bsdf type="principledthin"><rgb name="base_color" value="0.3, 0.6, 0.2"/>'
                      '<float name="spec_trans" value="0.4"/><float name="diff_trans" value="0.8"/>'
                      '<float name="eta" value="1.4"/><float name="roughness" value="0.3"/>'
                      '<float name="spec_tint" value="0.2"/></bsdf>')))),
    Case("principledthin_sphere", "principledthin (diff_trans, sheen, flatness)", scene(lit(SKY + sphere(
        '<bsdf type="principledthin"><rgb name="base_color" value="0.8, 0.5, 0.4"/><float name="diff_trans" value="1.2"/>'
        '<float name="sheen" value="0.6"/><float name="sheen_tint" value="0.4"/><float name="flatness" value="0.5"/>'
        '<float name="roughness" value="0.6"/></bsdf>')))),
]
