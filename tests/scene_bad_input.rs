//! Bad input to a [`Scene`] gets a typed error, and a failed call changes nothing: the
//! particle and spring counts, every position, step velocity, tuning and rest length, and
//! what is awake stay as they were.
//!
//! Cases: a spring from a particle to itself; unknown particle and spring ids (never
//! issued, or removed); non-positive, NaN or infinite masses and rest lengths; full
//! capacity; NaN, infinite or out-of-range positions, velocities and impulses; pinned
//! particles asked to take a velocity or an impulse; a bad configuration; and the
//! network limit under [`LimitPolicy::Reject`].

use stiffspring::length::{Exact, LengthKernel, Linearised};
use stiffspring::scene::{
    AngularScene, LimitPolicy, ParticleId, Scene, SceneConfig, SleepThreshold, SpringId,
};
use stiffspring::{Error, I16F16, I32F32, Parameter, Scalar, Tuning};

const NAN: f64 = f64::NAN;
const INF: f64 = f64::INFINITY;

fn v2<S: Scalar>(x: f64, y: f64) -> [S; 2] {
    [S::from_f64(x), S::from_f64(y)]
}

/// Everything a failed call must leave unchanged, as text.
fn snapshot<S: Scalar, const D: usize, const P: usize, const K: usize, L: LengthKernel<S>>(
    s: &Scene<S, D, P, K, L>,
) -> String {
    let particles: Vec<_> = s
        .particles()
        .map(|(p, x)| {
            (
                p,
                x,
                s.is_pinned(p).unwrap(),
                s.is_asleep(p).unwrap(),
                s.step_velocity(p).unwrap(),
            )
        })
        .collect();
    let springs: Vec<_> = s
        .springs()
        .map(|(k, a, b)| (k, a, b, s.tuning(k).unwrap(), s.rest_length(k).unwrap()))
        .collect();
    format!(
        "{} {} {particles:?} {springs:?} {:?}",
        s.particle_count(),
        s.spring_count(),
        s.active()
    )
}

/// A small scene: three free particles in a chain and an anchor spring (a pinned
/// particle); one more particle and one more spring fit (the slots of a removed particle
/// and a removed spring). Plus ids that name nothing in it:
/// one never issued (from a larger scene) and one removed, for particles and springs.
struct Fixture<S: Scalar, L: LengthKernel<S>> {
    scene: Scene<S, 2, 5, 4, L>,
    free: [ParticleId; 3],
    pinned: ParticleId,
    spring: SpringId,
    unknown_particles: [ParticleId; 2],
    unknown_springs: [SpringId; 2],
}

fn fixture<S: Scalar, L: LengthKernel<S>>() -> Fixture<S, L> {
    let config = SceneConfig::new(0.01)
        .unwrap()
        .gravity([0.0, -9.81])
        .unwrap();
    let mut scene = Scene::<S, 2, 5, 4, L>::new(config).unwrap();
    let t = Tuning::from_coefficients(0.3, 0.3).unwrap();
    let free = [
        scene.add_particle(v2(0.0, 0.0), 1.0).unwrap(),
        scene.add_particle(v2(1.0, 0.0), 2.0).unwrap(),
        scene.add_particle(v2(2.0, 0.0), 0.5).unwrap(),
    ];
    let spring = scene.add_spring(free[0], free[1], 1.0, t).unwrap().spring;
    scene.add_spring(free[1], free[2], 1.0, t).unwrap();
    let (pinned, _) = scene.add_anchor(v2(0.0, 1.0), free[0], 1.0, t).unwrap();
    // A removed particle and a removed spring (their slots are free again, but these ids
    // stay dead until the slots are reused).
    let gone = scene.add_particle(v2(5.0, 5.0), 1.0).unwrap();
    let gone_spring = scene.add_spring(gone, free[2], 1.0, t).unwrap().spring;
    scene.remove_spring(gone_spring).unwrap();
    scene.remove_particle(gone).unwrap();
    for _ in 0..10 {
        scene.step();
    }
    // Ids this scene never issued.
    let mut big = Scene::<f32, 1, 40, 40>::new(SceneConfig::new(0.01).unwrap()).unwrap();
    let mut far = big.add_particle([0.0], 1.0).unwrap();
    let mut far_spring = None;
    for i in 1..30 {
        let next = big.add_particle([i as f32], 1.0).unwrap();
        far_spring = Some(
            big.add_spring(far, next, 1.0, Tuning::from_coefficients(0.1, 0.1).unwrap())
                .unwrap()
                .spring,
        );
        far = next;
    }
    Fixture {
        scene,
        free,
        pinned,
        spring,
        unknown_particles: [far, gone],
        unknown_springs: [far_spring.unwrap(), gone_spring],
    }
}

