//! The progress bar (indicatif): shown on a terminal, hidden when piped or with `--quiet`.

use std::io::IsTerminal;

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};

/// A bar over samples (elapsed time, ETA, samples per second), or over a time budget.
pub struct Progress {
    bar: ProgressBar,
    /// The bar's length is a time budget in ms, advanced by the clock.
    timed: bool,
}

impl Progress {
    /// A bar over `total` samples.
    pub fn new(total: u64, quiet: bool) -> Self {
        let template = "{elapsed_precise} [{wide_bar}] {percent:>3}%  {per_sec} samples  ETA {eta}";
        Self::with(total, template, quiet, false)
    }

    /// A bar over a time budget (its length in ms), advanced by the clock, not by samples.
    pub fn timed(budget: std::time::Duration, quiet: bool) -> Self {
        let ms = budget.as_millis().max(1) as u64;
        let template = "{elapsed_precise} [{wide_bar}] {percent:>3}% of the time budget";
        Self::with(ms, template, quiet, true)
    }

    fn with(length: u64, template: &str, quiet: bool, timed: bool) -> Self {
        let bar = ProgressBar::new(length);
        if quiet || !std::io::stderr().is_terminal() {
            bar.set_draw_target(ProgressDrawTarget::hidden());
        }
        if let Ok(style) = ProgressStyle::with_template(template) {
            bar.set_style(style.progress_chars("=> "));
        }
        Self { bar, timed }
    }

    /// Samples done (a timed bar shows the time spent instead).
    pub fn set(&self, done: u64) {
        if self.timed {
            let ms = self.bar.elapsed().as_millis() as u64;
            self.bar
                .set_position(ms.min(self.bar.length().unwrap_or(ms)));
        } else {
            self.bar.set_position(done);
        }
    }

    pub fn finish(&self) {
        self.bar.finish_and_clear();
    }
}
