//! Issue 15, item 3: hexagonal and square patterns aligned with a direction field. Each
//! pattern is discretised with exact planes and checked by this suite's own means: validity
//! by `common::validity` (own-plane simplicity, overlap along the mean normal by the `geo`
//! library, Euler characteristic and boundary loops from the loops), and alignment by the
//! angle between every interior facet edge, projected into the tangent plane at the facet's
//! seed, and the nearest direction of the field (modulo 60 degrees for hexagons, 90 for
//! squares), the field computed here from the surface's derivatives: principal directions
//! as eigenvectors of the shape operator I^-1 II in parameters (not the crate's frame
//! rotation), asymptotic directions from the principal curvatures, the uv direction mapped
//! by (Su, Sv).
//!
//! `cargo test --release -p tpi-core --test pattern_align -- --nocapture` prints the table.
// Index loops read better in geometry checks.
#![allow(clippy::needless_range_loop)]

mod common;

use std::collections::BTreeMap;

use common::validity::check;
use common::*;
use glam::DVec3;
use tpi_core::{
    aligned_pattern, discretise, AlignField, DirectionField, DiscretiseOptions, Lattice, Surface,
};

/// Principal curvatures k1 <= k2 of s * II (s = `sign`) and their unit 3D directions, from
/// the shape operator in parameters: (II - k I) (du, dv) = 0.
fn principal(surface: &dyn Surface, uv: [f64; 2], sign: f64) -> (f64, f64, DVec3, DVec3, DVec3) {
    let d = surface.evaluate(uv[0], uv[1]);
    let n = d.su.cross(d.sv).normalize();
    let (e, f, g) = (d.su.dot(d.su), d.su.dot(d.sv), d.sv.dot(d.sv));
    let (l, m, nn) = (
        sign * d.suu.dot(n),
        sign * d.suv.dot(n),
        sign * d.svv.dot(n),
    );
    // (EG - F^2) k^2 - (EN + GL - 2FM) k + (LN - M^2) = 0
    let a = e * g - f * f;
    let b = -(e * nn + g * l - 2.0 * f * m);
    let c = l * nn - m * m;
    let disc = (b * b - 4.0 * a * c).max(0.0).sqrt();
    let k1 = (-b - disc) / (2.0 * a);
    let k2 = (-b + disc) / (2.0 * a);
    let direction = |k: f64| {
        // Rows of II - k I; the eigenvector is orthogonal to the longer row.
        let r1 = (l - k * e, m - k * f);
        let r2 = (m - k * f, nn - k * g);
        let (p, q) = if r1.0.hypot(r1.1) >= r2.0.hypot(r2.1) {
            r1
        } else {
            r2
        };
        (d.su * (-q) + d.sv * p).normalize()
    };
    let d1 = direction(k1);
    (k1, k2, d1, direction(k2), n)
}

/// The sign that makes the mean curvature's average over a grid non-negative.
fn orientation(surface: &dyn Surface) -> f64 {
    let dom = surface.domain();
    let mut sum = 0.0;
    for i in 0..=20 {
        for j in 0..=20 {
            let [u, v] = dom.from_normalised([i as f64 / 20.0, j as f64 / 20.0]);
            sum += gaussian_and_mean(surface, u, v).1;
        }
    }
    if sum < 0.0 {
        -1.0
    } else {
        1.0
    }
}

#[derive(Clone, Copy, Debug)]
enum Field {
    Principal,
    Asymptotic,
    Uv(f64),
    /// The direction (cos 45 s, sin 45 s) degrees in normalised parameters, given to the
    /// crate as a direction file sampled on 9 x 9 nodes.
    Turning,
}

/// The `Turning` field's angle (degrees) at normalised s.
fn turning_degrees(s: f64) -> f64 {
    45.0 * s
}

impl Field {
    fn name(self) -> String {
        match self {
            Field::Principal => "principal".into(),
            Field::Asymptotic => "asymptotic".into(),
            Field::Uv(a) => format!("uv:{a}"),
            Field::Turning => "file (turning)".into(),
        }
    }

    fn spec(self) -> AlignField {
        match self {
            Field::Turning => {
                let directions = (0..9)
                    .flat_map(|i| {
                        (0..9).map(move |_| {
                            let (s, c) = turning_degrees(i as f64 / 8.0).to_radians().sin_cos();
                            [c, s]
                        })
                    })
                    .collect();
                AlignField::File(DirectionField {
                    size: [9, 9],
                    directions,
                })
            }
            _ => AlignField::parse(&self.name()).unwrap(),
        }
    }

