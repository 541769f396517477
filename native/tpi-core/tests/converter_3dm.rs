//! tools/3dm_to_tpi.py (.3dm in, without Rhino): tests/converter/check_3dm_to_tpi.py builds a
//! model with rhino3dm (a NURBS dome, a degree 7 x 5 rational surface, a sphere, a box, a plane
//! trimmed by a circle, a capped cylinder, a slab with a hole; millimetres), converts it, and records rhino3dm's
//! points of the source geometry; the surface files are read here with tpi-core and must agree.
//!
//! Polysurfaces: the script also builds and converts a model of Breps with several faces (a
//! hyperbolic paraboloid z = x y / S as six bilinear faces from a quad mesh, a box, a capped
//! cylinder, an extruded polyline). The polysurface file of the paraboloid is discretised and checked against the
//! closed form (seeds on z = x y / S, facet vertices on the closed-form tangent plane of their
//! seed) and for one disc (Euler characteristic and boundary loops counted from the output
//! JSON's facet loops); its adjacency against the faces' centres; the box is refused with the
//! typed layout error.
//!
//! The script runs at test time with `python3` (or the interpreter named by TPI_PYTHON); a
//! missing interpreter or rhino3dm fails these tests, they never skip.

use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::OnceLock;

use glam::DVec3;
use serde::Deserialize;
use serde_json::Value;
use tpi_core::{
    discretise, DiscretiseOptions, Generator, Surface, SurfaceModel, SurfaceSpec, TpiError, Units,
};

/// Points agree to this fraction of the control net's bounding-box diagonal.
const POINT_TOLERANCE: f64 = 1e-9;

#[derive(Deserialize)]
struct Expected {
    poly_index: String,
    poly_off_index: String,
    hypar: Hypar,
    strip: Strip,
    unit_cases: Vec<UnitCase>,
    plain_index: String,
    trims_index: String,
    faces: Vec<ExpectedFace>,
}

/// z = x y / scale over [-x, x] x [-y, y], `quads` mesh quads in x and in y.
#[derive(Deserialize)]
struct Hypar {
    scale: f64,
    x: f64,
    y: f64,
    quads: [usize; 2],
}

