//! The editor's memory of each document, kept by the server in its own
//! state folder: the page's draft (unsaved scheme and undo history) of each
//! scheme file and of each scheme in no file yet (New, a sample, a file
//! from the browser's computer: `unnamed:ID`), the document the page was on
//! last for each file the editor starts on, and the port it last served
//! that file on. A draft in the browser belongs to one origin (one port);
//! here it belongs to the document, so any port, any reload, any browser
//! and any restart find it. Each draft has a revision: a tab that writes
//! over a draft another tab wrote since it read it is told, not obeyed.

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
        if let Some(id) = unnamed_id(file) {
            let here = std::env::current_dir().unwrap_or_else(|_| PathBuf::from("."));
            return format!("{} (unnamed {id})", here.display());
        }
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

    /// `file`'s draft and its revision (0: none kept).
    pub fn load_revised(&self, file: &str) -> (Option<Value>, u64) {
        let Kept {
            draft, revision, ..
        } = self.kept(file);
        (draft, revision)
    }

    /// `file`'s draft entry, read once: the draft, its revision and the
    /// tab that wrote it.
    fn kept(&self, file: &str) -> Kept {
        let mut entry = self.read_entry("drafts", file).unwrap_or(Value::Null);
        Kept {
            draft: entry.get_mut("draft").map(Value::take),
            revision: entry.get("revision").and_then(Value::as_u64).unwrap_or(0),
            tab: entry
                .get("tab")
                .and_then(Value::as_str)
                .unwrap_or_default()
                .to_owned(),
        }
    }

    /// Keeps `draft` as `file`'s (written whole or not at all).
    ///
    /// # Errors
    /// When the state folder or its file cannot be written.
    pub fn store(&self, file: &str, draft: &Value) -> Result<(), rse_world::Error> {
        self.write("drafts", file, "draft", draft)
    }

    /// Keeps `draft` as `file`'s, written by the tab `tab` from the draft of
    /// revision `base` it read or wrote last, as revision `base + 1`, or
    /// older. Another tab's draft written since (a later revision by
    /// another tab) is not overwritten: the answer is that draft and its
    /// revision, for the page to offer both. `force` overwrites it (the
    /// user chose this tab's).
    ///
    /// # Errors
    /// When the state folder or its file cannot be written.
    pub fn store_revised(
        &self,
        file: &str,
        draft: &Value,
        tab: &str,
        base: u64,
        force: bool,
    ) -> Result<Stored, rse_world::Error> {
        let Kept {
            draft: theirs,
            revision,
            tab: writer,
        } = self.kept(file);
        if let Some(theirs) = theirs
            && revision > base
            && writer != tab
            && !force
        {
            return Ok(Stored::Conflict { theirs, revision });
        }
        let revision = revision.max(base) + 1;
        let entry = self.entry("drafts", file);
        let kept = serde_json::json!({
            "file": Self::identity(file),
            "draft": draft,
            "revision": revision,
            "tab": tab,
        });
        write_entry(&entry, &kept)?;
        Ok(Stored::Kept { revision })
    }

    /// The document the page was on last when the editor started on
    /// `start` (a file, or "": none), if any.
    pub fn current(&self, start: &str) -> Option<String> {
        self.read("current", start, "document")?
            .as_str()
            .map(str::to_owned)
    }

    /// Remembers that the page started on `start` is on `document` now.
    ///
    /// # Errors
    /// When the state folder or its file cannot be written.
    pub fn set_current(&self, start: &str, document: &str) -> Result<(), rse_world::Error> {
        self.write("current", start, "document", &Value::from(document))
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
        self.read_entry(kind, file)?.get_mut(field).map(Value::take)
    }

    /// `file`'s whole entry of `kind`, if it is `file`'s.
    fn read_entry(&self, kind: &str, file: &str) -> Option<Value> {
        let text = std::fs::read(self.entry(kind, file)).ok()?;
        let kept: Value = serde_json::from_slice(&text).ok()?;
        (kept.get("file")?.as_str()? == Self::identity(file)).then_some(kept)
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

/// A draft entry as read: the draft, its revision and its writer.
struct Kept {
    draft: Option<Value>,
    revision: u64,
    tab: String,
}

/// What [`Drafts::store_revised`] did.
#[derive(Debug, Clone, PartialEq)]
pub enum Stored {
    /// Kept as this revision.
    Kept {
        /// The revision the tab writes from next.
        revision: u64,
    },
    /// Not kept: another tab wrote this draft since.
    Conflict {
        /// The other tab's draft.
        theirs: Value,
        /// Its revision (a forced write goes over it).
        revision: u64,
    },
}

/// The id of a document in no file yet (`unnamed:ID`, ID of letters,
/// digits and `-`, at most 64), or None.
pub fn unnamed_id(document: &str) -> Option<&str> {
    let id = document.strip_prefix("unnamed:")?;
    (!id.is_empty() && id.len() <= 64 && id.chars().all(|c| c.is_ascii_alphanumeric() || c == '-'))
        .then_some(id)
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

    /// Two tabs on one draft: each writes over its own, never over the
    /// other's written since it read it, unless told to.
    #[test]
    fn a_tab_never_overwrites_another_tabs_later_draft_unasked() {
        let state = tempfile::tempdir().unwrap();
        let drafts = Drafts::new(state.path().to_path_buf());
        let doc = "unnamed:abc-1";
        let kept = |s: Stored| match s {
            Stored::Kept { revision } => revision,
            Stored::Conflict { .. } => panic!("{s:?}"),
        };
        let a1 = kept(
            drafts
                .store_revised(doc, &json!({"s": "a1"}), "A", 0, false)
                .unwrap(),
        );
        let a2 = kept(
            drafts
                .store_revised(doc, &json!({"s": "a2"}), "A", a1, false)
                .unwrap(),
        );
        // B read a2, then wrote.
        let b1 = kept(
            drafts
                .store_revised(doc, &json!({"s": "b1"}), "B", a2, false)
                .unwrap(),
        );
        // A still writes from a2: told of B's.
        let conflict = drafts
            .store_revised(doc, &json!({"s": "a3"}), "A", a2, false)
            .unwrap();
        assert_eq!(
            conflict,
            Stored::Conflict {
                theirs: json!({"s": "b1"}),
                revision: b1
            }
        );
        assert_eq!(drafts.load(doc), Some(json!({"s": "b1"})));
        // A keeps its own, on purpose.
        kept(
            drafts
                .store_revised(doc, &json!({"s": "a3"}), "A", b1, true)
                .unwrap(),
        );
        assert_eq!(drafts.load(doc), Some(json!({"s": "a3"})));
        // Unnamed documents and files are apart; the current one is kept per start file.
        assert_eq!(drafts.load("unnamed:other"), None);
        drafts.set_current("x.csv", doc).unwrap();
        assert_eq!(drafts.current("x.csv").as_deref(), Some(doc));
        assert_eq!(drafts.current("y.csv"), None);
        assert_eq!(unnamed_id("unnamed:../x"), None);
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
