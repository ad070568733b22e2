//! Scheme CSV: reading, aliases, canonical writing, and every refusal of docs/schemes.md.

use rse_core::{
    Globals, Obstacle, ObstacleFields, ObstacleKind, Param, Scheme, SchemeError, SchemeErrorKind,
};

use crate::util::scheme;

fn refuse(text: &str) -> SchemeError {
    match Scheme::from_csv(text, Some("bad.csv")) {
        Ok(s) => panic!("accepted:\n{text}\nas {s:?}"),
        Err(e) => e,
    }
}

/// Asserts the error's place (line, column, field) and that its text names them.
fn assert_at(error: &SchemeError, line: u64, column: Option<u64>, field: &str) {
    assert_eq!(error.file.as_deref(), Some("bad.csv"), "{error}");
    assert_eq!(error.line, Some(line), "{error}");
    assert_eq!(error.column, column, "{error}");
    assert_eq!(error.field.as_deref(), Some(field), "{error}");
    let text = error.to_string();
    let place = match column {
        Some(c) => format!("bad.csv:{line}:{c}: {field}: "),
        None => format!("bad.csv:{line}: {field}: "),
    };
    assert!(
        text.starts_with(&place),
        "{text:?} should start with {place:?}"
    );
}

const HEAD: &str = "# size: 20x10\ntype,height,angle,x1,y1,x2,y2\n";

#[test]
fn reads_the_spec_example() {
    let s = scheme(
        "# size: 50x50\n# block_size: 0.1\n# step_height: 0.1\n\
         type,height,angle,x1,y1,x2,y2\nrandom,2,,,,,\nwall,4,45,5,5,40,5\n\
         peak,3,30,10..40,10..40,,\nlong_pit,2,90,25,0,25,49\n",
    );
    assert_eq!(s.globals().size, [50, 50]);
    let kinds: Vec<_> = s.obstacles().iter().map(Obstacle::kind).collect();
    let expected = [
        ObstacleKind::Random,
        ObstacleKind::Wall,
        ObstacleKind::Peak,
        ObstacleKind::LongPit,
    ];
    assert_eq!(kinds, expected);
    assert_eq!(s.obstacles()[2].fields().x1, Some(Param::Range(10, 40)));
    assert_eq!(s.obstacles()[1].fields().angle, Some(Param::Fixed(45.0)));
}

#[test]
fn columns_by_name_in_any_order_with_aliases_and_case() {
    let a = scheme(&format!("{HEAD}Long Pit,2,90,1,1,5,1\nNORMAL,3,,,,,\n"));
    let b = scheme(
        "# size: 20x10\ny2,X2,y1,x1,Angle,Height,TYPE\n1,5,1,1,90,2,long_pit\n,,,,,3,gaussian\n",
    );
    assert_eq!(a, b);
    assert_eq!(a.obstacles()[1].kind(), ObstacleKind::Gaussian);
}

#[test]
fn missing_trailing_fields_blank_rows_and_table_comments_are_fine() {
    let s = scheme(
        "# size: 20x10\ntype,height,angle,x1,y1,x2,y2\nrandom,2\n,,,,,,\n# a comment\n\npeak,1,45,3,3\n",
    );
    assert_eq!(s.obstacles().len(), 2);
}

#[test]
fn byte_order_mark_and_crlf_are_accepted() {
    let s = scheme("\u{feff}# size: 20x10\r\ntype,height\r\nrandom,2\r\n");
    assert_eq!(s.globals().size, [20, 10]);
    assert_eq!(s.obstacles().len(), 1);
}

#[test]
fn canonical_text_round_trips_exactly() {
    let text = "# Figure 9 of the paper - a note\n\
                # pallets: 2x3\n# pallet_size: 3\n# pallet_boundary: false\n\
                # block_size: 0.05\n# step_height: 0.025\n# base: 0.02\n# amount: 40\n# seed: 18446744073709551615\n\
                type,height,angle,x1,y1,x2,y2,sigma\n\
                random,1..3,,,,,,\ngaussian,4,,,,,,0.7..1.3\n\
                wall,4,22.5,0..2,1,5,3..8,\nlong_pit,2,90,3,0,3,8,\npit,1,33.3..60,4,4,,,\n";
    let s = scheme(text);
    assert_eq!(s.to_csv(), text);
    assert_eq!(scheme(&s.to_csv()), s);
}

