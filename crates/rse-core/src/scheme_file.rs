//! Reading a scheme file from disk: a regular file only, never more than
//! [`MAX_SCHEME_BYTES`], counted while it is read. A FIFO would block the
//! reader for good (the editor's Open held a worker thread), and a device
//! such as `/dev/zero` reports size 0 and never ends.

use std::io::Read as _;
use std::path::Path;

/// The largest scheme file read (16 MiB): far above any table a person
/// writes (200,000 obstacles take 1.8 MB), and the most a world's
/// `rse.json`, which records the scheme, may hold.
pub const MAX_SCHEME_BYTES: u64 = 16 << 20;

/// The bytes of the scheme file at `path` (links followed, as a user's
/// path means): refused unless it is a regular file of at most
/// [`MAX_SCHEME_BYTES`] as read. Opened without blocking, so a FIFO
/// answers at once, then checked on the open descriptor.
pub fn read_scheme_file(path: &Path) -> std::io::Result<Vec<u8>> {
    let file = open_without_blocking(path)?;
    if !file.metadata()?.is_file() {
        return Err(std::io::Error::new(
            std::io::ErrorKind::InvalidInput,
            "not a regular file (a FIFO, device, socket or folder)",
        ));
    }
    let mut bytes = Vec::new();
    file.take(MAX_SCHEME_BYTES + 1).read_to_end(&mut bytes)?;
    if bytes.len() as u64 > MAX_SCHEME_BYTES {
        return Err(std::io::Error::new(
            std::io::ErrorKind::InvalidData,
            format!(
                "larger than any scheme ({} MiB at most)",
                MAX_SCHEME_BYTES >> 20
            ),
        ));
    }
    Ok(bytes)
}

/// Opens `path` to read with `O_NONBLOCK` where there is one: opening a
/// FIFO with no writer returns at once (the regular-file test then refuses
/// it); a regular file reads as ever.
fn open_without_blocking(path: &Path) -> std::io::Result<std::fs::File> {
    let mut options = std::fs::OpenOptions::new();
    options.read(true);
    #[cfg(unix)]
    {
        use std::os::unix::fs::OpenOptionsExt as _;
        options.custom_flags(rustix::fs::OFlags::NONBLOCK.bits() as i32);
    }
    options.open(path)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_regular_file_is_read_and_anything_else_refused() {
        let tmp = tempfile::tempdir().unwrap();
        let dir = tmp.path().to_path_buf();
        let csv = dir.join("a.csv");
        std::fs::write(&csv, "type,height\nrandom,1\n").unwrap();
        assert_eq!(read_scheme_file(&csv).unwrap(), b"type,height\nrandom,1\n");
        let folder = read_scheme_file(&dir).unwrap_err();
        assert_eq!(folder.kind(), std::io::ErrorKind::InvalidInput, "{folder}");
        #[cfg(target_os = "linux")]
        {
            // A device of size 0 that never ends.
            let zero = read_scheme_file(Path::new("/dev/zero")).unwrap_err();
            assert_eq!(zero.kind(), std::io::ErrorKind::InvalidInput, "{zero}");
            // A FIFO with no writer: refused at once, not waited on.
            let fifo = dir.join("f.csv");
            rustix::fs::mknodat(
                rustix::fs::CWD,
                &fifo,
                rustix::fs::FileType::Fifo,
                rustix::fs::Mode::RUSR | rustix::fs::Mode::WUSR,
                0,
            )
            .unwrap();
            let error = read_scheme_file(&fifo).unwrap_err();
            assert_eq!(error.kind(), std::io::ErrorKind::InvalidInput, "{error}");
        }
        let big = dir.join("big.csv");
        std::fs::write(&big, vec![b'#'; (MAX_SCHEME_BYTES + 1) as usize]).unwrap();
        let error = read_scheme_file(&big).unwrap_err();
        assert!(
            error.to_string().contains("larger than any scheme"),
            "{error}"
        );
    }
}
