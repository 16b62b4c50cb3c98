//! Decoding image files with bounded work: the size the header claims is checked before any
//! pixel is inflated, and the decoder itself runs under an allocation cap.
//!
//! A 48 KB PNG can claim 20000×20000 pixels; the decoded copy, its RGB conversion and the
//! texture built from it would take gigabytes and a minute. Such an image is refused up front.

use std::io::Cursor;

use image::{DynamicImage, ImageDecoder, ImageReader, Limits};

/// Widest and tallest texture or sprite sheet accepted, in pixels.
pub const MAX_TEXTURE_SIDE: u32 = 4096;

/// Most bytes an image file may hold: a 4096×4096 RGBA image stored uncompressed, plus room.
pub const MAX_IMAGE_FILE_BYTES: u64 = 80 << 20;

/// Most bytes the decoder may allocate (a 16-bit RGBA image at the largest size takes 128 MiB).
const MAX_DECODE_ALLOC: u64 = 160 << 20;

/// Decodes `bytes` if the image is at most `max_w` × `max_h` pixels and not empty.
///
/// # Errors
/// Not a readable image, no pixels, or larger than allowed (named with both sizes).
pub fn decode_within(bytes: &[u8], max_w: u32, max_h: u32) -> Result<DynamicImage, String> {
    let reader = ImageReader::new(Cursor::new(bytes))
        .with_guessed_format()
        .map_err(|e| e.to_string())?;
    let mut decoder = reader.into_decoder().map_err(|e| e.to_string())?;
    let (w, h) = decoder.dimensions();
    check_size((w, h), (max_w, max_h))?;
    let mut limits = Limits::default();
    limits.max_image_width = Some(max_w);
    limits.max_image_height = Some(max_h);
    limits.max_alloc = Some(MAX_DECODE_ALLOC);
    decoder.set_limits(limits).map_err(|e| e.to_string())?;
    DynamicImage::from_decoder(decoder).map_err(|e| e.to_string())
}

/// Refuses an empty image or one over `max` (the message names both sizes).
///
/// # Errors
/// "image has no pixels" or "image is WxH pixels; the limit is MxN".
pub fn check_size((w, h): (u32, u32), (max_w, max_h): (u32, u32)) -> Result<(), String> {
    if w == 0 || h == 0 {
        return Err("image has no pixels".into());
    }
    if w > max_w || h > max_h {
        return Err(format!(
            "image is {w}x{h} pixels; the limit is {max_w}x{max_h}"
        ));
    }
    Ok(())
}

/// The width and height an image's header claims, without decoding any pixel.
///
/// # Errors
/// Not a readable image header.
pub fn image_dimensions(bytes: &[u8]) -> Result<(u32, u32), String> {
    ImageReader::new(Cursor::new(bytes))
        .with_guessed_format()
        .map_err(|e| e.to_string())?
        .into_dimensions()
        .map_err(|e| e.to_string())
}

/// [`decode_within`] at the texture limit ([`MAX_TEXTURE_SIDE`] on both sides).
///
/// # Errors
/// As [`decode_within`].
pub fn decode_texture_image(bytes: &[u8]) -> Result<DynamicImage, String> {
    decode_within(bytes, MAX_TEXTURE_SIDE, MAX_TEXTURE_SIDE)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A PNG whose IHDR claims `w`×`h` 1-bit grey pixels, with no pixel data at all.
    fn claimed_png(w: u32, h: u32) -> Vec<u8> {
        let img = image::GrayImage::new(1, 1);
        let mut png = Vec::new();
        img.write_to(&mut Cursor::new(&mut png), image::ImageFormat::Png)
            .unwrap();
        // IHDR data starts at byte 16 (8 signature + 4 length + 4 type); its CRC follows at 29.
        png[16..20].copy_from_slice(&w.to_be_bytes());
        png[20..24].copy_from_slice(&h.to_be_bytes());
        let crc = crc32(&png[12..29]);
        png[29..33].copy_from_slice(&crc.to_be_bytes());
        png
    }

    fn crc32(bytes: &[u8]) -> u32 {
        let mut crc = flate2::Crc::new();
        crc.update(bytes);
        crc.sum()
    }

    #[test]
    fn a_header_claiming_a_huge_image_is_refused_before_decoding() {
        assert_eq!(
            decode_texture_image(&claimed_png(20000, 20000)).unwrap_err(),
            "image is 20000x20000 pixels; the limit is 4096x4096"
        );
        assert_eq!(
            decode_texture_image(&claimed_png(5000, 1)).unwrap_err(),
            "image is 5000x1 pixels; the limit is 4096x4096"
        );
    }

    #[test]
    fn images_within_the_limit_decode() {
        let img = decode_texture_image(&claimed_png(1, 1)).unwrap();
        assert_eq!((img.width(), img.height()), (1, 1));
    }

    #[test]
    fn garbage_is_an_error() {
        assert!(decode_texture_image(b"\x89PNG\r\n\x1a\nxx").is_err());
        assert!(decode_texture_image(b"").is_err());
    }
}
