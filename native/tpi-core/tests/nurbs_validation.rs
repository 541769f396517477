//! Every bad NURBS input gets its specific typed error naming the offending item; no input
//! panics.

use glam::DVec3;
use tpi_core::tolerance::MAX_NURBS_DEGREE;
use tpi_core::{Direction, NurbsSpec, NurbsSurface, Surface, TpiError};

/// A valid bicubic-by-quadratic spec: degree [3, 2], count [5, 4], Rhino-convention knots,
/// rational.
fn valid_spec() -> NurbsSpec {
    let (nu, nv) = (5, 4);
    let mut points = Vec::new();
    for i in 0..nu {
        for j in 0..nv {
            points.push([i as f64, j as f64, ((i + j) % 3) as f64 * 0.25]);
        }
    }
    NurbsSpec {
        degree: [3, 2],
        count: [nu, nv],
        knots_u: vec![1.0, 1.0, 1.0, 1.5, 3.0, 3.0, 3.0],
        knots_v: vec![-2.0, -2.0, -1.0, 0.0, 0.0],
        weights: Some((0..nu * nv).map(|k| 1.0 + 0.1 * (k % 4) as f64).collect()),
        points,
        units: None,
        trim: None,
    }
}

fn build_error(spec: &NurbsSpec) -> TpiError {
    match spec.build() {
        Ok(_) => panic!("{spec:?} was accepted"),
        Err(error) => error,
    }
}

#[test]
fn the_reference_spec_is_valid_in_both_knot_conventions() {
    let spec = valid_spec();
    let surface = spec.build().expect("valid");
    assert_eq!(surface.domain().u.min, 1.0);
    assert_eq!(surface.domain().u.max, 3.0);
    assert_eq!(surface.domain().v.min, -2.0);
    assert_eq!(surface.domain().v.max, 0.0);
    let textbook = NurbsSpec {
        knots_u: vec![1.0, 1.0, 1.0, 1.0, 1.5, 3.0, 3.0, 3.0, 3.0],
        knots_v: vec![-2.0, -2.0, -2.0, -1.0, 0.0, 0.0, 0.0],
        ..spec.clone()
    };
    assert_eq!(textbook.build(), Ok(surface));
}

#[test]
fn degree_zero_is_rejected() {
    let spec = NurbsSpec {
        degree: [0, 2],
        knots_u: vec![1.0, 1.5, 2.0, 2.5],
        ..valid_spec()
    };
    match build_error(&spec) {
        TpiError::InvalidDegree {
            direction: Direction::U,
            degree: 0,
            count: 5,
            ..
        } => {}
        other => panic!("unexpected {other:?}"),
    }
    let spec = NurbsSpec {
        degree: [3, 0],
        ..valid_spec()
    };
    match build_error(&spec) {
        TpiError::InvalidDegree {
            direction: Direction::V,
            degree: 0,
            count: 4,
            ..
        } => {}
        other => panic!("unexpected {other:?}"),
    }
}

#[test]
fn degree_not_below_count_is_rejected() {
    // count == degree: one control point too few.
    let spec = NurbsSpec {
        degree: [5, 2],
        ..valid_spec()
    };
    match build_error(&spec) {
        TpiError::InvalidDegree {
            direction: Direction::U,
            degree: 5,
            count: 5,
            reason,
        } => {
            assert!(reason.contains("degree + 1"), "{reason}")
        }
        other => panic!("unexpected {other:?}"),
    }
    let spec = NurbsSpec {
        degree: [3, 7],
        ..valid_spec()
    };
    match build_error(&spec) {
        TpiError::InvalidDegree {
            direction: Direction::V,
            degree: 7,
            count: 4,
            ..
        } => {}
        other => panic!("unexpected {other:?}"),
    }
    // No control points at all.
    let spec = NurbsSpec {
        count: [0, 4],
        points: vec![],
        weights: None,
        ..valid_spec()
    };
    match build_error(&spec) {
        TpiError::InvalidDegree {
            direction: Direction::U,
            degree: 3,
            count: 0,
            ..
        } => {}
        other => panic!("unexpected {other:?}"),
    }
}

