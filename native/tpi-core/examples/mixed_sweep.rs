//! Sweep of seeded random mixed-curvature surfaces (issue 10): bicubic height fields with a
//! crest, a trough or flank term and a bump, so that each has K > 0, K < 0 and parabolic
//! lines between, independent of the samples the code was tuned on. For each surface and
//! pattern it runs exact and adjusted planes and prints the invalid facets by the test
//! suite's independent check (`tests/common/validity.rs`: own-plane simplicity, overlap along
//! the mean normal, Euler characteristic and boundary loops from the mesh), the tilt figures
//! of the adjusted run and the times.
//!
//! ```sh
//! cargo run --release -p tpi-core --example mixed_sweep -- [SURFACES [FIRST_SEED [SIZES]]]
//! # e.g. 20 surfaces from seed 1, sizes 300 and 2000:
//! cargo run --release -p tpi-core --example mixed_sweep -- 20 1 300,2000
//! ```
//!
//! With `SWEEP_SAVE=DIR` each surface and pattern is also written to DIR/mixedSEED.json and
//! DIR/mixedSEED-PATTERN.json (surface and pattern files for `tpi discretise`); with `SWEEP_PARABOLIC=1` the invalid facets of the exact planes are
//! counted by their distance from the nearest parabolic line (in pattern spacings), and those
//! beyond 2 spacings listed, and so are the facets flagged non-convex (where K > 0 around
//! them the envelope makes facets convex) of both runs; with `SWEEP_EXACT_ONLY=1` the adjusted run is skipped (its
//! columns repeat the exact one). With `SWEEP_DETAIL=1` each facet still invalid after adjustment is listed with its seed,
//! the Gaussian curvature there and the tilts of its plane and its neighbours'. The last two
//! columns are the exact and adjusted meshes' largest vertex deviation in pattern spacings.
#![allow(
    dead_code,
    clippy::needless_range_loop,
    clippy::neg_cmp_op_on_partial_ord
)]

#[path = "../tests/common/mod.rs"]
mod common;

use std::time::Instant;

