//! Pattern generators: syntax, counts, placement, determinism, Poisson-disk distances.

use tpi_core::{Generator, GridSize, Pattern, TpiError};
use tpi_core::{SplitMix64, MAX_GENERATED_POINTS, MIN_POISSON_RADIUS};

fn generate(spec: &str) -> Pattern {
    let g = Generator::parse(spec).unwrap_or_else(|e| panic!("{spec}: {e}"));
    let p = g.generate();
    assert_eq!(p.validate(), Ok(()), "{spec}: generated patterns validate");
    for &[s, t] in &p.uv {
        assert!(
            (0.0..=1.0).contains(&s) && (0.0..=1.0).contains(&t),
            "{spec}: ({s}, {t}) inside"
        );
    }
    if let Some(n) = g.expected_count() {
        assert_eq!(p.len(), n, "{spec}: expected_count");
    }
    p
}

#[test]
fn splitmix64_reference_values() {
    // Reference outputs of SplitMix64 (Vigna's splitmix64.c) from state 0: they pin every
    // generated pattern across platforms and versions.
    let mut r = SplitMix64::new(0);
    assert_eq!(r.next_u64(), 0xE220_A839_7B1D_CDAF);
    assert_eq!(r.next_u64(), 0x6E78_9E6A_A1B9_65F4);
    assert_eq!(r.next_u64(), 0x06C4_5D18_8009_454F);
    let mut r = SplitMix64::new(7);
    for _ in 0..1000 {
        let x = r.next_f64();
        assert!((0.0..1.0).contains(&x));
        assert!(r.below(10) < 10);
    }
    assert_eq!(r.below(0), 0);
}

#[test]
fn generated_points_are_pinned() {
    // A change of any generator's output is a format change for users who stored a spec.
    let p = generate("random:2:seed=0");
    let mut r = SplitMix64::new(0);
    let expected: Vec<[f64; 2]> = (0..2).map(|_| [r.next_f64(), r.next_f64()]).collect();
    assert_eq!(p.uv, expected);
    assert_eq!(
        p.uv[0][0],
        (0xE220_A839_7B1D_CDAFu64 >> 11) as f64 / (1u64 << 53) as f64
    );
}

#[test]
fn square_grid_counts_and_cell_centres() {
    let p = generate("grid:20x15");
    assert_eq!(p.len(), 300);
    // u-major: point (i, j) at index i * 15 + j, at the cell centre.
    assert_eq!(p.uv[0], [0.025, 1.0 / 30.0]);
    assert_eq!(p.uv[15 + 2], [1.5 / 20.0, 2.5 / 15.0]);
    assert_eq!(p.uv[299], [19.5 / 20.0, 14.5 / 15.0]);
    assert!(
        p.uv.iter()
            .all(|&[s, t]| s > 0.0 && s < 1.0 && t > 0.0 && t < 1.0),
        "no point on the border"
    );

    assert_eq!(generate("grid:1x1").uv, vec![[0.5, 0.5]]);
    assert_eq!(generate("grid:spacing=0.05").len(), 400);
    assert_eq!(
        generate("grid:spacing=0.3").len(),
        9,
        "round(1/0.3) = 3 per side"
    );
    assert_eq!(generate("grid:spacing=1").len(), 1);
    assert_eq!(generate("grid:spacing=0.8").len(), 1, "max(1, round(1.25))");
    assert_eq!(generate("grid:spacing=0.05").uv, generate("grid:20x20").uv);
}

