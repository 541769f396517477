//! Acceptance: a live surface edited point by point (moves, adds, removes) gives exactly the
//! discretisation of the edited pattern from scratch, after every one of thousands of random
//! edits: the same facets in the same order, the same vertex positions and numbering, the
//! same report and diagnostics (the whole output contract as JSON, byte for byte), and most
//! edits take the incremental path (issue 7, item 3).

use glam::DVec3;
use tpi_core::benchmark::{nurbs_dome, paraboloid, random_pattern};
use tpi_core::SplitMix64;
use tpi_core::{discretise, AnalyticSurface, DiscretiseOptions, LiveChanges, LiveSurface, Surface};

/// A host's copy of the mesh kept only by [`LiveSurface::take_changes`] (issue 13): vertex
/// positions by live id, facet loops and planes.
#[derive(Default)]
struct Replica {
    vertices: Vec<Option<DVec3>>,
    loops: Vec<Vec<u32>>,
    planes: Vec<(DVec3, DVec3)>,
}

impl Replica {
    fn apply(&mut self, changes: &LiveChanges) {
        if changes.everything {
            *self = Replica::default();
        }
        self.vertices.resize(changes.vertex_id_bound, None);
        self.loops.truncate(changes.facet_count);
        self.loops.resize(changes.facet_count, Vec::new());
        self.planes
            .resize(changes.facet_count, (DVec3::NAN, DVec3::NAN));
        for (k, &f) in changes.facets.iter().enumerate() {
            self.loops[f as usize] = changes.facet_loop(k).to_vec();
            self.planes[f as usize] = changes.planes[k];
        }
        for (&id, &x) in changes.vertex_ids.iter().zip(&changes.vertices) {
            self.vertices[id as usize] = Some(x);
        }
    }

    /// Takes the live surface's changes and checks the copy against its assembled mesh:
    /// every facet's vertices and plane, bit for bit. Returns how many facets were listed.
    fn follow(&mut self, live: &mut LiveSurface, step: usize, what: &str) -> usize {
        let changes = live.take_changes();
        assert_eq!(changes.facet_offsets.len(), changes.facets.len() + 1);
        assert!(
            changes.facets.windows(2).all(|w| w[0] < w[1]),
            "{what}: facets ascending"
        );
        self.apply(&changes);
        let mesh = live.discretisation();
        assert_eq!(self.loops.len(), mesh.facet_count(), "edit {step} ({what})");
        let bits = |x: DVec3| x.to_array().map(f64::to_bits);
        for i in 0..mesh.facet_count() {
            let expected: Vec<_> = mesh
                .facet(i)
                .iter()
                .map(|&v| bits(mesh.vertices[v as usize]))
                .collect();
            let got: Vec<_> = self.loops[i]
                .iter()
                .map(|&v| {
                    bits(self.vertices[v as usize].unwrap_or_else(|| {
                        panic!("edit {step} ({what}): facet {i} holds vertex id {v} never listed")
                    }))
                })
                .collect();
            assert_eq!(got, expected, "edit {step} ({what}): facet {i}'s vertices");
            let (p, n) = mesh.facet_plane(i);
            assert_eq!(
                (bits(self.planes[i].0), bits(self.planes[i].1)),
                (bits(p), bits(n)),
                "edit {step} ({what}): facet {i}'s plane"
            );
        }
        changes.facets.len()
    }
}

/// Compares the live mesh with a fresh run, byte for byte.
fn check(live: &mut LiveSurface, surface: &dyn Surface, step: usize, what: &str) {
    let options = *live.options();
    let scratch = discretise(surface, live.points(), &options)
        .expect("the edited pattern discretises")
        .to_json(false);
    let edited = live.discretisation().to_json(false);
    if edited != scratch {
        let at = edited
            .bytes()
            .zip(scratch.bytes())
            .position(|(a, b)| a != b)
            .unwrap_or(edited.len().min(scratch.len()));
        let lo = at.saturating_sub(120);
        panic!(
            "edit {step} ({what}): the live mesh differs from a fresh run at byte {at} (lengths {} / {}):\n  live:    ...{}...\n  scratch: ...{}...",
            edited.len(),
            scratch.len(),
            &edited[lo..(at + 120).min(edited.len())],
            &scratch[lo..(at + 120).min(scratch.len())]
        );
    }
}

