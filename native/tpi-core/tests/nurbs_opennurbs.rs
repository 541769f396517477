//! Agreement with openNURBS: tests/conformance/rhino3dm_cases.py builds random NURBS surfaces
//! with the PyPI package rhino3dm and records NurbsSurface.PointAt / NormalAt; the surfaces are
//! rebuilt here from the recorded surface-file records (NurbsSpec) and must agree.
//!
//! Degrees 1..=11 (Rhino's limit, [`MAX_NURBS_DEGREE`]) in each direction, every pair of
//! degrees 6..=11 among them.
//!
//! The script runs at test time with `python3` (or the interpreter named by TPI_PYTHON). A
//! missing interpreter or a missing rhino3dm fails these tests; they never skip.

use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::OnceLock;

use glam::DVec3;
use serde::Deserialize;
use tpi_core::tolerance::MAX_NURBS_DEGREE;
use tpi_core::{NurbsSpec, NurbsSurface, Surface};

/// Points agree to this fraction of the control net's bounding-box diagonal.
const POINT_TOLERANCE: f64 = 1e-9;
/// Unit normals agree to this absolute distance.
const NORMAL_TOLERANCE: f64 = 1e-9;
/// The generator makes well-conditioned nets: |Su x Sv| >= this * |Su| |Sv| everywhere.
const MIN_SINE_SU_SV: f64 = 1e-3;

#[derive(Deserialize)]
struct CaseFile {
    generator: String,
    cases: Vec<Case>,
}

#[derive(Deserialize)]
struct Case {
    name: String,
    surface: NurbsSpec,
    domain_u: [f64; 2],
    domain_v: [f64; 2],
    samples: Vec<Sample>,
}

#[derive(Deserialize)]
struct Sample {
    u: f64,
    v: f64,
    point: [f64; 3],
    normal: [f64; 3],
}

fn script_path() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../tests/conformance/rhino3dm_cases.py")
}

/// Runs the generator once per test binary; every test that needs the cases fails with its
/// message if it could not run.
fn cases() -> &'static CaseFile {
    static CASES: OnceLock<Result<CaseFile, String>> = OnceLock::new();
    match CASES.get_or_init(generate_cases) {
        Ok(cases) => cases,
        Err(message) => panic!("{message}"),
    }
}

fn generate_cases() -> Result<CaseFile, String> {
    let dir = std::env::temp_dir().join(format!("tpi-nurbs-opennurbs-{}", std::process::id()));
    std::fs::create_dir_all(&dir).map_err(|e| format!("cannot create {}: {e}", dir.display()))?;
    let result = run_generator(&dir.join("cases.json"));
    let _ = std::fs::remove_dir_all(&dir);
    result
}

fn run_generator(out: &Path) -> Result<CaseFile, String> {
    let python = std::env::var("TPI_PYTHON").unwrap_or_else(|_| "python3".to_string());
    let script = script_path();
    let output = Command::new(&python)
        .arg(&script)
        .arg("--out")
        .arg(out)
        .output()
        .map_err(|e| {
            format!(
                "cannot run `{python}` for the openNURBS conformance cases ({e}). Install Python 3 and rhino3dm \
             (`python3 -m pip install 'rhino3dm==8.*'`), or point TPI_PYTHON at an interpreter that has it."
            )
        })?;
    if !output.status.success() {
        return Err(format!(
            "`{python} {}` failed ({}); rhino3dm is required (`{python} -m pip install 'rhino3dm==8.*'`):\n{}",
            script.display(),
            output.status,
            String::from_utf8_lossy(&output.stderr)
        ));
    }
    let text =
        std::fs::read_to_string(out).map_err(|e| format!("cannot read {}: {e}", out.display()))?;
    serde_json::from_str(&text).map_err(|e| format!("malformed conformance cases: {e}"))
}

fn build(case: &Case) -> NurbsSurface {
    // Through the surface-file format: serialise the record and read it back before building.
    let json = serde_json::to_string(&case.surface).expect("a NurbsSpec serialises");
    let spec: NurbsSpec = serde_json::from_str(&json).expect("a serialised NurbsSpec reads back");
    spec.build()
        .unwrap_or_else(|e| panic!("{}: rhino3dm's surface is rejected: {e}", case.name))
}

#[test]
fn conformance_cases_cover_the_required_range() {
    let file = cases();
    assert!(
        file.generator.starts_with("rhino3dm 8."),
        "generator {}",
        file.generator
    );
    assert!(
        file.cases.len() >= 200,
        "only {} surfaces",
        file.cases.len()
    );
    let mut degrees_seen = [[false; MAX_NURBS_DEGREE + 1]; 2];
    let mut high_degree_pairs = std::collections::BTreeSet::new();
    let (mut rational, mut non_rational) = (0, 0);
    for case in &file.cases {
        assert!(
            case.samples.len() >= 50,
            "{}: only {} samples",
            case.name,
            case.samples.len()
        );
        let spec = &case.surface;
        if spec.degree[0] > 5 && spec.degree[1] > 5 {
            high_degree_pairs.insert(spec.degree);
        }
        for direction in 0..2 {
            degrees_seen[direction][spec.degree[direction]] = true;
            let rhino_len = spec.count[direction] + spec.degree[direction] - 1;
            let knots = if direction == 0 {
                &spec.knots_u
            } else {
                &spec.knots_v
            };
            assert_eq!(
                knots.len(),
                rhino_len,
                "{}: Rhino's knot convention is count + degree - 1",
                case.name
            );
        }
        assert!(
            case.domain_u[0] != 0.0 && case.domain_v[0] != 0.0,
            "{}: domain starts at 0",
            case.name
        );
        if spec.weights.is_some() {
            rational += 1;
        } else {
            non_rational += 1;
        }
    }
    for (direction, seen) in degrees_seen.iter().enumerate() {
        assert!(
            seen[1..=MAX_NURBS_DEGREE].iter().all(|&s| s),
            "direction {direction}: degrees seen {seen:?}"
        );
    }
    // Every pair of degrees 6..=11 (Rhino's limit).
    assert_eq!(high_degree_pairs.len(), 36, "{high_degree_pairs:?}");
    assert!(
        rational >= 50 && non_rational >= 50,
        "{rational} rational, {non_rational} non-rational"
    );
}

