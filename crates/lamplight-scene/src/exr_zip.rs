//! OpenEXR files in ZIP compression (blocks of 16 scan lines) compressed at
//! deflate's fastest level, in parallel.
//!
//! Why not the `exr` crate's own writer: it deflates every ZIP block at level 4,
//! fixed. On rendered images that took 4.5 times as long as level 1 for files
//! 2 % smaller on a noisy path-traced image and 7 % on a smooth Whitted one
//! (512x512 Cornell box: 68 ms against 15 ms on one core; a 1280x720 `luxo`:
//! 112 ms against 26 ms; BENCHMARKS.md), the largest step of a short render
//! after the render itself. The file is still the crate's: its header, offset
//! table and chunk framing come from `exr::block::writer::write_chunks_with`;
//! this module only makes each block's bytes, as OpenEXR's ZIP compressor
//! defines them:
//!
//! 1. the block's scan lines in order, each line every channel in name order,
//!    each channel its row of 32-bit floats, little-endian;
//! 2. the bytes split in two halves, the even-numbered bytes first;
//! 3. each byte after the first replaced by `(byte - previous byte + 128) mod 256`
//!    (the previous byte of step 2's order);
//! 4. zlib (deflate level 1, `miniz_oxide`).
//!
//! A block that does not shrink is stored as step 1's bytes, as OpenEXR does
//! (readers tell the two apart by the size). Any OpenEXR reader reads these
//! files; the tests read them back with the `exr` crate, and
//! `bench/mitsuba_cornell.py` reads every benchmark render with Mitsuba's
//! OpenEXR.

use std::io::Cursor;

use exr::block::chunk::{Chunk, CompressedBlock, CompressedScanLineBlock};
use exr::block::writer::ChunksWriter;
use exr::meta::attribute::{ChannelDescription, LineOrder, SampleType};
use exr::meta::header::{Header, LayerAttributes};
use exr::meta::{BlockDescription, Headers};
use exr::prelude::{Compression, SmallVec};
use rayon::prelude::*;

/// Scan lines per ZIP block (OpenEXR's `ZIP_COMPRESSION`).
const LINES: usize = 16;
/// Deflate level: the fastest (module doc).
const LEVEL: u8 = 1;

/// Where a channel's values are: its own row-major plane, or component `k` of
/// row-major RGB pixels.
#[derive(Clone, Copy, Debug)]
pub(crate) enum Samples<'a> {
    /// One value per pixel.
    Plane(&'a [f32]),
    /// Component `k` (the second field: 0, 1 or 2) of each pixel.
    Component(&'a [[f32; 3]], usize),
}

impl Samples<'_> {
    fn len(&self) -> usize {
        match self {
            Samples::Plane(v) => v.len(),
            Samples::Component(p, _) => p.len(),
        }
    }

    /// Appends the values of pixels `range` as little-endian bytes.
    fn extend_le(&self, range: std::ops::Range<usize>, out: &mut Vec<u8>) {
        match *self {
            Samples::Plane(v) => v[range].iter().for_each(|x| out.extend_from_slice(&x.to_le_bytes())),
            Samples::Component(p, k) => p[range].iter().for_each(|x| out.extend_from_slice(&x[k].to_le_bytes())),
        }
    }
}

