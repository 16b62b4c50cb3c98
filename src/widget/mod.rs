//! ratatui widgets for showing the engine: the 3D view, the minimap and the DDA debug pane.
//!
//! Each widget only reads its inputs and draws into the area it is given; they hold no state
//! and know nothing of the terminal, so any ratatui app (or a test buffer) can use them.

pub(crate) mod debug_pane;
pub(crate) mod half_block;
pub(crate) mod minimap;
pub(crate) mod plot;
pub(crate) mod revealed;
pub(crate) mod text;

pub use debug_pane::{DebugPane, KeptLines};
pub use half_block::HalfBlockView;
pub use minimap::{Marker, Minimap};
pub use revealed::RevealedTrace;