#[test]
fn domains_agree_with_opennurbs() {
    for case in &cases().cases {
        let domain = build(case).domain();
        assert_eq!([domain.u.min, domain.u.max], case.domain_u, "{}", case.name);
        assert_eq!([domain.v.min, domain.v.max], case.domain_v, "{}", case.name);
    }
}

#[test]
fn points_agree_with_opennurbs() {
    let mut worst = (0.0, String::new());
    let mut compared = 0;
    for case in &cases().cases {
        let surface = build(case);
        let diagonal = surface.bounding_box_diagonal();
        for sample in &case.samples {
            let expected = DVec3::from_array(sample.point);
            for (what, point) in [
                ("evaluate", surface.evaluate(sample.u, sample.v).point),
                ("point_at", surface.point_at(sample.u, sample.v)),
            ] {
                let relative = (point - expected).length() / diagonal;
                assert!(
                    relative <= POINT_TOLERANCE,
                    "{}: {what} at ({}, {}) = {point}, openNURBS {expected}: off by {relative:e} of the net diagonal",
                    case.name,
                    sample.u,
                    sample.v
                );
                if relative > worst.0 {
                    worst = (relative, case.name.clone());
                }
            }
            compared += 1;
        }
    }
    println!(
        "{compared} points compared; worst relative deviation {:e} ({})",
        worst.0, worst.1
    );
}

#[test]
fn normals_agree_with_opennurbs() {
    let mut worst = (0.0, String::new());
    for case in &cases().cases {
        let surface = build(case);
        for sample in &case.samples {
            let d = surface.evaluate(sample.u, sample.v);
            let cross = d.su.cross(d.sv);
            let sine = cross.length() / (d.su.length() * d.sv.length());
            assert!(
                sine >= MIN_SINE_SU_SV,
                "{}: the generator made a nearly degenerate net at ({}, {}): sin(Su, Sv) = {sine:e}",
                case.name,
                sample.u,
                sample.v
            );
            let normal = cross / cross.length();
            let expected = DVec3::from_array(sample.normal);
            let deviation = (normal - expected).length();
            assert!(
                deviation <= NORMAL_TOLERANCE,
                "{}: normal at ({}, {}) = {normal}, openNURBS {expected}: off by {deviation:e}",
                case.name,
                sample.u,
                sample.v
            );
            if deviation > worst.0 {
                worst = (deviation, case.name.clone());
            }
        }
    }
    println!("worst normal deviation {:e} ({})", worst.0, worst.1);
}

/// The textbook vector: one superfluous knot more at each end (any value that keeps the vector
/// non-decreasing; it does not affect the surface).
fn textbook(knots: &[f64], extension: f64) -> Vec<f64> {
    let mut full = Vec::with_capacity(knots.len() + 2);
    full.push(knots[0] - extension);
    full.extend_from_slice(knots);
    full.push(knots[knots.len() - 1] + extension);
    full
}

#[test]
fn textbook_knots_give_identical_results() {
    for (index, case) in cases().cases.iter().enumerate() {
        let rhino = build(case);
        // Alternate between clamped-looking (repeated) and arbitrary superfluous end knots.
        let extension = if index % 2 == 0 {
            0.0
        } else {
            0.37 * (index as f64)
        };
        let spec = NurbsSpec {
            knots_u: textbook(&case.surface.knots_u, extension),
            knots_v: textbook(&case.surface.knots_v, extension),
            ..case.surface.clone()
        };
        let full = spec
            .build()
            .unwrap_or_else(|e| panic!("{}: textbook knots rejected: {e}", case.name));
        assert_eq!(full.domain(), rhino.domain(), "{}", case.name);
        assert_eq!(
            full.knots_u(),
            case.surface.knots_u.as_slice(),
            "{}",
            case.name
        );
        assert_eq!(
            full.knots_v(),
            case.surface.knots_v.as_slice(),
            "{}",
            case.name
        );
        for sample in &case.samples {
            assert_eq!(
                full.evaluate(sample.u, sample.v),
                rhino.evaluate(sample.u, sample.v),
                "{}",
                case.name
            );
            assert_eq!(
                full.point_at(sample.u, sample.v),
                rhino.point_at(sample.u, sample.v),
                "{}",
                case.name
            );
        }
    }
}

#[test]
fn to_spec_round_trips_rhino_records() {
    for case in &cases().cases {
        let surface = build(case);
        let spec = surface.to_spec();
        assert_eq!(spec, case.surface, "{}", case.name);
        assert_eq!(spec.build().as_ref(), Ok(&surface), "{}", case.name);
        assert_eq!(surface.degree(), case.surface.degree);
        assert_eq!(surface.count(), case.surface.count);
        assert_eq!(surface.is_rational(), case.surface.weights.is_some());
        assert_eq!(surface.weights(), case.surface.weights.as_deref());
        assert_eq!(surface.control_points().len(), case.surface.points.len());
    }
}
