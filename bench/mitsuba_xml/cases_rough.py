"""Cases of bench/mitsuba_xml_compare.py for issue 26's last BSDF items:
`roughconductor` (and `roughdielectric`) whose `alpha`, or `alpha_u` and
`alpha_v`, is a texture that Mitsuba reads per hit (`eval_1` at the hit's uv),
`roughconductor` under a `normalmap` (isotropic and anisotropic: the
perturbed frame's tangent and Mitsuba's flip of invalid normals and shadowing
term), and `principledthin` with a textured `eta`. write_assets writes the
roughness stripes, the index map and the bumpy normal map. Imported by
cases.py, which appends them to its CASES."""
import os

import numpy as np

from .cases import LIGHT, SKY, Case, lit, scene, sphere
from .cases_bsdfs2 import PANE

DIFFUSE = '<bsdf type="diffuse"><rgb name="reflectance" value="0.7, 0.2, 0.15"/></bsdf>'
# Looked at from above, so that the floor shows the light's reflection.
ABOVE = '<lookat origin="0, 2.6, 3" target="0, 0.2, 0" up="0, 1, 0"/>'


def alpha_bitmap(name="alpha", filename="alpha_stripes.png", extra=""):
    return (f'<texture type="bitmap" name="{name}"><string name="filename" value="{filename}"/>'
            f'<boolean name="raw" value="true"/>{extra}</texture>')


def checker(name, c0, c1, scale=4):
    return (f'<texture type="checkerboard" name="{name}"><float name="color0" value="{c0}"/>'
            f'<float name="color1" value="{c1}"/><transform name="to_uv"><scale x="{scale}" y="{scale}"/></transform></texture>')


def conductor(alpha, distribution="ggx", material="Cu"):
    return (f'<bsdf type="roughconductor"><string name="material" value="{material}"/>'
            f'<string name="distribution" value="{distribution}"/>{alpha}</bsdf>')


def floor(bsdf):
    """An OBJ quad (uv from the file) turned about y, and a diffuse sphere on it."""
    return f"""    <shape type="obj"><string name="filename" value="quad.obj"/>
        <transform name="to_world"><rotate y="1" angle="25"/><scale value="1.6"/></transform>
        {bsdf}
    </shape>
""" + sphere(DIFFUSE, center="-0.4, 0.35, -0.3", radius=0.35)


def normalmap(bsdf):
    return ('<bsdf type="normalmap"><texture type="bitmap" name="normalmap"><string name="filename" value="bumps.png"/>'
            f'<boolean name="raw" value="true"/></texture>{bsdf}</bsdf>')


