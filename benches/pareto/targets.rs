//! The host cost targets of issue 12: a batch of [`BATCH`] `f32` values (2 Hz, ζ 0.3 and
//! 1, at 60, 120 and 1000 Hz), stepped frame by frame, every implementation timed in the
//! same run (interleaved) and counted by callgrind (instructions inside the stepping loop
//! only, per value step).
//!
//! | implementation | what steps a frame |
//! |---|---|
//! | `minimal` | `lab::pareto::MinimalBatch`: `u = r·u − k·x; x += u` over two `f32` arrays, coefficients hoisted |
//! | `value/advance` | `SpringValue::<f32, 1>::advance` on each of 1000 values (no rest test) |
//! | `value/step` | `SpringValue::<f32, 1>::step` on each (rest test on, with a threshold nothing reaches) |
//! | `batch/advance` | `SpringBatch::<f32, 1, 1000>::advance` (no rest test) |
//! | `batch/step` | `SpringBatch::<f32, 1, 1000>::step` (rest test on, never reached) |
//! | `damped-springs` | `Spring::<f32>::update` on each, one precomputed `SpringTimeStep` |
//! | `animato/semi-implicit-euler` | animato-spring's `Spring::update(dt)` on each |
//!
//! The error is the worst `|x − x(t)|` over every value and frame, relative to each
//! value's distance to its target, against the analytic solution (`lab::reference`).

use lab::measure::Candidate;
use lab::pareto::{
    AnimatoBatch, BATCH, BatchRunner, BatchScene, DampedBatch, FREQUENCY, MinimalBatch,
    batch_candidate, batch_count, batch_error,
};
use std::hint::black_box;
use stiffspring::{BatchIndex, RestThreshold, SpringBatch, SpringValue, Tuning};

/// The implementations, in the order of the table.
pub const IMPLEMENTATIONS: [&str; 7] = [
    "minimal",
    "value/advance",
    "value/step",
    "batch/advance",
    "batch/step",
    "damped-springs",
    "animato/semi-implicit-euler",
];

/// What to do with a runner once it is built (a generic method, so that every runner's
/// frame loop is monomorphised and inlined into its timing and counting loops).
pub trait Visit {
    /// Called with the implementation's name, its bytes of state per value, and the
    /// runner at the scene's start.
    fn visit<R: BatchRunner + 'static>(&mut self, name: &'static str, bytes: usize, r: R);
}

/// Builds implementation `which` (an index into [`IMPLEMENTATIONS`]) on `scene` and
/// hands it to `v`; every implementation when `which` is `None`.
pub fn each(scene: &BatchScene, which: Option<usize>, v: &mut impl Visit) {
    let wanted = |i: usize| which.is_none_or(|w| w == i);
    let name = |i: usize| IMPLEMENTATIONS[i];
    if wanted(0) {
        v.visit(name(0), 8, MinimalBatch::new(scene));
    }
    let value_bytes = size_of::<SpringValue<f32, 1>>();
    if wanted(1) {
        v.visit(name(1), value_bytes, Values::<false>::new(scene));
    }
    if wanted(2) {
        v.visit(name(2), value_bytes, Values::<true>::new(scene));
    }
    let batch_bytes = size_of::<SpringBatch<f32, 1, BATCH>>() / BATCH;
    if wanted(3) {
        v.visit(name(3), batch_bytes, Batch::<false>::new(scene));
    }
    if wanted(4) {
        v.visit(name(4), batch_bytes, Batch::<true>::new(scene));
    }
    if wanted(5) {
        v.visit(
            name(5),
            DampedBatch::BYTES_PER_VALUE,
            DampedBatch::new(scene),
        );
    }
    if wanted(6) {
        v.visit(
            name(6),
            AnimatoBatch::BYTES_PER_VALUE,
            AnimatoBatch::new(scene),
        );
    }
}

/// The tuning of the scene (the exact map) and a rest threshold nothing reaches.
fn tuning(scene: &BatchScene) -> (Tuning, RestThreshold) {
    (
        Tuning::from_frequency(FREQUENCY, scene.zeta, scene.dt()).expect("valid scene"),
        RestThreshold::new(1e-30, 1e-30).expect("positive"),
    )
}

