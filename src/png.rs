//! PNG bytes from pixels, for every layer that writes pictures (textures, sprite sheets, frames):
//! one encoder set-up, so a texture written by the generator and a frame written by `render`
//! come out of the same code.

use image::DynamicImage;

use crate::color::Rgb;

/// Encodes a `width` × `height` picture whose pixel (x, y) is `pixel(x, y)`, as an RGB PNG.
///
/// # Errors
/// The encoder's message (only on failures inside `image`).
pub(crate) fn rgb(
    width: usize,
    height: usize,
    pixel: impl Fn(usize, usize) -> Rgb,
) -> Result<Vec<u8>, String> {
    let img = image::RgbImage::from_fn(width as u32, height as u32, |x, y| {
        let c = pixel(x as usize, y as usize);
        image::Rgb([c.r, c.g, c.b])
    });
    encode(img)
}

/// As [`rgb`], with an alpha per pixel (sprite sheets keep their transparency).
///
/// # Errors
/// The encoder's message.
pub(crate) fn rgba(
    width: usize,
    height: usize,
    pixel: impl Fn(usize, usize) -> (Rgb, u8),
) -> Result<Vec<u8>, String> {
    let img = image::RgbaImage::from_fn(width as u32, height as u32, |x, y| {
        let (c, a) = pixel(x as usize, y as usize);
        image::Rgba([c.r, c.g, c.b, a])
    });
    encode(img)
}

/// Encodes `img` as PNG in memory.
fn encode(img: impl Into<DynamicImage>) -> Result<Vec<u8>, String> {
    let mut out = std::io::Cursor::new(Vec::new());
    img.into()
        .write_to(&mut out, image::ImageFormat::Png)
        .map_err(|e| e.to_string())?;
    Ok(out.into_inner())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn round_trips_through_the_decoder() {
        let bytes = rgb(3, 2, |x, y| Rgb::new(x as u8 * 80, y as u8, 7)).unwrap();
        let back = image::load_from_memory(&bytes).unwrap().to_rgb8();
        assert_eq!((back.width(), back.height()), (3, 2));
        assert_eq!(back.get_pixel(2, 1).0, [160, 1, 7]);
    }

    #[test]
    fn alpha_is_kept() {
        let bytes = rgba(2, 1, |x, _| (Rgb::new(9, 8, 7), x as u8 * 255)).unwrap();
        let back = image::load_from_memory(&bytes).unwrap().to_rgba8();
        assert_eq!(back.get_pixel(0, 0).0, [9, 8, 7, 0]);
        assert_eq!(back.get_pixel(1, 0).0, [9, 8, 7, 255]);
    }
}
