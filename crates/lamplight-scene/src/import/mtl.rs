//! MTL (Wavefront material library) reader and its mapping onto lamplight's
//! [`Material`].
//!
//! MTL's model is the lecture's: `Ka`, `Kd`, `Ks` colours, a Phong exponent
//! `Ns`, emission `Ke`, transparency `d` (or `Tr = 1 - d`), index `Ni`, and an
//! illumination model `illum` that switches mirror and glass on. The mapping:
//!
//! | MTL | lamplight |
//! |---|---|
//! | `Kd` | `kd = Kd`, `color = 1` (so `kd * C = Kd` exactly) |
//! | `Ka` | `ka = Ka`; when absent `ka = 0.1 Kd` (lamplight's default ambient share) |
//! | `Ks`, `Ns` | `ks = Ks`, `shininess = Ns` (used as the Blinn exponent as is) |
//! | `Ke` | `emission = Ke` |
//! | `illum 0, 1` | `ks = 0` (no highlight) |
//! | `illum 2` (default) | as read |
//! | `illum 3, 8` | adds a mirror: `Reflection::Constant(Ks)` |
//! | `illum 5` | adds a Fresnel mirror: `Reflection::Dielectric { ior: Ni, 0, 1 }` |
//! | `illum 4, 6, 7, 9` | glass: `Material::glass(Ni, Ks, Ns)` (`Ni` absent: 1.5) with `Kd`, `Ka` kept |
//! | `d < 1` otherwise | see-through: `Refraction::Constant { ior: Ni or 1, weight: 1 - d }`, `kd`, `ka` scaled by `d`, shadows pass `1 - d` |
//!
//! | `map_Kd FILE` | `color` = the image (sRGB), so `kd * C = Kd x map_Kd` |
//! | `map_Ka FILE` | `ka` = `Ka x` the image (sRGB): the Whitted ambient term `ka C La` |
//! | `decal FILE` (with `map_Kd`) | the colour is `(1 - d) Kd + d map_Kd`, `d` the image's first channel (linear): `color` = a `mix` texture, `kd = 1`, `ka` default 0.1 |
//! | `map_Ks FILE` | `ks` = `Ks x` the image (sRGB) |
//! | `map_Ns FILE` | `shininess` = `Ns x` the image's first channel (linear) |
//! | `norm FILE` (with `-bm s`) | a tangent-space normal map of scale `s` |
//! | `map_d FILE` | a cut-out where the image's first channel (linear) is below 0.5 |
//! | `bump FILE`, `map_Bump FILE` (with `-bm s`) | a bump map ([`lamplight_core::materials::bump`]): height = the image's first channel (linear), displacement `s` x height |
//!
//! The PBR extension keys (Exocortex's, as Blender and tinyobjloader write
//! them) make the material a `pbr` one ([`lamplight_core::materials::pbr`]):
//!
//! | MTL | lamplight `pbr` |
//! |---|---|
//! | `Kd` x `map_Kd` | `base_color` |
//! | `Pm` x `map_Pm` (first channel, linear) | `metallic` (default 0) |
//! | `Pr` x `map_Pr` (first channel, linear) | perceptual `roughness` (default 0.5) |
//! | `Ke`, `norm`, `bump`, `map_d` | emission, normal map, bump map, cut-out, as above |
//!
//! `Ka`, `Ks`, `Ns`, `map_Ks`, `map_Ns`, `illum`, `d` and `Ni` do not apply to it.
//!
//! `Tr` follows the specification (`Tr = 1 - d`); whichever of `d`/`Tr` comes
//! last wins. A map statement's options (`-s`, `-o`, `-bm`, `-clamp`, ...) are
//! read past (`-bm` is the normal or bump map's scale, `-clamp on` its wrap mode) and
//! its file is found beside the `.mtl`; a file that cannot be read is reported
//! as a warning naming it and its line, and the material is kept without it.
//! Map keywords are matched without regard to case (`map_bump`, `Bump` are
//! `map_Bump`). What has no meaning in lamplight is reported once per keyword
//! as a warning at its first `FILE:LINE:COL`, and skipped: `disp` (lamplight
//! does not displace geometry; `bump` turns the shading normal), `refl`
//! (reflections are traced, not read from a map), a `decal` in a material
//! without `map_Kd` (nothing to blend in), and every other statement.

use std::collections::HashMap;
use std::path::Path;

use std::sync::Arc;

