//! Issue 16, polysurfaces: several faces sharing whole sides are discretised as one shell.
//!
//! Oracles, independent of the production path:
//! - a convex polysurface with a crease (four NURBS faces, in any order and orientation): every
//!   facet away from the boundary is exactly its face on the envelope of *all* tangent planes
//!   (`common::envelope_face`, Sutherland-Hodgman against every other plane), the mesh is one
//!   disc (Euler characteristic and loops from the facet loops alone) and valid by the
//!   independent check (`common::validity`, `geo` overlap areas);
//! - a saddle split into two analytic faces at its middle is the same surface as the single
//!   face, so it gives the same mesh;
//! - an ellipsoid made of two half faces (each with two poles) closes: Euler characteristic 2,
//!   and no vertex lies in front of any tangent plane of the closed-form ellipsoid.
#![allow(clippy::needless_range_loop)]

mod common;

use std::collections::BTreeSet;

use common::validity;
use common::*;
use glam::DVec3;
use tpi_core::{
    discretise, AnalyticKind, AnalyticSurface, Discretisation, DiscretiseOptions, Generator,
    MeshTopology, NurbsSurface, Polysurface, Surface, SurfaceModel, SurfaceSpec, TpiError, Trim,
};

const TOL: f64 = 1e-9;

fn joined(faces: Vec<SurfaceModel>) -> SurfaceModel {
    SurfaceModel::Polysurface(Box::new(
        Polysurface::new(faces).unwrap_or_else(|e| panic!("faces rejected: {e}")),
    ))
}

fn generated(spec: &str) -> Vec<[f64; 2]> {
    Generator::parse(spec).unwrap().generate().uv
}

/// The roof z = 1 - a x^2 - 0.4 y^2 - 0.25 |x| over [-1, 1]^2: smooth on each side of x = 0, a
/// convex crease along it.
fn roof(x: f64, y: f64) -> f64 {
    let a = if x < 0.0 { 0.3 } else { 0.5 };
    1.0 - a * x * x - 0.4 * y * y - 0.25 * x.abs()
}

/// One quadrant of the roof as a bicubic NURBS, placed in its parameters by `orientation`
/// (bit 0 swaps u and v, bit 1 reverses x, bit 2 reverses y), so that the faces meet in every
/// way Rhino's faces can.
fn roof_face(x: [f64; 2], y: [f64; 2], orientation: u8) -> SurfaceModel {
    let knots = [0.0, 0.0, 0.0, 0.3, 0.7, 1.0, 1.0, 1.0];
    let xy = move |s: f64, t: f64| {
        let (s, t) = if orientation & 1 != 0 { (t, s) } else { (s, t) };
        let s = if orientation & 2 != 0 { 1.0 - s } else { s };
        let t = if orientation & 4 != 0 { 1.0 - t } else { t };
        (x[0] + s * (x[1] - x[0]), y[0] + t * (y[1] - y[0]))
    };
    // Lift on the face's own side of the crease (its centre decides), so that both faces along
    // x = 0 share their edge's control points exactly.
    let side = 0.5 * (x[0] + x[1]);
    let lifted = lifted_net(
        [3, 3],
        &knots,
        &knots,
        xy,
        |px, py, _, _| {
            let a = if side < 0.0 { 0.3 } else { 0.5 };
            1.0 - a * px * px - 0.4 * py * py - 0.25 * px.abs()
        },
        None,
    );
    SurfaceModel::Nurbs(lifted)
}

fn creased_roof() -> SurfaceModel {
    // Given out of grid order, each face placed differently.
    joined(vec![
        roof_face([0.0, 1.0], [0.0, 1.0], 0b011),
        roof_face([-1.0, 0.0], [-1.0, 0.0], 0),
        roof_face([-1.0, 0.0], [0.0, 1.0], 0b101),
        roof_face([0.0, 1.0], [-1.0, 0.0], 0b110),
    ])
}

