//! Units (issue 16): the surface file's optional `"units"` on every surface type, read in any of
//! Rhino's names, written back in the short one, and carried to the discretisation and the
//! fabrication outputs.

use tpi_core::{
    discretise, fabricate, DiscretiseOptions, FabricateOptions, Generator, NurbsSpec, Surface,
    SurfaceSpec, TpiError, Units,
};

const RECORDS: [&str; 8] = [
    r#"{"type": "elliptic_paraboloid", "a": 1.0, "b": 0.1, "x": [-1, 1], "y": [-1, 1]"#,
    r#"{"type": "sphere_cap", "radius": 2.0, "x": [-1, 1], "y": [-1, 1]"#,
    r#"{"type": "ellipsoid_cap", "a": 3, "b": 2, "c": 1, "x": [-1, 1], "y": [-1, 1]"#,
    r#"{"type": "hyperbolic_paraboloid", "a": 0.5, "b": 0.5, "x": [-1, 1], "y": [-1, 1]"#,
    r#"{"type": "egg_crate", "amplitude": 0.3, "x": [-3.1, 3.1], "y": [-3.1, 3.1]"#,
    r#"{"type": "cylinder", "radius": 1.5, "x": [-1, 1], "y": [0, 4]"#,
    r#"{"type": "plane", "p": 0.1, "q": -0.2, "c0": 3, "x": [0, 1], "y": [0, 1]"#,
    r#"{"type": "nurbs", "degree": [1, 1], "count": [2, 2], "knots_u": [0, 1], "knots_v": [0, 1],
        "points": [[0, 0, 0], [0, 1, 0], [1, 0, 0], [1, 1, 1]]"#,
];

