//! SHA-256 digests as `rse.json` records them: lower-case hex.

use sha2::{Digest, Sha256};

/// The SHA-256 of `bytes` as lower-case hex.
pub fn sha256_hex(bytes: &[u8]) -> String {
    hex(&Sha256::digest(bytes))
}

/// A finished digest as lower-case hex (also of a hash computed as a file
/// streams, `OpenFolder::digest`).
pub(crate) fn hex(digest: &[u8]) -> String {
    digest.iter().fold(String::with_capacity(64), |mut s, b| {
        use std::fmt::Write as _;
        write!(s, "{b:02x}").expect("writing to a String cannot fail");
        s
    })
}
