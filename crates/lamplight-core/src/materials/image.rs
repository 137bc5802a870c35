//! `image`: a texture read from an image file (PNG, JPEG, BMP, TGA, HDR, EXR),
//! looked up at the surface's `(u, v)`.
//!
//! | parameter | type | default | meaning |
//! |---|---|---|---|
//! | `file` | string | required | the image: absolute, or relative to the scene file's folder |
//! | `color_space` | string | `"srgb"` | `"srgb"`: 8- and 16-bit values are sRGB-encoded colours, decoded to linear; `"linear"`: data (roughness, normals, masks) read as they are. HDR and EXR files are always linear |
//! | `wrap` | string | `"repeat"` | outside `[0, 1]`: `"repeat"`, `"mirror"` or `"clamp"` |
//! | `filter` | string | `"bilinear"` | `"nearest"`, `"bilinear"` or `"trilinear"` (MIP-mapped by the footprint of camera rays) |
//! | `channel` | string | `"rgb"` | `"rgb"`, or one of `"r"`, `"g"`, `"b"`, `"a"` as a grey value |
//! | `uv_scale`, `uv_rotate`, `uv_offset` | `[a, b]`, degrees, `[a, b]` | `[1, 1]`, 0, `[0, 0]` | the UV transform ([`super::uv_transform`]) |
//!
//! Texture space is `(s, t) = T(u, v)` with `(0, 0)` the bottom-left corner of
//! the image and `(1, 1)` the top-right (pbrt's and OBJ's convention; the glTF
//! importer flips its `v`). Texel `(x, y)`, `y = 0` the top row, has its centre
//! at `s = (x + 0.5) / w`, `t = 1 - (y + 0.5) / h`.
//!
//! Filters: nearest takes the texel containing `(s, t)`; bilinear weighs the
//! four texels around it by `(1 - fx)(1 - fy)`, `fx (1 - fy)`, ... (pbrt-v4's
//! `Image::Bilerp`); trilinear blends bilinear lookups in the two MIP levels
//! around `l = log2(width)`, where `width` is the footprint's largest extent
//! in texels of level 0 (`|ds| w` or `|dt| h`; pbrt-v4's `MIPMap::Filter` with
//! `FilterFunction::Bilinear`, for images that need not be square). Level `k + 1` is level `k` box-filtered 2x2 (in
//! linear values; [`super::image_data`] keeps the texels and builds the levels).
//!
//! A file is decoded once per colour space and shared by every texture that
//! names it (the loader, [`ImageLoader`], keeps the cache).

use std::sync::Arc;

pub use super::image_data::{ImageData, Texels};
use super::uv_transform::UvTransform;
use super::{ShadingPoint, Texture, TextureKind, Textures};
use crate::math::Rgb;
use crate::params::{Kind, Param, ParamResult, ParamType as T, Params};

/// Decodes an image file for [`Textures`]: the scene crate's implementation
/// reads it relative to the scene file, through the size checks, and caches it.
pub trait ImageLoader: Sync {
    /// The image `file` decoded (from sRGB when `srgb` and the file is 8- or
    /// 16-bit); the message says what went wrong, naming the file.
    fn load(&self, file: &str, srgb: bool) -> Result<Arc<ImageData>, String>;
}

/// What a lookup outside `[0, 1]` reads.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Wrap {
    /// The image tiles the plane.
    Repeat,
    /// Tiles alternate with their mirror images.
    Mirror,
    /// The border texels extend outwards.
    Clamp,
}

impl Wrap {
    /// Texel index `i` wrapped into `0..n`.
    #[inline]
    fn index(self, i: i64, n: usize) -> usize {
        let n = n as i64;
        (match self {
            Wrap::Repeat => i.rem_euclid(n),
            Wrap::Clamp => i.clamp(0, n - 1),
            Wrap::Mirror => {
                let m = i.rem_euclid(2 * n);
                if m >= n {
                    2 * n - 1 - m
                } else {
                    m
                }
            }
        }) as usize
    }
}

/// How texels are combined.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Filter {
    /// The texel containing the point.
    Nearest,
    /// The four around it, weighted.
    Bilinear,
    /// Bilinear in the two MIP levels of the footprint's size, blended.
    Trilinear,
}

