//! Bad input to a [`Scene`] gets a typed error, and a failed call changes nothing: the
//! particle and spring counts, every position, velocity, tuning and rest length, and what
//! is awake stay as they were. The rows of `docs/bad-input.md` for scenes, one by one.
//!
//! Cases: a spring from a particle to itself; removed ids and ids of another scene
//! (`Error::Stale`, never another particle's data); non-positive, NaN or infinite masses
//! and rest lengths; a tuning sampled at another `dt`; full capacity; NaN, infinite or
//! out-of-range positions, velocities and impulses; pinned particles asked to take a
//! velocity or an impulse; a bad configuration; the network limit under
//! [`LimitPolicy::Reject`].

use stiffspring::length::{Exact, LengthKernel, Linearised};
use stiffspring::scene::{
    AngularScene, LimitPolicy, ParticleId, Scene, SceneConfig, SleepThreshold, SpringId, Stepper,
    network_limit,
};
use stiffspring::{Bound, Error, I16F16, I32F32, Parameter, Remedy, Scalar, Tuning};

mod support;
use support::from;

const NAN: f64 = f64::NAN;
const INF: f64 = f64::INFINITY;
const DT: f64 = 0.01;

fn v2<S: Scalar>(x: f64, y: f64) -> [S; 2] {
    [from(x), from(y)]
}

fn raw(ck: f64, cd: f64) -> Tuning {
    Tuning::from_coefficients(ck, cd, DT).expect("in the square")
}

/// Everything a failed call must leave unchanged, as text.
fn snapshot<S: Scalar, const D: usize, const P: usize, const K: usize, L: LengthKernel<S>>(
    s: &Scene<S, D, P, K, L>,
) -> String {
    let particles: Vec<_> = s
        .particles()
        .map(|(p, x)| (p, x, s.is_pinned(p), s.is_asleep(p), s.velocity(p)))
        .collect();
    let springs: Vec<_> = s
        .springs()
        .map(|(k, a, b)| (k, a, b, s.tuning(k), s.rest_length(k)))
        .collect();
    format!(
        "{} {} {particles:?} {springs:?} {:?}",
        s.particle_count(),
        s.spring_count(),
        s.active()
    )
}

type Small<S, L> = Scene<S, 2, 5, 4, L>;

/// A small scene: three free particles in a chain and an anchor spring (a pinned
/// particle); one more particle and one more spring fit (the slots of a removed particle
/// and a removed spring). Plus ids that name nothing in it: one of another scene and one
/// removed, for particles and springs.
struct Fixture<S: Scalar, L: LengthKernel<S>> {
    scene: Small<S, L>,
    free: [ParticleId; 3],
    pinned: ParticleId,
    spring: SpringId,
    stale_particles: [ParticleId; 2],
    stale_springs: [SpringId; 2],
}

