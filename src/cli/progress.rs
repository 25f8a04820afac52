//! The progress bar (indicatif): shown on a terminal, hidden when piped or with `--quiet`.

use std::io::IsTerminal;

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};

/// A bar over `total` samples with elapsed time, ETA and samples per second.
pub struct Progress(ProgressBar);

impl Progress {
    pub fn new(total: u64, quiet: bool) -> Self {
        let bar = ProgressBar::new(total);
        if quiet || !std::io::stderr().is_terminal() {
            bar.set_draw_target(ProgressDrawTarget::hidden());
        }
        if let Ok(style) = ProgressStyle::with_template(
            "{elapsed_precise} [{wide_bar}] {percent:>3}%  {per_sec} samples  ETA {eta}",
        ) {
            bar.set_style(style.progress_chars("=> "));
        }
        Self(bar)
    }

    /// A bar over a time budget (its length in ms), advanced by the clock, not by samples.
    pub fn timed(budget: std::time::Duration, quiet: bool) -> Self {
        let bar = ProgressBar::new(budget.as_millis().max(1) as u64);
        if quiet || !std::io::stderr().is_terminal() {
            bar.set_draw_target(ProgressDrawTarget::hidden());
        }
        if let Ok(style) = ProgressStyle::with_template(
            "{elapsed_precise} [{wide_bar}] {percent:>3}% of the time budget",
        ) {
            bar.set_style(style.progress_chars("=> "));
        }
        bar.set_message("timed");
        Self(bar)
    }

    /// Samples done (a timed bar shows the time spent instead).
    pub fn set(&self, done: u64) {
        if self.0.length().is_some_and(|l| l > 0) && self.is_timed() {
            let ms = self.0.elapsed().as_millis() as u64;
            self.0.set_position(ms.min(self.0.length().unwrap_or(ms)));
        } else {
            self.0.set_position(done);
        }
    }

    fn is_timed(&self) -> bool {
        self.0.message() == "timed"
    }

    pub fn finish(&self) {
        self.0.finish_and_clear();
    }
}