    /// The field's two candidate unit directions at `uv` (domain parameters) and the unit
    /// normal. A line field of principal (asymptotic) directions has two families, d1 and d2
    /// (the asymptotic directions turned by +alpha and -alpha from d1); a hexagon's edges can
    /// follow either (90 degrees apart is 30 modulo 60), so the measure takes the family that
    /// fits the whole mesh better. The uv fields have one family, given twice.
    fn at(self, surface: &dyn Surface, uv: [f64; 2], sign: f64) -> ([DVec3; 2], DVec3) {
        let (k1, k2, d1, d2, n) = principal(surface, uv, sign);
        match self {
            Field::Principal => ([d1, d2], n),
            Field::Asymptotic => {
                if k1 < 0.0 && k2 > 0.0 {
                    let alpha = (-k1 / k2).sqrt().atan();
                    let (s, c) = alpha.sin_cos();
                    let side = n.cross(d1);
                    ([d1 * c + side * s, d1 * c - side * s], n)
                } else {
                    ([d1, d2], n)
                }
            }
            Field::Uv(_) | Field::Turning => {
                let d = surface.evaluate(uv[0], uv[1]);
                let dom = surface.domain();
                let degrees = match self {
                    Field::Uv(a) => a,
                    _ => turning_degrees(dom.to_normalised(uv)[0]),
                };
                let (s, c) = degrees.to_radians().sin_cos();
                let t = d.su * (c * dom.u.length()) + d.sv * (s * dom.v.length());
                let t = (t - n * t.dot(n)).normalize();
                ([t, t], n)
            }
        }
    }
}

struct Row {
    points: usize,
    invalid: usize,
    disc: bool,
    euler: i64,
    loops: usize,
    weighted_angle: f64,
    mean_angle: f64,
}

/// Discretises `uv` with exact planes and measures validity and alignment independently.
fn measure(surface: &dyn Surface, uv: &[[f64; 2]], lattice: Lattice, field: Field) -> Row {
    let d = discretise(surface, uv, &DiscretiseOptions::default()).unwrap();
    let v = check(&d);
    let sign = orientation(surface);
    let symmetry = match lattice {
        Lattice::Hex => 60.0,
        Lattice::Grid => 90.0,
    };
    // Interior edges: used by two facets.
    let mut uses: BTreeMap<(u32, u32), usize> = BTreeMap::new();
    for i in 0..d.facet_count() {
        let f = d.facet(i);
        for k in 0..f.len() {
            let (a, b) = (f[k], f[(k + 1) % f.len()]);
            if a != b {
                *uses.entry((a.min(b), a.max(b))).or_default() += 1;
            }
        }
    }
    // Per family: (sum of lengths, length-weighted sum of angles, sum of angles, edges).
    let mut sums = [(0.0, 0.0, 0.0, 0usize); 2];
    for i in 0..d.facet_count() {
        let (dirs, n) = field.at(surface, d.seeds[i].uv, sign);
        let f = d.facet(i);
        for k in 0..f.len() {
            let (a, b) = (f[k], f[(k + 1) % f.len()]);
            if a == b || uses.get(&(a.min(b), a.max(b))) != Some(&2) {
                continue;
            }
            let e = d.vertices[b as usize] - d.vertices[a as usize];
            let e = e - n * e.dot(n);
            let len = e.length();
            if !(len > 0.0) {
                continue;
            }
            for (dir, sum) in dirs.iter().zip(&mut sums) {
                let angle = n.dot(dir.cross(e)).atan2(dir.dot(e)).to_degrees();
                let folded = angle.rem_euclid(symmetry);
                let off = folded.min(symmetry - folded);
                sum.0 += len;
                sum.1 += len * off;
                sum.2 += off;
                sum.3 += 1;
            }
        }
    }
    let best = if sums[1].1 * sums[0].0 < sums[0].1 * sums[1].0 {
        sums[1]
    } else {
        sums[0]
    };
    let (sum_w, sum_wa, sum_a, count) = best;
    Row {
        points: uv.len(),
        invalid: v.invalid_facets().len(),
        disc: v.is_disc(),
        euler: v.euler,
        loops: v.boundary_loops,
        weighted_angle: sum_wa / sum_w,
        mean_angle: sum_a / count as f64,
    }
}

fn run(name: &str, surface: &dyn Surface, lattice: Lattice, field: Field, size: usize) -> Row {
    let uv = aligned_pattern(surface, lattice, size, &field.spec()).unwrap();
    let row = measure(surface, &uv, lattice, field);
    println!(
        "{name:16} {:4} {:12} target {size:5}: {:5} points, invalid {:3}, disc {} (Euler {}, \
         {} loops), edge angle to field: length-weighted {:5.2} deg, plain mean {:5.2} deg",
        format!("{lattice:?}").to_lowercase(),
        field.name(),
        row.points,
        row.invalid,
        row.disc,
        row.euler,
        row.loops,
        row.weighted_angle,
        row.mean_angle
    );
    row
}

