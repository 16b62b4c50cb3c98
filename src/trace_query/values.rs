//! The values a ray is asked for with, read from text the same way on the command line and in
//! a page's address: a finite number, `X,Y`, a field of view, `COLSxROWS`. The messages are
//! the ones `halfcast` prints for a bad flag.

use crate::vec2::Vec2;

/// Largest view in cells (columns × rows) a still frame or a trace is drawn for: the largest
/// frame `halfcast diff` reads.
pub const MAX_VIEW: (u16, u16) = (
    crate::termframe::MAX_FRAME.0 as u16,
    crate::termframe::MAX_FRAME.1 as u16,
);

/// A finite number.
///
/// # Errors
/// Text that is not a number, or infinity or NaN.
pub fn parse_finite(s: &str) -> Result<f64, String> {
    let v: f64 = s
        .trim()
        .parse()
        .map_err(|_| format!("'{s}' is not a number"))?;
    if v.is_finite() {
        Ok(v)
    } else {
        Err(format!("'{s}' is not a finite number"))
    }
}

/// A position `X,Y` in cells.
///
/// # Errors
/// Text that is not two finite numbers split by a comma.
pub fn parse_pos(s: &str) -> Result<Vec2, String> {
    let (x, y) = s
        .split_once(',')
        .ok_or_else(|| format!("'{s}' is not X,Y"))?;
    Ok(Vec2::new(parse_finite(x)?, parse_finite(y)?))
}

/// A horizontal field of view in degrees, 0 < FOV < 180.
///
/// # Errors
/// Not a number, or outside the open range.
pub fn parse_fov(s: &str) -> Result<f64, String> {
    let v = parse_finite(s)?;
    if v > 0.0 && v < 180.0 {
        Ok(v)
    } else {
        Err(format!(
            "field of view {v} must be between 0 and 180 degrees (exclusive)"
        ))
    }
}

/// A view size `COLSxROWS` in cells, 1×1 to [`MAX_VIEW`].
///
/// # Errors
/// Not two whole numbers split by `x`, or out of range.
pub fn parse_size(s: &str) -> Result<(u16, u16), String> {
    let (c, r) = s
        .split_once(['x', 'X'])
        .ok_or_else(|| format!("'{s}' is not COLSxROWS"))?;
    let num = |t: &str| {
        t.trim()
            .parse::<u16>()
            .map_err(|_| format!("'{s}' is not COLSxROWS"))
    };
    let (c, r) = (num(c)?, num(r)?);
    if c == 0 || r == 0 || c > MAX_VIEW.0 || r > MAX_VIEW.1 {
        return Err(format!(
            "size {c}x{r} is out of range (1x1 to {}x{})",
            MAX_VIEW.0, MAX_VIEW.1
        ));
    }
    Ok((c, r))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn values_read_as_the_flags_do() {
        assert_eq!(parse_pos("1.5, 2"), Ok(Vec2::new(1.5, 2.0)));
        assert_eq!(parse_pos("1.5").unwrap_err(), "'1.5' is not X,Y");
        assert_eq!(
            parse_finite("inf").unwrap_err(),
            "'inf' is not a finite number"
        );
        assert!(parse_fov("180").is_err());
        assert_eq!(parse_size("80x24"), Ok((80, 24)));
        assert_eq!(
            parse_size("0x24").unwrap_err().split(' ').next(),
            Some("size")
        );
        assert_eq!(parse_size("80").unwrap_err(), "'80' is not COLSxROWS");
    }
}
