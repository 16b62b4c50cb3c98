//! Whether `--pos` puts the eye somewhere a frame can be drawn from or a player can stand, as a
//! bad-input failure (exit 2); the rule and its words are the library's
//! ([`halfcast::trace_query::pose`]), so the browser's ray addresses say the same.

use halfcast::map::Map;
pub(crate) use halfcast::trace_query::pose::PoseUse;
use halfcast::Vec2;

use super::Failure;

/// `Ok` when `pos` is in an open cell of `map` for `use_`; else a bad-input failure naming the
/// map's size.
pub(crate) fn check_pos(map: &Map, pos: Vec2, use_: PoseUse) -> Result<(), Failure> {
    halfcast::trace_query::pose::check_pos(map, pos, use_).map_err(Failure::input)
}
