//! Issue 15, item 1: tolerance-driven patterns. Every mesh vertex is checked against the
//! tolerance independently of the crate: on the two quadrics of this file (a dome and a
//! saddle, neither among the samples, principal directions turned off the parameter lines)
//! by the closed-form distance to a quadric (`TurnedQuadric::distance`), on the samples by
//! this file's own projection (`common::closest_parameters`: brute force on a grid, then
//! Newton on |S - x|^2 inside the closed domain); never by the report's number or the crate's
//! projection. The uniform hexagonal baseline is found here by bisection on
//! `hex:spacing=1/N` with the same independent measure, as the acceptance reads.

mod common;

use common::*;
use glam::DVec3;
use tpi_core::{
    discretise, fit_pattern, DiscretiseOptions, Domain, Generator, Interval, Surface,
    SurfaceDerivatives,
};

/// The largest distance of a mesh vertex from the surface (by `distance`) and the mesh's
/// invalid facets.
fn independent_check_by(
    surface: &dyn Surface,
    uv: &[[f64; 2]],
    distance: &dyn Fn(DVec3) -> f64,
) -> (f64, usize) {
    let d = discretise(surface, uv, &DiscretiseOptions::default()).unwrap();
    d.sanity_check().unwrap();
    let max = max_over_used_vertices(&d, distance);
    (max, d.quality.unwrap().invalid_facets)
}

/// The distance to the surface by this file's own projection (grid, then Newton).
fn projected_distance(surface: &dyn Surface) -> impl Fn(DVec3) -> f64 + '_ {
    move |x| {
        let [u, v] = closest_parameters(surface, x, 12);
        surface.point_at(u, v).distance(x)
    }
}

/// The largest distance of a mesh vertex from the surface (own projection) and the mesh's
/// invalid facets.
fn independent_check(surface: &dyn Surface, uv: &[[f64; 2]]) -> (f64, usize) {
    independent_check_by(surface, uv, &projected_distance(surface))
}

/// The two uniform hexagonal baselines: `hex:spacing=1/N` (rows sqrt(3) / 2 of a column
/// apart, regular cells on a square domain) and `hex:NxN` (N columns and N rows).
const HEX_BASELINES: [&str; 2] = ["hex:spacing", "hex:NxN"];

/// The generator of a baseline at N.
fn hex_spec(baseline: &str, n: usize) -> String {
    match baseline {
        "hex:spacing" => format!("hex:spacing={}", 1.0 / n as f64),
        _ => format!("hex:{n}x{n}"),
    }
}

/// The smallest pattern of a baseline ([`HEX_BASELINES`]) meeting the tolerance by the
/// independent measure: N doubled from 4 until it does, then bisected. (count, invalid
/// facets).
fn hex_bisection(
    surface: &dyn Surface,
    tolerance: f64,
    distance: &dyn Fn(DVec3) -> f64,
    baseline: &str,
) -> (usize, usize) {
    let hex = |n: usize| {
        let uv = Generator::parse(&hex_spec(baseline, n))
            .unwrap()
            .generate()
            .uv;
        let (dev, invalid) = independent_check_by(surface, &uv, distance);
        println!(
            "  {} {n}: {} points, max deviation {dev:.5e}",
            baseline,
            uv.len()
        );
        (dev <= tolerance, uv.len(), invalid)
    };
    let (mut lo, mut hi) = (2, 4);
    let mut found = loop {
        let h = hex(hi);
        if h.0 {
            break h;
        }
        lo = hi;
        hi *= 2;
        assert!(hi <= 128, "no {baseline} up to 128 meets {tolerance}");
    };
    while hi - lo > 1 {
        let mid = (lo + hi) / 2;
        let h = hex(mid);
        if h.0 {
            hi = mid;
            found = h;
        } else {
            lo = mid;
        }
    }
    (found.1, found.2)
}

