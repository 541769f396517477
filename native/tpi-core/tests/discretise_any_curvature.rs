//! Acceptance of valid meshes on surfaces of any curvature (issue 10): saddles (K < 0
//! everywhere), a torus band, a rotated and a skewed hyperbolic paraboloid, with hex patterns
//! at several rotations, square grids and Poisson-disk patterns, give meshes that are valid by
//! the independent checks of `common::validity` (own-plane simplicity, overlap along the mean
//! normal measured by the `geo` polygon library, Euler characteristic and boundary loops from
//! the loops), boundary facets included. Mixed surfaces always give a disc, and every facet
//! the independent check finds invalid is flagged by the report.
//!
//! `TPI_TABLE=1 cargo test --release -p tpi-core --test discretise_any_curvature -- --nocapture`
//! prints the whole table.
// NaN-safe negated comparisons are intended; index loops read better in geometry checks.
#![allow(clippy::needless_range_loop, clippy::neg_cmp_op_on_partial_ord)]

mod common;

use common::validity::{check, Validity};
use common::*;
use glam::DVec3;
use tpi_core::{
    discretise, AnalyticKind, AnalyticSurface, Discretisation, DiscretiseOptions, Generator,
    NurbsSurface, PlaneMode, Surface,
};
use tpi_core::{FLAG_NON_SIMPLE, FLAG_OVERLAP};

/// A square grid of about `n` cell centres.
fn grid(n: usize) -> Vec<[f64; 2]> {
    let k = (n as f64).sqrt().round() as usize;
    (0..k)
        .flat_map(|i| {
            (0..k).map(move |j| [(i as f64 + 0.5) / k as f64, (j as f64 + 0.5) / k as f64])
        })
        .collect()
}

fn poisson(n: usize, seed: u64) -> Vec<[f64; 2]> {
    // Bridson's samples fill about 0.7 / r^2 points per unit area.
    let r = (0.7 / n as f64).sqrt();
    Generator::Poisson { radius: r, seed }.generate().uv
}

/// A rational biquadratic patch of the torus with major radius `big` and tube radius
/// `small`: tube angle `phi` (0 = outer equator) and revolution angle `theta` (radians).
fn torus_patch(big: f64, small: f64, phi: [f64; 2], theta: [f64; 2]) -> NurbsSurface {
    // Control points of a rational quadratic arc on the unit circle, with weights.
    let arc = |[a0, a1]: [f64; 2]| {
        let half = 0.5 * (a1 - a0);
        let mid = 0.5 * (a0 + a1);
        let w = half.cos();
        [
            ((a0.cos(), a0.sin()), 1.0),
            ((mid.cos() / w, mid.sin() / w), w),
            ((a1.cos(), a1.sin()), 1.0),
        ]
    };
    let (rev, tube) = (arc(theta), arc(phi));
    let mut points = Vec::new();
    let mut weights = Vec::new();
    for &((cx, cy), wu) in &rev {
        for &((px, pz), wv) in &tube {
            // Profile point (distance from the axis, height): the tube circle's centre (big, 0)
            // plus the arc's control point scaled by the tube radius.
            let radial = big + small * px;
            points.push(DVec3::new(radial * cx, radial * cy, small * pz));
            weights.push(wu * wv);
        }
    }
    NurbsSurface::new(
        [2, 2],
        [3, 3],
        &[0.0, 0.0, 1.0, 1.0],
        &[0.0, 0.0, 1.0, 1.0],
        &points,
        Some(&weights),
    )
    .unwrap_or_else(|e| panic!("torus patch rejected: {e}"))
}

fn hypar() -> AnalyticSurface {
    AnalyticSurface::new(
        AnalyticKind::HyperbolicParaboloid { a: 0.08, b: 0.08 },
        [-5.0, 5.0],
        [-5.0, 5.0],
    )
    .unwrap()
}

/// z = 0.08 x y: the hyperbolic paraboloid turned by 45 degrees (exact as a biquadratic net).
fn rotated_hypar() -> NurbsSurface {
    lifted_net(
        [2, 2],
        &[0.0, 0.0, 0.5, 1.0, 1.0],
        &[0.0, 0.0, 0.5, 1.0, 1.0],
        |s, t| (-5.0 + 10.0 * s, -5.0 + 10.0 * t),
        |x, y, _, _| 0.08 * x * y,
        None,
    )
}

/// A saddle whose curvature varies across the domain, skewed by a cubic term.
fn skewed_saddle() -> NurbsSurface {
    lifted_net(
        [3, 3],
        &[0.0, 0.0, 0.0, 0.3, 0.55, 1.0, 1.0, 1.0],
        &[0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0],
        |s, t| (-5.0 + 10.0 * s, -4.0 + 8.0 * t),
        |x, y, _, _| 0.05 * x * x - 0.09 * y * y + 0.03 * x * y + 0.003 * x * x * x,
        None,
    )
}

fn torus_band() -> NurbsSurface {
    torus_patch(
        10.0,
        3.0,
        [120f64.to_radians(), 240f64.to_radians()],
        [-45f64.to_radians(), 45f64.to_radians()],
    )
}

/// Largest Gaussian curvature over a 30 x 30 grid (negative: a saddle everywhere).
fn max_gaussian(surface: &dyn Surface) -> f64 {
    let dom = surface.domain();
    let mut worst = f64::NEG_INFINITY;
    for i in 0..=30 {
        for j in 0..=30 {
            let [u, v] = dom.from_normalised([i as f64 / 30.0, j as f64 / 30.0]);
            worst = worst.max(gaussian_and_mean(surface, u, v).0);
        }
    }
    worst
}

/// Whether the Gaussian curvature changes sign (or vanishes) within `radius` (normalised
/// parameters) of `st`: the point lies near a parabolic line.
fn near_parabolic_line(surface: &dyn Surface, st: [f64; 2], radius: f64) -> bool {
    let dom = surface.domain();
    let k = |s: f64, t: f64| {
        let [u, v] = dom.from_normalised([s.clamp(0.0, 1.0), t.clamp(0.0, 1.0)]);
        gaussian_and_mean(surface, u, v).0
    };
    let centre = k(st[0], st[1]);
    (1..=4).any(|r| {
        let rr = radius * r as f64 / 4.0;
        (0..24).any(|a| {
            let angle = a as f64 * std::f64::consts::TAU / 24.0;
            let other = k(st[0] + rr * angle.cos(), st[1] + rr * angle.sin());
            other * centre <= 0.0
        })
    })
}

struct Case {
    surface: String,
    pattern: String,
    points: usize,
    validity: Validity,
    flagged_missing: usize,
    /// Invalid facets with a boundary or corner vertex.
    invalid_at_boundary: usize,
    /// Invalid facets farther than 4 pattern spacings from every parabolic line.
    invalid_far_from_parabolic: usize,
    /// The crate's own structural check (`Discretisation::sanity_check`).
    sanity: Result<(), String>,
}

fn run(
    surface_name: &str,
    surface: &dyn Surface,
    pattern_name: &str,
    pattern: &[[f64; 2]],
) -> Case {
    run_with(
        surface_name,
        surface,
        pattern_name,
        pattern,
        &DiscretiseOptions::default(),
    )
    .0
}

