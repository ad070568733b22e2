//! Fuzz target: `rse_fuzz::obj`.
#![no_main]
libfuzzer_sys::fuzz_target!(|data: &[u8]| rse_fuzz::obj(data));
