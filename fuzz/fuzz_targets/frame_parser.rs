//! The frame parsers behind `halfcast diff` (PNG, cells text, ANSI, plain text).
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    halfcast::fuzzing::frame_parser(data);
});