/// Fits, checks every vertex by `distance`, compares with each of the [`HEX_BASELINES`]
/// measured the same way; returns the ratios of counts (fitted over baseline), in the order
/// of [`HEX_BASELINES`].
fn fit_and_compare_by(
    name: &str,
    surface: &dyn Surface,
    tolerance: f64,
    distance: &dyn Fn(DVec3) -> f64,
) -> [f64; 2] {
    let fitted = fit_pattern(surface, tolerance, 0, &DiscretiseOptions::default()).unwrap();
    assert!(fitted.met, "{name}: {fitted:?}");
    let (dev, invalid) = independent_check_by(surface, &fitted.uv, distance);
    // Rounding of the two projections apart, every vertex within D.
    assert!(
        dev <= tolerance * (1.0 + 1e-9),
        "{name}: {dev} > {tolerance}"
    );
    HEX_BASELINES.map(|baseline| {
        let (hex_count, hex_invalid) = hex_bisection(surface, tolerance, distance, baseline);
        let ratio = fitted.uv.len() as f64 / hex_count as f64;
        println!(
            "{name} D = {tolerance}: fitted {} points (independent max deviation {dev:.5e}, \
             {invalid} invalid), smallest {baseline} meeting D {hex_count} ({hex_invalid} \
             invalid): ratio {ratio:.3}",
            fitted.uv.len()
        );
        if hex_invalid == 0 {
            assert_eq!(
                invalid, 0,
                "{name}: invalid facets where uniform hex has none"
            );
        }
        ratio
    })
}

/// [`fit_and_compare_by`] on a sample, measured by this file's own projection.
fn fit_and_compare(name: &str, tolerance: f64) -> [f64; 2] {
    let surface = sample_surface(name);
    let distance = projected_distance(&surface);
    fit_and_compare_by(name, &surface, tolerance, &distance)
}

/// The quadric z = 1/2 (k1 X^2 + k2 Y^2) in a frame turned by `angle` about z
/// (X = c x + s y, Y = -s x + c y), over [-hx, hx] x [-hy, hy] in (x, y): a dome for
/// k1, k2 > 0 (its principal directions across the parameter lines), a saddle for k2 < 0.
struct TurnedQuadric {
    k: [f64; 2],
    angle: f64,
    half: [f64; 2],
}

impl TurnedQuadric {
    /// z and its derivatives at (x, y): (z, [zx, zy], [zxx, zxy, zyy]).
    fn height(&self, x: f64, y: f64) -> (f64, [f64; 2], [f64; 3]) {
        let (s, c) = self.angle.sin_cos();
        let (bx, by) = (c * x + s * y, -s * x + c * y);
        let [k1, k2] = self.k;
        let z = 0.5 * (k1 * bx * bx + k2 * by * by);
        let zx = k1 * bx * c - k2 * by * s;
        let zy = k1 * bx * s + k2 * by * c;
        let zxx = k1 * c * c + k2 * s * s;
        let zxy = (k1 - k2) * s * c;
        let zyy = k1 * s * s + k2 * c * c;
        (z, [zx, zy], [zxx, zxy, zyy])
    }

    /// The distance from p to the quadric patch in closed form: in the principal frame the
    /// foot is X = Px / (1 + k1 m), Y = Py / (1 + k2 m), m the root of
    /// g(m) = 1/2 (k1 X^2 + k2 Y^2) - Pz - m on the interval where 1 + k_i m > 0 (g falls
    /// there from +inf to -inf: one root, found by bisection to the last bit). When that
    /// foot lies outside the patch, the nearest point of the patch is on its boundary, and
    /// this file's projection is used instead.
    fn distance(&self, p: DVec3) -> Option<f64> {
        let (s, c) = self.angle.sin_cos();
        let (px, py) = (c * p.x + s * p.y, -s * p.x + c * p.y);
        let [k1, k2] = self.k;
        let foot = |m: f64| (px / (1.0 + k1 * m), py / (1.0 + k2 * m));
        let g = |m: f64| {
            let (x, y) = foot(m);
            0.5 * (k1 * x * x + k2 * y * y) - p.z - m
        };
        let bound = |k: f64| if k > 0.0 { -1.0 / k } else { 1.0 / -k };
        let (mut lo, mut hi) = (f64::NEG_INFINITY, f64::INFINITY);
        for k in [k1, k2] {
            if k > 0.0 {
                lo = lo.max(bound(k));
            } else if k < 0.0 {
                hi = hi.min(bound(k));
            }
        }
        // Finite ends: step in from the poles.
        let mut a = if lo.is_finite() { lo } else { -1.0 };
        let mut b = if hi.is_finite() { hi } else { 1.0 };
        while !lo.is_finite() && g(a) < 0.0 {
            a *= 2.0;
        }
        while !hi.is_finite() && g(b) > 0.0 {
            b *= 2.0;
        }
        for _ in 0..2000 {
            let mid = 0.5 * (a + b);
            if !(mid > a && mid < b) {
                break;
            }
            if g(mid) > 0.0 {
                a = mid;
            } else {
                b = mid;
            }
        }
        let (fx, fy) = foot(0.5 * (a + b));
        let (x, y) = (c * fx - s * fy, s * fx + c * fy);
        let slack = 1e-9 * (self.half[0] + self.half[1]);
        if x.abs() > self.half[0] + slack || y.abs() > self.half[1] + slack {
            return None;
        }
        let z = 0.5 * (k1 * fx * fx + k2 * fy * fy);
        Some(DVec3::new(x, y, z).distance(p))
    }
}

