"""Cases of bench/mitsuba_xml_compare.py for the coated and thin BSDFs and the
Beckmann distribution (plastic, roughplastic, thindielectric, roughdielectric
beckmann). Imported by cases.py, which appends them to its CASES."""
from .cases import SKY, Case, lit, scene, sphere

CHECKER = ('<texture type="checkerboard" name="diffuse_reflectance"><rgb name="color0" value="0.8, 0.3, 0.1"/>'
           '<rgb name="color1" value="0.1, 0.3, 0.8"/><transform name="to_uv"><scale x="4" y="4"/></transform></texture>')

PANE = """    <shape type="rectangle">
        <transform name="to_world"><scale x="0.9" y="0.7"/><rotate y="1" angle="35"/><translate x="0.2" y="0.7" z="1.4"/></transform>
        {bsdf}
    </shape>
"""

CASES = [
    Case("plastic_nonlinear_textured", "plastic (nonlinear, textured, int_ior)", scene(lit(SKY + sphere(
        '<bsdf type="plastic">' + CHECKER + '<boolean name="nonlinear" value="true"/><float name="int_ior" value="1.9"/></bsdf>')))),
    Case("roughplastic_ggx", "roughplastic (ggx)", scene(lit(SKY + sphere(
        '<bsdf type="roughplastic"><rgb name="diffuse_reflectance" value="0.2, 0.5, 0.7"/>'
        '<string name="distribution" value="ggx"/><float name="alpha" value="0.2"/></bsdf>')))),
    Case("roughplastic_beckmann", "roughplastic (beckmann, nonlinear)", scene(lit(SKY + sphere(
        '<bsdf type="roughplastic"><rgb name="diffuse_reflectance" value="0.7, 0.2, 0.15"/>'
        '<float name="alpha" value="0.3"/><boolean name="nonlinear" value="true"/></bsdf>')))),
    Case("thindielectric", "thindielectric", scene(lit(SKY + sphere(
        '<bsdf type="diffuse"><rgb name="reflectance" value="0.7, 0.2, 0.15"/></bsdf>')
        + PANE.format(bsdf='<bsdf type="thindielectric"/>')))),
    Case("roughdielectric_beckmann", "roughdielectric (beckmann)", scene(lit(SKY + sphere(
        '<bsdf type="roughdielectric"><float name="int_ior" value="1.5"/><float name="alpha" value="0.2"/></bsdf>')))),
]
