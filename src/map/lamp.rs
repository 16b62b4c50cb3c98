//! halfcast's `LIGHT x,y radius [strength]` lines: point lights that brighten what is near them
//! when the world is dark (night, or `SHADE` falloff).

use super::MapErrorKind;
use crate::vec2::Vec2;

/// Largest light radius, in cells; keeps the light map's build bounded on large maps.
pub const MAX_LIGHT_RADIUS: f64 = 16.0;

/// One point light as the map describes it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LightDef {
    /// Centre on the map plane, in cells.
    pub pos: Vec2,
    /// Distance at which its light has fallen to nothing, in cells.
    pub radius: f64,
    /// Brightness at its centre, 0–1 (1 = full daylight).
    pub strength: f64,
    /// Where the line was written (1-based line, column), for messages.
    pub at: (usize, usize),
}

fn bad(why: impl Into<String>) -> MapErrorKind {
    MapErrorKind::BadValue {
        id: "LIGHT".to_owned(),
        why: why.into(),
    }
}

/// Parses what follows `LIGHT` (position and radius, optional strength).
pub(super) fn parse_light(rest: &str, at: (usize, usize)) -> Result<LightDef, MapErrorKind> {
    let words: Vec<&str> = rest.split([' ', '\t']).filter(|w| !w.is_empty()).collect();
    let (pos, radius, strength) = match words[..] {
        [pos, radius] => (pos, radius, None),
        [pos, radius, strength] => (pos, radius, Some(strength)),
        _ => return Err(bad("write 'LIGHT x,y radius [strength]'")),
    };
    let number = |what: &str, s: &str| {
        s.parse::<f64>()
            .ok()
            .filter(|v| v.is_finite())
            .ok_or_else(|| bad(format!("{what} needs a number, got '{s}'")))
    };
    let (x, y) = pos
        .split_once(',')
        .ok_or_else(|| bad(format!("position must be x,y, got '{pos}'")))?;
    let pos = Vec2::new(number("x", x)?, number("y", y)?);
    let radius = number("radius", radius)?;
    if !(radius > 0.0 && radius <= MAX_LIGHT_RADIUS) {
        return Err(bad(format!(
            "radius must be above 0 and at most {MAX_LIGHT_RADIUS}, got {radius}"
        )));
    }
    let strength = match strength {
        Some(s) => number("strength", s)?,
        None => 1.0,
    };
    if !(0.0..=1.0).contains(&strength) {
        return Err(bad(format!("strength must be 0–1, got {strength}")));
    }
    Ok(LightDef {
        pos,
        radius,
        strength,
        at,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reads_position_radius_and_optional_strength() {
        let l = parse_light(" 3.5,2.25 4", (7, 1)).unwrap();
        assert_eq!(
            (l.pos, l.radius, l.strength, l.at),
            (Vec2::new(3.5, 2.25), 4.0, 1.0, (7, 1))
        );
        let l = parse_light("\t1,1\t2.5  0.6 ", (1, 1)).unwrap();
        assert_eq!((l.radius, l.strength), (2.5, 0.6));
    }

    #[test]
    fn bad_lines_say_what_is_wrong() {
        let msg = |s: &str| parse_light(s, (1, 1)).unwrap_err().to_string();
        assert_eq!(
            msg(" 1,2"),
            "bad value for LIGHT: write 'LIGHT x,y radius [strength]'"
        );
        assert_eq!(
            msg(" 1;2 3"),
            "bad value for LIGHT: position must be x,y, got '1;2'"
        );
        assert_eq!(
            msg(" 1,2 0"),
            "bad value for LIGHT: radius must be above 0 and at most 16, got 0"
        );
        assert_eq!(
            msg(" 1,2 3 1.5"),
            "bad value for LIGHT: strength must be 0–1, got 1.5"
        );
        assert_eq!(
            msg(" 1,nan 3"),
            "bad value for LIGHT: y needs a number, got 'nan'"
        );
    }
}