use lamplight_core::materials::alpha::AlphaMask;
use lamplight_core::materials::image::{Channel, Filter, Wrap};
use lamplight_core::materials::{
    BumpMap, ImageData, ImageTexture, Material, NormalMap, Reflection, Refraction, Slot, Texture, UvTransform,
};
use lamplight_core::math::Rgb;

use super::{number, words, Warnings};
use crate::error::LoadError;

/// The values of one `newmtl` block as read.
#[derive(Clone, Debug, Default)]
struct MtlValues {
    ka: Option<Rgb>,
    kd: Option<Rgb>,
    ks: Option<Rgb>,
    ke: Option<Rgb>,
    ns: Option<f64>,
    ni: Option<f64>,
    dissolve: Option<f64>,
    illum: Option<i64>,
    map_kd: Option<Texture>,
    map_ka: Option<Texture>,
    /// The decal mask and where its statement is (for the warning when there is no `map_Kd` to blend in).
    decal: Option<(Texture, usize, usize)>,
    map_ks: Option<Texture>,
    map_ns: Option<Texture>,
    norm: Option<NormalMap>,
    bump: Option<BumpMap>,
    map_d: Option<Texture>,
    pr: Option<f64>,
    pm: Option<f64>,
    map_pr: Option<Texture>,
    map_pm: Option<Texture>,
}

/// A map statement's file and options: `(file, -bm value, -clamp on)`.
fn map_statement(words: &[(usize, &str)]) -> Option<(String, f64, bool)> {
    let mut i = 1;
    let (mut bm, mut clamp) = (1.0, false);
    while i < words.len() && words[i].1.starts_with('-') && words[i].1.len() > 1 && words[i].1.parse::<f64>().is_err() {
        let option = words[i].1;
        // The numbers that follow an option are its arguments (up to three for -o, -s, -t).
        let args = match option {
            "-o" | "-s" | "-t" => words[i + 1..].iter().take(3).take_while(|w| w.1.parse::<f64>().is_ok()).count().max(1),
            "-mm" => 2,
            _ => 1,
        };
        match option {
            "-bm" => bm = words.get(i + 1).and_then(|w| w.1.parse().ok()).unwrap_or(1.0),
            "-clamp" => clamp = words.get(i + 1).is_some_and(|w| w.1 == "on"),
            _ => {}
        }
        i += 1 + args;
    }
    let file = words.get(i..)?.iter().map(|w| w.1).collect::<Vec<_>>().join(" ");
    (!file.is_empty()).then_some((file, bm, clamp))
}

