//! End-to-end tests of `tpi fabricate`: every output is written and reads back, and a bad
//! thickness fails with one line naming it and leaves no file behind.

mod common;

use std::fs;

use common::{sample, scratch, stderr, tpi};

#[test]
fn every_output_is_written_and_reads_back() {
    let dir = scratch("all");
    let out = |f: &str| dir.join(f).to_string_lossy().into_owned();
    let slots = dir.join("slots.json");
    fs::write(&slots, r#"{"slots": [{"edge": [0, 1], "at": [0.5]}]}"#).unwrap();
    let o = tpi(&[
        "fabricate",
        "--surface",
        &sample("paraboloid.json"),
        "--pattern",
        "hex:12x10",
        "--thickness",
        "0.05",
        "--slots",
        &slots.to_string_lossy(),
        "--slot-size",
        "0.1x0.06",
        "--sheet",
        "3x1.5",
        "--gap",
        "0.03",
        "--tool-diameter",
        "0.008",
        "--density",
        "450",
        "--units",
        "mm",
        "--out",
        &out("panels.json"),
        "--out",
        &out("panels.obj"),
        "--out",
        &out("sheets.svg"),
        "--out",
        &out("sheets.dxf"),
        "--out",
        &out("cut.nc"),
        "--out",
        &out("bevels.csv"),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let err = stderr(&o);
    for needle in [
        "120 panels",
        "1 cleats",
        "sheets:",
        "utilisation",
        "mass",
        "bevels",
    ] {
        assert!(err.contains(needle), "summary lacks {needle}: {err}");
    }
    let json: serde_json::Value =
        serde_json::from_str(&fs::read_to_string(dir.join("panels.json")).unwrap()).unwrap();
    let panels = json["panels"].as_array().unwrap();
    assert_eq!(panels.len(), 120);
    assert_eq!(json["thickness"], 0.05);
    let slotted: usize = panels
        .iter()
        .map(|p| p["slots"].as_array().unwrap().len())
        .sum();
    assert_eq!(slotted, 2, "one slot, in both panels of the edge");
    let obj = fs::read_to_string(dir.join("panels.obj")).unwrap();
    assert_eq!(obj.lines().filter(|l| l.starts_with("o ")).count(), 121);
    let dxf = fs::read_to_string(dir.join("sheets.dxf")).unwrap();
    let dxf: Vec<&str> = dxf.lines().map(str::trim).collect();
    let at = dxf.iter().position(|l| *l == "$INSUNITS").unwrap();
    assert_eq!(dxf[at + 1..at + 3], ["70", "4"]);
    assert_eq!(dxf[dxf.len() - 2..], ["0", "EOF"]);
    let nc = fs::read_to_string(dir.join("cut.nc")).unwrap();
    assert!(
        nc.starts_with("(tpi fabricate: sheet 0") && nc.contains("G21") && nc.ends_with("M30\n")
    );
    let csv = fs::read_to_string(dir.join("bevels.csv")).unwrap();
    assert!(csv.starts_with("panel,side,neighbour,length,dihedral_deg,bevel_deg\n"));
    let svg = fs::read_to_string(dir.join("sheets.svg")).unwrap();
    assert_eq!(svg.matches("<polygon stroke=\"#c00\"").count(), 120);
    fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_bad_thickness_is_named_and_nothing_is_written() {
    let dir = scratch("bad");
    let json = dir.join("p.json").to_string_lossy().into_owned();
    for (t, needle) in [
        ("nan", "--thickness: thickness = NaN"),
        ("-0.1", "--thickness: thickness = -0.1"),
        ("0", "must be a finite number > 0"),
        ("5", "collapses at thickness"),
    ] {
        let o = tpi(&[
            "fabricate",
            "--surface",
            &sample("hypar.json"),
            "--pattern",
            "random:400:seed=1",
            "--thickness",
            t,
            "--sheet",
            "100x100",
            "--out",
            &json,
        ]);
        assert_eq!(o.status.code(), Some(1), "{t}: {}", stderr(&o));
        let err = stderr(&o);
        assert!(err.contains(needle), "{t}: {err}");
        assert_eq!(err.lines().count(), 1, "{err}");
        assert_eq!(
            fs::read_dir(&dir).unwrap().count(),
            0,
            "{t}: a file was written"
        );
    }
    let o = tpi(&[
        "fabricate",
        "--surface",
        &sample("hypar.json"),
        "--pattern",
        "hex:5x5",
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("--thickness is required"));
    fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn collapsed_edges_are_clipped_and_named_on_stderr_and_in_the_json() {
    // The ellipsoid with a coarse hex pattern: its first bottom edge collapses at a thickness of
    // about 1.26; at 1.9 the panels around each collapsed edge are clipped, not refused.
    let dir = scratch("collapse");
    let json = dir.join("p.json");
    let o = tpi(&[
        "fabricate",
        "--surface",
        &sample("ellipsoid.json"),
        "--pattern",
        "hex:7x6",
        "--thickness",
        "1.9",
        "--sheet",
        "100x100",
        "--out",
        &json.to_string_lossy(),
    ]);
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(0), "{err}");
    let lines: Vec<&str> = err
        .lines()
        .filter(|l| l.contains("collapsed edge: the bottom edge of panel"))
        .collect();
    let v: serde_json::Value = serde_json::from_str(&fs::read_to_string(&json).unwrap()).unwrap();
    let named: Vec<&serde_json::Value> = v["diagnostics"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|d| d["kind"] == "edge_collapsed")
        .collect();
    assert!(lines.len() >= 5, "{err}");
    assert_eq!(lines.len(), named.len(), "{err}");
    let panels = v["panels"].as_array().unwrap().len() as u64;
    for (line, d) in lines.iter().zip(&named) {
        let panel = d["panel"].as_u64().unwrap();
        let at = d["at_thickness"].as_f64().unwrap();
        assert!(panel < panels && at > 0.0 && at <= 1.9, "{d}");
        assert!(
            line.contains(&format!("panel {panel} along")),
            "{line} vs {d}"
        );
        let [a, b] = [&d["vertices"][0], &d["vertices"][1]];
        assert!(line.contains(&format!("(vertices {a} and {b})")), "{line}");
    }
    // Every bottom vertex still lies at the thickness below its top face's plane.
    for p in v["panels"].as_array().unwrap() {
        let pt = |x: &serde_json::Value| -> [f64; 3] { [0, 1, 2].map(|c| x[c].as_f64().unwrap()) };
        let top: Vec<[f64; 3]> = p["top"].as_array().unwrap().iter().map(pt).collect();
        let mut n = [0.0f64; 3];
        for k in 0..top.len() {
            let (a, b) = (top[k], top[(k + 1) % top.len()]);
            n[0] += a[1] * b[2] - a[2] * b[1];
            n[1] += a[2] * b[0] - a[0] * b[2];
            n[2] += a[0] * b[1] - a[1] * b[0];
        }
        let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
        for b in p["bottom"].as_array().unwrap().iter().map(pt) {
            let d: f64 = (0..3).map(|c| (b[c] - top[0][c]) * n[c] / len).sum();
            assert!((d.abs() - 1.9).abs() < 1e-9, "panel {}: {d}", p["seed"]);
        }
    }
    fs::remove_dir_all(&dir).unwrap();
}
