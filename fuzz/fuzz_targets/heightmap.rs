//! Fuzz target: `rse_fuzz::heightmap`.
#![no_main]
libfuzzer_sys::fuzz_target!(|data: &[u8]| rse_fuzz::heightmap(data));
