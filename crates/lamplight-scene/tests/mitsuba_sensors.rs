//! Film and sensor settings of Mitsuba XML and their TOML form: pixel filters,
//! crop windows and principal point offsets (lens shifts), with the exact
//! errors for bad values and renders that keep their promises (a crop is the
//! full film's pixels).

use std::path::{Path, PathBuf};

use lamplight_core::params::{Table, Value};
use lamplight_core::RenderControl;
use lamplight_scene::formats::mitsuba;
use lamplight_scene::request::{Naming, Request, SceneRequest};

fn write(dir: &Path, name: &str, text: &str) -> PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path
}

/// A lit sphere seen by a camera with `sensor` properties, on a 16 x 12 film with `film` properties.
fn scene(sensor: &str, film: &str) -> String {
    format!(
        r#"<scene version="3.0.0">
    <integrator type="path"><integer name="max_depth" value="3"/></integrator>
    <sensor type="perspective">
        <float name="fov" value="45"/>{sensor}
        <transform name="to_world"><lookat origin="0, 1, 5" target="0, 0.5, 0" up="0, 1, 0"/></transform>
        <sampler type="independent"><integer name="sample_count" value="4"/></sampler>
        <film type="hdrfilm"><integer name="width" value="16"/><integer name="height" value="12"/>{film}</film>
    </sensor>
    <shape type="sphere"><point name="center" value="0, 0.5, 0"/><float name="radius" value="0.5"/><bsdf type="diffuse"/></shape>
    <emitter type="constant"><rgb name="radiance" value="0.5, 0.6, 0.7"/></emitter>
</scene>
"#
    )
}

fn table(text: &str) -> (Table, Vec<String>) {
    let dir = tempfile::tempdir().unwrap();
    let path = write(dir.path(), "s.xml", text);
    let (t, source) = mitsuba::read_table(&path, &[]).unwrap();
    let warnings = source.warnings.iter().map(|w| w.replace(&format!("{}/", dir.path().display()), "")).collect();
    (t, warnings)
}

fn error(name: &str, text: &str) -> String {
    let dir = tempfile::tempdir().unwrap();
    let path = write(dir.path(), name, text);
    let message = match SceneRequest::resolve(path.to_str().unwrap()) {
        Ok(scene) => match scene.build() {
            Ok(_) => panic!("read but should fail:\n{text}"),
            Err(e) => e.to_string(),
        },
        Err(e) => e.to_string(),
    };
    message.replace(&format!("{}/", dir.path().display()), "")
}

fn get<'a>(t: &'a Table, section: &str, key: &str) -> &'a Value {
    let Value::Table(s) = &t.get(section).unwrap().item.value else { panic!("{section}: not a table") };
    &s.get(key).unwrap_or_else(|| panic!("no {section}.{key}")).item.value
}

fn numbers(v: &Value) -> Vec<f64> {
    match v {
        Value::Number(n) => vec![*n],
        Value::Integer(i) => vec![*i as f64],
        Value::Array(items) => items.iter().flat_map(|i| numbers(&i.value)).collect(),
        other => panic!("not numbers: {other:?}"),
    }
}

/// The linear pixels of `path` rendered with `request`, and the image's width.
fn render(path: &Path, request: Request) -> (Vec<[f32; 3]>, u32) {
    let scene = SceneRequest::resolve(path.to_str().unwrap()).unwrap();
    let job = Request { threads: Some(2), ..request }.resolve(&scene.defaults, Naming::Flags).unwrap();
    let image = job.run(&scene.build().unwrap(), &RenderControl::default()).unwrap().image;
    (image.pixels, image.width)
}

#[test]
fn filters_read_as_lamplights() {
    for (rfilter, expected, warning) in [
        ("<rfilter type=\"tent\"/>", "tent", None),
        ("<rfilter type=\"gaussian\"/>", "gaussian", None),
        ("", "gaussian", None),
        (
            "<rfilter type=\"tent\"><float name=\"radius\" value=\"2\"/></rfilter>",
            "tent",
            Some("s.xml:7:148: rfilter \"tent\": radius 2 is read as 1 (lamplight's tent)"),
        ),
        ("<rfilter type=\"mitchell\"/>", "mitchell", None),
        (
            "<rfilter type=\"mitchell\"><float name=\"B\" value=\"0.5\"/><float name=\"C\" value=\"0.25\"/></rfilter>",
            "mitchell(B=0.5, C=0.25)",
            None,
        ),
        ("<rfilter type=\"catmullrom\"/>", "catmullrom", None),
        ("<rfilter type=\"lanczos\"/>", "lanczos", None),
        ("<rfilter type=\"lanczos\"><integer name=\"lobes\" value=\"2\"/></rfilter>", "lanczos(lobes=2)", None),
        ("<rfilter type=\"lanczos\"><integer name=\"lobes\" value=\"3\"/></rfilter>", "lanczos", None),
        ("<rfilter type=\"sinc\"/>", "box", Some("s.xml:7:99: rfilter \"sinc\": not supported, the box filter is used")),
    ] {
        let (t, warnings) = table(&scene("", rfilter));
        assert_eq!(get(&t, "render", "filter"), &Value::String(expected.into()), "{rfilter}");
        assert_eq!(warnings, warning.map(String::from).into_iter().collect::<Vec<_>>(), "{rfilter}");
    }
}

