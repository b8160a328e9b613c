//! The progress of a run on the terminal: a bar over the steps (on stderr) and one line per
//! finished phase (on stdout), both silent with `--quiet`.

use super::summary::PhaseSummary;
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};

/// The bar and the phase lines.
pub(super) struct Progress {
    bar: ProgressBar,
    quiet: bool,
}

impl Progress {
    /// A bar over `total` steps (hidden when `quiet`).
    pub(super) fn new(total: usize, quiet: bool) -> Self {
        let bar = if quiet {
            ProgressBar::hidden()
        } else {
            ProgressBar::with_draw_target(Some(total as u64), ProgressDrawTarget::stderr())
        };
        bar.set_style(
            ProgressStyle::with_template(
                "{prefix} [{bar:30}] {pos}/{len} steps, {msg} ({elapsed})",
            )
            .unwrap_or_else(|_| ProgressStyle::default_bar())
            .progress_chars("=> "),
        );
        Self { bar, quiet }
    }

    /// A phase starts.
    pub(super) fn begin_phase(&self, name: &str) {
        self.bar.set_prefix(format!("phase `{name}`"));
    }

    /// A step is done at time `t` after `iterations` contact iterations.
    pub(super) fn step(&self, t: f64, iterations: usize) {
        self.bar
            .set_message(format!("t = {t:.4}, {iterations} iterations"));
        self.bar.inc(1);
    }

    /// A phase is done: its line, above the bar.
    pub(super) fn end_phase(&self, s: &PhaseSummary) {
        let line = format!(
            "phase `{}`: {} steps, t {} → {}: {} contact iterations, {} adhesion iterations, {} F* builds, {} stiffness changes, {:.3} s",
            s.name,
            s.steps,
            s.t_start,
            s.t_end,
            s.contact_iterations,
            s.adhesion_iterations,
            s.flexibility_builds,
            s.stiffness_changes,
            s.wall_time_s
        );
        self.line(&line);
    }

    /// A line above the bar (nothing when quiet).
    pub(super) fn line(&self, line: &str) {
        if !self.quiet {
            self.bar.suspend(|| crate::out::outln!("{line}"));
        }
    }

    /// The run is over (done or failed): the bar goes.
    pub(super) fn finish(&self) {
        self.bar.finish_and_clear();
    }
}