#[test]
fn count_of_degree_plus_one_is_a_valid_bezier_patch() {
    let points: Vec<DVec3> = (0..12)
        .map(|k| DVec3::new((k / 3) as f64, (k % 3) as f64, 0.0))
        .collect();
    let surface = NurbsSurface::new(
        [3, 2],
        [4, 3],
        &[0.0, 0.0, 0.0, 2.0, 2.0, 2.0],
        &[5.0, 5.0, 6.0, 6.0],
        &points,
        None,
    )
    .expect("a Bezier patch is valid");
    assert_eq!(surface.domain().u.max, 2.0);
}

#[test]
fn degree_above_the_maximum_is_rejected() {
    let degree = MAX_NURBS_DEGREE + 1;
    let count = degree + 1;
    let knots: Vec<f64> = (0..count + degree - 1).map(|k| k as f64).collect();
    let points = vec![DVec3::ZERO; count * 2];
    match NurbsSurface::new([degree, 1], [count, 2], &knots, &[0.0, 1.0], &points, None) {
        Err(TpiError::InvalidDegree {
            direction: Direction::U,
            degree: d,
            count: c,
            reason,
        }) => {
            assert_eq!((d, c), (degree, count));
            assert!(reason.contains(&MAX_NURBS_DEGREE.to_string()), "{reason}");
        }
        other => panic!("unexpected {other:?}"),
    }
}

#[test]
fn point_count_must_be_nu_times_nv() {
    let mut spec = valid_spec();
    spec.points.pop();
    assert_eq!(
        build_error(&spec),
        TpiError::PointCount {
            expected: 20,
            found: 19
        }
    );
    let mut spec = valid_spec();
    spec.points.push([0.0; 3]);
    assert_eq!(
        build_error(&spec),
        TpiError::PointCount {
            expected: 20,
            found: 21
        }
    );
}

#[test]
fn overflowing_point_count_is_an_error_not_a_panic() {
    let spec = NurbsSpec {
        degree: [1, 1],
        count: [usize::MAX, 3],
        points: vec![[0.0; 3]; 6],
        weights: None,
        ..valid_spec()
    };
    assert_eq!(
        build_error(&spec),
        TpiError::PointCount {
            expected: usize::MAX,
            found: 6
        }
    );
    let spec = NurbsSpec {
        degree: [2, 2],
        count: [usize::MAX, usize::MAX],
        points: vec![],
        weights: None,
        ..valid_spec()
    };
    assert_eq!(
        build_error(&spec),
        TpiError::PointCount {
            expected: usize::MAX,
            found: 0
        }
    );
}

#[test]
fn knot_count_fitting_neither_convention_is_rejected() {
    let spec = NurbsSpec {
        knots_u: vec![1.0, 1.0, 1.0, 1.5, 3.0, 3.0, 3.0, 3.0],
        ..valid_spec()
    };
    assert_eq!(
        build_error(&spec),
        TpiError::KnotCount {
            direction: Direction::U,
            found: 8,
            count: 5,
            degree: 3,
            rhino: 7,
            full: 9
        }
    );
    let spec = NurbsSpec {
        knots_v: vec![],
        ..valid_spec()
    };
    assert_eq!(
        build_error(&spec),
        TpiError::KnotCount {
            direction: Direction::V,
            found: 0,
            count: 4,
            degree: 2,
            rhino: 5,
            full: 7
        }
    );
}

#[test]
fn non_finite_knots_are_named() {
    let mut spec = valid_spec();
    spec.knots_u[3] = f64::NAN;
    match build_error(&spec) {
        TpiError::NonFinite { field, value } => {
            assert_eq!(field, "knots_u[3]");
            assert!(value.is_nan());
        }
        other => panic!("unexpected {other:?}"),
    }
    let mut spec = valid_spec();
    spec.knots_v[4] = f64::INFINITY;
    assert_eq!(
        build_error(&spec),
        TpiError::NonFinite {
            field: "knots_v[4]".into(),
            value: f64::INFINITY
        }
    );
    let error = build_error(&spec);
    assert!(error.to_string().contains("knots_v[4]"), "{error}");
}

#[test]
fn knots_spanning_an_infinite_range_are_rejected() {
    let spec = NurbsSpec {
        knots_v: vec![-1e308, -1e308, 0.0, 1e308, 1e308],
        ..valid_spec()
    };
    match build_error(&spec) {
        TpiError::NonFinite { field, value } => {
            assert_eq!(field, "knots_v[4] - knots_v[0]");
            assert_eq!(value, f64::INFINITY);
        }
        other => panic!("unexpected {other:?}"),
    }
}

