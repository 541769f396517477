//! Exact NURBS derivatives against finite differences of the point, on random surfaces of the
//! same kind as the openNURBS conformance cases (degrees 1..5, rational or not, non-uniform knots
//! with repeated interior knots, clamped or not, domains not starting at 0), generated here with
//! a small deterministic PRNG.

use glam::DVec3;
use tpi_core::{NurbsSurface, Surface};

/// Finite differences agree with the exact derivatives to this relative error.
const RELATIVE_TOLERANCE: f64 = 1e-6;
/// Finite-difference step as a fraction of the local length scale (see `local_scale`).
const STEP_FRACTION: f64 = 0.02;

/// SplitMix64: tiny, deterministic, good enough for test data.
struct Rng(u64);

impl Rng {
    fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in [0, 1).
    fn unit(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }

    fn range(&mut self, min: f64, max: f64) -> f64 {
        min + (max - min) * self.unit()
    }

    /// Uniform integer in min..=max.
    fn int(&mut self, min: usize, max: usize) -> usize {
        min + (self.next_u64() % (max - min + 1) as u64) as usize
    }
}

struct RandomSurface {
    surface: NurbsSurface,
    knots: [Vec<f64>; 2],
    degree: [usize; 2],
    label: String,
}

/// Rhino-convention knots over a random domain not starting at 0, with repeated interior knots.
fn random_knots(rng: &mut Rng, degree: usize, count: usize, clamped: bool) -> Vec<f64> {
    let sign = if rng.unit() < 0.5 { -1.0 } else { 1.0 };
    let start = sign * rng.range(0.1, 60.0);
    let length = 10f64.powf(rng.range(-1.0, 1.5));
    let mut multiplicities = Vec::new();
    let mut remaining = count - degree - 1;
    while remaining > 0 {
        let multiplicity = if degree > 1 && remaining >= 2 && rng.unit() < 0.3 {
            rng.int(2, degree.min(remaining))
        } else {
            1
        };
        multiplicities.push(multiplicity);
        remaining -= multiplicity;
    }
    let gaps: Vec<f64> = (0..=multiplicities.len())
        .map(|_| rng.range(0.2, 1.0))
        .collect();
    let scale = length / gaps.iter().sum::<f64>();
    let mut knots = Vec::new();
    let mut before = Vec::new();
    let step = length / gaps.len() as f64;
    let mut position = start;
    for _ in 1..degree {
        position -= if clamped {
            0.0
        } else {
            step * rng.range(0.3, 1.0)
        };
        before.push(position);
    }
    knots.extend(before.iter().rev());
    knots.push(start);
    let mut breakpoint = start;
    for (gap, &multiplicity) in gaps.iter().zip(&multiplicities) {
        breakpoint += scale * gap;
        knots.extend(std::iter::repeat(breakpoint).take(multiplicity));
    }
    let end = start + length;
    knots.push(end);
    let mut position = end;
    for _ in 1..degree {
        position += if clamped {
            0.0
        } else {
            step * rng.range(0.3, 1.0)
        };
        knots.push(position);
    }
    assert_eq!(knots.len(), count + degree - 1);
    knots
}

fn random_surface(rng: &mut Rng, index: usize) -> RandomSurface {
    let degree = [rng.int(1, 5), rng.int(1, 5)];
    let count = [
        rng.int(degree[0] + 1, degree[0] + 6),
        rng.int(degree[1] + 1, degree[1] + 6),
    ];
    let rational = rng.unit() < 0.5;
    let clamped = rng.unit() < 0.8;
    let knots = [
        random_knots(rng, degree[0], count[0], clamped),
        random_knots(rng, degree[1], count[1], clamped),
    ];
    let size = 10f64.powf(rng.range(-1.0, 2.0));
    let offset = DVec3::new(
        rng.range(-10.0, 10.0),
        rng.range(-10.0, 10.0),
        rng.range(-10.0, 10.0),
    );
    let mut x = 0.0;
    let mut points = Vec::new();
    for _ in 0..count[0] {
        x += rng.range(0.5, 1.5);
        let mut y = 0.0;
        for _ in 0..count[1] {
            y += rng.range(0.5, 1.5);
            let local = DVec3::new(
                x + rng.range(-0.15, 0.15),
                y + rng.range(-0.15, 0.15),
                rng.range(-0.6, 0.6),
            );
            points.push(offset + size * local);
        }
    }
    let weights: Option<Vec<f64>> =
        rational.then(|| points.iter().map(|_| rng.range(0.3, 3.0)).collect());
    let surface = NurbsSurface::new(
        degree,
        count,
        &knots[0],
        &knots[1],
        &points,
        weights.as_deref(),
    )
    .unwrap_or_else(|e| panic!("random surface {index} rejected: {e}"));
    let label = format!(
        "random surface {index} (degree {}x{}, {}, {})",
        degree[0],
        degree[1],
        if rational { "rational" } else { "non-rational" },
        if clamped { "clamped" } else { "unclamped" }
    );
    RandomSurface {
        surface,
        knots,
        degree,
        label,
    }
}