fn fixture<S: Scalar, L: LengthKernel<S>>() -> Fixture<S, L> {
    let config = SceneConfig::new(DT)
        .expect("dt")
        .gravity(v2(0.0, -9.81))
        .expect("g");
    let mut scene = Small::<S, L>::new(config);
    let t = raw(0.3, 0.3);
    let m = |m: f64| S::from_f64(m);
    let free = [
        scene.add_particle(v2(0.0, 0.0), m(1.0)).expect("room"),
        scene.add_particle(v2(1.0, 0.0), m(2.0)).expect("room"),
        scene.add_particle(v2(2.0, 0.0), m(0.5)).expect("room"),
    ];
    let spring = scene
        .add_spring(free[0], free[1], m(1.0), &t)
        .expect("valid")
        .spring;
    scene
        .add_spring(free[1], free[2], m(1.0), &t)
        .expect("valid");
    let (pinned, _) = scene
        .add_anchor(v2(0.0, 1.0), free[0], m(1.0), &t)
        .expect("valid");
    // A removed particle and a removed spring: their slots are free again, and the next
    // particle and spring to take them get new generations.
    let gone = scene.add_particle(v2(3.0, 0.0), m(1.0)).expect("room");
    let gone_spring = scene
        .add_spring(gone, free[2], m(1.0), &t)
        .expect("valid")
        .spring;
    scene.remove_spring(gone_spring).expect("live");
    scene.remove_particle(gone).expect("live");
    for _ in 0..10 {
        let _ = scene.step();
    }
    // Ids another scene issued, for slots this one does not have.
    let mut big = Scene::<f32, 1, 40, 40>::new(SceneConfig::new(DT).expect("dt"));
    let mut far = big.add_particle([0.0], 1.0).expect("room");
    let mut far_spring = None;
    for i in 1..30 {
        let next = big.add_particle([i as f32], 1.0).expect("room");
        far_spring = Some(
            big.add_spring(far, next, 1.0, &raw(0.1, 0.1))
                .expect("valid")
                .spring,
        );
        far = next;
    }
    Fixture {
        scene,
        free,
        pinned,
        spring,
        stale_particles: [far, gone],
        stale_springs: [far_spring.expect("added"), gone_spring],
    }
}

/// Runs `call` on the fixture's scene, checks its error and that nothing changed.
#[track_caller]
fn refused<S: Scalar, L: LengthKernel<S>, T: std::fmt::Debug>(
    f: &mut Fixture<S, L>,
    expected: Error,
    call: impl FnOnce(&mut Small<S, L>) -> Result<T, Error>,
) {
    let before = snapshot(&f.scene);
    let got = call(&mut f.scene);
    assert_eq!(got.map(|_| ()), Err(expected), "{} {}", S::NAME, L::NAME);
    assert_eq!(
        snapshot(&f.scene),
        before,
        "{} {}: changed",
        S::NAME,
        L::NAME
    );
}

