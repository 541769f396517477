//! A progress line on stderr for long runs.
//!
//! Drawn only when stderr is a terminal and only once the run has taken more than one
//! second; otherwise nothing at all is written (no carriage returns in logs or pipes).
//! The core's stages report no fractions, so the bar counts the CLI's steps (read,
//! pattern, discretise, render, write) and a spinner with the elapsed time shows that the
//! current step is alive. The line is cleared when the run ends.

use std::io::{IsTerminal, Write};
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::{Arc, Mutex};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

/// Delay before anything is drawn.
pub(crate) const SHOW_AFTER: Duration = Duration::from_secs(1);

/// Environment variable overriding [`SHOW_AFTER`] in milliseconds (for tests: `0` draws at
/// once, still only on a terminal).
pub(crate) const DELAY_VARIABLE: &str = "TPI_PROGRESS_DELAY_MS";

fn show_after() -> Duration {
    std::env::var(DELAY_VARIABLE)
        .ok()
        .and_then(|v| v.trim().parse::<u64>().ok())
        .map_or(SHOW_AFTER, Duration::from_millis)
}

struct Shared {
    start: Instant,
    delay: Duration,
    total: usize,
    step: AtomicUsize,
    label: Mutex<String>,
    done: AtomicBool,
}

/// A progress line (inert when stderr is not a terminal).
pub(crate) struct Progress {
    shared: Option<Arc<Shared>>,
    thread: Option<JoinHandle<()>>,
}

impl Progress {
    /// Starts a progress line of `total` steps; inert unless stderr is a terminal.
    pub(crate) fn start(total: usize) -> Self {
        if !std::io::stderr().is_terminal() {
            return Self {
                shared: None,
                thread: None,
            };
        }
        let shared = Arc::new(Shared {
            start: Instant::now(),
            delay: show_after(),
            total: total.max(1),
            step: AtomicUsize::new(0),
            label: Mutex::new(String::new()),
            done: AtomicBool::new(false),
        });
        let worker = Arc::clone(&shared);
        let thread = std::thread::Builder::new()
            .name("tpi-progress".into())
            .spawn(move || draw_loop(&worker))
            .ok();
        Self {
            shared: Some(shared),
            thread,
        }
    }

    /// Enters the next step, described by `label`.
    pub(crate) fn step(&self, label: impl Into<String>) {
        if let Some(s) = &self.shared {
            if let Ok(mut l) = s.label.lock() {
                *l = label.into();
            }
            s.step.fetch_add(1, Ordering::Relaxed);
        }
    }

    /// Stops drawing and clears the line.
    pub(crate) fn finish(mut self) {
        self.stop();
    }

    fn stop(&mut self) {
        if let Some(s) = &self.shared {
            s.done.store(true, Ordering::Relaxed);
        }
        if let Some(t) = self.thread.take() {
            t.thread().unpark();
            let _ = t.join();
        }
    }
}

impl Drop for Progress {
    fn drop(&mut self) {
        self.stop();
    }
}

const SPINNER: [char; 4] = ['|', '/', '-', '\\'];
const WIDTH: usize = 20;

fn draw_loop(s: &Shared) {
    let mut drawn = false;
    let mut tick = 0usize;
    loop {
        let elapsed = s.start.elapsed();
        if s.done.load(Ordering::Relaxed) {
            break;
        }
        if elapsed < s.delay {
            std::thread::park_timeout(s.delay - elapsed);
            continue;
        }
        let step = s.step.load(Ordering::Relaxed).clamp(1, s.total);
        let label = s.label.lock().map(|l| l.clone()).unwrap_or_default();
        let filled = (step - 1) * WIDTH / s.total;
        let bar: String = (0..WIDTH)
            .map(|i| {
                if i < filled {
                    '#'
                } else if i == filled {
                    SPINNER[tick % 4]
                } else {
                    '.'
                }
            })
            .collect();
        let line = format!(
            "tpi [{bar}] {step}/{} {label} {:.1} s",
            s.total,
            elapsed.as_secs_f64()
        );
        let mut err = std::io::stderr().lock();
        let _ = write!(err, "\r\x1b[2K{line}");
        let _ = err.flush();
        drawn = true;
        tick += 1;
        std::thread::park_timeout(Duration::from_millis(100));
    }
    if drawn {
        let mut err = std::io::stderr().lock();
        let _ = write!(err, "\r\x1b[2K");
        let _ = err.flush();
    }
}
