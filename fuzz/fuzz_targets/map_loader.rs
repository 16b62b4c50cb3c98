//! The map loader (parse, then load with embedded textures and bake lights).
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    halfcast::fuzzing::map_loader(data);
});