CASES = [
    Case("roughconductor_alpha_bitmap", "roughconductor (ggx, alpha a bitmap; OBJ floor)",
         scene(SKY + LIGHT + floor(conductor(alpha_bitmap())), to_world=ABOVE)),
    Case("roughconductor_alpha_bitmap_nearest", "roughconductor (beckmann, alpha a bitmap, nearest; rectangle)",
         scene(SKY + LIGHT + """    <shape type="rectangle">
        <transform name="to_world"><rotate x="1" angle="-90"/><rotate y="1" angle="20"/><scale value="1.6"/></transform>
        """ + conductor(alpha_bitmap(extra='<string name="filter_type" value="nearest"/>'), "beckmann", "Al") + """
    </shape>
""" + sphere(DIFFUSE, center="0.4, 0.35, -0.2", radius=0.35), to_world=ABOVE)),
    Case("roughconductor_alpha_checkerboard", "roughconductor (ggx, alpha a checkerboard; sphere)",
         scene(lit(SKY + sphere(conductor(checker("alpha", 0.04, 0.45)))))),
    Case("roughconductor_alpha_uv_textures", "roughconductor (beckmann, alpha_u and alpha_v inverted checkerboards; OBJ floor)",
         scene(SKY + LIGHT + floor(conductor(checker("alpha_u", 0.04, 0.4, 3) + checker("alpha_v", 0.4, 0.04, 3),
                                             "beckmann", "Au")), to_world=ABOVE)),
    Case("roughdielectric_alpha_bitmap", "roughdielectric (ggx, alpha a bitmap; a pane before a sphere)",
         scene(lit(SKY + sphere(DIFFUSE) + PANE.format(
             bsdf='<bsdf type="roughdielectric"><float name="int_ior" value="1.5"/><string name="distribution" value="ggx"/>'
             + alpha_bitmap() + '</bsdf>')))),
    Case("roughconductor_normalmap", "normalmap of roughconductor (ggx, alpha 0.15; OBJ floor)",
         scene(SKY + LIGHT + floor(normalmap(conductor('<float name="alpha" value="0.15"/>'))), to_world=ABOVE)),
    Case("roughconductor_normalmap_aniso", "normalmap of roughconductor (ggx, alpha_u 0.05, alpha_v 0.35; OBJ floor)",
         scene(SKY + LIGHT + floor(normalmap(conductor('<float name="alpha_u" value="0.05"/><float name="alpha_v" value="0.35"/>'))),
               to_world=ABOVE)),
    Case("roughconductor_normalmap_sphere", "normalmap of roughconductor (beckmann, alpha 0.2; sphere)",
         scene(lit(SKY + sphere(normalmap(conductor('<float name="alpha" value="0.2"/>', "beckmann", "Ag")))))),
    Case("principledthin_eta_checkerboard", "principledthin (eta a checkerboard 1.1 / 2.2; a pane before a sphere)",
         scene(lit(SKY + sphere(DIFFUSE) + PANE.format(
             bsdf='<bsdf type="principledthin"><rgb name="base_color" value="0.3, 0.6, 0.8"/>'
             '<float name="spec_trans" value="0.8"/><float name="roughness" value="0.4"/>'
             + checker("eta", 1.1, 2.2) + '</bsdf>')))),
    Case("principledthin_eta_bitmap", "principledthin (eta a grey EXR bitmap; a pane before a sphere)",
         scene(lit(SKY + sphere(DIFFUSE) + PANE.format(
             bsdf='<bsdf type="principledthin"><rgb name="base_color" value="0.8, 0.7, 0.3"/>'
             '<float name="spec_trans" value="0.6"/><float name="diff_trans" value="0.5"/><float name="roughness" value="0.3"/>'
             '<texture type="bitmap" name="eta"><string name="filename" value="eta.exr"/></texture></bsdf>')))),
]


def write_assets(d):
    """The roughness stripes, the index map and the bumpy normal map, into folder d."""
    import mitsuba as mi
    # Eight stripes across u, alpha from 0.03 to 0.6 (linear, raw), a ramp along v.
    h, w = 16, 16
    yy, xx = np.mgrid[0:h, 0:w].astype(np.float64)
    alpha = 0.03 + 0.57 * ((xx // 2) / 7.0) * (0.6 + 0.4 * yy / (h - 1))
    mi.Bitmap((alpha * 255).round().astype(np.uint8)[:, :, None], mi.Bitmap.PixelFormat.Y).write(
        os.path.join(d, "alpha_stripes.png"))
    # An index of refraction from 1.05 to 2.4 in float, grey (Mitsuba's eval_1 of
    # RGB is the luminance, here the value; lamplight reads no one-channel EXR).
    eta = 1.05 + 1.35 * (0.5 + 0.5 * np.sin(xx / w * 2 * np.pi) * np.cos(yy / h * 2 * np.pi))
    mi.Bitmap(np.repeat(eta.astype(np.float32)[:, :, None], 3, axis=2), mi.Bitmap.PixelFormat.RGB).write(os.path.join(d, "eta.exr"))
    # Bumps tilted along both x and y (so that the map's second axis counts).
    h, w = 32, 32
    yy, xx = np.mgrid[0:h, 0:w].astype(np.float64)
    n = np.stack([0.45 * np.sin(xx / w * 4 * np.pi), 0.35 * np.sin(yy / h * 2 * np.pi + 0.5), np.ones_like(xx)], axis=2)
    n /= np.linalg.norm(n, axis=2, keepdims=True)
    mi.Bitmap(((n * 0.5 + 0.5) * 255).round().astype(np.uint8), mi.Bitmap.PixelFormat.RGB).write(os.path.join(d, "bumps.png"))
