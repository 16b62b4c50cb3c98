//! Library tests: the engine, encoder, widgets and game rules driven through the crate as a user
//! of it would, with no features (`cargo test --no-default-features` runs them too). One binary,
//! so the support code and the link are paid once.

#[path = "../support/capture/mod.rs"]
mod capture;
#[path = "../support/world_common/mod.rs"]
#[allow(dead_code)] // each test binary uses its own part of the shared world helpers
mod world_common;

mod architecture;
mod code_shape;
mod embed_view;
mod encode_roundtrip;
mod game_creatures;
mod game_items;
mod game_render;
mod glyph_grid;
mod heights_golden;
mod lamps_heights;
mod lean_backend;
mod ratatui_dashboard;
mod world_projection;
