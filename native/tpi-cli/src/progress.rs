//! Progress bars on stderr for long runs (indicatif), one per stage that runs.
//!
//! The command's own steps (reading the surface and the pattern, encoding and writing the
//! outputs, each only when it happens) and the core's stages ([`tpi_core::Stage`]: samples,
//! delaunay, neighbours, facets, mesh, report, as `tpi_core::discretise_with_progress`
//! reports them) each get a line under the previous ones. A stage whose total is known shows
//! a bar with count/total, percentage and estimated time left; one without a total a spinner
//! with the time it has taken. A finished stage keeps its line with its final count and
//! duration while the next runs.
//!
//! Drawn only when stderr is a terminal (and `TERM` is set and not `dumb`: indicatif's rule)
//! and only once the run has taken more than [`SHOW_AFTER`]; otherwise not a byte is written
//! (no carriage returns in logs or pipes). Everything is cleared when the run ends, before
//! the summary or the error message.

use std::borrow::Cow;
use std::io::IsTerminal;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Arc, Condvar, Mutex, RwLock};
use std::thread::JoinHandle;
use std::time::Duration;

use indicatif::{
    HumanCount, HumanDuration, MultiProgress, ProgressBar, ProgressDrawTarget, ProgressState,
    ProgressStyle,
};
use tpi_core::Stage;

/// Delay before anything is drawn.
pub(crate) const SHOW_AFTER: Duration = Duration::from_secs(1);

/// Environment variable overriding [`SHOW_AFTER`] in milliseconds (for tests: `0` draws at
/// once, still only on a terminal).
pub(crate) const DELAY_VARIABLE: &str = "TPI_PROGRESS_DELAY_MS";

/// How often a spinner turns (and a bar's elapsed time and estimate are redrawn when no work
/// is reported).
const TICK: Duration = Duration::from_millis(100);

/// Redraws per second at most.
const REFRESH_HZ: u8 = 10;

/// A stage with a known total: count/total (each as wide as the total), percentage,
/// estimate; what it works on, cut to the terminal's width, last.
const BAR_TEMPLATE: &str =
    "{prefix:>10} [{bar:24}] {human_pos:>WIDTH}/{human_len:<WIDTH} {percent:>3}% ETA {left:<5} {wide_msg}";
/// A finished stage with a total: its count and duration.
const BAR_DONE_TEMPLATE: &str =
    "{prefix:>10} [{bar:24}] {human_pos:>WIDTH}/{human_len:<WIDTH} {percent:>3}% in  {took:<5} {wide_msg}";
/// A stage without a total: a spinner and the time it has taken.
const SPINNER_TEMPLATE: &str = "{prefix:>10} {spinner} {took:<5} {wide_msg}";
/// The bar's characters: done, the current position, to do.
const BAR_CHARS: &str = "#>-";
/// The spinner's frames, then the finished state.
const SPINNER_CHARS: &str = "|/-\\+";
/// Times below this are shown in tenths of a second.
const TENTHS_BELOW: Duration = Duration::from_secs(10);

fn show_after() -> Duration {
    std::env::var(DELAY_VARIABLE)
        .ok()
        .and_then(|v| v.trim().parse::<u64>().ok())
        .map_or(SHOW_AFTER, Duration::from_millis)
}

/// A duration as `0.4s` below [`TENTHS_BELOW`], else as indicatif writes it (`12s`, `3m`).
fn write_duration(w: &mut dyn std::fmt::Write, d: Duration) {
    let _ = if d < TENTHS_BELOW {
        write!(w, "{:.1}s", d.as_secs_f64())
    } else {
        write!(w, "{:#}", HumanDuration(d))
    };
}