#[test]
fn bad_filter_parameters_are_errors_at_their_place() {
    let lanczos = |lobes: &str| scene("", &format!("<rfilter type=\"lanczos\"><integer name=\"lobes\" value=\"{lobes}\"/></rfilter>"));
    assert_eq!(error("s.xml", &lanczos("0")), "s.xml:7:152: rfilter \"lanczos\": lobes must be between 1 and 32, got 0");
    assert_eq!(error("s.xml", &lanczos("33")), "s.xml:7:152: rfilter \"lanczos\": lobes must be between 1 and 32, got 33");
    let mitchell = scene("", "<rfilter type=\"mitchell\"><float name=\"B\" value=\"inf\"/></rfilter>");
    assert_eq!(error("s.xml", &mitchell), "s.xml:7:147: rfilter \"mitchell\": B: expected a finite number, got \"inf\"");
    // The same filters named in a request (the CLI's --filter, Python's filter=).
    let dir = tempfile::tempdir().unwrap();
    let path = write(dir.path(), "s.xml", &scene("", "<rfilter type=\"box\"/>"));
    let scene = SceneRequest::resolve(path.to_str().unwrap()).unwrap();
    let resolve = |name: &str| {
        let request = Request { filter: Some(name.into()), ..Request::default() };
        request.resolve(&scene.defaults, Naming::Flags).map(|job| job.options.filter).map_err(|e| e.to_string())
    };
    assert_eq!(resolve("lanczos(lobes=2)"), Ok(lamplight_core::film::Filter::Lanczos { lobes: 2 }));
    assert_eq!(resolve("mitchell"), Ok(lamplight_core::film::Filter::Mitchell { b: 1.0 / 3.0, c: 1.0 / 3.0 }));
    assert_eq!(
        resolve("lanczos(lobes=0)"),
        Err("--filter: filter \"lanczos(lobes=0)\": lobes must be a whole number from 1 to 32, got 0".into())
    );
    assert_eq!(
        resolve("sinc"),
        Err("--filter must be \"box\", \"tent\", \"gaussian\", \"mitchell\" (B, C), \"catmullrom\" or \"lanczos\" (lobes), got \"sinc\""
            .into())
    );
}

#[test]
fn signed_filters_render_finite_pixels() {
    // Mitchell, Catmull-Rom and Lanczos on the lit sphere: every pixel finite,
    // near the box's on average (the image is smooth but for the sphere's edge).
    let dir = tempfile::tempdir().unwrap();
    let (boxed, _) =
        render(&write(dir.path(), "box.xml", &scene("", "<rfilter type=\"box\"/>")), Request { spp: Some(16), ..Request::default() });
    let mean = |p: &[[f32; 3]]| p.iter().map(|c| (c[0] + c[1] + c[2]) as f64).sum::<f64>() / p.len() as f64;
    for rfilter in ["<rfilter type=\"mitchell\"/>", "<rfilter type=\"catmullrom\"/>", "<rfilter type=\"lanczos\"/>"] {
        let path = write(dir.path(), "s.xml", &scene("", rfilter));
        let (pixels, width) = render(&path, Request { spp: Some(16), ..Request::default() });
        assert_eq!((pixels.len(), width), (16 * 12, 16));
        assert!(pixels.iter().flatten().all(|c| c.is_finite()), "{rfilter}");
        assert!((mean(&pixels) / mean(&boxed) - 1.0).abs() < 0.05, "{rfilter}: {} vs {}", mean(&pixels), mean(&boxed));
    }
}