/// The non-empty spans [a, b] inside the domain of one direction (Rhino-convention knots).
fn spans(knots: &[f64], degree: usize) -> Vec<(f64, f64)> {
    let count = knots.len() + 1 - degree;
    (degree - 1..count - 1)
        .map(|k| (knots[k], knots[k + 1]))
        .filter(|(a, b)| a < b)
        .collect()
}

/// The parameter length over which the surface changes character in one direction: the knot
/// span's width, or |S'| / |S''| where the surface turns faster (high degree and uneven weights
/// near a clamped end). Finite-difference steps are a fraction of it.
fn local_scale(span_width: f64, first: DVec3, second: DVec3) -> f64 {
    span_width.min(first.length() / second.length())
}

/// Central difference of `f` at 0 with step h, Richardson-extrapolated twice (steps h, h/2,
/// h/4; error O(h^6)), so that steps can stay large enough for rounding not to matter.
fn richardson(f: impl Fn(f64) -> DVec3, h: f64, second: bool) -> DVec3 {
    let difference = |h: f64| {
        if second {
            (f(h) - 2.0 * f(0.0) + f(-h)) / (h * h)
        } else {
            (f(h) - f(-h)) / (2.0 * h)
        }
    };
    let (d1, d2, d4) = (difference(h), difference(0.5 * h), difference(0.25 * h));
    let (r1, r2) = ((4.0 * d2 - d1) / 3.0, (4.0 * d4 - d2) / 3.0);
    (16.0 * r2 - r1) / 15.0
}

fn assert_close(
    label: &str,
    what: &str,
    uv: (f64, f64),
    exact: DVec3,
    approximate: DVec3,
    scale: f64,
    worst: &mut f64,
) {
    let relative = (exact - approximate).length() / scale;
    assert!(
        relative <= RELATIVE_TOLERANCE,
        "{label}: {what} at {uv:?}: exact {exact}, finite differences {approximate}, relative error {relative:e}"
    );
    *worst = worst.max(relative);
}

/// For each surface and random (u, v) well inside one knot span in each direction (the finite
/// difference stencil never crosses a knot, where derivatives may jump): the exact derivatives
/// against Richardson-extrapolated central differences of the point. Errors are relative to
/// the derivative's length, floored for second derivatives at the magnitude the first derivative
/// implies over one knot span (|Su| / span width), so that a vanishing component is no excuse for
/// a failure or a pass.
#[test]
fn derivatives_match_central_differences_on_random_surfaces() {
    let mut rng = Rng(0x007E_570F_D1FF);
    let mut worst = [0.0f64; 5];
    let mut compared = 0;
    for index in 0..240 {
        let random = random_surface(&mut rng, index);
        let surface = &random.surface;
        let spans_u = spans(&random.knots[0], random.degree[0]);
        let spans_v = spans(&random.knots[1], random.degree[1]);
        for _ in 0..50 {
            let (a, b) = spans_u[rng.int(0, spans_u.len() - 1)];
            let (c, d) = spans_v[rng.int(0, spans_v.len() - 1)];
            let (margin_u, margin_v) = (STEP_FRACTION * (b - a), STEP_FRACTION * (d - c));
            let u = rng.range(a + margin_u, b - margin_u);
            let v = rng.range(c + margin_v, d - margin_v);
            let exact = surface.evaluate(u, v);
            let hu = STEP_FRACTION * local_scale(b - a, exact.su, exact.suu);
            let hv = STEP_FRACTION * local_scale(d - c, exact.sv, exact.svv);
            let point = |du: f64, dv: f64| surface.point_at(u + du, v + dv);

            let su = richardson(|t| point(t, 0.0), hu, false);
            let sv = richardson(|t| point(0.0, t), hv, false);
            let suu = richardson(|t| point(t, 0.0), hu, true);
            let svv = richardson(|t| point(0.0, t), hv, true);
            // Mixed: central difference in v of the central difference in u, both extrapolated.
            let suv = richardson(|t| richardson(|s| point(s, t), hu, false), hv, false);

            let label = &random.label;
            let uv = (u, v);
            assert_close(
                label,
                "Su",
                uv,
                exact.su,
                su,
                exact.su.length(),
                &mut worst[0],
            );
            assert_close(
                label,
                "Sv",
                uv,
                exact.sv,
                sv,
                exact.sv.length(),
                &mut worst[1],
            );
            let floor_uu = exact.su.length() / (b - a);
            let floor_vv = exact.sv.length() / (d - c);
            let floor_uv = (exact.su.length() / (d - c)).max(exact.sv.length() / (b - a));
            assert_close(
                label,
                "Suu",
                uv,
                exact.suu,
                suu,
                exact.suu.length().max(floor_uu),
                &mut worst[2],
            );
            assert_close(
                label,
                "Svv",
                uv,
                exact.svv,
                svv,
                exact.svv.length().max(floor_vv),
                &mut worst[3],
            );
            assert_close(
                label,
                "Suv",
                uv,
                exact.suv,
                suv,
                exact.suv.length().max(floor_uv),
                &mut worst[4],
            );
            compared += 1;
        }
    }
    println!(
        "{compared} points; worst relative errors Su {:e}, Sv {:e}, Suu {:e}, Svv {:e}, Suv {:e}",
        worst[0], worst[1], worst[2], worst[3], worst[4]
    );
}