/// One disc, valid by the independent check, sanity check passed.
fn assert_valid_disc(name: &str, d: &Discretisation, n: usize) {
    assert_eq!(d.facet_count(), n, "{name}: one facet per seed");
    d.sanity_check()
        .unwrap_or_else(|e| panic!("{name}: sanity check: {e}"));
    let t = topology(d);
    assert!(t.problems.is_empty(), "{name}: {:?}", t.problems);
    assert_eq!(
        (t.components, t.euler, t.boundary_loops),
        (1, 1, 1),
        "{name}: not one disc (an open seam would add a loop)"
    );
    let v = validity::check(d);
    assert!(
        v.invalid_facets().is_empty() && v.is_disc(),
        "{name}: invalid facets {:?}",
        v.invalid_facets()
    );
}

#[test]
fn creased_convex_polysurface_is_the_envelope_of_all_tangent_planes() {
    let surface = creased_roof();
    let SurfaceModel::Polysurface(p) = &surface else {
        unreachable!()
    };
    assert_eq!(p.grid(), (2, 2));
    let mut rng = Rng::new(16);
    for (k, &n) in [300usize, 1200].iter().enumerate() {
        let pattern = if k == 0 {
            uniform_pattern(&mut rng, n)
        } else {
            jittered_pattern(&mut rng, n)
        };
        let d = discretise(&surface, &pattern, &DiscretiseOptions::default()).unwrap();
        let name = format!("creased roof n={n}");
        assert_valid_disc(&name, &d, n);
        // Seeds lie on the roof (the closed form, which the control nets approximate to about
        // 0.03): the layout maps every pattern point onto the right face.
        let diag = seed_diagonal(&d);
        for s in &d.seeds {
            let p = s.point;
            assert!(
                (p.z - roof(p.x, p.y)).abs() < 0.05,
                "{name}: seed {p} far from the roof"
            );
        }
        let points: Vec<DVec3> = d.seeds.iter().map(|s| s.point).collect();
        let normals: Vec<DVec3> = d.seeds.iter().map(|s| s.normal).collect();
        let sides = sides_from_samples(&surface, &points, &normals);
        let topo = topology(&d);
        let (mut checked, mut across_crease) = (0, 0);
        for i in 0..n {
            if touches_boundary(&d, i) {
                continue;
            }
            checked += 1;
            let face = envelope_face(i, &points, &normals, &sides, 10.0 * diag, TOL * diag);
            let expected = face.neighbours();
            let allowed: BTreeSet<usize> = expected
                .union(&face.ambiguous.iter().copied().collect())
                .copied()
                .collect();
            let mine = &topo.neighbours[i];
            assert!(
                face.bounded && expected.is_subset(mine) && mine.is_subset(&allowed),
                "{name}: facet {i} neighbours {mine:?}, envelope {expected:?}"
            );
            let mesh_loop = merge_loop(&facet_points(&d, i), TOL * diag);
            assert!(
                cyclic_match(&mesh_loop, &face.vertices, TOL * diag).is_some(),
                "{name}: facet {i} vertices differ from the envelope's"
            );
            if mine
                .iter()
                .any(|&j| (points[j].x < 0.0) != (points[i].x < 0.0))
            {
                across_crease += 1;
            }
        }
        assert!(checked * 2 > n, "{name}: only {checked} interior facets");
        assert!(
            across_crease > 0,
            "{name}: no facet has a neighbour across the crease"
        );
    }
}

fn hypar(x: [f64; 2]) -> SurfaceModel {
    SurfaceModel::Analytic(
        AnalyticSurface::new(
            AnalyticKind::HyperbolicParaboloid { a: 0.4, b: 0.4 },
            x,
            [-1.0, 1.0],
        )
        .unwrap(),
    )
}

#[test]
fn saddle_split_in_two_faces_gives_the_single_face_mesh() {
    let single = hypar([-1.0, 1.0]);
    let halves = joined(vec![hypar([0.0, 1.0]), hypar([-1.0, 0.0])]);
    for spec in ["hex:16x18", "grid:15x15", "jitter:14x14:seed=2"] {
        let pattern = generated(spec);
        let n = pattern.len();
        let options = DiscretiseOptions::default();
        let a = discretise(&single, &pattern, &options).unwrap();
        let b = discretise(&halves, &pattern, &options).unwrap();
        let name = format!("saddle {spec}");
        assert_valid_disc(&name, &b, n);
        let diag = seed_diagonal(&a);
        for i in 0..n {
            let (pa, pb) = (facet_points(&a, i), facet_points(&b, i));
            assert_eq!(pa.len(), pb.len(), "{name}: facet {i}");
            let far = pa
                .iter()
                .zip(&pb)
                .map(|(x, y)| x.distance(*y))
                .fold(0.0, f64::max);
            assert!(far <= TOL * diag, "{name}: facet {i} moved by {far:e}");
        }
    }
}

