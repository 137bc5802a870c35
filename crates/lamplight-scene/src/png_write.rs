//! PNG files of an image: 8-bit RGB, adaptive row filters and fast deflate
//! (the `png` crate's encoder, with the settings `image`'s PNG encoder uses
//! by default).
//!
//! The encoder filters and compresses on one thread, and before it could
//! start the whole image had to be converted to 8 bits: after a 1280x720
//! render, some 3 ms of conversion and 4-5 ms of encoding one after the
//! other, while the other cores waited (`BENCHMARKS.md`, issue 24). Here a
//! second thread converts the image a band of rows at a time and hands each
//! band to the encoder, which starts on the first band at once: the two
//! overlap. The file's pixels are the same; its bytes differ from a one-shot
//! encoding of the same rows only in how the compressed stream is cut into
//! chunks.

use std::sync::mpsc;

use lamplight_core::film::{linear8, Image, Srgb8};

use crate::image_io::Transfer;

/// Rows a band holds: about 120 KB of 8-bit values at 1280 pixels a row, a
/// small part of the encoder's time, so that it starts soon.
const BAND_ROWS: usize = 32;

/// Bands the converting thread may run ahead of the encoder.
const BANDS_AHEAD: usize = 4;

/// The PNG file of `image` (whose size the caller has checked: at least one
/// pixel, `width * height` of them), its values encoded with `transfer`.
pub(crate) fn encode(image: &Image, transfer: Transfer) -> Result<Vec<u8>, String> {
    let width = image.width as usize;
    let mut bytes = Vec::new();
    let mut encoder = png::Encoder::new(&mut bytes, image.width, image.height);
    encoder.set_color(png::ColorType::Rgb);
    encoder.set_depth(png::BitDepth::Eight);
    encoder.set_compression(png::Compression::Fast);
    encoder.set_filter(png::Filter::Adaptive);
    let mut header = encoder.write_header().map_err(|e| e.to_string())?;
    let mut stream = header.stream_writer().map_err(|e| e.to_string())?;
    std::thread::scope(|scope| -> Result<(), String> {
        let (send, receive) = mpsc::sync_channel::<Vec<u8>>(BANDS_AHEAD);
        let converter = std::thread::Builder::new().name("png-rows".into()).spawn_scoped(scope, move || {
            let quantizer = Srgb8::get();
            for rows in image.pixels.chunks(BAND_ROWS * width) {
                let values = rows.as_flattened();
                let mut band = vec![0u8; values.len()];
                match transfer {
                    Transfer::Srgb => quantizer.encode_all(values, &mut band),
                    Transfer::Linear => band.iter_mut().zip(values).for_each(|(b, &v)| *b = linear8(v)),
                }
                // The encoder has stopped (an error): nothing more to do.
                if send.send(band).is_err() {
                    return;
                }
            }
        });
        converter.map_err(|e| format!("cannot start a thread to convert the rows: {e}"))?;
        for band in receive {
            std::io::Write::write_all(&mut stream, &band).map_err(|e| e.to_string())?;
        }
        Ok(())
    })?;
    stream.finish().map_err(|e| e.to_string())?;
    header.finish().map_err(|e| e.to_string())?;
    Ok(bytes)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// An image of several bands and a part band (70 rows), with values
    /// below 0, above 1 and NaN, read back: the 8-bit values of
    /// `to_srgb8` and `to_linear8`, row for row.
    #[test]
    fn the_file_holds_the_images_8_bit_values() {
        let (width, height) = (37u32, 2 * BAND_ROWS as u32 + 6);
        let pixels = (0..width * height)
            .map(|i| {
                let v = (i % 97) as f32 / 80.0 - 0.1;
                [v, if i % 31 == 0 { f32::NAN } else { 1.0 - v }, (i / width) as f32 / height as f32]
            })
            .collect();
        let image = Image { width, height, pixels };
        for (transfer, expected) in [(Transfer::Srgb, image.to_srgb8()), (Transfer::Linear, image.to_linear8())] {
            let file = encode(&image, transfer).unwrap();
            let read = image::load_from_memory_with_format(&file, image::ImageFormat::Png).unwrap().to_rgb8();
            assert_eq!(read.dimensions(), (width, height));
            assert_eq!(read.into_raw(), expected, "{transfer:?}");
        }
    }
}