fn run_with(
    surface_name: &str,
    surface: &dyn Surface,
    pattern_name: &str,
    pattern: &[[f64; 2]],
    options: &DiscretiseOptions,
) -> (Case, Discretisation) {
    let d = discretise(surface, pattern, options)
        .unwrap_or_else(|e| panic!("{surface_name} / {pattern_name}: {e}"));
    let validity = check(&d);
    if std::env::var_os("TPI_DEBUG").is_some() && !validity.is_disc() {
        eprintln!("{surface_name} {pattern_name}: {:?}", d.diagnostics);
        let t = topology(&d);
        let boundary: Vec<_> = t
            .edge_facets
            .iter()
            .filter(|(_, f)| f.len() == 1)
            .map(|(e, f)| (*e, f[0], d.vertex_kinds[e.0 as usize]))
            .collect();
        let interior: Vec<_> = boundary
            .iter()
            .filter(|b| b.2 == tpi_core::VertexKind::Interior)
            .collect();
        eprintln!("interior-kind boundary edges: {interior:?}");
    }
    // Every facet the independent check finds invalid must be flagged by the report.
    let flagged_missing = unflagged_invalid(&d, &validity);
    if std::env::var_os("TPI_DEBUG").is_some() {
        let q = d.quality.as_ref().unwrap();
        eprintln!("{surface_name} {pattern_name}: {:?}", q.neighbours);
    }
    let invalid_at_boundary = validity
        .invalid_facets()
        .into_iter()
        .filter(|&i| touches_boundary(&d, i))
        .count();
    let spacing = 1.0 / (pattern.len() as f64).sqrt();
    let invalid_far_from_parabolic = validity
        .invalid_facets()
        .into_iter()
        .filter(|&i| !near_parabolic_line(surface, pattern[i], 4.0 * spacing))
        .count();
    let sanity = d.sanity_check().map_err(|e| e.to_string());
    (
        Case {
            surface: surface_name.into(),
            pattern: pattern_name.into(),
            points: pattern.len(),
            validity,
            flagged_missing,
            invalid_at_boundary,
            invalid_far_from_parabolic,
            sanity,
        },
        d,
    )
}

fn patterns(n: usize) -> Vec<(String, Vec<[f64; 2]>)> {
    let mut out: Vec<(String, Vec<[f64; 2]>)> = [0.0, 15.0, 30.0, 45.0, 72.0]
        .iter()
        .map(|&deg| (format!("hex{n}@{deg}"), rotated_hex(n, deg)))
        .collect();
    out.push((format!("grid{n}"), grid(n)));
    out.push((format!("poisson{n}"), poisson(n, 7 + n as u64)));
    out
}

fn report(cases: &[Case]) {
    if std::env::var_os("TPI_TABLE").is_none() {
        return;
    }
    println!(
        "{:<16} {:<14} {:>6} {:>8} {:>6} {:>8} {:>6} {:>6} {:>8}",
        "surface", "pattern", "points", "inv(bnd)", "open", "nonsimp", "pairs", "euler", "loops"
    );
    for c in cases {
        let v = &c.validity;
        println!(
            "{:<16} {:<14} {:>6} {:>8} {:>6} {:>8} {:>6} {:>6} {:>8}{}",
            c.surface,
            c.pattern,
            c.points,
            format!("{}({})", v.invalid_facets().len(), c.invalid_at_boundary),
            v.open.len(),
            v.non_simple.len(),
            v.overlapping_pairs.len(),
            v.euler,
            v.boundary_loops,
            if c.flagged_missing > 0 {
                format!("  UNFLAGGED {}", c.flagged_missing)
            } else {
                String::new()
            } + &if c.invalid_far_from_parabolic > 0 {
                format!("  FAR {}", c.invalid_far_from_parabolic)
            } else {
                String::new()
            }
        );
    }
}

/// A roof with a crest along y flowing into flanks: z = 2 cos(0.45 x) + 0.04 y^2, a saddle
/// on the crest (|x| < 3.49), K > 0 on the flanks, parabolic lines at x = +-3.49 between.
fn crest_roof() -> NurbsSurface {
    lifted_net(
        [3, 3],
        &[0.0, 0.0, 0.0, 0.2, 0.35, 0.5, 0.65, 0.8, 1.0, 1.0, 1.0],
        &[0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0],
        |s, t| (-6.0 + 12.0 * s, -4.0 + 8.0 * t),
        |x, y, _, _| 2.0 * (0.45 * x).cos() + 0.04 * y * y,
        None,
    )
}

fn saddles() -> Vec<(&'static str, Box<dyn Surface>)> {
    vec![
        ("hypar", Box::new(hypar())),
        ("skewed-saddle", Box::new(skewed_saddle())),
        ("torus-band", Box::new(torus_band())),
    ]
}

