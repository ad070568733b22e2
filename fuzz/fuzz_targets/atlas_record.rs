//! Fuzz target: `rse_fuzz::atlas_record`.
#![no_main]
libfuzzer_sys::fuzz_target!(|data: &[u8]| rse_fuzz::atlas_record(data));
