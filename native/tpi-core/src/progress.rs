//! Progress of a discretisation, for a caller that shows it (the CLI's per-stage bars).
//!
//! [`crate::discretise_with_progress`] reports to a [`Progress`] observer as the pipeline
//! runs. For every stage that runs, in order:
//!
//! 1. [`Progress::stage_started`] with the stage's total number of work items, where it is
//!    known beforehand (`None`: the stage can only say that it is alive);
//! 2. [`Progress::advanced`], any number of times and from any rayon worker thread, with a
//!    number of items just done; each worker counts its items itself and reports them in
//!    chunks of at most [`PROGRESS_CHUNK`] (and what is left when its share ends), so the hot
//!    loops pay an integer increment per item and one call per chunk;
//! 3. [`Progress::stage_finished`], also when the run ends with an error inside the stage.
//!
//! The stages are those of [`crate::Timings`] and are reported where they are timed. A stage
//! that does not run is not reported (no `delaunay` on a surface folded across its seam,
//! whose triangulation is part of its neighbour decision; no `report` with the quality report
//! off); with adjusted planes on a developable surface the pipeline may run twice and report
//! its stages twice. The work items counted, where a total is known:
//!
//! | stage | total | counted |
//! |---|---|---|
//! | `samples` | the pattern points (inside the trim) | each point's evaluation |
//! | `delaunay` | none | |
//! | `neighbours` | the interior edges of the candidate triangulation, on the convex path; none elsewhere | each edge's decision in the flip loop (the orientation, hull trim and repair count after it are not counted) |
//! | `facets` | dual triangles + facets | each triangle's vertex, then each facet's loop |
//! | `mesh` | facets | each facet's loop numbered (welding before it is not counted) |
//! | `report` | facets + mesh vertices | each facet's shape, then each vertex's deviation (the edge, overlap and topology checks between them are not counted) |
//!
//! Cancelling: the observer's [`Progress::cancelled`] is asked where a stage starts and where
//! it ends (before the run goes on to the next), and where the candidate triangulation is
//! built; once it answers true, the run returns [`crate::TpiError::Cancelled`] naming the stage
//! it had reached, and nothing of it is kept. A stage that has started runs to its end (the
//! facets and the mesh assembly run as one step: asked in the facets, the run stops after the
//! mesh), so a run stops within one stage's time (each under a second at a million points on
//! two cores, docs/performance.md).
//!
//! Every count reaches its total when the stage finishes normally. Observing never changes the
//! result: the counters are written by the workers and read by nobody in the pipeline.
//! [`NoProgress`], what [`crate::discretise()`] uses, ignores everything.

use std::cell::Cell;

use crate::TpiError;

/// Items a worker counts before it reports them to the observer (fewer when its share of the
/// stage ends first).
pub const PROGRESS_CHUNK: usize = 1024;

/// A stage of the pipeline as reported to a [`Progress`] observer (the fields of
/// [`crate::Timings`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum Stage {
    /// Evaluation and curvature at every pattern point.
    Samples,
    /// The candidate triangulation (Delaunay in parameter or slope space, the hull of a
    /// closed convex surface, the strips of a developable one).
    Delaunay,
    /// The neighbour decision: flips, hull trimming, validity flips, plane adjustment.
    Neighbours,
    /// Facet vertices (three-plane intersections, inside tests), boundary crossings, loops.
    Facets,
    /// Mesh assembly: welding, shared vertex numbering.
    Mesh,
    /// The quality report.
    Report,
}

impl Stage {
    /// Every stage, in pipeline order.
    pub const ALL: [Stage; 6] = [
        Stage::Samples,
        Stage::Delaunay,
        Stage::Neighbours,
        Stage::Facets,
        Stage::Mesh,
        Stage::Report,
    ];

    /// The stage's name, as in [`crate::Timings`] and `tpi bench`: `samples`, `delaunay`,
    /// `neighbours`, `facets`, `mesh`, `report`.
    pub fn name(self) -> &'static str {
        match self {
            Stage::Samples => "samples",
            Stage::Delaunay => "delaunay",
            Stage::Neighbours => "neighbours",
            Stage::Facets => "facets",
            Stage::Mesh => "mesh",
            Stage::Report => "report",
        }
    }
}

/// An observer of the pipeline's progress (see the module doc). Every method does nothing by
/// default. Calls come from the thread that runs the pipeline and, for
/// [`Progress::advanced`], from rayon's workers: keep them short and non-blocking (an atomic
/// counter, a rate-limited redraw).
pub trait Progress: Sync {
    /// `stage` starts; `total` is its number of work items where known.
    fn stage_started(&self, stage: Stage, total: Option<usize>) {
        let _ = (stage, total);
    }

    /// `items` more work items of `stage` are done.
    fn advanced(&self, stage: Stage, items: usize) {
        let _ = (stage, items);
    }

    /// `stage` ends (normally, or because the run failed inside it).
    fn stage_finished(&self, stage: Stage) {
        let _ = stage;
    }