#[test]
fn hex_grid_counts_and_offsets() {
    let p = generate("hex:24x20");
    assert_eq!(p.len(), 480);
    // Row j at t = (j + 1/2)/20; even rows start at 1/4 step, odd rows at 3/4 step.
    assert_eq!(p.uv[0], [0.25 / 24.0, 0.5 / 20.0]);
    assert_eq!(p.uv[1], [0.75 / 24.0, 1.5 / 20.0]);
    assert_eq!(p.uv[20], [1.25 / 24.0, 0.5 / 20.0]);
    let row0: Vec<f64> =
        p.uv.iter()
            .filter(|q| q[1] == 0.5 / 20.0)
            .map(|q| q[0])
            .collect();
    let row1: Vec<f64> =
        p.uv.iter()
            .filter(|q| q[1] == 1.5 / 20.0)
            .map(|q| q[0])
            .collect();
    assert_eq!((row0.len(), row1.len()), (24, 24));
    for (a, b) in row0.iter().zip(&row1) {
        assert!(
            (b - a - 0.5 / 24.0).abs() < 1e-15,
            "odd rows shifted by half a step"
        );
    }
    // Spacing D: NU = round(1/D), NV = round(2/(sqrt(3) D)) rows, sqrt(3)/2 of a step apart.
    let d = 0.05;
    let g = Generator::parse("hex:spacing=0.05").unwrap();
    assert_eq!(GridSize::Spacing(d).hex_counts(), (20, 23));
    assert_eq!(g.expected_count(), Some(460));
    let p = generate("hex:spacing=0.05");
    assert_eq!(p.len(), 460);
    let column_step = 1.0 / 20.0;
    let row_step = 1.0 / 23.0;
    assert!(
        (row_step / column_step - 3f64.sqrt() / 2.0).abs() < 0.02,
        "rows about sqrt(3)/2 steps apart"
    );
    // Nearest neighbours of an interior point are (nearly) equidistant: a triangular lattice.
    let c = p.uv[10 * 23 + 11];
    let mut d2: Vec<f64> =
        p.uv.iter()
            .map(|q| (q[0] - c[0]).hypot(q[1] - c[1]))
            .filter(|&x| x > 0.0)
            .collect();
    d2.sort_by(f64::total_cmp);
    assert!(
        d2[5] / d2[0] < 1.02,
        "six nearly equal nearest neighbours: {:?}",
        &d2[..7]
    );
    assert_eq!(generate("hex:1x1").uv, vec![[0.25, 0.5]]);
    assert_eq!(generate("hex:3x2").len(), 6);
}

#[test]
fn jittered_grid_stays_in_its_cells() {
    let grid = generate("grid:20x10");
    let p = generate("jitter:20x10:amount=0.3:seed=7");
    assert_eq!(p.len(), 200);
    for (q, c) in p.uv.iter().zip(&grid.uv) {
        assert!(
            (q[0] - c[0]).abs() <= 0.15 / 20.0 + 1e-15,
            "s offset within amount/2 of the cell"
        );
        assert!(
            (q[1] - c[1]).abs() <= 0.15 / 10.0 + 1e-15,
            "t offset within amount/2 of the cell"
        );
    }
    assert_ne!(p.uv, grid.uv);
    assert_eq!(
        generate("jitter:20x10:amount=0:seed=7").uv,
        grid.uv,
        "amount 0 is the grid"
    );
    // Amount 1 spreads points over whole cells, still one per cell.
    let p = generate("jitter:8x8:amount=1:seed=3");
    for (k, q) in p.uv.iter().enumerate() {
        let (i, j) = (k / 8, k % 8);
        assert!(q[0] >= i as f64 / 8.0 && q[0] <= (i + 1) as f64 / 8.0);
        assert!(q[1] >= j as f64 / 8.0 && q[1] <= (j + 1) as f64 / 8.0);
    }
    assert_eq!(generate("jitter:spacing=0.1:seed=1").len(), 100);
    assert_eq!(
        Generator::parse("jitter:4x4").unwrap(),
        Generator::Jitter {
            size: GridSize::Counts { nu: 4, nv: 4 },
            amount: 0.5,
            seed: 0
        },
        "default amount 0.5, seed 0"
    );
}

#[test]
fn random_points_count_and_spread() {
    let p = generate("random:1000:seed=7");
    assert_eq!(p.len(), 1000);
    let mean_s = p.uv.iter().map(|q| q[0]).sum::<f64>() / 1000.0;
    let mean_t = p.uv.iter().map(|q| q[1]).sum::<f64>() / 1000.0;
    assert!((mean_s - 0.5).abs() < 0.05 && (mean_t - 0.5).abs() < 0.05);
    assert_eq!(generate("random:1").len(), 1);
}

