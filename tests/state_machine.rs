//! A state-machine property test: random sequences of operations on a scene and a knob,
//! with the invariants checked after every one (values and batches have their own,
//! `tests/value_state_machine.rs`).
//!
//! Operations: add and remove particles (free and pinned), springs and anchors, retune
//! springs, change masses (and pin or free particles), move particles and anchors, set
//! velocities, apply impulses, step; drive a knob with wild angles and velocities, reset
//! it, rebuild it with another configuration. Arguments are drawn mostly valid and
//! sometimes bad (NaN, infinities, zero, negative, huge, stale ids, full capacity), so
//! every operation either succeeds or returns a typed error.
//!
//! Invariants, after every operation:
//!
//! - nothing panics;
//! - a failed operation changes no count, and the counts match a shadow model and never
//!   exceed the capacities; an operation on a removed particle or spring fails with
//!   `Error::Stale` (ids are generational: a stale id never names a new particle);
//! - every position and step velocity is finite and within the backend's network
//!   magnitude (floats); the knob's torque is finite and in `[−1, 1]`;
//! - every spring's coefficients are within `network_limit` of its share count, computed
//!   from the shadow model;
//! - **momentum accounting** (f64, no gravity, no sleep): a step changes the total
//!   momentum of the free particles only through springs to pinned particles; an
//!   impulse changes it by exactly the impulse; a new velocity by `m·Δv`.
//!
//! `cargo test --test state_machine` runs 64 sequences per backend (part of `cargo
//! test`); `PROPTEST_CASES=5000 cargo test --release --test state_machine` is the full
//! run.

use proptest::prelude::*;
use stiffspring::scene::{
    Added, LimitPolicy, ParticleId, Scene, SceneConfig, SpringId, Stepper, network_limit,
};
use stiffspring::{Error, I16F16, Knob, KnobConfig, Scalar, Tuning};

mod support;
use support::{from, number};

const DT: f64 = 1.0 / 60.0;

const P: usize = 8;
const K: usize = 12;

#[derive(Clone, Debug)]
enum Op {
    AddParticle(f64, f64, f64),
    AddPinned(f64, f64),
    RemoveParticle(usize),
    AddSpring(usize, usize, f64, f64, f64),
    AddSpringAtRest(usize, usize, f64, f64),
    RemoveSpring(usize),
    AddAnchor(usize, f64, f64, f64, f64, f64),
    SetTuning(usize, f64, f64),
    SetMass(usize, Option<f64>),
    SetPosition(usize, f64, f64),
    SetVelocity(usize, f64, f64),
    Impulse(usize, f64, f64),
    Step(u16),
    KnobUpdate(f64, f64),
    KnobReset(f64),
    KnobRebuild(f64, f64, f64, f64),
}

fn op() -> impl Strategy<Value = Op> {
    // Mostly a live element (modulo their number), sometimes a removed one.
    let index = 0usize..100;
    let coef = prop_oneof![4 => 0.0..=1.0f64, 1 => number(-0.5, 1.5)];
    prop_oneof![
        8 => (number(-5.0, 5.0), number(-5.0, 5.0), number(0.1, 10.0))
            .prop_map(|(x, y, m)| Op::AddParticle(x, y, m)),
        1 => (number(-5.0, 5.0), number(-5.0, 5.0)).prop_map(|(x, y)| Op::AddPinned(x, y)),
        1 => index.clone().prop_map(Op::RemoveParticle),
        10 => (index.clone(), index.clone(), number(0.1, 3.0), coef.clone(), coef.clone())
            .prop_map(|(a, b, r, k, d)| Op::AddSpring(a, b, r, k, d)),
        4 => (index.clone(), index.clone(), coef.clone(), coef.clone())
            .prop_map(|(a, b, k, d)| Op::AddSpringAtRest(a, b, k, d)),
        1 => index.clone().prop_map(Op::RemoveSpring),
        2 => (index.clone(), number(-5.0, 5.0), number(-5.0, 5.0), number(0.0, 3.0), coef.clone(), coef.clone())
            .prop_map(|(p, x, y, r, k, d)| Op::AddAnchor(p, x, y, r, k, d)),
        2 => (index.clone(), coef.clone(), coef.clone()).prop_map(|(s, k, d)| Op::SetTuning(s, k, d)),
        1 => (index.clone(), prop::option::of(number(0.1, 10.0))).prop_map(|(p, m)| Op::SetMass(p, m)),
        2 => (index.clone(), number(-5.0, 5.0), number(-5.0, 5.0))
            .prop_map(|(p, x, y)| Op::SetPosition(p, x, y)),
        2 => (index.clone(), number(-10.0, 10.0), number(-10.0, 10.0))
            .prop_map(|(p, x, y)| Op::SetVelocity(p, x, y)),
        2 => (index.clone(), number(-10.0, 10.0), number(-10.0, 10.0))
            .prop_map(|(p, x, y)| Op::Impulse(p, x, y)),
        5 => (1u16..300).prop_map(Op::Step),
        3 => (number(-10.0, 10.0), number(-1e3, 1e3)).prop_map(|(a, v)| Op::KnobUpdate(a, v)),
        1 => number(-10.0, 10.0).prop_map(Op::KnobReset),
        1 => (number(0.0, 0.05), number(0.0, 0.05), number(1e-3, 0.5), number(-3.0, 3.0))
            .prop_map(|(d, r, w, c)| Op::KnobRebuild(d, r, w, c)),
    ]
}

