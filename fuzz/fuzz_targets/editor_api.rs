//! Fuzz target: `rse_fuzz::editor_api`.
#![no_main]
libfuzzer_sys::fuzz_target!(|data: &[u8]| rse_fuzz::editor_api(data));