#[test]
fn decreasing_knots_name_the_index() {
    let spec = NurbsSpec {
        knots_u: vec![1.0, 1.0, 1.0, 2.5, 1.5, 3.0, 3.0],
        ..valid_spec()
    };
    assert_eq!(
        build_error(&spec),
        TpiError::KnotsDecreasing {
            direction: Direction::U,
            index: 4,
            previous: 2.5,
            value: 1.5
        }
    );
    // Indices refer to the vector as given, also in the textbook convention, superfluous ends included.
    let spec = NurbsSpec {
        knots_v: vec![-2.0, -2.0, -2.0, -1.0, 0.0, 0.0, -0.5],
        ..valid_spec()
    };
    assert_eq!(
        build_error(&spec),
        TpiError::KnotsDecreasing {
            direction: Direction::V,
            index: 6,
            previous: 0.0,
            value: -0.5
        }
    );
    let error = build_error(&spec);
    assert!(
        error.to_string().contains("knots_v[6]") && error.to_string().contains("knots_v[5]"),
        "{error}"
    );
}

#[test]
fn interior_knot_multiplicity_above_degree_is_rejected() {
    // Degree 2 in v, knot 0.5 three times.
    let spec = NurbsSpec {
        count: [5, 6],
        knots_v: vec![-2.0, -2.0, 0.5, 0.5, 0.5, 1.0, 1.0],
        // A flat net (one point repeated is refused: MIN_NET_EXTENT).
        points: (0..30)
            .map(|k| [(k / 6) as f64, (k % 6) as f64, 0.0])
            .collect(),
        weights: None,
        ..valid_spec()
    };
    assert_eq!(
        build_error(&spec),
        TpiError::KnotMultiplicity {
            direction: Direction::V,
            index: 2,
            value: 0.5,
            multiplicity: 3,
            degree: 2
        }
    );
    // Multiplicity equal to the degree is fine (C0).
    let spec = NurbsSpec {
        knots_v: vec![-2.0, -2.0, 0.5, 0.5, 1.0, 1.0, 1.0],
        ..spec
    };
    assert_eq!(
        build_error(&spec),
        TpiError::KnotMultiplicity {
            direction: Direction::V,
            index: 4,
            value: 1.0,
            multiplicity: 3,
            degree: 2
        }
    );
    let spec = NurbsSpec {
        knots_v: vec![-2.0, -2.0, 0.5, 0.5, 0.7, 1.0, 1.0],
        ..spec
    };
    assert!(spec.build().is_ok());
}

#[test]
fn end_knot_multiplicity_follows_opennurbs() {
    // Rhino convention: a clamped end has `degree` equal knots; one more is rejected.
    let spec = NurbsSpec {
        knots_u: vec![1.0, 1.0, 1.0, 1.0, 3.0, 3.0, 3.0],
        ..valid_spec()
    };
    assert_eq!(
        build_error(&spec),
        TpiError::KnotMultiplicity {
            direction: Direction::U,
            index: 0,
            value: 1.0,
            multiplicity: 4,
            degree: 3
        }
    );
    // Textbook convention: degree + 1 equal end knots are clamped and valid, the superfluous
    // first knot is not counted; degree + 2 are rejected, the index is in the vector as given.
    let spec = NurbsSpec {
        knots_u: vec![1.0, 1.0, 1.0, 1.0, 1.5, 3.0, 3.0, 3.0, 3.0],
        ..valid_spec()
    };
    assert!(spec.build().is_ok());
    let spec = NurbsSpec {
        knots_u: vec![1.0, 1.0, 1.0, 1.0, 1.0, 3.0, 3.0, 3.0, 3.0],
        ..valid_spec()
    };
    assert_eq!(
        build_error(&spec),
        TpiError::KnotMultiplicity {
            direction: Direction::U,
            index: 1,
            value: 1.0,
            multiplicity: 4,
            degree: 3
        }
    );
}

