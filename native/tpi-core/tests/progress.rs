//! The progress observer (`discretise_with_progress`, issue 14 item 6): every stage that runs
//! is started and finished once, in pipeline order, its items counted up to its total; the
//! stages that do not run are not reported; and the result is byte for byte the one of
//! `discretise` without an observer.

mod common;

use std::collections::HashMap;
use std::sync::Mutex;

use common::*;
use tpi_core::{
    discretise, discretise_with_progress, DiscretiseOptions, PlaneMode, Progress, Stage, Surface,
    SurfacePatternSpec, SurfaceSpec, PROGRESS_CHUNK,
};

/// What the observer saw, in order: (stage, total) when started, (stage, items counted so
/// far) when finished.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Event {
    Started(Stage, Option<usize>),
    Finished(Stage, usize),
}

#[derive(Default)]
struct Recorder {
    events: Mutex<Vec<Event>>,
    counts: Mutex<HashMap<Stage, usize>>,
    largest_call: Mutex<usize>,
}

impl Progress for Recorder {
    fn stage_started(&self, stage: Stage, total: Option<usize>) {
        self.events
            .lock()
            .unwrap()
            .push(Event::Started(stage, total));
        self.counts.lock().unwrap().insert(stage, 0);
    }

    fn advanced(&self, stage: Stage, items: usize) {
        *self.counts.lock().unwrap().entry(stage).or_insert(0) += items;
        let mut largest = self.largest_call.lock().unwrap();
        *largest = (*largest).max(items);
    }

    fn stage_finished(&self, stage: Stage) {
        let count = self
            .counts
            .lock()
            .unwrap()
            .get(&stage)
            .copied()
            .unwrap_or(0);
        self.events
            .lock()
            .unwrap()
            .push(Event::Finished(stage, count));
    }
}

fn analytic(json: &str) -> tpi_core::SurfaceModel {
    SurfaceSpec::from_json(json, "test")
        .unwrap()
        .build()
        .unwrap()
}

/// Runs with and without the observer, checks that the two results are identical and that
/// the events are well formed (each stage started, then finished, in pipeline order, every
/// count at its total), and returns the stages seen with their totals.
fn observed(
    name: &str,
    surface: &dyn Surface,
    pattern: &[[f64; 2]],
    options: &DiscretiseOptions,
) -> Vec<(Stage, Option<usize>)> {
    let plain = discretise(surface, pattern, options).unwrap();
    let recorder = Recorder::default();
    let watched = discretise_with_progress(surface, pattern, options, &recorder).unwrap();
    assert_eq!(
        plain.to_json(false),
        watched.to_json(false),
        "{name}: the observer changed the result"
    );
    let events = recorder.events.into_inner().unwrap();
    assert!(
        *recorder.largest_call.lock().unwrap() <= PROGRESS_CHUNK,
        "{name}: items are reported in chunks of at most {PROGRESS_CHUNK}"
    );
    assert_eq!(events.len() % 2, 0, "{name}: {events:?}");
    let mut stages = Vec::new();
    for pair in events.chunks(2) {
        let (Event::Started(stage, total), Event::Finished(finished, count)) = (pair[0], pair[1])
        else {
            panic!("{name}: a stage started before the previous one finished: {events:?}");
        };
        assert_eq!(stage, finished, "{name}: {events:?}");
        match total {
            Some(total) => assert_eq!(
                count,
                total,
                "{name}: {} counted {count} of {total} items",
                stage.name()
            ),
            None => assert_eq!(count, 0, "{name}: {} has no total", stage.name()),
        }
        stages.push((stage, total));
    }
    // In pipeline order (the pipeline runs once here).
    let order = |s: Stage| Stage::ALL.iter().position(|&x| x == s).unwrap();
    assert!(
        stages.windows(2).all(|w| order(w[0].0) < order(w[1].0)),
        "{name}: stages out of order: {stages:?}"
    );
    stages
}

fn names(stages: &[(Stage, Option<usize>)]) -> Vec<&'static str> {
    stages.iter().map(|(s, _)| s.name()).collect()
}

#[test]
fn the_convex_path_counts_every_stage_to_its_total() {
    // 3,000 points: several chunks per stage, across rayon's workers.
    let n = 3000;
    let pattern = uniform_pattern(&mut Rng::new(14), n);
    let surface = sample_surface("nurbs-dome.json");
    let options = DiscretiseOptions::default();
    let stages = observed("nurbs dome", &surface, &pattern, &options);
    assert_eq!(
        names(&stages),
        [
            "samples",
            "delaunay",
            "neighbours",
            "facets",
            "mesh",
            "report"
        ]
    );
    let result = discretise(&surface, &pattern, &options).unwrap();
    let triangles = result.dual_triangles.len();
    let total = |s: Stage| stages.iter().find(|(x, _)| *x == s).and_then(|(_, t)| *t);
    assert_eq!(total(Stage::Samples), Some(n));
    assert_eq!(total(Stage::Delaunay), None);
    // The interior edges of the candidate triangulation.
    assert!(total(Stage::Neighbours).is_some_and(|e| e > n && e < 3 * n));
    assert_eq!(total(Stage::Facets), Some(triangles + n));
    assert_eq!(total(Stage::Mesh), Some(n));
    assert_eq!(total(Stage::Report), Some(n + result.vertices.len()));
}

