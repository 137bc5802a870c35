"""Film and sensor cases of bench/mitsuba_xml_compare.py: crop windows (with a
filter wider than a pixel, so the crop's edges are cut as Mitsuba cuts them),
principal point offsets on perspective (non-square films, so the units of x
and y differ; Mitsuba 3.9's thinlens does not take them: it reports them as
unreferenced properties), and the Gaussian filter on a scene whose edges are
bright and structured (a filter that were not cut at the image's edge would
blur the border), and the filters with negative lobes (Mitchell-Netravali,
Catmull-Rom, Lanczos) on the same sharp edges, where their ringing shows, and
in a crop window."""
from .cases import DIFFUSE_RED, SKY, Case, lit, scene, sphere

BRIGHT_EDGES = lit(SKY + sphere(DIFFUSE_RED, center="0.9, 0.5, 0", radius=0.7)
                   + sphere('<bsdf type="diffuse"><rgb name="reflectance" value="0.8, 0.8, 0.8"/></bsdf>',
                            center="-1.1, 0.4, 0.5", radius=0.5))


def film_scene(body, film_props, rfilter, **kw):
    """`scene` with extra `hdrfilm` properties before the filter."""
    return scene(body, rfilter=film_props + rfilter, **kw)


CROP = ('<integer name="crop_offset_x" value="10"/><integer name="crop_offset_y" value="6"/>'
        '<integer name="crop_width" value="30"/><integer name="crop_height" value="34"/>')
PRINCIPAL = ('<float name="principal_point_offset_x" value="0.2"/>'
             '<float name="principal_point_offset_y" value="-0.15"/>')

CASES = [
    Case("rfilter_gaussian_edges", "rfilter gaussian (edges)", scene(BRIGHT_EDGES, rfilter='<rfilter type="gaussian"/>')),
    Case("rfilter_tent_edges", "rfilter tent (edges)", scene(BRIGHT_EDGES, rfilter='<rfilter type="tent"/>')),
    Case("rfilter_mitchell_edges", "rfilter mitchell (edges)", scene(BRIGHT_EDGES, rfilter='<rfilter type="mitchell"/>')),
    Case("rfilter_mitchell_bc_edges", "rfilter mitchell B, C (edges)",
         scene(BRIGHT_EDGES, rfilter='<rfilter type="mitchell"><float name="B" value="0.1"/><float name="C" value="0.6"/></rfilter>')),
    Case("rfilter_catmullrom_edges", "rfilter catmullrom (edges)", scene(BRIGHT_EDGES, rfilter='<rfilter type="catmullrom"/>')),
    Case("rfilter_lanczos_edges", "rfilter lanczos (edges)", scene(BRIGHT_EDGES, rfilter='<rfilter type="lanczos"/>')),
    Case("crop_window_lanczos", "hdrfilm crop window (lanczos, 2 lobes)",
         film_scene(BRIGHT_EDGES, CROP, '<rfilter type="lanczos"><integer name="lobes" value="2"/></rfilter>')),
    Case("crop_window", "hdrfilm crop window (gaussian)", film_scene(BRIGHT_EDGES, CROP, '<rfilter type="gaussian"/>')),
    Case("crop_window_box", "hdrfilm crop window (box)", film_scene(BRIGHT_EDGES, CROP, '<rfilter type="box"/>')),
    Case("principal_point", "perspective principal_point_offset_x/y",
         scene(BRIGHT_EDGES, size=(64, 40), sensor_props=PRINCIPAL)),
    Case("principal_point_tall", "perspective principal_point_offset_x/y (portrait film)",
         scene(BRIGHT_EDGES, size=(40, 56), sensor_props=PRINCIPAL)),
    Case("principal_point_crop", "principal_point_offset with a crop window (tent)",
         film_scene(BRIGHT_EDGES, CROP, '<rfilter type="tent"/>', sensor_props=PRINCIPAL)),
]