impl Surface for TurnedQuadric {
    fn domain(&self) -> Domain {
        Domain::new(
            Interval::new(-self.half[0], self.half[0]),
            Interval::new(-self.half[1], self.half[1]),
        )
    }

    fn evaluate(&self, x: f64, y: f64) -> SurfaceDerivatives {
        let (z, [zx, zy], [zxx, zxy, zyy]) = self.height(x, y);
        SurfaceDerivatives {
            point: DVec3::new(x, y, z),
            su: DVec3::new(1.0, 0.0, zx),
            sv: DVec3::new(0.0, 1.0, zy),
            suu: DVec3::new(0.0, 0.0, zxx),
            suv: DVec3::new(0.0, 0.0, zxy),
            svv: DVec3::new(0.0, 0.0, zyy),
        }
    }
}

/// A quadric's distance: its closed form, this file's projection where the foot leaves the
/// patch (boundary vertices).
fn quadric_distance(q: &TurnedQuadric) -> impl Fn(DVec3) -> f64 + '_ {
    move |x| {
        q.distance(x).unwrap_or_else(|| {
            let [u, v] = closest_parameters(q, x, 24);
            q.point_at(u, v).distance(x)
        })
    }
}

/// The closed form is the distance: at points placed along the normal of the quadric at
/// known heights, it gives the height back (and this file's projection agrees).
#[test]
fn the_quadric_oracle_gives_the_height_along_the_normal() {
    for q in [DOME, SADDLE] {
        for (x, y, h) in [(0.3, -1.2, 0.01), (-2.0, 1.5, -0.02), (1.0, 0.5, 0.005)] {
            let d = q.evaluate(x, y);
            let n = d.su.cross(d.sv).normalize();
            let p = d.point + h * n;
            let closed = q.distance(p).unwrap();
            assert!((closed - f64::abs(h)).abs() < 1e-12, "{closed} vs {h}");
            let [u, v] = closest_parameters(&q, p, 24);
            assert!((q.point_at(u, v).distance(p) - closed).abs() < 1e-10);
        }
    }
}

/// A dome not among the samples: curvatures 0.12 and 0.05 with principal directions at
/// 30 degrees to the parameter lines, over 12 x 8.
const DOME: TurnedQuadric = TurnedQuadric {
    k: [0.12, 0.05],
    angle: 0.5235987755982988,
    half: [6.0, 4.0],
};

/// A saddle not among the samples: curvatures 0.1 and -0.06 turned by 20 degrees, over
/// 10 x 10.
const SADDLE: TurnedQuadric = TurnedQuadric {
    k: [0.1, -0.06],
    angle: 0.3490658503988659,
    half: [5.0, 5.0],
};

#[test]
fn a_turned_anisotropic_dome_needs_at_most_60_percent_of_the_uniform_hex_points() {
    for tolerance in [0.01, 0.003] {
        let ratios = fit_and_compare_by("turned dome", &DOME, tolerance, &quadric_distance(&DOME));
        // Measured 0.395 / 0.412 (D = 0.01) and 0.378 / 0.458 (0.003) since the near misses
        // are relaxed (0.419 / 0.438 and 0.386 / 0.467 before): the 0.60 with room,
        // tightened to catch a loss.
        assert!(ratios.iter().all(|&r| r <= 0.5), "{tolerance}: {ratios:?}");
    }
}

#[test]
fn a_turned_saddle_needs_at_most_60_percent_of_the_uniform_hex_points() {
    for tolerance in [0.01, 0.003] {
        let ratios = fit_and_compare_by(
            "turned saddle",
            &SADDLE,
            tolerance,
            &quadric_distance(&SADDLE),
        );
        // Measured 0.312 / 0.400 (D = 0.01) and 0.231 / 0.284 (0.003).
        assert!(ratios.iter().all(|&r| r <= 0.45), "{tolerance}: {ratios:?}");
    }
}