/// One-sided differences at the domain's corners and edges, where central stencils do not fit:
/// second-order forward/backward differences, Richardson-extrapolated.
#[test]
fn first_derivatives_match_one_sided_differences_at_the_boundary() {
    let mut rng = Rng(0x00B0_4DA7);
    for index in 0..100 {
        let random = random_surface(&mut rng, index);
        let surface = &random.surface;
        let domain = surface.domain();
        let spans_u = spans(&random.knots[0], random.degree[0]);
        let spans_v = spans(&random.knots[1], random.degree[1]);
        let (first_u, last_u) = (spans_u[0], spans_u[spans_u.len() - 1]);
        let (first_v, last_v) = (spans_v[0], spans_v[spans_v.len() - 1]);
        for (u, v, su_width, sv_width, u_sign, v_sign) in [
            (
                domain.u.min,
                domain.v.min,
                first_u.1 - first_u.0,
                first_v.1 - first_v.0,
                1.0,
                1.0,
            ),
            (
                domain.u.max,
                domain.v.min,
                last_u.1 - last_u.0,
                first_v.1 - first_v.0,
                -1.0,
                1.0,
            ),
            (
                domain.u.min,
                domain.v.max,
                first_u.1 - first_u.0,
                last_v.1 - last_v.0,
                1.0,
                -1.0,
            ),
            (
                domain.u.max,
                domain.v.max,
                last_u.1 - last_u.0,
                last_v.1 - last_v.0,
                -1.0,
                -1.0,
            ),
        ] {
            let exact = surface.evaluate(u, v);
            // f'(0) ~ (-3 f(0) + 4 f(s h) - f(2 s h)) / (2 s h), error O(h^2); extrapolated O(h^3).
            let one_sided = |f: &dyn Fn(f64) -> DVec3, h: f64, sign: f64| {
                let difference = |h: f64| {
                    (-3.0 * f(0.0) + 4.0 * f(sign * h) - f(2.0 * sign * h)) / (2.0 * sign * h)
                };
                (4.0 * difference(0.5 * h) - difference(h)) / 3.0
            };
            let hu = 0.1 * STEP_FRACTION * local_scale(su_width, exact.su, exact.suu);
            let hv = 0.1 * STEP_FRACTION * local_scale(sv_width, exact.sv, exact.svv);
            let su = one_sided(&|t| surface.point_at(u + t, v), hu, u_sign);
            let sv = one_sided(&|t| surface.point_at(u, v + t), hv, v_sign);
            let mut worst = 0.0;
            assert_close(
                &random.label,
                "Su (one-sided)",
                (u, v),
                exact.su,
                su,
                exact.su.length(),
                &mut worst,
            );
            assert_close(
                &random.label,
                "Sv (one-sided)",
                (u, v),
                exact.sv,
                sv,
                exact.sv.length(),
                &mut worst,
            );
        }
    }
}

#[test]
fn point_at_agrees_with_evaluate() {
    let mut rng = Rng(0x0090_17A7);
    for index in 0..100 {
        let random = random_surface(&mut rng, index);
        let surface = &random.surface;
        let domain = surface.domain();
        for _ in 0..50 {
            let (u, v) = (domain.u.lerp(rng.unit()), domain.v.lerp(rng.unit()));
            let deviation = (surface.point_at(u, v) - surface.evaluate(u, v).point).length();
            assert!(
                deviation <= 1e-14 * surface.bounding_box_diagonal(),
                "{}: {deviation:e}",
                random.label
            );
        }
    }
}

