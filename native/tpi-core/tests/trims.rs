//! Trimmed surfaces (issue 16): a dome trimmed to a disc, and to a disc with a hole.
//!
//! Oracles, all computed here: which pattern points lie inside the trim (even-odd
//! point-in-polygon), the closest surface point of every boundary vertex (grid search and
//! Newton, `common::closest_parameters`) and its distance from the trim polylines, the
//! topology (Euler characteristic, boundary loops) from the facet loops, and the envelope of
//! the tangent planes of the kept points (an interior vertex of a graph surface convex
//! upwards lies on or above every tangent plane).

mod common;

use common::*;
use glam::DVec3;
use tpi_core::{
    discretise, Diagnostic, Discretisation, DiscretiseOptions, Generator, LiveSurface, PlaneMode,
    Surface, SurfaceModel, SurfaceSpec, TpiError, Trim, VertexKind,
};

/// A circle of `n` points, counter-clockwise (or clockwise).
fn circle(centre: [f64; 2], radius: f64, n: usize, ccw: bool) -> Vec<[f64; 2]> {
    (0..n)
        .map(|k| {
            let a = std::f64::consts::TAU * k as f64 / n as f64;
            let a = if ccw { a } else { -a };
            [centre[0] + radius * a.cos(), centre[1] + radius * a.sin()]
        })
        .collect()
}

fn in_polygon(points: &[[f64; 2]], p: [f64; 2]) -> bool {
    let mut inside = false;
    let n = points.len();
    let mut j = n - 1;
    for i in 0..n {
        let (a, b) = (points[i], points[j]);
        if (a[1] > p[1]) != (b[1] > p[1])
            && p[0] < (b[0] - a[0]) * (p[1] - a[1]) / (b[1] - a[1]) + a[0]
        {
            inside = !inside;
        }
        j = i;
    }
    inside
}

