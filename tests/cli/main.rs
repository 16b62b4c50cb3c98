//! The `halfcast` binary and the terminal end to end: commands and their exit codes, frames read
//! back through a terminal model, the game played in a pty and in tmux. One binary, so the
//! support code and the link are paid once.

#[path = "../support/capture/mod.rs"]
mod capture;
#[path = "../support/common/mod.rs"]
mod common;
#[path = "../support/oracle/mod.rs"]
mod oracle;
#[path = "../support/pty_support/mod.rs"]
mod pty_support;
#[path = "../support/tmux/mod.rs"]
mod tmux;
#[path = "../support/world_common/mod.rs"]
#[allow(dead_code)] // each test binary uses its own part of the shared world helpers
mod world_common;

mod ansi_levels;
mod ansi_round_trip;
mod bench_bytes_only;
mod cli_colors;
mod cli_default_play;
mod cli_errors;
mod colour;
mod colour_fidelity;
mod config_cli;
mod corpus;
mod diff;
mod docs_bench;
mod docs_commands;
mod docs_dda;
mod docs_outputs_ignored;
mod encode_with_ratatui;
mod feature_tables;
mod flat_unchanged;
mod fuzz_stable;
mod game_play_pty;
mod game_replay;
mod glyphs_cli;
mod glyphs_tmux;
mod golden;
mod heights_json;
mod heights_minimap_pty;
mod heights_play;
mod heights_reference;
mod heights_replay;
mod input_limits;
mod map_errors;
mod package_links;
mod play_colour_detect;
mod play_keys_pty;
mod play_pty;
mod play_stalled;
mod play_tmux;
mod properties;
mod ray_pane_pty;
mod readme_screenshot;
mod render_json;
mod render_scale;
mod replay;
mod replay_pty;
mod replay_sizes_pty;
mod screen_sizes;
mod texture_fallback;
mod trace_figure;
mod widgets;
mod world_cli;
mod world_doors;
mod world_golden;
mod world_lamps;
