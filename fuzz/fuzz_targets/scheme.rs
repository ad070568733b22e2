//! Fuzz target: `rse_fuzz::scheme`.
#![no_main]
libfuzzer_sys::fuzz_target!(|data: &[u8]| rse_fuzz::scheme(data));