/// What the test knows independently of the scene.
#[derive(Default)]
struct Shadow {
    /// Live particles: id, pinned, mass.
    particles: Vec<(ParticleId, bool, f64)>,
    /// Live springs: id and ends.
    springs: Vec<(SpringId, ParticleId, ParticleId)>,
    /// Ids that were removed (stale).
    stale_particles: Vec<ParticleId>,
    stale_springs: Vec<SpringId>,
}

impl Shadow {
    /// `i` in `0..100`: below 90 a live particle, else a removed one.
    fn particle(&self, i: usize) -> Option<ParticleId> {
        let (live, stale) = (&self.particles, &self.stale_particles);
        if i < 90 && !live.is_empty() {
            Some(live[i % live.len()].0)
        } else if !stale.is_empty() {
            Some(stale[i % stale.len()])
        } else {
            None
        }
    }

    /// As [`Shadow::particle`], for springs.
    fn spring(&self, i: usize) -> Option<SpringId> {
        let (live, stale) = (&self.springs, &self.stale_springs);
        if i < 90 && !live.is_empty() {
            Some(live[i % live.len()].0)
        } else if !stale.is_empty() {
            Some(stale[i % stale.len()])
        } else {
            None
        }
    }

    fn is_stale_particle(&self, p: ParticleId) -> bool {
        self.stale_particles.contains(&p)
    }

    fn is_stale_spring(&self, s: SpringId) -> bool {
        self.stale_springs.contains(&s)
    }

    fn pinned(&self, p: ParticleId) -> bool {
        self.particles
            .iter()
            .any(|&(q, pinned, _)| q == p && pinned)
    }

    fn share_count(&self, a: ParticleId, b: ParticleId) -> usize {
        [a, b]
            .iter()
            .filter(|&&p| !self.pinned(p))
            .map(|&p| {
                self.springs
                    .iter()
                    .filter(|&&(_, x, y)| x == p || y == p)
                    .count()
            })
            .max()
            .unwrap_or(0)
    }

    /// True when no spring connects a free particle to a pinned one (then internal
    /// springs alone act and momentum is conserved).
    fn closed(&self) -> bool {
        self.springs
            .iter()
            .all(|&(_, a, b)| self.pinned(a) == self.pinned(b))
    }
}

struct Machine<S: Scalar> {
    scene: Scene<S, 2, P, K>,
    stepper: Stepper,
    shadow: Shadow,
    knob: Knob<S>,
    momentum_checked: bool,
}

fn v2<S: Scalar>(x: f64, y: f64) -> [S; 2] {
    // The float backends take NaN and infinity as they come; fixed point cannot hold them.
    [from(x), from(y)]
}

fn tuning(ck: f64, cd: f64) -> Option<Tuning> {
    Tuning::from_coefficients(ck, cd, DT).ok()
}

fn knob_config() -> KnobConfig {
    KnobConfig::new(1_000.0, 1e-5, 0.05, 16384)
}

impl<S: Scalar> Machine<S> {
    fn new(stepper: Stepper, policy: LimitPolicy, gravity: bool, sleep: bool) -> Self {
        let g = if gravity { -9.81 } else { 0.0 };
        let mut config = SceneConfig::new(DT)
            .expect("dt > 0")
            .stepper(stepper)
            .limit_policy(policy)
            .gravity([S::ZERO, S::from_f64(g)])
            .expect("finite");
        if !sleep {
            config = config.no_sleep();
        }
        Machine {
            scene: Scene::new(config),
            stepper,
            shadow: Shadow::default(),
            knob: Knob::new(&knob_config(), S::ZERO).expect("valid"),
            momentum_checked: !gravity && !sleep && S::NAME == "f64",
        }
    }