/// `edits` random edits: mostly small drags, some jumps anywhere, adds and removes.
/// `min_share` is the least fraction of incremental edits expected: edits whose neighbourhood
/// touches a facet on the boundary run the whole pipeline, and with a few hundred points that
/// band is a good part of the pattern.
#[allow(clippy::too_many_arguments)]
fn random_edits(
    name: &str,
    surface: &dyn Surface,
    boxed: Box<dyn Surface>,
    points: usize,
    edits: usize,
    seed: u64,
    options: DiscretiseOptions,
    min_share: f64,
) {
    let mut live = LiveSurface::new(boxed, random_pattern(points), options).expect("discretises");
    check(&mut live, surface, 0, "new");
    let mut replica = Replica::default();
    assert_eq!(
        replica.follow(&mut live, 0, "new"),
        points,
        "the first changes list everything"
    );
    let mut rng = SplitMix64::new(seed);
    let mut last_incremental = live.stats().incremental;
    for step in 1..=edits {
        let n = live.points().len();
        let roll = rng.next_f64();
        let what = if roll < 0.6 {
            let i = rng.below(n);
            let p = live.points()[i];
            let r = 0.5 / (n as f64).sqrt();
            let q = [
                (p[0] + r * (rng.next_f64() - 0.5)).clamp(0.0, 1.0),
                (p[1] + r * (rng.next_f64() - 0.5)).clamp(0.0, 1.0),
            ];
            live.move_point(i, q).expect("move");
            format!("drag {i} to {q:?}")
        } else if roll < 0.75 {
            let i = rng.below(n);
            let q = [rng.next_f64(), rng.next_f64()];
            live.move_point(i, q).expect("move");
            format!("move {i} to {q:?}")
        } else if roll < 0.88 {
            let q = [rng.next_f64(), rng.next_f64()];
            let i = live.add_point(q).expect("add");
            format!("add {i} at {q:?}")
        } else {
            let i = rng.below(n);
            live.remove_point(i).expect("remove");
            format!("remove {i}")
        };
        check(&mut live, surface, step, &what);
        let incremental = live.stats().incremental;
        let listed = replica.follow(&mut live, step, &what);
        if what.starts_with("drag") && incremental > last_incremental {
            assert!(
                listed < 30,
                "edit {step} ({what}): {listed} facets listed for a drag"
            );
        }
        last_incremental = incremental;
    }
    let stats = live.stats();
    println!(
        "{name}: {edits} edits, {} incremental, {} full runs",
        stats.incremental, stats.full
    );
    assert!(
        stats.incremental as f64 >= min_share * edits as f64,
        "{name}: only {} of {edits} edits were incremental",
        stats.incremental
    );
}

#[test]
fn nurbs_dome_edits_equal_fresh_runs() {
    random_edits(
        "NURBS dome",
        &nurbs_dome(),
        Box::new(nurbs_dome()),
        300,
        1200,
        71,
        DiscretiseOptions::default(),
        0.4,
    );
}

#[test]
fn paraboloid_edits_equal_fresh_runs() {
    random_edits(
        "paraboloid",
        &paraboloid(),
        Box::new(paraboloid()),
        250,
        800,
        72,
        DiscretiseOptions::default(),
        0.4,
    );
}

#[test]
fn edits_without_report_equal_fresh_runs() {
    let options = DiscretiseOptions {
        quality_report: false,
        ..DiscretiseOptions::default()
    };
    random_edits(
        "NURBS dome, no report",
        &nurbs_dome(),
        Box::new(nurbs_dome()),
        200,
        400,
        73,
        options,
        0.3,
    );
}

#[test]
fn edits_with_adjusted_planes_equal_fresh_runs() {
    // On a convex surface adjusted planes are the exact ones (tilt 0), also after edits.
    let options = DiscretiseOptions {
        planes: tpi_core::PlaneMode::Adjusted,
        ..DiscretiseOptions::default()
    };
    random_edits(
        "NURBS dome, adjusted planes",
        &nurbs_dome(),
        Box::new(nurbs_dome()),
        150,
        200,
        74,
        options,
        0.3,
    );
}