#[test]
fn saving_writes_canonical_spelling_of_the_same_table() {
    let s = scheme(
        "# size: 20x10\nTYPE, height ,x1,y1,angle,x2,y2\nLONG PIT,2,1,1,90,5,1\nNormal,3,,,,,\n",
    );
    assert_eq!(
        s.to_csv(),
        "# size: 20x10\n# block_size: 0.1\n# step_height: 0.1\ntype,height,angle,x1,y1,x2,y2\n\
         long_pit,2,90,1,1,5,1\ngaussian,3,,,,,\n"
    );
    assert_eq!(scheme(&s.to_csv()), s);
}

#[test]
fn obstacles_built_in_code_match_the_file() {
    let fields = ObstacleFields {
        height: Some(Param::Fixed(3)),
        angle: Some(Param::Range(30.0, 60.0)),
        x1: Some(Param::Fixed(4)),
        y1: Some(Param::Range(2, 6)),
        ..ObstacleFields::default()
    };
    let globals = Globals {
        size: [20, 10],
        ..Globals::default()
    };
    let built = Scheme::new(
        globals,
        vec![Obstacle::new(ObstacleKind::Peak, fields).unwrap()],
    )
    .unwrap();
    let read = scheme("# size: 20x10\ntype,height,angle,x1,y1\npeak,3,30..60,4,2..6\n");
    assert_eq!(built, read);
    assert_eq!(scheme(&built.to_csv()), built);
}

#[test]
fn unknown_type() {
    let e = refuse(&format!("{HEAD}random,2,,,,,\nhill,2,,,,,\n"));
    assert_at(&e, 4, Some(1), "type");
    assert!(matches!(e.kind, SchemeErrorKind::UnknownType(ref t) if t == "hill"));
}

#[test]
fn unknown_column() {
    let e = refuse("# size: 20x10\ntype,height,colour\nrandom,2,red\n");
    assert_at(&e, 2, Some(3), "colour");
    assert!(matches!(e.kind, SchemeErrorKind::UnknownColumn(_)));
}

#[test]
fn duplicate_column() {
    let e = refuse("type,height,height\nrandom,2,2\n");
    assert_at(&e, 1, Some(3), "height");
}

#[test]
fn header_without_type() {
    let e = refuse("height,angle\n2,45\n");
    assert_eq!(e.line, Some(1));
    assert_eq!(e.kind, SchemeErrorKind::MissingTypeColumn);
}

#[test]
fn missing_required_field() {
    let e = refuse(&format!("{HEAD}wall,3,45,1,1,,4\n"));
    assert_at(&e, 3, Some(6), "x2");
    assert_eq!(e.kind, SchemeErrorKind::MissingField("wall"));
    // A column left out of the header is missing too, with no column number.
    let e = refuse("# size: 20x10\ntype,height,x1,y1\npeak,3,1,1\n");
    assert_at(&e, 3, None, "angle");
    let e = refuse(&format!("{HEAD},3,45,1,1,,\n"));
    assert_at(&e, 3, Some(1), "type");
}

#[test]
fn field_the_type_does_not_use() {
    let e = refuse(&format!("{HEAD}random,3,45,,,,\n"));
    assert_at(&e, 3, Some(3), "angle");
    assert_eq!(e.kind, SchemeErrorKind::UnusedField("random"));
}

