//! PNG bytes from any image the project builds (frames, textures, sprite sheets).

use image::DynamicImage;

/// Encodes `img` as PNG in memory, so every PNG writer shares one encoder setup.
///
/// # Errors
/// The encoder's message (only on failures inside `image`).
pub fn encode(img: impl Into<DynamicImage>) -> Result<Vec<u8>, String> {
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
        let img = image::RgbImage::from_fn(3, 2, |x, y| image::Rgb([x as u8 * 80, y as u8, 7]));
        let bytes = encode(img.clone()).unwrap();
        let back = image::load_from_memory(&bytes).unwrap().to_rgb8();
        assert_eq!(back, img);
    }
}
