//! SHA-256 digests as `rse.json` records them: lower-case hex.

use sha2::{Digest, Sha256};

/// The SHA-256 of `bytes` as lower-case hex.
pub fn sha256_hex(bytes: &[u8]) -> String {
    Sha256::digest(bytes)
        .iter()
        .fold(String::with_capacity(64), |mut s, b| {
            use std::fmt::Write as _;
            write!(s, "{b:02x}").expect("writing to a String cannot fail");
            s
        })
}