#[test]
fn non_numbers() {
    for (row, column, field) in [
        ("peak,three,45,1,1,,", 2, "height"),
        ("peak,3,steep,1,1,,", 3, "angle"),
        ("peak,3,45,1.5,1,,", 4, "x1"),
        ("peak,3,45,1,1..z,,", 5, "y1"),
        ("peak,3,NaN,1,1,,", 3, "angle"),
        ("peak,2.5,45,1,1,,", 2, "height"),
    ] {
        let e = refuse(&format!("{HEAD}{row}\n"));
        assert_at(&e, 3, Some(column), field);
        assert!(matches!(e.kind, SchemeErrorKind::NotANumber { .. }), "{e}");
    }
}

#[test]
fn negative_and_too_large_heights() {
    let e = refuse(&format!("{HEAD}random,-2,,,,,\n"));
    assert_at(&e, 3, Some(2), "height");
    assert_eq!(e.kind, SchemeErrorKind::NegativeHeight(-2));
    let e = refuse(&format!("{HEAD}random,0..70000,,,,,\n"));
    assert_eq!(e.kind, SchemeErrorKind::HeightTooLarge(70000));
}

/// Once accepted, and `check` then failed the worlds: a wall 6,553 m tall
/// and 0.1 m wide has corners within one f32 unit of its other edges.
#[test]
fn heights_too_tall_for_an_exact_mesh() {
    let e = refuse(&format!("{HEAD}random,65535,,,,,\n"));
    assert_at(&e, 3, Some(2), "height");
    assert!(
        matches!(e.kind, SchemeErrorKind::TooTall { height: 65535, .. }),
        "{e}"
    );
    assert!(e.to_string().contains("1000 block sizes"), "{e}");
    // The top of a range counts; 1000 steps of 0.1 m on 0.1 m blocks is
    // the most there is.
    let e = refuse(&format!("{HEAD}peak,1..1001,90,1,1,,\n"));
    assert!(matches!(e.kind, SchemeErrorKind::TooTall { .. }), "{e}");
    scheme(&format!("{HEAD}random,1000,,,,,\n"));
    // A larger block size allows more.
    scheme(&format!("# block_size: 1\n{HEAD}random,10000,,,,,\n"));
}

#[test]
fn globals_whose_products_are_not_finite() {
    for (text, line, key) in [
        ("# step_height: 1e308\ntype,height\n", 1, "step_height"),
        ("# base: 1e308\ntype,height\n", 1, "base"),
        ("# block_size: 1e308\ntype,height\n", 1, "block_size"),
        (
            "# size: 10000x10\n# block_size: 100\ntype,height\n",
            2,
            "block_size",
        ),
    ] {
        let e = refuse(text);
        assert_at(&e, line, None, key);
        assert!(!e.to_string().contains("0000000000"), "{e}");
    }
}

#[test]
fn angle_outside_0_to_90() {
    for angle in ["91", "-1", "30..95"] {
        let e = refuse(&format!("{HEAD}peak,3,{angle},1,1,,\n"));
        assert_at(&e, 3, Some(3), "angle");
        assert!(matches!(e.kind, SchemeErrorKind::AngleOutOfRange(_)), "{e}");
    }
}

#[test]
fn point_outside_the_grid() {
    let e = refuse(&format!("{HEAD}peak,3,45,20,1,,\n"));
    assert_at(&e, 3, Some(4), "x1");
    assert!(matches!(
        e.kind,
        SchemeErrorKind::PointOutsideGrid {
            value: 20,
            axis: 'x',
            max: 19,
            ..
        }
    ));
    let e = refuse(&format!("{HEAD}wall,3,45,1,1,5,3..10\n"));
    assert_at(&e, 3, Some(7), "y2");
    let e = refuse(&format!("{HEAD}peak,3,45,-1,1,,\n"));
    assert_at(&e, 3, Some(4), "x1");
}

#[test]
fn point_outside_a_grid_shrunk_later_still_names_the_line() {
    let s = scheme(&format!("{HEAD}random,1,,,,,\npeak,3,45,15,1,,\n"));
    let globals = Globals {
        size: [10, 10],
        ..*s.globals()
    };
    let mut e = s.with_globals(globals).unwrap_err();
    assert_eq!((e.line, e.column, e.obstacle), (Some(4), Some(4), Some(1)));
    e.file = Some("bad.csv".into());
    assert_at(&e, 4, Some(4), "x1");
}

