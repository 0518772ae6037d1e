//! A state-machine property test of a value and a batch: random sequences of their calls,
//! mostly valid and sometimes not (NaN, infinities, huge, stale indices, a full batch),
//! with the invariants checked after every one.
//!
//! - The infallible setters never fail: NaN is ignored (nothing changes), anything else
//!   saturates to `±Scalar::MAX`, and the target is what was asked (saturated).
//! - A `try_` setter, `set_tuning` or a push that fails leaves everything as it was.
//! - Every read is finite; a step that reports `Settled` leaves the value on its target, a
//!   step that reports `Resting` changes nothing.
//! - A batch's length matches a shadow list of live indices; a removed index reads `None`,
//!   is ignored by the infallible setters (no live value moves), and is `Error::Stale` for
//!   the `try_` ones; a step reports as many moving values as are awake, and the values it
//!   names as settled are live and on their targets.
//!
//! `cargo test --release --test value_state_machine` runs 64 sequences per backend;
//! `PROPTEST_CASES=5000 cargo test --release --test value_state_machine` is a longer run.

use proptest::prelude::*;
use stiffspring::{
    BatchIndex, Error, I16F16, I32F32, Motion, Parameter, Scalar, SpringBatch, SpringValue, Tuning,
};

mod support;
use support::{from, number};

const DT: f64 = 1.0 / 60.0;
const N: usize = 4;

#[derive(Clone, Debug)]
enum Op {
    Target(f64, f64),
    TryTarget(f64, f64),
    Position(f64, f64),
    TryPosition(f64, f64),
    Fling(f64, f64),
    TryFling(f64, f64),
    Rate(f64),
    Retune(f64, f64),
    Step(u16),
    Advance(u16),
    Push(f64, f64),
    Remove(usize),
    BatchTarget(usize, f64, f64),
    BatchTryTarget(usize, f64, f64),
    BatchFling(usize, f64, f64),
    BatchTryFling(usize, f64, f64),
    BatchRetune(f64, f64),
    BatchStep(u16),
}

fn op() -> impl Strategy<Value = Op> {
    let xy = || (number(-100.0, 100.0), number(-100.0, 100.0));
    let v = || (number(-1e3, 1e3), number(-1e3, 1e3));
    let i = 0usize..100;
    prop_oneof![
        3 => xy().prop_map(|(x, y)| Op::Target(x, y)),
        2 => xy().prop_map(|(x, y)| Op::TryTarget(x, y)),
        1 => xy().prop_map(|(x, y)| Op::Position(x, y)),
        1 => xy().prop_map(|(x, y)| Op::TryPosition(x, y)),
        2 => v().prop_map(|(x, y)| Op::Fling(x, y)),
        2 => v().prop_map(|(x, y)| Op::TryFling(x, y)),
        1 => number(1e-4, 0.1).prop_map(Op::Rate),
        1 => (number(0.1, 20.0), number(0.0, 20.0)).prop_map(|(f, z)| Op::Retune(f, z)),
        3 => (1u16..300).prop_map(Op::Step),
        1 => (1u16..30).prop_map(Op::Advance),
        3 => xy().prop_map(|(x, y)| Op::Push(x, y)),
        2 => i.clone().prop_map(Op::Remove),
        3 => (i.clone(), number(-100.0, 100.0), number(-100.0, 100.0))
            .prop_map(|(i, x, y)| Op::BatchTarget(i, x, y)),
        2 => (i.clone(), number(-100.0, 100.0), number(-100.0, 100.0))
            .prop_map(|(i, x, y)| Op::BatchTryTarget(i, x, y)),
        1 => (i.clone(), number(-1e3, 1e3), number(-1e3, 1e3))
            .prop_map(|(i, x, y)| Op::BatchFling(i, x, y)),
        1 => (i.clone(), number(-1e3, 1e3), number(-1e3, 1e3))
            .prop_map(|(i, x, y)| Op::BatchTryFling(i, x, y)),
        1 => (number(0.1, 20.0), number(0.0, 20.0)).prop_map(|(f, z)| Op::BatchRetune(f, z)),
        3 => (1u16..300).prop_map(Op::BatchStep),
    ]
}

fn v2<S: Scalar>(x: f64, y: f64) -> [S; 2] {
    [from(x), from(y)]
}

/// What an infallible setter makes of an input: `None` for NaN, else saturated to `MAX`.
fn saturated<S: Scalar>(x: S) -> Option<S> {
    let max = S::from_f64(S::MAX);
    let f = x.to_f64();
    if f.is_nan() {
        None
    } else if f > S::MAX {
        Some(max)
    } else if f < -S::MAX {
        Some(max.neg())
    } else {
        Some(x)
    }
}