/// The style of a stage's line: a bar for `Some(total)`, a spinner otherwise; `done` for a
/// finished stage (its duration instead of the estimate).
fn style(total: Option<u64>, done: bool) -> ProgressStyle {
    let width = |total: u64| HumanCount(total).to_string().len().to_string();
    let template = match (total, done) {
        (Some(total), false) => BAR_TEMPLATE.replace("WIDTH", &width(total)),
        (Some(total), true) => BAR_DONE_TEMPLATE.replace("WIDTH", &width(total)),
        (None, _) => SPINNER_TEMPLATE.to_string(),
    };
    let fallback = match total {
        Some(_) => ProgressStyle::default_bar(),
        None => ProgressStyle::default_spinner(),
    };
    ProgressStyle::with_template(&template)
        .unwrap_or(fallback)
        .progress_chars(BAR_CHARS)
        .tick_chars(SPINNER_CHARS)
        // The time the stage took (finished) or has taken so far.
        .with_key(
            "took",
            |state: &ProgressState, w: &mut dyn std::fmt::Write| {
                let took = if state.is_finished() {
                    state.duration()
                } else {
                    state.elapsed()
                };
                write_duration(w, took);
            },
        )
        .with_key(
            "left",
            |state: &ProgressState, w: &mut dyn std::fmt::Write| {
                write_duration(w, state.eta());
            },
        )
}

struct Shared {
    multi: MultiProgress,
    /// Every bar made, kept until the end (a dropped bar would leave its line behind).
    bars: Mutex<Vec<ProgressBar>>,
    /// The bar of the stage that runs now.
    current: RwLock<Option<ProgressBar>>,
    /// Whether the run has ended (the display thread waits on it).
    done: Mutex<bool>,
    wake: Condvar,
}

impl Shared {
    /// The display's one thread: shows the bars once `delay` has passed (unless `delay` is
    /// zero: shown already), then redraws the current stage every [`TICK`] (its spinner, its
    /// time and estimate) until the run ends: one thread for the whole run, where
    /// indicatif's steady tick would start one per bar.
    fn run(&self, delay: Duration) {
        let wait = |timeout: Duration| -> bool {
            // Whether the run has ended.
            match self.done.lock() {
                Ok(done) => self
                    .wake
                    .wait_timeout_while(done, timeout, |done| !*done)
                    .map_or(true, |(done, _)| *done),
                Err(_) => true,
            }
        };
        if !delay.is_zero() {
            if wait(delay) {
                return;
            }
            self.show();
        }
        while !wait(TICK) {
            if let Ok(current) = self.current.read() {
                if let Some(bar) = current.as_ref() {
                    bar.tick();
                }
            }
        }
    }

    /// Shows everything made so far and draws from now on.
    fn show(&self) {
        self.multi
            .set_draw_target(ProgressDrawTarget::stderr_with_hz(REFRESH_HZ));
        if let Ok(bars) = self.bars.lock() {
            for bar in bars.iter() {
                bar.tick();
            }
        }
    }
}

/// The progress display of one command (inert when stderr is not a terminal).
pub(crate) struct Progress {
    shared: Option<Arc<Shared>>,
    timer: Option<JoinHandle<()>>,
}

impl Progress {
    /// Starts the display; inert unless stderr is a terminal. Nothing is drawn before the
    /// delay ([`SHOW_AFTER`], or [`DELAY_VARIABLE`]) has passed.
    pub(crate) fn start() -> Self {
        if !std::io::stderr().is_terminal() {
            return Self {
                shared: None,
                timer: None,
            };
        }
        let shared = Arc::new(Shared {
            multi: MultiProgress::with_draw_target(ProgressDrawTarget::hidden()),
            bars: Mutex::new(Vec::new()),
            current: RwLock::new(None),
            done: Mutex::new(false),
            wake: Condvar::new(),
        });
        let delay = show_after();
        if delay.is_zero() {
            shared.show();
        }
        let worker = Arc::clone(&shared);
        let timer = std::thread::Builder::new()
            .name("tpi-progress".into())
            .spawn(move || worker.run(delay))
            .ok();
        Self {
            shared: Some(shared),
            timer,
        }
    }

