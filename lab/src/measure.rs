//! Run time on a noisy machine: every candidate of a scene is timed in the same process,
//! in batches interleaved round-robin, and each reports the median of its batches.
//!
//! Interleaving is what makes the *ratios* hold when the machine is shared: a burst of
//! load from another process slows the batches that run during it, which belong to every
//! candidate in turn, and the median of each candidate then drops the slowed batches.
//! Absolute nanoseconds still move from run to run; compare ratios from one run.
//!
//! Used by `benches/pareto` and the tour (`examples/tour/bench.rs`).

use std::time::{Duration, Instant};

/// One thing to time: a closure that performs `runs` repetitions of a scene run of
/// `steps_per_run` steps. It is called through a `dyn` pointer once per batch; the steps
/// inside it are monomorphised and inlined.
pub struct Candidate<'a> {
    /// Steps in one run of the scene.
    pub steps_per_run: usize,
    /// What one step is divided by for the report: 1 for a value, the number of
    /// springs for a network (ns per spring step).
    pub units_per_step: usize,
    /// Performs `runs` runs.
    pub batch: Box<dyn FnMut(usize) + 'a>,
}

impl<'a> Candidate<'a> {
    /// A candidate stepping one value (or one knob) per step.
    pub fn new(steps_per_run: usize, batch: impl FnMut(usize) + 'a) -> Self {
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
    let n = candidates.len();
    let mut runs = vec![1usize; n];
    for (c, r) in candidates.iter_mut().zip(runs.iter_mut()) {
        (c.batch)(1);
        let mut best = Duration::MAX;
        for _ in 0..3 {
            let t = Instant::now();
            (c.batch)(1);
            best = best.min(t.elapsed());
        }
        let per_run = best.as_nanos().max(1) as f64;
        *r = ((plan.batch.as_nanos() as f64 / per_run).ceil() as usize).clamp(1, 1 << 24);
    }
    let mut samples: Vec<Vec<f64>> = vec![Vec::with_capacity(plan.rounds); n];
    for round in 0..plan.rounds {
        for k in 0..n {
            let i = (k + round) % n;
            let c = &mut candidates[i];
            let t = Instant::now();
            (c.batch)(runs[i]);
            let ns = t.elapsed().as_nanos() as f64;
            let units = (runs[i] * c.steps_per_run * c.units_per_step) as f64;
            samples[i].push(ns / units);
        }
    }
    samples.into_iter().map(median).collect()
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
