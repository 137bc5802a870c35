//! Mitsuba's `principled` BSDF, read from XML as lamplight's `principled`
//! material: every parameter with Mitsuba's defaults, the lobe the path tracer
//! gets, and the exact errors of bad input.

use lamplight_core::bsdfs::principled::{eta_from_specular, PrincipledParams};
use lamplight_core::bsdfs::Lobe;
use lamplight_core::materials::{bsdf_for, Model, Texture};
use lamplight_core::math::{Rgb, Vec3};
use lamplight_core::Scene;

use crate::common::mitsuba_xml::{error, one_sphere as xml, read};

fn params(s: &Scene) -> PrincipledParams {
    match &s.materials[s.objects[0].material].model {
        Some(Model::Principled(p)) => *p,
        other => panic!("{other:?}"),
    }
}

#[test]
fn defaults_are_mitsubas_and_there_is_no_warning() {
    let (s, warnings) = read(&xml(r#"<bsdf type="principled"/>"#));
    assert!(warnings.is_empty(), "{warnings:?}");
    assert_eq!(params(&s), PrincipledParams::default());
    assert_eq!((params(&s).roughness, params(&s).eta), (0.5, 1.5));
    let m = &s.materials[s.objects[0].material];
    assert_eq!(m.color, Texture::Constant(Rgb::splat(0.5)));
    assert!(!m.one_sided, "Mitsuba's principled tells its sides apart itself");
    assert!(matches!(bsdf_for(m, Vec3::ZERO, true).lobes(), [Lobe::Principled(_)]));
}

#[test]
fn every_parameter_reaches_the_lobe() {
    let (s, warnings) =
        read(&xml(r#"<bsdf type="principled"><rgb name="base_color" value="0.2, 0.5, 0.7"/><float name="roughness" value="0.3"/>
        <float name="metallic" value="0.25"/><float name="spec_trans" value="0.4"/><float name="specular" value="0.3"/>
        <float name="spec_tint" value="0.1"/><float name="sheen" value="0.6"/><float name="sheen_tint" value="0.7"/>
        <float name="clearcoat" value="0.8"/><float name="clearcoat_gloss" value="0.9"/><float name="anisotropic" value="0"/>
        <float name="diffuse_reflectance_sampling_rate" value="0.5"/><float name="main_specular_sampling_rate" value="2"/>
        <float name="clearcoat_sampling_rate" value="0.25"/></bsdf>"#));
    assert!(warnings.is_empty(), "{warnings:?}");
    let expected = PrincipledParams {
        roughness: 0.3,
        anisotropic: 0.0,
        metallic: 0.25,
        spec_trans: 0.4,
        eta: eta_from_specular(0.3),
        spec_tint: 0.1,
        sheen: 0.6,
        sheen_tint: 0.7,
        clearcoat: 0.8,
        clearcoat_gloss: 0.9,
        flatness: 0.0,
        diffuse_rate: 0.5,
        specular_rate: 2.0,
        clearcoat_rate: 0.25,
    };
    assert_eq!(params(&s), expected);
    assert_eq!(s.materials[s.objects[0].material].color, Texture::Constant(Rgb::new(0.2, 0.5, 0.7)));
}

#[test]
fn transmission_moves_an_index_of_one_off_the_boundary() {
    // As Mitsuba: with spec_trans, eta 1 becomes 1.001 and specular 0 becomes 0.001.
    let (s, _) = read(&xml(r#"<bsdf type="principled"><float name="spec_trans" value="0.5"/><float name="eta" value="1"/></bsdf>"#));
    assert_eq!(params(&s).eta, 1.001);
    let (s, _) = read(&xml(r#"<bsdf type="principled"><float name="spec_trans" value="0.5"/><float name="specular" value="0"/></bsdf>"#));
    assert_eq!(params(&s).eta, eta_from_specular(1e-3));
    let (s, _) = read(&xml(r#"<bsdf type="principled"><float name="spec_trans" value="0"/><float name="eta" value="1"/></bsdf>"#));
    assert_eq!(params(&s).eta, 1.0);
}

#[test]
fn scalars_take_textures() {
    let (s, _) = read(&xml(
        r#"<bsdf type="principled"><texture type="checkerboard" name="roughness"><float name="color0" value="0.1"/><float name="color1" value="0.9"/></texture></bsdf>"#,
    ));
    let m = &s.materials[s.objects[0].material];
    let maps = m.textures.as_ref().expect("a roughness texture");
    assert_eq!(maps.len(), 1);
    let at = |u: f64| {
        let mut p = lamplight_core::materials::ShadingPoint::at(Vec3::ZERO);
        p.uv = [u, 0.25];
        match &m.at(&p).model {
            Some(Model::Principled(p)) => p.roughness,
            other => panic!("{other:?}"),
        }
    };
    // lamplight's (0.25, 0.25) is Mitsuba's uv (0.25, 0.75) (the reader turns v
    // over), where Mitsuba's scalar lookup gives `color0` (0.1) and its colour
    // lookup `color1`: the reader swaps the two for a scalar, as Mitsuba does.
    assert_eq!((at(0.25), at(0.75)), (0.1, 0.9));
}

#[test]
fn bad_principled_parameters_give_their_exact_errors() {
    let cases = [
        (
            r#"<bsdf type="principled"><float name="eta" value="1.4"/><float name="specular" value="0.4"/></bsdf>"#,
            "s.xml:3:26: bsdf \"principled\": give either eta or specular, not both (as Mitsuba)",
        ),
        (
            r#"<bsdf type="principled"><float name="anisotropic" value="1.5"/></bsdf>"#,
            "s.xml:3:83: material \"bsdf_1\": anisotropic: must be between 0 and 1, got 1.5",
        ),
        (
            r#"<bsdf type="principled"><float name="metallic" value="1.5"/></bsdf>"#,
            "s.xml:3:80: material \"bsdf_1\": metallic: must be between 0 and 1, got 1.5",
        ),
        (
            r#"<bsdf type="principled"><rgb name="roughness" value="0.1, 0.2, 0.3"/></bsdf>"#,
            "s.xml:3:79: bsdf \"principled\": roughness: expected a float, got a colour",
        ),
        // Mitsuba's own refusal ("expected float, got object"), not a silent 1.5.
        (
            r#"<bsdf type="principled"><texture type="checkerboard" name="eta"/></bsdf>"#,
            "s.xml:3:50: bsdf \"principled\": eta: expected a float, got a <texture> (Mitsuba takes no texture here)",
        ),
        (
            r#"<bsdf type="principled"><texture type="checkerboard" name="specular"/></bsdf>"#,
            "s.xml:3:50: bsdf \"principled\": specular: expected a float, got a <texture> (Mitsuba takes no texture here)",
        ),
        (
            r#"<bsdf type="principledthin"><float name="diff_trans" value="2.5"/></bsdf>"#,
            "s.xml:3:86: material \"bsdf_1\": diff_trans: must be between 0 and 2, got 2.5",
        ),
    ];
    for (bsdf, expected) in cases {
        assert_eq!(error(&xml(bsdf)), expected);
    }
}

#[test]
fn principledthin_reads_as_the_thin_sheet() {
    use lamplight_core::bsdfs::principled_thin::ThinParams;
    let (s, warnings) =
        read(&xml(r#"<bsdf type="principledthin"><rgb name="base_color" value="0.3, 0.6, 0.2"/><float name="spec_trans" value="0.4"/>
        <float name="diff_trans" value="0.8"/><float name="eta" value="1.4"/><float name="flatness" value="0.2"/>
        <float name="diffuse_transmittance_sampling_rate" value="0.5"/></bsdf>"#));
    assert!(warnings.is_empty(), "{warnings:?}");
    let m = &s.materials[s.objects[0].material];
    let Some(Model::PrincipledThin(p)) = &m.model else { panic!("{:?}", m.model) };
    // Mitsuba halves diff_trans (0 to 2) before using it.
    let expected =
        ThinParams { spec_trans: 0.4, diff_trans: 0.4, eta: 1.4, flatness: 0.2, rates: [1.0, 1.0, 1.0, 0.5], ..ThinParams::default() };
    assert_eq!(*p, expected);
    assert!(!m.one_sided);
    assert!(matches!(bsdf_for(m, Vec3::ZERO, false).lobes(), [Lobe::PrincipledThin(_)]));
}