#[test]
fn every_type_reads_units_in_any_name_and_round_trips_them() {
    for record in RECORDS {
        for (name, units) in [
            ("mm", Units::Millimetres),
            ("Millimeters", Units::Millimetres),
            ("MILLIMETRES", Units::Millimetres),
            ("um", Units::Microns),
            ("Microns", Units::Microns),
            ("km", Units::Kilometres),
            ("in", Units::Inches),
            ("Feet", Units::Feet),
            ("yd", Units::Yards),
            ("miles", Units::Miles),
        ] {
            let text = format!(r#"{record}, "units": "{name}"}}"#);
            let spec = SurfaceSpec::from_json(&text, "s.json").unwrap();
            assert_eq!(spec.units(), Some(units), "{text}");
            let model = spec.build().unwrap();
            assert_eq!(model.units(), Some(units), "{text}");
            assert_eq!(model.to_spec(), spec, "{text}");
            let json = serde_json::to_string(&model.to_spec()).unwrap();
            assert!(
                json.contains(&format!(r#""units":"{}""#, units.short_name())),
                "{json}"
            );
            assert_eq!(SurfaceSpec::from_json(&json, "again").unwrap(), spec);
        }
        // Absent: unitless, and nothing is written.
        let spec = SurfaceSpec::from_json(&format!("{record}}}"), "s.json").unwrap();
        assert_eq!(spec.units(), None);
        assert_eq!(spec.build().unwrap().units(), None);
        let json = serde_json::to_string(&spec.build().unwrap().to_spec()).unwrap();
        assert!(!json.contains("units"), "{json}");
    }
}

#[test]
fn unknown_units_are_a_parse_error_listing_the_accepted_names() {
    for record in RECORDS {
        let text = format!("{record},\n \"units\": \"furlongs\"}}");
        match SurfaceSpec::from_json(&text, "s.json") {
            Err(TpiError::Parse { line, message, .. }) => {
                assert!(line >= 2, "{line}: {message}");
                assert!(message.contains("units"), "{message}");
                assert!(message.contains("`furlongs`"), "{message}");
                for u in Units::ALL {
                    assert!(
                        message.contains(&format!("`{}`", u.short_name())),
                        "{message}"
                    );
                }
                assert!(message.contains("`Millimeters`"), "{message}");
            }
            other => panic!("{text}: {other:?}"),
        }
        let text = format!(r#"{record}, "units": 4}}"#);
        assert!(
            matches!(
                SurfaceSpec::from_json(&text, "s.json"),
                Err(TpiError::Parse { .. })
            ),
            "{text}"
        );
    }
}

#[test]
fn nurbs_spec_carries_units_through_build() {
    let spec: NurbsSpec = serde_json::from_str(
        r#"{"degree": [1, 1], "count": [2, 2], "knots_u": [0, 1], "knots_v": [0, 1],
            "points": [[0, 0, 0], [0, 1, 0], [1, 0, 0], [1, 1, 1]], "units": "cm"}"#,
    )
    .unwrap();
    assert_eq!(spec.units, Some(Units::Centimetres));
    let surface = spec.build().unwrap();
    assert_eq!(surface.units(), Some(Units::Centimetres));
    assert_eq!(surface.to_spec(), spec);
}

fn dome(units: &str) -> tpi_core::SurfaceModel {
    let text = format!(
        r#"{{"type": "elliptic_paraboloid", "a": 1.0, "b": 1.0, "x": [-1, 1], "y": [-1, 1]{units}}}"#
    );
    SurfaceSpec::from_json(&text, "dome")
        .unwrap()
        .build()
        .unwrap()
}

#[test]
fn the_discretisation_and_the_fabrication_carry_the_units() {
    let pattern = Generator::parse("grid:6x6").unwrap().generate();
    let mesh = discretise(
        &dome(r#", "units": "mm""#),
        &pattern.uv,
        &DiscretiseOptions::default(),
    )
    .unwrap();
    assert_eq!(mesh.units, Some(Units::Millimetres));
    let json: serde_json::Value = serde_json::from_str(&mesh.to_json(false)).unwrap();
    assert_eq!(json["units"], "mm");

    let options = FabricateOptions {
        thickness: 0.01,
        ..FabricateOptions::default()
    };
    let fab = fabricate(&mesh, &options).unwrap();
    assert_eq!(fab.units, Some(Units::Millimetres));
    let panels: serde_json::Value = serde_json::from_str(&fab.to_json()).unwrap();
    assert_eq!(panels["units"], "mm");
    assert!(fab.to_obj().contains("\n# units: mm\n"));

    let unitless = discretise(&dome(""), &pattern.uv, &DiscretiseOptions::default()).unwrap();
    assert_eq!(unitless.units, None);
    let json: serde_json::Value = serde_json::from_str(&unitless.to_json(false)).unwrap();
    assert!(json["units"].is_null(), "{json}");
    let fab = fabricate(&unitless, &options).unwrap();
    assert!(fab.to_obj().contains("\n# units: unitless\n"));
}

#[test]
fn dxf_insunits_follow_the_units() {
    let pattern = Generator::parse("grid:5x5").unwrap().generate();
    let mesh = discretise(&dome(""), &pattern.uv, &DiscretiseOptions::default()).unwrap();
    let options = FabricateOptions {
        thickness: 0.01,
        ..FabricateOptions::default()
    };
    let fab = fabricate(&mesh, &options).unwrap();
    for (units, code) in [
        (Units::Inches, 1),
        (Units::Feet, 2),
        (Units::Miles, 3),
        (Units::Millimetres, 4),
        (Units::Centimetres, 5),
        (Units::Metres, 6),
        (Units::Kilometres, 7),
        (Units::Yards, 10),
        (Units::Microns, 13),
    ] {
        let dxf = fab.sheets_dxf(units).unwrap();
        let lines: Vec<&str> = dxf.lines().map(str::trim).collect();
        let at = lines.iter().position(|l| *l == "$INSUNITS").unwrap();
        assert_eq!(lines[at + 1], "70");
        assert_eq!(lines[at + 2], code.to_string(), "{units}");
    }
}
