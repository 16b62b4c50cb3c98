//! ratatui-cells' integration tests, one binary: reading back what real backends send, what
//! the strict and loose comparisons tell apart, stored snapshots in insta's workflow, and the
//! sizes the README states.

mod public_api;
mod read_back;
mod sizes;
mod stored;
mod strictness;
