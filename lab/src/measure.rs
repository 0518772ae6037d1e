//! Run time on a noisy machine: every candidate of a scene is timed in the same process,
//! in batches interleaved round-robin, and each reports the median of its batches.
//!
//! Interleaving is what makes the *ratios* hold when the machine is shared: a burst of
//! load from another process slows the batches that run during it, which belong to every
//! candidate in turn, and the median (or the fastest batch) of each candidate then drops
//! the slowed batches. Absolute nanoseconds still move from run to run; compare ratios
//! from one run.
//!
//! Instruction counts: [`callgrind`] runs a program under Valgrind's callgrind and
//! counts the instructions executed inside [`counted`] only (what a closure passed to it
//! runs), so that set-up, resets and reports are left out. The count is exact and the
//! same from run to run; it is the host's (x86-64) instruction count, not cycles.
//!
//! Used by `benches/pareto` and the tour (`examples/tour/bench.rs`).

use std::path::Path;
use std::process::Command;
use std::time::{Duration, Instant};

/// One thing to time: a closure that performs `runs` repetitions of a scene run of
/// `steps_per_run` steps and returns how long they took. It is called through a `dyn`
/// pointer once per batch; the steps inside it are monomorphised and inlined.
pub struct Candidate<'a> {
    /// Steps in one run of the scene.
    pub steps_per_run: usize,
    /// What one step is divided by for the report: 1 for a value, the number of
    /// springs for a network (ns per spring step), the number of values of a batch.
    pub units_per_step: usize,
    /// Performs `runs` runs and returns the time they took.
    pub batch: Box<dyn FnMut(usize) -> Duration + 'a>,
}

impl<'a> Candidate<'a> {
    /// A candidate stepping one value (or one knob) per step; the whole call is timed.
    pub fn new(steps_per_run: usize, mut batch: impl FnMut(usize) + 'a) -> Self {
        Candidate {
            steps_per_run,
            units_per_step: 1,
            batch: Box::new(move |runs| {
                let t = Instant::now();
                batch(runs);
                t.elapsed()
            }),
        }
    }

    /// A candidate that times itself: `batch(runs)` performs the runs and returns the time
    /// of the part that counts (the steps, without the resets between runs, whose cost
    /// depends on the size of the state and not on the step).
    pub fn self_timed(steps_per_run: usize, batch: impl FnMut(usize) -> Duration + 'a) -> Self {
        Candidate {
            steps_per_run,
            units_per_step: 1,
            batch: Box::new(batch),
        }
    }

    /// The same candidate, reported per spring of a step that moves `springs` springs.
    pub fn per(mut self, springs: usize) -> Self {
        self.units_per_step = springs.max(1);
        self
    }
}

/// How long and how often to measure.
#[derive(Clone, Copy, Debug)]
pub struct Plan {
    /// Each batch runs at least this long (the run count is calibrated once).
    pub batch: Duration,
    /// Batches per candidate; the median of them is reported.
    pub rounds: usize,
}

/// Median nanoseconds per unit step of every candidate, measured interleaved.
///
/// Calibration runs each candidate once (a warm-up that also pages in its code and data)
/// and then times single runs to choose how many runs fill a batch. The rounds then visit
/// the candidates in a rotated order, so that no candidate always follows the same one.
pub fn medians(candidates: &mut [Candidate<'_>], plan: Plan) -> Vec<f64> {
    samples(candidates, plan).into_iter().map(median).collect()
}

/// The fastest batch of every candidate, in nanoseconds per unit step, measured
/// interleaved as [`medians`] does.
///
/// On a machine shared with other jobs, a batch can only be slowed down by them: the
/// fastest batch is the least disturbed one, and it moves far less from run to run than
/// the median when the load is heavy (more runnable jobs than cores).
pub fn fastest(candidates: &mut [Candidate<'_>], plan: Plan) -> Vec<f64> {
    samples(candidates, plan)
        .into_iter()
        .map(|v| v.into_iter().fold(f64::NAN, f64::min))
        .collect()
}

/// Every batch's nanoseconds per unit step, per candidate.
fn samples(candidates: &mut [Candidate<'_>], plan: Plan) -> Vec<Vec<f64>> {
    let n = candidates.len();
    let mut runs = vec![1usize; n];
    for (c, r) in candidates.iter_mut().zip(runs.iter_mut()) {
        (c.batch)(1);
        let mut best = Duration::MAX;
        for _ in 0..3 {
            best = best.min((c.batch)(1));
        }
        let per_run = best.as_nanos().max(1) as f64;
        *r = ((plan.batch.as_nanos() as f64 / per_run).ceil() as usize).clamp(1, 1 << 24);
    }
    let mut samples: Vec<Vec<f64>> = vec![Vec::with_capacity(plan.rounds); n];
    for round in 0..plan.rounds {
        for k in 0..n {
            let i = (k + round) % n;
            let c = &mut candidates[i];
            let ns = (c.batch)(runs[i]).as_nanos() as f64;
            let units = (runs[i] * c.steps_per_run * c.units_per_step) as f64;
            samples[i].push(ns / units);
        }
    }
    samples
}

/// The median (the mean of the two middle values for an even count).
pub fn median(mut v: Vec<f64>) -> f64 {
    if v.is_empty() {
        return f64::NAN;
    }
    v.sort_by(f64::total_cmp);
    let m = v.len() / 2;
    if v.len() % 2 == 1 {
        v[m]
    } else {
        0.5 * (v[m - 1] + v[m])
    }
}

/// Runs `work` once. Under [`callgrind`] only the instructions executed inside this
/// function are counted; it is never inlined, so that it stays a function to toggle on.
#[inline(never)]
pub fn counted(work: &mut dyn FnMut()) {
    work();
    std::hint::black_box(());
}

/// The symbol pattern of [`counted`] for callgrind's `--toggle-collect`.
pub const COUNTED: &str = "*lab::measure::counted*";

/// The number of instructions executed inside [`counted`] when `program` runs with
/// `args` under callgrind:
///
/// ```text
/// valgrind --tool=callgrind --toggle-collect='*lab::measure::counted*' \
///     --callgrind-out-file=<out> <program> <args>
/// ```
///
/// `None` when Valgrind is not installed or the run fails (the caller reports the count
/// as missing). The output file goes to `out`.
pub fn callgrind(program: &Path, args: &[String], out: &Path) -> Option<u64> {
    let status = Command::new("valgrind")
        .arg("--tool=callgrind")
        .arg(format!("--toggle-collect={COUNTED}"))
        .arg(format!("--callgrind-out-file={}", out.display()))
        .arg(program)
        .args(args)
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::null())
        .status()
        .ok()?;
    if !status.success() {
        return None;
    }
    let text = std::fs::read_to_string(out).ok()?;
    // `totals:` is the sum over the run of the events collected (Ir, the instructions).
    text.lines()
        .find_map(|l| l.strip_prefix("totals:"))
        .or_else(|| text.lines().find_map(|l| l.strip_prefix("summary:")))
        .and_then(|v| v.split_whitespace().next()?.parse().ok())
}