#[test]
fn a_crop_window_is_the_full_films_pixels() {
    let crop = r#"<integer name="crop_offset_x" value="3"/><integer name="crop_offset_y" value="2"/><integer name="crop_width" value="9"/><rfilter type="box"/>"#;
    let (t, _) = table(&scene("", crop));
    assert_eq!(numbers(get(&t, "render", "crop")), [3.0, 2.0, 9.0, 10.0], "the height defaults to the rest of the film");
    let dir = tempfile::tempdir().unwrap();
    let full = write(dir.path(), "full.xml", &scene("", "<rfilter type=\"box\"/>"));
    let cropped = write(dir.path(), "crop.xml", &scene("", crop));
    let (all, w) = render(&full, Request::default());
    let (part, pw) = render(&cropped, Request::default());
    assert_eq!((w, pw, part.len()), (16, 9, 90));
    for (k, p) in part.iter().enumerate() {
        let (x, y) = (3 + k % 9, 2 + k / 9);
        assert_eq!(*p, all[y * 16 + x], "pixel ({x}, {y}): the box filter never leaves its pixel, so the crop changes nothing");
    }
    // A window of a cropped film is in the full film's pixels, inside the crop.
    let (window, ww) = render(&cropped, Request { window: Some((4, 3, 2, 2)), ..Request::default() });
    assert_eq!((ww, window), (2, vec![all[3 * 16 + 4], all[3 * 16 + 5], all[4 * 16 + 4], all[4 * 16 + 5]]));
    let scene_req = SceneRequest::resolve(cropped.to_str().unwrap()).unwrap();
    let outside = Request { window: Some((0, 0, 4, 4)), ..Request::default() }.resolve(&scene_req.defaults, Naming::Flags);
    assert_eq!(
        outside.unwrap_err().to_string(),
        "--window (x0=0, y0=0, width=4, height=4) must be non-empty and inside the scene's crop (x0=3, y0=2, width=9, height=10)"
    );
    let resized = Request { width: Some(32), ..Request::default() }.resolve(&scene_req.defaults, Naming::Flags);
    assert_eq!(
        resized.unwrap_err().to_string(),
        "the scene crops its 16x12 image to (x0=3, y0=2, width=9, height=10); --width and --height must keep that size (or remove [render] crop)"
    );
}