/// Reads a material library into lamplight materials by name.
/// Every image it reads is added to `sources` (once per file and colour space).
pub(super) fn parse(
    path: &Path,
    text: &str,
    warnings: &mut Warnings,
    sources: &mut Vec<super::ImageSource>,
) -> Result<HashMap<String, Material>, LoadError> {
    let mut done = HashMap::new();
    let mut images: HashMap<(String, bool), Arc<ImageData>> = HashMap::new();
    let mut current: Option<(String, MtlValues)> = None;
    let mut ignored = std::collections::HashSet::new();
    for (line_index, raw) in text.lines().enumerate() {
        let line_no = line_index + 1;
        let line = raw.split('#').next().unwrap_or("");
        let w = words(line);
        let Some(&(_, keyword)) = w.first() else { continue };
        // Map keywords in any case; the bump map's two names as one.
        let written = keyword;
        let keyword = match keyword.to_ascii_lowercase().as_str() {
            "map_kd" => "map_Kd",
            "map_ka" => "map_Ka",
            "map_ks" => "map_Ks",
            "map_ns" => "map_Ns",
            "map_d" => "map_d",
            "norm" => "norm",
            "bump" | "map_bump" => "map_Bump",
            "map_pr" => "map_Pr",
            "map_pm" => "map_Pm",
            _ => keyword,
        };
        if keyword == "newmtl" {
            if let Some((name, values)) = current.take() {
                done.insert(name, to_material(&values, path, warnings));
            }
            let name = line.trim_start()["newmtl".len()..].trim();
            if name.is_empty() {
                return Err(LoadError::at(path, line_no, w[0].0 + 6, "expected a material name after `newmtl`"));
            }
            current = Some((name.to_string(), MtlValues::default()));
            continue;
        }
        let is_map = keyword.starts_with("map_") || matches!(keyword, "bump" | "disp" | "decal" | "refl" | "norm");
        let read_map =
            matches!(keyword, "map_Kd" | "map_Ka" | "map_Ks" | "map_Ns" | "norm" | "map_d" | "map_Bump" | "map_Pr" | "map_Pm" | "decal");
        if read_map {
            let Some((_, values)) = current.as_mut() else {
                return Err(LoadError::at(path, line_no, w[0].0, format!("`{written}` before any `newmtl`")));
            };
            let Some((file, bm, clamp)) = map_statement(&w) else {
                let end = line.trim_end().chars().count() + 1;
                return Err(LoadError::at(path, line_no, end, format!("expected a file name after `{written}`")));
            };
            let srgb = matches!(keyword, "map_Kd" | "map_Ka" | "map_Ks");
            let key = (file.clone(), srgb);
            let image = match images.get(&key) {
                Some(i) => Some(i.clone()),
                None => match crate::texture_files::read_texture(&path.parent().unwrap_or(Path::new("")).join(&file), srgb) {
                    Ok(i) => {
                        let i = Arc::new(i);
                        images.insert(key, i.clone());
                        let origin = super::ImageOrigin::File(path.parent().unwrap_or(Path::new("")).join(&file));
                        sources.push(super::ImageSource { data: i.clone(), srgb, origin });
                        Some(i)
                    }
                    Err(e) => {
                        warnings.once(format!("{}:{line_no}:{}: MTL {written} ignored: {e}", path.display(), w[0].0));
                        None
                    }
                },
            };
            if let Some(image) = image {
                let channel = if matches!(keyword, "map_Ns" | "map_d" | "map_Bump" | "map_Pr" | "map_Pm" | "decal") {
                    Channel::One(0)
                } else {
                    Channel::Rgb
                };
                let wrap = if clamp { Wrap::Clamp } else { Wrap::Repeat };
                let texture = Texture::Image(Arc::new(ImageTexture {
                    image,
                    wrap,
                    filter: Filter::Bilinear,
                    transform: UvTransform::IDENTITY,
                    channel,
                }));
                match keyword {
                    "map_Kd" => values.map_kd = Some(texture),
                    "map_Ka" => values.map_ka = Some(texture),
                    "decal" => values.decal = Some((texture, line_no, w[0].0)),
                    "map_Ks" => values.map_ks = Some(texture),
                    "map_Ns" => values.map_ns = Some(texture),
                    "map_d" => values.map_d = Some(texture),
                    "map_Bump" => values.bump = Some(BumpMap { texture, scale: bm }),
                    "map_Pr" => values.map_pr = Some(texture),
                    "map_Pm" => values.map_pm = Some(texture),
                    _ => values.norm = Some(NormalMap { texture, scale: bm }),
                }
            }
            continue;
        }
        let known = matches!(keyword, "Ka" | "Kd" | "Ks" | "Ke" | "Ns" | "Ni" | "d" | "Tr" | "illum" | "Pr" | "Pm");
        if !known {
            let why = match keyword {
                "disp" => "lamplight does not displace geometry; a bump map (`bump`) turns the shading normal instead",
                "refl" => "reflections are traced, not looked up in a map (`illum 3` mirrors with `Ks`)",
                _ if is_map => "only map_Kd, map_Ka, map_Ks, map_Ns, map_d, bump/map_Bump, norm, decal, map_Pr and map_Pm maps are read",
                _ => "not an MTL statement lamplight reads",
            };
            // Once per keyword, at its first place.
            if ignored.insert(keyword.to_string()) {
                warnings.once(format!("{}:{line_no}:{}: MTL `{keyword}` ignored: {why}", path.display(), w[0].0));
            }
            continue;
        }
        let Some((_, values)) = current.as_mut() else {
            return Err(LoadError::at(path, line_no, w[0].0, format!("`{keyword}` before any `newmtl`")));
        };
        let num = |i: usize, what: &str| number(path, line_no, line, &w, i, what);
        let rgb = |what: &str| -> Result<Rgb, LoadError> {
            let r = num(1, what)?;
            // `Kd r` alone means grey, as in the specification.
            let (g, b) = if w.len() == 2 { (r, r) } else { (num(2, what)?, num(3, what)?) };
            let c = Rgb::new(r, g, b);
            if c.min_element() < 0.0 {
                return Err(LoadError::at(path, line_no, w[1].0, format!("expected non-negative {what}, found {c}")));
            }
            Ok(c)
        };
        match keyword {
            "Ka" => values.ka = Some(rgb("Ka colour")?),
            "Kd" => values.kd = Some(rgb("Kd colour")?),
            "Ks" => values.ks = Some(rgb("Ks colour")?),
            "Ke" => values.ke = Some(rgb("Ke colour")?),
            "Ns" => values.ns = Some(num(1, "Ns exponent")?.max(0.0)),
            "Pr" | "Pm" => {
                let v = num(1, if keyword == "Pr" { "Pr roughness" } else { "Pm metallic" })?;
                if !(0.0..=1.0).contains(&v) {
                    return Err(LoadError::at(path, line_no, w[1].0, format!("expected a value in [0, 1], found {v}")));
                }
                *(if keyword == "Pr" { &mut values.pr } else { &mut values.pm }) = Some(v);
            }
            "Ni" => {
                let ni = num(1, "Ni index of refraction")?;
                if !(ni > 0.0) {
                    return Err(LoadError::at(path, line_no, w[1].0, format!("expected a positive index of refraction, found {ni}")));
                }
                values.ni = Some(ni);
            }
            "d" | "Tr" => {
                // `d -halo f` is a variant of `d`; its factor is the last word.
                let v = num(w.len() - 1, "transparency")?;
                if !(0.0..=1.0).contains(&v) {
                    return Err(LoadError::at(path, line_no, w[w.len() - 1].0, format!("expected a value in [0, 1], found {v}")));
                }
                values.dissolve = Some(if keyword == "d" { v } else { 1.0 - v });
            }
            _ => {
                let v = num(1, "illumination model")?;
                if !(v.fract() == 0.0 && (0.0..=10.0).contains(&v)) {
                    return Err(LoadError::at(path, line_no, w[1].0, format!("expected an illumination model 0..10, found {v}")));
                }
                if v == 10.0 {
                    warnings.once("MTL illum 10 (shadow matte) read as illum 2".to_string());
                }
                values.illum = Some(v as i64);
            }
        }
    }
    if let Some((name, values)) = current.take() {
        done.insert(name, to_material(&values, path, warnings));
    }
    Ok(done)
}

