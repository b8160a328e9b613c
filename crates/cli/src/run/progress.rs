//! The progress of a run: on a terminal, a bar over the steps (on stderr); into a log (stderr
//! not a terminal), one line per tenth of the steps and at least every [`LOG_EVERY_S`] seconds
//! (on stderr too); and one line per finished phase (on stdout). Every path (dense, active
//! set, matrix-free; 2D and 3D) reports the same way. All silent with `--quiet`.

use super::summary::PhaseSummary;
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::cell::{Cell, RefCell};
use std::io::IsTerminal;
use std::time::Instant;

/// Longest wait between two progress lines in a log, in seconds.
const LOG_EVERY_S: f64 = 10.0;

/// The bar (or the log lines) and the phase lines.
pub(super) struct Progress {
    bar: ProgressBar,
    quiet: bool,
    /// Log lines instead of the bar: stderr is not a terminal.
    log: bool,
    total: usize,
    done: Cell<usize>,
    phase: RefCell<String>,
    start: Instant,
    last_line: Cell<f64>,
}

impl Progress {
    /// A bar over `total` steps (hidden when `quiet`, or when stderr is not a terminal: log
    /// lines then).
    pub(super) fn new(total: usize, quiet: bool) -> Self {
        let log = !quiet && !std::io::stderr().is_terminal();
        let bar = if quiet || log {
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
        Self {
            bar,
            quiet,
            log,
            total,
            done: Cell::new(0),
            phase: RefCell::new(String::new()),
            start: Instant::now(),
            last_line: Cell::new(0.0),
        }
    }

    /// A phase starts.
    pub(super) fn begin_phase(&self, name: &str) {
        self.bar.set_prefix(format!("phase `{name}`"));
        *self.phase.borrow_mut() = name.to_string();
    }

    /// A step is done at time `t` after `iterations` contact iterations, solved by `path`
    /// (`dense`, `active set`, `matrix-free`).
    pub(super) fn step(&self, t: f64, iterations: usize, path: &str) {
        let msg = format!("t = {t:.4}, {iterations} iterations, {path}");
        self.bar.set_message(msg.clone());
        self.bar.inc(1);
        let k = self.done.get() + 1;
        self.done.set(k);
        if !self.log {
            return;
        }
        let now = self.start.elapsed().as_secs_f64();
        let tenth = self.total.div_ceil(10).max(1);
        if k.is_multiple_of(tenth) || k == self.total || now - self.last_line.get() >= LOG_EVERY_S {
            self.last_line.set(now);
            eprintln!(
                "progress: step {k}/{} (phase `{}`): {msg}, {now:.1} s",
                self.total,
                self.phase.borrow()
            );
        }
    }

    /// A phase is done: its line, above the bar (with the counters of its dimension's
    /// summary: `F*` builds in 2D, penetration-check passes and factorisations in 3D).
    pub(super) fn end_phase<const D: usize>(&self, s: &PhaseSummary<D>) {
        let (c, t) = (&s.counters, &s.totals);
        let work = if D == 2 {
            format!(
                "{} contact iterations, {} adhesion iterations, {} F* builds, {} stiffness changes",
                c.contact_iterations,
                c.adhesion_iterations,
                c.flexibility_builds,
                c.stiffness_changes
            )
        } else {
            format!(
                "{} contact iterations, {} adhesion iterations, {} active-set passes, {} \
                 factorisations",
                t.contact_iterations,
                t.adhesion_iterations,
                t.passes,
                t.factorizations()
            )
        };
        self.line(&format!(
            "phase `{}`: {} steps, t {} → {}: {work}, {:.3} s",
            s.name, s.steps, s.t_start, s.t_end, s.wall_time_s
        ));
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

/// How a step was solved, for the progress lines.
pub(super) fn path_name(rep: &contact_solver::StepReport) -> &'static str {
    rep.path.path.name()
}
