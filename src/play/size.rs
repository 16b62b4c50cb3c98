//! The terminal sizes a session draws: a client's claim is clamped to them, never trusted.

/// Widest terminal a client may claim, in columns (larger claims are clamped, never trusted).
pub const MAX_COLS: u16 = 500;
/// Tallest terminal a client may claim, in rows.
pub const MAX_ROWS: u16 = 200;
/// Turns a client's claimed terminal size into one we render: each side clamped to 1..=max.
///
/// The SSH wire carries `u32`; anything above the bounds (including values that would wrap a
/// `u16`) becomes the bound, and 0 becomes 1.
#[must_use]
pub fn clamp_size(cols: u32, rows: u32) -> (u16, u16) {
    let c = cols.clamp(1, u32::from(MAX_COLS));
    let r = rows.clamp(1, u32::from(MAX_ROWS));
    // Both are now within u16 range by construction.
    (
        u16::try_from(c).unwrap_or(MAX_COLS),
        u16::try_from(r).unwrap_or(MAX_ROWS),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sizes_are_clamped_without_wrapping() {
        assert_eq!(clamp_size(0, 0), (1, 1));
        assert_eq!(clamp_size(80, 24), (80, 24));
        assert_eq!(clamp_size(501, 201), (500, 200));
        assert_eq!(clamp_size(65_536 + 80, 65_536 + 24), (500, 200));
        assert_eq!(clamp_size(u32::MAX, u32::MAX), (500, 200));
    }
}