/// Hyperbolic paraboloids z = k / 2 (x^2 - y^2) over 10 x 10 with their principal
/// directions along the parameter lines, as the uniform hex pattern's rows are (so the hex's
/// interior vertices stand off only a quarter of a dome's of the same curvature, and it is set
/// by its walls and corners), asymptotic directions at 45 degrees: curvatures 0.24 and 0.1,
/// not among the samples (samples/hypar.json is 0.16). Before the lattices refined at their
/// walls and the saddle rows (fit.rs) the ratios were 0.858 and 0.492 (k = 0.24, D = 0.01 and
/// 0.003) and 0.415 and 0.736 (k = 0.1); after, 0.545, 0.291, 0.415, 0.374. Against
/// hex:spacing / hex:NxN (2026-11-28): k = 0.24 0.406 / 0.520 (117 points) and 0.199 /
/// 0.491, k = 0.1 0.364 / 0.493 and 0.341 / 0.481; since the inset saddle lattices (branch
/// fit22): k = 0.24 0.326 / 0.418 (94 points) and 0.142 / 0.351 (237), k = 0.1 0.333 / 0.451
/// (65) and 0.341 / 0.481 (212, unchanged).
const ALIGNED_HYPARS: [TurnedQuadric; 2] = [
    TurnedQuadric {
        k: [0.24, -0.24],
        angle: 0.0,
        half: [5.0, 5.0],
    },
    TurnedQuadric {
        k: [0.1, -0.1],
        angle: 0.0,
        half: [5.0, 5.0],
    },
];

#[test]
fn aligned_hypars_need_at_most_60_percent_of_the_uniform_hex_points() {
    for q in &ALIGNED_HYPARS {
        for tolerance in [0.01, 0.003] {
            let name = format!("aligned hypar k = {}", q.k[0]);
            let ratios = fit_and_compare_by(&name, q, tolerance, &quadric_distance(q));
            // Against hex:NxN (rows a column apart, which suits the walls of a hypar) the
            // 60 % was not met at k = 0.24, D = 0.01 with 153 points against 225 (0.680);
            // 117 points (0.520) before the inset saddle lattices, 94 (0.418) since; the
            // largest now 0.481 (k = 0.1, D = 0.003).
            assert!(
                ratios[0] <= 0.4 && ratios[1] <= 0.52,
                "{name}, {tolerance}: {ratios:?}"
            );
        }
    }
}

#[test]
fn a_free_form_dome_needs_at_most_60_percent_of_the_uniform_hex_points() {
    let ratios = fit_and_compare("nurbs-dome.json", 0.01);
    // Measured 0.375 / 0.431 (314 points against 837 and 729; 331 points, 0.395 / 0.454,
    // before the near misses relaxed towards a minimax covering).
    assert!(ratios.iter().all(|&r| r <= 0.47), "{ratios:?}");
}

#[test]
fn a_free_form_saddle_needs_at_most_60_percent_of_the_uniform_hex_points() {
    let ratios = fit_and_compare("saddle.json", 0.01);
    // Measured 0.262 / 0.250 (132 points against 504 and 529; 149 points, 0.296 / 0.282,
    // before the inset saddle lattices).
    assert!(ratios.iter().all(|&r| r <= 0.3), "{ratios:?}");
}