    /// Whether the run should stop ([`crate::TpiError::Cancelled`]); asked between stages
    /// (see the module doc). Once true it should stay true.
    fn cancelled(&self) -> bool {
        false
    }
}

/// The observer that ignores everything (what [`crate::discretise()`] uses).
#[derive(Clone, Copy, Debug, Default)]
pub struct NoProgress;

impl Progress for NoProgress {}

/// The pipeline's side of the observer: which stage is current, so that every started stage
/// is finished exactly once (also on an early return, when this is dropped).
pub(crate) struct Stages<'a> {
    observer: &'a dyn Progress,
    current: Cell<Option<Stage>>,
    /// The last stage started, for the cancellation's message.
    last: Cell<Stage>,
}

impl<'a> Stages<'a> {
    pub(crate) fn new(observer: &'a dyn Progress) -> Self {
        Self {
            observer,
            current: Cell::new(None),
            last: Cell::new(Stage::Samples),
        }
    }

    /// The observer, for the workers' [`Tally`]s.
    pub(crate) fn observer(&self) -> &'a dyn Progress {
        self.observer
    }

    /// Finishes the current stage (if any) and starts `stage`, unless it is current already.
    pub(crate) fn enter(&self, stage: Stage, total: Option<usize>) {
        if self.current.get() == Some(stage) {
            return;
        }
        self.leave();
        self.observer.stage_started(stage, total);
        self.current.set(Some(stage));
        self.last.set(stage);
    }

    /// [`TpiError::Cancelled`] when the observer asks the run to stop, naming the current
    /// stage, or else the last one that ran (`samples` before any).
    pub(crate) fn check(&self) -> Result<(), TpiError> {
        if let Some(stage) = self.current.get() {
            self.last.set(stage);
        }
        if self.observer.cancelled() {
            return Err(TpiError::Cancelled {
                stage: self.last.get().name().to_string(),
            });
        }
        Ok(())
    }

    /// Finishes the current stage, if any.
    pub(crate) fn leave(&self) {
        if let Some(stage) = self.current.take() {
            self.observer.stage_finished(stage);
        }
    }
}

impl Drop for Stages<'_> {
    fn drop(&mut self) {
        self.leave();
    }
}

/// One worker's count of a stage's items, reported in chunks of [`PROGRESS_CHUNK`] and when
/// dropped. Made per rayon job (`map_init`) or once for a sequential loop.
pub(crate) struct Tally<'a> {
    observer: &'a dyn Progress,
    stage: Stage,
    count: usize,
}

impl<'a> Tally<'a> {
    pub(crate) fn new(observer: &'a dyn Progress, stage: Stage) -> Self {
        Self {
            observer,
            stage,
            count: 0,
        }
    }

    /// Counts `items` done.
    #[inline]
    pub(crate) fn add(&mut self, items: usize) {
        self.count += items;
        if self.count >= PROGRESS_CHUNK {
            self.flush();
        }
    }

    fn flush(&mut self) {
        if self.count > 0 {
            self.observer.advanced(self.stage, self.count);
            self.count = 0;
        }
    }
}

impl Drop for Tally<'_> {
    fn drop(&mut self) {
        self.flush();
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::Mutex;

    #[derive(Default)]
    struct Log(Mutex<Vec<String>>);

    impl Progress for Log {
        fn stage_started(&self, stage: Stage, total: Option<usize>) {
            if let Ok(mut l) = self.0.lock() {
                l.push(format!("start {} {total:?}", stage.name()));
            }
        }
        fn advanced(&self, stage: Stage, items: usize) {
            if let Ok(mut l) = self.0.lock() {
                l.push(format!("{} +{items}", stage.name()));
            }
        }
        fn stage_finished(&self, stage: Stage) {
            if let Ok(mut l) = self.0.lock() {
                l.push(format!("end {}", stage.name()));
            }
        }
    }

    fn log(l: Log) -> Vec<String> {
        l.0.into_inner().unwrap_or_default()
    }

    #[test]
    fn every_started_stage_is_finished_once_also_on_an_early_return() {
        let l = Log::default();
        {
            let stages = Stages::new(&l);
            stages.enter(Stage::Samples, Some(3));
            stages.enter(Stage::Delaunay, None);
            // Entering the current stage again changes nothing.
            stages.enter(Stage::Delaunay, None);
            stages.leave();
            stages.leave();
            stages.enter(Stage::Facets, Some(5));
            // Dropped inside the facets, as on an error returned by `?`.
        }
        assert_eq!(
            log(l),
            [
                "start samples Some(3)",
                "end samples",
                "start delaunay None",
                "end delaunay",
                "start facets Some(5)",
                "end facets"
            ]
        );
    }

    #[test]
    fn a_tally_reports_in_chunks_and_the_rest_when_dropped() {
        let l = Log::default();
        {
            let mut tally = Tally::new(&l, Stage::Mesh);
            for _ in 0..PROGRESS_CHUNK + 10 {
                tally.add(1);
            }
        }
        assert_eq!(
            log(l),
            [format!("mesh +{PROGRESS_CHUNK}"), "mesh +10".to_string()]
        );
    }
}
