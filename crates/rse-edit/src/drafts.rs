//! The editor's memory of each scheme file, kept by the server in its own
//! state folder: the page's draft (unsaved scheme and undo history) and the
//! port the editor last served the file on. A draft in the browser belongs
//! to one origin (one port); here it belongs to the file, so any port, any
//! reload and any browser find it.

use std::path::{Path, PathBuf};

use serde_json::Value;

/// The state folder and what it keeps per file (one JSON file each,
/// named by a hash of the scheme file's absolute path).
#[derive(Debug, Clone)]
pub struct Drafts {
    folder: PathBuf,
}

impl Drafts {
    /// Drafts kept under `folder` (made when the first is written).
    pub fn new(folder: PathBuf) -> Self {
        Self { folder }
    }

    /// What identifies `file` across runs: its absolute path, its links
    /// resolved when it exists (two spellings of one file share a draft).
    /// A scheme in no file yet ("") is the one of the folder the editor
    /// runs in.
    fn identity(file: &str) -> String {
        let path = if file.is_empty() {
            std::env::current_dir().map_or_else(|_| PathBuf::from("."), |d| d.join("(unnamed)"))
        } else {
            let given = Path::new(file);
            given
                .canonicalize()
                .or_else(|_| std::path::absolute(given))
                .unwrap_or_else(|_| given.to_path_buf())
        };
        path.to_string_lossy().into_owned()
    }

    fn entry(&self, kind: &str, file: &str) -> PathBuf {
        let digest = rse_world::sha256_hex(Self::identity(file).as_bytes());
        self.folder
            .join(kind)
            .join(format!("{}.json", &digest[..24]))
    }

    /// `file`'s draft as the page last stored it, or None.
    pub fn load(&self, file: &str) -> Option<Value> {
        self.read("drafts", file, "draft")
    }

    /// Keeps `draft` as `file`'s (written whole or not at all).
    ///
    /// # Errors
    /// When the state folder or its file cannot be written.
    pub fn store(&self, file: &str, draft: &Value) -> Result<(), rse_world::Error> {
        self.write("drafts", file, "draft", draft)
    }

    /// Forgets `file`'s draft (it was saved or discarded).
    pub fn forget(&self, file: &str) {
        // Nothing there is the same as forgotten.
        let _ = std::fs::remove_file(self.entry("drafts", file));
    }

    /// The port the editor last served `file` on, if any.
    pub fn last_port(&self, file: &str) -> Option<u16> {
        u16::try_from(self.read("ports", file, "port")?.as_u64()?).ok()
    }

    /// Remembers that `file` is served on `port`.
    ///
    /// # Errors
    /// When the state folder or its file cannot be written.
    pub fn remember_port(&self, file: &str, port: u16) -> Result<(), rse_world::Error> {
        self.write("ports", file, "port", &Value::from(port))
    }

    /// The `field` of `file`'s entry of `kind`, or None. The entry names its
    /// file: a hash collision never hands over another file's.
    fn read(&self, kind: &str, file: &str, field: &str) -> Option<Value> {
        let text = std::fs::read(self.entry(kind, file)).ok()?;
        let mut kept: Value = serde_json::from_slice(&text).ok()?;
        (kept.get("file")?.as_str()? == Self::identity(file))
            .then(|| kept.get_mut(field).map(Value::take))?
    }

    /// Writes `file`'s entry of `kind` holding `value` as its `field`.
    fn write(
        &self,
        kind: &str,
        file: &str,
        field: &str,
        value: &Value,
    ) -> Result<(), rse_world::Error> {
        let entry = self.entry(kind, file);
        let mut kept = serde_json::json!({ "file": Self::identity(file) });
        kept[field] = value.clone();
        write_entry(&entry, &kept)
    }
}

fn write_entry(entry: &Path, value: &Value) -> Result<(), rse_world::Error> {
    if let Some(parent) = entry.parent() {
        std::fs::create_dir_all(parent).map_err(|source| rse_world::Error::Io {
            action: "create",
            path: parent.to_path_buf(),
            source,
        })?;
    }
    rse_world::write_atomically(entry, value.to_string().as_bytes())
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde_json::json;

    #[test]
    fn a_draft_is_kept_per_file_and_forgotten() {
        let state = tempfile::tempdir().unwrap();
        let files = tempfile::tempdir().unwrap();
        let a = files.path().join("a.csv");
        let b = files.path().join("b.csv");
        std::fs::write(&a, "").unwrap();
        let drafts = Drafts::new(state.path().to_path_buf());
        let (a, b) = (a.to_str().unwrap(), b.to_str().unwrap());
        assert_eq!(drafts.load(a), None);
        drafts.store(a, &json!({ "scheme": 1 })).unwrap();
        drafts.store(b, &json!({ "scheme": 2 })).unwrap();
        assert_eq!(drafts.load(a), Some(json!({ "scheme": 1 })));
        assert_eq!(drafts.load(b), Some(json!({ "scheme": 2 })));
        drafts.forget(a);
        assert_eq!(drafts.load(a), None);
        assert_eq!(drafts.load(b), Some(json!({ "scheme": 2 })));
    }

    #[test]
    fn ports_are_remembered_per_file() {
        let state = tempfile::tempdir().unwrap();
        let drafts = Drafts::new(state.path().to_path_buf());
        assert_eq!(drafts.last_port("x.csv"), None);
        drafts.remember_port("x.csv", 41234).unwrap();
        drafts.remember_port("y.csv", 41235).unwrap();
        assert_eq!(drafts.last_port("x.csv"), Some(41234));
        assert_eq!(drafts.last_port("y.csv"), Some(41235));
    }
}
