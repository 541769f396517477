//! The surface file: reading, writing, building, and every way a record can be wrong.

use tpi_core::sampled_bounding_box;
use tpi_core::{AnalyticSurface, Direction, Surface, SurfaceModel, SurfaceSpec, TpiError};

fn parse_err(text: &str) -> (usize, usize, String) {
    match SurfaceSpec::from_json(text, "test.json") {
        Err(TpiError::Parse {
            context,
            line,
            column,
            message,
        }) => {
            assert_eq!(context, "test.json");
            (line, column, message)
        }
        other => panic!("expected a Parse error for {text}, got {other:?}"),
    }
}

#[test]
fn every_analytic_type_reads_builds_and_round_trips() {
    let texts = [
        r#"{"type": "elliptic_paraboloid", "a": 1.0, "b": 0.1, "x": [-1, 1], "y": [-1, 1]}"#,
        r#"{"type": "sphere_cap", "radius": 2.0, "x": [-1, 1], "y": [-1, 1]}"#,
        r#"{"type": "ellipsoid_cap", "a": 3, "b": 2, "c": 1, "x": [-1, 1], "y": [-1, 1]}"#,
        r#"{"type": "hyperbolic_paraboloid", "a": 0.5, "b": 0.5, "x": [-1, 1], "y": [-1, 1]}"#,
        r#"{"type": "egg_crate", "amplitude": 0.3, "x": [-3.1, 3.1], "y": [-3.1, 3.1]}"#,
        r#"{"type": "cylinder", "radius": 1.5, "x": [-1, 1], "y": [0, 4]}"#,
        r#"{"type": "plane", "p": 0.1, "q": -0.2, "c0": 3, "x": [0, 1], "y": [0, 1]}"#,
    ];
    let names = [
        "elliptic_paraboloid",
        "sphere_cap",
        "ellipsoid_cap",
        "hyperbolic_paraboloid",
        "egg_crate",
        "cylinder",
        "plane",
    ];
    for (text, name) in texts.iter().zip(names) {
        let spec = SurfaceSpec::from_json(text, "surface").unwrap();
        assert_eq!(spec.type_name(), name);
        let model = spec.build().unwrap();
        assert!(matches!(model, SurfaceModel::Analytic(_)));
        // Built surface -> record -> JSON -> record -> surface: all equal.
        assert_eq!(model.to_spec(), spec);
        let json = serde_json::to_string(&spec).unwrap();
        assert!(json.contains(&format!("\"type\":\"{name}\"")), "{json}");
        let again = SurfaceSpec::from_json(&json, "round trip").unwrap();
        assert_eq!(again, spec);
        assert_eq!(again.build().unwrap(), model);
    }
}

#[test]
fn model_dispatches_to_the_analytic_surface() {
    let a = AnalyticSurface::elliptic_paraboloid(1.0, 0.1, [-1.0, 1.0], [-2.0, 2.0]).unwrap();
    let m = SurfaceModel::from(a);
    assert_eq!(m.domain(), a.domain());
    assert_eq!(m.evaluate(0.3, -0.7), a.evaluate(0.3, -0.7));
    assert_eq!(m.point_at(0.3, -0.7), a.point_at(0.3, -0.7));
    // Checked evaluation rejects what plain evaluation clamps.
    assert!(m.evaluate_checked(0.3, -0.7).is_ok());
    assert!(
        matches!(m.evaluate_checked(1.5, 0.0), Err(TpiError::OutOfDomain { u, .. }) if u == 1.5)
    );
    assert!(matches!(
        m.evaluate_checked(f64::NAN, 0.0),
        Err(TpiError::OutOfDomain { .. })
    ));
    assert_eq!(m.evaluate(1.5, 0.0), m.evaluate(1.0, 0.0));
}