/// The bytes of a one-part scan-line OpenEXR file, ZIP-compressed, of a
/// `width x height` image with `channels` (name, values), all 32-bit float.
/// Channels are written in name order, as the format requires.
pub(crate) fn encode(width: usize, height: usize, mut channels: Vec<(String, Samples<'_>)>) -> Result<Vec<u8>, String> {
    if width == 0 || height == 0 {
        return Err(format!("the image is empty ({width}x{height})"));
    }
    if let Some((name, s)) = channels.iter().find(|(_, s)| s.len() != width * height) {
        return Err(format!("channel {name} has {} values for {} pixels", s.len(), width * height));
    }
    channels.sort_by(|a, b| a.0.cmp(&b.0));
    let list: SmallVec<[ChannelDescription; 5]> =
        channels.iter().map(|(name, _)| ChannelDescription::named(name.as_str(), SampleType::F32)).collect();
    let header = Header::new("".into(), (width, height), list)
        .with_encoding(Compression::ZIP16, BlockDescription::ScanLines, LineOrder::Increasing)
        .with_attributes(LayerAttributes::default());
    let headers: Headers = std::iter::once(header).collect();

    let blocks: Vec<Vec<u8>> = (0..height.div_ceil(LINES))
        .into_par_iter()
        .map(|b| {
            let lines = b * LINES..((b + 1) * LINES).min(height);
            let mut raw = Vec::with_capacity(lines.len() * width * channels.len() * 4);
            for y in lines {
                for (_, samples) in &channels {
                    samples.extend_le(y * width..(y + 1) * width, &mut raw);
                }
            }
            let compressed = miniz_oxide::deflate::compress_to_vec_zlib(&predicted(&raw), LEVEL);
            if compressed.len() < raw.len() {
                compressed
            } else {
                raw
            }
        })
        .collect();

    let mut bytes = Cursor::new(Vec::new());
    exr::block::writer::write_chunks_with(&mut bytes, headers, false, |_, writer| {
        for (b, compressed_pixels) in blocks.into_iter().enumerate() {
            let block = CompressedScanLineBlock { y_coordinate: (b * LINES) as i32, compressed_pixels_le: compressed_pixels };
            writer.write_chunk(b, Chunk { layer_index: 0, compressed_block: CompressedBlock::ScanLine(block) })?;
        }
        Ok(())
    })
    .map_err(|e| e.to_string())?;
    Ok(bytes.into_inner())
}

/// Steps 2 and 3 of the module doc: the even bytes, then the odd ones, each as
/// its difference from the one before plus 128.
fn predicted(raw: &[u8]) -> Vec<u8> {
    let half = raw.len().div_ceil(2);
    let mut out = vec![0u8; raw.len()];
    let (even, odd) = out.split_at_mut(half);
    for (k, pair) in raw.chunks(2).enumerate() {
        even[k] = pair[0];
        if let Some(&b) = pair.get(1) {
            odd[k] = b;
        }
    }
    let mut previous = out.first().copied().unwrap_or(0);
    for byte in out.iter_mut().skip(1) {
        let current = *byte;
        *byte = current.wrapping_sub(previous).wrapping_add(128);
        previous = current;
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Read back by the project's EXR reader (the `exr` crate's), through a file.
    fn decode(bytes: &[u8]) -> (usize, usize, Vec<(String, Vec<f32>)>) {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("out.exr");
        std::fs::write(&path, bytes).unwrap();
        crate::exr_layers::read_exr_channels(&path).unwrap()
    }

    /// The crate's own predictor, which its reader inverts: step 2 and 3 of the
    /// module doc written out with indices.
    #[test]
    fn the_predictor_is_openexrs() {
        let raw: Vec<u8> = (0..37u32).map(|i| (i * 97 % 251) as u8).collect();
        let out = predicted(&raw);
        let half = raw.len().div_ceil(2);
        let split: Vec<u8> = (0..raw.len()).map(|i| if i < half { raw[2 * i] } else { raw[2 * (i - half) + 1] }).collect();
        assert_eq!(out[0], split[0]);
        for i in 1..raw.len() {
            assert_eq!(out[i], split[i].wrapping_sub(split[i - 1]).wrapping_add(128), "byte {i}");
        }
        assert!(predicted(&[]).is_empty());
        assert_eq!(predicted(&[7]), vec![7]);
    }

    #[test]
    fn files_read_back_float_exact_in_name_order() {
        // Sizes off the 16-line block, one-pixel-wide, and values that compress
        // (smooth) and that do not (noise, stored raw), NaN and infinities kept.
        let mut state = 0x1234_5678u32;
        let mut noise = move || {
            state = state.wrapping_mul(747_796_405).wrapping_add(2_891_336_453);
            f32::from_bits(state.rotate_left(11) & 0x7f7f_ffff)
        };
        for (w, h) in [(37, 23), (1, 40), (16, 16), (5, 1), (300, 33)] {
            let rgb: Vec<[f32; 3]> =
                (0..w * h).map(|i| [i as f32 * 0.25, noise(), if i % 7 == 0 { f32::NAN } else { f32::INFINITY }]).collect();
            let samples: Vec<f32> = (0..w * h).map(|i| (i / 3) as f32).collect();
            let channels = vec![
                ("R".to_string(), Samples::Component(&rgb, 0)),
                ("G".to_string(), Samples::Component(&rgb, 1)),
                ("B".to_string(), Samples::Component(&rgb, 2)),
                ("samples.Y".to_string(), Samples::Plane(&samples)),
            ];
            let (rw, rh, back) = decode(&encode(w, h, channels).unwrap());
            assert_eq!((rw, rh), (w, h));
            // Bit-exact through NaN payloads: the samples stayed 32-bit floats.
            let names: Vec<&str> = back.iter().map(|(n, _)| n.as_str()).collect();
            assert_eq!(names, ["B", "G", "R", "samples.Y"]);
            for (c, (_, values)) in back.iter().take(3).enumerate() {
                let expected: Vec<u32> = rgb.iter().map(|p| p[2 - c].to_bits()).collect();
                assert_eq!(values.iter().map(|v| v.to_bits()).collect::<Vec<_>>(), expected, "{w}x{h} channel {c}");
            }
            assert_eq!(back[3].1, samples);
        }
    }

    #[test]
    fn smooth_images_shrink_and_bad_sizes_are_refused() {
        let rgb = vec![[0.5f32, 0.25, 0.125]; 64 * 64];
        let channels = || vec![("R".to_string(), Samples::Component(&rgb, 0)), ("G".to_string(), Samples::Component(&rgb, 1))];
        let bytes = encode(64, 64, channels()).unwrap();
        assert!(bytes.len() < 64 * 64 * 8 / 10, "a flat image compresses: {} bytes", bytes.len());
        assert_eq!(encode(0, 64, channels()).unwrap_err(), "the image is empty (0x64)");
        assert_eq!(encode(64, 63, channels()).unwrap_err(), "channel R has 4096 values for 4032 pixels");
    }
}
