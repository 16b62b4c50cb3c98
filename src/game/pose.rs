//! Whether a start pose has room for the eye: a still frame (`render --pos … --z …`) or a
//! player set down at `--pos` or a replay's start. Asked before anything is drawn, so a pose
//! inside a low ceiling is an error naming the cell, not a picture from inside the ceiling.

use super::body::Body;
use super::CROUCH_EYE;
use crate::map::{Map, Span};
use crate::render::view::EYE_RANGE;
use crate::vec2::Vec2;

/// How far below its cell's ceiling a still frame's eye must stay: as on a plain floor, where
/// the highest eye is [`EYE_RANGE`]`.1` under a ceiling at 1.
pub const EYE_MARGIN: f64 = 1.0 - EYE_RANGE.1;

/// The open span of the cell at `pos`, or why there is none (a wall, the void).
fn span_at(map: &Map, pos: Vec2, what: &str) -> Result<((i64, i64), Span), String> {
    let cell = (pos.x.floor() as i64, pos.y.floor() as i64);
    map.span(cell.0, cell.1).map(|s| (cell, s)).ok_or_else(|| {
        format!(
            "{what} {},{} is not on a floor cell of {}",
            pos.x, pos.y, map.name
        )
    })
}

/// Whether a still frame's eye `eye_z` above the floor at `pos` has room: the span it looks
/// from, or `None` where `pos` is in no open cell (a wall: drawn as it always was), or an error
/// when the eye would be in (or within [`EYE_MARGIN`] of) its cell's ceiling.
///
/// # Errors
/// `eye_z` too high for the cell at `pos`.
pub fn still_eye(map: &Map, pos: Vec2, eye_z: f64) -> Result<Option<Span>, String> {
    let Ok((cell, span)) = span_at(map, pos, "--pos") else {
        return Ok(None);
    };
    let most = span.height() - EYE_MARGIN;
    if eye_z <= most + 1e-9 {
        Ok(Some(span))
    } else {
        Err(format!(
            "--z {eye_z} puts the eye inside the ceiling: cell ({},{}) of {} is {} high \
             (floor {}, ceiling {}), so the eye may be at most {} above its floor",
            cell.0,
            cell.1,
            map.name,
            round(span.height()),
            span.floor,
            span.ceil,
            round(most)
        ))
    }
}

/// Whether a player can start at `pos`: on a floor cell with room for at least a crouching
/// body (where standing does not fit, the game starts crouched). `what` names the source of
/// the position in the message (`--pos`, a replay's `start`).
///
/// # Errors
/// `pos` on no floor cell, or a cell too low even to crouch in.
pub fn player_start(map: &Map, pos: Vec2, what: &str) -> Result<Span, String> {
    let (cell, span) = span_at(map, pos, what)?;
    let crouched = Body {
        feet: span.floor,
        eye: CROUCH_EYE,
    };
    if crouched.fits_under(span) {
        Ok(span)
    } else {
        Err(format!(
            "{what} {},{} has no room for the eye: cell ({},{}) of {} is {} high, and even \
             crouching needs {}",
            pos.x,
            pos.y,
            cell.0,
            cell.1,
            map.name,
            round(span.height()),
            round(CROUCH_EYE + super::body::HEAD_ROOM)
        ))
    }
}

/// A height for messages: at most 4 decimals, no float noise (0.4, not 0.39999999999999997).
fn round(v: f64) -> f64 {
    (v * 10_000.0).round() / 10_000.0
}

#[cfg(test)]
mod tests {
    use super::*;

    fn map() -> Map {
        let text = "NO n\nSO s\nWE w\nEA e\nF 1,2,3\nC 4,5,6\nHa 0 0.5\nHb 0.5 0.8\nHc 1 4\n\
                    111111\n1Nabc1\n111111\n";
        crate::map::parse_map("low.cub", text.as_bytes()).unwrap()
    }

    #[test]
    fn a_still_eye_must_stay_under_its_cells_ceiling() {
        let m = map();
        assert!(
            still_eye(&m, Vec2::new(1.5, 1.5), 0.95).is_ok(),
            "plain floor, as always"
        );
        assert!(still_eye(&m, Vec2::new(2.5, 1.5), 0.45).is_ok());
        assert_eq!(
            still_eye(&m, Vec2::new(2.5, 1.5), 0.5).unwrap_err(),
            "--z 0.5 puts the eye inside the ceiling: cell (2,1) of low.cub is 0.5 high \
             (floor 0, ceiling 0.5), so the eye may be at most 0.45 above its floor"
        );
        assert!(still_eye(&m, Vec2::new(4.5, 1.5), 0.95).is_ok());
        assert_eq!(still_eye(&m, Vec2::new(0.5, 1.5), 0.9), Ok(None), "a wall");
    }

    #[test]
    fn a_player_starts_where_at_least_crouching_fits() {
        let m = map();
        assert!(player_start(&m, Vec2::new(1.5, 1.5), "--pos").is_ok());
        assert!(
            player_start(&m, Vec2::new(2.5, 1.5), "--pos").is_ok(),
            "crouching fits"
        );
        assert_eq!(
            player_start(&m, Vec2::new(3.5, 1.5), "--pos").unwrap_err(),
            "--pos 3.5,1.5 has no room for the eye: cell (3,1) of low.cub is 0.3 high, and \
             even crouching needs 0.4"
        );
    }
}
