//! ratatui-cells' integration tests, one binary: reading back what real backends send, and
//! what the strict and loose comparisons tell apart.

mod read_back;
mod strictness;
