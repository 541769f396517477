//! Units end to end (issue 16): the surface file's `"units"` reach the JSON, the OBJ header, the
//! summary, the SVG, and `tpi fabricate`'s panels.json, panels.obj and DXF `$INSUNITS`;
//! `--units` contradicting the surface file is a usage error.

mod common;

use std::fs;
use std::path::Path;

use common::{scratch, stderr, tpi};

fn dome(dir: &Path, units: &str) -> String {
    let path = dir.join(format!("dome{}.json", units.len()));
    fs::write(
        &path,
        format!(
            r#"{{"type": "elliptic_paraboloid", "a": 0.2, "b": 0.2, "x": [-1, 1], "y": [-1, 1]{units}}}"#
        ),
    )
    .unwrap();
    path.to_string_lossy().into_owned()
}

#[test]
fn discretise_outputs_say_the_units() {
    let dir = scratch("discretise");
    let p = |name: &str| dir.join(name).to_string_lossy().into_owned();
    let surface = dome(&dir, r#", "units": "Millimeters""#);
    let out = tpi(&[
        "discretise",
        "--surface",
        &surface,
        "--pattern",
        "hex:6x6",
        "--out",
        &p("r.json"),
        "--out",
        &p("r.obj"),
        "--out",
        &p("r.svg"),
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    assert!(stderr(&out).contains("\n  units: mm\n"), "{}", stderr(&out));
    let json: serde_json::Value =
        serde_json::from_str(&fs::read_to_string(p("r.json")).unwrap()).unwrap();
    assert_eq!(json["units"], "mm");
    assert!(fs::read_to_string(p("r.obj"))
        .unwrap()
        .contains("\n# units: mm\n"));
    assert!(fs::read_to_string(p("r.svg"))
        .unwrap()
        .contains("units: mm"));

    let unitless = dome(&dir, "");
    let out = tpi(&[
        "discretise",
        "--surface",
        &unitless,
        "--pattern",
        "hex:6x6",
        "--out",
        &p("u.json"),
        "--out",
        &p("u.obj"),
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    assert!(
        stderr(&out).contains("  units: unitless"),
        "{}",
        stderr(&out)
    );
    let json: serde_json::Value =
        serde_json::from_str(&fs::read_to_string(p("u.json")).unwrap()).unwrap();
    assert!(json["units"].is_null());
    assert!(fs::read_to_string(p("u.obj"))
        .unwrap()
        .contains("\n# units: unitless"));

    let info = tpi(&["info", &surface]);
    assert!(info.status.success(), "{}", stderr(&info));
    assert!(
        String::from_utf8_lossy(&info.stdout).contains("\n  units: mm\n"),
        "{}",
        String::from_utf8_lossy(&info.stdout)
    );

    let bad = dome(&dir, r#", "units": "furlongs""#);
    let out = tpi(&["discretise", "--surface", &bad, "--pattern", "hex:6x6"]);
    assert_eq!(out.status.code(), Some(1), "{}", stderr(&out));
    assert!(
        stderr(&out).contains("unknown units `furlongs`"),
        "{}",
        stderr(&out)
    );
}

fn insunits(dxf: &str) -> String {
    let lines: Vec<&str> = dxf.lines().map(str::trim).collect();
    let at = lines.iter().position(|l| *l == "$INSUNITS").unwrap();
    lines[at + 2].to_string()
}

#[test]
fn fabricate_takes_the_units_from_the_surface_file() {
    let dir = scratch("fabricate");
    let p = |name: &str| dir.join(name).to_string_lossy().into_owned();
    let surface = dome(&dir, r#", "units": "in""#);
    let run = |surface: &str, extra: &[&str], tag: &str| {
        let (json, obj, dxf, nc) = (
            p(&format!("{tag}.json")),
            p(&format!("{tag}.obj")),
            p(&format!("{tag}.dxf")),
            p(&format!("{tag}.nc")),
        );
        let mut args = vec![
            "fabricate",
            "--surface",
            surface,
            "--pattern",
            "hex:5x5",
            "--thickness",
            "0.01",
            "--out",
            &json,
            "--out",
            &obj,
            "--out",
            &dxf,
            "--out",
            &nc,
        ];
        args.extend_from_slice(extra);
        let out = tpi(&args);
        (out, json, obj, dxf, nc)
    };
    let (out, json, obj, dxf, nc) = run(&surface, &[], "a");
    assert!(out.status.success(), "{}", stderr(&out));
    assert!(
        stderr(&out).contains("units: in (from the surface file)"),
        "{}",
        stderr(&out)
    );
    let panels: serde_json::Value =
        serde_json::from_str(&fs::read_to_string(json).unwrap()).unwrap();
    assert_eq!(panels["units"], "in");
    assert!(fs::read_to_string(obj).unwrap().contains("\n# units: in\n"));
    assert_eq!(insunits(&fs::read_to_string(dxf).unwrap()), "1");
    assert!(fs::read_to_string(nc).unwrap().contains("G20"));

    // The same units again are fine; others are a usage error, and nothing is written.
    let (out, ..) = run(&surface, &["--units", "Inches"], "b");
    assert!(out.status.success(), "{}", stderr(&out));
    let (out, json, ..) = run(&surface, &["--units", "mm"], "c");
    assert_eq!(out.status.code(), Some(2), "{}", stderr(&out));
    assert!(stderr(&out).contains("--units mm"), "{}", stderr(&out));
    assert!(!Path::new(&json).exists());

    // A unitless surface: --units decides, metres by default.
    let unitless = dome(&dir, "");
    let (out, _, _, dxf, _) = run(&unitless, &["--units", "yd"], "d");
    assert!(out.status.success(), "{}", stderr(&out));
    assert_eq!(insunits(&fs::read_to_string(dxf).unwrap()), "10");
    let (out, json, _, dxf, _) = run(&unitless, &[], "e");
    assert!(out.status.success(), "{}", stderr(&out));
    assert_eq!(insunits(&fs::read_to_string(dxf).unwrap()), "6");
    let panels: serde_json::Value =
        serde_json::from_str(&fs::read_to_string(json).unwrap()).unwrap();
    assert!(panels["units"].is_null());
    let (out, ..) = run(&unitless, &["--units", "furlong"], "f");
    assert_eq!(out.status.code(), Some(2), "{}", stderr(&out));
    assert!(
        stderr(&out).contains("unknown units `furlong`"),
        "{}",
        stderr(&out)
    );
}