#[test]
fn anisotropic_and_saddle_surfaces_fall_back_and_still_agree() {
    // Convex, but its normals turn too far for the slope embedding (the mixed path): every
    // edit runs the pipeline, with the same result.
    let s = AnalyticSurface::elliptic_paraboloid(10.0, 1.0, [-0.4, 0.4], [-1.0, 1.0]).unwrap();
    let mut live = LiveSurface::new(
        Box::new(s),
        random_pattern(200),
        DiscretiseOptions::default(),
    )
    .unwrap();
    let mut rng = SplitMix64::new(5);
    for step in 1..=30 {
        let i = rng.below(live.points().len());
        live.move_point(i, [rng.next_f64(), rng.next_f64()])
            .unwrap();
        check(&mut live, &s, step, "move");
    }
    assert_eq!(live.stats().incremental, 0);
    // Strong but milder anisotropy on the slope path: the envelope overrules the Delaunay
    // candidates on many edges (envelope repairs > 0), edits stay incremental.
    let s = AnalyticSurface::elliptic_paraboloid(1.0, 0.1, [-0.5, 0.5], [-1.0, 1.0]).unwrap();
    let mut live = LiveSurface::new(
        Box::new(s),
        random_pattern(300),
        DiscretiseOptions::default(),
    )
    .unwrap();
    assert!(
        live.discretisation()
            .quality
            .as_ref()
            .unwrap()
            .neighbours
            .envelope_repairs
            > 0
    );
    for step in 1..=150 {
        let i = rng.below(live.points().len());
        let p = live.points()[i];
        let q = [
            (p[0] + 0.02 * (rng.next_f64() - 0.5)).clamp(0.0, 1.0),
            (p[1] + 0.02 * (rng.next_f64() - 0.5)).clamp(0.0, 1.0),
        ];
        live.move_point(i, q).unwrap();
        check(&mut live, &s, step, "drag");
    }
    assert!(live.stats().incremental > 40, "{:?}", live.stats());
    // A saddle: no incremental path, every edit runs the pipeline, same result.
    let h = AnalyticSurface::hyperbolic_paraboloid(0.5, 0.5, [-1.0, 1.0], [-1.0, 1.0]).unwrap();
    let mut live = LiveSurface::new(
        Box::new(h),
        random_pattern(150),
        DiscretiseOptions::default(),
    )
    .unwrap();
    for step in 1..=20 {
        let i = rng.below(live.points().len());
        live.move_point(i, [rng.next_f64(), rng.next_f64()])
            .unwrap();
        check(&mut live, &h, step, "move on a saddle");
    }
    assert_eq!(live.stats().incremental, 0);
}

#[test]
fn failed_edits_change_nothing() {
    let s = nurbs_dome();
    let mut live = LiveSurface::new(
        Box::new(s.clone()),
        random_pattern(100),
        DiscretiseOptions::default(),
    )
    .unwrap();
    let before = live.discretisation().to_json(false);
    let p = live.points()[3];
    assert!(live.move_point(7, p).is_err(), "a duplicate is an error");
    assert!(live.move_point(1000, [0.5, 0.5]).is_err());
    assert!(live.remove_point(1000).is_err());
    assert!(live.add_point(p).is_err());
    assert!(live.move_point(2, [1.5, 0.5]).is_err());
    assert_eq!(live.points().len(), 100);
    assert_eq!(live.discretisation().to_json(false), before);
    check(&mut live, &s, 0, "after failed edits");
    // Replacing the surface recomputes everything.
    let other = paraboloid();
    live.set_surface(Box::new(other)).unwrap();
    check(&mut live, &other, 1, "new surface");
}

#[test]
fn welded_vertices_do_not_stop_edits_elsewhere() {
    // Four points on a circle on the paraboloid of revolution: their four tangent planes meet
    // in one point, so two triangle vertices are welded there. Edits elsewhere stay
    // incremental; the result is a fresh run's, welds included.
    let s = paraboloid();
    let mut pattern = random_pattern(300);
    let (c, h) = ([0.503, 0.497], 0.004);
    pattern.retain(|p| (p[0] - c[0]).hypot(p[1] - c[1]) > 0.05);
    pattern.extend([
        [c[0] - h, c[1] - h],
        [c[0] + h, c[1] - h],
        [c[0] + h, c[1] + h],
        [c[0] - h, c[1] + h],
    ]);
    let mut live = LiveSurface::new(Box::new(s), pattern, DiscretiseOptions::default()).unwrap();
    let q = live.discretisation().quality.clone().unwrap();
    assert!(q.trivalent_fraction < 1.0, "the test needs a weld: {q:?}");
    let mut rng = SplitMix64::new(9);
    for step in 1..=200 {
        let n = live.points().len();
        let i = rng.below(n - 4);
        let p = live.points()[i];
        let to = [
            (p[0] + 0.02 * (rng.next_f64() - 0.5)).clamp(0.0, 1.0),
            (p[1] + 0.02 * (rng.next_f64() - 0.5)).clamp(0.0, 1.0),
        ];
        if (to[0] - c[0]).hypot(to[1] - c[1]) < 0.05 {
            continue;
        }
        live.move_point(i, to).unwrap();
        check(&mut live, &s, step, "drag beside a weld");
    }
    assert!(live.stats().incremental > 60, "{:?}", live.stats());
}