#[test]
fn reversed_range() {
    let e = refuse(&format!("{HEAD}peak,3,45,9..2,1,,\n"));
    assert_at(&e, 3, Some(4), "x1");
    assert!(matches!(e.kind, SchemeErrorKind::ReversedRange { .. }));
}

#[test]
fn grid_too_large() {
    let e = refuse("# size: 20000x20000\ntype,height\nrandom,1\n");
    assert_at(&e, 1, None, "size");
    assert!(matches!(e.kind, SchemeErrorKind::GridTooLarge { .. }));
    let e = refuse("# pallets: 1000x1000\n# pallet_size: 100\ntype,height\n");
    assert_at(&e, 1, None, "pallets");
}

#[test]
fn bad_globals() {
    for (text, line, key) in [
        ("# size: 20\n", 1, "size"),
        ("# size: 0x5\n", 1, "size"),
        ("# size: 5x5\n# block_size: -0.1\n", 2, "block_size"),
        ("# step_height: 0\n", 1, "step_height"),
        ("# step_height: inf\n", 1, "step_height"),
        ("# base: -1\n", 1, "base"),
        ("# pallet_size: 3\n", 1, "pallet_size"),
        (
            "# pallets: 2x2\n# pallet_boundary: maybe\n",
            2,
            "pallet_boundary",
        ),
        ("# seed: -4\n", 1, "seed"),
        ("# size: 5x5\n# size: 6x6\n", 2, "size"),
        ("# step_hieght: 0.05\n", 1, "step_hieght"),
    ] {
        let e = refuse(&format!("{text}type,height\nrandom,1\n"));
        assert_at(&e, line, None, key);
    }
}

#[test]
fn too_many_fields_in_a_row() {
    let e = refuse("type,height\nrandom,1,7\n");
    assert_eq!(e.line, Some(2));
    assert!(matches!(
        e.kind,
        SchemeErrorKind::TooManyFields {
            found: 3,
            expected: 2
        }
    ));
}

#[test]
fn not_utf8() {
    let e = Scheme::from_csv_bytes(b"type,height\nrandom,\xff\n", Some("bad.csv")).unwrap_err();
    assert_eq!(e.kind, SchemeErrorKind::NotUtf8);
    assert_eq!(e.line, Some(2));
}

#[test]
fn load_names_a_missing_file() {
    let e = Scheme::load("no/such/scheme.csv").unwrap_err();
    // The path in the message; the system's reason once, as the source.
    assert_eq!(e.to_string(), "cannot read no/such/scheme.csv");
    let source = std::error::Error::source(&e).expect("the system's reason");
    assert!(source.to_string().contains("No such file"), "{source}");
}

#[test]
fn an_empty_note_line_survives_saving() {
    let s = scheme("#\n# size: 10x10\ntype,height\n");
    assert_eq!(s.notes(), [""]);
    assert_eq!(scheme(&s.to_csv()), s);
}

/// Issue 22, item 9: a comment that spells a global's name with a slip is
/// an error naming the global, on its line; free text stays a note.
#[test]
fn a_misspelt_global_comment_is_refused_with_the_name_meant() {
    for (line, near) in [
        ("# step-height: 0.05", "step_height"),
        ("# Step Height: 0.05", "step_height"),
        ("# Seeds: 3", "seed"),
        ("# blocksize: 0.2", "block_size"),
    ] {
        let e = refuse(&format!("{line}\n{HEAD}random,2,,,,,\n"));
        assert_eq!(e.line, Some(1), "{e}");
        assert!(
            matches!(e.kind, SchemeErrorKind::NearGlobal { near: n, .. } if n == near),
            "{line}: {e}"
        );
        assert!(
            e.to_string().contains(&format!("did you mean `{near}`")),
            "{e}"
        );
    }
    let fine = Scheme::from_csv(
        &format!("# Husky runs: see the wiki\n# size - 3 rows\n{HEAD}"),
        None,
    )
    .unwrap();
    assert_eq!(fine.notes(), ["Husky runs: see the wiki", "size - 3 rows"]);
}