/// Which values a lookup returns.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Channel {
    /// The colour.
    Rgb,
    /// One channel (0 to 3: r, g, b, a) as a grey value.
    One(usize),
}

/// An image placed on a surface: the shared data and how it is looked up.
#[derive(Clone, Debug, PartialEq)]
pub struct ImageTexture {
    /// The decoded image.
    pub image: Arc<ImageData>,
    /// Outside `[0, 1]`.
    pub wrap: Wrap,
    /// Texel filter.
    pub filter: Filter,
    /// `(u, v)` to `(s, t)`.
    pub transform: UvTransform,
    /// What is returned.
    pub channel: Channel,
}

impl ImageTexture {
    /// The image's value at the shading point (module documentation).
    pub fn evaluate(&self, at: &ShadingPoint) -> Rgb {
        let st = self.transform.apply(at.uv);
        // A coordinate that is not finite (a degenerate parametrization) reads the origin.
        let st = if st.iter().all(|x| x.is_finite()) { st } else { [0.0, 0.0] };
        let rgba = match self.filter {
            Filter::Nearest => self.nearest(0, st),
            Filter::Bilinear => self.bilinear(0, st),
            Filter::Trilinear => self.trilinear(st, at),
        };
        match self.channel {
            Channel::Rgb => Rgb::new(rgba[0], rgba[1], rgba[2]),
            Channel::One(c) => Rgb::splat(rgba[c]),
        }
    }

    fn nearest(&self, level: usize, st: [f64; 2]) -> [f64; 4] {
        let l = self.image.level(level);
        let x = (st[0] * l.width as f64).floor();
        let y = ((1.0 - st[1]) * l.height as f64).floor();
        let (x, y) = (self.wrap.index(saturate(x), l.width), self.wrap.index(saturate(y), l.height));
        self.image.read(l, x, y).map(f64::from)
    }

    fn bilinear(&self, level: usize, st: [f64; 2]) -> [f64; 4] {
        let l = self.image.level(level);
        let x = st[0] * l.width as f64 - 0.5;
        let y = (1.0 - st[1]) * l.height as f64 - 0.5;
        let (x0, y0) = (x.floor(), y.floor());
        let (fx, fy) = (x - x0, y - y0);
        let (x0, y0) = (saturate(x0), saturate(y0));
        let xs = [self.wrap.index(x0, l.width), self.wrap.index(x0.saturating_add(1), l.width)];
        let ys = [self.wrap.index(y0, l.height), self.wrap.index(y0.saturating_add(1), l.height)];
        let mut out = [0.0; 4];
        for (j, wy) in [(0, 1.0 - fy), (1, fy)] {
            for (i, wx) in [(0, 1.0 - fx), (1, fx)] {
                let t = self.image.read(l, xs[i], ys[j]);
                for c in 0..4 {
                    out[c] += wx * wy * f64::from(t[c]);
                }
            }
        }
        out
    }

    fn trilinear(&self, st: [f64; 2], at: &ShadingPoint) -> [f64; 4] {
        let (dx, dy) = (self.transform.apply_vector(at.duv_dx), self.transform.apply_vector(at.duv_dy));
        let (w, h) = self.image.size();
        // The footprint in texels of level 0, per axis of the image (it need not be square).
        let texels = |d: [f64; 2]| (d[0] * w as f64).abs().max((d[1] * h as f64).abs());
        let width = texels(dx).max(texels(dy));
        let levels = self.image.level_count();
        let level = width.max(1e-30).log2();
        if !(level > 0.0) {
            return self.bilinear(0, st);
        }
        if level >= (levels - 1) as f64 {
            return self.bilinear(levels - 1, st);
        }
        let below = level.floor() as usize;
        let f = level - below as f64;
        let (a, b) = (self.bilinear(below, st), self.bilinear(below + 1, st));
        std::array::from_fn(|c| a[c] * (1.0 - f) + b[c] * f)
    }
}

/// A texel coordinate as an integer, saturating far outside (and NaN to 0).
#[inline]
fn saturate(x: f64) -> i64 {
    x as i64
}

