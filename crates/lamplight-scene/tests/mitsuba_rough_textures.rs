//! Issue 26's last BSDF items, read from Mitsuba XML: a textured `alpha`
//! (`alpha_u`, `alpha_v`) of `roughconductor` and `roughdielectric` and a
//! textured `eta` of `principledthin`, each a texture slot evaluated per hit
//! as Mitsuba's `eval_1` (a uniform texture renders the bytes of the constant);
//! and what Mitsuba's `normalmap` keeps of the unmapped surface (its side, and
//! its shadowing term), checked against the integral it should give.

use std::io::Cursor;
use std::path::Path;

use lamplight_core::bsdfs::Lobe;
use lamplight_core::materials::{bsdf_for, Material, Model, ShadingPoint};
use lamplight_core::math::Vec3;
use lamplight_core::shapes::SurfaceCoords;
use lamplight_core::RenderControl;
use lamplight_scene::request::{Naming, Request, SceneRequest};

use crate::common::mitsuba_xml::{error as xml_error, one_sphere as xml, read};

/// The lobes of `m` with its textures evaluated at lamplight's `uv`.
fn lobes_at(m: &Material, uv: [f64; 2]) -> Vec<Lobe> {
    let at = ShadingPoint::with_coords(Vec3::ZERO, &SurfaceCoords::new(uv, Vec3::X, Vec3::Y));
    bsdf_for(&m.at(&at), Vec3::ZERO, true).lobes().to_vec()
}

fn slot_names(m: &Material) -> Vec<&'static str> {
    m.textures.as_deref().unwrap_or_default().iter().map(|(slot, _)| slot.name()).collect()
}

/// A checkerboard texture named `name` of the two numbers.
fn checker(name: &str, c0: f64, c1: f64) -> String {
    format!(
        r#"<texture type="checkerboard" name="{name}"><float name="color0" value="{c0}"/><float name="color1" value="{c1}"/></texture>"#
    )
}

// Mitsuba's checkerboard `eval_1` (what its BSDFs read for a number) gives
// `color1` at its uv (0.25, 0.25) and `color0` at (0.75, 0.25) (measured in
// Mitsuba 3.9.1); lamplight's v is 1 - Mitsuba's.
const CELL1: [f64; 2] = [0.25, 0.75];
const CELL0: [f64; 2] = [0.75, 0.75];