#[test]
fn empty_domain_is_rejected() {
    // Degree 1, two control points, both domain knots equal.
    let spec = NurbsSpec {
        degree: [1, 2],
        count: [2, 4],
        knots_u: vec![2.0, 2.0],
        points: vec![[0.0; 3]; 8],
        weights: None,
        ..valid_spec()
    };
    assert_eq!(
        build_error(&spec),
        TpiError::EmptyDomain {
            direction: Direction::U,
            min: 2.0,
            max: 2.0
        }
    );
    // Unclamped degree 2 with count 3: the domain [k1, k2] collapses although no knot repeats
    // more than twice.
    let spec = NurbsSpec {
        count: [5, 3],
        knots_v: vec![0.0, 1.0, 1.0, 2.0],
        points: vec![[0.0; 3]; 15],
        weights: None,
        ..valid_spec()
    };
    assert_eq!(
        build_error(&spec),
        TpiError::EmptyDomain {
            direction: Direction::V,
            min: 1.0,
            max: 1.0
        }
    );
}

#[test]
fn non_finite_points_name_point_and_coordinate() {
    let mut spec = valid_spec();
    spec.points[12][1] = f64::NAN;
    match build_error(&spec) {
        TpiError::NonFinite { field, value } => {
            assert_eq!(field, "points[12][1]");
            assert!(value.is_nan());
        }
        other => panic!("unexpected {other:?}"),
    }
    let mut spec = valid_spec();
    spec.points[19][2] = f64::NEG_INFINITY;
    assert_eq!(
        build_error(&spec),
        TpiError::NonFinite {
            field: "points[19][2]".into(),
            value: f64::NEG_INFINITY
        }
    );
}

#[test]
fn weight_count_must_match_the_points() {
    let mut spec = valid_spec();
    spec.weights.as_mut().expect("rational").pop();
    assert_eq!(
        build_error(&spec),
        TpiError::WeightCount {
            expected: 20,
            found: 19
        }
    );
    let spec = NurbsSpec {
        weights: Some(vec![1.0; 21]),
        ..valid_spec()
    };
    assert_eq!(
        build_error(&spec),
        TpiError::WeightCount {
            expected: 20,
            found: 21
        }
    );
    let spec = NurbsSpec {
        weights: Some(vec![]),
        ..valid_spec()
    };
    assert_eq!(
        build_error(&spec),
        TpiError::WeightCount {
            expected: 20,
            found: 0
        }
    );
}

#[test]
fn non_positive_weights_are_rejected() {
    let mut spec = valid_spec();
    spec.weights.as_mut().expect("rational")[5] = 0.0;
    assert_eq!(
        build_error(&spec),
        TpiError::NonPositiveWeight {
            index: 5,
            value: 0.0
        }
    );
    let mut spec = valid_spec();
    spec.weights.as_mut().expect("rational")[17] = -0.5;
    assert_eq!(
        build_error(&spec),
        TpiError::NonPositiveWeight {
            index: 17,
            value: -0.5
        }
    );
}

#[test]
fn non_finite_weights_are_named() {
    let mut spec = valid_spec();
    spec.weights.as_mut().expect("rational")[5] = f64::NAN;
    match build_error(&spec) {
        TpiError::NonFinite { field, value } => {
            assert_eq!(field, "weights[5]");
            assert!(value.is_nan());
        }
        other => panic!("unexpected {other:?}"),
    }
    let mut spec = valid_spec();
    spec.weights.as_mut().expect("rational")[0] = f64::INFINITY;
    assert_eq!(
        build_error(&spec),
        TpiError::NonFinite {
            field: "weights[0]".into(),
            value: f64::INFINITY
        }
    );
}

#[test]
fn overflowing_homogeneous_coordinates_are_rejected() {
    let mut spec = valid_spec();
    spec.points[7] = [1e300, 0.0, 0.0];
    spec.weights.as_mut().expect("rational")[7] = 1e10;
    assert_eq!(
        build_error(&spec),
        TpiError::NonFinite {
            field: "points[7][0] * weights[7]".into(),
            value: f64::INFINITY
        }
    );
}

#[test]
fn subnormal_weights_evaluate_like_equal_weights() {
    let spec = valid_spec();
    let plain = NurbsSpec {
        weights: None,
        ..spec.clone()
    }
    .build()
    .expect("valid");
    let tiny = NurbsSpec {
        weights: Some(vec![1e-310; 20]),
        ..spec
    }
    .build()
    .expect("subnormal weights are > 0");
    let diagonal = plain.bounding_box_diagonal();
    for (u, v) in [(1.0, -2.0), (1.7, -0.4), (3.0, 0.0)] {
        let (a, b) = (plain.evaluate(u, v), tiny.evaluate(u, v));
        for (x, y) in [
            (a.point, b.point),
            (a.su, b.su),
            (a.sv, b.sv),
            (a.suu, b.suu),
            (a.suv, b.suv),
            (a.svv, b.svv),
        ] {
            assert!(
                y.is_finite() && (x - y).length() <= 1e-9 * diagonal.max(x.length()),
                "{x} vs {y}"
            );
        }
    }
}

