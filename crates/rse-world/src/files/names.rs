//! What a world may be named. A world's name is its folder's name, and it
//! is written into every simulator file: XML attributes and comments
//! (SDF, MJCF, URDF, `model.config`), Webots and USD strings. Escaping
//! cannot make every such place safe (`--` may not appear in an XML
//! comment at all), so a name is one of a few plain characters, or it is
//! refused before anything is built — from the command line, Python and a
//! forged `rse.json` alike.

/// The longest world name, bytes.
pub const MAX_WORLD_NAME: usize = 128;

/// Why `name` cannot name a world, or `None` when it can: 1 to
/// [`MAX_WORLD_NAME`] ASCII letters, digits, `_`, `-` and `.`, neither
/// first character `.` or `-`, and no `--`.
pub fn world_name_problem(name: &str) -> Option<String> {
    let allowed = |c: char| c.is_ascii_alphanumeric() || matches!(c, '_' | '-' | '.');
    let plain = !name.is_empty()
        && name.len() <= MAX_WORLD_NAME
        && name.chars().all(allowed)
        && !name.starts_with(['.', '-'])
        && !name.contains("--");
    (!plain).then(|| {
        format!(
            "\"{}\" cannot name a world: the name is written into SDF, MJCF, URDF, Webots and USD \
             files, so it must be 1 to {MAX_WORLD_NAME} letters, digits, '_', '-' and '.' \
             (not '.' or '-' first, no '--')",
            name.escape_debug()
        )
    })
}

#[cfg(test)]
mod tests {
    use super::world_name_problem;

    #[test]
    fn plain_names_pass_and_markup_does_not() {
        for good in ["world_0007", "atlas", "my-atlas.v2", "A1"] {
            assert_eq!(world_name_problem(good), None, "{good}");
        }
        let long = "a".repeat(129);
        for bad in [
            "", "a\"--><b", "a--b", "-a", ".hidden", "a b", "a/b", "é", "a\u{1b}b", &long,
        ] {
            assert!(world_name_problem(bad).is_some(), "{bad:?}");
        }
        let said = world_name_problem("a\"--><b\u{7}").unwrap();
        assert!(
            said.starts_with(r#""a\"--><b\u{7}" cannot name a world"#),
            "{said}"
        );
    }
}