fn table(surfaces: &[(&'static str, Box<dyn Surface>)]) -> Vec<Case> {
    let mut cases = Vec::new();
    for (name, surface) in surfaces {
        for n in [300, 2000] {
            for (pattern_name, pattern) in patterns(n) {
                cases.push(run(name, surface.as_ref(), &pattern_name, &pattern));
            }
        }
    }
    report(&cases);
    cases
}

#[test]
fn saddles_give_valid_meshes_with_exact_planes() {
    let surfaces = saddles();
    for (name, surface) in &surfaces {
        assert!(
            max_gaussian(surface.as_ref()) < 0.0,
            "{name} is not a saddle everywhere"
        );
    }
    for c in &table(&surfaces) {
        let v = &c.validity;
        assert!(
            v.is_disc(),
            "{} / {}: not a disc: {v:?}",
            c.surface,
            c.pattern
        );
        assert_eq!(
            c.flagged_missing, 0,
            "{} / {}: invalid facets not flagged",
            c.surface, c.pattern
        );
        let invalid = v.invalid_facets().len();
        assert_eq!(
            invalid, 0,
            "{} / {}: invalid facets {v:?}",
            c.surface, c.pattern
        );
        // Valid by the independent check: the crate's structural check agrees.
        assert_eq!(c.sanity, Ok(()), "{} / {}", c.surface, c.pattern);
    }
}

/// A bicubic graph z(x, y) over [-hx, hx] x [-hy, hy] (control points lifted at their
/// Greville abscissae, so the NURBS is close to the function, not equal to it).
fn graph_net(hx: f64, hy: f64, z: impl Fn(f64, f64) -> f64) -> NurbsSurface {
    let knots = [
        0.0, 0.0, 0.0, 0.125, 0.25, 0.375, 0.5, 0.625, 0.75, 0.875, 1.0, 1.0, 1.0,
    ];
    lifted_net(
        [3, 3],
        &knots,
        &knots,
        |s, t| (-hx + 2.0 * hx * s, -hy + 2.0 * hy * t),
        |x, y, _, _| z(x, y),
        None,
    )
}

/// Saddles unlike the ones the code was tuned on, with irregular patterns: Scherk's minimal
/// surface, a one-sheet hyperboloid seen as a graph, and a steep twisted hyperbolic
/// paraboloid whose curvature varies a hundredfold; Poisson-disk patterns of several seeds
/// and hex patterns at odd rotations and offsets. Every mesh is a disc with every invalid
/// facet flagged, and no facet of the whole family is invalid with exact planes (before the
/// detour flips of `validity_flips`, 36 facets in 11 of the 24 meshes were; before its pair
/// detours, 3 of 26,000).
#[test]
fn unseen_saddles_with_irregular_patterns() {
    let surfaces: Vec<(&'static str, NurbsSurface)> = vec![
        (
            "scherk",
            graph_net(1.2, 1.8, |x, y| {
                let s = 1.1 / 1.8;
                ((s * y).cos() / (s * x).cos()).ln() / s
            }),
        ),
        (
            "hyperboloid",
            graph_net(1.7, 1.5, |x, y| {
                (1.0 + (x / 1.7 * 1.5).powi(2) - (y / 1.5 * 0.7).powi(2)).sqrt() * 1.5
            }),
        ),
        (
            "steep-hypar",
            graph_net(2.7, 1.2, |x, y| 0.76 * x * x - 0.96 * y * y - 0.34 * x * y),
        ),
    ];
    let mut rng = Rng::new(31);
    let mut total_facets = 0;
    let mut total_invalid = 0;
    let mut table = Vec::new();
    for (name, surface) in &surfaces {
        assert!(
            max_gaussian(surface) < 0.0,
            "{name} is not a saddle everywhere"
        );
        let mut cases: Vec<(String, Vec<[f64; 2]>)> = Vec::new();
        for n in [300usize, 2000] {
            for _ in 0..2 {
                let seed = rng.next_u64();
                let r = (0.7 / n as f64).sqrt();
                cases.push((
                    format!("poisson{n}#{seed:x}"),
                    Generator::Poisson { radius: r, seed }.generate().uv,
                ));
            }
            for _ in 0..2 {
                let degrees = rng.range(0.0, 180.0);
                let offset = [rng.f64(), rng.f64()];
                cases.push((
                    format!("hex{n}@{degrees:.0}"),
                    offset_hex(n, degrees, offset),
                ));
            }
        }
        for (pattern_name, pattern) in &cases {
            let c = run(name, surface, pattern_name, pattern);
            assert!(c.validity.is_disc(), "{name} / {pattern_name}: not a disc");
            assert_eq!(c.flagged_missing, 0, "{name} / {pattern_name}: unflagged");
            total_facets += c.points;
            total_invalid += c.validity.invalid_facets().len();
            table.push(c);
        }
    }
    report(&table);
    assert_eq!(
        total_invalid, 0,
        "{total_invalid} invalid facets of {total_facets}"
    );
}

/// [`rotated_hex`] with the lattice shifted by `offset` (in lattice spacings).
fn offset_hex(n: usize, degrees: f64, offset: [f64; 2]) -> Vec<[f64; 2]> {
    let shift = [offset[0] - 0.25, offset[1] - 0.2];
    let h = (2.0 / (3f64.sqrt() * n as f64)).sqrt();
    let (s, c) = degrees.to_radians().sin_cos();
    let (dx, dy) = (shift[0] * h, shift[1] * h);
    rotated_hex(n, degrees)
        .into_iter()
        .map(|[u, v]| [u + c * dx - s * dy, v + s * dx + c * dy])
        .filter(|p| p.iter().all(|x| (0.0..=1.0).contains(x)))
        .collect()
}

/// The hyperbolic paraboloid turned by 45 degrees has its rulings (asymptotic lines) along
/// the sides of its domain and along the rows of a square grid: tangent planes of seeds on a
/// ruling meet on the ruling itself. Known gap: a few facets stay invalid there; the mesh is
/// a disc and every invalid facet is flagged.
#[test]
fn ruled_boundaries_give_discs_with_every_invalid_facet_flagged() {
    let surfaces: Vec<(&'static str, Box<dyn Surface>)> =
        vec![("rotated-hypar", Box::new(rotated_hypar()))];
    for c in &table(&surfaces) {
        let v = &c.validity;
        assert!(
            v.is_disc(),
            "{} / {}: not a disc: {v:?}",
            c.surface,
            c.pattern
        );
        let invalid = v.invalid_facets().len();
        if c.pattern.starts_with("hex") {
            assert_eq!(
                invalid, 0,
                "{} / {}: invalid facets {v:?}",
                c.surface, c.pattern
            );
        }
        assert!(
            invalid * 33 <= c.points,
            "{} / {}: {invalid} invalid facets",
            c.surface,
            c.pattern
        );
    }
}

#[test]
fn mixed_surfaces_stay_discs_and_flag_every_invalid_facet() {
    let surfaces: Vec<(&'static str, Box<dyn Surface>)> = vec![
        ("mixed-roof", Box::new(sample_surface("mixed-roof.json"))),
        ("crest-roof", Box::new(crest_roof())),
    ];
    for c in &table(&surfaces) {
        let v = &c.validity;
        assert!(
            v.is_disc(),
            "{} / {}: not a disc: {v:?}",
            c.surface,
            c.pattern
        );
        assert_eq!(
            c.flagged_missing, 0,
            "{} / {}: invalid facets not flagged",
            c.surface, c.pattern
        );
        // Invalid facets sit mostly at parabolic lines (within 4 spacings). Known gap: where a
        // pattern row runs close to an asymptotic direction of a saddle region (the crest
        // with hex@45), a cluster of up to 1.5 % of the facets stays invalid.
        assert!(
            c.invalid_far_from_parabolic * 66 <= c.points,
            "{} / {}: {} invalid facets far from parabolic lines",
            c.surface,
            c.pattern,
            c.invalid_far_from_parabolic
        );
    }
}

/// The first row of facets along a side of a saddle region of a mixed surface, far from any
/// parabolic line: on the seeded mixed surface 11 with a hex pattern of 2000 points, the
/// |II| metric shears the rows so that each first-row seed keeps one real neighbour, its facet
/// closed by ghost planes and ending in a spike a spacing deep into the region; the spike's
/// vertex (a vertex of that facet alone) stayed inside, and the facet's edge with its real
/// neighbour crossed the spike (five non-simple facets). Interior vertices that ran away
/// near a parabolic line, feet beyond the wall, also cut holes in the clip, and the whole
/// mesh fell back to its closed facets. By the independent check: a disc, every invalid facet
/// flagged, and none farther than two spacings from a parabolic line.
#[test]
fn the_first_row_along_a_saddle_side_of_a_mixed_surface_is_valid() {
    let surface = mixed_surface(11);
    let pattern = rotated_hex(2000, 0.0);
    let d = discretise(&surface, &pattern, &DiscretiseOptions::default()).expect("mixed11");
    let v = check(&d);
    assert!(v.is_disc(), "not a disc: {v:?}");
    let spacing = 1.0 / (pattern.len() as f64).sqrt();
    let far: Vec<usize> = v
        .invalid_facets()
        .into_iter()
        .filter(|&i| !near_parabolic_line(&surface, pattern[i], 2.0 * spacing))
        .collect();
    assert!(
        far.is_empty(),
        "invalid facets far from parabolic lines: {far:?}"
    );
    let unflagged: Vec<usize> = v
        .invalid_facets()
        .into_iter()
        .filter(|&i| d.facet_flags[i] & (FLAG_NON_SIMPLE | FLAG_OVERLAP) == 0)
        .collect();
    assert!(
        unflagged.is_empty(),
        "invalid facets not flagged: {unflagged:?}"
    );
}

/// A seed a small fraction of a spacing from a corner of a mixed surface: its ghosts across
/// both sides stand closer to it than any real seed, and in the |II| metric the flips once
/// took every real neighbour from it, leaving its facet closed by ghost planes alone, a panel
/// apart from the mesh (Euler characteristic 2, two boundary loops). Every seed must share an
/// edge with another facet, and the mesh must be a disc, by the independent topology.
#[test]
fn a_seed_at_a_corner_of_a_mixed_surface_stays_joined_to_the_mesh() {
    let corners = [
        [0.0014, 0.0054],
        [0.9986, 0.0041],
        [0.9981, 0.9960],
        [0.0033, 0.9974],
    ];
    let exact = DiscretiseOptions::default();
    // The adjusted planes flip edges too, from the same structure.
    let adjusted = DiscretiseOptions {
        planes: PlaneMode::Adjusted,
        ..DiscretiseOptions::default()
    };
    for seed in [7, 1, 2, 3] {
        let surface = mixed_surface(seed);
        for (degrees, options) in [(0.0, &exact), (30.0, &exact), (0.0, &adjusted)] {
            let mut pattern = rotated_hex(300, degrees);
            // The hex pattern's own points near the corners give way to the corner seeds.
            pattern.retain(|p| {
                corners
                    .iter()
                    .all(|c| (p[0] - c[0]).hypot(p[1] - c[1]) > 0.03)
            });
            pattern.extend_from_slice(&corners);
            let d = discretise(&surface, &pattern, options).expect("a mixed surface");
            let v = check(&d);
            let name = format!(
                "mixed{seed} hex300@{degrees} with corner seeds, {:?} planes",
                options.planes
            );
            assert!(v.is_disc(), "{name}: not a disc: {v:?}");
            let t = topology(&d);
            for i in 0..d.facet_count() {
                assert!(
                    !t.neighbours[i].is_empty(),
                    "{name}: facet {i} (seed {:?}) shares no edge with another facet",
                    d.seeds[i].uv
                );
            }
        }
    }
}

/// An egg crate (bumps, dips and saddles packed closely, parabolic lines everywhere): every
/// invalid facet is flagged and the mesh is a disc. Where three tangent planes share a
/// direction exactly (the crate's symmetry: on the line x = 0 every normal lies in the
/// xz-plane) their vertex is unreachable; the validity flips turn that triangle's edge
/// (`State::flip_unreachable`), since a stand-in vertex per facet edge would cut a hole (as it
/// did, named by a diagnostic, before). One exception is exact: with the grid symmetric about
/// x = 0, five tangent planes pass through one point and the facet of the middle one has no
/// area; it is flagged open. Collapsed to one vertex, its loop is an extra boundary loop;
/// collapsed to two (the grid of 2,025 points since runaway triangles are flipped away by
/// local spacings), its two-gon adds one to the Euler characteristic. Either is exact: the
/// mesh less such facets is a disc.
#[test]
fn egg_crate_flags_every_invalid_facet_and_stays_a_disc() {
    let crate_surface = AnalyticSurface::new(
        AnalyticKind::EggCrate { amplitude: 0.6 },
        [-3.0, 3.0],
        [-3.0, 3.0],
    )
    .unwrap();
    for n in [300, 2000] {
        for (pattern_name, pattern) in patterns(n) {
            let d = discretise(&crate_surface, &pattern, &DiscretiseOptions::default()).unwrap();
            let v = check(&d);
            assert!(
                v.unflagged(&d).is_empty(),
                "egg crate / {pattern_name}: invalid facets not flagged: {:?}",
                v.unflagged(&d)
            );
            // The exception: facets collapsed to one vertex, each a one-vertex loop (a
            // boundary loop and its self-edge's topology problems of its own), or to two, each
            // a face on an edge its neighbours share (Euler characteristic one more).
            let collapsed = |k: usize| v.open.iter().filter(|&&i| d.facet(i).len() == k).count();
            let (points, two_gons) = (collapsed(1), collapsed(2));
            let only_collapsed = points + two_gons == v.open.len();
            assert!(
                v.is_disc()
                    || (only_collapsed
                        && v.euler == 1 + two_gons as i64
                        && v.boundary_loops == 1 + points),
                "egg crate / {pattern_name}: not a disc: {v:?}"
            );
        }
    }
}

/// A hex pattern of about `n` points laid symmetrically about the line u = 1/2 (a column of
/// points on it in every other row).
fn symmetric_hex(n: usize) -> Vec<[f64; 2]> {
    let h = (2.0 / (3f64.sqrt() * n as f64)).sqrt();
    let row = h * 0.75f64.sqrt();
    let mut out = Vec::new();
    let mut r = 0;
    while (r as f64 + 0.5) * row < 1.0 {
        let v = (r as f64 + 0.5) * row;
        let shift = if r % 2 == 0 { 0.0 } else { 0.5 * h };
        let columns = (0.5 / h).ceil() as i64 + 1;
        for q in -columns..=columns {
            let u = 0.5 + q as f64 * h + shift;
            if u > 0.0 && u < 1.0 {
                out.push([u, v]);
            }
        }
        r += 1;
    }
    out
}

/// A wave roof z = 1.2 sin(x/2) - 0.04 y^2: an inflection across its parabolic line x = 0,
/// where the tangent planes of seeds mirrored about the line are exactly parallel (f_x is
/// even in x). With a hex pattern symmetric about the line, such two seeds were neighbours,
/// their shared vertex unreachable, and the stand-ins left a hole of eight vertices (Euler
/// characteristic 0, two boundary loops); now a disc with every invalid facet flagged.
#[test]
fn parallel_tangent_planes_across_a_parabolic_line_leave_no_hole() {
    let wave = saddles::height_field(8.0, 5.0, 0.0, |x, y| {
        let (s, c) = (0.5 * x).sin_cos();
        [
            1.2 * s - 0.04 * y * y,
            0.6 * c,
            -0.08 * y,
            -0.3 * s,
            0.0,
            -0.08,
        ]
    });
    for n in [500, 2000] {
        let pattern = symmetric_hex(n);
        let d = discretise(&wave, &pattern, &DiscretiseOptions::default()).unwrap();
        let v = check(&d);
        assert!(v.is_disc(), "wave / symmetric hex {n}: not a disc: {v:?}");
        assert!(
            v.unflagged(&d).is_empty(),
            "wave / symmetric hex {n}: invalid facets not flagged: {:?}",
            v.unflagged(&d)
        );
        // The mirrored pair's vertex: no facet may hold a non-finite vertex.
        assert!(d.vertices.iter().all(|x| x.is_finite()));
    }
}

/// Uniform random points (close pairs included) cannot always give valid facets with exact
/// planes, but the mesh is always a disc and every invalid facet is flagged; so with points
/// on the domain's sides and corners.
#[test]
fn random_patterns_give_discs_on_any_curvature() {
    let mut surfaces = saddles();
    surfaces.push(("rotated-hypar", Box::new(rotated_hypar())));
    surfaces.push(("mixed-roof", Box::new(sample_surface("mixed-roof.json"))));
    surfaces.push(("crest-roof", Box::new(crest_roof())));
    let mut rng = Rng::new(2026);
    // Points on the sides and corners too: a 12 x 12 grid of the closed unit square.
    let closed_grid: Vec<[f64; 2]> = (0..12)
        .flat_map(|i| (0..12).map(move |j| [i as f64 / 11.0, j as f64 / 11.0]))
        .collect();
    for (name, surface) in &surfaces {
        for n in [200, 1000] {
            let pattern = uniform_pattern(&mut rng, n);
            let c = run(name, surface.as_ref(), &format!("random{n}"), &pattern);
            assert!(
                c.validity.is_disc(),
                "{name} / random{n}: not a disc: {:?}",
                c.validity
            );
            assert_eq!(
                c.flagged_missing, 0,
                "{name} / random{n}: invalid facets not flagged"
            );
        }
        let c = run(name, surface.as_ref(), "closed-grid", &closed_grid);
        assert!(
            c.validity.is_disc(),
            "{name} / closed grid: not a disc: {:?}",
            c.validity
        );
        assert_eq!(
            c.flagged_missing, 0,
            "{name} / closed grid: invalid facets not flagged"
        );
    }
}

/// The plane of facet i measured from its vertices alone: Newell's normal (oriented like the
/// seed's normal), the largest distance of a vertex from the plane through their centroid,
/// and the distance of the seed's surface point from that plane.
fn measured_plane(d: &Discretisation, i: usize) -> (DVec3, f64, f64) {
    let points: Vec<DVec3> = d.facet(i).iter().map(|&v| d.vertices[v as usize]).collect();
    let centroid = points.iter().copied().sum::<DVec3>() / points.len() as f64;
    let mut normal = DVec3::ZERO;
    for k in 0..points.len() {
        let (a, b) = (
            points[k] - centroid,
            points[(k + 1) % points.len()] - centroid,
        );
        normal += a.cross(b);
    }
    let mut normal = normal.normalize();
    if normal.dot(d.seeds[i].normal) < 0.0 {
        normal = -normal;
    }
    let flatness = points
        .iter()
        .map(|p| (*p - centroid).dot(normal).abs())
        .fold(0.0, f64::max);
    (
        normal,
        flatness,
        (d.seeds[i].point - centroid).dot(normal).abs(),
    )
}

/// Adjusted planes (`PlaneMode::Adjusted`) on saddles, ruled sides, mixed surfaces and
/// uniform random patterns: a disc, and every facet exactly planar in a plane through its
/// seed tilted by at most 5 degrees from the tangent plane, all measured from the mesh's
/// vertices, not taken from the result's fields. On saddles (K < 0 everywhere) every facet
/// is valid by the independent check, and so on the mixed surfaces (the mixed roof and the
/// crest roof, where exact planes leave 1-4 % of the facets invalid).
#[test]
fn adjusted_planes_give_valid_meshes_on_any_curvature() {
    // The adjustment pulls vertices to within 2.5 mean neighbour distances of their seeds;
    // the check here is looser (its spacing is measured on the final mesh's neighbours).
    const MAX_REACH_SEEN: f64 = 3.0;
    let options = DiscretiseOptions {
        planes: PlaneMode::Adjusted,
        ..DiscretiseOptions::default()
    };
    let mut surfaces = saddles();
    surfaces.push(("rotated-hypar", Box::new(rotated_hypar())));
    surfaces.push(("mixed-roof", Box::new(sample_surface("mixed-roof.json"))));
    surfaces.push(("crest-roof", Box::new(crest_roof())));
    let mut rng = Rng::new(2027);
    let mut cases = Vec::new();
    let mut tilts = Vec::new();
    let mut failures = Vec::new();
    let mut offsets = Vec::new();
    for (name, surface) in &surfaces {
        let mut all = patterns(300);
        all.extend(patterns(2000));
        all.push(("random1000".into(), uniform_pattern(&mut rng, 1000)));
        for (pattern_name, pattern) in all {
            let (case, d) = run_with(name, surface.as_ref(), &pattern_name, &pattern, &options);
            let v = &case.validity;
            let what = format!("{name} / {pattern_name}");
            // Validity is collected (the whole table is worth seeing when a case fails).
            if !v.is_disc()
                || !v.invalid_facets().is_empty()
                || case.flagged_missing > 0
                || (v.invalid_facets().is_empty() && case.sanity.is_err())
            {
                failures.push(format!(
                    "{what}: {v:?} {:?}; neighbours {:?}",
                    case.sanity,
                    d.quality.as_ref().map(|q| q.neighbours)
                ));
            }
            assert_eq!(d.plane_adjustments.len(), d.facet_count(), "{what}");
            let diagonal = seed_diagonal(&d);
            // Runaway vertices are pulled in too: each vertex within a few local spacings
            // (mean distance to the neighbouring seeds) of its seed.
            let mut spacing = vec![(0.0, 0usize); d.facet_count()];
            for [a, b] in d.neighbour_pairs() {
                let h = d.seeds[a as usize]
                    .point
                    .distance(d.seeds[b as usize].point);
                for x in [a, b] {
                    spacing[x as usize].0 += h;
                    spacing[x as usize].1 += 1;
                }
            }
            let far = (0..d.facet_count())
                .filter(|&i| {
                    let h = spacing[i].0 / spacing[i].1.max(1) as f64;
                    d.facet(i).iter().any(|&v| {
                        d.vertices[v as usize].distance(d.seeds[i].point) > MAX_REACH_SEEN * h
                    })
                })
                .count();
            // Not all: uneven random spacing leaves a few (at most 0.5 %).
            if far * 200 > d.facet_count() {
                failures.push(format!(
                    "{what}: {far} facets reach beyond {MAX_REACH_SEEN} spacings"
                ));
            }
            for i in 0..d.facet_count() {
                let (normal, flatness, seed_distance) = measured_plane(&d, i);
                assert!(flatness <= 1e-9 * diagonal, "{what}: facet {i} not planar");
                let offset = d.plane_adjustments[i].offset;
                assert!(
                    (seed_distance - offset.abs()).abs() <= 1e-9 * diagonal,
                    "{what}: facet {i}'s plane is {seed_distance} from its seed, reported {offset}"
                );
                offsets.push(seed_distance / diagonal);
                let tilt = normal.angle_between(d.seeds[i].normal).to_degrees();
                assert!(
                    tilt <= 5.0 + 1e-4,
                    "{what}: facet {i} tilted {tilt} degrees"
                );
                let reported = d.plane_adjustments[i].tilt_degrees;
                assert!(
                    (tilt - reported).abs() <= 1e-4,
                    "{what}: facet {i} tilted {tilt} degrees, reported {reported}"
                );
                tilts.push(tilt);
            }
            if std::env::var_os("TPI_TABLE").is_some() {
                let tilted = sorted_tilts(&d);
                let exact = check(
                    &discretise(surface.as_ref(), &pattern, &DiscretiseOptions::default()).unwrap(),
                );
                println!(
                    "TILT {name:<14} {pattern_name:<12} {:>5} invalid exact {:>3} adjusted {:>2}  tilted {:>3}  max {:.2}  median {:.2}",
                    d.facet_count(),
                    exact.invalid_facets().len(),
                    v.invalid_facets().len(),
                    tilted.len(),
                    tilted.last().copied().unwrap_or(0.0),
                    tilted.get(tilted.len() / 2).copied().unwrap_or(0.0)
                );
            }
            cases.push(case);
        }
    }
    report(&cases);
    if std::env::var_os("TPI_TABLE").is_some() {
        let tilted: Vec<f64> = tilts.iter().copied().filter(|&t| t > 1e-9).collect();
        println!(
            "tilted {} of {} facets, max {:.2} deg; offset {} facets, max {:.2e} of the diagonal",
            tilted.len(),
            tilts.len(),
            tilted.iter().copied().fold(0.0, f64::max),
            offsets.iter().filter(|&&o| o > 1e-12).count(),
            offsets.iter().copied().fold(0.0, f64::max)
        );
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// Seeded random mixed height fields (`mixed_surface`, the surfaces of the example
/// `mixed_sweep`) where a plane adjustment from the first neighbour decision leaves facets at
/// a parabolic line invalid (mixed0 with 300 uniform random points: one facet of 9 sides;
/// mixed2 with 300 Poisson-disk points: two of 15 sides, tilted 2 and 5 degrees): decided
/// again with another weight of the metric's isotropic term, every facet is valid by the
/// independent check, the mesh a disc, every facet planar and within 5 degrees of its tangent
/// plane (measured from its vertices).
#[test]
fn adjusted_planes_leave_no_invalid_facet_where_a_first_decision_did() {
    let options = DiscretiseOptions {
        planes: PlaneMode::Adjusted,
        ..DiscretiseOptions::default()
    };
    for (seed, wanted) in [(0, "random300"), (2, "poisson300")] {
        let surface: Box<dyn Surface> = if seed == 0 {
            Box::new(sample_surface("mixed-roof.json"))
        } else {
            Box::new(mixed_surface(seed))
        };
        let (_, pattern) = sweep_patterns(300, seed)
            .into_iter()
            .find(|(name, _)| name == wanted)
            .expect("a sweep pattern");
        let what = format!("mixed{seed} / {wanted}");
        let d = discretise(surface.as_ref(), &pattern, &options).expect(&what);
        assert_valid_planar_within_5_degrees(&d, &what);
    }
}

/// A wall flip that leaves a facet cut by the wall into parts (all but the one around the
/// seed left out, a gap beside the wall) is refused: `samples/saddle.json` with 12,697
/// Poisson-disk points (radius 0.007) has no such facet and no invalid one, as without the
/// wall flips (with them, before the refusal, facet 11793 lost a part).
#[test]
fn wall_flips_cut_no_facet_into_parts() {
    let surface = sample_surface("saddle.json");
    let pattern = Generator::Poisson {
        radius: 0.007,
        seed: 0,
    }
    .generate()
    .uv;
    let d = discretise(&surface, &pattern, &DiscretiseOptions::default()).unwrap();
    let cut: Vec<_> = d
        .diagnostics
        .iter()
        .filter(|g| matches!(g, tpi_core::Diagnostic::FacetPartsLeftOut { .. }))
        .collect();
    assert!(cut.is_empty(), "facets cut into parts: {cut:?}");
    let v = check(&d);
    assert!(v.is_disc() && v.invalid_facets().is_empty(), "{v:?}");
}

/// Where a boundary vertex of a saddle mesh stands, by an independent projection: on the
/// boundary's wall (the ruled surface S(b) + t n(b) of the normals along the boundary curve),
/// beyond it, or short of it inside the domain (normalised distance from the boundary).
enum WallPlace {
    OnWall,
    Beyond,
    Inside(f64),
}

fn wall_place(surface: &dyn Surface, x: DVec3, spacing: f64) -> WallPlace {
    let uv = closest_parameters(surface, x, 48);
    let measure = inside_measure(surface, uv);
    if measure > 1e-7 {
        return WallPlace::Inside(measure);
    }
    // The foot is on the boundary: x is on the wall when x - S(foot) runs along the normal.
    let r = x - surface.point_at(uv[0], uv[1]);
    let n = unit_normal(surface, uv[0], uv[1]);
    if (r - n * r.dot(n)).length() <= 1e-6 * spacing {
        WallPlace::OnWall
    } else {
        WallPlace::Beyond
    }
}

/// Issue 10, item 2: saddle meshes end on the boundary's wall as convex ones do, not with
/// boundary facets reaching out beyond it. Every boundary-loop vertex lies on the wall or
/// (where a triangle vertex with a ghost ends a facet first) inside the domain within one
/// seed spacing of the boundary; none beyond the wall; most on it; and every vertex of the
/// mesh lies within a tenth of the spacing of the surface.
#[test]
fn saddle_meshes_end_on_the_wall() {
    let surfaces = saddles();
    for (name, surface) in &surfaces {
        let surface = surface.as_ref();
        for (pattern_name, pattern) in patterns(300) {
            let d = discretise(surface, &pattern, &DiscretiseOptions::default()).unwrap();
            let n = d.facet_count();
            let spacing = seed_diagonal(&d) / (2.0 * n as f64).sqrt();
            let t = topology(&d);
            let (mut on, mut inside) = (0, 0);
            for (v, _) in t.on_boundary.iter().enumerate().filter(|(_, &b)| b) {
                match wall_place(surface, d.vertices[v], spacing) {
                    WallPlace::OnWall => on += 1,
                    WallPlace::Inside(m) => {
                        inside += 1;
                        assert!(
                            m <= 1.0 / (n as f64).sqrt(),
                            "{name} / {pattern_name}: boundary vertex {v} {m} inside"
                        );
                    }
                    WallPlace::Beyond => {
                        panic!("{name} / {pattern_name}: boundary vertex {v} beyond the wall")
                    }
                }
            }
            assert!(
                on > inside,
                "{name} / {pattern_name}: {on} boundary vertices on the wall, {inside} inside"
            );
            for (v, &x) in d.vertices.iter().enumerate() {
                let uv = closest_parameters(surface, x, 48);
                let off = x.distance(surface.point_at(uv[0], uv[1]));
                assert!(
                    off <= 0.1 * spacing,
                    "{name} / {pattern_name}: vertex {v} {off} from the surface (spacing {spacing})"
                );
            }
        }
    }
}

/// Saddles with closed-form derivatives that none of the code's samples resemble
/// (`common::saddles`: an anisotropic turned hyperbolic paraboloid, the inner band of a
/// torus, sectors of a hyperboloid of one sheet and of a catenoid, a helicoid, a skewed saddle
/// whose curvature varies tenfold), with hex patterns at odd rotations, a square grid and
/// Poisson-disk patterns: with exact planes every mesh is a disc without an invalid facet by
/// the independent check. The Poisson cases are those the example `saddle_sweep` found
/// failing before the pair detours of `validity_flips` (1, 2 and 1 invalid facets), and
/// the two it found failing before a second decision of the neighbours (1 each).
#[test]
fn sweep_saddles_give_valid_discs_with_exact_planes() {
    use common::saddles::{
        catenoid, check_derivatives, helicoid, hypar_ab, hyperboloid, skewed_saddle, torus,
    };
    let poisson_seeded = |n: usize, seed: u64| {
        Generator::Poisson {
            radius: (0.7 / n as f64).sqrt(),
            seed,
        }
        .generate()
        .uv
    };
    /// Surface name, surface, pattern name, pattern.
    type SweepCase = (&'static str, Box<dyn Surface>, String, Vec<[f64; 2]>);
    let cases: Vec<SweepCase> = vec![
        (
            "hypar-aniso",
            Box::new(hypar_ab(3.0, 9.0, 6.0, 4.0, 25.0)),
            "poisson1000".into(),
            poisson_seeded(1000, 1007),
        ),
        (
            "torus-inner",
            Box::new(torus(10.0, 3.0, [-50.0, 50.0], [105.0, 255.0])),
            "poisson2000".into(),
            poisson_seeded(2000, 2007),
        ),
        (
            "hyperboloid-sector",
            Box::new(hyperboloid(2.0, 3.0, [-60.0, 160.0], [-0.9, 0.9])),
            "poisson2000".into(),
            poisson_seeded(2000, 2007),
        ),
        (
            "skewed",
            Box::new(skewed_saddle(2)),
            "hex300@47".into(),
            rotated_hex(300, 47.0),
        ),
        (
            "catenoid-sector",
            Box::new(catenoid(2.0, [0.0, 200.0], [-2.5, 2.5])),
            "hex1000@13".into(),
            rotated_hex(1000, 13.0),
        ),
        (
            "helicoid",
            Box::new(helicoid(1.5, [0.0, 240.0], [-3.0, 3.0])),
            "grid400".into(),
            grid(400),
        ),
        // Two the pair detours left with one invalid boundary facet each, valid with a
        // second decision of the neighbours (structure::decide_again).
        (
            "hp-ab-long",
            Box::new(hypar_ab(5.0, 2.5, 10.0, 2.5, 70.0)),
            "poisson1000#0".into(),
            poisson_seeded(1000, 1007),
        ),
        (
            "skew2",
            Box::new(skewed_saddle(2)),
            "poisson1000#1".into(),
            poisson_seeded(1000, 1107),
        ),
    ];
    let mut table = Vec::new();
    for (name, surface, pattern_name, pattern) in &cases {
        let surface = surface.as_ref();
        check_derivatives(name, surface);
        assert!(
            max_gaussian(surface) < 0.0,
            "{name} is not a saddle everywhere"
        );
        let c = run(name, surface, pattern_name, pattern);
        let v = &c.validity;
        assert!(v.is_disc(), "{name} / {pattern_name}: not a disc: {v:?}");
        assert_eq!(
            v.invalid_facets().len(),
            0,
            "{name} / {pattern_name}: invalid facets {v:?}"
        );
        assert_eq!(c.sanity, Ok(()), "{name} / {pattern_name}");
        table.push(c);
    }
    report(&table);
}

/// Where a triangle with a ghost has its vertex inside the region, its two real facets are
/// carried along their common line out to the wall (`facets::extend_to_wall`) instead of
/// ending on the ghost's plane short of it. Measured independently: the distance from the
/// surface's boundary curve to the mesh's edges (edges held by one facet), in spacings, on the
/// 17 analytic saddles with hex (0 and 30 degrees), grid and Poisson patterns of about 400
/// points. Before the extension the mean was 0.0427 and the 90th percentiles of hp-ab-long
/// (hex) and skew1 (grid) 0.125 and 0.146; with it 0.0369, 0.083 and 0.098. The wall flips
/// (`facets::wall_flips`) close notches the extension cannot; refusing those that raise the
/// deviation of the facets they change, cut a corner off or deepen the mesh's edge, the mean
/// is 0.0337, the mean of the 90th percentiles 0.110 to 0.097, those two cases 0.067 and
/// 0.076 (all flips kept: 0.0295, 0.069, 0.009 and 0.043, but the largest deviation of hex
/// meshes on samples/saddle.json doubled).
#[test]
fn saddle_meshes_reach_the_wall() {
    let patterns: Vec<(&str, Vec<[f64; 2]>)> = vec![
        ("hex@0", rotated_hex(400, 0.0)),
        ("hex@30", rotated_hex(400, 30.0)),
        ("grid", grid(400)),
        (
            "poisson",
            Generator::Poisson {
                radius: 0.03,
                seed: 0,
            }
            .generate()
            .uv,
        ),
    ];
    let (mut sum, mut p90_sum, mut count) = (0.0, 0.0, 0);
    for (name, surface) in saddles::saddles() {
        for (pattern, uv) in &patterns {
            let d = discretise(surface.as_ref(), uv, &DiscretiseOptions::default())
                .unwrap_or_else(|e| panic!("{name} {pattern}: {e}"));
            let validity = check(&d);
            assert!(
                validity.is_disc() && validity.invalid_facets().is_empty(),
                "{name} {pattern}: {validity:?}"
            );
            let gaps = boundary_gaps(surface.as_ref(), &d, 300);
            let mean = gaps.iter().sum::<f64>() / gaps.len() as f64;
            let p90 = gaps[gaps.len() * 9 / 10];
            if std::env::var("TPI_TABLE").is_ok() {
                println!("{name:12} {pattern:8} mean {mean:.4} p90 {p90:.3}");
            }
            if matches!(
                (name.as_str(), *pattern),
                ("hp-ab-long", "hex@0") | ("skew1", "grid")
            ) {
                assert!(
                    p90 <= 0.08,
                    "{name} {pattern}: 90 % of the edge within {p90:.3} spacings"
                );
            }
            sum += mean;
            p90_sum += p90;
            count += 1;
        }
    }
    let mean = sum / count as f64;
    assert!(
        mean <= 0.035,
        "mean distance of the mesh's edge from the wall: {mean:.4} spacings"
    );
    let p90 = p90_sum / count as f64;
    assert!(
        p90 <= 0.1,
        "mean 90th percentile of the mesh's edge from the wall: {p90:.4} spacings"
    );
}

/// Two facets that share only a boundary vertex, where the vertex's fan of three facets
/// wraps past a full turn, overlap: the report must flag them, as every facet the
/// independent check finds invalid. A seeded mixed surface unseen by the tuning (mixed21 with
/// the hex pattern turned 30 degrees, exact planes) had such a pair the report left
/// unflagged, since it tested pairs sharing only a vertex where four or more facets meet.
#[test]
fn overlaps_at_a_boundary_vertex_are_flagged() {
    let (seed, wanted) = (21, "hex300@30");
    let (_, pattern) = sweep_patterns(300, seed)
        .into_iter()
        .find(|(name, _)| name == wanted)
        .expect("a sweep pattern");
    let what = format!("mixed{seed} / {wanted}");
    let d = discretise(
        &mixed_surface(seed),
        &pattern,
        &DiscretiseOptions::default(),
    )
    .expect(&what);
    let v = check(&d);
    assert!(v.is_disc(), "{what}: not a disc: {v:?}");
    let unflagged = v.unflagged(&d);
    assert!(
        unflagged.is_empty(),
        "{what}: invalid by the check, not flagged: {unflagged:?} (overlapping pairs {:?})",
        v.overlapping_pairs
    );
}

/// A nearly developable mixed surface (mixed19: a crest whose cross curvature nearly
/// vanishes, K within +-1e-3 over most of it) with a square grid: TPI facets there run
/// several spacings along the rulings, and holding their vertices within `MAX_REACH` left 8
/// facets non-simple after every second decision, with runaway strips 21 model units off the
/// surface. The adjustment again with `FALLBACK_REACH` gives a valid mesh (the independent
/// check), every facet planar and within 5 degrees of its tangent plane, and no vertex
/// farther from the surface than a tenth of the grid's spacing (the deviation measured by
/// projecting each vertex onto the surface, not by the report).
#[test]
fn adjusted_planes_reach_further_on_a_nearly_developable_band() {
    let options = DiscretiseOptions {
        planes: PlaneMode::Adjusted,
        ..DiscretiseOptions::default()
    };
    let surface = mixed_surface(19);
    let (_, pattern) = sweep_patterns(300, 19)
        .into_iter()
        .find(|(name, _)| name == "grid300")
        .expect("a sweep pattern");
    let d = discretise(&surface, &pattern, &options).expect("mixed19 / grid300");
    assert_valid_planar_within_5_degrees(&d, "mixed19 / grid300");
    // The grid's spacing on the surface: the mean distance between seeds of neighbouring
    // facets.
    let pairs = d.neighbour_pairs();
    let spacing = pairs
        .iter()
        .map(|p| {
            d.seeds[p[0] as usize]
                .point
                .distance(d.seeds[p[1] as usize].point)
        })
        .sum::<f64>()
        / pairs.len() as f64;
    let farthest = max_over_used_vertices(&d, |x| {
        let [u, v] = closest_parameters(&surface, x, 12);
        surface.point_at(u, v).distance(x)
    });
    assert!(
        farthest <= 0.1 * spacing,
        "a vertex {farthest} from the surface (spacing {spacing})"
    );
}

/// The mesh is a disc with no invalid facet (the independent check), every facet planar
/// (measured from its vertices) and within 5 degrees of its tangent plane.
fn assert_valid_planar_within_5_degrees(d: &tpi_core::Discretisation, what: &str) {
    let v = check(d);
    assert!(v.is_disc(), "{what}: not a disc: {v:?}");
    assert!(
        v.invalid_facets().is_empty(),
        "{what}: invalid facets {:?}",
        v.invalid_facets()
    );
    let diagonal = seed_diagonal(d);
    for i in 0..d.facet_count() {
        let (normal, flatness, _) = measured_plane(d, i);
        assert!(flatness <= 1e-9 * diagonal, "{what}: facet {i} not planar");
        let tilt = normal.angle_between(d.seeds[i].normal).to_degrees();
        assert!(
            tilt <= 5.0 + 1e-4,
            "{what}: facet {i} tilted {tilt} degrees"
        );
    }
}

/// Near a corner a seed's ghosts across both sides stand a fraction of a spacing away, and
/// the Lawson flips in the |II| metric can link two seeds of the top row to ghosts only: on
/// the unseen mixed surface 55 (hex 300, random 300 and 2000, hex 2000 at 30 degrees) their
/// two facets were an island apart from the mesh (Euler characteristic 2, two loops). The
/// flips now keep every real seed linked to the others by real edges
/// (`neighbours::isolates_real_points`): each mesh of the surface is a disc by the
/// independent check, and its report agrees.
#[test]
fn the_flips_cut_no_group_of_seeds_off_the_mesh() {
    for n in [300, 2000] {
        assert_mixed_meshes_are_discs(55, n);
    }
}

/// A boundary pinched at a vertex (two boundary facets touching there only) is two loops by
/// the independent check's walk. On the unseen mixed surfaces 28 (random, 2000 points) and 44
/// (grid, 300 points) the wall clip cut a runaway boundary facet in two and left out the part
/// away from its seed, which pinched the boundary; the report and the facet stage's shape
/// check counted connected boundary edges, so the mesh passed as a disc without a warning.
/// Both now count the pinch (`sanity::BoundaryLoops`): the clip that makes it is declined,
/// and every mesh of both surfaces is a disc whose report agrees with the check.
#[test]
fn the_wall_clip_leaves_no_pinched_boundary_and_the_report_agrees() {
    for (seed, n) in [(28, 2000), (44, 300)] {
        assert_mixed_meshes_are_discs(seed, n);
    }
}

/// Every mesh of the mixed surface `seed` with the sweep's patterns of about `n` points and
/// exact planes: a disc by the independent check, the report's Euler characteristic and
/// boundary loops the check's, and every invalid facet flagged.
fn assert_mixed_meshes_are_discs(seed: u64, n: usize) {
    let surface = mixed_surface(seed);
    for (name, pattern) in sweep_patterns(n, seed) {
        let d = discretise(&surface, &pattern, &DiscretiseOptions::default()).unwrap();
        let v = check(&d);
        assert!(v.is_disc(), "mixed{seed} / {name}: not a disc: {v:?}");
        let q = d.quality.as_ref().expect("a report");
        assert_eq!(
            (q.euler_characteristic, q.boundary_loops),
            (v.euler, v.boundary_loops),
            "mixed{seed} / {name}: the report's topology differs from the check's"
        );
        assert!(
            v.unflagged(&d).is_empty(),
            "mixed{seed} / {name}: invalid facets not flagged: {:?}",
            v.unflagged(&d)
        );
    }
}

/// Where clipping the whole mesh on the wall fails only in places (on these mixed surfaces
/// with adjusted planes: a facet the wall leaves nothing of, standing alone beyond it, which
/// made an island), only the facets to blame and a ring or so of neighbours keep their closed
/// fans: the rest of the mesh's edge stays on the wall. Before, the whole edge kept its
/// closed facets, every boundary vertex beyond the wall. By the independent projection
/// ([`wall_place`]): at most a tenth of the boundary vertices lie beyond the wall; every mesh
/// is a disc with no invalid facet, its planes within 5 degrees.
#[test]
fn a_clip_that_fails_in_places_keeps_the_rest_of_the_edge_on_the_wall() {
    let options = DiscretiseOptions {
        planes: PlaneMode::Adjusted,
        ..DiscretiseOptions::default()
    };
    for (seed, wanted) in [(13, "hex300@0"), (13, "poisson300"), (22, "hex300@72")] {
        let surface = mixed_surface(seed);
        let (_, pattern) = sweep_patterns(300, seed)
            .into_iter()
            .find(|(name, _)| name == wanted)
            .expect("a sweep pattern");
        let what = format!("mixed{seed} / {wanted}");
        let d = discretise(&surface, &pattern, &options).expect(&what);
        assert_valid_planar_within_5_degrees(&d, &what);
        let spacing = seed_diagonal(&d) / (2.0 * d.facet_count() as f64).sqrt();
        let t = topology(&d);
        let (mut beyond, mut total) = (0usize, 0usize);
        for (v, _) in t.on_boundary.iter().enumerate().filter(|(_, &b)| b) {
            total += 1;
            if matches!(
                wall_place(&surface, d.vertices[v], spacing),
                WallPlace::Beyond
            ) {
                beyond += 1;
            }
        }
        eprintln!("{what}: {beyond} of {total} boundary vertices beyond the wall");
        assert!(
            beyond * 10 <= total,
            "{what}: {beyond} of {total} boundary vertices beyond the wall"
        );
    }
}

/// Runaway vertices of nearly parallel planes at the parabolic lines of a mixed surface,
/// exact planes: the validity repairs made them as often as they met them
/// (samples/mixed-roof.json, bounding diagonal 23.1: with hex:30x30 a vertex 22.3 model units
/// off the surface, with random:1500 one 65.7 off). Where a second search that counts facets
/// reaching farther from their seeds than the seeds' diagonal as invalid leaves no more
/// invalid facets and fewer such facets, its mesh is kept. By an independent projection (a
/// parameter grid, then Newton: `closest_parameters`) every vertex lies within a quarter of
/// the diagonal of the surface (2.8 and 4.4 now); by the independent check the mesh is a
/// disc and every invalid facet is flagged.
#[test]
fn runaway_vertices_at_parabolic_lines_are_brought_in_with_exact_planes() {
    for spec in ["hex:30x30", "random:1500"] {
        assert_mixed_roof_within(spec, 0.25);
    }
}

/// With exact planes a facet reaching beyond the whole patch is worth no more than a
/// self-intersecting one: where the search that counts such runaways as invalid leaves fewer
/// facets that are either, its mesh is kept even with a few more invalid facets (all
/// flagged). On the mixed roof with 2,000 uniform random points the other search left a vertex
/// 1,110 units off a roof of diagonal 23.6 (81 invalid facets); now, by an independent
/// projection, every vertex lies within the diagonal (16.2 since runaways are judged by the
/// local spacing, 11.2 before; 79 invalid facets), the mesh is a disc and every invalid
/// facet is flagged.
#[test]
fn runaway_vertices_are_traded_for_flagged_invalid_facets_with_exact_planes() {
    assert_mixed_roof_within("random:2000:seed=3000", 1.0);
}

/// Runaways are judged by the local spacing, not only by the whole roof: on the README's
/// showcase (samples/mixed-roof.json, hex:30x24, exact planes) a sheet of facets ran 15 units
/// (18 local spacings) off the roof while every vertex stayed within its diagonal; now the
/// validity search counts a facet reaching beyond 3 local spacings from its seed as a runaway,
/// and its last pass flips runaway triangles away. By the independent projection every
/// vertex lies within one local spacing of the surface (0.5), the mesh is a disc and every
/// invalid facet is flagged. (Not yet everywhere: hex:40x32 leaves 6.9 spacings, grid:40x40
/// 12.6.)
#[test]
fn the_mixed_roof_showcase_keeps_every_vertex_within_a_local_spacing_with_exact_planes() {
    let surface = sample_surface("mixed-roof.json");
    let pattern = Generator::parse("hex:30x24").unwrap().generate().uv;
    let d = discretise(&surface, &pattern, &DiscretiseOptions::default()).unwrap();
    let farthest = deviation_spacings(&surface, &d)
        .into_iter()
        .fold(0.0, f64::max);
    assert!(farthest <= 1.0, "a vertex {farthest} local spacings off");
    let validity = check(&d);
    assert!(validity.is_disc(), "not a disc: {validity:?}");
    assert_eq!(unflagged_invalid(&d, &validity), 0);
}

/// samples/mixed-roof.json with the pattern `spec` and exact planes: every vertex within
/// `fraction` of the seeds' diagonal of the surface (an independent projection: a parameter
/// grid, then Newton), a disc by the independent check, every invalid facet flagged.
fn assert_mixed_roof_within(spec: &str, fraction: f64) {
    let surface = sample_surface("mixed-roof.json");
    let pattern = Generator::parse(spec).expect(spec).generate().uv;
    let d = discretise(&surface, &pattern, &DiscretiseOptions::default()).expect(spec);
    let diagonal = seed_diagonal(&d);
    let farthest = max_over_used_vertices(&d, |x| {
        let [u, v] = closest_parameters(&surface, x, 64);
        surface.point_at(u, v).distance(x)
    });
    assert!(
        farthest <= fraction * diagonal,
        "{spec}: a vertex {farthest} off the surface (diagonal {diagonal})"
    );
    let validity = check(&d);
    assert!(validity.is_disc(), "{spec}: not a disc: {validity:?}");
    assert_eq!(
        unflagged_invalid(&d, &validity),
        0,
        "{spec}: invalid facets not flagged"
    );
}

/// The facets the independent check finds invalid that the report does not flag as
/// non-simple or overlapping.
fn unflagged_invalid(d: &Discretisation, validity: &Validity) -> usize {
    validity
        .invalid_facets()
        .into_iter()
        .filter(|&i| {
            d.facet_flags
                .get(i)
                .map_or(true, |f| f & (FLAG_NON_SIMPLE | FLAG_OVERLAP) == 0)
        })
        .count()
}
