//! The colour a key and the doors it opens share, so a locked door reads at a glance; the textures
//! and sprite sheets are tinted with it when a world loads.

use crate::color::Rgb;

/// The colour of key `name`: well-known colour names look like themselves, any other name gets
/// a stable bright colour from a hash of its letters.
#[must_use]
pub fn key_colour(name: &str) -> Rgb {
    let named = match name.to_ascii_lowercase().as_str() {
        "red" => Some((230, 40, 40)),
        "blue" => Some((50, 90, 240)),
        "green" => Some((40, 200, 60)),
        "yellow" => Some((240, 220, 40)),
        "gold" => Some((240, 190, 40)),
        "orange" => Some((250, 140, 30)),
        "purple" | "violet" => Some((160, 60, 220)),
        "cyan" => Some((40, 220, 230)),
        "white" | "silver" => Some((235, 235, 235)),
        "pink" | "magenta" => Some((240, 80, 200)),
        _ => None,
    };
    if let Some((r, g, b)) = named {
        return Rgb::new(r, g, b);
    }
    // FNV-1a: the same name gives the same colour in every build and on every machine.
    let mut h: u32 = 0x811C_9DC5;
    for b in name.bytes() {
        h = (h ^ u32::from(b)).wrapping_mul(0x0100_0193);
    }
    // A hue from the hash at full saturation, so it never comes out grey.
    let hue = f64::from(h % 360);
    let x = 1.0 - ((hue / 60.0) % 2.0 - 1.0).abs();
    let (r, g, b) = match (hue / 60.0) as u32 {
        0 => (1.0, x, 0.0),
        1 => (x, 1.0, 0.0),
        2 => (0.0, 1.0, x),
        3 => (0.0, x, 1.0),
        4 => (x, 0.0, 1.0),
        _ => (1.0, 0.0, x),
    };
    let ch = |v: f64| (40.0 + v * 200.0) as u8;
    Rgb::new(ch(r), ch(g), ch(b))
}

/// `c` recoloured toward `tint` by its own lightness: dark stays dark, light takes the tint.
#[must_use]
pub fn tinted(c: Rgb, tint: Rgb) -> Rgb {
    let l = f64::from(c.luma()) / 255.0;
    let k = 0.3 + 0.9 * l;
    let ch = |t: u8| (f64::from(t) * k).round().clamp(0.0, 255.0) as u8;
    Rgb::new(ch(tint.r), ch(tint.g), ch(tint.b))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn named_keys_look_like_their_names_and_others_are_stable_and_coloured() {
        let red = key_colour("red");
        assert!(red.r > 200 && red.g < 80 && red.b < 80);
        let blue = key_colour("Blue");
        assert!(blue.b > 200 && blue.r < 80);
        let a = key_colour("crypt");
        assert_eq!(a, key_colour("crypt"));
        assert_ne!(a, key_colour("vault"));
        let (hi, lo) = (a.r.max(a.g).max(a.b), a.r.min(a.g).min(a.b));
        assert!(hi - lo > 100, "{a:?} is not grey");
    }

    #[test]
    fn tint_keeps_dark_dark() {
        let red = key_colour("red");
        let dark = tinted(Rgb::new(10, 10, 10), red);
        let light = tinted(Rgb::new(240, 240, 240), red);
        assert!(dark.r < light.r && light.r > 200 && light.g < 80);
    }
}