#[test]
fn nurbs_records_are_read_with_their_fields() {
    let text = r#"{"type": "nurbs", "degree": [1, 1], "count": [2, 2],
        "knots_u": [0, 1], "knots_v": [0, 1],
        "points": [[0, 0, 0], [0, 1, 0], [1, 0, 0], [1, 1, 1]],
        "weights": [1, 1, 1, 2]}"#;
    let spec = SurfaceSpec::from_json(text, "surface").unwrap();
    let SurfaceSpec::Nurbs(n) = &spec else {
        panic!("expected nurbs, got {spec:?}")
    };
    assert_eq!(n.degree, [1, 1]);
    assert_eq!(n.count, [2, 2]);
    assert_eq!(n.points[3], [1.0, 1.0, 1.0]);
    assert_eq!(n.weights.as_deref(), Some(&[1.0, 1.0, 1.0, 2.0][..]));
    assert_eq!(spec.type_name(), "nurbs");
    let round = SurfaceSpec::from_json(&serde_json::to_string(&spec).unwrap(), "again").unwrap();
    assert_eq!(round, spec);
    // Weights are optional.
    let text = r#"{"type": "nurbs", "degree": [1, 1], "count": [2, 2], "knots_u": [0, 1],
        "knots_v": [0, 1], "points": [[0, 0, 0], [0, 1, 0], [1, 0, 0], [1, 1, 1]]}"#;
    let SurfaceSpec::Nurbs(n) = SurfaceSpec::from_json(text, "surface").unwrap() else {
        panic!()
    };
    assert_eq!(n.weights, None);
}