fn every_case<S: Scalar, L: LengthKernel<S>>() {
    let mut f = fixture::<S, L>();
    let [a, b, c] = f.free;
    let pin = f.pinned;
    let t = raw(0.1, 0.1);
    let one = S::ONE;

    // A spring from a particle to itself (free or pinned).
    refused(&mut f, Error::SameParticle, |s| s.add_spring(a, a, one, &t));
    refused(&mut f, Error::SameParticle, |s| {
        s.add_spring(pin, pin, one, &t)
    });
    refused(&mut f, Error::SameParticle, |s| {
        s.add_spring_at_rest(c, c, &t)
    });

    // Stale ids, in every call that takes one.
    let particle = Error::Stale {
        parameter: Parameter::Particle,
    };
    for p in f.stale_particles {
        refused(&mut f, particle, |s| s.add_spring(p, a, one, &t));
        refused(&mut f, particle, |s| s.add_spring(a, p, one, &t));
        refused(&mut f, particle, |s| s.add_spring_at_rest(p, a, &t));
        refused(&mut f, particle, |s| s.add_anchor(v2(0.0, 0.0), p, one, &t));
        refused(&mut f, particle, |s| s.remove_particle(p));
        refused(&mut f, particle, |s| s.set_mass(p, Some(one)));
        refused(&mut f, particle, |s| s.set_mass(p, None));
        refused(&mut f, particle, |s| s.set_position(p, v2(0.0, 0.0)));
        refused(&mut f, particle, |s| s.set_velocity(p, v2(0.0, 0.0)));
        refused(&mut f, particle, |s| s.apply_impulse(p, v2(0.0, 0.0)));
        refused(&mut f, particle, |s| s.position(p));
        refused(&mut f, particle, |s| s.precise_position(p));
        refused(&mut f, particle, |s| s.velocity(p));
        refused(&mut f, particle, |s| s.is_pinned(p));
        refused(&mut f, particle, |s| s.is_asleep(p));
        // A stale id is reported before a same-particle spring.
        refused(&mut f, particle, |s| s.add_spring(p, p, one, &t));
    }
    let spring = Error::Stale {
        parameter: Parameter::Spring,
    };
    for k in f.stale_springs {
        refused(&mut f, spring, |s| s.remove_spring(k));
        refused(&mut f, spring, |s| s.set_tuning(k, &t));
        refused(&mut f, spring, |s| s.rest_length(k));
        refused(&mut f, spring, |s| s.ends(k));
        refused(&mut f, spring, |s| s.tuning(k));
    }

    // Masses: zero, negative, NaN, infinite (the last two only exist in floats).
    let mass = Parameter::Mass;
    let mut masses = vec![(0.0, -0.0), (-0.0, -0.0), (-1.0, -1.0)];
    if S::RESOLUTION == 0.0 {
        masses.extend([(NAN, NAN), (INF, INF), (-INF, -INF)]);
    }
    for (m, value) in masses {
        let e = if value.is_finite() {
            Error::OutOfRange {
                parameter: mass,
                value: S::from_f64(value).to_f64(),
                bound: Bound::Positive,
            }
        } else {
            Error::NotFinite { parameter: mass }
        };
        refused(&mut f, e, |s| s.add_particle(v2(3.0, 0.0), from(m)));
        refused(&mut f, e, |s| s.set_mass(b, Some(from(m))));
        refused(&mut f, e, |s| s.set_mass(pin, Some(from(m))));
    }

    // Rest lengths: negative, NaN, infinite; zero only for a kernel that holds no length
    // of zero (the exact kernel takes it: a point spring, a drag handle).
    let rest = Parameter::RestLength;
    let least = if L::ZERO_REST {
        0.0
    } else {
        S::RESOLUTION.max(f64::MIN_POSITIVE)
    };
    let within = Bound::Within {
        min: least,
        max: S::MAX,
    };
    let mut lengths = vec![-1.0, -S::RESOLUTION.max(1e-30)];
    if !L::ZERO_REST {
        lengths.push(0.0);
    }
    for l in lengths {
        let value = S::from_f64(l).to_f64();
        let e = Error::OutOfRange {
            parameter: rest,
            value,
            bound: within,
        };
        refused(&mut f, e, |s| s.add_spring(a, c, from(l), &t));
        refused(&mut f, e, |s| s.add_anchor(v2(3.0, 3.0), c, from(l), &t));
    }
    if S::RESOLUTION == 0.0 {
        for l in [NAN, INF, -INF] {
            let e = Error::NotFinite { parameter: rest };
            refused(&mut f, e, |s| s.add_spring(a, c, from(l), &t));
            refused(&mut f, e, |s| s.add_anchor(v2(3.0, 3.0), c, from(l), &t));
        }
    }
    if !L::ZERO_REST {
        // Coincident particles have no length to rest at.
        let (at_a, at_c) = (
            f.scene.position(a).expect("live"),
            f.scene.position(c).expect("live"),
        );
        f.scene.set_position(c, at_a).expect("live");
        let e = Error::OutOfRange {
            parameter: rest,
            value: 0.0,
            bound: within,
        };
        refused(&mut f, e, |s| s.add_spring_at_rest(a, c, &t));
        f.scene.set_position(c, at_c).expect("live");
    }

    // A tuning sampled at another time step.
    let t60 = Tuning::from_frequency(2.0, 0.7, 1.0 / 60.0).expect("valid");
    let mismatch = Error::TimeStepMismatch {
        expected: DT,
        found: 1.0 / 60.0,
    };
    refused(&mut f, mismatch, |s| s.add_spring(a, c, one, &t60));
    refused(&mut f, mismatch, |s| s.add_spring_at_rest(a, c, &t60));
    refused(&mut f, mismatch, |s| {
        s.add_anchor(v2(3.0, 3.0), c, one, &t60)
    });
    let k = f.spring;
    refused(&mut f, mismatch, |s| s.set_tuning(k, &t60));

    // Pinned particles take no velocity and no impulse.
    refused(&mut f, Error::Pinned, |s| s.set_velocity(pin, v2(1.0, 0.0)));
    refused(&mut f, Error::Pinned, |s| {
        s.apply_impulse(pin, v2(1.0, 0.0))
    });

    // Impulses: NaN or infinite (floats), or so large on a light particle that the step
    // velocity leaves the state's range.
    if S::RESOLUTION == 0.0 {
        for j in [[NAN, 0.0], [0.0, INF], [-INF, 0.0]] {
            let e = Error::NotFinite {
                parameter: Parameter::Impulse,
            };
            refused(&mut f, e, |s| s.apply_impulse(b, v2(j[0], j[1])));
        }
    }
    // (Mass 1e−3 in floats, a last bit in I16F16: the step of a full-range impulse is
    // beyond the bound; I32F32's range is too wide for one at dt = 0.01.)
    let m = if S::RESOLUTION > 0.0 {
        S::RESOLUTION
    } else {
        1e-3
    };
    let light = f
        .scene
        .add_particle(v2(4.0, 4.0), S::from_f64(m))
        .expect("room");
    if S::NAME != "I32F32" {
        let before = snapshot(&f.scene);
        let got = f.scene.apply_impulse(light, [S::ZERO, S::from_f64(S::MAX)]);
        assert!(
            matches!(
                got,
                Err(Error::Unrepresentable {
                    parameter: Parameter::Impulse,
                    remedy: Remedy::LargerUnit,
                    ..
                })
            ),
            "{}: {got:?}",
            S::NAME
        );
        assert_eq!(snapshot(&f.scene), before);
    }

    // Full capacity (the light particle took the last particle slot): nothing more, and a
    // failed add_anchor leaves no anchor behind.
    let d = light;
    let particles = Error::CapacityFull { capacity: 5 };
    let springs = Error::CapacityFull { capacity: 4 };
    refused(&mut f, particles, |s| s.add_particle(v2(4.0, 0.0), one));
    refused(&mut f, particles, |s| s.add_pinned(v2(4.0, 0.0)));
    refused(&mut f, particles, |s| {
        s.add_anchor(v2(4.0, 0.0), d, one, &t)
    });
    f.scene.add_spring_at_rest(c, d, &t).expect("room");
    refused(&mut f, springs, |s| s.add_spring(a, d, one, &t));
    // Removing d frees a particle slot and its spring's slot; fill the spring slot: now
    // add_anchor would find a slot for its anchor but none for its spring.
    f.scene.remove_particle(d).expect("live");
    f.scene.add_spring_at_rest(pin, c, &t).expect("room");
    refused(&mut f, springs, |s| s.add_anchor(v2(4.0, 0.0), c, one, &t));
    refused(&mut f, springs, |s| s.add_spring(a, c, one, &t));

    // A gain the backend cannot hold (below the state's resolution, or subnormal).
    let faint = if S::RESOLUTION > 0.0 { 1e-12 } else { 1e-320 };
    let faint = Tuning::from_coefficients(faint, 0.5, DT).expect("in the square");
    let before = snapshot(&f.scene);
    let got = f.scene.add_spring(a, c, one, &faint);
    assert!(
        matches!(
            got,
            Err(Error::Unrepresentable {
                parameter: Parameter::Stiffness,
                ..
            })
        ),
        "{}: {got:?}",
        S::NAME
    );
    assert_eq!(snapshot(&f.scene), before);

    // The network limit under Reject: b carries two springs. (The linearised kernel
    // lowers the limit by the stretch the spring has: gravity has pulled it a little.)
    let spring = f.spring;
    let limit = network_limit(2, Stepper::GaussSeidel);
    let before = snapshot(&f.scene);
    let got = f.scene.set_tuning(spring, &Tuning::rigid(DT).expect("dt"));
    match got {
        Err(Error::ExceedsNetworkLimit {
            coefficient,
            limit: l,
        }) => {
            assert_eq!(coefficient, 1.0);
            assert!(l <= limit && l > 0.99 * limit, "{l} against {limit}");
            if !L::NAME.contains("linearised") {
                assert_eq!(l, limit);
            }
        }
        other => panic!("{} {}: {other:?}", S::NAME, L::NAME),
    }
    assert_eq!(snapshot(&f.scene), before);
}