use common::validity::check;
use common::*;
use tpi_core::{discretise, DiscretiseOptions, PlaneMode, Surface, FLAG_NON_CONVEX, INVALID_FLAGS};

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let surfaces: u64 = args.first().and_then(|a| a.parse().ok()).unwrap_or(10);
    let first: u64 = args.get(1).and_then(|a| a.parse().ok()).unwrap_or(1);
    let sizes: Vec<usize> = args
        .get(2)
        .map(|a| a.split(',').filter_map(|x| x.parse().ok()).collect())
        .unwrap_or_else(|| vec![300, 2000]);
    let only: Option<String> = args.get(3).cloned();
    let detail = std::env::var_os("SWEEP_DETAIL").is_some();
    let parabolic = std::env::var_os("SWEEP_PARABOLIC").is_some();
    let exact_only = std::env::var_os("SWEEP_EXACT_ONLY").is_some();
    let bands = [0.5, 1.0, 1.5, 2.0, 3.0, 4.0];
    let mut histogram = [0usize; 7];
    // Facets flagged non-convex (K > 0 around them, the envelope's region), exact and
    // adjusted, by the same bands.
    let mut non_convex = [[0usize; 7]; 2];
    let adjusted = DiscretiseOptions {
        planes: PlaneMode::Adjusted,
        ..DiscretiseOptions::default()
    };
    println!(
        "{:<8} {:<12} {:>6} {:>6} {:>6} {:>5} {:>6} {:>6} {:>7} {:>7} {:>7} {:>7}",
        "surface",
        "pattern",
        "facets",
        "exact",
        "adjust",
        "disc",
        "max",
        "median",
        "t_ex",
        "t_adj",
        "far_ex",
        "far_adj"
    );
    let (mut total_exact, mut total_adjusted, mut time_adjusted) = (0, 0, 0.0);
    let mut total_unflagged = 0;
    for seed in first..first + surfaces {
        // Seed 0 is the sample roof of samples/mixed-roof.json.
        let surface: Box<dyn Surface> = if seed == 0 {
            Box::new(sample_surface("mixed-roof.json"))
        } else {
            Box::new(mixed_surface(seed))
        };
        if let (Some(dir), true) = (std::env::var_os("SWEEP_SAVE"), seed > 0) {
            // The surface as a surface file (docs/formats.md), for the CLI.
            let spec = mixed_surface(seed).to_spec();
            let mut json = serde_json::to_value(&spec).expect("a NURBS record");
            json["type"] = "nurbs".into();
            let path = std::path::Path::new(&dir).join(format!("mixed{seed}.json"));
            std::fs::write(&path, json.to_string()).expect("writable SWEEP_SAVE");
        }
        let surface = surface.as_ref();
        for &n in &sizes {
            for (name, pattern) in sweep_patterns(n, seed) {
                if only.as_ref().is_some_and(|o| !name.starts_with(o.as_str())) {
                    continue;
                }
                if let Some(dir) = std::env::var_os("SWEEP_SAVE") {
                    let path = std::path::Path::new(&dir).join(format!("mixed{seed}-{name}.json"));
                    let json = serde_json::json!({ "uv": pattern });
                    std::fs::write(&path, json.to_string()).expect("writable SWEEP_SAVE");
                }
                let start = Instant::now();
                let exact = discretise(surface, &pattern, &DiscretiseOptions::default())
                    .expect("exact planes");
                let t_exact = start.elapsed().as_secs_f64();
                let start = Instant::now();
                let d = if exact_only {
                    exact.clone()
                } else {
                    discretise(surface, &pattern, &adjusted).expect("adjusted planes")
                };
                let t_adjusted = start.elapsed().as_secs_f64();
                let v_exact = check(&exact);
                let v = check(&d);
                let tilted = sorted_tilts(&d);
                let invalid = v.invalid_facets();
                total_exact += v_exact.invalid_facets().len();
                // Every facet the independent check finds invalid must be flagged.
                let unflagged: Vec<usize> = v_exact
                    .invalid_facets()
                    .into_iter()
                    .filter(|&i| exact.facet_flags[i] & INVALID_FLAGS == 0)
                    .chain(
                        invalid
                            .iter()
                            .copied()
                            .filter(|&i| !exact_only && d.facet_flags[i] & INVALID_FLAGS == 0),
                    )
                    .collect();
                if !unflagged.is_empty() {
                    println!("    UNFLAGGED invalid facets: {unflagged:?}");
                }
                total_unflagged += unflagged.len();
                if parabolic {
                    let spacing = 1.0 / (n as f64).sqrt();
                    for (k, mesh) in [&exact, &d].into_iter().enumerate() {
                        for i in 0..mesh.facet_count() {
                            if mesh.facet_flags[i] & FLAG_NON_CONVEX != 0 {
                                let r = parabolic_distance(surface, pattern[i], spacing);
                                let band = bands.iter().position(|&b| r <= b);
                                non_convex[k][band.unwrap_or(bands.len())] += 1;
                            }
                        }
                    }
                    for i in v_exact.invalid_facets() {
                        let r = parabolic_distance(surface, pattern[i], spacing);
                        let band = bands.iter().position(|&b| r <= b).unwrap_or(bands.len());
                        histogram[band] += 1;
                        if r > 2.0 {
                            let [s, t] = pattern[i];
                            let (gauss, _) = gaussian_and_mean(surface, s, t);
                            println!(
                                "    far: {name} facet {i} at ({s:.4}, {t:.4}) K {gauss:+.2e}: \
                                 {r:.2} spacings, sides {}, non-simple {}, boundary {}",
                                exact.facet(i).len(),
                                v_exact.non_simple.contains(&i),
                                touches_boundary(&exact, i)
                            );
                        }
                    }
                }
                total_adjusted += invalid.len();
                time_adjusted += t_adjusted;
                println!(
                    "mixed{seed:<3} {name:<12} {:>6} {:>6} {:>6} {:>5} {:>6.2} {:>6.2} {:>7.3} {:>7.3} {:>7.2} {:>7.2}",
                    d.facet_count(),
                    v_exact.invalid_facets().len(),
                    invalid.len(),
                    if v.is_disc() { "yes" } else { "NO" },
                    tilted.last().copied().unwrap_or(0.0),
                    tilted.get(tilted.len() / 2).copied().unwrap_or(0.0),
                    t_exact,
                    t_adjusted,
                    far_spacings(&exact),
                    far_spacings(&d)
                );
                if detail {
                    for &i in &invalid {
                        let [s, t] = pattern[i];
                        let (gauss, mean) = gaussian_and_mean(surface, s, t);
                        // Exact planes (SWEEP_EXACT_ONLY) have no adjustments: tilt 0.
                        let tilt =
                            |j: usize| d.plane_adjustments.get(j).map_or(0.0, |a| a.tilt_degrees);
                        let ring: Vec<String> = d
                            .neighbour_pairs()
                            .into_iter()
                            .filter(|p| p[0] as usize == i || p[1] as usize == i)
                            .map(|p| {
                                let j = if p[0] as usize == i { p[1] } else { p[0] } as usize;
                                format!("{j}:{:.2}", tilt(j))
                            })
                            .collect();
                        println!(
                            "    facet {i} at ({s:.3}, {t:.3}) K {gauss:+.2e} H {mean:+.2e} \
                             tilt {:.2} sides {} open {} nonsimple {} ring {}",
                            tilt(i),
                            d.facet(i).len(),
                            v.open.contains(&i),
                            v.non_simple.contains(&i),
                            ring.join(" ")
                        );
                    }
                }
            }
        }
    }
    if parabolic {
        println!("exact planes' invalid facets by distance from a parabolic line (spacings): <= {bands:?}, beyond: {histogram:?}");
        println!(
            "facets flagged non-convex by the same bands: exact {:?}, adjusted {:?}",
            non_convex[0], non_convex[1]
        );
    }
    println!(
        "total invalid exact {total_exact}, adjusted {total_adjusted}; adjusted time {time_adjusted:.2} s; \
         invalid by the check but not flagged by the report: {total_unflagged}"
    );
}