/// `first_derivatives` gives `evaluate`'s point and first derivatives bit for bit (projections
/// mix the two, and their results must not depend on which was called), inside the domain,
/// on its sides and beyond them (clamped), on random surfaces and the benchmark dome (the
/// non-rational bicubic path).
#[test]
fn first_derivatives_are_those_of_evaluate_bit_for_bit() {
    let mut rng = Rng(0x00F1_257D);
    let mut surfaces: Vec<NurbsSurface> = (0..100)
        .map(|index| random_surface(&mut rng, index).surface)
        .collect();
    surfaces.push(tpi_core::benchmark::nurbs_dome());
    surfaces.push(tpi_core::benchmark::saddle());
    for surface in &surfaces {
        let domain = surface.domain();
        for _ in 0..200 {
            // Parameters up to a fifth of the domain beyond each side.
            let (s, t) = (1.4 * rng.unit() - 0.2, 1.4 * rng.unit() - 0.2);
            let (u, v) = (domain.u.lerp(s), domain.v.lerp(t));
            let d = surface.evaluate(u, v);
            let [point, su, sv] = surface.first_derivatives(u, v);
            for (a, b) in [(point, d.point), (su, d.su), (sv, d.sv)] {
                assert_eq!(
                    a.to_array().map(f64::to_bits),
                    b.to_array().map(f64::to_bits)
                );
            }
        }
    }
}

/// The surface is continuous across interior knots (multiplicity <= degree): the limits from
/// both sides agree with the value at the knot.
#[test]
fn surfaces_are_continuous_across_knots() {
    let mut rng = Rng(0x00C0_471A);
    for index in 0..100 {
        let random = random_surface(&mut rng, index);
        let surface = &random.surface;
        let domain = surface.domain();
        let diagonal = surface.bounding_box_diagonal();
        for &knot in random.knots[0]
            .iter()
            .filter(|&&k| domain.u.min < k && k < domain.u.max)
        {
            let v = domain.v.lerp(rng.unit());
            let at = surface.point_at(knot, v);
            let h = 1e-12 * domain.u.length();
            for side in [knot - h, knot + h] {
                let deviation = (surface.point_at(side, v) - at).length();
                assert!(
                    deviation <= 1e-9 * diagonal,
                    "{}: jump {deviation:e} at u = {knot}",
                    random.label
                );
            }
        }
    }
}

/// Outside the domain the surface is evaluated at the clamped parameters (module doc); infinite
/// parameters clamp too, NaN gives NaN and never a panic.
#[test]
fn evaluation_outside_the_domain_is_clamped() {
    let mut rng = Rng(0x000C_1A39);
    for index in 0..60 {
        let random = random_surface(&mut rng, index);
        let surface = &random.surface;
        let domain = surface.domain();
        let (u, v) = (domain.u.lerp(rng.unit()), domain.v.lerp(rng.unit()));
        let below_u = domain.u.min - 0.5 * domain.u.length();
        let above_v = domain.v.max + 3.0 * domain.v.length();
        assert_eq!(
            surface.evaluate(below_u, v),
            surface.evaluate(domain.u.min, v),
            "{}",
            random.label
        );
        assert_eq!(
            surface.evaluate(u, above_v),
            surface.evaluate(u, domain.v.max),
            "{}",
            random.label
        );
        assert_eq!(
            surface.evaluate(f64::NEG_INFINITY, f64::INFINITY),
            surface.evaluate(domain.u.min, domain.v.max),
            "{}",
            random.label
        );
        assert_eq!(
            surface.point_at(below_u, above_v),
            surface.point_at(domain.u.min, domain.v.max)
        );
        let nan = surface.evaluate(f64::NAN, v);
        assert!(nan.point.is_nan(), "{}", random.label);
        assert!(surface.point_at(u, f64::NAN).is_nan(), "{}", random.label);
    }
}

/// Inside the domain, every output is finite (no NaN), also exactly on knots and corners.
#[test]
fn evaluation_is_finite_everywhere_in_the_domain() {
    let mut rng = Rng(0x000F_117E);
    for index in 0..100 {
        let random = random_surface(&mut rng, index);
        let surface = &random.surface;
        let domain = surface.domain();
        let mut parameters_u: Vec<f64> = random.knots[0].clone();
        let mut parameters_v: Vec<f64> = random.knots[1].clone();
        parameters_u.extend((0..5).map(|_| domain.u.lerp(rng.unit())));
        parameters_v.extend((0..5).map(|_| domain.v.lerp(rng.unit())));
        for &u in &parameters_u {
            for &v in &parameters_v {
                let d = surface.evaluate(u, v);
                for vector in [d.point, d.su, d.sv, d.suu, d.suv, d.svv] {
                    assert!(vector.is_finite(), "{}: {d:?} at ({u}, {v})", random.label);
                }
            }
        }
    }
}
