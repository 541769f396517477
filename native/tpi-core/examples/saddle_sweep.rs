//! Sweep of saddle surfaces (K < 0 everywhere) that are not the repository's samples (issue
//! 10): hyperbolic paraboloids z = x y / c and z = x^2/a^2 - y^2/b^2 of several aspects,
//! rotations and extents, seeded random skewed saddles with strongly varying curvature (cubic
//! terms, K < 0 checked on a grid), the inner band of a torus, sectors of a catenoid and of a
//! hyperboloid of one sheet, and a helicoid patch, all analytic with their own derivatives.
//!
//! Exact planes with hex patterns at several rotations, square grids and Poisson-disk
//! patterns: invalid facets by the test suite's independent check (`tests/common/validity.rs`:
//! own-plane simplicity, overlap along the mean normal, Euler characteristic and boundary
//! loops from the mesh) and whether the mesh is a disc. Then uniform random patterns with
//! adjusted planes on the same surfaces and on the mixed surfaces of `mixed_sweep`: invalid
//! facets, disc, max and median tilt.
//!
//! ```sh
//! cargo run --release -p tpi-core --example saddle_sweep -- [SIZES [SURFACE [PATTERN]]]
//! # e.g. sizes 300 and 2000, every surface whose name starts with "hp", hex patterns only:
//! cargo run --release -p tpi-core --example saddle_sweep -- 300,2000 hp hex
//! ```
//!
//! `SWEEP_ANGLES=7,22` replaces the hex rotations (degrees); `SWEEP_ADJUST_ALL=1` runs the
//! first part (hex, grid, Poisson) with adjusted planes too. `SWEEP_MIXED=N` sets the number of random mixed surfaces in the adjusted part (default 3,
//! plus the sample roof); with `SWEEP_DETAIL=1` each invalid facet is listed with its seed,
//! whether it touches the boundary and what is wrong with it.
#![allow(
    dead_code,
    clippy::needless_range_loop,
    clippy::neg_cmp_op_on_partial_ord
)]

#[path = "../tests/common/mod.rs"]
mod common;

use std::time::Instant;

use common::saddles::*;
use common::validity::{check, Validity};
use common::*;
use tpi_core::{discretise, Discretisation, DiscretiseOptions, PlaneMode, Surface};

/// The exact-plane patterns at size `n`: hex at several rotations, a grid and Poisson disks.
fn exact_patterns(n: usize, seed: u64) -> Vec<(String, Vec<[f64; 2]>)> {
    // SWEEP_ANGLES=a,b,... replaces the hex rotations (degrees).
    let angles: Vec<f64> = std::env::var("SWEEP_ANGLES")
        .ok()
        .map(|a| a.split(',').filter_map(|x| x.parse().ok()).collect())
        .unwrap_or_else(|| vec![0.0, 13.0, 30.0, 47.0, 60.0]);
    let mut out: Vec<(String, Vec<[f64; 2]>)> = angles
        .iter()
        .map(|&a| (format!("hex{n}@{a}"), rotated_hex(n, a)))
        .collect();
    for (name, pattern) in sweep_patterns(n, seed) {
        if name.starts_with("grid") {
            out.push((name, pattern));
        }
    }
    // Poisson-disk patterns from three seeds: the irregular patterns are where exact planes
    // are hardest.
    for k in 0..3 {
        let uv = tpi_core::Generator::Poisson {
            radius: (0.7 / n as f64).sqrt(),
            seed: seed + 100 * k + n as u64,
        }
        .generate()
        .uv;
        out.push((format!("poisson{n}#{k}"), uv));
    }
    out
}

fn detail(surface: &dyn Surface, pattern: &[[f64; 2]], d: &Discretisation, v: &Validity) {
    if let Some(q) = &d.quality {
        println!(
            "    report: invalid {} validity flips {} unresolved {}, tilts {}",
            q.invalid_facets,
            q.neighbours.validity_flips,
            q.neighbours.validity_unresolved,
            q.neighbours.plane_tilts
        );
    }
    for &i in &v.invalid_facets() {
        let [s, t] = pattern[d.pattern_index(i)];
        let dom = surface.domain();
        let [u, w] = dom.from_normalised([s, t]);
        let (gauss, _) = gaussian_and_mean(surface, u, w);
        let partners: Vec<usize> = v
            .overlapping_pairs
            .iter()
            .filter(|p| p.0 == i || p.1 == i)
            .map(|p| if p.0 == i { p.1 } else { p.0 })
            .collect();
        println!(
            "    facet {i} at ({s:.3}, {t:.3}) K {gauss:+.2e} sides {} boundary {} open {} \
             nonsimple {} overlaps {:?}",
            d.facet(i).len(),
            touches_boundary(d, i),
            v.open.contains(&i),
            v.non_simple.contains(&i),
            partners
        );
        if std::env::var("SWEEP_DETAIL").as_deref() == Ok("2") {
            let seed = &d.seeds[i];
            let (e1, e2) = frame(seed.normal);
            for &x in d.facet(i) {
                let p = d.vertices[x as usize] - seed.point;
                println!(
                    "      v{x:<5} {:?} ({:+.4}, {:+.4}) h {:+.2e}",
                    d.vertex_kinds[x as usize],
                    p.dot(e1),
                    p.dot(e2),
                    p.dot(seed.normal)
                );
            }
        }
    }
}