/// Everything a value shows, compared bit for bit.
fn snapshot<S: Scalar>(v: &SpringValue<S, 2>) -> [u64; 11] {
    let b = |x: S| x.to_f64().to_bits();
    let (p, t, o, u, w) = (
        v.position(),
        v.target(),
        v.offset(),
        v.step_velocity(),
        v.velocity(),
    );
    [
        b(p[0]),
        b(p[1]),
        b(t[0]),
        b(t[1]),
        b(o[0]),
        b(o[1]),
        b(u[0]),
        b(u[1]),
        b(w[0]),
        b(w[1]),
        u64::from(v.is_at_rest()),
    ]
}

fn finite<S: Scalar>(xs: impl IntoIterator<Item = S>) -> bool {
    xs.into_iter().all(|x| x.to_f64().is_finite())
}

struct Machine<S: Scalar> {
    value: SpringValue<S, 2>,
    tuning: Tuning,
    batch: SpringBatch<S, 2, N>,
    live: Vec<BatchIndex>,
    stale: Vec<BatchIndex>,
}

impl<S: Scalar> Machine<S> {
    fn new() -> Self {
        let tuning = Tuning::from_frequency(2.0, 0.5, DT).expect("valid");
        Machine {
            value: SpringValue::new([S::ZERO; 2], &tuning).expect("representable"),
            tuning,
            batch: SpringBatch::new(&tuning).expect("representable"),
            live: Vec::new(),
            stale: Vec::new(),
        }
    }

    /// Below 80 a live index (if any), else a removed one (if any).
    fn index(&self, i: usize) -> Option<BatchIndex> {
        if i < 80 && !self.live.is_empty() {
            Some(self.live[i % self.live.len()])
        } else if !self.stale.is_empty() {
            Some(self.stale[i % self.stale.len()])
        } else {
            None
        }
    }

    fn batch_positions(&self) -> Vec<Option<[S; 2]>> {
        self.live.iter().map(|&i| self.batch.position(i)).collect()
    }

    fn apply(&mut self, op: &Op) -> Result<(), TestCaseError> {
        let before = snapshot(&self.value);
        let value_failed = match *op {
            Op::Target(x, y) | Op::Position(x, y) => {
                let input: [S; 2] = v2(x, y);
                let target = self.value.target();
                if matches!(op, Op::Target(..)) {
                    self.value.set_target(input);
                } else {
                    self.value.set_position(input);
                }
                match (saturated(input[0]), saturated(input[1])) {
                    (Some(a), Some(b)) if matches!(op, Op::Target(..)) => {
                        prop_assert_eq!(self.value.target(), [a, b]);
                    }
                    (Some(_), Some(_)) => prop_assert_eq!(self.value.target(), target),
                    _ => prop_assert_eq!(snapshot(&self.value), before, "NaN changed it"),
                }
                false
            }
            Op::TryTarget(x, y) => self.value.try_set_target(v2(x, y)).is_err(),
            Op::TryPosition(x, y) => self.value.try_set_position(v2(x, y)).is_err(),
            Op::Fling(x, y) => {
                let input: [S; 2] = v2(x, y);
                self.value.fling(input);
                if input.iter().any(|c| c.to_f64().is_nan()) {
                    prop_assert_eq!(snapshot(&self.value), before, "NaN changed it");
                }
                false
            }
            Op::TryFling(x, y) => self.value.try_fling(v2(x, y)).is_err(),
            Op::Rate(dt) => match self.tuning.with_dt(dt) {
                Ok(t) => self.retune(t),
                Err(_) => false,
            },
            Op::Retune(f, z) => match Tuning::from_frequency(f, z, self.tuning.dt()) {
                Ok(t) => self.retune(t),
                Err(_) => false,
            },
            Op::Step(n) => {
                for _ in 0..n {
                    let was_resting = self.value.is_at_rest();
                    let at = snapshot(&self.value);
                    match self.value.step() {
                        Motion::Resting => {
                            prop_assert!(was_resting);
                            prop_assert_eq!(snapshot(&self.value), at);
                        }
                        Motion::Settled => {
                            prop_assert!(self.value.is_at_rest());
                            prop_assert_eq!(self.value.position(), self.value.target());
                        }
                        Motion::Moving => prop_assert!(!self.value.is_at_rest()),
                    }
                }
                false
            }
            Op::Advance(n) => {
                for _ in 0..n {
                    self.value.advance();
                }
                false
            }
            _ => {
                self.apply_batch(op)?;
                false
            }
        };
        if value_failed {
            prop_assert_eq!(
                snapshot(&self.value),
                before,
                "{:?} failed and changed it",
                op
            );
        }
        let v = &self.value;
        prop_assert!(finite(
            v.position()
                .into_iter()
                .chain(v.velocity())
                .chain(v.step_velocity())
        ));
        self.check_batch()
    }

    /// `set_tuning`; true when it failed (the tuning is then kept).
    fn retune(&mut self, t: Tuning) -> bool {
        match self.value.set_tuning(&t) {
            Ok(()) => {
                self.tuning = t;
                false
            }
            Err(_) => true,
        }
    }

