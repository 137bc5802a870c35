//! The decoded image behind `image` textures ([`super::image`]): texels kept
//! at the file's depth, the table that turns them into linear values, and the
//! MIP pyramid.
//!
//! **Depth.** 8- and 16-bit texels stay integers and are decoded through a
//! table at lookup (256 or 65536 entries, sRGB or linear, shared by every
//! image of that depth and colour space); only float files (HDR, EXR) are kept
//! as `f32`. An 8192 x 8192 RGBA 16-bit PNG is 512 MiB as `u16` against 1 GiB
//! as floats, so two of them fit where one did before (issue 30's memory
//! budget). pbrt-v4's `Image` keeps 8-bit, half and float texels the same way.
//! The table entry for a 16-bit value `v` is the one the float path gave,
//! `decode(f32(v) / 65535)`, so a lookup reads the same value it did.
//!
//! **MIP pyramid.** Level `k + 1` is level `k` box-filtered 2x2 (3 along an
//! odd side's last texel), averaged in linear values and stored at level 0's
//! depth (re-encoded through the table: the nearest entry). It is built the
//! first time a trilinear lookup asks for a smaller level, once, shared by
//! every texture of the image; nearest and bilinear lookups (the default)
//! read level 0 only and never pay its third more memory.

use std::sync::{Arc, OnceLock};

/// Texel values of one MIP level, RGBA, rows top to bottom.
#[derive(Clone, Debug, PartialEq)]
pub enum Texels {
    /// 8-bit, decoded through the image's table (sRGB or linear) at lookup.
    U8(Vec<[u8; 4]>),
    /// 16-bit, decoded through the image's table (sRGB or linear) at lookup.
    U16(Vec<[u16; 4]>),
    /// Linear floats (HDR and EXR files).
    F32(Vec<[f32; 4]>),
}

impl Texels {
    fn len(&self) -> usize {
        match self {
            Texels::U8(t) => t.len(),
            Texels::U16(t) => t.len(),
            Texels::F32(t) => t.len(),
        }
    }
}

/// One MIP level.
#[derive(Clone, Debug, PartialEq)]
pub(super) struct Level {
    pub(super) width: usize,
    pub(super) height: usize,
    texels: Texels,
}

/// A decoded image with its MIP pyramid, shared by textures.
#[derive(Clone)]
pub struct ImageData {
    base: Level,
    /// Levels 1 and below, built on the first trilinear lookup (module doc).
    smaller: OnceLock<Vec<Level>>,
    /// Integer value -> linear value of the colour channels (empty for floats).
    table: Arc<[f32]>,
}

impl PartialEq for ImageData {
    /// The same texels in the same colour space, whether or not either has built its pyramid.
    fn eq(&self, other: &ImageData) -> bool {
        self.base == other.base && self.table == other.table
    }
}

impl std::fmt::Debug for ImageData {
    /// The size, not the texels (a material's debug text stays short).
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let (w, h) = self.size();
        let depth = match self.base.texels {
            Texels::U8(_) => "8-bit",
            Texels::U16(_) => "16-bit",
            Texels::F32(_) => "float",
        };
        write!(f, "ImageData({w}x{h}, {depth})")
    }
}

/// The shared table of linear values for integer texels of `max + 1` values.
fn table(max: u16, srgb: bool) -> Arc<[f32]> {
    static TABLES: [OnceLock<Arc<[f32]>>; 4] = [OnceLock::new(), OnceLock::new(), OnceLock::new(), OnceLock::new()];
    let slot = usize::from(max == u16::MAX) * 2 + usize::from(srgb);
    TABLES[slot]
        .get_or_init(|| {
            (0..=max)
                .map(|v| {
                    let x = f32::from(v) / f32::from(max);
                    if srgb {
                        crate::film::srgb_decode(f64::from(x)) as f32
                    } else {
                        x
                    }
                })
                .collect()
        })
        .clone()
}

impl ImageData {
    /// An image of `width x height` texels (`texels.len() == width * height`,
    /// rows top to bottom); integer colour channels are sRGB-encoded when `srgb`.
    pub fn new(width: usize, height: usize, texels: Texels, srgb: bool) -> Result<ImageData, crate::Error> {
        let len = texels.len();
        if width == 0 || height == 0 || width.checked_mul(height) != Some(len) {
            return Err(crate::Error::invalid("image", format!("{len} texels for {width} x {height}")));
        }
        let table = match texels {
            Texels::U8(_) => table(255, srgb),
            Texels::U16(_) => table(u16::MAX, srgb),
            Texels::F32(_) => Arc::from(Vec::new()),
        };
        Ok(ImageData { base: Level { width, height, texels }, smaller: OnceLock::new(), table })
    }

    /// Width and height of level 0.
    pub fn size(&self) -> (usize, usize) {
        (self.base.width, self.base.height)
    }

    /// Number of MIP levels (1 for a 1x1 image); builds the pyramid.
    pub fn level_count(&self) -> usize {
        1 + self.smaller().len()
    }

    /// Bytes the texels hold: level 0, and the smaller levels once built.
    pub fn texel_bytes(&self) -> usize {
        let bytes = |l: &Level| match &l.texels {
            Texels::U8(t) => t.len() * 4,
            Texels::U16(t) => t.len() * 8,
            Texels::F32(t) => t.len() * 16,
        };
        bytes(&self.base) + self.smaller.get().map_or(0, |s| s.iter().map(bytes).sum())
    }

