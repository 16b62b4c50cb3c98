//! The SSH server's keystroke parser.
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    halfcast::fuzzing::ssh_input(data);
});