/// Issue 16: live edits on a cylinder (strips) and a plane (clipped Voronoi cells) run the
/// whole pipeline, and give exactly what a fresh run of the edited pattern gives.
#[test]
fn cylinder_and_plane_edits_equal_fresh_runs() {
    let cylinder = AnalyticSurface::cylinder(1.0, [-0.8, 0.8], [0.0, 3.0]).unwrap();
    let plane = AnalyticSurface::plane(0.3, -0.7, 2.0, [0.0, 5.0], [-2.0, 1.0]).unwrap();
    for (name, surface) in [("cylinder", cylinder), ("plane", plane)] {
        random_edits(
            name,
            &surface,
            Box::new(surface),
            150,
            30,
            16,
            DiscretiseOptions::default(),
            0.0,
        );
    }
}

/// The bicubic Bezier dome of the .NET tests (z = 1.5 (u (1 - u) + v (1 - v)) over
/// [-1, 1]^2): its slopes follow the parameters, so a point dragged along a hex row lies
/// exactly on the line of its row neighbours in slope space.
fn bezier_dome() -> tpi_core::NurbsSurface {
    let c = [0.0, 1.0, 1.0, 0.0];
    let mut points = Vec::new();
    for (i, ci) in c.iter().enumerate() {
        for (j, cj) in c.iter().enumerate() {
            points.push(glam::DVec3::new(
                -1.0 + 2.0 * i as f64 / 3.0,
                -1.0 + 2.0 * j as f64 / 3.0,
                0.5 * (ci + cj),
            ));
        }
    }
    let knots = [0.0, 0.0, 0.0, 1.0, 1.0, 1.0];
    tpi_core::NurbsSurface::new([3, 3], [4, 4], &knots, &knots, &points, None).expect("dome")
}

/// Issue 13: points of a hex pattern dragged along their rows and columns (their slopes on
/// the edge between two neighbours') stay incremental (the edge is split) and agree with
/// fresh runs.
#[test]
fn hex_rows_dragged_along_themselves_equal_fresh_runs() {
    let hex = tpi_core::Generator::parse("hex:24x24")
        .expect("spec")
        .generate()
        .uv;
    for (name, surface) in [
        ("Bezier dome", Box::new(bezier_dome()) as Box<dyn Surface>),
        ("paraboloid", Box::new(paraboloid())),
    ] {
        let fresh: Box<dyn Surface> = if name == "paraboloid" {
            Box::new(paraboloid())
        } else {
            Box::new(bezier_dome())
        };
        let mut live =
            LiveSurface::new(surface, hex.clone(), DiscretiseOptions::default()).expect("new");
        let mut replica = Replica::default();
        replica.follow(&mut live, 0, name);
        let mut rng = SplitMix64::new(13);
        let edits = 300;
        for step in 1..=edits {
            let i = rng.below(live.points().len());
            let p = live.points()[i];
            let d = (0.2 + 0.6 * rng.next_f64()) / 24.0;
            let q = if rng.next_f64() < 0.7 {
                [(p[0] + d).clamp(0.0, 1.0), p[1]]
            } else {
                [p[0], (p[1] - d).clamp(0.0, 1.0)]
            };
            if live.move_point(i, q).is_err() {
                continue; // a duplicate
            }
            check(
                &mut live,
                fresh.as_ref(),
                step,
                &format!("{name}: drag {i} to {q:?}"),
            );
        }
        let stats = live.stats();
        println!("{name}: {edits} row and column drags, {stats:?}");
        assert!(
            stats.incremental as f64 >= 0.5 * edits as f64,
            "{name}: {stats:?}"
        );
    }
}
