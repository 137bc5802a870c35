//! `<spectrum>` values as Mitsuba's RGB variants (`scalar_rgb`) see them.
//!
//! - `value="v"`: a reflectance of `v` (grey); inside an `<emitter>`, a flat
//!   (equal-energy) spectrum of `v`, which is not white in sRGB: `v (1.2049, 0.9482, 0.9093)`.
//! - `value="l1:v1, l2:v2, ..."` (nm, increasing): the piecewise linear spectrum
//!   `s(l)`, zero outside `[l1, ln]`, integrated against the CIE 1931 matching
//!   functions on 1000 evenly spaced wavelengths `l_i` of `[360, 830]` nm:
//!   `XYZ = (470 / 1000) N sum_i xyz(l_i) s(l_i) w(l_i)` with `N = 1 / int y`,
//!   where a reflectance is weighted by the D65 illuminant (`w = D65`, so a flat 1
//!   is white to 0.1 %) and emission is not (`w = 1`); then linear sRGB
//!   by the XYZ to sRGB (D65) matrix, a reflectance clamped to `[0, 1]`, emission to `>= 0`.
//! - `filename="f.spd"`: the same, with the pairs read from lines `l v`.

use lamplight_core::math::Rgb;
use lamplight_core::params::{Loc, ParamError};

use super::cie_tables::{CIE_Y_NORMALIZATION, TABLE};
use super::properties::parse_float;
use super::xml::El;

/// Most wavelength:value pairs of one spectrum.
pub const MAX_PAIRS: usize = 1 << 16;
const CIE_MIN: f64 = 360.0;
const CIE_MAX: f64 = 830.0;
const STEPS: usize = 1000;

fn err(loc: &Loc, message: impl Into<String>) -> ParamError {
    ParamError { loc: loc.clone(), message: message.into() }
}

/// The RGB colour of a `<spectrum>` element; `emission` when it sits in an emitter.
pub fn spectrum(el: &El, loc: &Loc, emission: bool) -> Result<Rgb, ParamError> {
    if let Some(f) = el.attr("filename") {
        let text = std::fs::read_to_string(&f.value).map_err(|e| err(&f.loc, format!("spectrum: cannot read \"{}\": {e}", f.value)))?;
        let text: String = text.lines().filter(|l| !l.trim_start().starts_with('#')).collect::<Vec<_>>().join(",");
        let pairs = text.split(',').map(|l| l.split_whitespace().collect::<Vec<_>>().join(":")).collect::<Vec<_>>().join(",");
        return list(&pairs, &f.loc, emission);
    }
    let v = el.require("value")?;
    if v.value.contains(':') {
        list(&v.value, loc, emission)
    } else {
        let g = parse_float(&v.value, loc)?;
        Ok(if emission { flat_emission() * g } else { Rgb::splat(g) })
    }
}

/// `l:v` pairs, comma separated, to RGB.
fn list(text: &str, loc: &Loc, emission: bool) -> Result<Rgb, ParamError> {
    let mut pairs: Vec<(f64, f64)> = Vec::new();
    for item in text.split(',').map(str::trim).filter(|s| !s.is_empty()) {
        if pairs.len() >= MAX_PAIRS {
            return Err(err(loc, format!("spectrum: more than {MAX_PAIRS} wavelength:value pairs")));
        }
        let (l, v) = item.split_once(':').ok_or_else(|| err(loc, format!("spectrum: expected wavelength:value pairs, got \"{item}\"")))?;
        let (l, v) = (parse_float(l, loc)?, parse_float(v, loc)?);
        if pairs.last().is_some_and(|&(p, _)| l <= p) {
            return Err(err(loc, format!("spectrum: wavelengths must increase, got {l} after {}", pairs.last().map_or(0.0, |p| p.0))));
        }
        pairs.push((l, v));
    }
    if pairs.is_empty() {
        return Err(err(loc, "spectrum: expected wavelength:value pairs, got none"));
    }
    Ok(to_srgb(&pairs, !emission))
}

