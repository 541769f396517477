//! tools/3dm_to_tpi.py (.3dm in, without Rhino): tests/converter/check_3dm_to_tpi.py builds a
//! model with rhino3dm (a NURBS dome, a degree 7 x 5 rational surface, a sphere, a box, a plane
//! trimmed by a circle, a capped cylinder, a slab with a hole; millimetres), converts it, and records rhino3dm's
//! points of the source geometry; the surface files are read here with tpi-core and must agree.
//!
//! The script runs at test time with `python3` (or the interpreter named by TPI_PYTHON); a
//! missing interpreter or rhino3dm fails these tests, they never skip.

use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::OnceLock;

use glam::DVec3;
use serde::Deserialize;
use serde_json::Value;
use tpi_core::{Surface, SurfaceModel, SurfaceSpec, Units};

/// Points agree to this fraction of the control net's bounding-box diagonal.
const POINT_TOLERANCE: f64 = 1e-9;

#[derive(Deserialize)]
struct Expected {
    unit_cases: Vec<UnitCase>,
    plain_index: String,
    trims_index: String,
    faces: Vec<ExpectedFace>,
}

#[derive(Deserialize)]
struct UnitCase {
    rhino: String,
    index_units: Option<String>,
    file: String,
}

#[derive(Deserialize)]
struct ExpectedFace {
    file: String,
    samples: Vec<Sample>,
}

#[derive(Deserialize)]
struct Sample {
    u: f64,
    v: f64,
    point: [f64; 3],
}

struct Run {
    dir: PathBuf,
    expected: Expected,
    plain: Value,
    trims: Value,
}

fn run() -> &'static Run {
    static RUN: OnceLock<Result<Run, String>> = OnceLock::new();
    match RUN.get_or_init(convert) {
        Ok(run) => run,
        Err(message) => panic!("{message}"),
    }
}

