//! Every refusal the page shows, in the words of someone filling in its
//! form: what is wrong and what to change, never a command-line flag, file
//! syntax (`# key: value`), Rust range syntax, an integer type's bound or
//! a system error's text. rse-core and rse-world word their errors for
//! scheme files and the command line; where the page's words differ, they
//! are here.

use std::io::ErrorKind;
use std::path::{Path, PathBuf};

use rse_core::{GlobalKey, QUOTE_CHARS, SchemeError, SchemeErrorKind, excerpt};

/// A scheme fault as the page says it (the field it concerns is marked
/// and named by the page).
pub fn scheme_fault(kind: &SchemeErrorKind) -> String {
    let text = match kind {
        SchemeErrorKind::PalletsOff => {
            "is used only with pallets: set pallets (e.g. 2x3), or empty this field".to_owned()
        }
        SchemeErrorKind::ReversedRange { lo, hi } => format!(
            "the low end {} is above the high end {}: swap them",
            quote(lo),
            quote(hi)
        ),
        SchemeErrorKind::NoteReadsAsGlobal(key) => format!(
            "a line of the notes starts with `{}:`, which a scheme file would read as a setting: reword its start",
            quote(key)
        ),
        SchemeErrorKind::UnknownGlobal(key) => format!(
            "`{}` is not a setting of a scheme; for a note, start the line with `note:`",
            quote(key)
        ),
        SchemeErrorKind::NearGlobal { found, near } => format!(
            "`{}` is not a setting of a scheme; did you mean `{near}`?",
            quote(found)
        ),
        SchemeErrorKind::NotANumber { value, expected } => format!(
            "`{}` is not {}: type one in the first field (and a larger one in the \
             second for a random range)",
            quote(value),
            page_words(expected)
        ),
        SchemeErrorKind::BadGlobal { value, reason } if reason.contains("NXxNY") => format!(
            "`{}` is not a size: type two whole numbers, columns x rows, e.g. 60x40",
            quote(value)
        ),
        other => other.to_string(),
    };
    with_labels(&text)
}

/// What a field expects, as the page says it: no `lo..hi` (the page has
/// a second field for a range's high end), no `≥`.
fn page_words(expected: &str) -> String {
    expected
        .trim_end_matches(" or a range lo..hi")
        .replace("≥ 0", "of 0 or more")
        .replace("cells ≥ 1", "cells, 1 or more")
}

/// A fault of a scheme file being opened: where in the file (line, the
/// field) and what, in the page's words.
pub fn file_fault(e: &SchemeError) -> String {
    let place = match (e.line, e.obstacle) {
        (Some(line), _) => format!("line {line}: "),
        (None, Some(obstacle)) => format!("obstacle {}: ", obstacle + 1),
        (None, None) => String::new(),
    };
    let field = e
        .field
        .as_deref()
        .map_or_else(String::new, |field| format!("{}: ", with_labels(field)));
    format!("{place}{field}{}", scheme_fault(&e.kind))
}

/// `text` with each global key spelt as the page labels it (`step
/// height`, not `step_height`).
fn with_labels(text: &str) -> String {
    GlobalKey::ALL.iter().fold(text.to_owned(), |text, key| {
        text.replace(key.name(), &key.name().replace('_', " "))
    })
}

fn quote(text: &str) -> String {
    excerpt(text, QUOTE_CHARS)
}

/// A whole number the page's `label` field holds that is not one.
pub fn not_a_whole_number(label: &str, text: &str) -> String {
    if !text.is_empty() && text.bytes().all(|b| b.is_ascii_digit()) {
        format!("the {label} `{}` is too large", quote(text))
    } else {
        format!(
            "the {label} must be a whole number of 0 or more, not `{}`",
            quote(text)
        )
    }
}