    fn mass(&self, p: ParticleId) -> f64 {
        self.shadow
            .particles
            .iter()
            .find(|&&(q, _, _)| q == p)
            .map_or(0.0, |&(_, _, m)| m)
    }

    fn apply(&mut self, op: &Op) -> Result<(), TestCaseError> {
        let counts = (self.scene.particle_count(), self.scene.spring_count());
        let momentum = self.scene.momentum();
        let mut expected_momentum = None;
        // Whether the op names a removed particle or spring: it must then fail as stale.
        let mut stale = false;
        let mut stale_error = false;
        let mut note = |r: Option<&Error>, is_stale: bool| {
            stale |= is_stale;
            stale_error |= matches!(r, Some(Error::Stale { .. }));
        };
        let failed = match *op {
            Op::AddParticle(x, y, m) => match self.scene.add_particle(v2(x, y), from(m)) {
                Ok(p) => {
                    self.shadow.particles.push((p, false, m));
                    false
                }
                Err(_) => true,
            },
            Op::AddPinned(x, y) => match self.scene.add_pinned(v2(x, y)) {
                Ok(p) => {
                    self.shadow.particles.push((p, true, 0.0));
                    false
                }
                Err(_) => true,
            },
            Op::RemoveParticle(i) => match self.shadow.particle(i) {
                Some(p) => {
                    let r = self.scene.remove_particle(p);
                    note(r.as_ref().err(), self.shadow.is_stale_particle(p));
                    match r {
                        Ok(()) => {
                            self.shadow.particles.retain(|&(q, _, _)| q != p);
                            let (gone, kept): (Vec<_>, Vec<_>) = self
                                .shadow
                                .springs
                                .iter()
                                .partition(|&&(_, a, b)| a == p || b == p);
                            self.shadow.springs = kept;
                            self.shadow.stale_springs.extend(gone.iter().map(|s| s.0));
                            self.shadow.stale_particles.push(p);
                            // A removed slot may be reused: it is not stale any more then.
                            false
                        }
                        Err(_) => true,
                    }
                }
                None => true,
            },
            Op::AddSpring(a, b, rest, ck, cd) => {
                match (
                    self.shadow.particle(a),
                    self.shadow.particle(b),
                    tuning(ck, cd),
                ) {
                    (Some(pa), Some(pb), Some(t)) => {
                        let added = self.scene.add_spring(pa, pb, from(rest), &t);
                        let st =
                            self.shadow.is_stale_particle(pa) || self.shadow.is_stale_particle(pb);
                        note(added.as_ref().err(), st);
                        self.add_spring(added, pa, pb)
                    }
                    _ => true,
                }
            }
            Op::AddSpringAtRest(a, b, ck, cd) => {
                match (
                    self.shadow.particle(a),
                    self.shadow.particle(b),
                    tuning(ck, cd),
                ) {
                    (Some(pa), Some(pb), Some(t)) => {
                        let added = self.scene.add_spring_at_rest(pa, pb, &t);
                        let st =
                            self.shadow.is_stale_particle(pa) || self.shadow.is_stale_particle(pb);
                        note(added.as_ref().err(), st);
                        self.add_spring(added, pa, pb)
                    }
                    _ => true,
                }
            }
            Op::AddAnchor(i, x, y, rest, ck, cd) => match (self.shadow.particle(i), tuning(ck, cd))
            {
                (Some(p), Some(t)) => {
                    let added = self.scene.add_anchor(v2(x, y), p, from(rest), &t);
                    note(added.as_ref().err(), self.shadow.is_stale_particle(p));
                    match added {
                        Ok((anchor, added)) => {
                            self.shadow.particles.push((anchor, true, 0.0));
                            self.shadow.springs.push((added.spring, anchor, p));
                            false
                        }
                        Err(_) => true,
                    }
                }
                _ => true,
            },
            Op::RemoveSpring(i) => match self.shadow.spring(i) {
                Some(s) => {
                    let r = self.scene.remove_spring(s);
                    note(r.as_ref().err(), self.shadow.is_stale_spring(s));
                    match r {
                        Ok(()) => {
                            self.shadow.springs.retain(|&(q, _, _)| q != s);
                            self.shadow.stale_springs.push(s);
                            false
                        }
                        Err(_) => true,
                    }
                }
                None => true,
            },
            Op::SetTuning(i, ck, cd) => match (self.shadow.spring(i), tuning(ck, cd)) {
                (Some(s), Some(t)) => {
                    let r = self.scene.set_tuning(s, &t);
                    note(r.as_ref().err(), self.shadow.is_stale_spring(s));
                    r.is_err()
                }
                _ => true,
            },
            Op::SetMass(i, m) => match self.shadow.particle(i) {
                Some(p) => {
                    let r = self.scene.set_mass(p, m.map(from));
                    note(r.as_ref().err(), self.shadow.is_stale_particle(p));
                    match r {
                        Ok(()) => {
                            for e in self.shadow.particles.iter_mut().filter(|e| e.0 == p) {
                                *e = (p, m.is_none(), m.unwrap_or(0.0));
                            }
                            false
                        }
                        Err(_) => true,
                    }
                }
                None => true,
            },
            Op::SetPosition(i, x, y) => match self.shadow.particle(i) {
                Some(p) => {
                    let pinned = self.shadow.pinned(p);
                    let r = self.scene.set_position(p, v2(x, y));
                    note(r.as_ref().err(), self.shadow.is_stale_particle(p));
                    let ok = r.is_ok();
                    if ok && pinned {
                        // A moved anchor pushes its springs this step: external.
                        self.momentum_checked = false;
                    }
                    !ok
                }
                None => true,
            },
            Op::SetVelocity(i, x, y) => match self.shadow.particle(i) {
                Some(p) => {
                    let before = self.scene.velocity(p);
                    let r = self.scene.set_velocity(p, v2(x, y));
                    note(r.as_ref().err(), self.shadow.is_stale_particle(p));
                    match r {
                        Ok(()) => {
                            let (m, after) = (self.mass(p), self.scene.velocity(p).unwrap());
                            let before = before.unwrap();
                            expected_momentum = Some([
                                momentum[0] + m * (after[0].to_f64() - before[0].to_f64()),
                                momentum[1] + m * (after[1].to_f64() - before[1].to_f64()),
                            ]);
                            false
                        }
                        Err(_) => true,
                    }
                }
                None => true,
            },
            Op::Impulse(i, x, y) => match self.shadow.particle(i) {
                Some(p) => {
                    let j: [S; 2] = v2(x, y);
                    let r = self.scene.apply_impulse(p, j);
                    note(r.as_ref().err(), self.shadow.is_stale_particle(p));
                    match r {
                        Ok(()) => {
                            let (jx, jy) = (j[0].to_f64(), j[1].to_f64());
                            expected_momentum = Some([momentum[0] + jx, momentum[1] + jy]);
                            false
                        }
                        Err(_) => true,
                    }
                }
                None => true,
            },
            Op::Step(n) => {
                for _ in 0..n {
                    let _ = self.scene.step();
                }
                if self.shadow.closed() {
                    expected_momentum = Some(momentum);
                }
                false
            }
            Op::KnobUpdate(angle, velocity) => {
                for out in [
                    self.knob.update(from(angle)),
                    self.knob.update_with_velocity(from(angle), from(velocity)),
                ] {
                    let t = out.torque.to_f64();
                    prop_assert!(t.is_finite() && t.abs() <= 1.0, "torque {t}");
                }
                false
            }
            Op::KnobReset(angle) => {
                self.knob.reset(from(angle));
                false
            }
            Op::KnobRebuild(detent, ret, width, centre) => {
                let config = knob_config()
                    .endstops(-3.0, 3.0)
                    .detent_width(width)
                    .detent_stiffness(detent)
                    .return_to_centre(centre, ret);
                match Knob::new(&config, S::ZERO) {
                    Ok(k) => {
                        self.knob = k;
                        false
                    }
                    Err(_) => true,
                }
            }
        };
        if failed {
            prop_assert_eq!(
                (self.scene.particle_count(), self.scene.spring_count()),
                counts,
                "{:?} failed and changed the counts",
                op
            );
        }
        prop_assert!(
            !stale || stale_error,
            "{:?} named a removed id and did not fail as stale",
            op
        );
        self.check(expected_momentum)
    }