/// Freeing a pinned particle makes its springs count on it: three springs of 0.9, each
/// alone on its free end (limit 1), share the freed particle (limit for three: lower).
#[test]
fn freeing_a_pinned_particle_above_the_limit_is_refused() {
    let mut s = Scene::<f32, 2, 4, 3>::new(SceneConfig::new(DT).expect("dt"));
    let hub = s.add_pinned([0.0, 0.0]).expect("room");
    let t = raw(0.9, 0.9);
    for x in [[1.0, 0.0], [0.0, 1.0], [-1.0, 0.0]] {
        let p = s.add_particle(x, 1.0).expect("room");
        s.add_spring_at_rest(hub, p, &t)
            .expect("alone on its free end");
    }
    let before = snapshot(&s);
    let limit = network_limit(3, Stepper::GaussSeidel);
    assert!(limit < 0.9);
    let e = Error::ExceedsNetworkLimit {
        coefficient: 0.9f32 as f64,
        limit,
    };
    assert_eq!(s.set_mass(hub, Some(1.0)), Err(e));
    assert_eq!(snapshot(&s), before);
}

#[test]
fn bad_input_gets_a_typed_error_and_changes_nothing() {
    every_case::<f64, Exact>();
    every_case::<f32, Exact>();
    every_case::<I32F32, Exact>();
    every_case::<I16F16, Exact>();
    every_case::<f64, Linearised>();
    every_case::<I16F16, Linearised>();
}

