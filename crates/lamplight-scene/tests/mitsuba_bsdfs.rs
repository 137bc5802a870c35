//! Mitsuba's coated and thin BSDFs and the Beckmann distribution, read from XML and
//! from the TOML kinds they map to: the lobes the path tracer gets, with Mitsuba's
//! parameters and defaults, and the exact errors of bad input.

use std::path::Path;

use lamplight_core::bsdfs::{Distribution, Lobe};
use lamplight_core::materials::{bsdf_for, Model};
use lamplight_core::math::Vec3;
use lamplight_core::Scene;

use crate::common::mitsuba_xml::{error, one_sphere as xml, read};

fn lobes(s: &Scene) -> Vec<Lobe> {
    bsdf_for(&s.materials[s.objects[0].material], Vec3::ZERO, true).lobes().to_vec()
}

#[test]
fn plastic_reads_with_mitsubas_indices_and_defaults() {
    let (s, warnings) = read(&xml(
        r#"<bsdf type="plastic"><rgb name="diffuse_reflectance" value="0.1, 0.27, 0.36"/><float name="int_ior" value="1.9"/><boolean name="nonlinear" value="true"/></bsdf>"#,
    ));
    assert!(warnings.is_empty(), "{warnings:?}");
    let m = &s.materials[s.objects[0].material];
    let Some(Model::Plastic(c)) = &m.model else { panic!("{:?}", m.model) };
    assert!((c.eta - 1.9 / 1.00028).abs() < 1e-12 && c.nonlinear && c.rough.is_none());
    // Mitsuba's sampling weight: mean(ks) / (mean(d) + mean(ks)).
    assert!((c.specular_weight - 1.0 / (1.0 + 0.73 / 3.0)).abs() < 1e-12);
    assert!(matches!(lobes(&s)[..], [Lobe::Plastic(_)]));
    // Defaults: polypropylene in air.
    let (s, _) = read(&xml(r#"<bsdf type="plastic"/>"#));
    let Some(Model::Plastic(c)) = &s.materials[s.objects[0].material].model else { panic!() };
    assert!((c.eta - 1.49 / 1.00028).abs() < 1e-12 && !c.nonlinear);
}

#[test]
fn roughplastic_defaults_to_beckmann_of_alpha_one_tenth() {
    let (s, warnings) = read(&xml(r#"<bsdf type="roughplastic"><string name="int_ior" value="bk7"/></bsdf>"#));
    assert!(warnings.is_empty(), "{warnings:?}");
    let Some(Model::Plastic(c)) = &s.materials[s.objects[0].material].model else { panic!() };
    let (m, _) = c.rough.expect("rough");
    assert_eq!((m.distribution, m.alpha_u), (Distribution::Beckmann, 0.1));
    assert!((c.eta - 1.5046 / 1.00028).abs() < 1e-12);
    assert!(matches!(lobes(&s)[..], [Lobe::RoughPlastic(_)]));
    let (s, _) =
        read(&xml(r#"<bsdf type="roughplastic"><string name="distribution" value="ggx"/><float name="alpha" value="0.3"/></bsdf>"#));
    let Some(Model::Plastic(c)) = &s.materials[s.objects[0].material].model else { panic!() };
    assert_eq!(c.rough.map(|(m, _)| (m.distribution, m.alpha_u)), Some((Distribution::Ggx, 0.3)));
}

#[test]
fn beckmann_reaches_rough_metal_and_glass_without_a_warning() {
    let (s, warnings) = read(&xml(r#"<bsdf type="roughconductor"><float name="alpha" value="0.2"/></bsdf>"#));
    assert!(warnings.is_empty(), "{warnings:?}");
    assert!(
        matches!(lobes(&s)[..], [Lobe::RoughConductor(m)] if m.alpha == 0.2 && m.distribution == Distribution::Beckmann),
        "{:?}",
        lobes(&s)
    );
    let (s, _) = read(&xml(r#"<bsdf type="roughdielectric"><string name="distribution" value="ggx"/></bsdf>"#));
    assert!(matches!(lobes(&s)[..], [Lobe::RoughGlass(g)] if g.distribution == Distribution::Ggx), "{:?}", lobes(&s));
    let (s, _) = read(&xml(r#"<bsdf type="roughdielectric"/>"#));
    assert!(matches!(lobes(&s)[..], [Lobe::RoughGlass(g)] if g.distribution == Distribution::Beckmann), "{:?}", lobes(&s));
}

#[test]
fn thindielectric_is_a_thin_sheet_of_bk7() {
    let (s, warnings) = read(&xml(r#"<bsdf type="thindielectric"/>"#));
    assert!(warnings.is_empty(), "{warnings:?}");
    assert!(matches!(lobes(&s)[..], [Lobe::ThinGlass(t)] if (t.eta - 1.5046 / 1.00028).abs() < 1e-12), "{:?}", lobes(&s));
    // Both faces see the same sheet.
    let back = bsdf_for(&s.materials[s.objects[0].material], Vec3::ZERO, false);
    assert_eq!(back.lobes(), &lobes(&s)[..]);
}

#[test]
fn bad_coatings_give_their_exact_errors() {
    let cases = [
        (
            r#"<bsdf type="roughplastic"><float name="int_ior" value="1.2"/><float name="ext_ior" value="1.2"/></bsdf>"#,
            "s.xml:3:81: bsdf \"roughplastic\": int_ior and ext_ior must differ",
        ),
        (
            r#"<bsdf type="roughplastic"><string name="distribution" value="phong"/></bsdf>"#,
            "s.xml:3:87: bsdf \"roughplastic\": distribution: expected beckmann or ggx, got \"phong\"",
        ),
        (
            r#"<bsdf type="plastic"><texture type="checkerboard" name="specular_reflectance"/></bsdf>"#,
            "s.xml:3:47: bsdf \"plastic\": specular_reflectance: a texture here is not supported",
        ),
        (
            r#"<bsdf type="thindielectric"><string name="int_ior" value="unobtainium"/></bsdf>"#,
            "s.xml:3:84: bsdf \"thindielectric\": int_ior: unknown material \"unobtainium\" (expected a number or vacuum, helium, \
             hydrogen, air, carbon dioxide, water, acetone, ethanol, carbon tetrachloride, glycerol, benzene, silicone oil, bromine, \
             water ice, fused quartz, pyrex, acrylic glass, polypropylene, bk7, sodium chloride, amber, pet, diamond)",
        ),
    ];
    for (bsdf, expected) in cases {
        assert_eq!(error(&xml(bsdf)), expected);
    }
}

#[test]
fn toml_kinds_check_their_numbers() {
    let camera = "[camera]\neye = [0, 0, 5]\nlook_at = [0, 0, 0]\nvfov = 40\n";
    let sphere = "[[objects]]\ntype = \"sphere\"\ncenter = [0, 0, 0]\nradius = 1\nmaterial = \"m\"\n";
    let build = |material: &str| {
        let text = format!("{camera}[materials.m]\n{material}\n{sphere}");
        match lamplight_scene::instantiate::SceneFile::parse(Path::new("t.toml"), &text) {
            Ok(f) => f.build().map_err(|e| e.to_string()),
            Err(e) => Err(e.to_string()),
        }
    };
    let s = build("type = \"plastic\"\nroughness = 0.2\ndistribution = \"beckmann\"\ndiffuse_reflectance = [0.2, 0.4, 0.6]").unwrap();
    assert!(matches!(lobes(&s)[..], [Lobe::RoughPlastic(_)]));
    let s = build("type = \"thin_dielectric\"\nint_ior = 1.33").unwrap();
    assert!(matches!(lobes(&s)[..], [Lobe::ThinGlass(t)] if (t.eta - 1.33 / 1.00028).abs() < 1e-12));
    let s = build("reflection = { type = \"conductor\", metal = \"gold\" }\nkd = 0\nroughness = 0.3\ndistribution = \"beckmann\"").unwrap();
    assert!(matches!(lobes(&s)[..], [Lobe::RoughConductor(m)] if m.distribution == Distribution::Beckmann));
    for (material, expected) in [
        ("type = \"plastic\"\nspecular_reflectance = 2", "specular_reflectance: must be between 0 and 1"),
        ("type = \"plastic\"\nroughness = 1.5", "roughness: must be between 0 and 1, got 1.5"),
        ("type = \"plastic\"\ndistribution = \"phong\"", "distribution: unknown value \"phong\""),
        ("type = \"thin_dielectric\"\nint_ior = -1", "int_ior: must be a positive number, got -1"),
    ] {
        let e = build(material).unwrap_err();
        assert!(e.contains(expected), "{material}: {e}");
    }
}

#[test]
fn blendbsdf_reads_as_a_blend_of_its_two_nested_bsdfs() {
    let (s, warnings) =
        read(&xml(r#"<bsdf type="blendbsdf"><float name="weight" value="0.3"/><bsdf type="diffuse"/><bsdf type="conductor"/></bsdf>"#));
    assert!(warnings.is_empty(), "{warnings:?}");
    let m = &s.materials[s.objects[0].material];
    let blend = m.blend.as_ref().expect("a blend");
    assert_eq!(blend.weight, lamplight_core::materials::Texture::Constant(lamplight_core::math::Rgb::splat(0.3)));
    // Mitsuba's diffuse and conductor are one-sided, each component on its own.
    assert!(blend.a.one_sided && blend.b.one_sided && !m.one_sided);
    assert!(blend.a.kd != lamplight_core::math::Rgb::ZERO && blend.b.kd == lamplight_core::math::Rgb::ZERO);
    // Inside a twosided both scatter on both sides; a <ref> is read in place; a texture weight is read.
    let (s, _) = read(
        r#"<scene version="3.0.0">
    <sensor type="perspective"><film type="hdrfilm"><integer name="width" value="8"/><integer name="height" value="8"/></film></sensor>
    <bsdf type="diffuse" id="red"><rgb name="reflectance" value="0.5, 0, 0"/></bsdf>
    <shape type="sphere"><bsdf type="twosided"><bsdf type="blendbsdf">
        <texture type="checkerboard" name="weight"><float name="color0" value="0"/><float name="color1" value="1"/></texture>
        <ref id="red"/><bsdf type="roughconductor"/></bsdf></bsdf></shape>
</scene>
"#,
    );
    let blend = s.materials[s.objects[0].material].blend.clone().expect("a blend");
    assert!(!blend.a.one_sided && !blend.b.one_sided);
    // Mitsuba's checkerboard eval_1 (a weight) gives color1 where eval gives color0.
    let lamplight_core::materials::Texture::UvChecker(c) = &blend.weight else { panic!("{:?}", blend.weight) };
    assert_eq!((c.even, c.odd), (lamplight_core::math::Rgb::ONE, lamplight_core::math::Rgb::ZERO));
    assert_eq!(blend.a.color, lamplight_core::materials::Texture::Constant(lamplight_core::math::Rgb::new(0.5, 0.0, 0.0)));
    assert_eq!(
        error(&xml(r#"<bsdf type="blendbsdf"><bsdf type="diffuse"/></bsdf>"#)),
        "s.xml:3:26: bsdf \"blendbsdf\": needs two nested BSDFs, got 1"
    );
}