/// The report's largest vertex deviation in pattern spacings: the seeds' bounding-box
/// diagonal over the square root of the facet count, one global spacing (the report's
/// `max_deviation_spacings` divides by each facet's local one instead).
fn far_spacings(d: &tpi_core::Discretisation) -> f64 {
    let Some(q) = &d.quality else {
        return f64::NAN;
    };
    q.max_deviation / (q.bounding_box_diagonal / (q.facet_count.max(1) as f64).sqrt())
}

/// Distance (in pattern spacings, normalised parameters) from `st` to the nearest place where
/// the Gaussian curvature changes sign against its value at `st`, searched on rings of 24
/// points every quarter spacing up to 8 spacings (infinity beyond).
fn parabolic_distance(surface: &dyn Surface, st: [f64; 2], spacing: f64) -> f64 {
    let dom = surface.domain();
    let k = |s: f64, t: f64| {
        let [u, v] = dom.from_normalised([s.clamp(0.0, 1.0), t.clamp(0.0, 1.0)]);
        gaussian_and_mean(surface, u, v).0
    };
    let centre = k(st[0], st[1]);
    for r in 1..=32 {
        let radius = spacing * r as f64 / 4.0;
        let hit = (0..24).any(|a| {
            let angle = a as f64 * std::f64::consts::TAU / 24.0;
            k(st[0] + radius * angle.cos(), st[1] + radius * angle.sin()) * centre <= 0.0
        });
        if hit {
            return r as f64 / 4.0;
        }
    }
    f64::INFINITY
}