/// Positions and velocities: NaN, infinite, beyond the network bound (floats only: a
/// fixed-point value cannot be any of these). A float scene keeps positions and step
/// velocities within `Scalar::NETWORK_MAX` (`2⁶⁰` in `f32`, `2⁵⁰⁰` in `f64`), so that a
/// squared length stays finite; set-up refuses what the step would have to clamp.
fn float_positions<S: Scalar, L: LengthKernel<S>>() {
    let mut f = fixture::<S, L>();
    let [a, _, _] = f.free;
    let pin = f.pinned;
    let t = raw(0.1, 0.1);
    let beyond = 2.0 * S::NETWORK_MAX;
    let position = Parameter::Position;
    let out = Error::OutOfRange {
        parameter: position,
        value: beyond,
        bound: Bound::MagnitudeAtMost {
            max: S::NETWORK_MAX,
        },
    };
    for (x, e) in [
        (
            NAN,
            Error::NotFinite {
                parameter: position,
            },
        ),
        (
            INF,
            Error::NotFinite {
                parameter: position,
            },
        ),
        (beyond, out),
    ] {
        for p in [v2::<S>(x, 0.0), v2::<S>(0.0, x)] {
            refused(&mut f, e, |s| s.add_particle(p, S::ONE));
            refused(&mut f, e, |s| s.add_pinned(p));
            refused(&mut f, e, |s| s.set_position(a, p));
            refused(&mut f, e, |s| s.set_position(pin, p));
            refused(&mut f, e, |s| s.add_anchor(p, a, S::ONE, &t));
        }
    }
    let velocity = Parameter::Velocity;
    for (v, e) in [
        (
            NAN,
            Error::NotFinite {
                parameter: velocity,
            },
        ),
        (
            -INF,
            Error::NotFinite {
                parameter: velocity,
            },
        ),
        (
            2.0 * S::MAX,
            Error::OutOfRange {
                parameter: velocity,
                value: 2.0 * S::MAX,
                bound: Bound::MagnitudeAtMost { max: S::MAX },
            },
        ),
    ] {
        refused(&mut f, e, |s| s.set_velocity(a, v2(v, 0.0)));
        refused(&mut f, e, |s| s.set_velocity(a, v2(0.0, v)));
    }
    let twice = S::from_f64(2.0 * S::MAX);
    let e = Error::OutOfRange {
        parameter: Parameter::Impulse,
        value: 2.0 * S::MAX,
        bound: Bound::MagnitudeAtMost { max: S::MAX },
    };
    refused(&mut f, e, |s| s.apply_impulse(a, [twice, S::ZERO]));
    let [_, _, c] = f.free;
    let least = if L::ZERO_REST { 0.0 } else { f64::MIN_POSITIVE };
    let e = Error::OutOfRange {
        parameter: Parameter::RestLength,
        value: 2.0 * S::MAX,
        bound: Bound::Within {
            min: least,
            max: S::MAX,
        },
    };
    refused(&mut f, e, |s| s.add_spring(a, c, twice, &t));
    // At a long time step, a velocity within range whose step is beyond the bound.
    let dt = 4.0;
    let mut s = Scene::<S, 1, 1, 1, L>::new(SceneConfig::new(dt).expect("dt"));
    let p = s.add_particle([S::ZERO], S::ONE).expect("room");
    let v = S::from_f64(S::MAX);
    let e = Error::OutOfRange {
        parameter: velocity,
        value: S::MAX,
        bound: Bound::MagnitudeAtMost {
            max: S::NETWORK_MAX / dt,
        },
    };
    assert_eq!(s.set_velocity(p, [v]), Err(e), "{}", S::NAME);
    assert_eq!(s.velocity(p), Ok([S::ZERO]));
    let e = s.apply_impulse(p, [v]).expect_err("beyond the bound");
    assert!(
        matches!(
            e,
            Error::Unrepresentable {
                parameter: Parameter::Impulse,
                ..
            }
        ),
        "{e:?}"
    );
    assert_eq!(s.velocity(p), Ok([S::ZERO]));
}

