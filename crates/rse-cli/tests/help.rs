//! Every `--help` page, kept as text in `tests/help/`: a
//! change of the help shows in review. `RSE_UPDATE_HELP=1 cargo test -p
//! rse-cli --test cli help` writes the pages anew.

use std::path::PathBuf;
use std::process::Command;

use super::repo;

/// Every help page: the top level, each subcommand, `templates export`.
const PAGES: [&[&str]; 13] = [
    &[],
    &["heightmap"],
    &["preview"],
    &["mesh"],
    &["hfield"],
    &["batch"],
    &["atlas"],
    &["check"],
    &["check-curriculum"],
    &["contact-sheet"],
    &["edit"],
    &["templates"],
    &["templates", "export"],
];

fn help(words: &[&str]) -> String {
    let out = Command::new(env!("CARGO_BIN_EXE_rse-gen"))
        .args(words)
        .arg("--help")
        .env("COLUMNS", "100")
        .output()
        .expect("rse-gen runs");
    assert!(out.status.success(), "{words:?} --help");
    String::from_utf8(out.stdout).unwrap()
}

fn page_file(words: &[&str]) -> PathBuf {
    let name = if words.is_empty() {
        "rse-gen".to_owned()
    } else {
        words.join("-")
    };
    repo()
        .join("crates/rse-cli/tests/help")
        .join(format!("{name}.txt"))
}

#[test]
fn help_pages_are_as_kept() {
    let update = std::env::var_os("RSE_UPDATE_HELP").is_some();
    for words in PAGES {
        let text = help(words);
        let file = page_file(words);
        if update {
            std::fs::write(&file, &text).unwrap();
            continue;
        }
        let kept = std::fs::read_to_string(&file).unwrap_or_default();
        assert!(
            kept == text,
            "`rse-gen {} --help` changed; if meant, run RSE_UPDATE_HELP=1 cargo test -p rse-cli --test cli help and review tests/help/. Now:\n{text}",
            words.join(" ")
        );
    }
}

#[test]
fn every_subcommand_has_examples_and_only_its_own_flags() {
    for words in &PAGES[1..] {
        if *words == ["templates"] {
            continue; // a group: its one subcommand has the examples
        }
        let text = help(words);
        assert!(text.contains("\nExamples:\n  "), "{words:?}: no examples");
    }
    // Scheme overrides only where a scheme is read.
    for words in [&["check"][..], &["templates", "export"]] {
        assert!(
            !help(words).contains("--size"),
            "{words:?} lists scheme overrides it ignores"
        );
    }
    for words in [&["batch"][..], &["heightmap"], &["edit"], &[]] {
        assert!(help(words).contains("--step-height <M>"), "{words:?}");
    }
    let edit = help(&["edit"]);
    let port = edit
        .lines()
        .skip_while(|l| !l.contains("--port"))
        .take(2)
        .collect::<String>();
    assert_eq!(port.matches("[default:").count(), 1, "{port}");
    assert!(help(&["preview"]).contains("Pixels per cell, 1 to 256"));
}

#[test]
fn the_preview_accepts_the_pixel_range_its_help_states() {
    let dir = tempfile::tempdir().unwrap();
    let png = dir.path().join("p.png");
    let png = png.to_str().unwrap();
    for (n, ok) in [("0", false), ("1", true), ("256", true), ("257", false)] {
        let out = super::rse_gen(&["preview", "schemes/peak.csv", "-o", png, "--cell-pixels", n]);
        assert_eq!(
            out.status.success(),
            ok,
            "--cell-pixels {n}: {}",
            super::stderr(&out)
        );
    }
}

#[test]
fn flags_before_the_subcommand_still_apply_and_are_refused_where_ignored() {
    let out = super::stdout(&super::rse_gen(&[
        "--size",
        "7x3",
        "heightmap",
        "schemes/random.csv",
    ]));
    assert_eq!(out.lines().count(), 3);
    let out = super::stdout(&super::rse_gen(&[
        "--size",
        "7x3",
        "heightmap",
        "schemes/random.csv",
        "--size",
        "4x2",
    ]));
    assert_eq!(out.lines().count(), 2, "the subcommand's own flag wins");
    let out = super::rse_gen(&["check", "schemes", "--size", "5x5"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(
        super::stderr(&out).contains("unexpected argument '--size'"),
        "{}",
        super::stderr(&out)
    );
}