#[test]
fn a_textured_alpha_is_the_roughness_slot_read_per_hit_as_mitsubas_eval_1() {
    let (s, warnings) = read(&xml(&format!(
        r#"<bsdf type="roughconductor"><string name="distribution" value="ggx"/>{}</bsdf>"#,
        checker("alpha", 0.04, 0.45)
    )));
    assert!(warnings.is_empty(), "{warnings:?}");
    let m = &s.materials[s.objects[0].material];
    assert_eq!(slot_names(m), ["roughness"]);
    for (uv, alpha) in [(CELL1, 0.45), (CELL0, 0.04)] {
        let [Lobe::RoughConductor(c)] = lobes_at(m, uv)[..] else { panic!("{:?}", lobes_at(m, uv)) };
        assert_eq!((c.alpha, c.alpha_v), (alpha, alpha), "{uv:?}");
    }
    // Both anisotropic roughnesses as textures (Mitsuba's carbon-fibre example).
    let (s, warnings) =
        read(&xml(&format!(r#"<bsdf type="roughconductor">{}{}</bsdf>"#, checker("alpha_u", 0.05, 0.4), checker("alpha_v", 0.4, 0.05))));
    assert!(warnings.is_empty(), "{warnings:?}");
    let m = &s.materials[s.objects[0].material];
    assert_eq!(slot_names(m), ["roughness", "roughness_v"]);
    for (uv, u, v) in [(CELL1, 0.4, 0.05), (CELL0, 0.05, 0.4)] {
        let [Lobe::RoughConductor(c)] = lobes_at(m, uv)[..] else { panic!() };
        assert_eq!((c.alpha, c.alpha_v), (u, v), "{uv:?}");
    }
    // One textured, one a number: the number stays.
    let (s, _) =
        read(&xml(&format!(r#"<bsdf type="roughdielectric">{}<float name="alpha_v" value="0.3"/></bsdf>"#, checker("alpha_u", 0.1, 0.2))));
    let m = &s.materials[s.objects[0].material];
    let [Lobe::RoughGlass(g)] = lobes_at(m, CELL0)[..] else { panic!("{:?}", lobes_at(m, CELL0)) };
    assert_eq!((g.alpha, g.alpha_v), (0.1, 0.3));
}

#[test]
fn roughplastic_keeps_its_error_for_a_textured_alpha() {
    let bsdf = format!(r#"<bsdf type="roughplastic">{}</bsdf>"#, checker("alpha", 0.1, 0.2));
    assert_eq!(xml_error(&xml(&bsdf)), "s.xml:3:52: bsdf \"roughplastic\": alpha: a texture here is not supported, expected a number");
}

#[test]
fn a_textured_thin_eta_is_a_slot_read_per_hit() {
    let (s, warnings) =
        read(&xml(&format!(r#"<bsdf type="principledthin"><float name="spec_trans" value="0.7"/>{}</bsdf>"#, checker("eta", 1.1, 2.2))));
    assert!(warnings.is_empty(), "{warnings:?}");
    let m = &s.materials[s.objects[0].material];
    assert_eq!(slot_names(m), ["principled_thin.eta"]);
    let Some(Model::PrincipledThin(built)) = &m.model else { panic!() };
    assert_eq!(built.eta, 1.5, "the constant field keeps the default until a hit evaluates the texture");
    for (uv, eta) in [(CELL1, 2.2), (CELL0, 1.1)] {
        let here = m.at(&ShadingPoint::with_coords(Vec3::ZERO, &SurfaceCoords::new(uv, Vec3::X, Vec3::Y)));
        let Some(Model::PrincipledThin(p)) = &here.model else { panic!() };
        assert_eq!((p.eta, p.spec_trans), (eta, 0.7), "{uv:?}");
    }
}

/// A sphere with `bsdf` under a point light and a grey sky, path-traced: the
/// sRGB bytes.
fn render_sphere(dir: &Path, name: &str, bsdf: &str) -> Vec<u8> {
    let text = format!(
        r#"<scene version="3.0.0">
    <integrator type="path"><integer name="max_depth" value="4"/></integrator>
    <sensor type="perspective"><float name="fov" value="35"/>
        <transform name="to_world"><lookat origin="0, 0, 4" target="0, 0, 0" up="0, 1, 0"/></transform>
        <sampler type="independent"><integer name="sample_count" value="8"/></sampler>
        <film type="hdrfilm"><integer name="width" value="24"/><integer name="height" value="24"/></film>
    </sensor>
    <emitter type="constant"><rgb name="radiance" value="0.3, 0.35, 0.4"/></emitter>
    <emitter type="point"><point name="position" value="2, 2, 3"/><rgb name="intensity" value="30, 30, 30"/></emitter>
    <shape type="sphere">{bsdf}</shape>
</scene>
"#
    );
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    let scene = SceneRequest::resolve(path.to_str().unwrap()).unwrap();
    let job = Request { threads: Some(2), ..Request::default() }.resolve(&scene.defaults, Naming::Flags).unwrap();
    job.run(&scene.build().unwrap(), &RenderControl::default()).unwrap().image.to_srgb8()
}

#[test]
fn a_uniform_texture_renders_the_bytes_of_its_constant() {
    let dir = tempfile::tempdir().unwrap();
    let conductor = |alpha: &str| format!(r#"<bsdf type="roughconductor"><string name="material" value="Au"/>{alpha}</bsdf>"#);
    let constant = render_sphere(dir.path(), "a.xml", &conductor(r#"<float name="alpha" value="0.25"/>"#));
    let textured = render_sphere(dir.path(), "b.xml", &conductor(&checker("alpha", 0.25, 0.25)));
    assert!(constant.iter().any(|&b| b > 30), "the sphere is lit");
    assert_eq!(constant, textured, "a uniform alpha texture");
    // And the textured one differs from another constant: the slot is read.
    let other = render_sphere(dir.path(), "c.xml", &conductor(&checker("alpha", 0.05, 0.05)));
    assert_ne!(constant, other);
    let thin = |eta: &str| format!(r#"<bsdf type="principledthin"><float name="spec_trans" value="0.6"/>{eta}</bsdf>"#);
    let constant = render_sphere(dir.path(), "d.xml", &thin(r#"<float name="eta" value="1.33"/>"#));
    assert_eq!(constant, render_sphere(dir.path(), "e.xml", &thin(&checker("eta", 1.33, 1.33))), "a uniform eta texture");
    assert_ne!(constant, render_sphere(dir.path(), "f.xml", &thin(&checker("eta", 2.0, 2.0))));
}

#[test]
fn normalmap_and_bumpmap_take_mitsubas_shadowing_term_unless_it_is_off() {
    let png = normal_png([191, 128, 238]);
    for (bsdf, on) in [
        (r#"<bsdf type="normalmap">MAP<bsdf type="diffuse"/></bsdf>"#, true),
        (r#"<bsdf type="normalmap"><boolean name="use_shadowing_function" value="false"/>MAP<bsdf type="diffuse"/></bsdf>"#, false),
        (r#"<bsdf type="normalmap"><boolean name="flip_invalid_normals" value="false"/>MAP<bsdf type="diffuse"/></bsdf>"#, true),
        (r#"<bsdf type="bumpmap"><texture type="checkerboard"/><bsdf type="diffuse"/></bsdf>"#, true),
        (
            r#"<bsdf type="bumpmap"><boolean name="use_shadowing_function" value="false"/><texture type="checkerboard"/><bsdf type="diffuse"/></bsdf>"#,
            false,
        ),
    ] {
        let map = r#"<texture type="bitmap" name="normalmap"><string name="filename" value="n.png"/></texture>"#;
        let dir = tempfile::tempdir().unwrap();
        std::fs::write(dir.path().join("n.png"), &png).unwrap();
        let path = dir.path().join("s.xml");
        std::fs::write(&path, xml(&bsdf.replace("MAP", map))).unwrap();
        let built = SceneRequest::resolve(path.to_str().unwrap()).unwrap().build().unwrap();
        assert_eq!(built.materials[built.objects[0].material].map_shadowing, on, "{bsdf}");
    }
}

/// A 1 x 1 PNG of the normal map texel `rgb`.
fn normal_png(rgb: [u8; 3]) -> Vec<u8> {
    let mut out = Cursor::new(Vec::new());
    image::DynamicImage::ImageRgb8(image::RgbImage::from_pixel(1, 1, image::Rgb(rgb))).write_to(&mut out, image::ImageFormat::Png).unwrap();
    out.into_inner()
}

/// The mean of a diffuse floor (albedo 0.8) whose normal map tilts every normal
/// by the same angle, under a sky of radiance 1 from every direction, direct
/// light only, seen from above: lamplight's image, Mitsuba's rules.
fn tilted_floor(shadowing: bool) -> f64 {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("n.png"), normal_png([191, 128, 238])).unwrap();
    let text = format!(
        r#"<scene version="3.0.0">
    <integrator type="path"><integer name="max_depth" value="2"/></integrator>
    <sensor type="perspective"><float name="fov" value="20"/>
        <transform name="to_world"><lookat origin="0, 0, 4" target="0, 0, 0" up="0, 1, 0"/></transform>
        <sampler type="independent"><integer name="sample_count" value="256"/></sampler>
        <film type="hdrfilm"><integer name="width" value="8"/><integer name="height" value="8"/><rfilter type="box"/></film>
    </sensor>
    <emitter type="constant"><rgb name="radiance" value="1, 1, 1"/></emitter>
    <shape type="rectangle"><transform name="to_world"><scale value="3"/></transform>
        <bsdf type="normalmap"><boolean name="use_shadowing_function" value="{shadowing}"/>
            <texture type="bitmap" name="normalmap"><string name="filename" value="n.png"/><boolean name="raw" value="true"/></texture>
            <bsdf type="diffuse"><rgb name="reflectance" value="0.8, 0.8, 0.8"/></bsdf>
        </bsdf>
    </shape>
</scene>
"#
    );
    let path = dir.path().join("floor.xml");
    std::fs::write(&path, text).unwrap();
    let scene = SceneRequest::resolve(path.to_str().unwrap()).unwrap();
    let job = Request { threads: Some(2), ..Request::default() }.resolve(&scene.defaults, Naming::Flags).unwrap();
    let image = job.run(&scene.build().unwrap(), &RenderControl::default()).unwrap().image;
    image.pixels.iter().map(|p| p.iter().map(|&c| c as f64).sum::<f64>() / 3.0).sum::<f64>() / image.pixels.len() as f64
}

/// `(albedo / pi) integral of cos' G` over the directions above both the floor
/// (`z`) and the mapped normal `n`, by the midpoint rule on the upper hemisphere.
fn expected_floor(n: Vec3, shadowing: bool) -> f64 {
    let tan2 = |c: f64| (1.0 - c * c) / (c * c);
    let a2 = if shadowing { (0.125 * tan2(n.z)).min(1.0) } else { 0.0 };
    let (rows, cols) = (400, 800);
    let (dt, dp) = (std::f64::consts::FRAC_PI_2 / rows as f64, 2.0 * std::f64::consts::PI / cols as f64);
    let mut sum = 0.0;
    for i in 0..rows {
        let theta = (i as f64 + 0.5) * dt;
        let g = 2.0 / (1.0 + (1.0 + a2 * theta.tan().powi(2)).sqrt());
        for j in 0..cols {
            let phi = (j as f64 + 0.5) * dp;
            let w = Vec3::new(theta.sin() * phi.cos(), theta.sin() * phi.sin(), theta.cos());
            sum += n.dot(w).max(0.0) * g * theta.sin() * dt * dp;
        }
    }
    0.8 / std::f64::consts::PI * sum
}

#[test]
fn a_tilted_normal_sees_no_light_from_below_the_floor_and_is_shadowed_as_mitsubas() {
    // The texel (191, 128, 238) read linearly: n = normalize(2 c - 1), about 30 degrees off.
    let n = Vec3::new(2.0 * 191.0 / 255.0 - 1.0, 2.0 * 128.0 / 255.0 - 1.0, 2.0 * 238.0 / 255.0 - 1.0).normalize();
    let side_only = expected_floor(n, false);
    // The lune of the mapped hemisphere below the floor is cut off: (1 + cos) / 2 of the albedo.
    assert!((side_only - 0.8 * (1.0 + n.z) / 2.0).abs() < 1e-4, "{side_only}");
    for (shadowing, expected) in [(false, side_only), (true, expected_floor(n, true))] {
        let got = tilted_floor(shadowing);
        assert!((got - expected).abs() < 0.01 * expected, "shadowing {shadowing}: {got} vs {expected}");
    }
    // Both differ from the albedo (the whole mapped hemisphere) by more than the tolerance.
    assert!(expected_floor(n, true) < side_only - 0.03 && side_only < 0.8 - 0.03);
}