#[test]
fn uneven_faces_spread_a_pattern_by_length_and_stay_valid() {
    // A saddle cut at x = -0.6: columns as wide as the faces are long, so a uniform pattern
    // keeps one density across the cut.
    let surface = joined(vec![hypar([-1.0, -0.6]), hypar([-0.6, 1.0])]);
    let pattern = generated("hex:20x20");
    let d = discretise(&surface, &pattern, &DiscretiseOptions::default()).unwrap();
    assert_valid_disc("uneven saddle", &d, pattern.len());
    let left = d.seeds.iter().filter(|s| s.point.x < -0.6).count() as f64;
    let share = left / pattern.len() as f64;
    assert!(
        (share - 0.2).abs() < 0.05,
        "{share} of the points on the face that is a fifth of the width"
    );
}

/// Half of the ellipsoid x^2/a^2 + y^2/b^2 + z^2/c^2 = 1: a rational quadratic half circle in u
/// (from angle `start`, in quarter turns), a half meridian from pole to pole in v.
fn half_ellipsoid(axes: [f64; 3], start: usize) -> SurfaceModel {
    let w = std::f64::consts::FRAC_1_SQRT_2;
    let circle = rational_circle();
    let meridian = [
        (0.0, -1.0, 1.0),
        (1.0, -1.0, w),
        (1.0, 0.0, 1.0),
        (1.0, 1.0, w),
        (0.0, 1.0, 1.0),
    ];
    let mut points = Vec::new();
    let mut weights = Vec::new();
    for k in 0..5 {
        let (x, y, wu) = circle[(2 * start + k) % 8];
        for &(r, z, wv) in &meridian {
            points.push(DVec3::new(axes[0] * x * r, axes[1] * y * r, axes[2] * z));
            weights.push(wu * wv);
        }
    }
    let knots = [0.0, 0.0, 1.0, 1.0, 2.0, 2.0];
    SurfaceModel::Nurbs(
        NurbsSurface::new([2, 2], [5, 5], &knots, &knots, &points, Some(&weights)).unwrap(),
    )
}

#[test]
fn ellipsoid_of_two_faces_closes_with_the_envelope() {
    let axes = [1.5, 1.0, 0.8];
    let surface = joined(vec![half_ellipsoid(axes, 0), half_ellipsoid(axes, 2)]);
    let layout = tpi_core::surface_layout(&surface);
    assert!(layout.is_sphere(), "{layout:?}");
    let pattern = generated("random:600:seed=9");
    let d = discretise(&surface, &pattern, &DiscretiseOptions::default()).unwrap();
    assert_eq!(d.facet_count(), pattern.len());
    assert_eq!(
        d.topology,
        MeshTopology {
            euler: 2,
            boundary_loops: 0
        }
    );
    d.sanity_check().unwrap();
    let t = topology(&d);
    assert_eq!((t.euler, t.boundary_loops), (2, 0));
    let [a, b, c] = axes;
    let tolerance = 1e-9 * 2.0 * (a * a + b * b + c * c).sqrt();
    let planes: Vec<(DVec3, DVec3)> = d
        .seeds
        .iter()
        .map(|s| {
            let p = s.point;
            let on = (p.x / a).powi(2) + (p.y / b).powi(2) + (p.z / c).powi(2);
            assert!((on - 1.0).abs() < 1e-12, "seed {p} off the ellipsoid");
            let normal = DVec3::new(p.x / (a * a), p.y / (b * b), p.z / (c * c)).normalize();
            (p, normal)
        })
        .collect();
    for (v, x) in d.vertices.iter().enumerate() {
        for (i, (p, normal)) in planes.iter().enumerate() {
            assert!(
                normal.dot(*x - *p) <= tolerance,
                "vertex {v} lies in front of the tangent plane of seed {i}"
            );
        }
    }
    for i in 0..d.facet_count() {
        let (p, normal) = planes[i];
        let flat = to_2d(p, normal, &facet_points(&d, i));
        assert!(is_simple(&flat) && is_convex(&flat), "facet {i}");
    }
}