#[test]
fn non_finite_and_out_of_bound_positions_and_velocities_are_refused() {
    float_positions::<f64, Exact>();
    float_positions::<f32, Exact>();
    float_positions::<f32, Linearised>();
}

/// Fixed point: the state holds a step of 300 000 units (30 000 units/s at dt = 10 s),
/// beyond the position range: the velocity is accepted and reads back.
#[test]
fn fixed_point_holds_a_step_beyond_the_position_range() {
    let mut s = Scene::<I16F16, 1, 1, 1>::new(SceneConfig::new(10.0).expect("dt"));
    let p = s.add_particle([I16F16::ZERO], I16F16::ONE).expect("room");
    let v = I16F16::from_num(30_000);
    s.set_velocity(p, [v]).expect("the state holds it");
    assert_eq!(s.velocity(p), Ok([v]));
}

#[test]
fn angular_rest_angles_may_be_any_finite_value() {
    let mut s = AngularScene::<f32, 2, 2>::new(SceneConfig::new(DT).expect("dt"));
    let a = s.add_pinned([0.0]).expect("room");
    let b = s.add_particle([1.0], 0.1).expect("room");
    let t = raw(0.1, 0.1);
    for l in [NAN, INF] {
        let e = Error::NotFinite {
            parameter: Parameter::RestLength,
        };
        assert_eq!(s.add_spring(a, b, l as f32, &t).map(|_| ()), Err(e));
        assert_eq!(s.spring_count(), 0);
    }
    assert_eq!(s.add_spring(a, b, 0.0, &t).map(|a| a.clamped), Ok(0));
    assert_eq!(s.add_spring(a, b, -20.0, &t).map(|a| a.clamped), Ok(0));
    assert_eq!(
        s.add_spring(a, b, 1.0, &t).map(|_| ()),
        Err(Error::CapacityFull { capacity: 2 }),
        "two springs fit"
    );
    assert_eq!(
        s.add_spring(b, b, 1.0, &t).map(|_| ()),
        Err(Error::SameParticle)
    );
}