    fn add_spring(&mut self, added: Result<Added, Error>, a: ParticleId, b: ParticleId) -> bool {
        match added {
            Ok(added) => {
                self.shadow.springs.push((added.spring, a, b));
                self.shadow.stale_springs.retain(|&s| s != added.spring);
                false
            }
            Err(_) => true,
        }
    }

    fn check(&mut self, expected_momentum: Option<[f64; 2]>) -> Result<(), TestCaseError> {
        // Removed slots may have been reused by later additions.
        let live: Vec<ParticleId> = self.shadow.particles.iter().map(|p| p.0).collect();
        self.shadow.stale_particles.retain(|p| !live.contains(p));
        let live: Vec<SpringId> = self.shadow.springs.iter().map(|s| s.0).collect();
        self.shadow.stale_springs.retain(|s| !live.contains(s));

        prop_assert_eq!(self.scene.particle_count(), self.shadow.particles.len());
        prop_assert_eq!(self.scene.spring_count(), self.shadow.springs.len());
        prop_assert!(self.scene.particle_count() <= P && self.scene.spring_count() <= K);
        for (p, x) in self.scene.particles() {
            // The step velocity is the velocity times dt.
            let u = self
                .scene
                .velocity(p)
                .expect("live")
                .map(|v| v.to_f64() * DT);
            for c in x.iter().map(|c| c.to_f64()).chain(u) {
                prop_assert!(
                    c.is_finite() && c.abs() <= S::NETWORK_MAX * (1.0 + 1e-6),
                    "{p:?}: {c}"
                );
            }
        }
        for &(s, a, b) in &self.shadow.springs {
            let t = self.scene.tuning(s).expect("live");
            let limit = network_limit(self.shadow.share_count(a, b), self.stepper);
            // The backend stores the coefficient rounded (f32: half an ULP).
            let slack = limit * 1e-7;
            prop_assert!(
                t.stiffness() <= limit + slack && t.damping() <= limit + slack,
                "{s:?} {t:?} above {limit}"
            );
        }
        if let (Some(expected), true) = (expected_momentum, self.momentum_checked) {
            let got = self.scene.momentum();
            let scale: f64 = self
                .scene
                .particles()
                .map(|(p, _)| {
                    let v = self.scene.velocity(p).expect("live");
                    self.mass(p) * (v[0].to_f64().abs() + v[1].to_f64().abs())
                })
                .sum::<f64>()
                + expected[0].abs()
                + expected[1].abs();
            for k in 0..2 {
                prop_assert!(
                    (got[k] - expected[k]).abs() <= 1e-9 * (1.0 + scale),
                    "momentum {got:?}, expected {expected:?}"
                );
            }
        }
        Ok(())
    }
}