fn convert() -> Result<Run, String> {
    let dir = std::env::temp_dir().join(format!("tpi-converter-3dm-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).map_err(|e| format!("cannot create {}: {e}", dir.display()))?;
    let python = std::env::var("TPI_PYTHON").unwrap_or_else(|_| "python3".to_string());
    let script =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../../tests/converter/check_3dm_to_tpi.py");
    let output = Command::new(&python)
        .arg(&script)
        .arg("--out")
        .arg(&dir)
        .output()
        .map_err(|e| {
            format!(
                "cannot run `{python}` for the .3dm converter test ({e}); install Python 3 and \
                 rhino3dm (`python3 -m pip install 'rhino3dm==8.*'`) or set TPI_PYTHON"
            )
        })?;
    if !output.status.success() {
        return Err(format!(
            "`{python} {}` failed ({}); rhino3dm is required:\n{}",
            script.display(),
            output.status,
            String::from_utf8_lossy(&output.stderr)
        ));
    }
    let read = |name: &str| -> Result<String, String> {
        std::fs::read_to_string(dir.join(name)).map_err(|e| format!("cannot read {name}: {e}"))
    };
    let expected: Expected =
        serde_json::from_str(&read("expected.json")?).map_err(|e| format!("expected.json: {e}"))?;
    let plain = serde_json::from_str(&read(&expected.plain_index)?).map_err(|e| e.to_string())?;
    let trims = serde_json::from_str(&read(&expected.trims_index)?).map_err(|e| e.to_string())?;
    Ok(Run {
        dir,
        expected,
        plain,
        trims,
    })
}

fn surface_text(subdir: &str, file: &str) -> String {
    let path = run().dir.join(subdir).join(file);
    std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

fn model(file: &str) -> (SurfaceSpec, SurfaceModel) {
    let spec = SurfaceSpec::from_json(&surface_text("plain", file), file)
        .unwrap_or_else(|e| panic!("{file}: tpi rejects the converted surface: {e}"));
    let model = spec
        .build()
        .unwrap_or_else(|e| panic!("{file}: tpi rejects the converted surface: {e}"));
    (spec, model)
}

fn faces(index: &Value) -> &Vec<Value> {
    index["faces"].as_array().expect("faces")
}

#[test]
fn every_face_evaluates_like_rhino3dm() {
    let run = run();
    assert_eq!(run.expected.faces.len(), 20);
    let mut worst = 0.0f64;
    for face in &run.expected.faces {
        let (spec, model) = model(&face.file);
        let SurfaceModel::Nurbs(nurbs) = &model else {
            panic!("{}: not NURBS", face.file)
        };
        assert_eq!(spec.type_name(), "nurbs");
        let diagonal = nurbs.bounding_box_diagonal();
        for s in &face.samples {
            let expected = DVec3::from_array(s.point);
            let got = model.point_at(s.u, s.v);
            let off = (got - expected).length() / diagonal;
            assert!(
                off <= POINT_TOLERANCE,
                "{} at ({}, {}): tpi {got}, rhino3dm {expected}: {off:e} of the net diagonal",
                face.file,
                s.u,
                s.v
            );
            worst = worst.max(off);
        }
    }
    println!("worst deviation {worst:e} of the net diagonal");
}

#[test]
fn units_degrees_poles_and_closedness_are_carried() {
    let index = &run().plain;
    assert_eq!(index["units"], "mm");
    assert_eq!(index["rhino_units"], "Millimeters");
    for face in faces(index) {
        let file = face["file"].as_str().unwrap();
        let (spec, model) = model(file);
        assert_eq!(spec.units(), Some(Units::Millimetres), "{file}");
        assert_eq!(model.units(), Some(Units::Millimetres), "{file}");
        assert_eq!(face["units"], "mm");
    }
    let by_object = |object: u64| -> Vec<&Value> {
        faces(index)
            .iter()
            .filter(|f| f["object"] == object)
            .collect()
    };
    let high = by_object(1);
    assert_eq!(high[0]["degree"], serde_json::json!([7, 5]));
    assert_eq!(high[0]["rational"], true);
    let sphere = by_object(2);
    assert_eq!(sphere.len(), 1);
    assert_eq!(sphere[0]["closed"], serde_json::json!([true, false]));
    assert_eq!(
        sphere[0]["poles"],
        serde_json::json!(["south (v min)", "north (v max)"])
    );
    assert_eq!(sphere[0]["trimmed"], false);
    assert_eq!(by_object(3).len(), 6);
    let cylinder = by_object(5);
    assert_eq!(cylinder.len(), 3);
    assert_eq!(cylinder[0]["closed"], serde_json::json!([true, false]));
}

#[test]
fn every_rhino_unit_system_tpi_knows_is_carried_and_others_are_unitless() {
    let cases = &run().expected.unit_cases;
    let expected = [
        ("Inches", Some(Units::Inches)),
        ("Meters", Some(Units::Metres)),
        ("Microns", Some(Units::Microns)),
        ("Yards", Some(Units::Yards)),
        ("None", None),
        ("Parsecs", None),
    ];
    assert_eq!(cases.len(), expected.len());
    for (case, (rhino, units)) in cases.iter().zip(expected) {
        assert_eq!(case.rhino, rhino);
        assert_eq!(
            case.index_units.as_deref(),
            units.map(Units::short_name),
            "{rhino}"
        );
        let text = std::fs::read_to_string(run().dir.join(&case.file)).unwrap();
        let spec = SurfaceSpec::from_json(&text, &case.file).unwrap();
        assert_eq!(spec.units(), units, "{rhino}");
        assert_eq!(spec.build().unwrap().units(), units, "{rhino}");
    }
}

#[test]
fn a_box_has_twelve_shared_edges() {
    let index = &run().plain;
    let box_faces: Vec<u64> = faces(index)
        .iter()
        .enumerate()
        .filter(|(_, f)| f["object"] == 3)
        .map(|(k, _)| k as u64)
        .collect();
    let shared: Vec<&Value> = index["shared_edges"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|e| e["object"] == 3)
        .collect();
    assert_eq!(shared.len(), 12);
    let mut per_face = std::collections::BTreeMap::new();
    for edge in &shared {
        let uses = edge["uses"].as_array().unwrap();
        assert_eq!(uses.len(), 2, "{edge}");
        let a = uses[0]["face"].as_u64().unwrap();
        let b = uses[1]["face"].as_u64().unwrap();
        assert_ne!(a, b);
        for f in [a, b] {
            assert!(box_faces.contains(&f));
            *per_face.entry(f).or_insert(0) += 1;
        }
        let (start, end) = (&edge["start"], &edge["end"]);
        assert_ne!(start, end);
    }
    assert!(per_face.values().all(|&n| n == 4), "{per_face:?}");
    for &f in &box_faces {
        let neighbours = faces(index)[f as usize]["neighbours"].as_array().unwrap();
        assert_eq!(neighbours.len(), 4, "face {f}");
        assert!(neighbours
            .iter()
            .all(|n| box_faces.contains(&n["face"].as_u64().unwrap())));
    }
    // The cylinder's two circular edges are shared by the wall and a cap; the slab's 4 walls
    // share 4 vertical edges, 8 with the caps, and its hole's wall 2 circles with the caps.
    // The sphere, the cylinder and the hole's wall each have one seam.
    let others = index["shared_edges"].as_array().unwrap().len() - 12;
    assert_eq!(others, 2 + 12 + 2);
    assert_eq!(index["seams"].as_array().unwrap().len(), 3);
}

/// Signed area of a closed polyline.
fn area(poly: &[[f64; 2]]) -> f64 {
    (0..poly.len())
        .map(|k| {
            let (a, b) = (poly[k], poly[(k + 1) % poly.len()]);
            a[0] * b[1] - b[0] * a[1]
        })
        .sum::<f64>()
        / 2.0
}

fn polyline(v: &Value) -> Vec<[f64; 2]> {
    serde_json::from_value(v.clone()).expect("a polyline of [u, v]")
}

#[test]
fn trims_are_the_projected_edges() {
    let run = run();
    for (plain, with) in faces(&run.plain).iter().zip(faces(&run.trims)) {
        let file = plain["file"].as_str().unwrap();
        let written: Value = serde_json::from_str(&surface_text("trims", file)).unwrap();
        let untouched: Value = serde_json::from_str(&surface_text("plain", file)).unwrap();
        assert!(untouched.get("trim").is_none(), "{file}");
        assert_eq!(with["trimmed"], plain["trimmed"]);
        if plain["trimmed"] == true {
            assert_eq!(written["trim"], plain["trim"], "{file}");
            let outer = polyline(&plain["trim"]["outer"]);
            assert!(outer.len() >= 4, "{file}");
            assert!(
                area(&outer) > 0.0,
                "{file}: outer loop not counter-clockwise"
            );
            for hole in plain["trim"]["holes"].as_array().unwrap() {
                assert!(area(&polyline(hole)) < 0.0, "{file}: hole not clockwise");
            }
        } else {
            assert!(written.get("trim").is_none(), "{file}");
            assert!(plain["trim"].is_null(), "{file}");
        }
    }
    // The plane trimmed by the circle of radius 800 mm around (3000, 7000, 0).
    let face = faces(&run.plain).iter().find(|f| f["object"] == 4).unwrap();
    assert_eq!(face["trimmed"], true);
    let (_, plane) = model(face["file"].as_str().unwrap());
    assert!(polyline(&face["trim"]["outer"]).len() >= 16);
    for [u, v] in polyline(&face["trim"]["outer"]) {
        let p = plane.point_at(u, v);
        let radius = (p - DVec3::new(3000.0, 7000.0, 0.0)).length();
        assert!(
            (radius - 800.0).abs() < 1e-6,
            "({u}, {v}) -> {p}: radius {radius}"
        );
    }
    // The caps of the cylinder and of the slab are trimmed, the walls and the box faces not.
    let trimmed: Vec<(u64, u64)> = faces(&run.plain)
        .iter()
        .filter(|f| f["trimmed"] == true)
        .map(|f| (f["object"].as_u64().unwrap(), f["face"].as_u64().unwrap()))
        .collect();
    assert_eq!(trimmed, [(4, 0), (5, 1), (5, 2), (6, 5), (6, 6)]);
    // The slab's caps: the whole rectangle as the outer loop, one hole of radius 200 mm
    // around (9000, 500).
    for face in faces(&run.plain)
        .iter()
        .filter(|f| f["object"] == 6 && f["trimmed"] == true)
    {
        let (_, slab) = model(face["file"].as_str().unwrap());
        let outer = polyline(&face["trim"]["outer"]);
        assert_eq!(outer.len(), 4);
        let domain = slab.domain();
        assert!((area(&outer) - domain.u.length() * domain.v.length()).abs() < 1e-6);
        let holes = face["trim"]["holes"].as_array().unwrap();
        assert_eq!(holes.len(), 1);
        for [u, v] in polyline(&holes[0]) {
            let p = slab.point_at(u, v);
            let radius = ((p.x - 9000.0).powi(2) + (p.y - 500.0).powi(2)).sqrt();
            assert!(
                (radius - 200.0).abs() < 1e-6,
                "({u}, {v}) -> {p}: radius {radius}"
            );
        }
    }
}