    fn apply_batch(&mut self, op: &Op) -> Result<(), TestCaseError> {
        let (len, positions) = (self.batch.len(), self.batch_positions());
        match *op {
            Op::Push(x, y) => match self.batch.push(v2(x, y)) {
                Ok(i) => {
                    prop_assert!(!self.live.contains(&i) && !self.stale.contains(&i));
                    self.live.push(i);
                }
                Err(e) => {
                    // Full only when it is; a bad position is reported first.
                    let full = e == Error::CapacityFull { capacity: N };
                    let position = matches!(e.parameter(), Some(Parameter::Position));
                    prop_assert!((full && len == N) || position, "{:?} at {}", e, len);
                    prop_assert_eq!(self.batch_positions(), positions);
                }
            },
            Op::Remove(i) => {
                if let Some(i) = self.index(i) {
                    let live = self.live.contains(&i);
                    prop_assert_eq!(self.batch.remove(i).is_some(), live);
                    if live {
                        self.live.retain(|&j| j != i);
                        self.stale.push(i);
                    }
                }
            }
            Op::BatchTarget(i, x, y) | Op::BatchFling(i, x, y) => {
                if let Some(i) = self.index(i) {
                    if matches!(op, Op::BatchTarget(..)) {
                        self.batch.set_target(i, v2(x, y));
                    } else {
                        self.batch.fling(i, v2(x, y));
                    }
                    if self.stale.contains(&i) {
                        prop_assert_eq!(self.batch_positions(), positions);
                    }
                }
            }
            Op::BatchTryTarget(i, x, y) | Op::BatchTryFling(i, x, y) => {
                if let Some(i) = self.index(i) {
                    let r = if matches!(op, Op::BatchTryTarget(..)) {
                        self.batch.try_set_target(i, v2(x, y))
                    } else {
                        self.batch.try_fling(i, v2(x, y))
                    };
                    if self.stale.contains(&i) {
                        let stale = Error::Stale {
                            parameter: Parameter::Index,
                        };
                        prop_assert_eq!(r, Err(stale));
                    }
                    if r.is_err() {
                        prop_assert_eq!(self.batch_positions(), positions);
                    }
                }
            }
            Op::BatchRetune(f, z) => {
                if let Ok(t) = Tuning::from_frequency(f, z, self.batch.tuning().dt()) {
                    let old = self.batch.tuning();
                    if self.batch.set_tuning(&t).is_err() {
                        prop_assert_eq!(self.batch.tuning(), old);
                        prop_assert_eq!(self.batch_positions(), positions);
                    }
                }
            }
            Op::BatchStep(n) => {
                for _ in 0..n {
                    let motion = self.batch.step();
                    prop_assert_eq!(motion.moving, self.batch.awake());
                    prop_assert_eq!(motion.settled, self.batch.just_settled().count());
                    for i in self.batch.just_settled() {
                        prop_assert!(self.live.contains(&i));
                        prop_assert_eq!(self.batch.position(i), self.batch.target(i));
                        prop_assert_eq!(self.batch.is_at_rest(i), Some(true));
                    }
                    for (i, _) in self.batch.moving() {
                        prop_assert!(self.live.contains(&i));
                    }
                }
            }
            _ => unreachable!("a value op"),
        }
        Ok(())
    }

    fn check_batch(&self) -> Result<(), TestCaseError> {
        prop_assert_eq!(self.batch.len(), self.live.len());
        for &i in &self.live {
            let p = self.batch.position(i);
            prop_assert!(p.is_some_and(finite), "{:?}: {:?}", i, p);
            prop_assert!(self.batch.velocity(i).is_some_and(finite));
        }
        for &i in &self.stale {
            prop_assert_eq!(self.batch.position(i), None);
            prop_assert_eq!(self.batch.velocity(i), None);
        }
        Ok(())
    }
}

fn run<S: Scalar>(ops: &[Op]) -> Result<(), TestCaseError> {
    let mut machine = Machine::<S>::new();
    for op in ops {
        machine.apply(op)?;
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn f32_values_and_batches_keep_their_invariants(ops in prop::collection::vec(op(), 1..150)) {
        run::<f32>(&ops)?;
    }

    #[test]
    fn f64_values_and_batches_keep_their_invariants(ops in prop::collection::vec(op(), 1..150)) {
        run::<f64>(&ops)?;
    }

    #[test]
    fn i16f16_values_and_batches_keep_their_invariants(ops in prop::collection::vec(op(), 1..150)) {
        run::<I16F16>(&ops)?;
    }

    #[test]
    fn i32f32_values_and_batches_keep_their_invariants(ops in prop::collection::vec(op(), 1..150)) {
        run::<I32F32>(&ops)?;
    }
}