    /// Finishes the current stage (if any) and starts the next, `name` with `total` work items
    /// where known (a bar), else a spinner; `message` says what it works on.
    pub(crate) fn stage(
        &self,
        name: &str,
        total: Option<u64>,
        message: impl Into<Cow<'static, str>>,
    ) {
        let Some(shared) = &self.shared else {
            return;
        };
        self.end_stage();
        let bar = match total {
            Some(total) => shared.multi.add(ProgressBar::new(total)),
            None => shared.multi.add(ProgressBar::new_spinner()),
        };
        bar.set_style(style(total, false));
        bar.set_prefix(name.to_string());
        bar.set_message(message);
        if let Ok(mut bars) = shared.bars.lock() {
            bars.push(bar.clone());
        }
        if let Ok(mut current) = shared.current.write() {
            *current = Some(bar);
        }
    }

    /// `items` more work items of the current stage are done.
    pub(crate) fn advance(&self, items: u64) {
        if let Some(shared) = &self.shared {
            if let Ok(current) = shared.current.read() {
                if let Some(bar) = current.as_ref() {
                    bar.inc(items);
                }
            }
        }
    }

    /// Says what the current stage works on now.
    pub(crate) fn message(&self, message: impl Into<Cow<'static, str>>) {
        if let Some(shared) = &self.shared {
            if let Ok(current) = shared.current.read() {
                if let Some(bar) = current.as_ref() {
                    bar.set_message(message);
                }
            }
        }
    }

    /// Finishes the current stage: its line stays with its final count and duration.
    pub(crate) fn end_stage(&self) {
        let Some(shared) = &self.shared else {
            return;
        };
        let bar = shared.current.write().ok().and_then(|mut c| c.take());
        if let Some(bar) = bar {
            bar.set_style(style(bar.length(), true));
            // The count as reached, not forced to the total.
            bar.abandon();
        }
    }

    /// Stops drawing and clears every line.
    pub(crate) fn finish(mut self) {
        self.stop();
    }

    fn stop(&mut self) {
        let Some(shared) = self.shared.take() else {
            return;
        };
        if let Ok(mut done) = shared.done.lock() {
            *done = true;
        }
        shared.wake.notify_all();
        if let Some(timer) = self.timer.take() {
            let _ = timer.join();
        }
        let _ = shared.multi.clear();
        shared.multi.set_draw_target(ProgressDrawTarget::hidden());
    }
}

impl Drop for Progress {
    fn drop(&mut self) {
        self.stop();
    }
}

/// The discretisations a pattern made on a surface runs (a fit's tens, a relaxation's one per
/// iteration), shown as the message of the command's current stage (`pattern`, `fit`):
/// "LABEL: run K, STAGE". A line per run and stage would scroll a fit's hundreds of stages
/// by; the one line says that it is alive and how far it is.
pub(crate) struct PatternRuns<'a> {
    progress: &'a Progress,
    label: String,
    runs: AtomicUsize,
}

impl<'a> PatternRuns<'a> {
    /// Reports to `progress`'s current stage, each message starting with `label`.
    pub(crate) fn new(progress: &'a Progress, label: impl Into<String>) -> Self {
        Self {
            progress,
            label: label.into(),
            runs: AtomicUsize::new(0),
        }
    }
}

impl tpi_core::Progress for PatternRuns<'_> {
    fn stage_started(&self, stage: Stage, _total: Option<usize>) {
        let run = if stage == Stage::Samples {
            self.runs.fetch_add(1, Ordering::SeqCst) + 1
        } else {
            self.runs.load(Ordering::SeqCst)
        };
        self.progress
            .message(format!("{}: run {run}, {}", self.label, stage.name()));
    }
}

/// The core reports its stages to the same display.
impl tpi_core::Progress for Progress {
    fn stage_started(&self, stage: Stage, total: Option<usize>) {
        self.stage(stage.name(), total.map(|t| t as u64), "");
    }

    fn advanced(&self, _stage: Stage, items: usize) {
        self.advance(items as u64);
    }

    fn stage_finished(&self, _stage: Stage) {
        self.end_stage();
    }
}
