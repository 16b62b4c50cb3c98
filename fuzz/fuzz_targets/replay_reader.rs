//! The .hcr replay reader.
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    halfcast::fuzzing::replay_reader(data);
});