/// 1000 `SpringValue`s, each stepped with `step` (`REST`) or `advance`.
pub struct Values<const REST: bool> {
    start: Vec<SpringValue<f32, 1>>,
    values: Vec<SpringValue<f32, 1>>,
}

impl<const REST: bool> Values<REST> {
    fn new(scene: &BatchScene) -> Self {
        let (tuning, never) = tuning(scene);
        let values: Vec<_> = scene
            .targets()
            .iter()
            .map(|&t| {
                let mut v = SpringValue::<f32, 1>::new([0.0], &tuning)
                    .expect("valid")
                    .with_rest_threshold(never);
                v.set_target([t as f32]);
                v
            })
            .collect();
        Values {
            start: values.clone(),
            values,
        }
    }
}

impl<const REST: bool> BatchRunner for Values<REST> {
    fn reset(&mut self) {
        self.values.clone_from(&self.start);
    }
    #[inline(always)]
    fn frame(&mut self) {
        for v in self.values.iter_mut() {
            if REST {
                let _ = black_box(v.step());
            } else {
                v.advance();
            }
        }
    }
    fn offset(&self, i: usize) -> f64 {
        self.values[i].offset()[0] as f64
    }
}

/// One `SpringBatch<f32, 1, 1000>`, stepped with `step` (`REST`) or `advance`.
pub struct Batch<const REST: bool> {
    start: Box<SpringBatch<f32, 1, BATCH>>,
    batch: Box<SpringBatch<f32, 1, BATCH>>,
    ids: Vec<BatchIndex>,
}

impl<const REST: bool> Batch<REST> {
    fn new(scene: &BatchScene) -> Self {
        let (tuning, never) = tuning(scene);
        let mut batch = Box::new(
            SpringBatch::<f32, 1, BATCH>::new(&tuning)
                .expect("valid")
                .with_rest_threshold(never),
        );
        let ids: Vec<_> = scene
            .targets()
            .iter()
            .map(|&t| {
                let i = batch.push([0.0]).expect("room");
                batch.set_target(i, [t as f32]);
                i
            })
            .collect();
        Batch {
            start: batch.clone(),
            batch,
            ids,
        }
    }
}

impl<const REST: bool> BatchRunner for Batch<REST> {
    fn reset(&mut self) {
        self.batch.clone_from(&self.start);
    }
    #[inline(always)]
    fn frame(&mut self) {
        if REST {
            let _ = black_box(self.batch.step());
        } else {
            self.batch.advance();
        }
    }
    fn offset(&self, i: usize) -> f64 {
        let id = self.ids[i];
        match (self.batch.position(id), self.batch.target(id)) {
            (Some([p]), Some([t])) => p as f64 - t as f64,
            _ => f64::NAN,
        }
    }
}

/// One implementation on one scene, before timing.
pub struct Pending {
    /// The implementation.
    pub implementation: &'static str,
    /// Bytes of state per value.
    pub bytes: usize,
    /// The worst relative error over the run.
    pub error: f64,
    /// The timing closure (per value step).
    pub candidate: Candidate<'static>,
}

/// Collects [`Pending`] rows.
pub struct Collect<'a>(pub &'a BatchScene, pub Vec<Pending>);

impl Visit for Collect<'_> {
    fn visit<R: BatchRunner + 'static>(&mut self, name: &'static str, bytes: usize, mut r: R) {
        let error = batch_error(&mut r, self.0);
        self.1.push(Pending {
            implementation: name,
            bytes,
            error,
            candidate: batch_candidate(self.0, r),
        });
    }
}

/// Runs one run of the runner inside `lab::measure::counted` (the callgrind child).
pub struct Count<'a>(pub &'a BatchScene);

impl Visit for Count<'_> {
    fn visit<R: BatchRunner + 'static>(&mut self, _: &'static str, _: usize, mut r: R) {
        batch_count(self.0, &mut r);
    }
}