    /// MIP level `index` (0 is the image itself; [`ImageData::level_count`] bounds it).
    #[inline]
    pub(super) fn level(&self, index: usize) -> &Level {
        if index == 0 {
            &self.base
        } else {
            &self.smaller()[index - 1]
        }
    }

    fn smaller(&self) -> &[Level] {
        self.smaller.get_or_init(|| {
            let mut levels: Vec<Level> = Vec::new();
            while let Some(next) = self.next_level(levels.last().unwrap_or(&self.base)) {
                levels.push(next);
            }
            levels
        })
    }

    /// Texel `(x, y)` of `level` as linear RGBA (`x < width`, `y < height`).
    #[inline]
    pub fn texel(&self, level: usize, x: usize, y: usize) -> [f32; 4] {
        self.read(self.level(level), x, y)
    }

    /// Texel `(x, y)` of level `l` (from [`ImageData::level`]) as linear RGBA:
    /// a bilinear lookup finds its level once for its four texels. Always
    /// inlined: a call per texel cost the textured guard case 1 %.
    #[inline(always)]
    pub(super) fn read(&self, l: &Level, x: usize, y: usize) -> [f32; 4] {
        let table = &self.table;
        match &l.texels {
            Texels::U8(t) => {
                let [r, g, b, a] = t[y * l.width + x];
                [table[r as usize], table[g as usize], table[b as usize], f32::from(a) / 255.0]
            }
            Texels::U16(t) => {
                let [r, g, b, a] = t[y * l.width + x];
                [table[r as usize], table[g as usize], table[b as usize], f32::from(a) / 65535.0]
            }
            Texels::F32(t) => t[y * l.width + x],
        }
    }

    /// The level below `src`, box-filtered; `None` at 1x1. Each target texel
    /// averages the source texels whose index maps into it (2x2, or 3 along an
    /// odd side's last texel).
    fn next_level(&self, src: &Level) -> Option<Level> {
        if src.width == 1 && src.height == 1 {
            return None;
        }
        let (w, h) = ((src.width / 2).max(1), (src.height / 2).max(1));
        let mut sums = vec![[0f32; 4]; w * h];
        let mut counts = vec![0f32; w * h];
        for y in 0..src.height {
            let ty = (y * h / src.height).min(h - 1);
            for x in 0..src.width {
                let tx = (x * w / src.width).min(w - 1);
                let t = self.read(src, x, y);
                let s = &mut sums[ty * w + tx];
                for c in 0..4 {
                    s[c] += t[c];
                }
                counts[ty * w + tx] += 1.0;
            }
        }
        let linear = sums.iter().zip(&counts).map(|(s, n)| s.map(|c| c / n));
        // Integer levels stay at their depth: re-encoded through the table's inverse.
        let texels = match &src.texels {
            Texels::F32(_) => Texels::F32(linear.collect()),
            Texels::U8(_) => Texels::U8(
                linear
                    .map(|t| [self.encode(t[0]) as u8, self.encode(t[1]) as u8, self.encode(t[2]) as u8, (t[3] * 255.0).round() as u8])
                    .collect(),
            ),
            Texels::U16(_) => Texels::U16(
                linear.map(|t| [self.encode(t[0]), self.encode(t[1]), self.encode(t[2]), (t[3] * 65535.0).round() as u16]).collect(),
            ),
        };
        Some(Level { width: w, height: h, texels })
    }

    /// The integer value whose table entry is nearest `v`.
    fn encode(&self, v: f32) -> u16 {
        let last = self.table.len() - 1;
        let i = self.table.partition_point(|&t| t < v).min(last);
        if i > 0 && (v - self.table[i - 1]).abs() <= (self.table[i] - v).abs() {
            (i - 1) as u16
        } else {
            i as u16
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sixteen_bit_texels_read_as_the_float_path_did() {
        let values = [0u16, 1, 257, 12345, 40000, 65534, 65535];
        let texels: Vec<[u16; 4]> = values.iter().map(|&v| [v, v, v, v]).collect();
        for srgb in [false, true] {
            let image = ImageData::new(values.len(), 1, Texels::U16(texels.clone()), srgb).unwrap();
            for (x, &v) in values.iter().enumerate() {
                let f = f32::from(v) / 65535.0;
                let colour = if srgb { crate::film::srgb_decode(f64::from(f)) as f32 } else { f };
                assert_eq!(image.texel(0, x, 0), [colour, colour, colour, f], "{v} srgb {srgb}");
            }
        }
    }

    #[test]
    fn the_pyramid_is_built_on_demand_at_level_zero_s_depth() {
        // 2 x 2 16-bit linear: 0, 1 over 1, 1; the 1x1 level is their mean, 0.75.
        let texels = vec![[0; 4], [65535; 4], [65535; 4], [65535; 4]];
        let image = ImageData::new(2, 2, Texels::U16(texels), false).unwrap();
        assert_eq!(image.texel_bytes(), 4 * 8, "level 0 only until a smaller level is read");
        assert_eq!(image.level_count(), 2);
        assert_eq!(image.texel_bytes(), 5 * 8);
        assert_eq!(image.texel(1, 0, 0), [49151.0 / 65535.0; 4], "0.75 (49151.25) re-encoded to the nearest 16-bit value");
        let again = ImageData::new(2, 2, Texels::U16(vec![[0; 4], [65535; 4], [65535; 4], [65535; 4]]), false).unwrap();
        assert_eq!(image, again, "an image equals its copy whether or not the pyramid is built");
    }
}
