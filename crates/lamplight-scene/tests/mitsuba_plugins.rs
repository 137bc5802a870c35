//! Issue 26: `docs/mitsuba.md`'s list of every plugin Mitsuba 3.9.1 ships,
//! kept honest. The doc's tables are the single source: for each row, a
//! minimal scene using the plugin is read and built, and the outcome must be
//! the status the row states (`read` and `differs`: read without a warning;
//! `skipped`: read, with the quoted warning; `refused`: the quoted error). A
//! plugin the reader accepts but the doc marks refused, or the reverse, fails.
//! The names are checked against Mitsuba 3.9.1's own list too, so that a
//! plugin cannot drop out of the doc unnoticed.

use std::io::Cursor;

use crate::common::mitsuba_xml::{one_sphere, outcome};

/// The doc whose tables are checked.
const DOC: &str = include_str!("../../../docs/mitsuba.md");

/// The section of [`DOC`] that lists the plugins.
const SECTION: &str = "## Every Mitsuba 3.9.1 plugin";

/// Mitsuba 3.9.1's plugins by the doc's category headings: the `add_plugin`
/// names of `src/<folder>/CMakeLists.txt` at tag v3.9.1, and the plugins its
/// Python package registers (`mi.register_integrator`, `mi.register_sensor`
/// in `src/python/python/ad/`).
const MITSUBA: &[(&str, &[&str])] = &[
    (
        "BSDFs",
        &[
            "blendbsdf",
            "bumpmap",
            "conductor",
            "dielectric",
            "diffuse",
            "hair",
            "mask",
            "measured",
            "normalmap",
            "null",
            "plastic",
            "roughconductor",
            "roughdielectric",
            "roughplastic",
            "thindielectric",
            "twosided",
            "polarizer",
            "retarder",
            "circular",
            "measured_polarized",
            "pplastic",
            "principled",
            "principledthin",
        ],
    ),
    ("Emitters", &["area", "point", "constant", "envmap", "directional", "directionalarea", "spot", "projector", "sunsky", "timed_sunsky"]),
    (
        "Shapes",
        &[
            "obj",
            "ply",
            "blender",
            "serialized",
            "cylinder",
            "disk",
            "rectangle",
            "sdfgrid",
            "sphere",
            "cube",
            "bsplinecurve",
            "linearcurve",
            "shapegroup",
            "instance",
            "merge",
            "ellipsoids",
            "ellipsoidsmesh",
        ],
    ),
    ("Sensors", &["perspective", "orthographic", "radiancemeter", "thinlens", "irradiancemeter", "distant", "batch", "flat_sensor"]),
    ("Films", &["hdrfilm", "specfilm"]),
    ("Reconstruction filters", &["box", "tent", "lanczos", "mitchell", "catmullrom", "gaussian"]),
    ("Samplers", &["independent", "stratified", "multijitter", "orthogonal", "ldsampler"]),
    (
        "Integrators",
        &[
            "aov",
            "depth",
            "direct",
            "moment",
            "path",
            "ptracer",
            "stokes",
            "volpath",
            "volpathmis",
            "direct_projective",
            "prb",
            "prb_basic",
            "prb_projective",
            "prbvolpath",
            "volprim_rf_basic",
        ],
    ),
    ("Textures", &["bitmap", "checkerboard", "mesh_attribute", "volume"]),
    ("Spectra", &["blackbody", "d65", "irregular", "regular", "rawconstant", "srgb", "uniform"]),
    ("Media", &["homogeneous", "heterogeneous"]),
    ("Phase functions", &["hg", "isotropic", "blendphase", "rayleigh", "sggx", "tabphase"]),
    ("Volumes", &["constvolume", "gridvolume"]),
];

/// What the doc says the reader does with a plugin.
#[derive(Debug, PartialEq)]
enum Status {
    /// Read as Mitsuba means it.
    Read,
    /// Read, with a difference the row states.
    Differs,
    /// Read without it, with this warning.
    Skipped(String),
    /// An error with this message.
    Refused(String),
}

/// One row of the doc's tables.
#[derive(Debug)]
struct Row {
    category: String,
    plugin: String,
    status: Status,
    line: usize,
}

/// The first code span of `cell`.
fn code(cell: &str) -> Option<&str> {
    let start = cell.find('`')? + 1;
    let len = cell[start..].find('`')?;
    Some(&cell[start..start + len])
}

