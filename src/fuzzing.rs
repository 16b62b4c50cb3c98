//! Fuzz targets: one function per untrusted-input parser, shared by the cargo-fuzz targets in
//! `fuzz/` (nightly, coverage-guided) and the stable mutation loop in `tests/fuzz_stable.rs`,
//! so both drive exactly the same code.
//!
//! Each target takes arbitrary bytes and panics only when an invariant breaks (a refused input
//! is fine; a panic, a wrong-sized result or an error without its file name is a finding).

use crate::map::parse_map;
use crate::replay::Replay;
use crate::termframe::{parse_frame, TermFrame, MAX_FRAME};
use crate::ui::key_bytes::{InputParser, MAX_SEQUENCE};
use crate::world::{TextureSource, World};

/// The file name the map and replay targets parse under; every error must name it.
pub const FUZZ_FILE: &str = "fuzz.input";

/// The map loader: parse, then (when valid) load with the embedded textures and bake its lights.
///
/// Returns whether the input was accepted (the stable loop counts them, to show how deep the
/// mutants reach).
///
/// # Panics
/// On a finding: an error that does not name its file.
pub fn map_loader(data: &[u8]) -> bool {
    match parse_map(FUZZ_FILE, data) {
        Ok(map) => {
            let loaded = World::load(map, &TextureSource::Embedded, false);
            assert!(loaded.is_ok(), "non-strict loading never fails");
            true
        }
        Err(e) => {
            let msg = e.to_string();
            assert!(msg.starts_with(FUZZ_FILE), "error without its file: {msg}");
            false
        }
    }
}

/// The `.hcr` replay reader.
///
/// Returns whether the input was accepted.
///
/// # Panics
/// On a finding: an error without its file, or more frames than the format allows.
pub fn replay_reader(data: &[u8]) -> bool {
    let Ok(text) = std::str::from_utf8(data) else {
        return false;
    };
    match Replay::parse(FUZZ_FILE, text) {
        Ok(r) => {
            assert!(r.frames.len() <= crate::replay::MAX_FRAMES);
            true
        }
        Err(e) => {
            let msg = e.to_string();
            assert!(msg.starts_with(FUZZ_FILE), "error without its file: {msg}");
            false
        }
    }
}

fn check_frame(f: &TermFrame) {
    assert!(
        f.cols <= MAX_FRAME.0 && f.rows <= MAX_FRAME.1,
        "frame over the limit"
    );
    assert_eq!(
        f.cells.len(),
        f.cols * f.rows,
        "cells do not fill the frame"
    );
}

/// The frame parsers behind `halfcast diff`: PNG, cells text, ANSI (through the terminal
/// model) and plain text.
///
/// Returns whether the input was accepted.
///
/// # Panics
/// On a finding: a frame over [`MAX_FRAME`] or whose cells do not match its size.
pub fn frame_parser(data: &[u8]) -> bool {
    parse_frame(data)
        .map(|(frame, _)| check_frame(&frame))
        .is_ok()
}

/// The SSH server's keystroke parser, fed in pieces split where the first byte says.
///
/// Returns whether the input produced any event.
///
/// # Panics
/// On a finding: an unfinished sequence buffered beyond [`MAX_SEQUENCE`] bytes.
pub fn ssh_input(data: &[u8]) -> bool {
    let split = data.first().map_or(1, |&b| usize::from(b % 16) + 1);
    let mut parser = InputParser::new();
    let mut events = Vec::new();
    for chunk in data.chunks(split) {
        parser.feed(chunk, &mut events);
        // The parser keeps its tail private; its debug form lists the pending bytes, which is
        // enough to see that an unfinished sequence stays bounded.
        let pending = if parser.has_pending() {
            format!("{parser:?}").matches(',').count() + 1
        } else {
            0
        };
        assert!(
            pending <= MAX_SEQUENCE,
            "{pending} bytes pending after a read"
        );
    }
    parser.flush(&mut events);
    assert!(!parser.has_pending());
    assert!(events.len() <= data.len() + 1);
    !events.is_empty()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_target_accepts_empty_and_garbage_input() {
        for data in [&b""[..], b"\x1b[", b"\xff\xfe", b"NO x\n1\n"] {
            map_loader(data);
            replay_reader(data);
            frame_parser(data);
            ssh_input(data);
        }
    }

    #[test]
    fn the_bugs_found_before_now_refuse_cleanly() {
        frame_parser(b"\x1b[65535;65535Hx");
        frame_parser(b"\x1b[10000;10000Hx");
        frame_parser(b"halfcast-cells v1 17216961135462248175x1\n\n");
        frame_parser(b"halfcast-cells v2 17216961135462248175x1\n\n");
        frame_parser(b"halfcast-cells v2 1x1\n\"a\"\nstyles:\ny0 x0-18446744073709551615 bold\n");
    }
}