/// The PBR extension's mapping (module doc), when the block uses its keys.
fn to_pbr(v: &MtlValues) -> Option<Material> {
    if v.pr.is_none() && v.pm.is_none() && v.map_pr.is_none() && v.map_pm.is_none() {
        return None;
    }
    let kd = v.kd.unwrap_or(Rgb::splat(0.8));
    let base = match &v.map_kd {
        None => Texture::Constant(kd),
        Some(t) if kd == Rgb::ONE => t.clone(),
        Some(t) => Texture::Scale(Arc::new([t.clone(), Texture::Constant(kd)])),
    };
    let (metallic, roughness) = (v.pm.unwrap_or(0.0), v.pr.unwrap_or(0.5));
    let mut maps = Vec::new();
    for (slot, map, factor) in [(lamplight_core::materials::pbr::METALLIC, &v.map_pm, metallic), (Slot::ROUGHNESS, &v.map_pr, roughness)] {
        if let Some(t) = map {
            maps.push((slot, Texture::Scale(Arc::new([t.clone(), Texture::Constant(Rgb::splat(factor))]))));
        }
    }
    let mut m = lamplight_core::materials::pbr::material(base, metallic, roughness, v.ke.unwrap_or(Rgb::ZERO), maps);
    m.normal_map = v.norm.clone().map(Arc::new);
    m.bump = v.bump.clone().map(Arc::new);
    m.alpha = v.map_d.clone().map(|texture| Arc::new(AlphaMask::mask(texture, 0.5)));
    Some(m)
}