/// The rows of [`SECTION`]'s tables, each under its `### ` category heading.
fn rows() -> Vec<Row> {
    let start = DOC.find(SECTION).unwrap_or_else(|| panic!("docs/mitsuba.md has no \"{SECTION}\" section"));
    let first_line = DOC[..start].lines().count() + 1;
    let mut rows = Vec::new();
    let mut category = None;
    for (i, line) in DOC[start..].lines().enumerate().skip(1) {
        let line_no = first_line + i;
        if line.starts_with("## ") {
            break;
        }
        if let Some(h) = line.strip_prefix("### ") {
            category = Some(h.trim().to_string());
            continue;
        }
        let Some(inner) = line.strip_prefix('|') else { continue };
        let cells: Vec<&str> = inner.trim_end().trim_end_matches('|').split('|').map(str::trim).collect();
        if cells[0] == "plugin" || cells[0].starts_with("---") {
            continue;
        }
        let category = category.clone().unwrap_or_else(|| panic!("docs/mitsuba.md:{line_no}: a table row before any ### heading"));
        assert_eq!(cells.len(), 3, "docs/mitsuba.md:{line_no}: expected | plugin | status | notes |");
        let plugin = code(cells[0]).unwrap_or_else(|| panic!("docs/mitsuba.md:{line_no}: the plugin is not in `code`")).to_string();
        let quoted = || {
            code(cells[2])
                .unwrap_or_else(|| panic!("docs/mitsuba.md:{line_no}: {plugin}: the notes must start with the message in `code`"))
                .to_string()
        };
        let status = match cells[1] {
            "read" => Status::Read,
            "differs" => Status::Differs,
            "skipped" => Status::Skipped(quoted()),
            "refused" => Status::Refused(quoted()),
            other => panic!("docs/mitsuba.md:{line_no}: {plugin}: status \"{other}\", expected read, differs, skipped or refused"),
        };
        rows.push(Row { category, plugin, status, line: line_no });
    }
    rows
}

const FILM: &str = r#"<film type="hdrfilm"><integer name="width" value="8"/><integer name="height" value="8"/></film>"#;