#[test]
fn unknown_fields_are_rejected_by_name_in_every_variant() {
    let (line, column, message) = parse_err(
        "{\"type\": \"sphere_cap\",\n \"radius\": 2.0,\n \"radus\": 2.0, \"x\": [-1, 1], \"y\": [-1, 1]}",
    );
    assert!(message.contains("unknown field `radus`"), "{message}");
    assert!(
        message.contains("`radius`, `x`, `y`"),
        "lists the accepted fields: {message}"
    );
    assert_eq!((line, column), (3, 8), "points at the offending name");

    for (kind, fields) in [
        ("elliptic_paraboloid", r#""a": 1, "b": 1"#),
        ("hyperbolic_paraboloid", r#""a": 1, "b": 1"#),
        ("ellipsoid_cap", r#""a": 3, "b": 3, "c": 1"#),
        ("egg_crate", r#""amplitude": 1"#),
        ("cylinder", r#""radius": 2"#),
        ("plane", r#""p": 0, "q": 0, "c0": 0"#),
    ] {
        let text = format!(r#"{{"type": "{kind}", {fields}, "x": [-1, 1], "y": [-1, 1], "z": 1}}"#);
        let (_, _, message) = parse_err(&text);
        assert!(message.contains("unknown field `z`"), "{kind}: {message}");
        // The same record without the extra field is fine, and both readers agree on it.
        let good = text.replace(r#", "z": 1"#, "");
        let spec = SurfaceSpec::from_json(&good, "surface").unwrap();
        assert_eq!(
            serde_json::from_str::<SurfaceSpec>(&good).unwrap(),
            spec,
            "{kind}"
        );
        assert!(spec.build().is_ok(), "{kind}");
        // serde's own internally tagged reader rejects the unknown field as well.
        let e = serde_json::from_str::<SurfaceSpec>(&text).unwrap_err();
        assert!(e.to_string().contains("unknown field `z`"), "{e}");
    }

    let nurbs = r#"{"type": "nurbs", "degree": [1, 1], "count": [2, 2], "knots_u": [0, 1], "knots_v": [0, 1],
            "points": [[0, 0, 0], [0, 1, 0], [1, 0, 0], [1, 1, 1]], "wieghts": [1, 1, 1, 1]}"#;
    let (line, _, message) = parse_err(nurbs);
    assert!(message.contains("unknown field `wieghts`"), "{message}");
    assert_eq!(line, 2);
    let e = serde_json::from_str::<SurfaceSpec>(nurbs).unwrap_err();
    assert!(e.to_string().contains("unknown field `wieghts`"), "{e}");
}

#[test]
fn the_type_may_stand_anywhere_in_the_record() {
    let first = r#"{"type": "cylinder", "radius": 2, "x": [-1, 1], "y": [0, 1]}"#;
    let middle = r#"{"radius": 2, "type":"cylinder" , "x": [-1, 1], "y": [0, 1]}"#;
    let last = "{\"radius\": 2, \"x\": [-1, 1], \"y\": [0, 1],\n  \"type\" : \"cylinder\"\n}";
    let escaped = r#"{"radius": 2, "x": [-1, 1], "y": [0, 1], "t\u0079pe": "cyl\u0069nder"}"#;
    let expected = SurfaceSpec::Cylinder {
        radius: 2.0,
        x: [-1.0, 1.0],
        y: [0.0, 1.0],
        units: None,
        trim: None,
    };
    for text in [first, middle, last, escaped] {
        assert_eq!(
            SurfaceSpec::from_json(text, "s").unwrap(),
            expected,
            "{text}"
        );
    }
    // A record holding only its type reports the first missing field.
    let (_, _, message) = parse_err(r#"{"type": "cylinder"}"#);
    assert!(message.contains("missing field `radius`"), "{message}");
}

#[test]
fn only_a_top_level_member_is_the_type() {
    // Windows line ends around the tag, last in the record: blanked with its comma.
    let crlf = "{\"radius\": 2, \"x\": [-1, 1], \"y\": [0, 1],\r\n\"type\":\"cylinder\"\r\n}";
    assert!(SurfaceSpec::from_json(crlf, "s").is_ok());
    // A "type" inside a value (a trim's loop) is not the record's tag.
    let (line, column, message) =
        parse_err(r#"{"trim": {"type": "cylinder"}, "radius": 2, "x": [-1, 1], "y": [0, 1]}"#);
    assert!(message.contains("missing field `type`"), "{message}");
    assert_eq!((line, column), (1, 1));
    // A repeat spelled with an escape is a repeat, at its key; columns count bytes (`é` is 2).
    let (line, column, message) =
        parse_err("{\"é\": 1,\n \"type\": \"plane\", \"typ\\u0065\": \"plane\"}");
    assert!(message.contains("duplicate field `type`"), "{message}");
    assert_eq!((line, column), (2, 19));
    // An unknown field is placed at the end of its key, in bytes (`ü` is 2), as serde_json counts.
    let (line, column, message) = parse_err(
        "{\"type\": \"cylinder\", \"units\": \"mm\", \"radius\": 2, \"x\": [-1, 1], \"y\": [0, 1], \"ü\": 1}",
    );
    assert!(message.contains("unknown field `ü`"), "{message}");
    assert_eq!((line, column), (1, 80));
}

#[test]
fn unknown_missing_repeated_and_malformed_types_are_named() {
    let (line, column, message) =
        parse_err("{\n  \"type\": \"spere_cap\", \"radius\": 2.0, \"x\": [-1, 1], \"y\": [-1, 1]}");
    assert!(
        message.contains("unknown surface type `spere_cap`"),
        "{message}"
    );
    for name in SurfaceSpec::TYPE_NAMES {
        assert!(
            message.contains(&format!("`{name}`")),
            "lists the accepted types: {message}"
        );
    }
    assert_eq!((line, column), (2, 11), "points at the type's value");

    let (line, column, message) = parse_err("  {\"radius\": 2.0, \"x\": [-1, 1], \"y\": [-1, 1]}");
    assert!(message.contains("missing field `type`"), "{message}");
    assert!(message.contains("`sphere_cap`"), "{message}");
    assert_eq!((line, column), (1, 3));

    let (line, column, message) = parse_err(r#"{"type": "plane", "type": "cylinder"}"#);
    assert!(message.contains("duplicate field `type`"), "{message}");
    assert_eq!((line, column), (1, 19));

    let (_, column, message) = parse_err(r#"{"type": 3, "radius": 2.0}"#);
    assert!(message.contains("`type` must be a string"), "{message}");
    assert_eq!(column, 10);

    let (_, _, message) = parse_err(r#"[{"type": "plane"}]"#);
    assert!(
        message.contains("expected a JSON object with a \"type\" field, found an array"),
        "{message}"
    );

    let (_, _, message) = parse_err(r#"{"type": "sphere_cap", "x": [-1, 1], "y": [-1, 1]}"#);
    assert!(message.contains("missing field `radius`"), "{message}");
}

#[test]
fn malformed_json_reports_line_and_column() {
    // A missing comma on line 3.
    let (line, column, message) = parse_err(
        "{\n  \"type\": \"plane\",\n  \"p\": 0.1 \"q\": 0,\n  \"c0\": 0, \"x\": [0, 1], \"y\": [0, 1]}",
    );
    assert_eq!((line, column), (3, 12), "{message}");
    assert!(message.contains("expected `,` or `}`"), "{message}");
    assert!(
        !message.contains(" at line "),
        "the position is not repeated in the message"
    );

    // Truncated document.
    let (line, _, message) = parse_err("{\"type\": \"plane\",\n \"p\": ");
    assert_eq!(line, 2);
    assert!(message.contains("EOF"), "{message}");

    // Wrong value kind, positioned at the value.
    let (line, column, message) = parse_err(
        "{\"type\": \"sphere_cap\",\n \"radius\": \"two\", \"x\": [-1, 1], \"y\": [-1, 1]}",
    );
    assert!(
        message.contains("invalid type: string \"two\", expected f64"),
        "{message}"
    );
    assert_eq!((line, column), (2, 16));
    let (line, column, message) = parse_err(
        "{\"type\": \"nurbs\", \"degree\": [1, 1], \"count\": [2, 2],\n\"knots_u\": [0, \"1\"]}",
    );
    assert!(message.contains("invalid type: string \"1\""), "{message}");
    assert_eq!(
        (line, column),
        (2, 18),
        "serde_json reports the end of the bad value"
    );

    // Wrong array length for a range.
    let (_, column, message) =
        parse_err(r#"{"type": "sphere_cap", "radius": 2, "x": [-1, 0, 1], "y": [-1, 1]}"#);
    assert!(message.contains("more elements than expected"), "{message}");
    assert_eq!(column, 50, "at the third element");
    let (_, _, message) =
        parse_err(r#"{"type": "sphere_cap", "radius": 2, "x": [-1], "y": [-1, 1]}"#);
    assert!(
        message.contains("invalid length 1, expected an array of length 2"),
        "{message}"
    );
    let (_, _, message) =
        parse_err(r#"{"type": "plane", "p": 0, "q": 0, "c0": 0, "x": [0, 1], "y": [0, 1]} x"#);
    assert!(message.contains("trailing characters"), "{message}");

    // Not a number JSON allows.
    let (_, _, message) =
        parse_err(r#"{"type": "sphere_cap", "radius": NaN, "x": [-1, 1], "y": [-1, 1]}"#);
    assert!(message.contains("expected value"), "{message}");

    // The error displays with its context.
    let e = SurfaceSpec::from_json("[", "surf.json").unwrap_err();
    assert!(
        e.to_string().starts_with("surf.json: line 1, column 1"),
        "{e}"
    );
}

#[test]
fn invalid_analytic_values_fail_at_build_with_their_field() {
    let spec = SurfaceSpec::from_json(
        r#"{"type": "sphere_cap", "radius": -1, "x": [-1, 1], "y": [-1, 1]}"#,
        "surface",
    )
    .unwrap();
    assert!(
        matches!(spec.build(), Err(TpiError::InvalidParameter { field, .. }) if field == "radius")
    );
    let spec = SurfaceSpec::from_json(
        r#"{"type": "cylinder", "radius": 1, "x": [-0.5, 0.5], "y": [2, 2]}"#,
        "surface",
    )
    .unwrap();
    assert_eq!(
        spec.build(),
        Err(TpiError::EmptyDomain {
            direction: Direction::V,
            min: 2.0,
            max: 2.0
        })
    );
    let spec = SurfaceSpec::from_json(
        r#"{"type": "ellipsoid_cap", "a": 1, "b": 1, "c": 1, "x": [-1, 1], "y": [-0.1, 0.1]}"#,
        "surface",
    )
    .unwrap();
    assert!(
        matches!(spec.build(), Err(TpiError::InvalidParameter { field, .. }) if field == "x, y")
    );
    // Huge literals overflow to an error, not to infinity.
    let e = SurfaceSpec::from_json(
        r#"{"type": "egg_crate", "amplitude": 1e999, "x": [0, 1], "y": [0, 1]}"#,
        "s",
    );
    assert!(matches!(e, Err(TpiError::Parse { .. })), "{e:?}");
}

#[test]
fn nurbs_records_build_dispatch_and_round_trip() {
    // Textbook knots in the file; the model writes Rhino's convention back.
    let text = r#"{"type": "nurbs", "degree": [1, 2], "count": [2, 3],
        "knots_u": [0, 0, 2, 2], "knots_v": [1, 1, 1, 3, 3, 3],
        "points": [[0, 0, 0], [0, 1, 1], [0, 2, 0], [1, 0, 0], [1, 1, 2], [1, 2, 0]],
        "weights": [1, 2, 1, 1, 0.5, 1]}"#;
    let spec = SurfaceSpec::from_json(text, "surface").unwrap();
    let model = spec.build().unwrap();
    let SurfaceModel::Nurbs(n) = &model else {
        panic!("expected a NURBS model")
    };
    assert_eq!(model.domain(), n.domain());
    assert_eq!(model.evaluate(0.7, 2.2), n.evaluate(0.7, 2.2));
    assert_eq!(model.point_at(0.7, 2.2), n.point_at(0.7, 2.2));
    let SurfaceSpec::Nurbs(written) = model.to_spec() else {
        panic!("expected a NURBS record")
    };
    assert_eq!(
        written.knots_u,
        vec![0.0, 2.0],
        "Rhino convention: count + degree - 1"
    );
    assert_eq!(written.knots_v, vec![1.0, 1.0, 3.0, 3.0]);
    let again = SurfaceSpec::Nurbs(written).build().unwrap();
    assert_eq!(again.evaluate(0.7, 2.2), model.evaluate(0.7, 2.2));
    assert!(matches!(
        model.evaluate_checked(0.7, 0.5),
        Err(TpiError::OutOfDomain { .. })
    ));
}

#[test]
fn nurbs_validation_errors_pass_through_build() {
    let spec = SurfaceSpec::from_json(
        r#"{"type": "nurbs", "degree": [1, 1], "count": [2, 2], "knots_u": [0, 1], "knots_v": [0, 1],
            "points": [[0, 0, 0], [0, 1, 0], [1, 0, 0]]}"#,
        "surface",
    )
    .unwrap();
    assert_eq!(
        spec.build(),
        Err(TpiError::PointCount {
            expected: 4,
            found: 3
        })
    );
}

#[test]
fn sampled_bounding_box_covers_the_samples() {
    let s = AnalyticSurface::elliptic_paraboloid(1.0, 2.0, [-1.0, 2.0], [-1.0, 1.0]).unwrap();
    let [lo, hi] = sampled_bounding_box(&s, 31);
    assert_eq!([lo.x, lo.y, hi.x, hi.y], [-1.0, -1.0, 2.0, 1.0]);
    assert!(lo.z.abs() < 1e-12, "the apex (0, 0) is a grid sample");
    assert_eq!(hi.z, 4.0 + 2.0, "the corner (2, +-1)");
    let m: SurfaceModel = s.into();
    assert_eq!(sampled_bounding_box(&m, 31), [lo, hi]);
    // Fewer than 2 samples per side still includes the corners.
    let [lo, hi] = sampled_bounding_box(&s, 0);
    assert_eq!([lo.x, hi.x], [-1.0, 2.0]);
}

/// Issue 14: a wrong value names its path (serde_path_to_error), at serde_json's position.
#[test]
fn a_wrong_value_is_named_by_its_path() {
    let text = "{\"type\": \"nurbs\", \"degree\": [1, 1], \"count\": [2, 2],\n \"knots_u\": [0, 1], \"knots_v\": [0, 1],\n \"points\": [[0, 0, 0], [1, 0, 0], [0, 1, \"z\"], [1, 1, 1]]}";
    let (line, _, message) = parse_err(text);
    assert!(
        message.starts_with("points[2][2]: invalid type: string \"z\""),
        "{message}"
    );
    assert_eq!(line, 3);
    let e =
        tpi_core::Pattern::from_json(r#"{"uv": [[0.1, 0.2], [0.3, true]]}"#, "p.json").unwrap_err();
    assert!(
        e.to_string().contains("uv[1][1]: invalid type: boolean"),
        "{e}"
    );
    // Unknown and missing fields keep their own wording (the path would only repeat them).
    let (_, _, message) = parse_err(r#"{"type": "cylinder"}"#);
    assert!(message.starts_with("missing field `radius`"), "{message}");
}