/// Runs `call` on the fixture's scene, checks its error and that nothing changed.
#[track_caller]
fn refused<S: Scalar, L: LengthKernel<S>, T: std::fmt::Debug>(
    f: &mut Fixture<S, L>,
    expected: Error,
    call: impl FnOnce(&mut Scene<S, 2, 5, 4, L>) -> Result<T, Error>,
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
    let t = Tuning::from_coefficients(0.1, 0.1).unwrap();
    let index = Error::OutOfRange(Parameter::Index);

    // A spring from a particle to itself (free or pinned).
    refused(&mut f, Error::SameParticle, |s| s.add_spring(a, a, 1.0, t));
    refused(&mut f, Error::SameParticle, |s| {
        s.add_spring(pin, pin, 1.0, t)
    });
    refused(&mut f, Error::SameParticle, |s| {
        s.add_spring_at_rest(c, c, t)
    });

    // Unknown ids, in every call that takes one.
    for p in f.unknown_particles {
        refused(&mut f, index, |s| s.add_spring(p, a, 1.0, t));
        refused(&mut f, index, |s| s.add_spring(a, p, 1.0, t));
        refused(&mut f, index, |s| s.add_spring_at_rest(p, a, t));
        refused(&mut f, index, |s| s.add_anchor(v2(0.0, 0.0), p, 1.0, t));
        refused(&mut f, index, |s| s.remove_particle(p));
        refused(&mut f, index, |s| s.set_mass(p, Some(1.0)));
        refused(&mut f, index, |s| s.set_mass(p, None));
        refused(&mut f, index, |s| s.set_position(p, v2(0.0, 0.0)));
        refused(&mut f, index, |s| s.set_velocity(p, v2(0.0, 0.0)));
        refused(&mut f, index, |s| s.apply_impulse(p, [0.0, 0.0]));
        refused(&mut f, index, |s| s.position(p));
        refused(&mut f, index, |s| s.step_velocity(p));
        refused(&mut f, index, |s| s.velocity(p));
        refused(&mut f, index, |s| s.is_pinned(p));
        refused(&mut f, index, |s| s.is_asleep(p));
        // An unknown id is reported before a same-particle spring.
        refused(&mut f, index, |s| s.add_spring(p, p, 1.0, t));
    }
    for k in f.unknown_springs {
        refused(&mut f, index, |s| s.remove_spring(k));
        refused(&mut f, index, |s| s.set_tuning(k, t));
        refused(&mut f, index, |s| s.rest_length(k));
        refused(&mut f, index, |s| s.ends(k));
        refused(&mut f, index, |s| s.tuning(k));
    }

    // Masses: zero, negative, NaN, infinite; in add_particle and set_mass.
    let mass = Parameter::Mass;
    for (m, e) in [
        (0.0, Error::NotPositive(mass)),
        (-0.0, Error::NotPositive(mass)),
        (-1.0, Error::NotPositive(mass)),
        (NAN, Error::NotFinite(mass)),
        (INF, Error::NotFinite(mass)),
        (-INF, Error::NotFinite(mass)),
    ] {
        refused(&mut f, e, |s| s.add_particle(v2(3.0, 0.0), m));
        refused(&mut f, e, |s| s.set_mass(b, Some(m)));
        refused(&mut f, e, |s| s.set_mass(pin, Some(m)));
    }

    // Rest lengths: zero, negative, NaN, infinite; in add_spring and add_anchor (which
    // then removes its anchor again); coincident particles for add_spring_at_rest.
    let rest = Parameter::RestLength;
    for (l, e) in [
        (0.0, Error::NotPositive(rest)),
        (-0.0, Error::NotPositive(rest)),
        (-1.0, Error::NotPositive(rest)),
        (NAN, Error::NotFinite(rest)),
        (INF, Error::NotFinite(rest)),
        (-INF, Error::NotFinite(rest)),
    ] {
        refused(&mut f, e, |s| s.add_spring(a, c, l, t));
        refused(&mut f, e, |s| s.add_anchor(v2(3.0, 3.0), c, l, t));
    }
    let (at_a, at_c) = (f.scene.position(a).unwrap(), f.scene.position(c).unwrap());
    f.scene.set_position(c, at_a).unwrap();
    refused(&mut f, Error::NotPositive(rest), |s| {
        s.add_spring_at_rest(a, c, t)
    });
    f.scene.set_position(c, at_c).unwrap();

    // Pinned particles take no velocity and no impulse.
    refused(&mut f, Error::Pinned, |s| s.set_velocity(pin, v2(1.0, 0.0)));
    refused(&mut f, Error::Pinned, |s| s.apply_impulse(pin, [1.0, 0.0]));

    // Impulses: NaN, infinite, or so large the step velocity leaves the safe range.
    let impulse = Parameter::Impulse;
    for j in [[NAN, 0.0], [0.0, INF], [-INF, 0.0]] {
        refused(&mut f, Error::NotFinite(impulse), |s| s.apply_impulse(b, j));
    }
    let huge = 4.0 * S::SAFE_MAGNITUDE / 0.01;
    refused(&mut f, Error::OutOfRange(impulse), |s| {
        s.apply_impulse(b, [0.0, huge])
    });

    // Full capacity: one particle and one spring fit; then nothing more, and a failed
    // add_anchor leaves no anchor behind.
    let d = f.scene.add_particle(v2(3.0, 0.0), 1.0).unwrap();
    refused(&mut f, Error::CapacityFull, |s| {
        s.add_particle(v2(4.0, 0.0), 1.0)
    });
    refused(&mut f, Error::CapacityFull, |s| s.add_pinned(v2(4.0, 0.0)));
    refused(&mut f, Error::CapacityFull, |s| {
        s.add_anchor(v2(4.0, 0.0), d, 1.0, t)
    });
    f.scene.add_spring(c, d, 1.0, t).unwrap();
    refused(&mut f, Error::CapacityFull, |s| s.add_spring(a, d, 1.0, t));
    // Removing d frees a particle slot and its spring's slot; fill the spring slot: now
    // add_anchor can add its anchor but not its spring, and must take the anchor back.
    f.scene.remove_particle(d).unwrap();
    f.scene.add_spring(pin, c, 1.0, t).unwrap();
    refused(&mut f, Error::CapacityFull, |s| {
        s.add_anchor(v2(4.0, 0.0), c, 1.0, t)
    });
    refused(&mut f, Error::CapacityFull, |s| s.add_spring(a, c, 1.0, t));

    // The network limit under Reject: b carries two springs (limit(2)).
    let spring = f.spring;
    refused(&mut f, Error::ExceedsNetworkLimit, |s| {
        s.set_tuning(spring, Tuning::rigid())
    });
    // Freeing the anchor makes its two springs count on it (0.3 and 0.1 are within the
    // limit for two), and raising one above that limit is still refused.
    f.scene.set_mass(pin, Some(1.0)).unwrap();
    let over =
        stiffspring::scene::network_limit(2, stiffspring::scene::Stepper::GaussSeidel) + 0.01;
    refused(&mut f, Error::ExceedsNetworkLimit, |s| {
        s.set_tuning(spring, Tuning::from_coefficients(over, 0.3).unwrap())
    });
    f.scene.set_mass(pin, None).unwrap();
}

