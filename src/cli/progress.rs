//! Progress display on a terminal for runs that last more than a second: a bar over simulated
//! time for one run, a bar over points for sweeps.

use std::io::IsTerminal;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex};
use std::time::Duration;

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};

/// Positions of the time bar: simulated time is shown in per-mille steps of the span.
const TICKS: u64 = 1000;

/// Shows progress on stderr after one second, only when stderr is a terminal and not `--quiet`.
pub(crate) struct Progress {
    bar: Option<ProgressBar>,
}

/// Keeps the display of a run alive (steady redraw of elapsed time and ETA) until dropped.
pub(crate) struct RunGuard {
    done: Arc<AtomicBool>,
    bar: Option<ProgressBar>,
}

impl Drop for RunGuard {
    fn drop(&mut self) {
        self.done.store(true, Ordering::SeqCst);
        if let Some(b) = &self.bar {
            b.finish_and_clear();
        }
    }
}

/// Decimals that show simulated times of a span `t_end` (s) to about four significant digits.
fn decimals(t_end: f64) -> usize {
    (3.0 - t_end.abs().log10().floor()).clamp(0.0, 12.0) as usize
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

    /// The display of one run over the simulated span [t0, t_end] (s): the callback to pass to
    /// the run (called with the simulated time) and a guard that clears the display when
    /// dropped. After one second the display appears: a bar with percent, `t of t_end`, elapsed
    /// time and ETA, or a spinner with t when the span is unknown. Built-in models that
    /// simulate twice (an ideal reference, then the clearance run) restart the bar and show
    /// `pass 2`.
    pub(crate) fn run(
        &self,
        span: Option<(f64, f64)>,
    ) -> (Box<dyn Fn(f64) + Send + Sync>, RunGuard) {
        let done = Arc::new(AtomicBool::new(false));
        let Some(bar) = self.bar.clone() else {
            return (Box::new(|_| {}), RunGuard { done, bar: None });
        };
        let template = match span {
            Some(_) => "{bar:40} {percent:>3}% t = {msg} [{elapsed}, eta {eta}]",
            None => "{spinner} simulating t = {msg} [{elapsed}]",
        };
        bar.set_style(
            ProgressStyle::with_template(template).unwrap_or_else(|_| ProgressStyle::default_bar()),
        );
        let dec = span.map_or(4, |(_, te)| decimals(te));
        // the end time to four significant digits without trailing zeros (0.2, not
        // 0.20000000000000007 or 0.2000)
        let te_text = span.map_or_else(String::new, |(_, te)| {
            let s = format!("{te:.dec$}");
            if s.contains('.') {
                s.trim_end_matches('0').trim_end_matches('.').to_string()
            } else {
                s
            }
        });
        if let Some((t0, _)) = span {
            bar.set_length(TICKS);
            bar.set_message(format!("{t0:.dec$} of {te_text} s"));
        } else {
            bar.set_message("…".to_string());
        }
        // show after one second unless the run is over by then
        let (d, b) = (done.clone(), bar.clone());
        std::thread::spawn(move || {
            std::thread::sleep(Duration::from_secs(1));
            if !d.load(Ordering::SeqCst) {
                Self::show(&b);
                b.enable_steady_tick(Duration::from_millis(200));
            }
        });
        // (last time reported, pass number)
        let state = Mutex::new((f64::NEG_INFINITY, 1usize));
        let b = bar.clone();
        let callback = move |t: f64| {
            let Ok(mut st) = state.lock() else {
                return;
            };
            if t < st.0 {
                st.1 += 1;
                b.reset_eta();
            }
            st.0 = t;
            let pass = if st.1 > 1 {
                format!(" (pass {})", st.1)
            } else {
                String::new()
            };
            match span {
                Some((t0, te)) => {
                    let f = ((t - t0) / (te - t0)).clamp(0.0, 1.0);
                    b.set_position((f * TICKS as f64).round() as u64);
                    b.set_message(format!("{t:.dec$} of {te_text} s{pass}"));
                }
                None => b.set_message(format!("{t:.dec$} s{pass}")),
            }
        };
        (
            Box::new(callback),
            RunGuard {
                done,
                bar: Some(bar),
            },
        )
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

#[cfg(test)]
mod tests {
    use super::decimals;

    /// Four significant digits: 0.5 s → 0.5000, 2e-3 s → 0.002000, 12 s → 12.00.
    #[test]
    fn time_decimals_follow_the_span() {
        assert_eq!(format!("{:.*}", decimals(0.5), 0.5), "0.5000");
        assert_eq!(format!("{:.*}", decimals(2e-3), 2e-3), "0.002000");
        assert_eq!(format!("{:.*}", decimals(12.0), 12.0), "12.00");
    }
}
