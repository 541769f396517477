//! Pattern files and pattern validation: every bad input gives its specific error.

use tpi_core::tolerance::DUPLICATE_UV_TOLERANCE;
use tpi_core::{Domain, Interval, Pattern, TpiError};

fn out_of_range(uv: Vec<[f64; 2]>) -> (usize, f64, f64) {
    match Pattern::new(uv).validate() {
        Err(TpiError::PatternPointOutOfRange { index, s, t }) => (index, s, t),
        other => panic!("expected PatternPointOutOfRange, got {other:?}"),
    }
}

fn duplicate(uv: Vec<[f64; 2]>) -> (usize, usize, f64) {
    match Pattern::new(uv).validate() {
        Err(TpiError::DuplicatePatternPoint {
            index,
            duplicate_of,
            distance,
        }) => (index, duplicate_of, distance),
        other => panic!("expected DuplicatePatternPoint, got {other:?}"),
    }
}

#[test]
fn points_on_the_border_and_inside_are_valid() {
    let p = Pattern::new(vec![
        [0.0, 0.0],
        [1.0, 1.0],
        [0.0, 1.0],
        [1.0, 0.0],
        [0.5, 0.25],
    ]);
    assert_eq!(p.validate(), Ok(()));
    assert_eq!(
        Pattern::default().validate(),
        Ok(()),
        "an empty pattern is valid here"
    );
    assert_eq!(p.len(), 5);
    assert!(!p.is_empty());
}

#[test]
fn non_finite_and_out_of_range_points_are_named_by_index() {
    let base = vec![[0.1, 0.1], [0.2, 0.2], [0.3, 0.3]];
    for (bad, s, t) in [
        ([f64::NAN, 0.5], f64::NAN, 0.5),
        ([0.5, f64::NAN], 0.5, f64::NAN),
        ([f64::INFINITY, 0.5], f64::INFINITY, 0.5),
        ([0.5, f64::NEG_INFINITY], 0.5, f64::NEG_INFINITY),
        ([-1e-12, 0.5], -1e-12, 0.5),
        ([0.5, 1.0 + 1e-12], 0.5, 1.0 + 1e-12),
        ([2.0, -3.0], 2.0, -3.0),
    ] {
        let mut uv = base.clone();
        uv.push(bad);
        let (index, fs, ft) = out_of_range(uv);
        assert_eq!(index, 3);
        assert!(fs == s || (fs.is_nan() && s.is_nan()));
        assert!(ft == t || (ft.is_nan() && t.is_nan()));
    }
    // The first offending point is named, and range errors come before duplicates.
    let (index, _, _) = out_of_range(vec![[0.5, 0.5], [0.5, 0.5], [1.5, 0.5], [f64::NAN, 0.0]]);
    assert_eq!(index, 2);
}

#[test]
fn duplicates_name_the_later_point_and_the_nearest_earlier_one() {
    assert_eq!(
        duplicate(vec![[0.1, 0.2], [0.3, 0.4], [0.1, 0.2]]),
        (2, 0, 0.0)
    );
    // Closer than the tolerance, not equal.
    let (index, of, distance) =
        duplicate(vec![[0.5, 0.5], [0.7, 0.7], [0.5 + 0.4e-9, 0.5 + 0.3e-9]]);
    assert_eq!((index, of), (2, 0));
    assert!((distance - 0.5e-9).abs() < 1e-15, "{distance}");
    // Just beyond the tolerance: distinct.
    assert_eq!(
        Pattern::new(vec![[0.5, 0.5], [0.5 + 1.5 * DUPLICATE_UV_TOLERANCE, 0.5]]).validate(),
        Ok(())
    );
    // Straddling a hash cell boundary (cells have the tolerance's size).
    let edge = 123_456.0 * DUPLICATE_UV_TOLERANCE;
    assert_eq!(
        duplicate(vec![[edge - 0.2e-9, 0.3], [0.9, 0.9], [edge + 0.2e-9, 0.3]]).0,
        2,
        "neighbouring cells are searched"
    );
    // Several earlier candidates: the nearest is named.
    let (index, of, _) = duplicate(vec![[0.5, 0.5], [0.5 + 0.8e-9, 0.5], [0.5 + 0.7e-9, 0.5]]);
    assert_eq!(
        (index, of),
        (1, 0),
        "the first later point is reported first"
    );
    let (index, of, _) = duplicate(vec![
        [0.5, 0.5],
        [0.5 + 0.9e-9, 0.5 + 0.9e-9],
        [0.5 + 0.8e-9, 0.5 + 0.9e-9],
    ]);
    assert_eq!(
        (index, of),
        (2, 1),
        "(1) is farther than the tolerance from (0); (2) is nearest (1)"
    );
    // Exact duplicates at the corners and on the border.
    assert_eq!(
        duplicate(vec![[1.0, 1.0], [0.0, 0.0], [1.0, 1.0]]),
        (2, 0, 0.0)
    );
}

