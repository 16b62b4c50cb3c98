//! `halfcast serve` end to end: russh clients (and OpenSSH's `ssh` where installed) joining,
//! playing, being refused and disconnecting, and the inputs a hostile user controls (FIFOs,
//! floods of frames). One binary, so the support code and the link are paid once.

#[path = "../support/common/mod.rs"]
#[allow(dead_code)] // each test binary uses its own part of the shared helpers
mod common;
#[path = "../support/serve_process/mod.rs"]
mod serve_process;
#[path = "../support/serve_support/mod.rs"]
mod serve_support;
#[path = "../support/world_common/mod.rs"]
#[allow(dead_code)] // each test binary uses its own part of the shared world helpers
mod world_common;

mod game_serve;
mod input_hardening;
mod scores_json;
mod serve_abuse;
mod serve_auth;
mod serve_backup;
mod serve_browser;
mod serve_churn;
mod serve_cli;
mod serve_colour;
mod serve_colour_answerback;
mod serve_compression;
mod serve_drain;
mod serve_fleet;
mod serve_flood;
mod serve_glyphs;
mod serve_haproxy;
mod serve_health;
mod serve_json_log;
mod serve_metrics;
mod serve_names;
mod serve_openssh;
mod serve_openssh_colour;
mod serve_openssh_limits;
mod serve_pg_outage;
mod serve_postgres;
mod serve_proxy;
mod serve_putty;
mod serve_ray_debugger;
mod serve_refusals;
mod serve_rotation;
mod serve_session;
mod serve_shared_board;
mod serve_slow_link;
mod serve_stall;
mod serve_web;
mod serve_web_haproxy;