/// Item 9: lengths a mesh cannot hold apart are refused, naming the global.
#[test]
fn lengths_under_a_millimetre_are_refused() {
    for (key, value) in [
        ("step_height", "1e-7"),
        ("block_size", "1e-320"),
        ("base", "1e-320"),
        ("base", "0.0009"),
    ] {
        let e = refuse(&format!(
            "# size: 5x5\n# {key}: {value}\ntype,height\nrandom,1\n"
        ));
        assert_eq!(e.field.as_deref(), Some(key), "{e}");
        assert!(e.to_string().contains("0.001 m"), "{e}");
    }
    let slab = scheme(
        "# size: 5x5\n# base: 0\n# step_height: 0.001\n# block_size: 0.001\ntype,height\nrandom,1\n",
    );
    assert_eq!(slab.globals().step_height.to_bits(), 0.001f64.to_bits());
}

/// Item 9: `-0` is not a height as written, and a huge field is quoted
/// short and escaped.
#[test]
fn negative_zero_and_huge_fields_are_told_plainly() {
    let e = refuse(&format!("{HEAD}random,-0,,,,,\n"));
    assert!(matches!(e.kind, SchemeErrorKind::NotANumber { .. }), "{e}");
    assert!(!e.to_string().contains("above the largest"), "{e}");
    let huge = format!("\u{1b}[2J{}", "7".repeat(10_000_000));
    let e = refuse(&format!("{HEAD}random,{huge},,,,,\n"));
    let text = e.to_string();
    assert!(text.len() < 400, "{} bytes", text.len());
    assert!(
        !text.contains('\u{1b}') && text.contains("\\u{1b}[2J777"),
        "{text}"
    );
}

/// `base: -0` is the scheme of `base: 0`: read, written back and compared
/// as 0, from a file and from code alike.
#[test]
fn a_negative_zero_base_is_zero() {
    let text = "# base: -0\ntype,height\nrandom,1\n";
    let scheme = Scheme::from_csv(text, None).unwrap();
    assert!(scheme.globals().base.is_sign_positive());
    assert!(!scheme.to_csv().contains("-0"), "{}", scheme.to_csv());
    let zero = Scheme::from_csv("type,height\nrandom,1\n", None).unwrap();
    assert_eq!(scheme.to_csv(), zero.to_csv());
    let globals = Globals {
        base: -0.0,
        ..Globals::default()
    };
    let built = Scheme::new(globals, zero.obstacles().to_vec()).unwrap();
    assert!(built.globals().base.is_sign_positive());
}

/// A comment that reads as `word: text` is a parameter, so a note such as
/// `# Try: 0.05 for a small robot` is refused; the error says how to write
/// one, and `# note: …` is a note whatever follows, kept when saved.
#[test]
fn a_note_is_written_note_colon_and_the_refusal_says_so() {
    let e = refuse(&format!(
        "# Try: 0.05 for a small robot\n{HEAD}random,2,,,,,\n"
    ));
    assert_eq!(e.line, Some(1), "{e}");
    assert!(matches!(e.kind, SchemeErrorKind::UnknownGlobal(_)), "{e}");
    assert!(
        e.to_string().contains("a note is written `# note: …`"),
        "{e}"
    );
    let s = scheme(&format!(
        "# note: Try 0.05 for a small robot\n# Note: size: 9x9 is too small\n{HEAD}random,2,,,,,\n"
    ));
    assert_eq!(
        s.notes(),
        [
            "note: Try 0.05 for a small robot",
            "Note: size: 9x9 is too small"
        ]
    );
    assert_eq!(s.globals().grid().nx, 20);
    assert_eq!(scheme(&s.to_csv()), s);
    let kept = s
        .clone()
        .with_notes(vec!["note: seed: 3 was better".into()])
        .unwrap();
    assert_eq!(scheme(&kept.to_csv()), kept);
}
