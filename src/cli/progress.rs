//! A progress bar on a terminal for runs that last more than a second.

use std::io::IsTerminal;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use std::time::Duration;

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};

/// Shows progress on stderr after one second, only when stderr is a terminal and not `--quiet`.
pub(crate) struct Progress {
    bar: Option<ProgressBar>,
}

/// Keeps a spinner alive while a run without progress callbacks is going.
pub(crate) struct SpinnerGuard {
    done: Arc<AtomicBool>,
    bar: Option<ProgressBar>,
}

impl Drop for SpinnerGuard {
    fn drop(&mut self) {
        self.done.store(true, Ordering::SeqCst);
        if let Some(b) = &self.bar {
            b.finish_and_clear();
        }
    }
}

impl Progress {
    pub(crate) fn new(quiet: bool) -> Self {
        let enabled = !quiet && std::io::stderr().is_terminal();
        Self {
            bar: enabled.then(|| ProgressBar::with_draw_target(None, ProgressDrawTarget::hidden())),
        }
    }

    fn show(bar: &ProgressBar) {
        if bar.is_hidden() {
            bar.set_draw_target(ProgressDrawTarget::stderr());
        }
    }

    /// A callback for clr-models runs, called with the simulated time (s): shown as the
    /// spinner's message (see [`Progress::spinner`]).
    pub(crate) fn callback(&self, t_end: Option<f64>) -> Box<dyn Fn(f64) + Send + Sync> {
        let Some(bar) = self.bar.clone() else {
            return Box::new(|_| {});
        };
        Box::new(move |t| match t_end {
            Some(te) => bar.set_message(format!("t = {t:.4} s of {te} s")),
            None => bar.set_message(format!("t = {t:.4} s")),
        })
    }

    /// A spinner with the elapsed time (and the simulated time when the model reports it),
    /// shown after one second. clr-mbd runs report no intermediate progress, so a bar over
    /// simulated time cannot advance during a run; the spinner shows the run is alive.
    pub(crate) fn spinner(&self) -> SpinnerGuard {
        let done = Arc::new(AtomicBool::new(false));
        if let Some(bar) = self.bar.clone() {
            let d = done.clone();
            let b = bar.clone();
            std::thread::spawn(move || {
                std::thread::sleep(Duration::from_secs(1));
                if !d.load(Ordering::SeqCst) {
                    b.set_style(
                        ProgressStyle::with_template("{spinner} simulating {msg} [{elapsed}]")
                            .unwrap_or_else(|_| ProgressStyle::default_spinner()),
                    );
                    Self::show(&b);
                    b.enable_steady_tick(Duration::from_millis(120));
                }
            });
            return SpinnerGuard {
                done,
                bar: Some(bar),
            };
        }
        SpinnerGuard { done, bar: None }
    }

    /// A bar over `n` sweep points.
    pub(crate) fn points(&self, n: u64) -> Option<ProgressBar> {
        let bar = self.bar.clone()?;
        bar.set_length(n);
        bar.set_style(
            ProgressStyle::with_template("{bar:40} {pos}/{len} points [{elapsed}, eta {eta}]")
                .unwrap_or_else(|_| ProgressStyle::default_bar()),
        );
        Self::show(&bar);
        Some(bar)
    }

    pub(crate) fn finish(&self) {
        if let Some(b) = &self.bar {
            b.finish_and_clear();
        }
    }
}