#[test]
fn only_the_stages_that_run_are_reported() {
    let pattern = uniform_pattern(&mut Rng::new(7), 400);
    let exact = DiscretiseOptions::default();
    let no_report = DiscretiseOptions {
        quality_report: false,
        ..DiscretiseOptions::default()
    };
    let adjusted = DiscretiseOptions {
        planes: PlaneMode::Adjusted,
        ..DiscretiseOptions::default()
    };
    let all = [
        "samples",
        "delaunay",
        "neighbours",
        "facets",
        "mesh",
        "report",
    ];
    for (name, surface, options, expected) in [
        (
            "paraboloid",
            sample_surface("paraboloid.json"),
            exact,
            &all[..],
        ),
        (
            "paraboloid, no report",
            sample_surface("paraboloid.json"),
            no_report,
            &all[..5],
        ),
        ("hypar", sample_surface("hypar.json"), exact, &all[..]),
        (
            "mixed roof",
            sample_surface("mixed-roof.json"),
            exact,
            &all[..],
        ),
        (
            "mixed roof, adjusted",
            sample_surface("mixed-roof.json"),
            adjusted,
            &all[..],
        ),
        (
            "ellipsoid",
            sample_surface("ellipsoid.json"),
            exact,
            // A closed convex surface: the hull of the dual points is the whole decision.
            &["samples", "delaunay", "facets", "mesh", "report"][..],
        ),
        (
            // Normals too far apart for the slope frame: parameter-space candidates, flips.
            "steep sphere cap",
            analytic(
                r#"{"type": "sphere_cap", "radius": 1, "x": [-0.99, 0.99], "y": [-0.1, 0.1]}"#,
            ),
            exact,
            &all[..],
        ),
        (
            "plane",
            analytic(r#"{"type": "plane", "p": 0.1, "q": 0.2, "c0": 0, "x": [0, 1], "y": [0, 1]}"#),
            exact,
            // Voronoi cells of the seeds: no neighbour decision.
            &["samples", "delaunay", "facets", "mesh", "report"][..],
        ),
        (
            "cylinder",
            analytic(r#"{"type": "cylinder", "radius": 2, "x": [-1, 1], "y": [0, 3]}"#),
            exact,
            // Strips along the rulings, built directly.
            &["samples", "delaunay", "facets", "mesh", "report"][..],
        ),
        (
            "trimmed paraboloid",
            analytic(
                r#"{"type": "elliptic_paraboloid", "a": 1, "b": 1, "x": [-1, 1], "y": [-1, 1],
                    "trim": {"outer": [[-0.8, -0.8], [0.8, -0.8], [0.8, 0.8], [-0.8, 0.8]]}}"#,
            ),
            exact,
            &all[..],
        ),
    ] {
        let stages = observed(name, &surface, &pattern, &options);
        assert_eq!(names(&stages), expected, "{name}");
        // The neighbours count their edges on the convex (slope) path only, where one pass of
        // flips decides every edge; elsewhere they are a spinner.
        if let Some((_, total)) = stages.iter().find(|(s, _)| *s == Stage::Neighbours) {
            assert_eq!(total.is_some(), name.contains("paraboloid"), "{name}");
        }
        // Counted where a total is known: the points, the facets, the report's items.
        for (stage, total) in &stages {
            let counted = matches!(
                stage,
                Stage::Samples | Stage::Facets | Stage::Mesh | Stage::Report
            );
            assert!(
                !counted || total.is_some(),
                "{name}: {} without a total",
                stage.name()
            );
        }
    }
}

#[test]
fn a_failing_run_reports_only_what_it_started() {
    // A pattern point outside [0, 1]^2 fails before any stage: nothing is reported.
    let recorder = Recorder::default();
    let surface = sample_surface("paraboloid.json");
    let bad = [[0.1, 0.1], [0.5, 2.0], [0.9, 0.3]];
    let options = DiscretiseOptions::default();
    assert!(discretise_with_progress(&surface, &bad, &options, &recorder).is_err());
    assert!(recorder.events.lock().unwrap().is_empty());

    // Collinear in parameter space: refused after sampling, which was started and finished.
    let recorder = Recorder::default();
    let line: Vec<[f64; 2]> = (0..10).map(|i| [0.05 + 0.09 * i as f64, 0.5]).collect();
    assert!(discretise_with_progress(&surface, &line, &options, &recorder).is_err());
    let events = recorder.events.into_inner().unwrap();
    assert_eq!(
        events,
        [
            Event::Started(Stage::Samples, Some(10)),
            Event::Finished(Stage::Samples, 10)
        ]
    );
}

/// An observer that asks the run to stop once `stage` has started (or from the start).
struct CancelAt {
    stage: Option<Stage>,
    seen: Mutex<Vec<Stage>>,
    asked: std::sync::atomic::AtomicBool,
}

impl Progress for CancelAt {
    fn stage_started(&self, stage: Stage, _total: Option<usize>) {
        self.seen.lock().unwrap().push(stage);
        if Some(stage) == self.stage {
            self.asked.store(true, std::sync::atomic::Ordering::SeqCst);
        }
    }

    fn cancelled(&self) -> bool {
        self.stage.is_none() || self.asked.load(std::sync::atomic::Ordering::SeqCst)
    }
}

#[test]
fn a_cancelled_run_stops_in_the_stage_it_was_asked_in() {
    let pattern = uniform_pattern(&mut Rng::new(3), 2000);
    let surface = sample_surface("nurbs-dome.json");
    let options = DiscretiseOptions::default();
    // Asked before anything: no stage runs.
    let before = CancelAt {
        stage: None,
        seen: Mutex::default(),
        asked: Default::default(),
    };
    match discretise_with_progress(&surface, &pattern, &options, &before) {
        Err(tpi_core::TpiError::Cancelled { stage }) => assert_eq!(stage, "samples"),
        other => panic!("expected Cancelled, got {:?}", other.map(|_| ())),
    }
    assert!(before.seen.lock().unwrap().is_empty());
    // Asked when a stage starts: that stage ends, no later stage starts, and the error names it.
    for stage in Stage::ALL {
        let observer = CancelAt {
            stage: Some(stage),
            seen: Mutex::default(),
            asked: Default::default(),
        };
        // The facets and the mesh assembly are one step: asked in the facets, the run stops
        // after the mesh.
        let stops = if stage == Stage::Facets {
            Stage::Mesh
        } else {
            stage
        };
        let got = discretise_with_progress(&surface, &pattern, &options, &observer);
        match got {
            Err(tpi_core::TpiError::Cancelled { stage: named }) => {
                assert_eq!(named, stops.name())
            }
            other => panic!(
                "{}: expected Cancelled, got {:?}",
                stage.name(),
                other.map(|_| ())
            ),
        }
        let seen = observer.seen.into_inner().unwrap();
        assert_eq!(seen.last(), Some(&stops), "{}: {seen:?}", stage.name());
        let message = tpi_core::TpiError::Cancelled {
            stage: stage.name().into(),
        }
        .to_string();
        assert!(message.contains("cancelled") && message.contains(stage.name()));
    }
    // An observer that never asks changes nothing (the result equals discretise's above).
    observed("nurbs dome, not cancelled", &surface, &pattern, &options);
}

/// Cancels once the `runs`-th discretisation has started (its samples stage).
struct CancelAfterRuns {
    runs: usize,
    started: std::sync::atomic::AtomicUsize,
}

impl Progress for CancelAfterRuns {
    fn stage_started(&self, stage: Stage, _total: Option<usize>) {
        if stage == Stage::Samples {
            self.started
                .fetch_add(1, std::sync::atomic::Ordering::SeqCst);
        }
    }

    fn cancelled(&self) -> bool {
        self.started.load(std::sync::atomic::Ordering::SeqCst) >= self.runs
    }
}

/// Patterns made on a surface (issue 15) run many discretisations: a fit and a relaxation
/// report every one of them (as many as the fit's own count, or one per Lloyd iteration),
/// give the same points as without an observer, and stop with `Cancelled` as soon as the
/// observer asks, starting no further discretisation.
#[test]
fn a_fit_and_a_relaxation_report_their_discretisations_and_can_be_cancelled() {
    let surface = sample_surface("nurbs-dome.json");
    let options = DiscretiseOptions::default();
    for (text, lloyd) in [("fit:0.05", None), ("relax:3:random:200", Some(3))] {
        let spec = SurfacePatternSpec::parse(text).unwrap();
        let plain = spec.generate(&surface, &options).unwrap();
        let recorder = Recorder::default();
        let watched = spec
            .generate_with_progress(&surface, &options, &recorder)
            .unwrap();
        assert_eq!(plain.uv, watched.uv, "{text}");
        assert_eq!(plain.fit, watched.fit, "{text}");
        let events = recorder.events.into_inner().unwrap();
        let runs = |stage| {
            events
                .iter()
                .filter(|e| matches!(e, Event::Started(s, _) if *s == stage))
                .count()
        };
        let expected = match (&plain.fit, lloyd) {
            (Some(fit), None) => fit.discretisations,
            (None, Some(iterations)) => iterations,
            _ => panic!("{text}: unexpected outcome"),
        };
        assert!(expected >= 3, "{text}: {expected} discretisations");
        // Every discretisation runs every stage once, the report included.
        assert_eq!(runs(Stage::Samples), expected, "{text}");
        assert_eq!(runs(Stage::Report), expected, "{text}");

        let stopper = CancelAfterRuns {
            runs: 2,
            started: Default::default(),
        };
        match spec.generate_with_progress(&surface, &options, &stopper) {
            Err(tpi_core::TpiError::Cancelled { stage }) => assert_eq!(stage, "samples", "{text}"),
            other => panic!(
                "{text}: expected Cancelled, got {:?}",
                other.map(|p| p.uv.len())
            ),
        }
        assert_eq!(stopper.started.into_inner(), 2, "{text}");
    }
}