#[test]
fn errors_come_through_the_surface_file_format() {
    let json = r#"{"degree": [1, 1], "count": [2, 2], "knots_u": [0, 1], "knots_v": [3, 2],
                   "points": [[0,0,0],[0,1,0],[1,0,0],[1,1,0]]}"#;
    let spec: NurbsSpec = serde_json::from_str(json).expect("well-formed JSON");
    assert_eq!(
        build_error(&spec),
        TpiError::KnotsDecreasing {
            direction: Direction::V,
            index: 1,
            previous: 3.0,
            value: 2.0
        }
    );
    let unknown = r#"{"degree": [1, 1], "count": [2, 2], "knots_u": [0, 1], "knots_v": [0, 1],
                      "points": [], "colour": 3}"#;
    assert!(
        serde_json::from_str::<NurbsSpec>(unknown).is_err(),
        "unknown fields are rejected"
    );
}

/// SplitMix64 for the fuzz loop below.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    fn below(&mut self, n: u64) -> usize {
        (self.next() % n) as usize
    }

    /// Ordinary numbers in [-5, 5); with `nasty`, sometimes NaN, infinity, -0, huge or subnormal.
    fn number(&mut self, nasty: bool) -> f64 {
        match if nasty { self.below(20) } else { 20 } {
            0 => f64::NAN,
            1 => f64::INFINITY,
            2 => -0.0,
            3 => 1e308,
            4 => 1e-310,
            _ => (self.next() >> 11) as f64 / (1u64 << 53) as f64 * 10.0 - 5.0,
        }
    }
}

/// Random, mostly malformed inputs: building never panics; when it succeeds, evaluation inside
/// the domain is finite and never panics anywhere.
#[test]
fn random_inputs_never_panic() {
    let mut rng = Rng(0xBAD_1A9_u64);
    let mut accepted = 0;
    for _ in 0..20_000 {
        // Half of the cases are well-formed apart from chance (so that evaluation gets tested).
        let nasty = rng.below(2) == 0;
        let degree = if nasty {
            [rng.below(5), rng.below(5)]
        } else {
            [1 + rng.below(4), 1 + rng.below(4)]
        };
        let count = if nasty {
            [rng.below(8), rng.below(8)]
        } else {
            [degree[0] + 1 + rng.below(4), degree[1] + 1 + rng.below(4)]
        };
        let knots = |rng: &mut Rng, d: usize, n: usize| -> Vec<f64> {
            let len = match rng.below(if nasty { 4 } else { 2 }) {
                0 => n + d + 1,
                1 => (n + d).saturating_sub(1),
                _ => rng.below(14),
            };
            let mut knots: Vec<f64> = (0..len).map(|_| rng.number(nasty)).collect();
            if !nasty || rng.below(3) > 0 {
                knots.sort_by(|a, b| a.total_cmp(b));
            }
            if rng.below(2) == 0 {
                // Round to produce repeated knots.
                knots.iter_mut().for_each(|k| *k = k.round());
            }
            knots
        };
        let knots_u = knots(&mut rng, degree[0], count[0]);
        let knots_v = knots(&mut rng, degree[1], count[1]);
        let point_count = if nasty && rng.below(10) == 0 {
            rng.below(60)
        } else {
            count[0] * count[1]
        };
        let points: Vec<DVec3> = (0..point_count)
            .map(|_| DVec3::new(rng.number(nasty), rng.number(nasty), rng.number(nasty)))
            .collect();
        let weights: Option<Vec<f64>> = (rng.below(2) == 0).then(|| {
            (0..point_count)
                .map(|_| rng.number(nasty).abs() + if nasty { 0.0 } else { 0.1 })
                .collect()
        });
        if let Ok(surface) = NurbsSurface::new(
            degree,
            count,
            &knots_u,
            &knots_v,
            &points,
            weights.as_deref(),
        ) {
            accepted += 1;
            let domain = surface.domain();
            for (s, t) in [(0.0, 0.0), (1.0, 1.0), (0.5, 0.25), (0.999, 0.001)] {
                let [u, v] = domain.from_normalised([s, t]);
                let d = surface.evaluate(u, v);
                assert!(
                    d.point.is_finite(),
                    "non-finite point from {degree:?} {count:?} {knots_u:?} {knots_v:?} {points:?} {weights:?}"
                );
                assert!(surface.point_at(u, v).is_finite());
                if !nasty {
                    for vector in [d.su, d.sv, d.suu, d.suv, d.svv] {
                        assert!(
                            vector.is_finite(),
                            "non-finite derivative {d:?} from {degree:?} {count:?} {knots_u:?} {knots_v:?}"
                        );
                    }
                }
            }
            let _ = surface.evaluate(f64::NAN, f64::INFINITY);
            let _ = surface.point_at(-1e308, f64::NAN);
        }
    }
    println!("{accepted} of 20000 random inputs were valid");
    assert!(
        accepted > 1000,
        "only {accepted} random inputs were valid: the fuzz loop tests little"
    );
}