/// The paraboloid of revolution and the hypar have nearly uniform curvature and
/// parametrisation: what a pattern saves there is mostly at the boundary (uniform hex is set
/// by its corners and boundary vertices). On the hypar the 60 % holds since the
/// lattices refined at their walls and the lattices with other row densities on saddles
/// (`fit.rs`): 0.431 (110 points against 255; 0.702 with 179 before) at D = 0.01, 0.278 (71
/// points) since the saddle lattices inset from the walls (branch fit22). On the
/// paraboloid it holds against both since the near misses of the lattice search are relaxed
/// towards a minimax covering (`fit.rs`): 0.565 and 0.589 (285 points against 504 and 484;
/// 295 before, 0.585 and 0.610; 0.593 and 0.618 before the lattices with rows inset from the
/// walls, 0.659 against hex:spacing before the lattices with sparser sides, 0.623 before the
/// steeper grading). On the paraboloid the lattice's
/// cells are already as regular as cells can be (a hexagonal lattice is the thinnest
/// covering: at a given count no pattern has smaller circumcircles); what is left is the
/// fall of the curvature away from the apex (sqrt(k1 k2) dA goes as
/// (1 + 0.0256 r^2)^(-1/2) dx dy): a pattern with a perfect hexagon everywhere, each sized by
/// its own curvature, would have 0.848 of a uniform lattice's points and 0.928 of a lattice
/// graded along s and t, i.e. a ratio of 0.53..0.58, which only a varying yet regular
/// lattice could approach (the relaxed Poisson patterns of the rounds lose about 30 % to
/// their irregular cells). With the walls' waste counted that bound is 271 points at
/// D = 0.01 (0.559 against hex:NxN) and 888 at 0.003 (0.584 against the 1,521 of hex:39x39;
/// docs/performance.md, branch fit22), so on this surface 0.60 with room is out of reach for
/// any pattern at 0.003. Asserted: the measured ratios, with a little room.
#[test]
fn on_nearly_uniform_surfaces_the_pattern_still_beats_uniform_hex() {
    // Bounds against hex:spacing and hex:NxN: measured 0.565 and 0.589 on the paraboloid
    // (285 points against 504 and 484, since the near misses relaxed towards a minimax
    // covering; 295, 0.585 and 0.610, before; 299, 0.593 and 0.618, before the rows inset
    // from the walls; 312, 0.619 and 0.645, before the steeper grading of
    // FIT_STEEP_GRADING), 0.278 and 0.362 on the hypar (71 against 255 and 196, since the
    // saddle lattices inset from the walls; 110, 0.431 and 0.561, before; 135 points, 0.529
    // and 0.689, before the lattices of other row densities: hex:NxN's rows a column apart
    // suit the hypar's walls).
    for (name, bounds) in [
        ("paraboloid.json", [0.58, 0.6]),
        ("hypar.json", [0.33, 0.42]),
    ] {
        let ratios = fit_and_compare(name, 0.01);
        assert!(
            ratios.iter().zip(bounds).all(|(&r, b)| r <= b),
            "{name}: {ratios:?}"
        );
    }
}

#[test]
fn bad_tolerances_are_named() {
    let surface = sample_surface("paraboloid.json");
    for bad in [0.0, -1.0, f64::NAN, f64::INFINITY] {
        let e = fit_pattern(&surface, bad, 0, &DiscretiseOptions::default()).unwrap_err();
        assert!(e.to_string().contains("max_deviation"), "{e}");
    }
    // A tolerance needing far too many points is refused before any point is made.
    let e = fit_pattern(&surface, 1e-12, 0, &DiscretiseOptions::default()).unwrap_err();
    assert!(e.to_string().contains("pattern points"), "{e}");
}

/// A roof with crests, flanks and parabolic lines between them: where neighbouring tangent
/// planes are nearly parallel, exact vertices run away from the surface whatever points are
/// added there, so a refinement that keeps adding points never ends (it ran for more than
/// 15 minutes, each mesh slower than the last). The fit must stop refining a round that no
/// longer gets closer, and still return a pattern that meets D at every vertex by this
/// file's own projection, with no invalid facet.
#[test]
fn a_mixed_curvature_roof_is_fitted_without_endless_refinement() {
    let surface = sample_surface("mixed-roof.json");
    let tolerance = 0.01;
    let fitted = fit_pattern(&surface, tolerance, 0, &DiscretiseOptions::default()).unwrap();
    assert!(fitted.met, "{fitted:?}");
    let (dev, invalid) = independent_check(&surface, &fitted.uv);
    println!(
        "mixed-roof D = {tolerance}: {} points, {} discretisations, independent max deviation \
         {dev:.5e}, {invalid} invalid",
        fitted.uv.len(),
        fitted.discretisations
    );
    assert!(dev <= tolerance * (1.0 + 1e-9), "{dev} > {tolerance}");
    assert_eq!(invalid, 0);
}

/// A closed surface with poles: the refinement adds points at the feet of offending
/// vertices, and near a pole or the seam those feet used to be clamped onto the pole side
/// (a seed there is refused: "it lies on a pole") or onto both sides of the seam. Now they
/// keep clear of both, and neighbourhoods are judged on the surface, not in parameters.
#[test]
fn a_closed_surface_with_poles_is_fitted() {
    let surface = sample_surface("ellipsoid.json");
    let tolerance = 0.05;
    let fitted = fit_pattern(&surface, tolerance, 0, &DiscretiseOptions::default()).unwrap();
    assert!(fitted.met, "{fitted:?}");
    // The sample is the ellipsoid with semi-axes 12, 8, 5 about the origin: the oracle is
    // its closed-form distance (a projection from a grid stalls at the poles).
    let d = discretise(&surface, &fitted.uv, &DiscretiseOptions::default()).unwrap();
    d.sanity_check().unwrap();
    let dev = max_over_used_vertices(&d, |x| ellipsoid_distance([12.0, 8.0, 5.0], x));
    let invalid = d.quality.as_ref().unwrap().invalid_facets;
    println!(
        "ellipsoid D = {tolerance}: {} points, closed-form max deviation {dev:.5e}, {invalid} invalid",
        fitted.uv.len()
    );
    assert!(dev <= tolerance * (1.0 + 1e-9), "{dev} > {tolerance}");
    assert_eq!(invalid, 0);
}