/// The acceptance: aligned hexagons on the saddle samples are valid with exact planes, and
/// their edges follow the principal field within 5 degrees on average.
#[test]
fn aligned_hexagons_on_saddles_are_valid_and_follow_the_field() {
    for name in ["saddle.json", "torus-band.json", "hypar.json"] {
        let surface = sample_surface(name);
        for size in [300, 1000, 2000] {
            let row = run(name, &surface, Lattice::Hex, Field::Principal, size);
            assert!(
                (size * 7 / 10..=size * 13 / 10).contains(&row.points),
                "{name} {size}: {} points",
                row.points
            );
            assert_eq!(row.invalid, 0, "{name} {size}: invalid facets");
            assert!(row.disc, "{name} {size}: not a disc");
            assert!(
                row.weighted_angle <= 5.0,
                "{name} {size}: mean edge angle {} deg",
                row.weighted_angle
            );
        }
    }
}

/// Every field on both lattices on saddles, domes and a mixed roof (the table of the report);
/// checked: the count follows the target, the pattern is valid as a pattern and the same
/// when generated twice, the mesh is a disc, and on the saddles (K < 0 everywhere) and the
/// domes no facet is invalid. The angles are printed, not checked: only the principal
/// hexagons are held to 5 degrees (the test above).
#[test]
fn aligned_patterns_table() {
    let surfaces = [
        "saddle.json",
        "torus-band.json",
        "hypar.json",
        "nurbs-dome.json",
        "anisotropic-dome.json",
        "mixed-roof.json",
    ];
    let mut problems = Vec::new();
    for name in surfaces {
        let surface = sample_surface(name);
        for lattice in [Lattice::Hex, Lattice::Grid] {
            for field in [
                Field::Principal,
                Field::Asymptotic,
                Field::Uv(30.0),
                Field::Turning,
            ] {
                let size = 800;
                let row = run(name, &surface, lattice, field, size);
                if !row.disc || (name != "mixed-roof.json" && row.invalid > 0) {
                    problems.push(format!(
                        "{name} {lattice:?} {}: {} invalid, disc {}",
                        field.name(),
                        row.invalid,
                        row.disc
                    ));
                }
                if !(size * 7 / 10..=size * 13 / 10).contains(&row.points) {
                    problems.push(format!(
                        "{name} {lattice:?} {}: {} points",
                        field.name(),
                        row.points
                    ));
                }
                let again = aligned_pattern(&surface, lattice, size, &field.spec()).unwrap();
                let first = aligned_pattern(&surface, lattice, size, &field.spec()).unwrap();
                assert_eq!(first, again, "{name}: not deterministic");
                tpi_core::Pattern::new(first).validate().unwrap();
            }
        }
    }
    assert!(problems.is_empty(), "{problems:#?}");
}

/// Bad input gets a typed error, never a panic.
#[test]
fn bad_alignment_input_is_rejected() {
    for bad in [
        "",
        "principle",
        "uv:",
        "uv:abc",
        "uv:NaN",
        "uv:1e9",
        "field:x.json",
    ] {
        assert!(AlignField::parse(bad).is_err(), "{bad:?} accepted");
    }
    let field = |size: [usize; 2], directions: Vec<[f64; 2]>| DirectionField { size, directions };
    assert!(field([1, 2], vec![[1.0, 0.0]; 2]).validate().is_err());
    assert!(field([2, 2], vec![[1.0, 0.0]; 3]).validate().is_err());
    assert!(field([2, 2], vec![[0.0, 0.0]; 4]).validate().is_err());
    assert!(field([2, 2], vec![[f64::NAN, 0.0]; 4]).validate().is_err());
    assert!(field([usize::MAX, 2], vec![]).validate().is_err());
    assert!(DirectionField::from_json("{\"size\": [2, 2]}", "f.json").is_err());
    assert!(DirectionField::from_json(
        "{\"size\": [2, 2], \"directions\": [[1, 0], [1, 0], [0, 1], [0, 1]]}",
        "f.json"
    )
    .is_ok());
    let surface = sample_surface("saddle.json");
    assert!(aligned_pattern(&surface, Lattice::Hex, 0, &AlignField::Principal).is_err());
    let zero = AlignField::File(field([2, 2], vec![[0.0, 0.0]; 4]));
    assert!(aligned_pattern(&surface, Lattice::Hex, 100, &zero).is_err());
}