fn segment_distance(p: [f64; 2], a: [f64; 2], b: [f64; 2]) -> f64 {
    let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
    let t = (((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / (dx * dx + dy * dy)).clamp(0.0, 1.0);
    (a[0] + t * dx - p[0]).hypot(a[1] + t * dy - p[1])
}

fn polyline_distance(loops: &[Vec<[f64; 2]>], p: [f64; 2]) -> f64 {
    loops
        .iter()
        .flat_map(|l| (0..l.len()).map(move |k| segment_distance(p, l[k], l[(k + 1) % l.len()])))
        .fold(f64::INFINITY, f64::min)
}

/// The trim's loops, outer first.
fn loops_of(trim: &Trim) -> Vec<Vec<[f64; 2]>> {
    std::iter::once(trim.outer.clone())
        .chain(trim.holes.iter().cloned())
        .collect()
}

/// The pattern points inside the loops by the even-odd rule, in pattern order.
fn points_inside(
    domain: &tpi_core::Domain,
    loops: &[Vec<[f64; 2]>],
    pattern: &[[f64; 2]],
) -> Vec<usize> {
    (0..pattern.len())
        .filter(|&i| {
            let uv = domain.from_normalised(pattern[i]);
            loops.iter().filter(|l| in_polygon(l, uv)).count() % 2 == 1
        })
        .collect()
}

/// The surface of the surface file `record` (JSON) with `trim` added, read as a file is.
fn trimmed(record: serde_json::Value, trim: &Trim) -> SurfaceModel {
    let mut value = record;
    value["trim"] = serde_json::to_value(trim).unwrap();
    SurfaceSpec::from_json(&value.to_string(), "surface")
        .unwrap()
        .build()
        .unwrap()
}

/// [`trimmed`] of a surface file's text.
fn trimmed_text(text: &str, trim: &Trim) -> SurfaceModel {
    trimmed(serde_json::from_str(text).unwrap(), trim)
}

fn surface(kind: &str, trim: &Trim) -> SurfaceModel {
    let text = match kind {
        "paraboloid" => {
            r#"{"type": "elliptic_paraboloid", "a": 0.5, "b": 0.3, "x": [-1, 1], "y": [-1, 1]}"#
        }
        _ => r#"{"type": "sphere_cap", "radius": 2.5, "x": [-1, 1], "y": [-1, 1]}"#,
    };
    trimmed_text(text, trim)
}

/// Everything the issue asks of a trimmed run; returns (Euler characteristic, loops).
fn check(kind: &str, trim: &Trim, pattern: &[[f64; 2]]) -> (i64, usize) {
    let sign = if kind == "paraboloid" { 1.0 } else { -1.0 };
    check_model(kind, &surface(kind, trim), trim, pattern, sign)
}

/// [`check`] on any graph surface z = f(x, y) trimmed by `trim`, convex upwards (`sign` 1)
/// or downwards (-1).
fn check_model(
    kind: &str,
    model: &SurfaceModel,
    trim: &Trim,
    pattern: &[[f64; 2]],
    sign: f64,
) -> (i64, usize) {
    let domain = model.domain();
    let loops = loops_of(trim);
    let inside = points_inside(&domain, &loops, pattern);
    assert!(inside.len() < pattern.len(), "the trim leaves out no point");
    let d = discretise(model, pattern, &DiscretiseOptions::default()).unwrap();
    if d.facet_count() != inside.len() {
        let got: Vec<usize> = (0..d.facet_count()).map(|f| d.pattern_index(f)).collect();
        for &i in &inside {
            if !got.contains(&i) {
                let uv = domain.from_normalised(pattern[i]);
                eprintln!(
                    "missing {i} {:?} uv {uv:?} dist {}",
                    pattern[i],
                    polyline_distance(&loops, uv)
                );
            }
        }
        for &i in &got {
            if !inside.contains(&i) {
                eprintln!("extra {i} {:?}", pattern[i]);
            }
        }
    }
    assert_eq!(
        d.facet_count(),
        inside.len(),
        "{kind}: one facet per point inside"
    );
    assert_eq!(d.outside_trim, pattern.len() - inside.len());
    for (f, &p) in inside.iter().enumerate() {
        assert_eq!(d.pattern_index(f), p, "facet {f}'s pattern point");
        assert_eq!(d.seeds[f].uv, domain.from_normalised(pattern[p]));
        assert!(
            d.facet(f).len() >= 3,
            "facet {f} has {} vertices",
            d.facet(f).len()
        );
    }
    let json: serde_json::Value = serde_json::from_str(&d.to_json(false)).unwrap();
    let seeds: Vec<usize> = json["facets"]
        .as_array()
        .unwrap()
        .iter()
        .map(|f| f["seed"].as_u64().unwrap() as usize)
        .collect();
    assert_eq!(seeds, inside, "JSON seeds are pattern indices");

    d.sanity_check().unwrap();
    let q = d.quality.as_ref().unwrap();
    assert_eq!(q.invalid_facets, 0, "{kind}: {:?}", d.diagnostics);
    assert!(d.diagnostics.is_empty(), "{:?}", d.diagnostics);
    let topo = topology(&d);
    assert!(topo.problems.is_empty(), "{:?}", topo.problems);

    // Every boundary vertex (and corner) lies over the trim; every interior one inside.
    let size = domain.u.length().max(domain.v.length());
    let mut on_trim = 0;
    for (v, &x) in d.vertices.iter().enumerate() {
        let foot = closest_parameters(model, x, 64);
        let distance = polyline_distance(&loops, foot) / size;
        match d.vertex_kinds[v] {
            VertexKind::Boundary | VertexKind::Corner => {
                on_trim += 1;
                assert!(
                    distance <= 1e-6,
                    "{kind}: boundary vertex {v} ({:?}) has its foot {foot:?} {distance:e} off the trim",
                    d.vertex_kinds[v]
                );
            }
            VertexKind::Interior => {
                let inside = loops.iter().filter(|l| in_polygon(l, foot)).count() % 2 == 1;
                assert!(inside, "{kind}: interior vertex {v} lies outside the trim");
            }
        }
    }
    assert!(on_trim > 0);
    // Boundary edges are exactly those between boundary vertices.
    for (&(a, b), facets) in &topo.edge_facets {
        if facets.len() == 1 {
            for x in [a, b] {
                assert_ne!(d.vertex_kinds[x as usize], VertexKind::Interior);
            }
        }
    }

    // Interior vertices are on the envelope: on their facets' planes, above every plane.
    let diagonal = seed_diagonal(&d);
    for (f, seed) in d.seeds.iter().enumerate() {
        for &v in d.facet(f) {
            let x = d.vertices[v as usize];
            assert!(seed.normal.dot(x - seed.point).abs() <= 1e-9 * diagonal);
        }
    }
    for (v, &x) in d.vertices.iter().enumerate() {
        if d.vertex_kinds[v] != VertexKind::Interior {
            continue;
        }
        for seed in &d.seeds {
            // Graph surfaces convex upwards (z = f(x, y)): the upward normal points to the
            // centres of curvature, and the envelope lies above every tangent plane.
            let up = if seed.normal.z > 0.0 {
                seed.normal
            } else {
                -seed.normal
            };
            assert!(
                sign * up.dot(x - seed.point) >= -1e-9 * diagonal,
                "{kind}: interior vertex {v} is not on the envelope"
            );
        }
    }
    (topo.euler, topo.boundary_loops)
}

fn disc() -> Trim {
    Trim {
        outer: circle([0.05, -0.02], 0.85, 256, true),
        holes: Vec::new(),
    }
}

fn disc_with_hole() -> Trim {
    Trim {
        outer: circle([0.05, -0.02], 0.85, 256, true),
        holes: vec![circle([-0.1, 0.1], 0.3, 64, false)],
    }
}

fn random(seed: u64, n: usize) -> Vec<[f64; 2]> {
    let mut rng = Rng::new(seed);
    jittered_pattern(&mut rng, n)
}

fn hex(spec: &str) -> Vec<[f64; 2]> {
    Generator::parse(spec).unwrap().generate().uv
}

#[test]
fn paraboloid_trimmed_to_a_disc_is_a_disc() {
    for pattern in [random(1, 400), hex("hex:spacing=0.06")] {
        assert_eq!(check("paraboloid", &disc(), &pattern), (1, 1));
    }
}

#[test]
fn paraboloid_trimmed_to_a_disc_with_a_hole_has_two_boundary_loops() {
    for pattern in [random(2, 600), hex("hex:spacing=0.05")] {
        assert_eq!(check("paraboloid", &disc_with_hole(), &pattern), (0, 2));
    }
}

#[test]
fn sphere_cap_trimmed_to_a_disc_with_a_hole() {
    for pattern in [random(3, 500), hex("hex:spacing=0.06")] {
        assert_eq!(check("sphere", &disc_with_hole(), &pattern), (0, 2));
        assert_eq!(check("sphere", &disc(), &pattern), (1, 1));
    }
}

#[test]
fn a_square_trim_inside_the_domain_picks_up_its_corners() {
    let trim = Trim {
        outer: vec![[-0.7, -0.6], [0.8, -0.6], [0.8, 0.7], [-0.7, 0.7]],
        holes: vec![vec![[-0.2, -0.2], [-0.2, 0.3], [0.3, 0.3], [0.3, -0.2]]],
    };
    let pattern = random(4, 500);
    assert_eq!(check("paraboloid", &trim, &pattern), (0, 2));
    let d = discretise(
        &surface("paraboloid", &trim),
        &pattern,
        &DiscretiseOptions::default(),
    )
    .unwrap();
    let corners = d
        .vertex_kinds
        .iter()
        .filter(|&&k| k == VertexKind::Corner)
        .count();
    assert_eq!(corners, 8, "every trim corner is a vertex, once");
}

#[test]
fn the_untrimmed_output_is_unchanged_by_a_trim_covering_the_whole_domain_points() {
    // A trim that keeps every pattern point still ends the mesh on its own loop: it is not
    // the untrimmed mesh, but its facets are the same in number and order.
    let trim = Trim {
        outer: vec![[-1.0, -1.0], [1.0, -1.0], [1.0, 1.0], [-1.0, 1.0]],
        holes: Vec::new(),
    };
    let pattern: Vec<[f64; 2]> = random(5, 200)
        .into_iter()
        .map(|[s, t]| [0.02 + 0.96 * s, 0.02 + 0.96 * t])
        .collect();
    let model = surface("paraboloid", &trim);
    let trimmed = discretise(&model, &pattern, &DiscretiseOptions::default()).unwrap();
    let plain = discretise(model.untrimmed(), &pattern, &DiscretiseOptions::default()).unwrap();
    assert_eq!(trimmed.facet_count(), plain.facet_count());
    assert_eq!(trimmed.outside_trim, 0);
    assert_eq!(trimmed.dual_triangles, plain.dual_triangles);
    trimmed.sanity_check().unwrap();
    for (a, b) in trimmed.vertices.iter().zip(&plain.vertices) {
        assert!(a.distance(*b) <= 1e-9, "{a} vs {b}");
    }
}

fn spec_error(trim: serde_json::Value) -> TpiError {
    let text = serde_json::json!({
        "type": "elliptic_paraboloid", "a": 1, "b": 1, "x": [0, 2], "y": [0, 1], "trim": trim
    })
    .to_string();
    match SurfaceSpec::from_json(&text, "s") {
        Err(e) => e,
        Ok(spec) => match spec.build() {
            Err(e) => e,
            Ok(_) => panic!("{text} was accepted"),
        },
    }
}

fn invalid(trim: serde_json::Value) -> (String, String) {
    match spec_error(trim) {
        TpiError::InvalidTrim { item, reason } => (item, reason),
        other => panic!("expected InvalidTrim, got {other:?}"),
    }
}

#[test]
fn malformed_trims_are_rejected_naming_the_item() {
    use serde_json::json;
    let outer = json!([[0.2, 0.2], [1.8, 0.2], [1.8, 0.8], [0.2, 0.8]]);
    let (item, reason) = invalid(json!({"outer": [[0.2, 0.2], [1.8, 0.2]]}));
    assert_eq!(item, "trim.outer");
    assert!(reason.contains("at least 3"), "{reason}");
    let (item, reason) =
        invalid(json!({"outer": [[0.2, 0.2], [0.2, 0.8], [1.8, 0.8], [1.8, 0.2]]}));
    assert_eq!(item, "trim.outer");
    assert!(reason.contains("counter-clockwise"), "{reason}");
    let (item, reason) =
        invalid(json!({"outer": outer, "holes": [[[0.5, 0.4], [0.7, 0.4], [0.7, 0.6]]]}));
    assert_eq!(item, "trim.holes[0]");
    assert!(reason.contains("clockwise"), "{reason}");
    let (item, reason) =
        invalid(json!({"outer": [[0.2, 0.2], [1.8, 0.2], [2.5, 0.8], [0.2, 0.8]]}));
    assert_eq!(item, "trim.outer[2]");
    assert!(reason.contains("outside the surface's domain"), "{reason}");
    // A bow tie: counter-clockwise area, but self-intersecting.
    let (item, reason) =
        invalid(json!({"outer": [[0.2, 0.2], [1.8, 0.2], [1.8, 0.8], [1.0, 0.1], [0.2, 0.8]]}));
    assert_eq!(item, "trim.outer");
    assert!(reason.contains("intersects itself"), "{reason}");
    let (item, reason) =
        invalid(json!({"outer": outer, "holes": [[[1.5, 0.5], [1.5, 0.9], [1.9, 0.9]]]}));
    assert_eq!(item, "trim.holes[0]");
    assert!(reason.contains("meets segment"), "{reason}");
    let (item, reason) = invalid(
        json!({"outer": [[0.2, 0.2], [0.5, 0.2], [0.6, 0.3], [0.2, 0.3]], "holes": [[[1.0, 0.5], [1.1, 0.6], [1.2, 0.5]]]}),
    );
    assert_eq!(item, "trim.holes[0]");
    assert!(reason.contains("outside the outer loop"), "{reason}");
    match spec_error(json!({"outer": [[0.2, 0.2], [1.8, "a"], [0.2, 0.8]]})) {
        TpiError::Parse { message, .. } => {
            assert!(message.contains("trim.outer[1][1]"), "{message}")
        }
        other => panic!("{other:?}"),
    }
    match spec_error(json!({"outer": outer, "inner": []})) {
        TpiError::Parse { message, .. } => assert!(message.contains("inner"), "{message}"),
        other => panic!("{other:?}"),
    }
    // Non-finite coordinates cannot be written in JSON; the builder checks them.
    let trim = Trim {
        outer: vec![[0.2, 0.2], [1.8, f64::NAN], [0.2, 0.8]],
        holes: Vec::new(),
    };
    let model = SurfaceSpec::from_json(
        r#"{"type": "elliptic_paraboloid", "a": 1, "b": 1, "x": [0, 2], "y": [0, 1]}"#,
        "s",
    )
    .unwrap()
    .build()
    .unwrap();
    match SurfaceModel::trimmed(model, trim) {
        Err(TpiError::NonFinite { field, .. }) => assert_eq!(field, "trim.outer[1][1]"),
        other => panic!("{other:?}"),
    }
}

#[test]
fn a_trim_round_trips_through_the_surface_file() {
    let trim = disc_with_hole();
    let model = surface("paraboloid", &trim);
    let spec = model.to_spec();
    assert_eq!(spec.trim(), Some(&trim));
    let text = serde_json::to_string(&spec).unwrap();
    let again = SurfaceSpec::from_json(&text, "s").unwrap();
    assert_eq!(again, spec);
    assert_eq!(again.build().unwrap(), model);
}

#[test]
fn live_editing_of_a_trimmed_surface_says_it_is_not_supported() {
    let dome = surface("paraboloid", &disc());
    match LiveSurface::new(Box::new(dome), random(6, 200), DiscretiseOptions::default()) {
        Err(TpiError::TrimUnsupported { .. }) => {}
        Err(e) => panic!("{e:?}"),
        Ok(_) => panic!("live editing accepted a trimmed surface"),
    }
}

/// A rational quadratic cone patch as a surface file: a quarter circle of radius 2 at z = 0
/// (u) joined by straight rulings (v) to a quarter circle of radius 0.8 at z = 1.5.
fn cone_record() -> serde_json::Value {
    let w = std::f64::consts::FRAC_1_SQRT_2;
    serde_json::json!({"type": "nurbs", "degree": [2, 1], "count": [3, 2],
        "knots_u": [0, 0, 1, 1], "knots_v": [0, 1],
        "points": [[2, 0, 0], [0.8, 0, 1.5], [2, 2, 0], [0.8, 0.8, 1.5], [0, 2, 0], [0, 0.8, 1.5]],
        "weights": [1, 1, w, w, 1, 1]})
}

/// The exact tangent plane of a developable surface with rulings along v, along the ruling
/// through u: the plane through the ruling's ends S(u, v0), S(u, v1) and the tangent of the
/// end curve.
fn ruling_plane(s: &dyn Surface, u: f64) -> (DVec3, DVec3) {
    let domain = s.domain();
    let a = s.evaluate(u, domain.v.min);
    let b = s.evaluate(u, domain.v.max);
    (a.point, a.su.cross(b.point - a.point).normalize())
}

/// The trimmed strips' oracles; returns the facets the run says it cut, and the run.
fn check_trimmed_strips(
    name: &str,
    model: &SurfaceModel,
    trim: &Trim,
    pattern: &[[f64; 2]],
) -> (Vec<u32>, Discretisation) {
    let domain = model.domain();
    let loops = loops_of(trim);
    let inside = points_inside(&domain, &loops, pattern);
    let d = discretise(model, pattern, &DiscretiseOptions::default())
        .unwrap_or_else(|e| panic!("{name}: {e}"));
    assert_eq!(
        d.facet_count(),
        inside.len(),
        "{name}: one facet per point inside"
    );
    for (f, &p) in inside.iter().enumerate() {
        assert_eq!(d.pattern_index(f), p, "{name}: facet {f}'s pattern point");
    }
    assert!(
        d.diagnostics
            .iter()
            .any(|g| matches!(g, Diagnostic::RulingStrips { .. })),
        "{name}: not strips: {:?}",
        d.diagnostics
    );
    let v = validity::check(&d);
    assert!(
        v.invalid_facets().is_empty(),
        "{name}: invalid facets {:?}",
        v.invalid_facets()
    );
    // Every vertex of a facet lies in the exact plane along its seed's ruling.
    let diagonal = seed_diagonal(&d);
    for f in 0..d.facet_count() {
        let (p, n) = ruling_plane(model, d.seeds[f].uv[0]);
        for x in facet_points(&d, f) {
            assert!(
                n.dot(x - p).abs() <= 1e-9 * diagonal,
                "{name}: facet {f} leaves its ruling's plane by {:e}",
                n.dot(x - p)
            );
        }
    }
    // Boundary vertices lie over the trim, interior ones inside it.
    let size = domain.u.length().max(domain.v.length());
    for (k, &x) in d.vertices.iter().enumerate() {
        let foot = closest_parameters(model, x, 64);
        match d.vertex_kinds[k] {
            VertexKind::Boundary | VertexKind::Corner => {
                let off = polyline_distance(&loops, foot) / size;
                assert!(
                    off <= 1e-6,
                    "{name}: boundary vertex {k} is {off:e} off the trim"
                );
            }
            VertexKind::Interior => {
                let inside = loops.iter().filter(|l| in_polygon(l, foot)).count() % 2 == 1;
                assert!(inside, "{name}: interior vertex {k} lies outside the trim");
            }
        }
    }
    let cut: Vec<u32> = d
        .diagnostics
        .iter()
        .filter_map(|g| match g {
            Diagnostic::FacetPartsLeftOut { point, parts } => {
                assert!(*parts >= 2);
                Some(*point)
            }
            _ => None,
        })
        .collect();
    if cut.is_empty() {
        assert!(
            (v.euler, v.boundary_loops) == (1 - trim.holes.len() as i64, 1 + trim.holes.len())
                && v.topology_problems == 0,
            "{name}: Euler {}, boundary loops {}, topology problems {}",
            v.euler,
            v.boundary_loops,
            v.topology_problems
        );
        d.sanity_check()
            .unwrap_or_else(|e| panic!("{name}: sanity check: {e}"));
    }
    (cut, d)
}

/// Issue 16, items 1 and 4: a trimmed cylinder or cone (a barrel vault with a curved edge)
/// is discretised instead of refused. Its facets are the strips of the points inside the
/// trim, clipped on it: every vertex in the exact plane along its seed's ruling (closed
/// form), every boundary vertex over the trim, a disc (Euler characteristic 1, one boundary
/// loop) by the independent checks, for a convex trim and for one with a notch cut in from
/// the rulings' end.
#[test]
fn trimmed_cylinders_and_cones_are_their_strips_clipped_on_the_trim() {
    let cylinder = r#"{"type": "cylinder", "radius": 1.5, "x": [-1, 1], "y": [-1, 1]}"#;
    let notch = |domain: tpi_core::Domain| {
        let at = |s: f64, t: f64| domain.from_normalised([s, t]);
        Trim {
            outer: vec![
                at(0.0, 0.0),
                at(1.0, 0.0),
                at(1.0, 1.0),
                at(0.62, 1.0),
                at(0.55, 0.45),
                at(0.4, 0.5),
                at(0.35, 1.0),
                at(0.0, 1.0),
            ],
            holes: Vec::new(),
        }
    };
    let mut rng = Rng::new(1616);
    let patterns = [
        ("random:400", uniform_pattern(&mut rng, 400)),
        ("hex:spacing=0.06", hex("hex:spacing=0.06")),
        ("grid:15x15", hex("grid:15x15")),
    ];
    for (sname, record) in [
        ("cylinder", serde_json::from_str(cylinder).unwrap()),
        ("cone", cone_record()),
    ] {
        let untrimmed = trimmed(
            record.clone(),
            &Trim {
                outer: circle([0.5, 0.5], 0.49, 8, true),
                holes: Vec::new(),
            },
        )
        .domain();
        let to_domain = |t: Trim| Trim {
            outer: t
                .outer
                .iter()
                .map(|&p| untrimmed.from_normalised(untrimmed.to_normalised(p)))
                .collect(),
            holes: t.holes,
        };
        let ellipse = Trim {
            outer: circle([0.5, 0.5], 0.45, 128, true)
                .into_iter()
                .map(|p| untrimmed.from_normalised(p))
                .collect(),
            holes: Vec::new(),
        };
        for (tname, trim) in [
            ("an ellipse", to_domain(ellipse)),
            ("a notch", notch(untrimmed)),
        ] {
            let model = trimmed(record.clone(), &trim);
            for (pname, pattern) in &patterns {
                let name = format!("{sname} trimmed to {tname}, {pname}");
                let (cut, _) = check_trimmed_strips(&name, &model, &trim, pattern);
                assert!(cut.is_empty(), "{name}: facets cut {cut:?}");
            }
        }
    }
}

/// A hole across the rulings cuts the strips that pass it into two parts; a facet keeps the
/// part around its seed, every facet stays valid and ends on the trim, and the run names each
/// facet cut (whose seed's ruling must cross the hole).
#[test]
fn a_hole_across_the_strips_leaves_their_far_parts_out_and_says_so() {
    let record: serde_json::Value =
        serde_json::from_str(r#"{"type": "cylinder", "radius": 1.5, "x": [-1, 1], "y": [-1, 1]}"#)
            .unwrap();
    let trim = Trim {
        outer: circle([0.0, 0.0], 0.95, 128, true),
        holes: vec![circle([-0.1, 0.1], 0.3, 64, false)],
    };
    let model = trimmed(record, &trim);
    let mut rng = Rng::new(1617);
    let pattern = uniform_pattern(&mut rng, 400);
    let (cut, d) = check_trimmed_strips("cylinder with a hole", &model, &trim, &pattern);
    assert!(!cut.is_empty(), "no facet crosses the hole");
    for &point in &cut {
        // Diagnostics name pattern points.
        let f = (0..d.facet_count())
            .find(|&f| d.pattern_index(f) == point as usize)
            .unwrap();
        // The facet's strip, [u_min, u_max] over its vertices, overlaps the hole's [-0.4, 0.2].
        let u: Vec<f64> = facet_points(&d, f)
            .into_iter()
            .map(|x| closest_parameters(&model, x, 64)[0])
            .collect();
        let (low, high) = u
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &x| {
                (a.min(x), b.max(x))
            });
        assert!(
            low < 0.2 + 1e-9 && high > -0.4 - 1e-9,
            "facet {f} over u in [{low}, {high}] does not cross the hole"
        );
    }
}

#[test]
fn nurbs_domes_trimmed_to_a_disc_with_a_hole() {
    for (name, dome) in [("dome_a", dome_a()), ("dome_c", dome_c())] {
        let domain = dome.domain();
        let at = |s: f64, t: f64| domain.from_normalised([s, t]);
        let ellipse = |c: [f64; 2], r: f64, n: usize, ccw: bool| -> Vec<[f64; 2]> {
            circle([0.0, 0.0], 1.0, n, ccw)
                .into_iter()
                .map(|[x, y]| at(c[0] + r * x, c[1] + r * y))
                .collect()
        };
        let trim = Trim {
            outer: ellipse([0.5, 0.5], 0.45, 200, true),
            holes: vec![ellipse([0.45, 0.55], 0.15, 40, false)],
        };
        let model = SurfaceModel::trimmed(SurfaceModel::Nurbs(dome), trim.clone()).unwrap();
        for pattern in [random(7, 700), hex("hex:spacing=0.04")] {
            assert_eq!(
                check_model(name, &model, &trim, &pattern, -1.0),
                (0, 2),
                "{name}"
            );
        }
    }
}

/// A ring narrower than two pattern spacings: facet edges run from over the hole across the
/// ring and out past the outer loop, so a hull ray dips into the region between two outside
/// ends. Its crossings must be ordered along the edge from its right triangle (they were
/// reversed when the ray was on the left, giving non-simple facets).
#[test]
fn a_narrow_ring_keeps_its_facets_simple() {
    let trim = Trim {
        outer: vec![[-0.5, -0.5], [0.5, -0.5], [0.5, 0.5], [-0.5, 0.5]],
        holes: vec![vec![[-0.2, -0.2], [-0.2, 0.2], [0.2, 0.2], [0.2, -0.2]]],
    };
    for spec in ["grid:11x11", "grid:21x21", "hex:20x20"] {
        assert_eq!(check("paraboloid", &trim, &hex(spec)), (0, 2), "{spec}");
    }
}

#[test]
fn a_nurbs_surface_file_takes_a_trim_too() {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../samples/nurbs-dome.json");
    let mut value: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
    let trim = Trim {
        outer: circle([5.0, 4.0], 3.5, 128, true),
        holes: vec![circle([5.5, 3.5], 1.0, 32, false)],
    };
    value["trim"] = serde_json::to_value(&trim).unwrap();
    let text = value.to_string();
    let spec = SurfaceSpec::from_json(&text, "dome.json").unwrap();
    assert_eq!(spec, serde_json::from_str::<SurfaceSpec>(&text).unwrap());
    assert_eq!(spec.trim(), Some(&trim));
    let model = spec.build().unwrap();
    assert_eq!(model.trim(), Some(&trim));
    assert_eq!(model.to_spec(), spec);
    let d = discretise(&model, &random(8, 800), &DiscretiseOptions::default()).unwrap();
    d.sanity_check().unwrap();
    let q = d.quality.unwrap();
    assert_eq!(
        (q.euler_characteristic, q.boundary_loops, q.invalid_facets),
        (0, 2, 0)
    );
}

/// A centred disc with a centred hole and symmetric patterns: facet edges run exactly
/// through polyline points of the trim (a crossing on a corner must not add a zero-length
/// edge), and the disc touches the domain's sides.
#[test]
fn symmetric_patterns_through_trim_points() {
    let trim = Trim {
        outer: circle([0.0, 0.0], 1.0, 256, true),
        holes: vec![circle([0.0, 0.0], 0.3, 64, false)],
    };
    for spec in ["grid:30x30", "hex:spacing=0.05", "grid:31x31"] {
        assert_eq!(check("paraboloid", &trim, &hex(spec)), (0, 2), "{spec}");
    }
    let trim = Trim {
        outer: circle([0.0, 0.0], 1.0, 256, true),
        holes: Vec::new(),
    };
    assert_eq!(check("sphere", &trim, &hex("grid:30x30")), (1, 1));
}

/// A plane as a bicubic NURBS surface over [-1, 1]^2 whose parametrisation is far from
/// affine (control points crowded towards one corner), lying in z = 0.3 x - 0.7 y + 2.
fn warped_plane(trim: &Trim) -> SurfaceModel {
    let mut points = Vec::new();
    for i in 0..4 {
        for j in 0..4 {
            let (s, t) = (i as f64 / 3.0, j as f64 / 3.0);
            let (x, y) = (-1.0 + 2.0 * s * s, -1.0 + 2.0 * t.powf(1.5));
            points.push(serde_json::json!([x, y, 0.3 * x - 0.7 * y + 2.0]));
        }
    }
    let record = serde_json::json!({"type": "nurbs", "degree": [3, 3], "count": [4, 4],
        "knots_u": [-1, -1, -1, 1, 1, 1], "knots_v": [-1, -1, -1, 1, 1, 1], "points": points});
    trimmed(record, trim)
}

/// Issue 16, items 1 and 4: a trimmed plane (most real walls) is discretised instead of
/// refused. Its facets are the Voronoi cells of the points inside the trim, clipped on it.
/// Oracles computed here: which points lie inside (even-odd rule), every interior vertex
/// equidistant from the seeds of its facets with no kept seed closer (brute force), every
/// boundary vertex's closest surface point on a trim loop, the topology of a disc with its
/// holes, and the independent validity checks (simple facets, no overlaps).
#[test]
fn planes_trimmed_to_a_disc_with_a_hole_are_clipped_voronoi_cells() {
    let trims = [("disc", disc()), ("disc with a hole", disc_with_hole())];
    let mut rng = Rng::new(1606);
    let patterns = [
        ("random:500", uniform_pattern(&mut rng, 500)),
        ("jitter:400", jittered_pattern(&mut rng, 400)),
        ("hex:20x20", hex("hex:20x20")),
        ("grid:17x17", hex("grid:17x17")),
    ];
    for (tname, trim) in &trims {
        let analytic = trimmed_text(
            r#"{"type": "plane", "p": 0.3, "q": -0.7, "c0": 2, "x": [-1, 1], "y": [-1, 1]}"#,
            trim,
        );
        let warped = warped_plane(trim);
        for (sname, model) in [("plane", &analytic), ("warped plane", &warped)] {
            for (pname, pattern) in &patterns {
                let name = format!("{sname} trimmed to a {tname}, {pname}");
                let domain = model.domain();
                let loops = loops_of(trim);
                let inside = points_inside(&domain, &loops, pattern);
                let d = discretise(model, pattern, &DiscretiseOptions::default())
                    .unwrap_or_else(|e| panic!("{name}: {e}"));
                assert_eq!(
                    d.facet_count(),
                    inside.len(),
                    "{name}: one facet per point inside"
                );
                for (f, &p) in inside.iter().enumerate() {
                    assert_eq!(d.pattern_index(f), p, "{name}: facet {f}'s pattern point");
                }
                let v = validity::check(&d);
                let expected = (1 - trim.holes.len() as i64, 1 + trim.holes.len());
                assert!(
                    v.invalid_facets().is_empty()
                        && (v.euler, v.boundary_loops) == expected
                        && v.topology_problems == 0,
                    "{name}: invalid facets {:?}, Euler {}, boundary loops {}, topology problems {}",
                    v.invalid_facets(),
                    v.euler,
                    v.boundary_loops,
                    v.topology_problems
                );
                d.sanity_check()
                    .unwrap_or_else(|e| panic!("{name}: sanity check: {e}"));
                let diagonal = seed_diagonal(&d);
                let seeds: Vec<DVec3> = d.seeds.iter().map(|s| s.point).collect();
                let around = vertex_facets(&d);
                let size = domain.u.length().max(domain.v.length());
                let (mut interior, mut on_trim) = (0, 0);
                for (k, &x) in d.vertices.iter().enumerate() {
                    let z = 0.3 * x.x - 0.7 * x.y + 2.0;
                    assert!(
                        (x.z - z).abs() <= 1e-9 * diagonal,
                        "{name}: vertex {k} off the plane"
                    );
                    if d.vertex_kinds[k] != VertexKind::Interior {
                        let foot = closest_parameters(model, x, 64);
                        let distance = polyline_distance(&loops, foot) / size;
                        assert!(
                            distance <= 1e-6,
                            "{name}: boundary vertex {k} has its foot {foot:?} {distance:e} off the trim"
                        );
                        on_trim += 1;
                        continue;
                    }
                    let r: Vec<f64> = around[k].iter().map(|&f| x.distance(seeds[f])).collect();
                    let (lo, hi) = r
                        .iter()
                        .fold((f64::INFINITY, 0.0f64), |(a, b), &r| (a.min(r), b.max(r)));
                    assert!(
                        hi - lo <= 1e-9 * diagonal,
                        "{name}: vertex {k} is not equidistant from its seeds: {r:?}"
                    );
                    let nearest = seeds
                        .iter()
                        .map(|p| x.distance(*p))
                        .fold(f64::INFINITY, f64::min);
                    assert!(
                        nearest >= lo - 1e-9 * diagonal,
                        "{name}: a seed is closer ({nearest}) to vertex {k} than its own ({lo})"
                    );
                    interior += 1;
                }
                assert!(
                    interior > inside.len() && on_trim > 0,
                    "{name}: {interior} interior and {on_trim} boundary vertices"
                );
            }
        }
    }
}

/// Issue 16, item 1, beyond convex surfaces: a saddle and an egg crate of mixed curvature
/// (adjusted planes, which uniform random patterns need on such surfaces) trimmed to a disc
/// with a hole and to a square with a square hole. The facets end near the trim on ghosts
/// mirrored across its loops. Oracles computed here: which points lie inside (even-odd
/// rule), the topology of a disc with its hole, the independent validity checks, every
/// vertex in its facet's plane, every boundary vertex's closest surface point within three
/// mean pattern spacings of a trim loop (the untrimmed mesh would reach half the domain
/// beyond), every interior vertex's inside the region or within that of it.
#[test]
fn saddles_and_mixed_surfaces_trimmed_to_a_disc_with_a_hole() {
    let square = Trim {
        outer: vec![[-0.8, -0.8], [0.8, -0.8], [0.8, 0.8], [-0.8, 0.8]],
        holes: vec![vec![[-0.3, -0.3], [-0.3, 0.3], [0.3, 0.3], [0.3, -0.3]]],
    };
    let trims = [
        ("disc with a hole", disc_with_hole()),
        ("square with a hole", square),
    ];
    let cases = [
        (
            "saddle",
            r#"{"type": "hyperbolic_paraboloid", "a": 0.5, "b": 0.3, "x": [-1, 1], "y": [-1, 1]}"#,
            PlaneMode::Adjusted,
            1,
        ),
        (
            "egg crate",
            r#"{"type": "egg_crate", "amplitude": 0.3, "x": [-1, 1], "y": [-1, 1]}"#,
            PlaneMode::Adjusted,
            2,
        ),
    ];
    let mut rng = Rng::new(1616);
    let patterns = [
        ("random:500", uniform_pattern(&mut rng, 500)),
        ("hex:24x24", hex("hex:24x24")),
        ("poisson:0.04", hex("poisson:0.04:seed=2")),
    ];
    for (sname, text, planes, allowed) in cases {
        for (tname, trim) in &trims {
            let model = trimmed_text(text, trim);
            let loops = loops_of(trim);
            let domain = model.domain();
            let size = domain.u.length().max(domain.v.length());
            for (pname, pattern) in &patterns {
                let name = format!("{sname} trimmed to a {tname}, {pname}");
                let inside = points_inside(&domain, &loops, pattern);
                let options = DiscretiseOptions {
                    planes,
                    ..DiscretiseOptions::default()
                };
                let d =
                    discretise(&model, pattern, &options).unwrap_or_else(|e| panic!("{name}: {e}"));
                assert_eq!(
                    d.facet_count(),
                    inside.len(),
                    "{name}: one facet per point inside"
                );
                for (f, &p) in inside.iter().enumerate() {
                    assert_eq!(d.pattern_index(f), p, "{name}: facet {f}'s pattern point");
                }
                let v = validity::check(&d);
                assert!(
                    v.invalid_facets().len() <= allowed
                        && (v.euler, v.boundary_loops) == (0, 2)
                        && v.topology_problems == 0,
                    "{name}: invalid facets {:?}, Euler {}, boundary loops {}, topology problems {}",
                    v.invalid_facets(),
                    v.euler,
                    v.boundary_loops,
                    v.topology_problems
                );
                let diagonal = seed_diagonal(&d);
                // The reach allowed for a facet that ends on a ghost's plane instead of the
                // trim's wall: three mean spacings (the gaps of a uniform random pattern).
                let reach = 3.0 * size / (pattern.len() as f64).sqrt();
                for f in 0..d.facet_count() {
                    let (point, normal) = d.facet_plane(f);
                    for &k in d.facet(f) {
                        let x = d.vertices[k as usize];
                        assert!(
                            normal.dot(x - point).abs() <= 1e-9 * diagonal,
                            "{name}: vertex {k} off facet {f}'s plane"
                        );
                    }
                }
                for (k, &x) in d.vertices.iter().enumerate() {
                    let foot = closest_parameters(&model, x, 64);
                    let distance = polyline_distance(&loops, foot);
                    let inside = loops.iter().filter(|l| in_polygon(l, foot)).count() % 2 == 1;
                    if d.vertex_kinds[k] == VertexKind::Interior {
                        assert!(
                            inside || distance <= reach,
                            "{name}: interior vertex {k} lies {distance} outside the trim"
                        );
                    } else {
                        assert!(
                            distance <= reach,
                            "{name}: boundary vertex {k} lies {distance} from the trim"
                        );
                    }
                }
            }
        }
    }
}