#[test]
fn bad_configuration_gets_a_typed_error() {
    for (dt, e) in [
        (
            0.0,
            Error::OutOfRange {
                parameter: Parameter::TimeStep,
                value: 0.0,
                bound: Bound::Positive,
            },
        ),
        (
            -0.01,
            Error::OutOfRange {
                parameter: Parameter::TimeStep,
                value: -0.01,
                bound: Bound::Positive,
            },
        ),
        (
            NAN,
            Error::NotFinite {
                parameter: Parameter::TimeStep,
            },
        ),
        (
            INF,
            Error::NotFinite {
                parameter: Parameter::TimeStep,
            },
        ),
    ] {
        assert_eq!(SceneConfig::<f32, 2>::new(dt), Err(e));
    }
    let config = SceneConfig::<f32, 2>::new(DT).expect("dt");
    for g in [[NAN, 0.0], [0.0, INF], [-INF, 0.0]] {
        let e = Error::NotFinite {
            parameter: Parameter::Acceleration,
        };
        assert_eq!(config.gravity(v2(g[0], g[1])), Err(e));
    }
    assert!(matches!(
        config.gravity([0.0, -f32::MAX]),
        Err(Error::OutOfRange {
            parameter: Parameter::Acceleration,
            ..
        })
    ));
    for (v, t) in [(0.0, 1.0), (1.0, 0.0), (-1.0, 1.0), (NAN, 1.0), (1.0, INF)] {
        let e = SleepThreshold::new(v, t).expect_err("refused");
        assert_eq!(e.parameter(), Some(Parameter::Threshold), "{e:?}");
    }
}

#[test]
fn reject_policy_refuses_and_changes_nothing_and_clamp_lowers() {
    for policy in [LimitPolicy::Reject, LimitPolicy::Clamp] {
        let config = SceneConfig::new(DT).expect("dt").limit_policy(policy);
        let mut s = Scene::<f32, 2, 4, 4>::new(config);
        let p: Vec<_> = (0..4)
            .map(|i| s.add_particle([i as f32, 0.0], 1.0).expect("room"))
            .collect();
        s.add_spring(p[0], p[1], 1.0, &Tuning::rigid(DT).expect("dt"))
            .expect("alone");
        let before = snapshot(&s);
        let got = s.add_spring(p[1], p[2], 1.0, &raw(0.1, 0.1));
        let limit = network_limit(2, Stepper::GaussSeidel);
        match policy {
            LimitPolicy::Reject => {
                let e = Error::ExceedsNetworkLimit {
                    coefficient: 1.0,
                    limit,
                };
                assert_eq!(got.map(|_| ()), Err(e));
                assert_eq!(snapshot(&s), before);
            }
            LimitPolicy::Clamp => {
                // The rigid neighbour is lowered to the limit and counted.
                assert_eq!(got.map(|a| a.clamped), Ok(1));
                let (k, _, _) = s.springs().next().expect("the first spring");
                let t = s.tuning(k).expect("live");
                assert!(t.stiffness() <= limit * (1.0 + 1e-7));
            }
        }
    }
}

#[test]
fn masses_whose_inverse_overflows_are_refused() {
    let mut s = Scene::<f64, 2, 2, 1>::new(SceneConfig::new(DT).expect("dt").no_sleep());
    let b = s.add_particle([2.0, 0.0], 1.0).expect("room");
    // 1/1e-320 = ∞: the particle would have an infinite inverse mass.
    let e = Error::OutOfRange {
        parameter: Parameter::Mass,
        value: 1e-320,
        bound: Bound::Within {
            min: f64::MIN_POSITIVE,
            max: f64::MAX,
        },
    };
    assert_eq!(s.add_particle([0.0, 0.0], 1e-320), Err(e));
    assert_eq!(s.set_mass(b, Some(1e-320)), Err(e));
}