/// Positions, velocities: NaN, infinite, beyond the safe magnitude (floats only: a
/// fixed-point value cannot be any of these).
fn float_positions<S: Scalar, L: LengthKernel<S>>(from: fn(f64) -> S) {
    let mut f = fixture::<S, L>();
    let [a, _, _] = f.free;
    let pin = f.pinned;
    let position = Parameter::Position;
    let beyond = 2.0 * S::SAFE_MAGNITUDE;
    for (x, e) in [
        (NAN, Error::NotFinite(position)),
        (INF, Error::NotFinite(position)),
        (-INF, Error::NotFinite(position)),
        (beyond, Error::OutOfRange(position)),
        (-beyond, Error::OutOfRange(position)),
    ] {
        for p in [[from(x), S::ZERO], [S::ZERO, from(x)]] {
            refused(&mut f, e, |s| s.add_particle(p, 1.0));
            refused(&mut f, e, |s| s.add_pinned(p));
            refused(&mut f, e, |s| s.set_position(a, p));
            refused(&mut f, e, |s| s.set_position(pin, p));
            refused(&mut f, e, |s| {
                s.add_anchor(p, a, 1.0, Tuning::from_coefficients(0.1, 0.1).unwrap())
            });
        }
    }
    let velocity = Parameter::Velocity;
    for (v, e) in [
        (NAN, Error::NotFinite(velocity)),
        (INF, Error::NotFinite(velocity)),
        (-INF, Error::NotFinite(velocity)),
        // v·dt beyond the safe magnitude (dt = 0.01).
        (beyond * 200.0, Error::OutOfRange(velocity)),
    ] {
        let v = from(v);
        refused(&mut f, e, |s| s.set_velocity(a, [v, S::ZERO]));
        refused(&mut f, e, |s| s.set_velocity(a, [S::ZERO, v]));
    }
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

#[test]
fn non_finite_positions_and_velocities_are_refused() {
    float_positions::<f64, Exact>(|x| x);
    float_positions::<f32, Exact>(|x| x as f32);
    float_positions::<f32, Linearised>(|x| x as f32);
}

#[test]
fn fixed_point_velocities_beyond_the_step_range_are_refused() {
    // 30 000 units/s at dt = 10 s is a step of 300 000 units: beyond I16F16's range.
    let mut s = Scene::<I16F16, 1, 1, 1>::new(SceneConfig::new(10.0).unwrap()).unwrap();
    let p = s.add_particle([I16F16::ZERO], 1.0).unwrap();
    assert_eq!(
        s.set_velocity(p, [I16F16::from_num(30_000)]),
        Err(Error::OutOfRange(Parameter::Velocity))
    );
    assert_eq!(s.step_velocity(p).unwrap(), [I16F16::ZERO]);
}

#[test]
fn angular_rest_angles_may_be_any_finite_value() {
    let mut s = AngularScene::<f32, 2, 2>::new(SceneConfig::new(0.01).unwrap()).unwrap();
    let a = s.add_pinned([0.0]).unwrap();
    let b = s.add_particle([1.0], 0.1).unwrap();
    let t = Tuning::from_coefficients(0.1, 0.1).unwrap();
    for (l, e) in [
        (NAN, Error::NotFinite(Parameter::RestLength)),
        (INF, Error::NotFinite(Parameter::RestLength)),
    ] {
        assert_eq!(s.add_spring(a, b, l, t), Err(e));
        assert_eq!(s.spring_count(), 0);
    }
    assert_eq!(s.add_spring(a, b, 0.0, t).unwrap().clamped, 0);
    assert_eq!(s.add_spring(a, b, -20.0, t).unwrap().clamped, 0);
    assert_eq!(
        s.add_spring(a, b, 1.0, t),
        Err(Error::CapacityFull),
        "two springs fit"
    );
    assert_eq!(s.add_spring(b, b, 1.0, t), Err(Error::SameParticle));
}

#[test]
fn bad_configuration_gets_a_typed_error() {
    for (dt, e) in [
        (0.0, Error::NotPositive(Parameter::TimeStep)),
        (-0.01, Error::NotPositive(Parameter::TimeStep)),
        (NAN, Error::NotFinite(Parameter::TimeStep)),
        (INF, Error::NotFinite(Parameter::TimeStep)),
    ] {
        assert_eq!(SceneConfig::<2>::new(dt), Err(e));
    }
    let config = SceneConfig::<2>::new(0.01).unwrap();
    for g in [[NAN, 0.0], [0.0, INF], [-INF, 0.0]] {
        assert_eq!(
            config.gravity(g),
            Err(Error::NotFinite(Parameter::Acceleration))
        );
    }
    for (v, t) in [(0.0, 1.0), (1.0, 0.0), (-1.0, 1.0), (NAN, 1.0), (1.0, INF)] {
        assert!(matches!(
            SleepThreshold::new(v, t),
            Err(Error::NotPositive(Parameter::Threshold) | Error::NotFinite(Parameter::Threshold))
        ));
    }
}

#[test]
fn reject_policy_refuses_and_changes_nothing() {
    let mut s = Scene::<f32, 2, 4, 4>::new(
        SceneConfig::new(0.01)
            .unwrap()
            .limit_policy(LimitPolicy::Reject),
    )
    .unwrap();
    let p: Vec<_> = (0..4)
        .map(|i| s.add_particle([i as f32, 0.0], 1.0).unwrap())
        .collect();
    s.add_spring(p[0], p[1], 1.0, Tuning::rigid()).unwrap();
    let before = snapshot(&s);
    assert_eq!(
        s.add_spring(
            p[1],
            p[2],
            1.0,
            Tuning::from_coefficients(0.1, 0.1).unwrap()
        ),
        Err(Error::ExceedsNetworkLimit)
    );
    assert_eq!(snapshot(&s), before);
}

// ---------------------------------------------------------------------------
// Gaps found by these tests (ignored until fixed in src/)
// ---------------------------------------------------------------------------

#[test]
fn masses_whose_inverse_overflows_are_refused() {
    let mut s = Scene::<f64, 2, 2, 1>::new(SceneConfig::new(0.01).unwrap().no_sleep()).unwrap();
    let b = s.add_particle([2.0, 0.0], 1.0).unwrap();
    // 1/1e-320 = ∞: the particle would have an infinite inverse mass.
    assert_eq!(
        s.add_particle([0.0, 0.0], 1e-320),
        Err(Error::OutOfRange(Parameter::Mass))
    );
    assert_eq!(
        s.set_mass(b, Some(1e-320)),
        Err(Error::OutOfRange(Parameter::Mass))
    );
}

#[test]
fn rest_lengths_beyond_the_backend_range_are_refused() {
    let mut s = Scene::<I16F16, 1, 2, 1>::new(SceneConfig::new(0.01).unwrap()).unwrap();
    let a = s.add_particle([I16F16::ZERO], 1.0).unwrap();
    let b = s.add_particle([I16F16::ONE], 1.0).unwrap();
    assert_eq!(
        s.add_spring(a, b, 1e6, Tuning::rigid()),
        Err(Error::OutOfRange(Parameter::RestLength))
    );
}
