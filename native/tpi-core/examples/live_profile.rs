//! Where the time of one drag goes on a live surface (issue 13, item 4): the edit, the
//! changes since the last edit ([`LiveSurface::take_changes`], what a host redraws) and the
//! assembly of the whole mesh ([`LiveSurface::discretisation`], what a host that copies the
//! whole mesh pays). The surface and drags are those of the .NET display benchmark
//! (`DisplayUpdateBenchmark`): the Bezier dome, hex:NxN, random points moved 0.2 spacings
//! along s.
//!
//! ```sh
//! cargo run --release -p tpi-core --example live_profile -- 100 316
//! ```

use std::time::Instant;

use glam::DVec3;
use tpi_core::{DiscretiseOptions, Generator, LiveSurface, NurbsSurface, SplitMix64};

/// Drags per size and report setting.
const DRAGS: usize = 41;

/// The bicubic Bezier dome of the .NET tests: z = 1.5 (u (1 - u) + v (1 - v)) over [-1, 1]^2.
fn dome() -> NurbsSurface {
    let c = [0.0, 1.0, 1.0, 0.0];
    let mut points = Vec::new();
    for (i, ci) in c.iter().enumerate() {
        for (j, cj) in c.iter().enumerate() {
            let (x, y) = (-1.0 + 2.0 * i as f64 / 3.0, -1.0 + 2.0 * j as f64 / 3.0);
            points.push(DVec3::new(x, y, 0.5 * (ci + cj)));
        }
    }
    let knots = [0.0, 0.0, 0.0, 1.0, 1.0, 1.0];
    NurbsSurface::new([3, 3], [4, 4], &knots, &knots, &points, None).expect("a valid dome")
}

/// The median (and the largest) of a list of milliseconds.
fn median_max(mut times: Vec<f64>) -> (f64, f64) {
    times.sort_by(f64::total_cmp);
    (times[times.len() / 2], times[times.len() - 1])
}

fn main() {
    let sides: Vec<usize> = std::env::args()
        .skip(1)
        .map(|a| a.parse().expect("a hex side, e.g. 100"))
        .collect();
    let sides = if sides.is_empty() { vec![100] } else { sides };
    for side in sides {
        for report in [true, false] {
            let pattern = Generator::parse(&format!("hex:{side}x{side}"))
                .expect("a hex spec")
                .generate()
                .uv;
            let options = DiscretiseOptions {
                quality_report: report,
                ..DiscretiseOptions::default()
            };
            let mut live = LiveSurface::new(Box::new(dome()), pattern, options).expect("new");
            live.take_changes();
            let mut rng = SplitMix64::new(7);
            let (mut edit, mut changes, mut assemble, mut listed) = (vec![], vec![], vec![], 0);
            for _ in 0..DRAGS {
                let i = rng.below(live.points().len());
                let p = live.points()[i];
                let s = (p[0] + 0.2 / side as f64).clamp(0.01, 0.99);
                let start = Instant::now();
                live.move_point(i, [s, p[1]]).expect("a move");
                edit.push(start.elapsed().as_secs_f64() * 1e3);
                let start = Instant::now();
                listed += live.take_changes().facets.len();
                changes.push(start.elapsed().as_secs_f64() * 1e3);
                let start = Instant::now();
                live.discretisation();
                assemble.push(start.elapsed().as_secs_f64() * 1e3);
            }
            let ((e, e_max), (c, c_max), (a, _)) =
                (median_max(edit), median_max(changes), median_max(assemble));
            println!(
                "{} facets, report {}: edit {e:.3} ms (max {e_max:.1}), changes {c:.3} ms \
                 (max {c_max:.1}, {:.1} facets listed on average), whole mesh {a:.2} ms; {:?}",
                side * side,
                if report { "on" } else { "off" },
                listed as f64 / DRAGS as f64,
                live.stats()
            );
        }
    }
}