/// A failure to `action` ("open", "write", "create") `path`, in words: the
/// system's reason by its kind, never its text ("entity not found", "os
/// error 2"). A reason of rse's own (an error made with a message, no OS
/// code) is kept.
pub fn io_failure(action: &str, path: &Path, e: &std::io::Error) -> String {
    let shown = path.display();
    if e.raw_os_error().is_none() && e.get_ref().is_some() {
        return format!("cannot {action} {shown}: {e}");
    }
    match e.kind() {
        ErrorKind::NotFound => format!("cannot {action} {shown}: there is no such file or folder"),
        ErrorKind::PermissionDenied => {
            format!("cannot {action} {shown}: you are not allowed to (its permissions)")
        }
        ErrorKind::AlreadyExists => format!("cannot {action} {shown}: it exists already"),
        ErrorKind::IsADirectory => format!("cannot {action} {shown}: it is a folder"),
        ErrorKind::NotADirectory => {
            format!("cannot {action} {shown}: a part of the path is a file, not a folder")
        }
        ErrorKind::ReadOnlyFilesystem => {
            format!("cannot {action} {shown}: the disk it is on cannot be written")
        }
        ErrorKind::StorageFull | ErrorKind::QuotaExceeded => {
            format!("cannot {action} {shown}: the disk is full")
        }
        ErrorKind::InvalidFilename => format!("cannot {action} {shown}: the name is not allowed"),
        _ => format!("cannot {action} {shown}"),
    }
}

/// An error of rse-world's (a Save or a Generate) as the page says it.
pub fn world_failure(e: &rse_world::Error) -> String {
    match e {
        rse_world::Error::Io {
            action,
            path,
            source,
        } => io_failure(action, path, source),
        rse_world::Error::TooBig { message } => format!(
            "{}; use a smaller grid or fewer targets",
            message
                .strip_suffix(rse_world::FEWER_JOBS)
                .unwrap_or(message)
        ),
        rse_world::Error::Conflict { path, reason } => format!(
            "{} holds other worlds ({reason}): choose another output folder",
            path.display()
        ),
        rse_world::Error::Busy { path, .. } => format!(
            "another run is writing worlds into {} right now: wait for it to end, or choose another output folder",
            path.display()
        ),
        other => with_labels(&other.to_string()),
    }
}

/// An output folder beside `out` that does not exist yet (`out-2`,
/// `out-3`, …), offered when `out` holds other worlds.
pub fn free_folder_beside(out: &Path) -> Option<PathBuf> {
    let name = out.file_name()?.to_string_lossy().into_owned();
    (2..1000)
        .map(|n| out.with_file_name(format!("{name}-{n}")))
        .find(|candidate| !candidate.exists())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// What must never reach the page, and why: a flag, file syntax, Rust
    /// range syntax, an integer bound, a system's words, a key's spelling.
    const FORBIDDEN: [(&str, &str); 11] = [
        (" --", "a command-line flag"),
        ("rse-gen ", "a command"),
        ("`# ", "scheme-file syntax"),
        ("..=", "Rust range syntax"),
        ("18446744073709551615", "an integer type's bound"),
        ("os error", "a system error's text"),
        ("entity not found", "a system error's text"),
        ("No such file", "a system error's text"),
        ("Permission denied", "a system error's text"),
        ("step_height", "a key's spelling"),
        ("pallet_size", "a key's spelling"),
    ];

    fn assert_in_page_words(text: &str) {
        for (bad, what) in FORBIDDEN {
            assert!(!text.contains(bad), "{what} (`{bad}`) in {text:?}");
        }
    }

    #[test]
    fn every_scheme_fault_is_in_page_words() {
        for kind in SchemeErrorKind::examples() {
            assert_in_page_words(&scheme_fault(&kind));
        }
        assert_eq!(
            scheme_fault(&SchemeErrorKind::PalletsOff),
            "is used only with pallets: set pallets (e.g. 2x3), or empty this field"
        );
    }

    #[test]
    fn system_errors_are_said_by_kind() {
        for kind in [
            ErrorKind::NotFound,
            ErrorKind::PermissionDenied,
            ErrorKind::AlreadyExists,
            ErrorKind::IsADirectory,
            ErrorKind::NotADirectory,
            ErrorKind::ReadOnlyFilesystem,
            ErrorKind::StorageFull,
            ErrorKind::Other,
        ] {
            let text = io_failure("write", Path::new("a/b.csv"), &std::io::Error::from(kind));
            assert_in_page_words(&text);
            assert!(text.starts_with("cannot write a/b.csv"), "{text}");
        }
        let os = std::io::Error::from_raw_os_error(2);
        assert_eq!(
            io_failure("open", Path::new("x.csv"), &os),
            "cannot open x.csv: there is no such file or folder"
        );
    }

    #[test]
    fn whole_numbers_are_refused_without_a_bound() {
        assert_in_page_words(&not_a_whole_number("index", "-1"));
        assert_in_page_words(&not_a_whole_number("index", "99999999999999999999999"));
    }
}