#[test]
fn same_seed_same_points_different_seed_different_points() {
    for (a, b) in [
        (
            "jitter:12x9:amount=0.4:seed=1",
            "jitter:12x9:amount=0.4:seed=2",
        ),
        ("random:500:seed=1", "random:500:seed=2"),
        ("poisson:0.05:seed=1", "poisson:0.05:seed=2"),
    ] {
        let first = generate(a);
        assert_eq!(first, generate(a), "{a} is deterministic");
        assert_eq!(first, Generator::parse(a).unwrap().generate());
        let other = generate(b);
        assert_ne!(first.uv, other.uv, "{a} vs {b}");
        // Not merely reordered.
        assert!(
            !other.uv.iter().any(|q| first.uv.contains(q)),
            "{a} vs {b} share points"
        );
    }
    assert_eq!(
        generate("random:10").uv,
        generate("random:10:seed=0").uv,
        "seed defaults to 0"
    );
}

#[test]
fn poisson_disk_respects_the_minimum_distance() {
    for (r, seed) in [
        (0.1, 0u64),
        (0.05, 7),
        (0.03, 7),
        (0.02, 123_456_789),
        (0.011, u64::MAX),
    ] {
        let p = generate(&format!("poisson:{r}:seed={seed}"));
        let r2 = r * r;
        let mut nearest = f64::INFINITY;
        for i in 0..p.len() {
            for j in 0..i {
                let (dx, dy) = (p.uv[i][0] - p.uv[j][0], p.uv[i][1] - p.uv[j][1]);
                let d2 = dx * dx + dy * dy;
                assert!(
                    d2 >= r2,
                    "r = {r}, seed {seed}: points {j} and {i} at distance {}",
                    d2.sqrt()
                );
                nearest = nearest.min(d2);
            }
        }
        // Bridson fills the square: about 0.7 / r^2 points, and gaps are rare.
        let density = p.len() as f64 * r2;
        assert!(
            (0.45..0.85).contains(&density),
            "r = {r}: {} points, density {density}",
            p.len()
        );
        assert!(nearest.sqrt() < 1.2 * r, "dense packing reaches close to r");
        // Every point of the square lies within 2r of a sample (Bridson's coverage).
        let probe = 40;
        for a in 0..probe {
            for b in 0..probe {
                let q = [
                    (a as f64 + 0.5) / probe as f64,
                    (b as f64 + 0.5) / probe as f64,
                ];
                let covered =
                    p.uv.iter()
                        .any(|s| (s[0] - q[0]).hypot(s[1] - q[1]) < 2.0 * r);
                assert!(covered, "r = {r}: gap at {q:?}");
            }
        }
    }
    // A radius beyond the diagonal leaves the first point alone.
    assert_eq!(generate("poisson:1.5:seed=4").len(), 1);
    assert_eq!(generate("poisson:1e300:seed=4").len(), 1);
}

#[test]
fn display_prints_the_canonical_spec() {
    for (spec, canonical) in [
        ("grid:20x15", "grid:20x15"),
        ("grid:spacing=0.05", "grid:spacing=0.05"),
        ("hex:24x20", "hex:24x20"),
        ("hex:spacing=0.05", "hex:spacing=0.05"),
        (
            "jitter:20x20:amount=0.3:seed=7",
            "jitter:20x20:amount=0.3:seed=7",
        ),
        (
            "jitter:20x20:seed=7:amount=0.3",
            "jitter:20x20:amount=0.3:seed=7",
        ),
        ("jitter:spacing=0.1", "jitter:spacing=0.1:amount=0.5:seed=0"),
        ("random:1000:seed=7", "random:1000:seed=7"),
        ("random:1000", "random:1000:seed=0"),
        ("poisson:0.03:seed=7", "poisson:0.03:seed=7"),
        ("  poisson:0.03  ", "poisson:0.03:seed=0"),
        (
            "random:5:seed=18446744073709551615",
            "random:5:seed=18446744073709551615",
        ),
    ] {
        let g = Generator::parse(spec).unwrap();
        assert_eq!(g.to_string(), canonical);
        assert_eq!(
            Generator::parse(canonical).unwrap(),
            g,
            "{canonical} reads back"
        );
        assert_eq!(canonical.parse::<Generator>().unwrap(), g, "FromStr");
    }
    assert_eq!(
        Generator::parse("grid:20x15").unwrap(),
        Generator::Grid(GridSize::Counts { nu: 20, nv: 15 })
    );
    assert_eq!(
        Generator::parse("poisson:0.03:seed=7").unwrap(),
        Generator::Poisson {
            radius: 0.03,
            seed: 7
        }
    );
}