/// A flat spectrum of 1 as emission, in linear sRGB.
pub fn flat_emission() -> Rgb {
    to_srgb(&[(CIE_MIN, 1.0), (CIE_MAX, 1.0)], false)
}

/// The CIE table at `l` nm, linearly interpolated.
fn cie(l: f64) -> [f64; 4] {
    let t = (l - CIE_MIN).clamp(0.0, CIE_MAX - CIE_MIN);
    let i = (t.floor() as usize).min(TABLE.len() - 2);
    let f = t - i as f64;
    let (a, b) = (TABLE[i], TABLE[i + 1]);
    std::array::from_fn(|k| a[k] * (1.0 - f) + b[k] * f)
}

/// `pairs` (increasing wavelengths) to linear sRGB: a reflectance (`reflectance`:
/// D65-weighted and clamped to [0, 1]) or emission.
pub fn to_srgb(pairs: &[(f64, f64)], reflectance: bool) -> Rgb {
    let (first, last) = (pairs[0].0, pairs[pairs.len() - 1].0);
    let mut xyz = [0.0f64; 3];
    let mut j = 0;
    for i in 0..STEPS {
        let l = CIE_MIN + (i as f64 / (STEPS - 1) as f64) * (CIE_MAX - CIE_MIN);
        if l < first || l > last {
            continue;
        }
        while j + 2 < pairs.len() && pairs[j + 1].0 < l {
            j += 1;
        }
        let value = if pairs.len() == 1 {
            pairs[0].1
        } else {
            let (a, b) = (pairs[j], pairs[j + 1]);
            let f = ((l - a.0) / (b.0 - a.0)).clamp(0.0, 1.0);
            a.1 * (1.0 - f) + b.1 * f
        };
        let c = cie(l);
        let w = if reflectance { c[3] } else { 1.0 };
        for k in 0..3 {
            xyz[k] += c[k] * value * w;
        }
    }
    let norm = (CIE_MAX - CIE_MIN) / STEPS as f64 * CIE_Y_NORMALIZATION;
    let [x, y, z] = xyz.map(|v| v * norm);
    let rgb = Rgb::new(
        3.240479 * x - 1.537150 * y - 0.498535 * z,
        -0.969256 * x + 1.875991 * y + 0.041556 * z,
        0.055648 * x - 0.204043 * y + 1.057311 * z,
    );
    if reflectance {
        rgb.clamp(Rgb::ZERO, Rgb::ONE)
    } else {
        rgb.max(Rgb::ZERO)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Values printed by Mitsuba 3.9.1 `scalar_rgb` (`mi.traverse` of a diffuse
    /// BSDF's and a point light's `<spectrum>`), see `bench/mitsuba_cie_tables.py`.
    #[test]
    fn spectra_match_mitsuba_scalar_rgb() {
        let close = |a: Rgb, b: [f64; 3]| (a - Rgb::from_array(b)).abs().max_element() < 2e-4;
        type Case<'a> = (&'a [(f64, f64)], [f64; 3], [f64; 3]);
        let cases: [Case<'_>; 3] = [
            (&[(400.0, 0.5), (700.0, 0.5)], [0.497671, 0.499878, 0.497455], [0.599847, 0.47476, 0.451722]),
            (&[(500.0, 0.2), (600.0, 0.8)], [0.278771, 0.471364, 0.0], [0.31516, 0.461331, 0.0]),
            (&[(450.0, 0.1), (550.0, 0.9), (650.0, 0.3)], [0.463591, 0.792942, 0.0661394], [0.558847, 0.761361, 0.0460629]),
        ];
        for (pairs, reflectance, emission) in cases {
            assert!(close(to_srgb(pairs, true), reflectance), "{pairs:?}: {}", to_srgb(pairs, true));
            assert!(close(to_srgb(pairs, false), emission), "{pairs:?}: {}", to_srgb(pairs, false));
        }
        assert!(close(flat_emission(), [1.20488, 0.948229, 0.909267]), "{}", flat_emission());
    }
}
