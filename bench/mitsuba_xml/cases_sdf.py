"""Cases of bench/mitsuba_xml_compare.py for the signed-distance grid shape
(`sdfgrid`): a sphere's exact distance sampled on a 32^3 grid, with each kind
of shading normal. write_assets writes the grid."""
import os

from mitsuba_xml.cases import DIFFUSE_RED, Case, lit, scene

# The unit cube scaled by 1.5 around the grid's sphere (centre 0.5, radius 0.4):
# a sphere of radius 0.6 resting just above the floor, centred at (0, 0.62, 0).
PLACED = '<transform name="to_world"><scale value="1.5"/><translate x="-0.75" y="-0.13" z="-0.75"/></transform>'


def sdf(normals=""):
    option = f'<string name="normals" value="{normals}"/>' if normals else ""
    return f"""    <shape type="sdfgrid"><string name="filename" value="sphere32.vol"/>{option}
        {PLACED}
        {DIFFUSE_RED}
    </shape>
"""


CASES = [
    Case("sdfgrid", "sdfgrid (smooth normals, .vol)", scene(lit(sdf()))),
    Case("sdfgrid_analytic", "sdfgrid (analytic normals)", scene(lit(sdf("analytic")))),
]


def write_assets(d):
    """The grid these cases read, into folder d: the distance to a sphere of
    radius 0.4 at the cube's centre, at the 32^3 corners (i, j, k) / 31."""
    import mitsuba as mi
    import numpy as np
    x = np.linspace(0.0, 1.0, 32)
    z, y, x = np.meshgrid(x, x, x, indexing="ij")  # stored [z, y, x]: x fastest
    distance = np.sqrt((x - 0.5) ** 2 + (y - 0.5) ** 2 + (z - 0.5) ** 2) - 0.4
    mi.VolumeGrid(distance[..., None].astype(np.float32)).write(os.path.join(d, "sphere32.vol"))