/// The mapping of the module doc; a decal without a `map_Kd` to blend in is a warning.
fn to_material(v: &MtlValues, path: &Path, warnings: &mut Warnings) -> Material {
    if let (Some((_, line, column)), None) = (&v.decal, &v.map_kd) {
        warnings.once(format!("{}:{line}:{column}: MTL `decal` ignored: it blends in map_Kd, which the material lacks", path.display()));
    }
    if let Some(m) = to_pbr(v) {
        return m;
    }
    let kd = v.kd.unwrap_or(Rgb::splat(0.8));
    let ka = v.ka.unwrap_or(0.1 * kd);
    let ks = v.ks.unwrap_or(Rgb::ZERO);
    let ns = v.ns.unwrap_or(1.0);
    let illum = v.illum.unwrap_or(2);
    let mut m = Material {
        color: Texture::Constant(Rgb::ONE),
        ka,
        kd,
        ks: if illum <= 1 { Rgb::ZERO } else { ks },
        shininess: ns,
        emission: v.ke.unwrap_or(Rgb::ZERO),
        normal_map: v.norm.clone().map(Arc::new),
        bump: v.bump.clone().map(Arc::new),
        alpha: v.map_d.clone().map(|texture| Arc::new(AlphaMask::mask(texture, 0.5))),
        ..Material::default()
    };
    if let Some(t) = &v.map_kd {
        m.color = t.clone();
    }
    let scaled = |t: &Texture, by: Rgb| Texture::Scale(Arc::new([t.clone(), Texture::Constant(by)]));
    let mut maps = Vec::new();
    // decal d: the colour becomes (1 - d) Kd + d map_Kd, with kd = 1 (and ka's default 0.1) carrying no Kd twice.
    if let (Some((decal, _, _)), Some(t)) = (&v.decal, &v.map_kd) {
        m.color = Texture::Mix(Arc::new([Texture::Constant(kd), t.clone(), decal.clone()]));
        m.kd = Rgb::ONE;
        m.ka = v.ka.unwrap_or(Rgb::splat(0.1));
    }
    // map_Ka x Ka, and the dissolve's factor on ka, which the map replaces.
    if let Some(t) = &v.map_ka {
        let d = v.dissolve.filter(|&d| d < 1.0 && !matches!(illum, 4 | 6 | 7 | 9)).unwrap_or(1.0);
        maps.push((Slot::KA, scaled(t, m.ka * d)));
    }
    if let (Some(t), true) = (&v.map_ks, illum > 1) {
        maps.push((Slot::KS, scaled(t, ks)));
    }
    if let Some(t) = &v.map_ns {
        maps.push((Slot::SHININESS, scaled(t, Rgb::splat(ns))));
    }
    if !maps.is_empty() {
        m.textures = Some(maps.into());
    }
    match illum {
        3 | 8 => m.reflection = Reflection::Constant(ks),
        5 => m.reflection = Reflection::Dielectric { ior: v.ni.unwrap_or(1.5), min: 0.0, max: 1.0 },
        4 | 6 | 7 | 9 => {
            let glass = Material::glass(v.ni.unwrap_or(1.5), ks.max_element(), ns);
            return Material { ka: v.ka.unwrap_or(Rgb::ZERO), kd: v.kd.unwrap_or(Rgb::ZERO), emission: m.emission, ks, ..glass };
        }
        _ => {}
    }
    if let Some(d) = v.dissolve.filter(|&d| d < 1.0) {
        m.refraction = Refraction::Constant { ior: v.ni.unwrap_or(1.0), weight: Rgb::splat(1.0 - d) };
        m.kd *= d;
        m.ka *= d;
        m.shadow_transmittance = Rgb::splat(1.0 - d);
    }
    m
}

#[cfg(test)]
mod tests {
    use super::*;

    fn one(text: &str) -> Material {
        let mut w = Warnings::default();
        parse(Path::new("t.mtl"), text, &mut w, &mut Vec::new()).unwrap().remove("m").unwrap()
    }

    #[test]
    fn plastic_maps_exactly() {
        let m = one("newmtl m\nKa 0.1 0.2 0.3\nKd 0.5 0.6 0.7\nKs 0.2\nNs 40\n");
        assert_eq!((m.ka, m.kd, m.ks, m.shininess), (Rgb::new(0.1, 0.2, 0.3), Rgb::new(0.5, 0.6, 0.7), Rgb::splat(0.2), 40.0));
        assert_eq!(m.color, Texture::Constant(Rgb::ONE));
        assert_eq!(m.reflection, Reflection::None);
    }

    #[test]
    fn illum_switches_mirror_and_glass() {
        assert_eq!(one("newmtl m\nKs 0.9\nillum 3\n").reflection, Reflection::Constant(Rgb::splat(0.9)));
        assert_eq!(one("newmtl m\nKs 0.9\nillum 1\n").ks, Rgb::ZERO);
        let glass = one("newmtl m\nNi 1.33\nillum 7\n");
        assert_eq!(glass.refraction, Refraction::Fresnel { ior: 1.33 });
        assert_eq!(glass.shadow_transmittance, Rgb::ONE);
    }

    #[test]
    fn map_statements_read_their_file_past_the_options() {
        let w = words("map_Kd -s 2 2 1 -o 0.5 -clamp on my texture.png");
        assert_eq!(map_statement(&w), Some(("my texture.png".to_string(), 1.0, true)));
        assert_eq!(map_statement(&words("norm -bm 0.5 n.png")), Some(("n.png".to_string(), 0.5, false)));
        assert_eq!(map_statement(&words("map_Kd")), None);
    }