#[test]
fn validation_of_a_million_points_is_fast() {
    // Columns of a grid share s exactly: a sort-by-s sweep would be quadratic here.
    let n = 1000;
    let mut uv = Vec::with_capacity(n * n);
    for i in 0..n {
        for j in 0..n {
            uv.push([(i as f64 + 0.5) / n as f64, (j as f64 + 0.5) / n as f64]);
        }
    }
    let mut p = Pattern::new(uv);
    assert_eq!(p.validate(), Ok(()));
    p.uv.push([0.5005, 0.0005]);
    assert_eq!(
        p.validate().unwrap_err(),
        TpiError::DuplicatePatternPoint {
            index: n * n,
            duplicate_of: 500 * n,
            distance: 0.0
        }
    );
}

#[test]
fn pattern_files_read_validate_and_round_trip() {
    let p = Pattern::from_json(r#"{"uv": [[0, 0], [0.5, 0.25], [1, 1]]}"#, "p.json").unwrap();
    assert_eq!(p.uv, vec![[0.0, 0.0], [0.5, 0.25], [1.0, 1.0]]);
    let json = serde_json::to_string(&p).unwrap();
    assert_eq!(json, r#"{"uv":[[0.0,0.0],[0.5,0.25],[1.0,1.0]]}"#);
    assert_eq!(Pattern::from_json(&json, "again").unwrap(), p);
    assert_eq!(
        Pattern::from_json(r#"{"uv": []}"#, "empty").unwrap(),
        Pattern::default()
    );

    // Validation runs on reading.
    assert_eq!(
        Pattern::from_json(r#"{"uv": [[0.5, 0.5], [0.5, 1.5]]}"#, "p.json"),
        Err(TpiError::PatternPointOutOfRange {
            index: 1,
            s: 0.5,
            t: 1.5
        })
    );
    assert_eq!(
        Pattern::from_json(r#"{"uv": [[0.5, 0.5], [0.2, 0.2], [0.5, 0.5]]}"#, "p.json"),
        Err(TpiError::DuplicatePatternPoint {
            index: 2,
            duplicate_of: 0,
            distance: 0.0
        })
    );
}

#[test]
fn malformed_pattern_files_report_line_and_column() {
    let parse = |text: &str| match Pattern::from_json(text, "p.json") {
        Err(TpiError::Parse {
            context,
            line,
            column,
            message,
        }) => {
            assert_eq!(context, "p.json");
            (line, column, message)
        }
        other => panic!("expected Parse for {text}, got {other:?}"),
    };
    let (line, column, message) = parse("{\"uv\": [\n  [0.1, 0.2],\n  [0.3 0.4]\n]}");
    assert_eq!((line, column), (3, 8), "{message}");
    assert!(message.contains("expected `,` or `]`"), "{message}");

    let (line, _, message) = parse("{\"uv\": [[0.1, 0.2]], \"points\": []}");
    assert_eq!(line, 1);
    assert!(
        message.contains("unknown field `points`, expected `uv`"),
        "{message}"
    );

    let (_, _, message) = parse("{}");
    assert!(message.contains("missing field `uv`"), "{message}");

    let (line, column, message) = parse("{\"uv\": [[0.1, 0.2],\n [0.3]]}");
    assert!(
        message.contains("invalid length 1, expected an array of length 2"),
        "{message}"
    );
    assert_eq!((line, column), (2, 6));

    let (_, _, message) = parse("{\"uv\": [[0.1, \"a\"]]}");
    assert!(
        message.contains("invalid type: string \"a\", expected f64"),
        "{message}"
    );

    let (_, _, message) = parse("{\"uv\": [[0.1, 1e999]]}");
    assert!(message.contains("number out of range"), "{message}");

    let (_, _, message) = parse("");
    assert!(message.contains("EOF"), "{message}");
}

#[test]
fn points_map_linearly_onto_the_domain() {
    let domain = Domain::new(Interval::new(2.0, 4.0), Interval::new(-1.0, 0.0));
    let p = Pattern::new(vec![[0.0, 0.0], [1.0, 1.0], [0.25, 0.5]]);
    assert_eq!(
        p.to_domain(&domain),
        vec![[2.0, -1.0], [4.0, 0.0], [2.5, -0.5]]
    );
}