fn run<S: Scalar>(
    ops: &[Op],
    stepper: Stepper,
    clamp: bool,
    gravity: bool,
    sleep: bool,
) -> Result<(), TestCaseError> {
    let policy = if clamp {
        LimitPolicy::Clamp
    } else {
        LimitPolicy::Reject
    };
    let mut machine = Machine::<S>::new(stepper, policy, gravity, sleep);
    for op in ops {
        machine.apply(op)?;
    }
    Ok(())
}

fn stepper() -> impl Strategy<Value = Stepper> {
    prop_oneof![Just(Stepper::GaussSeidel), Just(Stepper::Jacobi)]
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn f64_scenes_and_knobs_keep_their_invariants(
        ops in prop::collection::vec(op(), 1..150),
        stepper in stepper(),
        (clamp, gravity, sleep) in (any::<bool>(), any::<bool>(), any::<bool>()),
    ) {
        run::<f64>(&ops, stepper, clamp, gravity, sleep)?;
    }

    #[test]
    fn f32_scenes_and_knobs_keep_their_invariants(
        ops in prop::collection::vec(op(), 1..150),
        stepper in stepper(),
        (clamp, gravity, sleep) in (any::<bool>(), any::<bool>(), any::<bool>()),
    ) {
        run::<f32>(&ops, stepper, clamp, gravity, sleep)?;
    }

    #[test]
    fn i16f16_scenes_and_knobs_keep_their_invariants(
        ops in prop::collection::vec(op(), 1..150),
        stepper in stepper(),
        (clamp, gravity, sleep) in (any::<bool>(), any::<bool>(), any::<bool>()),
    ) {
        run::<I16F16>(&ops, stepper, clamp, gravity, sleep)?;
    }
}