#[test]
fn invalid_generator_specs_name_the_problem() {
    let cases = [
        ("", "empty generator"),
        ("triangle:10x10", "unknown generator kind `triangle`"),
        ("Grid:10x10", "unknown generator kind `Grid`"),
        ("grid", "exactly one argument"),
        ("grid:20", "neither NUxNV"),
        ("grid:20x", "count `` in `20x`"),
        ("grid:ax5", "count `a` in `ax5`"),
        ("grid:-2x5", "count `-2`"),
        ("grid:0x5", "must both be at least 1"),
        ("grid:20x15:seed=1", "exactly one argument"),
        ("grid:spacing=0", "spacing 0 must be a number in (0, 1]"),
        ("grid:spacing=-0.1", "spacing -0.1 must be"),
        ("grid:spacing=1.5", "spacing 1.5 must be"),
        ("grid:spacing=nan", "spacing NaN must be"),
        ("grid:spacing=inf", "spacing inf must be"),
        ("grid:spacing=abc", "spacing `abc` is not a number"),
        ("grid:spacing=1e-9", "exceed the maximum"),
        ("hex:5000x5000", "exceed the maximum"),
        ("hex:18446744073709551615x2", "exceed the maximum"),
        ("hex:spacing=0", "spacing 0 must be"),
        ("jitter", "needs a grid size"),
        ("jitter:10x10:amount=1.5", "amount 1.5 must be in [0, 1]"),
        ("jitter:10x10:amount=-0.1", "amount -0.1 must be"),
        ("jitter:10x10:amount=x", "amount `x` is not a number"),
        (
            "jitter:10x10:amont=0.3",
            "unknown option `amont` (accepted: amount, seed)",
        ),
        ("jitter:10x10:seed=1:seed=2", "option `seed` is given twice"),
        ("jitter:10x10:7", "option `7` is not of the form key=value"),
        ("random", "needs a point count"),
        ("random:0", "at least 1"),
        ("random:-3", "point count `-3`"),
        ("random:1.5", "point count `1.5`"),
        ("random:20000000", "exceed the maximum"),
        (
            "random:10:seed=-1",
            "seed `-1` is not an unsigned 64-bit integer",
        ),
        ("random:10:seed=abc", "seed `abc`"),
        (
            "random:10:amount=0.5",
            "unknown option `amount` (accepted: seed)",
        ),
        ("poisson", "needs a radius"),
        ("poisson:0", "radius 0 must be a number >= 0.001"),
        ("poisson:0.0001", "radius 0.0001 must be"),
        ("poisson:-1", "radius -1 must be"),
        ("poisson:inf", "radius inf must be"),
        ("poisson:abc", "radius `abc` is not a number"),
        ("poisson:0.1:amount=1", "unknown option `amount`"),
    ];
    for (spec, reason_part) in cases {
        match Generator::parse(spec) {
            Err(TpiError::InvalidGenerator { spec: s, reason }) => {
                assert_eq!(s, spec);
                assert!(
                    reason.contains(reason_part),
                    "{spec}: reason `{reason}` lacks `{reason_part}`"
                );
            }
            other => panic!("{spec}: expected InvalidGenerator, got {other:?}"),
        }
    }
    assert_eq!(MIN_POISSON_RADIUS, 0.001);
    assert_eq!(MAX_GENERATED_POINTS, 10_000_000);
}

#[test]
fn hand_built_invalid_generators_are_caught() {
    let bad = [
        Generator::Grid(GridSize::Counts { nu: 0, nv: 3 }),
        Generator::Hex(GridSize::Spacing(f64::NAN)),
        Generator::Jitter {
            size: GridSize::Counts { nu: 2, nv: 2 },
            amount: 2.0,
            seed: 0,
        },
        Generator::Random {
            count: MAX_GENERATED_POINTS + 1,
            seed: 0,
        },
        Generator::Poisson {
            radius: 0.0,
            seed: 0,
        },
    ];
    for g in bad {
        assert!(
            matches!(g.validate(), Err(TpiError::InvalidGenerator { .. })),
            "{g:?}"
        );
        assert!(
            g.generate().is_empty(),
            "{g:?} generates nothing rather than failing"
        );
        assert_eq!(g.expected_count(), None);
    }
    assert_eq!(Generator::Random { count: 3, seed: 1 }.validate(), Ok(()));
}