/// The UV transform keys shared by the texture kinds that read `(u, v)`.
pub const UV_PARAMS: [Param; 3] = [
    Param::new("uv_scale", T::Pair, "[1, 1]", "", "multiplies `(u, v)` first"),
    Param::new("uv_rotate", T::Number, "0", "degrees", "then turns it counter-clockwise"),
    Param::new("uv_offset", T::Pair, "[0, 0]", "", "then adds this"),
];

/// Reads [`UV_PARAMS`].
pub fn read_uv_transform(p: &mut Params<'_>) -> ParamResult<UvTransform> {
    let scale = p.pair("uv_scale")?.unwrap_or([1.0, 1.0]);
    let rotate = p.number_or("uv_rotate", 0.0)?;
    let offset = p.pair("uv_offset")?.unwrap_or([0.0, 0.0]);
    Ok(UvTransform::new(scale, rotate.to_radians(), offset))
}

/// `image`.
pub const KIND: TextureKind = Kind {
    name: "image",
    summary: "an image file (PNG, JPEG, BMP, TGA, HDR, EXR) looked up at the surface's `(u, v)`",
    params: &[
        Param::new("file", T::String, "", "", "the image: an absolute path, or one relative to the scene file's folder"),
        Param::new(
            "color_space",
            T::String,
            "\"srgb\"",
            "",
            "`\"srgb\"` (colours: 8- and 16-bit values decoded from sRGB) or `\"linear\"` (data); HDR and EXR are linear",
        ),
        Param::new("wrap", T::String, "\"repeat\"", "", "outside `[0, 1]`: `\"repeat\"`, `\"mirror\"` or `\"clamp\"`"),
        Param::new(
            "filter",
            T::String,
            "\"bilinear\"",
            "",
            "`\"nearest\"`, `\"bilinear\"` or `\"trilinear\"` (MIP-mapped by the camera rays' footprint)",
        ),
        Param::new("channel", T::String, "\"rgb\"", "", "`\"rgb\"`, or `\"r\"`, `\"g\"`, `\"b\"`, `\"a\"` as a grey value"),
        UV_PARAMS[0],
        UV_PARAMS[1],
        UV_PARAMS[2],
    ],
    build,
};