    #[test]
    fn texture_maps_drive_the_colour_and_a_missing_file_is_a_warning() {
        let dir = tempfile::tempdir().unwrap();
        image::RgbImage::from_pixel(1, 1, image::Rgb([255, 0, 0])).save(dir.path().join("red.png")).unwrap();
        let mut w = Warnings::default();
        let text =
            "newmtl m\nKd 0.5\nmap_Kd -s 1 1 red.png\nnorm -bm 2 red.png\nmap_Ks missing.png\n  disp b.png\nmap_bump -bm 0.25 red.png\n\
                    disp c.png\nrefl -type sphere r.png\nmap_Ka red.png\ndecal red.png\nnewmtl n\ndecal red.png\n";
        let m = parse(&dir.path().join("t.mtl"), text, &mut w, &mut Vec::new()).unwrap().remove("m").unwrap();
        assert!(matches!(m.color, Texture::Mix(_)));
        assert_eq!(m.normal_map.as_ref().map(|n| n.scale), Some(2.0));
        assert_eq!(m.bump.as_ref().map(|b| b.scale), Some(0.25));
        let warnings: Vec<String> = w.into_vec().iter().map(|w| w.replace(&format!("{}/", dir.path().display()), "")).collect();
        assert!(
            warnings[0].starts_with("t.mtl:5:1: MTL map_Ks ignored: cannot read texture") && warnings[0].contains("missing.png"),
            "{warnings:?}"
        );
        // disp and refl once each, at their first place; a decal with nothing to blend in.
        assert_eq!(
            warnings[1..],
            [
                "t.mtl:6:3: MTL `disp` ignored: lamplight does not displace geometry; a bump map (`bump`) turns the shading normal instead",
                "t.mtl:9:1: MTL `refl` ignored: reflections are traced, not looked up in a map (`illum 3` mirrors with `Ks`)",
                "t.mtl:13:1: MTL `decal` ignored: it blends in map_Kd, which the material lacks",
            ]
        );
        // map_Ka drives ka (times Ka, default 0.1 once the decal takes Kd into the colour); the decal blends Kd and map_Kd.
        let slots: Vec<_> = m.textures.as_ref().unwrap().iter().map(|(s, _)| *s).collect();
        assert_eq!(slots, [Slot::KA]);
        assert_eq!((m.kd, m.ka), (Rgb::ONE, Rgb::splat(0.1)));
        let red_at = |m: &Material| m.at(&lamplight_core::materials::ShadingPoint::at(lamplight_core::math::Vec3::ZERO)).into_owned();
        // The 1x1 red decal is 1 in its first channel: the colour is map_Kd's red, ka 0.1 x red.
        let shaded = red_at(&m);
        assert_eq!((shaded.color.constant(), shaded.ka), (Some(Rgb::new(1.0, 0.0, 0.0)), Rgb::new(0.1, 0.0, 0.0)));
    }

    #[test]
    fn dissolve_and_tr_are_complements() {
        let a = one("newmtl m\nKd 1\nd 0.25\n");
        let b = one("newmtl m\nKd 1\nTr 0.75\n");
        assert_eq!(a, b);
        assert_eq!(a.refraction, Refraction::Constant { ior: 1.0, weight: Rgb::splat(0.75) });
        assert_eq!(a.kd, Rgb::splat(0.25));
    }

    #[test]
    fn the_pbr_extension_makes_a_metallic_roughness_material() {
        let m = one("newmtl m\nKd 1 0.5 0.25\nPr 0.3\nPm 1\n");
        let pbr = m.pbr.as_ref().expect("a pbr material");
        assert_eq!((pbr.metallic, m.roughness, m.color.constant()), (1.0, 0.3, Some(Rgb::new(1.0, 0.5, 0.25))));
        // A metal's lecture terms: no diffuse, ks = the base colour.
        assert_eq!((m.kd, m.ks), (Rgb::ZERO, Rgb::new(1.0, 0.5, 0.25)));
        let plain = one("newmtl m\nKd 0.5\nPr 0.7\n");
        assert_eq!((plain.pbr.as_ref().map(|p| p.metallic), plain.roughness), (Some(0.0), 0.7));
        assert!(one("newmtl m\nKd 0.5\n").pbr.is_none());
        let mut w = Warnings::default();
        let e = parse(Path::new("t.mtl"), "newmtl m\nPm 2\n", &mut w, &mut Vec::new()).unwrap_err().to_string();
        assert_eq!(e, "t.mtl:2:4: expected a value in [0, 1], found 2");
    }
}