fn tilts(d: &Discretisation) -> (f64, f64, usize) {
    let tilted = sorted_tilts(d);
    (
        tilted.last().copied().unwrap_or(0.0),
        tilted.get(tilted.len() / 2).copied().unwrap_or(0.0),
        tilted.len(),
    )
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let sizes: Vec<usize> = args
        .first()
        .map(|a| a.split(',').filter_map(|x| x.parse().ok()).collect())
        .unwrap_or_else(|| vec![300, 1000, 2000]);
    let only_surface = args.get(1).cloned().unwrap_or_default();
    let only_pattern = args.get(2).cloned().unwrap_or_default();
    let show = std::env::var_os("SWEEP_DETAIL").is_some();
    let mixed: u64 = std::env::var("SWEEP_MIXED")
        .ok()
        .and_then(|m| m.parse().ok())
        .unwrap_or(3);
    // SWEEP_ADJUST_ALL=1: the first part (hex, grid, Poisson) with adjusted planes too.
    let exact = DiscretiseOptions {
        planes: if std::env::var_os("SWEEP_ADJUST_ALL").is_some() {
            PlaneMode::Adjusted
        } else {
            PlaneMode::Exact
        },
        ..DiscretiseOptions::default()
    };
    let adjusted = DiscretiseOptions {
        planes: PlaneMode::Adjusted,
        ..DiscretiseOptions::default()
    };

    println!(
        "# {} planes",
        if exact.planes == PlaneMode::Adjusted {
            "adjusted"
        } else {
            "exact"
        }
    );
    println!(
        "{:<12} {:<14} {:>6} {:>7} {:>5} {:>7}   K range",
        "surface", "pattern", "facets", "invalid", "disc", "t"
    );
    let (mut cases, mut failing, mut total) = (0, 0, 0);
    let saddles = saddles();
    for (name, surface) in &saddles {
        if !name.starts_with(only_surface.as_str()) {
            continue;
        }
        let surface = surface.as_ref();
        check_derivatives(name, surface);
        let (lo, hi) = gaussian_range(surface, 30);
        assert!(hi < 0.0, "{name}: K up to {hi:e}, not a saddle everywhere");
        for &n in &sizes {
            for (pname, pattern) in exact_patterns(n, 7) {
                if !pname.starts_with(only_pattern.as_str()) || pname.starts_with("random") {
                    continue;
                }
                let start = Instant::now();
                let d = match discretise(surface, &pattern, &exact) {
                    Ok(d) => d,
                    Err(e) => {
                        println!("{name:<12} {pname:<14} error: {e}");
                        failing += 1;
                        continue;
                    }
                };
                let t = start.elapsed().as_secs_f64();
                let v = check(&d);
                let invalid = v.invalid_facets().len();
                cases += 1;
                total += invalid;
                if invalid > 0 || !v.is_disc() {
                    failing += 1;
                }
                println!(
                    "{name:<12} {pname:<14} {:>6} {:>7} {:>5} {t:>7.3}   [{lo:.2e}, {hi:.2e}]{}",
                    d.facet_count(),
                    invalid,
                    if v.is_disc() {
                        "yes".to_string()
                    } else {
                        format!("NO(e{} b{})", v.euler, v.boundary_loops)
                    },
                    if invalid > 0 || !v.is_disc() {
                        "  <--"
                    } else {
                        ""
                    }
                );
                if show {
                    detail(surface, &pattern, &d, &v);
                }
            }
        }
    }
    println!("exact: {cases} cases, {failing} failing, {total} invalid facets in all");

    if only_pattern.is_empty() || only_pattern.starts_with("random") {
        println!("# adjusted planes, random patterns");
        println!(
            "{:<12} {:<14} {:>6} {:>6} {:>6} {:>5} {:>6} {:>6} {:>5} {:>7}",
            "surface",
            "pattern",
            "facets",
            "exact",
            "adjust",
            "disc",
            "max",
            "median",
            "tilted",
            "t_adj"
        );
        let mut surfaces: Vec<(String, Box<dyn Surface>)> = saddles;
        surfaces.push((
            "mixed-roof".into(),
            Box::new(sample_surface("mixed-roof.json")),
        ));
        for seed in 1..=mixed {
            surfaces.push((format!("mixed{seed}"), Box::new(mixed_surface(seed))));
        }
        let (mut cases, mut failing, mut worst_tilt) = (0, 0, 0.0f64);
        for (name, surface) in &surfaces {
            if !name.starts_with(only_surface.as_str()) {
                continue;
            }
            let surface = surface.as_ref();
            for &n in &sizes {
                let pattern = tpi_core::Generator::Random {
                    count: n,
                    seed: 11 + n as u64,
                }
                .generate()
                .uv;
                let pname = format!("random{n}");
                let e = discretise(surface, &pattern, &exact).map(|d| check(&d));
                let start = Instant::now();
                let d = match discretise(surface, &pattern, &adjusted) {
                    Ok(d) => d,
                    Err(e) => {
                        println!("{name:<12} {pname:<14} error: {e}");
                        failing += 1;
                        continue;
                    }
                };
                let t = start.elapsed().as_secs_f64();
                let v = check(&d);
                let (max, median, count) = tilts(&d);
                let invalid = v.invalid_facets().len();
                cases += 1;
                worst_tilt = worst_tilt.max(max);
                if invalid > 0 || !v.is_disc() {
                    failing += 1;
                }
                println!(
                    "{name:<12} {pname:<14} {:>6} {:>6} {:>6} {:>5} {max:>6.2} {median:>6.2} {count:>5} {t:>7.3}{}",
                    d.facet_count(),
                    e.map_or("err".to_string(), |e| e.invalid_facets().len().to_string()),
                    invalid,
                    if v.is_disc() { "yes" } else { "NO" },
                    if invalid > 0 || !v.is_disc() {
                        "  <--"
                    } else {
                        ""
                    }
                );
                if show {
                    detail(surface, &pattern, &d, &v);
                }
            }
        }
        println!("adjusted: {cases} cases, {failing} failing, max tilt {worst_tilt:.2} deg");
    }
}