fn build(p: &mut Params<'_>, textures: &Textures<'_>) -> ParamResult<Texture> {
    let file = p.required_string("file")?;
    let srgb = p.choice("color_space", &["srgb", "linear"])? == "srgb";
    let wrap = match p.choice("wrap", &["repeat", "mirror", "clamp"])? {
        "mirror" => Wrap::Mirror,
        "clamp" => Wrap::Clamp,
        _ => Wrap::Repeat,
    };
    let filter = match p.choice("filter", &["bilinear", "nearest", "trilinear"])? {
        "nearest" => Filter::Nearest,
        "trilinear" => Filter::Trilinear,
        _ => Filter::Bilinear,
    };
    let channel = match p.choice("channel", &["rgb", "r", "g", "b", "a"])? {
        "r" => Channel::One(0),
        "g" => Channel::One(1),
        "b" => Channel::One(2),
        "a" => Channel::One(3),
        _ => Channel::Rgb,
    };
    let transform = read_uv_transform(p)?;
    let Some(loader) = textures.images else {
        return Err(p.key_error("file", "image textures can only be read from a scene file"));
    };
    let image = loader.load(file, srgb).map_err(|m| p.key_error("file", m))?;
    Ok(Texture::Image(Arc::new(ImageTexture { image, wrap, filter, transform, channel })))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// 2 x 2: red, green over blue, white (top row first), 8-bit linear.
    fn two_by_two() -> Arc<ImageData> {
        let texels = vec![[255, 0, 0, 255], [0, 255, 0, 255], [0, 0, 255, 255], [255, 255, 255, 0]];
        Arc::new(ImageData::new(2, 2, Texels::U8(texels), false).unwrap())
    }

    fn texture(filter: Filter, wrap: Wrap) -> ImageTexture {
        ImageTexture { image: two_by_two(), wrap, filter, transform: UvTransform::IDENTITY, channel: Channel::Rgb }
    }

    fn at(u: f64, v: f64) -> ShadingPoint {
        ShadingPoint { uv: [u, v], ..ShadingPoint::at(crate::math::Vec3::ZERO) }
    }

    #[test]
    fn texel_centres_read_back_exactly() {
        for filter in [Filter::Nearest, Filter::Bilinear, Filter::Trilinear] {
            let t = texture(filter, Wrap::Repeat);
            // (s, t) = (0.25, 0.75) is the centre of the top-left texel.
            assert_eq!(t.evaluate(&at(0.25, 0.75)), Rgb::new(1.0, 0.0, 0.0), "{filter:?}");
            assert_eq!(t.evaluate(&at(0.75, 0.75)), Rgb::new(0.0, 1.0, 0.0));
            assert_eq!(t.evaluate(&at(0.25, 0.25)), Rgb::new(0.0, 0.0, 1.0));
            assert_eq!(t.evaluate(&at(0.75, 0.25)), Rgb::ONE);
        }
        // Bilinear halfway between the two top texels.
        let mid = texture(Filter::Bilinear, Wrap::Clamp).evaluate(&at(0.5, 0.75));
        assert!((mid - Rgb::new(0.5, 0.5, 0.0)).length() < 1e-12, "{mid}");
    }

    #[test]
    fn wrap_modes_outside_the_unit_square() {
        // s = 1.25 is the first column again under repeat, the second under mirror and clamp.
        assert_eq!(texture(Filter::Nearest, Wrap::Repeat).evaluate(&at(1.25, 0.75)), Rgb::new(1.0, 0.0, 0.0));
        assert_eq!(texture(Filter::Nearest, Wrap::Mirror).evaluate(&at(1.25, 0.75)), Rgb::new(0.0, 1.0, 0.0));
        assert_eq!(texture(Filter::Nearest, Wrap::Clamp).evaluate(&at(1.25, 0.75)), Rgb::new(0.0, 1.0, 0.0));
        assert_eq!(texture(Filter::Nearest, Wrap::Mirror).evaluate(&at(-0.25, 0.75)), Rgb::new(1.0, 0.0, 0.0));
        assert_eq!(texture(Filter::Nearest, Wrap::Clamp).evaluate(&at(-7.0, -3.0)), Rgb::new(0.0, 0.0, 1.0));
        // Far away and NaN coordinates stay inside the image.
        let t = texture(Filter::Bilinear, Wrap::Repeat);
        assert!(t.evaluate(&at(1e300, -1e300)).is_finite());
        assert!(t.evaluate(&at(f64::NAN, 0.5)).is_finite());
    }

    #[test]
    fn mip_levels_average_in_linear_values_and_trilinear_picks_them_by_footprint() {
        let data = two_by_two();
        assert_eq!(data.level_count(), 2);
        // The 1x1 level: the mean of the four texels, alpha included.
        let top = data.texel(1, 0, 0);
        assert!((top[0] - 0.5).abs() < 3e-3 && (top[3] - 0.75).abs() < 3e-3, "{top:?}");
        let t = texture(Filter::Trilinear, Wrap::Repeat);
        let wide = ShadingPoint { duv_dx: [1.0, 0.0], duv_dy: [0.0, 1.0], ..at(0.25, 0.75) };
        assert!((t.evaluate(&wide) - Rgb::splat(0.5)).length() < 5e-3, "a footprint of the whole image reads its mean");
        // Channel selection.
        let alpha = ImageTexture { channel: Channel::One(3), ..texture(Filter::Nearest, Wrap::Repeat) };
        assert_eq!(alpha.evaluate(&at(0.75, 0.25)), Rgb::ZERO);
    }

    #[test]
    fn srgb_texels_are_decoded() {
        let image = ImageData::new(1, 1, Texels::U8(vec![[188, 255, 0, 255]]), true).unwrap();
        let t = ImageTexture {
            image: Arc::new(image),
            wrap: Wrap::Repeat,
            filter: Filter::Nearest,
            transform: UvTransform::IDENTITY,
            channel: Channel::Rgb,
        };
        let c = t.evaluate(&at(0.5, 0.5));
        assert!((c.x - 0.5).abs() < 3e-3 && c.y == 1.0 && c.z == 0.0, "{c}");
        assert!(ImageData::new(2, 2, Texels::U8(vec![[0; 4]; 3]), true).is_err());
    }
}
