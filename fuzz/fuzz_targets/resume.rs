//! Fuzz target: `rse_fuzz::resume`.
#![no_main]
libfuzzer_sys::fuzz_target!(|data: &[u8]| rse_fuzz::resume(data));
