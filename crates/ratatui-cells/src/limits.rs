//! How large a frame the readers accept, so any input gives bounded work.

/// Largest frame read back, in cells (columns, rows). Sizes found in a file or a byte stream
/// are checked against it before anything is allocated.
pub const MAX_FRAME: (usize, usize) = (4000, 2000);

/// The error for a frame larger than [`MAX_FRAME`].
pub(crate) fn too_large(what: &str, cols: usize, rows: usize) -> crate::Error {
    let (mc, mr) = MAX_FRAME;
    crate::Error::new(format!(
        "{what} is {cols}x{rows} cells; the limit is {mc}x{mr}"
    ))
}
