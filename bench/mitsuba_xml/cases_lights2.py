"""More scenes of bench/mitsuba_xml_compare.py: a spot light projecting an
image and a projector (issue 15). write_assets writes the image they project."""
import os

from mitsuba_xml.cases import FLOOR, DIFFUSE_RED, Case, scene, sphere

WALL = """    <shape type="rectangle">
        <transform name="to_world"><scale value="3"/><translate z="-1.5"/></transform>
        <bsdf type="diffuse"><rgb name="reflectance" value="0.7, 0.7, 0.7"/></bsdf>
    </shape>
"""

SPOT_TEXTURED = """    <emitter type="spot">
        <transform name="to_world"><lookat origin="0.4, 2.6, 0.6" target="0, 0, 0" up="0, 0, -1"/></transform>
        <rgb name="intensity" value="40, 40, 40"/>
        <float name="cutoff_angle" value="35"/>
        <texture type="bitmap" name="texture"><string name="filename" value="slide.png"/></texture>
    </emitter>
"""

PROJECTOR = """    <emitter type="projector">
        <transform name="to_world"><lookat origin="1.2, 1.6, 3" target="0, 0.4, -1.5" up="0, 1, 0"/></transform>
        <float name="fov" value="45"/>
        <float name="scale" value="6"/>
        <texture type="bitmap" name="irradiance"><string name="filename" value="slide.png"/>
            <string name="filter_type" value="nearest"/></texture>
    </emitter>
"""

PROJECTOR_FOCAL = """    <emitter type="projector">
        <transform name="to_world"><lookat origin="-1, 1.4, 3" target="0, 0.3, -1.5" up="0, 1, 0"/></transform>
        <string name="focal_length" value="35mm"/>
        <float name="scale" value="5"/>
        <texture type="bitmap" name="irradiance"><string name="filename" value="slide.png"/></texture>
    </emitter>
"""

CASES = [
    Case("spot_textured", "spot (texture, bilinear bitmap)", scene(FLOOR + sphere(DIFFUSE_RED, radius=0.4, center="0.6, 0.4, 0"),
                                                                   to_world='<lookat origin="0, 3, 3" target="0, 0, 0" up="0, 1, 0"/>')),
    Case("projector", "projector (fov, nearest bitmap)", scene(FLOOR + WALL + PROJECTOR + sphere(DIFFUSE_RED, radius=0.4))),
    Case("projector_focal_length", "projector (focal_length, bilinear bitmap)", scene(FLOOR + WALL + PROJECTOR_FOCAL)),
]
CASES[0] = CASES[0]._replace(xml=CASES[0].xml.replace("</scene>", SPOT_TEXTURED + "</scene>"))


def write_assets(d):
    """slide.png: 8 x 4 pixels of distinct colours, so that a flip or a turn shows."""
    import mitsuba as mi
    import numpy as np
    h, w = 4, 8
    yy, xx = np.mgrid[0:h, 0:w]
    rgb = np.stack([(xx + 1) / w, (yy + 1) / h, ((xx + yy) % 2) * 0.8 + 0.1], axis=-1)
    mi.Bitmap((rgb * 255).round().astype(np.uint8), mi.Bitmap.PixelFormat.RGB).write(os.path.join(d, "slide.png"))