/// The paraboloid z = -0.08 (x^2 + y^2) over [-5, 5]^2 with a bump 1e-4 high and 1e-5 wide
/// at its apex, where one node of the fit's curvature field lies: there the curvature is
/// 2e6, ten million times the rest. Real faces have such nodes next to degenerate poles
/// (curvature 1e13 at 2 of 4,225 nodes): taken as the surface's largest curvature they
/// floored the field everywhere and the fit asked for 1e14 points. The bump is far below
/// the tolerance, so the fit should not see it: about as many points as on the smooth
/// paraboloid, and every vertex within D by the independent projection.
#[test]
fn an_isolated_singular_curvature_does_not_set_the_spacing() {
    struct Bumped;
    const A: f64 = -0.08;
    const HEIGHT: f64 = 1e-4;
    const WIDTH: f64 = 1e-5;
    impl tpi_core::Surface for Bumped {
        fn domain(&self) -> tpi_core::Domain {
            tpi_core::Domain::new(
                tpi_core::Interval::new(-5.0, 5.0),
                tpi_core::Interval::new(-5.0, 5.0),
            )
        }
        fn evaluate(&self, x: f64, y: f64) -> tpi_core::SurfaceDerivatives {
            // z = A r^2 + H exp(-r^2 / w^2).
            let w2 = WIDTH * WIDTH;
            let e = HEIGHT * (-(x * x + y * y) / w2).exp();
            let z = A * (x * x + y * y) + e;
            let zx = 2.0 * A * x - 2.0 * x / w2 * e;
            let zy = 2.0 * A * y - 2.0 * y / w2 * e;
            let zxx = 2.0 * A + (4.0 * x * x / (w2 * w2) - 2.0 / w2) * e;
            let zyy = 2.0 * A + (4.0 * y * y / (w2 * w2) - 2.0 / w2) * e;
            let zxy = 4.0 * x * y / (w2 * w2) * e;
            tpi_core::SurfaceDerivatives {
                point: glam::DVec3::new(x, y, z),
                su: glam::DVec3::new(1.0, 0.0, zx),
                sv: glam::DVec3::new(0.0, 1.0, zy),
                suu: glam::DVec3::new(0.0, 0.0, zxx),
                suv: glam::DVec3::new(0.0, 0.0, zxy),
                svv: glam::DVec3::new(0.0, 0.0, zyy),
            }
        }
    }
    let tolerance = 0.01;
    let options = DiscretiseOptions::default();
    let smooth = fit_pattern(&sample_surface("paraboloid.json"), tolerance, 0, &options).unwrap();
    let bumped = fit_pattern(&Bumped, tolerance, 0, &options).unwrap();
    assert!(bumped.met, "{bumped:?}");
    // A vertex's distance to the bumped surface is at most its distance to the bumped
    // surface's point above its foot on the smooth paraboloid (projected independently; the
    // two surfaces share their parameters x, y), which is within HEIGHT exp(-r^2 / w^2) of
    // the smooth distance.
    let paraboloid = sample_surface("paraboloid.json");
    let bound = |x: DVec3| {
        let [u, v] = closest_parameters(&paraboloid, x, 12);
        let [a, b] = paraboloid.domain().to_normalised([u, v]);
        let [bu, bv] = Bumped.domain().from_normalised([a, b]);
        Bumped.point_at(bu, bv).distance(x)
    };
    let (dev, invalid) = independent_check_by(&Bumped, &bumped.uv, &bound);
    println!(
        "bumped paraboloid: {} points (smooth {}), independent max deviation {dev:.5e}",
        bumped.uv.len(),
        smooth.uv.len()
    );
    assert!(dev <= tolerance * (1.0 + 1e-9), "{dev} > {tolerance}");
    assert_eq!(invalid, 0);
    assert!(
        (bumped.uv.len() as f64) < 1.5 * smooth.uv.len() as f64,
        "{} points against {} on the smooth paraboloid",
        bumped.uv.len(),
        smooth.uv.len()
    );
}