/// A scene of `sensor` (the default camera when empty) and `body`.
fn scene(sensor: &str, body: &str) -> String {
    let sensor = if sensor.is_empty() { format!(r#"<sensor type="perspective">{FILM}</sensor>"#) } else { sensor.to_string() };
    format!("<scene version=\"3.0.0\">\n    {sensor}\n    {body}\n</scene>\n")
}

/// A 2 x 2 PNG image.
fn png() -> Vec<u8> {
    let mut out = Cursor::new(Vec::new());
    image::DynamicImage::ImageRgb8(image::RgbImage::from_pixel(2, 2, image::Rgb([128, 128, 255])))
        .write_to(&mut out, image::ImageFormat::Png)
        .unwrap();
    out.into_inner()
}

/// A 2 x 2 Radiance `.hdr` image of 1 (flat scanlines).
fn hdr() -> Vec<u8> {
    let mut out = b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 2 +X 2\n".to_vec();
    for _ in 0..4 {
        out.extend([128, 128, 128, 129]);
    }
    out
}

/// A version-4 `.serialized` file of one triangle, as Mitsuba writes it.
fn serialized() -> Vec<u8> {
    use std::io::Write;
    let mut body = Vec::new();
    body.extend(0x0001u32.to_le_bytes());
    body.extend(b"tri\0");
    body.extend(3u64.to_le_bytes());
    body.extend(1u64.to_le_bytes());
    for v in [0f32, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0] {
        body.extend(v.to_le_bytes());
    }
    for _ in 0..3 {
        for v in [0f32, 0.0, 1.0] {
            body.extend(v.to_le_bytes());
        }
    }
    for i in [0u32, 1, 2] {
        body.extend(i.to_le_bytes());
    }
    let mut z = flate2::write::ZlibEncoder::new(Vec::new(), flate2::Compression::default());
    z.write_all(&body).unwrap();
    let mut file = vec![0x1C, 0x04, 4, 0];
    file.extend(z.finish().unwrap());
    file.extend(0u64.to_le_bytes());
    file.extend(1u32.to_le_bytes());
    file
}

const PLY: &str = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n\
element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";

/// A minimal scene using the plugin `name` of `category`, and the files it names.
fn minimal(category: &str, name: &str) -> (String, Vec<(&'static str, Vec<u8>)>) {
    let mut files = Vec::new();
    let bitmap = |files: &mut Vec<(&'static str, Vec<u8>)>, slot: &str| {
        files.push(("t.png", png()));
        format!(r#"<texture type="bitmap" name="{slot}"><string name="filename" value="t.png"/></texture>"#)
    };
    let xml = match category {
        "BSDFs" => {
            let inner = match name {
                "twosided" | "mask" => r#"<bsdf type="diffuse"/>"#.to_string(),
                "blendbsdf" => r#"<bsdf type="diffuse"/><bsdf type="conductor"/>"#.to_string(),
                "bumpmap" => r#"<texture type="checkerboard" name="height"/><bsdf type="diffuse"/>"#.to_string(),
                "normalmap" => format!(r#"{}<bsdf type="diffuse"/>"#, bitmap(&mut files, "normalmap")),
                _ => String::new(),
            };
            one_sphere(&format!(r#"<bsdf type="{name}">{inner}</bsdf>"#))
        }
        "Emitters" => match name {
            "area" | "directionalarea" => scene("", &format!(r#"<shape type="sphere"><emitter type="{name}"/></shape>"#)),
            "envmap" => {
                files.push(("e.hdr", hdr()));
                scene("", r#"<emitter type="envmap"><string name="filename" value="e.hdr"/></emitter><shape type="sphere"/>"#)
            }
            "projector" => {
                scene("", &format!(r#"<emitter type="projector">{}</emitter><shape type="sphere"/>"#, bitmap(&mut files, "irradiance")))
            }
            _ => scene("", &format!(r#"<emitter type="{name}"/><shape type="sphere"/>"#)),
        },
        "Shapes" => {
            let file = |files: &mut Vec<(&'static str, Vec<u8>)>, file: &'static str, bytes: Vec<u8>| {
                files.push((file, bytes));
                format!(r#"<shape type="{name}"><string name="filename" value="{file}"/></shape>"#)
            };
            let body = match name {
                "obj" => file(&mut files, "m.obj", b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n".to_vec()),
                "ply" => file(&mut files, "m.ply", PLY.as_bytes().to_vec()),
                "serialized" => file(&mut files, "m.serialized", serialized()),
                "sdfgrid" => {
                    use lamplight_scene::formats::mitsuba::volume::{write, Grid};
                    let values = (0..8).map(|i| if i == 0 { -0.5 } else { 0.5 }).collect();
                    file(&mut files, "g.vol", write(&Grid { resolution: [2, 2, 2], values }))
                }
                "shapegroup" | "instance" => {
                    r#"<shape type="shapegroup" id="g"><shape type="sphere"/></shape><shape type="instance"><ref id="g"/></shape>"#
                        .to_string()
                }
                "merge" => r#"<shape type="merge"><shape type="sphere"/></shape>"#.to_string(),
                _ => format!(r#"<shape type="{name}"/>"#),
            };
            scene("", &body)
        }
        "Sensors" => {
            let extra = if name == "thinlens" { r#"<float name="focus_distance" value="1"/>"# } else { "" };
            scene(&format!(r#"<sensor type="{name}">{extra}{FILM}</sensor>"#), r#"<shape type="sphere"/>"#)
        }
        "Films" => scene(
            &format!(
                r#"<sensor type="perspective"><film type="{name}"><integer name="width" value="8"/><integer name="height" value="8"/></film></sensor>"#
            ),
            r#"<shape type="sphere"/>"#,
        ),
        "Reconstruction filters" => scene(
            &format!(
                r#"<sensor type="perspective"><film type="hdrfilm"><integer name="width" value="8"/><integer name="height" value="8"/><rfilter type="{name}"/></film></sensor>"#
            ),
            r#"<shape type="sphere"/>"#,
        ),
        "Samplers" => scene(
            &format!(
                r#"<sensor type="perspective">{FILM}<sampler type="{name}"><integer name="sample_count" value="4"/></sampler></sensor>"#
            ),
            r#"<shape type="sphere"/>"#,
        ),
        "Integrators" => {
            let inner = if name == "moment" { r#"<integrator type="path"/>"# } else { "" };
            scene("", &format!(r#"<integrator type="{name}">{inner}</integrator><shape type="sphere"/>"#))
        }
        "Textures" => {
            let texture = match name {
                "bitmap" => bitmap(&mut files, "reflectance"),
                "mesh_attribute" => {
                    r#"<texture type="mesh_attribute" name="reflectance"><string name="name" value="vertex_color"/></texture>"#.into()
                }
                _ => format!(r#"<texture type="{name}" name="reflectance"/>"#),
            };
            one_sphere(&format!(r#"<bsdf type="diffuse">{texture}</bsdf>"#))
        }
        "Spectra" => {
            let value = if name == "rawconstant" { r#"<float name="value" value="0.5"/>"# } else { "" };
            one_sphere(&format!(r#"<bsdf type="diffuse"><texture type="{name}" name="reflectance">{value}</texture></bsdf>"#))
        }
        "Media" => scene("", &format!(r#"<shape type="sphere"><medium type="{name}" name="interior"/></shape>"#)),
        "Phase functions" => scene(
            "",
            &format!(r#"<shape type="sphere"><medium type="homogeneous" name="interior"><phase type="{name}"/></medium></shape>"#),
        ),
        "Volumes" => scene(
            "",
            &format!(
                r#"<shape type="sphere"><medium type="heterogeneous" name="interior"><volume type="{name}" name="sigma_t"/></medium></shape>"#
            ),
        ),
        other => panic!("no minimal scene for the category \"{other}\""),
    };
    (xml, files)
}

/// An outcome in words, for the failure message.
fn describe(result: &Result<Vec<String>, String>) -> String {
    match result {
        Ok(w) if w.is_empty() => "read without a warning".into(),
        Ok(w) => format!("read with the warnings {w:?}"),
        Err(e) => format!("the error \"{e}\""),
    }
}

/// Whether `line` (`FILE:LINE:COL: message`) carries exactly `message`.
fn says(line: &str, message: &str) -> bool {
    line.strip_suffix(message).is_some_and(|place| place.ends_with(": "))
}

#[test]
fn every_plugin_in_the_doc_reads_as_its_status_says() {
    let rows = rows();
    assert!(!rows.is_empty(), "no plugin rows under \"{SECTION}\"");
    let mut wrong = Vec::new();
    for row in &rows {
        let (xml, files) = minimal(&row.category, &row.plugin);
        let got = outcome(&xml, &files);
        let ok = match (&row.status, &got) {
            (Status::Read | Status::Differs, Ok(warnings)) => warnings.is_empty(),
            (Status::Skipped(message), Ok(warnings)) => warnings.iter().any(|w| says(w, message)),
            (Status::Refused(message), Err(e)) => says(e, message),
            _ => false,
        };
        if !ok {
            wrong.push(format!(
                "docs/mitsuba.md:{}: {} `{}` is {:?}, but reading it gives {}\n{xml}",
                row.line,
                row.category,
                row.plugin,
                row.status,
                describe(&got)
            ));
        }
    }
    assert!(wrong.is_empty(), "{} of {} rows disagree with the reader:\n{}", wrong.len(), rows.len(), wrong.join("\n"));
}

#[test]
fn the_doc_lists_every_plugin_mitsuba_ships_once() {
    let rows = rows();
    let headings: Vec<&str> = rows.iter().map(|r| r.category.as_str()).fold(Vec::new(), |mut v, c| {
        if v.last() != Some(&c) {
            v.push(c);
        }
        v
    });
    assert_eq!(headings, MITSUBA.iter().map(|(c, _)| *c).collect::<Vec<_>>(), "the doc's categories, in order");
    for (category, names) in MITSUBA {
        let mut listed: Vec<&str> = rows.iter().filter(|r| r.category == *category).map(|r| r.plugin.as_str()).collect();
        let mut shipped = names.to_vec();
        listed.sort_unstable();
        shipped.sort_unstable();
        assert_eq!(listed, shipped, "{category}: the doc's rows against Mitsuba 3.9.1's plugins");
    }
}

#[test]
fn spectra_written_as_spectrum_elements_are_refused() {
    // The doc's note above the Spectra table: the `<spectrum type>` form is an error.
    for name in MITSUBA.iter().find(|(c, _)| *c == "Spectra").expect("listed").1 {
        let xml = one_sphere(&format!(r#"<bsdf type="diffuse"><spectrum type="{name}" name="reflectance"/></bsdf>"#));
        let got = outcome(&xml, &[]);
        let message = r#"bsdf "diffuse": reflectance: expected a colour or a <texture>, got <spectrum>"#;
        assert!(matches!(&got, Err(e) if says(e, message)), "{name}: {}", describe(&got));
    }
    let section = &DOC[DOC.find(SECTION).expect("section")..];
    assert!(
        section.contains("(`bsdf\n\"diffuse\": reflectance: expected a colour or a <texture>, got <spectrum>`)"),
        "the doc quotes the error"
    );
}