#[test]
fn a_gaussian_crop_is_cut_at_the_crops_edges() {
    // Under a constant sky every sample sees the same radiance, so every pixel,
    // at the crop's edges too, is that radiance whatever the filter's cut: the
    // weights of each pixel's samples average 1.
    let dir = tempfile::tempdir().unwrap();
    let sky = write(
        dir.path(),
        "sky.xml",
        &scene("", r#"<integer name="crop_offset_x" value="5"/><integer name="crop_width" value="4"/><rfilter type="gaussian"/>"#)
            .replace(r#"<shape type="sphere"><point name="center" value="0, 0.5, 0"/><float name="radius" value="0.5"/><bsdf type="diffuse"/></shape>"#, "")
            .replace(r#"value="4"/></sampler>"#, r#"value="256"/></sampler>"#),
    );
    let (pixels, w) = render(&sky, Request::default());
    assert_eq!((w, pixels.len()), (4, 48));
    for p in &pixels {
        for (c, want) in p.iter().zip([0.5f32, 0.6, 0.7]) {
            assert!((c - want).abs() < 0.02 * want, "{p:?}");
        }
    }
}

#[test]
fn crop_windows_out_of_the_film_are_errors_at_their_place() {
    let at = |film: &str| error("s.xml", &scene("", film));
    assert_eq!(
        at(r#"<integer name="crop_offset_x" value="-1"/>"#),
        "s.xml:7:136: film \"hdrfilm\": crop_offset_x: must be at least 0, got -1"
    );
    assert_eq!(
        at(r#"<integer name="crop_offset_y" value="4"/><integer name="crop_height" value="9"/>"#),
        "s.xml:7:175: film \"hdrfilm\": crop_height: the crop window (0, 4) + 16 x 9 must have a size >= 1 and lie inside the 16 x 12 film"
    );
    assert_eq!(
        at(r#"<integer name="crop_width" value="0"/>"#),
        "s.xml:7:133: film \"hdrfilm\": crop_width: the crop window (0, 0) + 0 x 12 must have a size >= 1 and lie inside the 16 x 12 film"
    );
    let toml = |crop: &str| {
        error(
            "s.toml",
            &format!("[render]\nwidth = 16\nheight = 12\ncrop = {crop}\n\n[camera]\neye = [0, 0, 5]\nlook_at = [0, 0, 0]\nvfov = 40\n"),
        )
    };
    assert_eq!(
        toml("[0, 0, 17, 4]"),
        "s.toml:4:8: render: crop: [0, 0, 17, 4] must have x, y >= 0, width, height >= 1 and lie inside the 16x12 image"
    );
    assert_eq!(
        toml("[-2, 0, 4, 4]"),
        "s.toml:4:8: render: crop: [-2, 0, 4, 4] must have x, y >= 0, width, height >= 1 and lie inside the 16x12 image"
    );
    assert_eq!(toml("[0, 0, 4]"), "s.toml:4:8: render: crop: expected [x, y, width, height] (four whole numbers), got an array of 3");
}

#[test]
fn principal_point_offsets_become_lens_shifts() {
    // 16 x 12: x in widths (16 / 16 of the larger side), y in heights, down
    // (12 / 16 of the larger side, up): [0.25, -0.2 * 0.75].
    let offsets = r#"<float name="principal_point_offset_x" value="0.25"/><float name="principal_point_offset_y" value="0.2"/>"#;
    let (t, warnings) = table(&scene(offsets, ""));
    let shift = numbers(get(&t, "camera", "shift"));
    assert!((shift[0] - 0.25).abs() < 1e-15 && (shift[1] + 0.15).abs() < 1e-15, "{shift:?}");
    assert!(warnings.is_empty(), "{warnings:?}");
    // thinlens: the same shift, and a warning that Mitsuba itself rejects it.
    let thin = scene(offsets, "")
        .replace("type=\"perspective\"", "type=\"thinlens\"")
        .replace("<float name=\"fov\" value=\"45\"/>", "<float name=\"fov\" value=\"45\"/><float name=\"focus_distance\" value=\"5\"/>");
    let (t, warnings) = table(&thin);
    assert_eq!(get(&t, "camera", "type"), &Value::String("thin_lens".into()));
    assert_eq!(numbers(get(&t, "camera", "shift")).len(), 2);
    assert_eq!(
        warnings,
        ["s.xml:4:125: sensor \"thinlens\": principal_point_offset is read as a lens shift (Mitsuba 3.9's thinlens rejects it as unreferenced)"]
    );
    // Zero offsets write no shift; bad values are errors at the value.
    let (t, _) = table(&scene(r#"<float name="principal_point_offset_x" value="0"/>"#, ""));
    let Value::Table(camera) = &t.get("camera").unwrap().item.value else { panic!() };
    assert!(camera.get("shift").is_none());
    assert_eq!(
        error("s.xml", &scene(r#"<float name="principal_point_offset_y" value="1e9"/>"#, "")),
        "s.xml:4:85: sensor \"perspective\": principal_point_offset_y: expected a finite number of at most 100 in magnitude, got 1000000000"
    );
    let ortho =
        scene(r#"<float name="principal_point_offset_x" value="0.1"/>"#, "").replace("type=\"perspective\"", "type=\"orthographic\"");
    assert_eq!(error("s.xml", &ortho), "s.xml:4:85: sensor \"orthographic\": principal_point_offset is not supported, expected 0");
}

#[test]
fn a_shifted_mirrored_camera_moves_its_window_center() {
    let offsets = r#"<float name="principal_point_offset_x" value="0.25"/>"#;
    let mirrored = scene(offsets, "").replace("<lookat", "<scale x=\"-1\"/><lookat");
    let (t, _) = table(&mirrored);
    let plain = scene("", "").replace("<lookat", "<scale x=\"-1\"/><lookat");
    let (p, _) = table(&plain);
    let (c, c0) = (numbers(get(&t, "camera", "window_center")), numbers(get(&p, "camera", "window_center")));
    let right = numbers(get(&p, "camera", "right"));
    // A quarter of the width is half the half-width vector `right`, twice.
    for k in 0..3 {
        assert!((c[k] - c0[k] - 0.5 * right[k]).abs() < 1e-12, "{c:?} {c0:?} {right:?}");
    }
}

#[test]
fn toml_shift_errors_name_the_key() {
    let toml = |shift: &str| {
        error(
            "s.toml",
            &format!("[render]\nwidth = 16\nheight = 12\n\n[camera]\neye = [0, 0, 5]\nlook_at = [0, 0, 0]\nvfov = 40\nshift = {shift}\n"),
        )
    };
    assert_eq!(toml("[0.1]"), "s.toml:9:9: camera: shift: expected [a, b], got an array of 1");
    assert_eq!(toml("[nan, 0]"), "s.toml:9:9: camera: shift: must be finite numbers, got [NaN, 0.0]");
    assert_eq!(toml("[200, 0]"), "s.toml:9:9: camera: invalid shift: must be two finite numbers of at most 100 in magnitude, got [200, 0]");
}