/// Issue 14: a dome with its knots scaled by 1e-80 (or its control points by 1e-100) was
/// accepted, its derivatives' products overflowed (or underflowed), and the surface was called
/// developable. The domain's length and the net's extent are bounded from below
/// (MIN_KNOT_DOMAIN, MIN_NET_EXTENT): just above the bounds the surface evaluates with finite
/// derivatives and a normal whose first fundamental form is finite and non-zero; just below
/// it is refused, naming the knots or the net and the bound.
#[test]
fn a_tiny_domain_or_net_is_refused_with_the_bound() {
    use tpi_core::{MIN_KNOT_DOMAIN, MIN_NET_EXTENT};
    let spec = valid_spec();
    let scaled_knots = |factor: f64| NurbsSpec {
        knots_u: spec.knots_u.iter().map(|k| k * factor).collect(),
        knots_v: spec.knots_v.iter().map(|k| k * factor).collect(),
        ..spec.clone()
    };
    let net = spec.build().expect("valid").bounding_box_diagonal();
    let scaled_points = |factor: f64| NurbsSpec {
        points: spec
            .points
            .iter()
            .map(|p| [p[0] * factor, p[1] * factor, p[2] * factor])
            .collect(),
        ..spec.clone()
    };
    // Both domains of valid_spec are 2 long, its net about 5 across.
    for accepted in [
        scaled_knots(MIN_KNOT_DOMAIN / 2.0 * 1.01),
        scaled_points(MIN_NET_EXTENT / net * 1.01),
        // The extreme ratio: the smallest domain with a net of 5e14.
        NurbsSpec {
            points: scaled_points(1e14).points,
            ..scaled_knots(MIN_KNOT_DOMAIN / 2.0 * 1.01)
        },
    ] {
        let surface = accepted.build().expect("within the bounds");
        let d = surface.domain();
        for (a, b) in [(0.3, 0.4), (0.5, 0.5), (0.9, 0.1)] {
            let e = surface.evaluate(d.u.lerp(a), d.v.lerp(b));
            let (su, sv) = (e.su, e.sv);
            let first = su.dot(su) * sv.dot(sv) - su.dot(sv).powi(2);
            assert!(
                [e.point, su, sv, e.suu, e.suv, e.svv]
                    .iter()
                    .all(|v| v.is_finite()),
                "{e:?}"
            );
            assert!(first.is_finite() && first > 0.0, "EG - F^2 = {first:e}");
        }
    }
    match build_error(&scaled_knots(MIN_KNOT_DOMAIN / 2.0 * 0.99)) {
        TpiError::OutOfBounds { field, value, .. } => {
            assert_eq!(field, "knots_u[4] - knots_u[2]");
            assert!(value < MIN_KNOT_DOMAIN);
        }
        other => panic!("{other:?}"),
    }
    match build_error(&scaled_points(MIN_NET_EXTENT / net * 0.99)) {
        TpiError::OutOfBounds { field, value, .. } => {
            assert_eq!(field, "bounding-box diagonal of points");
            assert!(value < MIN_NET_EXTENT);
        }
        other => panic!("{other:?}"),
    }
    // One point repeated: no surface at all.
    let mut single = spec.clone();
    single.points = vec![[1.0, 2.0, 3.0]; spec.points.len()];
    assert!(matches!(build_error(&single), TpiError::OutOfBounds { .. }));
}