fn expect_invalid(faces: Vec<SurfaceModel>, item: &str, words: &str) {
    match Polysurface::new(faces) {
        Err(TpiError::InvalidPolysurface { item: got, reason }) => {
            assert_eq!(got, item, "{reason}");
            assert!(reason.contains(words), "{reason}");
        }
        other => panic!("expected InvalidPolysurface for {item}, got {other:?}"),
    }
}

#[test]
fn faces_that_cannot_be_laid_out_are_named() {
    // Apart: the second face touches the first only at a corner.
    expect_invalid(
        vec![
            roof_face([-1.0, 0.0], [-1.0, 0.0], 0),
            roof_face([0.0, 1.0], [0.0, 1.0], 0),
        ],
        "faces[1]",
        "shares no whole side",
    );
    // Three quadrants: an L, not a rectangle.
    expect_invalid(
        vec![
            roof_face([-1.0, 0.0], [-1.0, 0.0], 0),
            roof_face([0.0, 1.0], [-1.0, 0.0], 0),
            roof_face([-1.0, 0.0], [0.0, 1.0], 0),
        ],
        "faces",
        "rectangle",
    );
    // A trimmed face.
    let trimmed = SurfaceModel::trimmed(
        hypar([0.0, 1.0]),
        Trim {
            outer: vec![[0.1, -0.9], [0.9, -0.9], [0.9, 0.9], [0.1, 0.9]],
            holes: vec![],
        },
    )
    .unwrap();
    expect_invalid(vec![hypar([-1.0, 0.0]), trimmed], "faces[1]", "trimmed");
    expect_invalid(vec![], "faces", "1 to");
}

#[test]
fn polysurface_record_reads_builds_and_writes_back() {
    let text = r#"{"type": "polysurface", "units": "mm", "faces": [
        {"type": "hyperbolic_paraboloid", "a": 0.4, "b": 0.4, "x": [0, 1], "y": [-1, 1]},
        {"type": "hyperbolic_paraboloid", "a": 0.4, "b": 0.4, "x": [-1, 0], "y": [-1, 1]}]}"#;
    let spec = SurfaceSpec::from_json(text, "two.json").unwrap();
    assert_eq!(spec.type_name(), "polysurface");
    let model = spec.build().unwrap();
    assert_eq!(tpi_core::units_label(model.units()), "mm");
    assert_eq!(model.to_spec().build().unwrap(), model);
    let back: SurfaceSpec = serde_json::from_str(&serde_json::to_string(&spec).unwrap()).unwrap();
    assert_eq!(back, spec);
    // A face that is not valid on its own is named with its index.
    let bad = text.replace(
        "\"a\": 0.4, \"b\": 0.4, \"x\": [-1, 0]",
        "\"a\": 0, \"b\": 0.4, \"x\": [-1, 0]",
    );
    let err = SurfaceSpec::from_json(&bad, "two.json")
        .unwrap()
        .build()
        .unwrap_err();
    assert!(err.to_string().starts_with("faces[1]: "), "{err}");
    // Unknown fields are refused.
    let extra = text.replace("\"units\": \"mm\"", "\"edges\": []");
    assert!(SurfaceSpec::from_json(&extra, "two.json").is_err());
}

#[test]
fn live_edits_on_a_polysurface_equal_fresh_runs() {
    let surface = creased_roof();
    let mut rng = Rng::new(77);
    let pattern = uniform_pattern(&mut rng, 400);
    let options = DiscretiseOptions::default();
    let mut live =
        tpi_core::LiveSurface::new(Box::new(surface.clone()), pattern.clone(), options).unwrap();
    let mut points = pattern;
    for edit in 0..40 {
        let i = (rng.next_u64() % points.len() as u64) as usize;
        // Across the crease and the smooth seam too: anywhere in the unit square.
        let to = [rng.range(0.001, 0.999), rng.range(0.001, 0.999)];
        live.move_point(i, to).unwrap();
        points[i] = to;
        let fresh = discretise(&surface, &points, &options).unwrap();
        assert_eq!(
            live.discretisation().to_json(false),
            fresh.to_json(false),
            "edit {edit}: live result differs from a fresh run"
        );
    }
}