/// The open polyline `profile` (in z = 0) extruded by `height` along z.
#[derive(Deserialize)]
struct Strip {
    profile: Vec<[f64; 2]>,
    height: f64,
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
    poly: Value,
    poly_off: Value,
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
    let poly = serde_json::from_str(&read(&expected.poly_index)?).map_err(|e| e.to_string())?;
    let poly_off =
        serde_json::from_str(&read(&expected.poly_off_index)?).map_err(|e| e.to_string())?;
    Ok(Run {
        dir,
        expected,
        plain,
        trims,
        poly,
        poly_off,
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

fn polysurface_records(index: &Value) -> &Vec<Value> {
    index["polysurfaces"].as_array().expect("polysurfaces")
}

fn polysurface_record(object: u64) -> &'static Value {
    polysurface_records(&run().poly)
        .iter()
        .find(|p| p["object"] == object)
        .unwrap_or_else(|| panic!("no polysurface record for object {object}"))
}

/// The text of a file the polysurface conversion wrote.
fn poly_text(file: &str) -> String {
    surface_text("poly", file)
}

#[test]
fn breps_of_untrimmed_faces_become_polysurface_files_and_trimmed_ones_do_not() {
    let run = run();
    let records = polysurface_records(&run.poly);
    // The three Breps have several faces; nothing else is listed.
    let objects: Vec<u64> = records
        .iter()
        .map(|p| p["object"].as_u64().unwrap())
        .collect();
    assert_eq!(objects, [0, 1, 2, 3]);
    let index_faces = faces(&run.poly);
    for record in [&records[0], &records[1], &records[3]] {
        let file = record["file"].as_str().expect("a polysurface file");
        assert!(record["not_written"].is_null(), "{record}");
        let text: Value = serde_json::from_str(&poly_text(file)).unwrap();
        assert_eq!(text["type"], "polysurface");
        assert_eq!(text["units"], "mm");
        let listed = text["faces"].as_array().unwrap();
        let expected = if record["object"] == 3 { 3 } else { 6 };
        assert_eq!(listed.len(), expected, "{file}");
        // Each face is its own surface file, untrimmed, in the Brep's order.
        for (k, face) in listed.iter().enumerate() {
            let g = record["faces"][k].as_u64().unwrap() as usize;
            let entry = &index_faces[g];
            assert_eq!(entry["object"], record["object"]);
            assert_eq!(entry["face"], k as u64);
            assert_eq!(entry["trimmed"], false);
            let own: Value =
                serde_json::from_str(&poly_text(entry["file"].as_str().unwrap())).unwrap();
            assert_eq!(face, &own, "{file} faces[{k}]");
            assert!(face.get("trim").is_none());
        }
        // tpi reads the file (the layout may still refuse it: the box, below).
        SurfaceSpec::from_json(&poly_text(file), file).unwrap();
    }
    // The capped cylinder: its caps are trimmed, so no file, and the record says which.
    let cylinder = &records[2];
    assert!(cylinder["file"].is_null());
    let reason = cylinder["not_written"].as_str().unwrap();
    let trimmed: Vec<&str> = index_faces
        .iter()
        .filter(|f| f["object"] == 2 && f["trimmed"] == true)
        .map(|f| f["file"].as_str().unwrap())
        .collect();
    assert_eq!(trimmed.len(), 2);
    for file in trimmed {
        assert!(reason.contains(file), "{reason}");
    }
    assert!(reason.contains("trim"), "{reason}");
    // --no-polysurfaces: the same records, no files.
    let off = polysurface_records(&run.poly_off);
    assert_eq!(off.len(), 4);
    for record in off {
        assert!(record["file"].is_null(), "{record}");
    }
    assert_eq!(off[0]["not_written"], "--no-polysurfaces");
    assert_eq!(off[2]["not_written"], cylinder["not_written"]);
    assert_eq!(off[0]["adjacency"], records[0]["adjacency"]);
    let written: Vec<String> = std::fs::read_dir(run.dir.join("poly-off"))
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|name| name.ends_with("_polysurface.json"))
        .collect();
    assert!(written.is_empty(), "{written:?}");
}

/// The faces of a polysurface file, each built on its own.
fn polysurface_faces(file: &str) -> Vec<SurfaceModel> {
    let text: Value = serde_json::from_str(&poly_text(file)).unwrap();
    text["faces"]
        .as_array()
        .unwrap()
        .iter()
        .map(|f| {
            SurfaceSpec::from_json(&f.to_string(), file)
                .and_then(|s| s.build())
                .unwrap()
        })
        .collect()
}

fn corners(face: &SurfaceModel) -> Vec<DVec3> {
    let d = face.domain();
    [
        (d.u.min, d.v.min),
        (d.u.max, d.v.min),
        (d.u.max, d.v.max),
        (d.u.min, d.v.max),
    ]
    .iter()
    .map(|&(u, v)| face.point_at(u, v))
    .collect()
}

/// The adjacency pairs of a record, as (smaller, larger) positions in its faces.
fn adjacency(record: &Value) -> Vec<(usize, usize, DVec3, DVec3)> {
    let point = |v: &Value| DVec3::from_array(serde_json::from_value(v.clone()).unwrap());
    record["adjacency"]
        .as_array()
        .unwrap()
        .iter()
        .map(|a| {
            let pair: [usize; 2] = serde_json::from_value(a["faces"].clone()).unwrap();
            assert_ne!(pair[0], pair[1]);
            (
                pair[0].min(pair[1]),
                pair[0].max(pair[1]),
                point(&a["start"]),
                point(&a["end"]),
            )
        })
        .collect()
}

#[test]
fn polysurface_adjacency_is_the_faces_shared_sides() {
    let hypar = &run().expected.hypar;
    let record = polysurface_record(0);
    let faces = polysurface_faces(record["file"].as_str().unwrap());
    let [nx, ny] = hypar.quads;
    assert_eq!(faces.len(), nx * ny);
    // Independently of the Brep's topology: two quads of the mesh are neighbours when their
    // centres are one quad apart in x or in y (the faces are pieces of one graph over xy).
    let (step_x, step_y) = (2.0 * hypar.x / nx as f64, 2.0 * hypar.y / ny as f64);
    let centre = |f: &SurfaceModel| {
        let d = f.domain();
        f.point_at(d.u.lerp(0.5), d.v.lerp(0.5))
    };
    let mut expected = Vec::new();
    for a in 0..faces.len() {
        for b in a + 1..faces.len() {
            let (p, q) = (centre(&faces[a]), centre(&faces[b]));
            let (dx, dy) = ((p.x - q.x).abs(), (p.y - q.y).abs());
            if ((dx - step_x).abs() < 1e-6 && dy < 1e-6)
                || ((dy - step_y).abs() < 1e-6 && dx < 1e-6)
            {
                expected.push((a, b));
            }
        }
    }
    assert_eq!(expected.len(), (nx - 1) * ny + nx * (ny - 1));
    let pairs = adjacency(record);
    let mut found: Vec<(usize, usize)> = pairs.iter().map(|&(a, b, _, _)| (a, b)).collect();
    found.sort_unstable();
    assert_eq!(found, expected);
    // Each shared edge runs between two corners of both its faces: a whole side.
    for &(a, b, start, end) in &pairs {
        for f in [a, b] {
            for p in [start, end] {
                assert!(
                    corners(&faces[f]).iter().any(|c| c.distance(p) < 1e-9),
                    "faces[{f}]: edge end {p} is not a corner"
                );
            }
        }
    }
    // The box: 12 edges, each face next to 4 others, never its opposite.
    let pairs = adjacency(polysurface_record(1));
    assert_eq!(pairs.len(), 12);
    let mut count = [0; 6];
    for &(a, b, _, _) in &pairs {
        count[a] += 1;
        count[b] += 1;
    }
    assert_eq!(count, [4; 6]);
}

/// V - E + F and the number of boundary loops of facet loops (each a list of vertex
/// indices), counted from the loops alone.
fn euler_and_boundary_loops(loops: &[Vec<usize>]) -> (i64, usize) {
    use std::collections::{BTreeMap, BTreeSet};
    let mut edges: BTreeMap<(usize, usize), usize> = BTreeMap::new();
    let mut vertices = BTreeSet::new();
    for facet in loops {
        for k in 0..facet.len() {
            let (a, b) = (facet[k], facet[(k + 1) % facet.len()]);
            vertices.insert(a);
            *edges.entry((a.min(b), a.max(b))).or_insert(0) += 1;
        }
    }
    assert!(
        edges.values().all(|&n| n <= 2),
        "an edge used by more than two facets"
    );
    let euler = vertices.len() as i64 - edges.len() as i64 + loops.len() as i64;
    // Boundary loops: connected components of the edges used once.
    let boundary: Vec<(usize, usize)> = edges
        .iter()
        .filter(|(_, &n)| n == 1)
        .map(|(&e, _)| e)
        .collect();
    let mut parent: BTreeMap<usize, usize> = BTreeMap::new();
    fn root(parent: &mut BTreeMap<usize, usize>, x: usize) -> usize {
        let p = *parent.entry(x).or_insert(x);
        if p == x {
            x
        } else {
            let r = root(parent, p);
            parent.insert(x, r);
            r
        }
    }
    for &(a, b) in &boundary {
        let (ra, rb) = (root(&mut parent, a), root(&mut parent, b));
        parent.insert(ra, rb);
    }
    let ends: BTreeSet<usize> = boundary.iter().flat_map(|&(a, b)| [a, b]).collect();
    let loops_count = ends
        .iter()
        .map(|&v| root(&mut parent, v))
        .collect::<BTreeSet<_>>()
        .len();
    (euler, loops_count)
}

#[test]
fn hyperbolic_paraboloid_polysurface_discretises_on_its_tangent_planes() {
    let hypar = &run().expected.hypar;
    let file = polysurface_record(0)["file"].as_str().unwrap();
    let spec = SurfaceSpec::from_json(&poly_text(file), file).unwrap();
    let model = spec
        .build()
        .unwrap_or_else(|e| panic!("{file}: tpi refuses the polysurface: {e}"));
    let SurfaceModel::Polysurface(layout) = &model else {
        panic!("{file}: not a polysurface")
    };
    let [nx, ny] = hypar.quads;
    let (columns, rows) = layout.grid();
    assert!(
        (columns, rows) == (nx, ny) || (columns, rows) == (ny, nx),
        "{columns} x {rows}"
    );
    assert_eq!(model.units(), Some(Units::Millimetres));
    let pattern = Generator::parse("hex:20x20").unwrap().generate();
    let result = discretise(&model, &pattern.uv, &DiscretiseOptions::default())
        .unwrap_or_else(|e| panic!("{file}: {e}"));
    // What `tpi discretise --out result.json` writes, read back as JSON.
    let output: Value = serde_json::from_str(&result.to_json(false)).unwrap();
    assert_eq!(output["units"], "mm");
    let vertices: Vec<DVec3> = output["vertices"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| DVec3::from_array(serde_json::from_value(v.clone()).unwrap()))
        .collect();
    let facets = output["facets"].as_array().unwrap();
    assert_eq!(facets.len(), 400);
    let loops: Vec<Vec<usize>> = facets
        .iter()
        .map(|f| serde_json::from_value(f["vertices"].clone()).unwrap())
        .collect();
    assert_eq!(euler_and_boundary_loops(&loops), (1, 1), "not one disc");
    // The closed form: z = x y / S, normal along (-y / S, -x / S, 1).
    let size = (2.0 * hypar.x).hypot(2.0 * hypar.y);
    let mut per_quad = vec![0usize; nx * ny];
    let mut up = None;
    let mut worst = 0.0f64;
    for (i, facet) in facets.iter().enumerate() {
        let point: [f64; 3] = serde_json::from_value(facet["point"].clone()).unwrap();
        let p = DVec3::from_array(point);
        assert!(
            (p.z - p.x * p.y / hypar.scale).abs() < 1e-9 * size,
            "facet {i}: seed {p} off the paraboloid"
        );
        let n = DVec3::new(-p.y / hypar.scale, -p.x / hypar.scale, 1.0).normalize();
        let given = DVec3::from_array(serde_json::from_value(facet["normal"].clone()).unwrap());
        assert!(
            n.cross(given).length() < 1e-9,
            "facet {i}: normal {given}, closed form {n}"
        );
        // One orientation over all faces.
        let sign = given.dot(n) > 0.0;
        assert_eq!(*up.get_or_insert(sign), sign, "facet {i}: normal flipped");
        for &v in &loops[i] {
            let off = (vertices[v] - p).dot(n).abs();
            worst = worst.max(off / size);
            assert!(
                off < 1e-9 * size,
                "facet {i}: vertex {v} {off} off the seed's tangent plane"
            );
        }
        let qx = (((p.x + hypar.x) / (2.0 * hypar.x) * nx as f64) as usize).min(nx - 1);
        let qy = (((p.y + hypar.y) / (2.0 * hypar.y) * ny as f64) as usize).min(ny - 1);
        per_quad[qx * ny + qy] += 1;
    }
    // The pattern spreads over the faces (equal quads: about equally).
    let fair = 400.0 / (nx * ny) as f64;
    assert!(
        per_quad
            .iter()
            .all(|&n| n as f64 > 0.7 * fair && (n as f64) < 1.3 * fair),
        "seeds per face {per_quad:?}"
    );
    println!("seeds per face {per_quad:?}, worst vertex off its plane {worst:e} of the size");
}

/// The extruded polyline: its three wall faces laid out as a strip, in the profile's order,
/// the strip as long as the profile (the columns' widths are the faces' lengths) and as high
/// as the extrusion.
#[test]
fn an_extruded_polyline_is_a_strip_as_long_as_its_profile() {
    let strip = &run().expected.strip;
    let file = polysurface_record(3)["file"].as_str().unwrap();
    let model = SurfaceSpec::from_json(&poly_text(file), file)
        .and_then(|s| s.build())
        .unwrap_or_else(|e| panic!("{file}: {e}"));
    let SurfaceModel::Polysurface(layout) = &model else {
        panic!("{file}: not a polysurface")
    };
    let segments = strip.profile.len() - 1;
    let length: f64 = strip
        .profile
        .windows(2)
        .map(|w| (w[1][0] - w[0][0]).hypot(w[1][1] - w[0][1]))
        .sum();
    let (columns, rows) = layout.grid();
    let d = model.domain();
    let (along, across, cells): (f64, f64, Vec<usize>) = if rows == 1 {
        assert_eq!(columns, segments);
        let cells = (0..columns).map(|i| layout.face_of_cell(i, 0).unwrap());
        (d.u.length(), d.v.length(), cells.collect())
    } else {
        assert_eq!((columns, rows), (1, segments));
        let cells = (0..rows).map(|j| layout.face_of_cell(0, j).unwrap());
        (d.v.length(), d.u.length(), cells.collect())
    };
    assert!(
        (along - length).abs() < 1e-9 * length,
        "{along} vs {length}"
    );
    assert!(
        (across - strip.height).abs() < 1e-9 * strip.height,
        "{across}"
    );
    // Cell k holds the wall of segment k (or of segment n - 1 - k: a strip read backwards).
    let faces = polysurface_faces(file);
    let segment_of = |face: usize| {
        let f = &faces[face];
        let dom = f.domain();
        let c = f.point_at(dom.u.lerp(0.5), dom.v.lerp(0.5));
        assert!((c.z - 0.5 * strip.height).abs() < 1e-9 * strip.height);
        (0..segments)
            .find(|&k| {
                let (a, b) = (strip.profile[k], strip.profile[k + 1]);
                let mid = [(a[0] + b[0]) / 2.0, (a[1] + b[1]) / 2.0];
                (c.x - mid[0]).hypot(c.y - mid[1]) < 1e-6 * length
            })
            .unwrap_or_else(|| panic!("face {face}: centre {c} on no segment's wall"))
    };
    let order: Vec<usize> = cells.iter().map(|&f| segment_of(f)).collect();
    let forward: Vec<usize> = (0..segments).collect();
    let backward: Vec<usize> = (0..segments).rev().collect();
    assert!(order == forward || order == backward, "{order:?}");
}

#[test]
fn a_closed_box_is_refused_naming_the_layout() {
    let file = polysurface_record(1)["file"].as_str().unwrap();
    let spec = SurfaceSpec::from_json(&poly_text(file), file).unwrap();
    match spec.build() {
        Err(TpiError::InvalidPolysurface { item, reason }) => {
            assert_eq!(item, "faces");
            assert!(
                reason.contains("do not fill a rectangle of rows and columns"),
                "{reason}"
            );
        }
        Err(other) => panic!("{file}: expected InvalidPolysurface, got {other}"),
        Ok(_) => panic!("{file}: a closed box laid out as rows and columns"),
    }
}
