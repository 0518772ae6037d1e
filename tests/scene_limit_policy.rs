//! The scene's network-limit policy: what it refuses, what it clamps, and what it counts.
//!
//! - [`LimitPolicy::Reject`] refuses any change that would put a spring or a neighbour
//!   above [`network_limit`] (a new spring, a retune, a pinned hub set free), reports the
//!   coefficient and the limit it broke, and changes nothing.
//! - [`LimitPolicy::Clamp`] lowers them to the limit and counts them in
//!   [`Added::clamped`]; a clamped mesh stays stable.
//! - Every limit is a multiple of 2⁻²⁴, exact in every backend's gain format, so a spring
//!   at exactly the limit stays accepted.
//! - A kernel that hardens with stretch ([`Linearised`]) is checked with its stiffening
//!   at the stretch the spring is added with: its axial stiffness `C_k·(3s² − 1)/2` and
//!   damping `C_d·s²` must be within the limit. The factors are checked here against the
//!   kernel's own extension, differentiated numerically.
//!
//! The limits themselves are measured in `tests/network_limits.rs`.

use proptest::prelude::*;
use stiffspring::length::{Exact, LengthKernel, Linearised};
use stiffspring::scene::{
    Added, LimitPolicy, ParticleId, Scene, SceneConfig, SpringId, Stepper, network_limit,
};
use stiffspring::{Error, I16F16, I32F32, Scalar, Tuning};

/// The time step of every scene here.
const DT: f64 = 0.01;

/// Raw coefficients at [`DT`].
fn coefficients(ck: f64, cd: f64) -> Tuning {
    Tuning::from_coefficients(ck, cd, DT).unwrap()
}

fn rigid() -> Tuning {
    Tuning::rigid(DT).unwrap()
}

/// True for the error of a spring above the network limit `limit`.
fn over_limit<T: std::fmt::Debug>(result: Result<T, Error>, limit: f64) -> bool {
    matches!(result, Err(Error::ExceedsNetworkLimit { limit: l, .. }) if (l - limit).abs() < 1e-12)
}

/// The limit's shape (its values are derived and measured in docs/networks.md and
/// tests/network_limits.rs): 1 for a lone spring, falling with the share count, never
/// stricter than the article's 1/(n + 1), Jacobi at most Gauss-Seidel, and exactly
/// representable in every coefficient format (a multiple of 2⁻²⁴).
#[test]
fn network_limit_falls_with_the_share_count_for_both_steppers() {
    for stepper in [Stepper::GaussSeidel, Stepper::Jacobi] {
        assert_eq!(network_limit(0, stepper), 1.0);
        assert_eq!(network_limit(1, stepper), 1.0);
        for n in 2..64 {
            let l = network_limit(n, stepper);
            assert!(l < network_limit(n - 1, stepper) || n == 2 && l <= 1.0);
            assert!(l >= 1.0 / (n as f64 + 1.0), "{stepper:?} {n}: {l}");
            assert_eq!((l * (1u64 << 24) as f64).fract(), 0.0);
            assert!(network_limit(n, Stepper::Jacobi) <= network_limit(n, Stepper::GaussSeidel));
        }
    }
}

/// The limit for `n` springs per particle with the default (Gauss-Seidel) stepper.
fn limit(n: usize) -> f64 {
    network_limit(n, Stepper::GaussSeidel)
}

/// Everything a failed call must leave unchanged.
fn snapshot<S: Scalar, const D: usize, const P: usize, const K: usize>(
    s: &Scene<S, D, P, K>,
) -> String {
    let particles: Vec<_> = s
        .particles()
        .map(|(p, x)| (p, x, s.is_pinned(p).unwrap(), s.velocity(p).unwrap()))
        .collect();
    let springs: Vec<_> = s
        .springs()
        .map(|(k, a, b)| (k, a, b, s.tuning(k).unwrap(), s.rest_length(k).unwrap()))
        .collect();
    format!("{particles:?} {springs:?} {:?}", s.active())
}

/// A chain p0 – p1 – p2 of free particles in f64 with the given policy, springs at
/// `(ck, cd)`, and a fourth free particle p3 on its own.
fn chain(
    policy: LimitPolicy,
    ck: f64,
    cd: f64,
) -> (Scene<f64, 2, 5, 5>, Vec<ParticleId>, Vec<Added>) {
    let config = SceneConfig::new(DT).unwrap().limit_policy(policy);
    let mut s = Scene::<f64, 2, 5, 5>::new(config);
    let p: Vec<_> = (0..4)
        .map(|i| s.add_particle([i as f64, 0.0], 1.0).unwrap())
        .collect();
    let added = vec![
        s.add_spring(p[0], p[1], 1.0, &coefficients(ck, cd))
            .unwrap(),
        s.add_spring(p[1], p[2], 1.0, &coefficients(ck, cd))
            .unwrap(),
    ];
    (s, p, added)
}

#[test]
fn reject_refuses_a_spring_over_its_own_limit_and_changes_nothing() {
    let (mut s, p, _) = chain(LimitPolicy::Reject, 0.3, 0.3);
    let before = snapshot(&s);
    // p2 would carry two springs: the limit is limit(2).
    let over = limit(2) + 0.01;
    for t in [&coefficients(over, 0.1), &coefficients(0.1, over), &rigid()] {
        assert!(over_limit(s.add_spring(p[2], p[3], 1.0, t), limit(2)));
        assert_eq!(snapshot(&s), before);
    }
    // Exactly at the limit is accepted.
    let at = limit(2);
    let added = s
        .add_spring(p[2], p[3], 1.0, &coefficients(at, at))
        .unwrap();
    assert_eq!(added.clamped, 0);
    assert_eq!(s.tuning(added.spring).unwrap().stiffness(), at);
}

#[test]
fn reject_refuses_a_spring_that_pushes_a_neighbour_over_its_limit() {
    // The chain between limit(3) and limit(2): fine with two springs on p1, not three.
    let c = 0.5 * (limit(2) + limit(3));
    let (mut s, p, added) = chain(LimitPolicy::Reject, c, c);
    let before = snapshot(&s);
    // A third spring on p1: its own 0.2 is within limit(3), but the chain's are not.
    assert!(over_limit(
        s.add_spring(p[1], p[3], 1.0, &coefficients(0.2, 0.2)),
        limit(3)
    ));
    assert_eq!(snapshot(&s), before);
    // Retuning above the limit is refused too, and within it accepted.
    assert!(over_limit(
        s.set_tuning(added[0].spring, &coefficients(limit(2) + 0.01, 0.1)),
        limit(2)
    ));
    assert_eq!(snapshot(&s), before);
    let retuned = s
        .set_tuning(added[0].spring, &coefficients(0.2, 0.1))
        .unwrap();
    assert_eq!(retuned.clamped, 0);
    assert_eq!(s.tuning(added[0].spring).unwrap().stiffness(), 0.2);
}

/// A pinned hub with three rigid springs: each free end carries one spring, so the
/// rigid spring is fine. Freeing the hub makes the three compete (limit(3)).
fn hub(policy: LimitPolicy) -> (Scene<f64, 2, 8, 8>, ParticleId, Vec<SpringId>) {
    let config = SceneConfig::new(DT).unwrap().limit_policy(policy);
    let mut s = Scene::<f64, 2, 8, 8>::new(config);
    let hub = s.add_pinned([0.0, 0.0]).unwrap();
    let mut springs = Vec::new();
    for i in 0..3 {
        let p = s.add_particle([i as f64, 1.0], 1.0).unwrap();
        let added = s.add_spring(hub, p, 1.0, &rigid()).unwrap();
        assert_eq!(added.clamped, 0, "pinned ends do not compete");
        springs.push(added.spring);
    }
    (s, hub, springs)
}

#[test]
fn reject_refuses_freeing_a_pinned_hub_whose_springs_would_compete() {
    let (mut s, hub, _) = hub(LimitPolicy::Reject);
    let before = snapshot(&s);
    assert!(over_limit(s.set_mass(hub, Some(1.0)), limit(3)));
    assert_eq!(snapshot(&s), before);
    assert!(s.is_pinned(hub).unwrap());
}

#[test]
fn a_free_hub_limits_its_springs_by_their_number() {
    let config = SceneConfig::new(DT).unwrap();
    let mut s = Scene::<f64, 2, 8, 8>::new(config);
    let hub = s.add_particle([0.0, 0.0], 1.0).unwrap();
    for i in 0..6 {
        let p = s.add_particle([i as f64, 1.0], 1.0).unwrap();
        // Six springs on the hub in the end: limit(6) for all of them.
        s.add_spring(hub, p, 1.0, &coefficients(limit(6), 0.1))
            .unwrap();
    }
    let p = s.add_particle([9.0, 1.0], 1.0).unwrap();
    let before = snapshot(&s);
    // A seventh: limit(7) is needed for all, and the others are at limit(6).
    assert!(over_limit(
        s.add_spring(hub, p, 1.0, &coefficients(0.01, 0.01)),
        limit(7)
    ));
    assert_eq!(snapshot(&s), before);
}

#[test]
fn clamp_lowers_the_spring_and_its_neighbours_and_counts_them() {
    let (mut s, p, added) = chain(LimitPolicy::Clamp, 1.0, 1.0);
    // The chain itself: the second rigid spring made p1 carry two, so both are at
    // limit(2).
    assert_eq!(added[0].clamped, 0);
    assert_eq!(added[1].clamped, 2);
    for a in &added {
        let t = s.tuning(a.spring).unwrap();
        assert_eq!(t.stiffness(), limit(2));
        assert!((t.damping() - limit(2)).abs() < 1e-15);
    }
    // A third spring on p1, rigid: itself and both neighbours to limit(3).
    let third_spring = s.add_spring(p[1], p[3], 1.0, &rigid()).unwrap();
    assert_eq!(third_spring.clamped, 3);
    for spring in [added[0].spring, added[1].spring, third_spring.spring] {
        let t = s.tuning(spring).unwrap();
        assert_eq!(t.stiffness(), limit(3));
        assert!((t.damping() - limit(3)).abs() < 1e-15);
    }
    // Retuning: clamped to the limit, counted once; within the limit, not clamped.
    let retuned = s.set_tuning(added[0].spring, &rigid()).unwrap();
    assert_eq!(retuned.clamped, 1);
    assert_eq!(s.tuning(added[0].spring).unwrap().stiffness(), limit(3));
    let retuned = s
        .set_tuning(added[0].spring, &coefficients(0.1, 0.2))
        .unwrap();
    assert_eq!(retuned.clamped, 0);
    assert_eq!(s.tuning(added[0].spring).unwrap().stiffness(), 0.1);
    // Only the coefficient above the limit moves.
    let retuned = s
        .set_tuning(added[0].spring, &coefficients(0.1, 0.9))
        .unwrap();
    assert_eq!(retuned.clamped, 1);
    let t = s.tuning(added[0].spring).unwrap();
    assert_eq!(t.stiffness(), 0.1);
    assert!((t.damping() - limit(3)).abs() < 1e-15);
}

#[test]
fn clamp_lowers_the_springs_of_a_freed_hub() {
    let (mut s, hub, springs) = hub(LimitPolicy::Clamp);
    s.set_mass(hub, Some(1.0)).unwrap();
    assert!(!s.is_pinned(hub).unwrap());
    for spring in springs {
        let t = s.tuning(spring).unwrap();
        assert_eq!(t.stiffness(), limit(3));
        assert!((t.damping() - limit(3)).abs() < 1e-15);
    }
}

#[test]
fn clamped_scenes_stay_stable() {
    // A mesh of rigid springs, clamped: every spring ends at or below its limit, and the
    // jelly, squashed, springs back without blowing up, in both steppers.
    for stepper in [Stepper::GaussSeidel, Stepper::Jacobi] {
        let config = SceneConfig::new(DT)
            .unwrap()
            .stepper(stepper)
            .limit_policy(LimitPolicy::Clamp)
            .no_sleep();
        let mut s = Scene::<f32, 2, 16, 64>::new(config);
        let ids: Vec<_> = (0..16)
            .map(|i| {
                let (c, r) = ((i % 4) as f32, (i / 4) as f32);
                s.add_particle([0.25 * c * 1.3, 0.25 * r * 0.7], 1.0)
                    .unwrap()
            })
            .collect();
        let mut total = 0;
        for i in 0..16 {
            let (c, r) = (i % 4, i / 4);
            let mut link = |j: usize, rest: f32| {
                total += s
                    .add_spring(ids[i], ids[j], rest, &rigid())
                    .unwrap()
                    .clamped;
            };
            if c < 3 {
                link(i + 1, 0.25);
            }
            if r < 3 {
                link(i + 4, 0.25);
            }
            if c < 3 && r < 3 {
                link(i + 5, 0.25 * std::f32::consts::SQRT_2);
            }
        }
        assert!(total >= s.spring_count());
        for (k, a, b) in s.springs() {
            let degree = [a, b]
                .iter()
                .map(|&p| s.springs().filter(|&(_, x, y)| x == p || y == p).count())
                .max()
                .unwrap();
            let limit = network_limit(degree, stepper);
            let t = s.tuning(k).unwrap();
            // f32 rounds the limit to nearest: allow its half ulp.
            assert!(t.stiffness() <= limit * (1.0 + 1e-7), "{t:?} vs {limit}");
            assert!(t.damping() <= limit * (1.0 + 1e-7), "{t:?} vs {limit}");
        }
        for _ in 0..2000 {
            let _ = s.step();
        }
        for (_, x) in s.particles() {
            assert!(x[0].abs() < 2.0 && x[1].abs() < 2.0, "{stepper:?}: {x:?}");
        }
    }
}

/// The limit is checked against the coefficients as the backend stores them. Every
/// limit is a multiple of 2⁻²⁴, so a spring set to exactly the limit is stored exactly
/// at it, and counts as within it at every later check of its neighbourhood: a rope at
/// the Gauss-Seidel limit for two springs per particle (¾), and a particle with three
/// springs at the Jacobi limit for three (the multiple of 2⁻²⁴ nearest ⅓).
fn spring_at_exactly_the_limit<S: Scalar>() {
    for (stepper, n) in [(Stepper::GaussSeidel, 2), (Stepper::Jacobi, 3)] {
        let l = network_limit(n, stepper);
        let config = SceneConfig::new(DT).unwrap().stepper(stepper);
        let mut s = Scene::<S, 2, 4, 3>::new(config);
        let p: Vec<_> = (0..4)
            .map(|i| {
                let at = [S::from_f64(i as f64), S::ZERO];
                s.add_particle(at, S::ONE).unwrap()
            })
            .collect();
        let t = &coefficients(l, l);
        let springs = [(0, 1), (1, 2), (1, 3)];
        for &(a, b) in &springs[..n] {
            let added = s.add_spring(p[a], p[b], S::ONE, t);
            assert_eq!(added.map(|a| a.clamped), Ok(0), "{} {stepper:?}", S::NAME);
        }
        for (k, _, _) in s.springs() {
            assert_eq!(s.tuning(k).unwrap().stiffness(), l, "{}", S::NAME);
        }
    }
}

#[test]
fn a_rope_at_exactly_the_limit_is_accepted_in_every_backend() {
    spring_at_exactly_the_limit::<f64>();
    spring_at_exactly_the_limit::<I32F32>();
    spring_at_exactly_the_limit::<f32>();
    spring_at_exactly_the_limit::<I16F16>();
}

#[test]
fn clamp_counts_only_springs_it_changes() {
    let config = SceneConfig::new(DT)
        .unwrap()
        .limit_policy(LimitPolicy::Clamp);
    let mut s = Scene::<f32, 2, 4, 3>::new(config);
    let p: Vec<_> = (0..4)
        .map(|i| s.add_particle([i as f32, 0.0], 1.0).unwrap())
        .collect();
    s.add_spring(p[0], p[1], 1.0, &rigid()).unwrap();
    assert_eq!(s.add_spring(p[1], p[2], 1.0, &rigid()).unwrap().clamped, 2);
    // p0 gets a second spring, within every limit: p0–p1 still has two springs on its
    // busiest end, its limit is unchanged and nothing needs clamping.
    let added = s
        .add_spring(p[0], p[3], 1.0, &coefficients(0.1, 0.1))
        .unwrap();
    assert_eq!(added.clamped, 0);
}

// ---------------------------------------------------------------------------
// Stiffening kernels
// ---------------------------------------------------------------------------

/// The `Linearised` kernel's axial stiffness and damping at stretch `s`, relative to the
/// exact spring's, from its own extension: the derivative of the impulse `x·n` along the
/// axis (central difference), and the axis length squared (the damping impulse is
/// `C_d·(n·u)·n`).
fn linearised_factors(s: f64) -> (f64, f64) {
    let rest = <Linearised as LengthKernel<f64>>::rest(1.0);
    let impulse = |d: f64| {
        let (x, n) = <Linearised as LengthKernel<f64>>::measure(&[d, 0.0], &rest);
        x * n[0]
    };
    let h = 1e-6;
    let stiffness = (impulse(s + h) - impulse(s - h)) / (2.0 * h);
    let (_, n) = <Linearised as LengthKernel<f64>>::measure(&[s, 0.0], &rest);
    (stiffness, n[0] * n[0])
}

/// A rope of two springs (share count 2) whose second spring is added stretched by `s`
/// with kernel `L`, at `(ck, cd)`, under `policy`.
fn stretched_rope<L: LengthKernel<f64>>(
    s: f64,
    (ck, cd): (f64, f64),
    policy: LimitPolicy,
) -> Result<(Scene<f64, 2, 3, 2, L>, Added), Error> {
    let config = SceneConfig::new(DT)?.limit_policy(policy);
    let mut scene = Scene::<f64, 2, 3, 2, L>::new(config);
    let p = [
        scene.add_particle([0.0, 0.0], 1.0)?,
        scene.add_particle([1.0, 0.0], 1.0)?,
        scene.add_particle([1.0 + s, 0.0], 1.0)?,
    ];
    scene.add_spring(p[0], p[1], 1.0, &coefficients(0.1, 0.1))?;
    let added = scene.add_spring(p[1], p[2], 1.0, &coefficients(ck, cd))?;
    Ok((scene, added))
}

#[test]
fn a_stretched_linearised_spring_is_held_to_the_limit_of_its_stiffening() {
    let limit = network_limit(2, Stepper::GaussSeidel);
    for s in [1.1, 1.25, 1.5] {
        let (a, b) = linearised_factors(s);
        // The kernel's factors are the documented ones...
        assert!((a - (3.0 * s * s - 1.0) / 2.0).abs() < 1e-6, "{s}: {a}");
        assert!((b - s * s).abs() < 1e-12, "{s}: {b}");
        // The limits they allow (from the closed forms the derivatives just matched).
        let (ka, kb) = (limit / ((3.0 * s * s - 1.0) / 2.0), limit / (s * s));
        // ...and the scene holds the spring to them: just within is accepted, just above
        // refused with the stiffened limit, and the exact kernel takes the plain limit.
        let reject = LimitPolicy::Reject;
        assert!(stretched_rope::<Linearised>(s, (ka * 0.999, kb * 0.999), reject).is_ok());
        let over = stretched_rope::<Linearised>(s, (ka * 1.001, 0.0), reject);
        assert!(over_limit(over.map(|r| r.1), ka), "{s}");
        let over = stretched_rope::<Linearised>(s, (0.0, kb * 1.001), reject);
        assert!(over_limit(over.map(|r| r.1), kb), "{s}");
        assert!(stretched_rope::<Exact>(s, (limit, limit), reject).is_ok());
        // Clamped: to exactly the stiffened limits.
        let (scene, added) =
            stretched_rope::<Linearised>(s, (limit, limit), LimitPolicy::Clamp).unwrap();
        assert_eq!(added.clamped, 1);
        let t = scene.tuning(added.spring).unwrap();
        assert!((t.stiffness() - ka).abs() < 1e-6 * ka, "{s}: {t:?}");
        assert!((t.damping() - kb).abs() < 1e-6 * kb, "{s}: {t:?}");
    }
    // Compressed (s < 1) it is softer than the exact spring: no factor.
    assert!(stretched_rope::<Linearised>(0.9, (limit, limit), LimitPolicy::Reject).is_ok());
}

/// A lone spring (no other spring on its free ends) is one spring in the relative
/// coordinate of its ends: a scene takes it wherever a `SpringValue` takes the tuning,
/// beyond the article's square up to Jury's `C_k + 2·C_d < 4`, in every backend, for one
/// free end (a pin) and for two (masses 1 and 3). Each runs 4 000 steps and stays within
/// the value's transient bound (`Tuning::growth`) of its start.
fn lone_springs_run_as_values<S: Scalar>() {
    let mut tunings = Vec::new();
    // The raw plane beyond the square, on a grid inside Jury's region.
    for i in 1..40 {
        for j in 0..20 {
            let (ck, cd) = (i as f64 * 0.1, j as f64 * 0.1);
            if let Ok(t) = Tuning::from_coefficients_extended(ck, cd, DT) {
                tunings.push(t);
            }
        }
    }
    // Undersampled exact maps: f·dt up to 0.45, ζ from 0 to 1.
    for f_dt in [0.17, 0.2, 0.3, 0.4, 0.45] {
        for zeta in [0.0, 0.1, 0.5, 1.0] {
            tunings.push(Tuning::from_frequency(f_dt / DT, zeta, DT).unwrap());
        }
    }
    let mut beyond = 0;
    for t in &tunings {
        let value = stiffspring::SpringValue::<S>::new([S::ZERO], t);
        if value.is_err() {
            continue; // a gain the backend cannot hold: not this test's subject
        }
        beyond += usize::from(t.stiffness() > 1.0 || t.damping() > 1.0);
        for free_pair in [false, true] {
            let mut s = Scene::<S, 1, 2, 1>::new(SceneConfig::new(DT).unwrap().no_sleep());
            let a = if free_pair {
                s.add_particle([S::ZERO], S::from_f64(3.0)).unwrap()
            } else {
                s.add_pinned([S::ZERO]).unwrap()
            };
            let b = s.add_particle([S::ONE], S::ONE).unwrap();
            let added = s.add_spring(a, b, S::ZERO, t);
            assert!(
                added.is_ok(),
                "{} {t:?} free pair {free_pair}: {added:?}",
                S::NAME
            );
            let bound = 2.0 * t.growth() + 1.0;
            for _ in 0..4000 {
                let _ = s.step();
                let d = s.position(b).unwrap()[0].to_f64() - s.position(a).unwrap()[0].to_f64();
                assert!(d.abs() <= bound, "{} {t:?}: {d} > {bound}", S::NAME);
            }
        }
    }
    assert!(beyond > 100, "{beyond}");
}

#[test]
fn a_lone_spring_is_accepted_wherever_a_value_accepts_it() {
    lone_springs_run_as_values::<f64>();
    lone_springs_run_as_values::<f32>();
    lone_springs_run_as_values::<I32F32>();
    lone_springs_run_as_values::<I16F16>();
    // A spring in a rope is still held to the network limit.
    let mut s = Scene::<f64, 1, 3, 2>::new(SceneConfig::new(DT).unwrap());
    let p: Vec<_> = (0..3)
        .map(|i| s.add_particle([i as f64], 1.0).unwrap())
        .collect();
    let wide = Tuning::from_coefficients_extended(1.5, 0.2, DT).unwrap();
    s.add_spring(p[0], p[1], 1.0, &wide).unwrap();
    assert!(over_limit(s.add_spring(p[1], p[2], 1.0, &wide), limit(2)));
}

/// The drag lowers a lone spring's damping (`1 − C_d → r·(1 − C_d)`) and with it Jury's
/// bound on `C_k` (`C_k < 2 + 2·r·(1 − C_d)`): an undersampled spring that the drag would
/// take out of its region is refused, with the drag it can have.
#[test]
fn a_drag_cannot_take_a_lone_spring_out_of_its_region() {
    let t = Tuning::from_coefficients_extended(3.5, 0.1, DT).unwrap();
    // With a drag of 50 per second (r = 0.61 at 100 Hz): 3.5 > 2 + 2·0.61·0.9 = 3.1.
    let config = SceneConfig::new(DT).unwrap().linear_damping(50.0).unwrap();
    let mut s = Scene::<f64, 1, 2, 1>::new(config);
    let pin = s.add_pinned([0.0]).unwrap();
    let body = s.add_particle([1.0], 1.0).unwrap();
    let refused = s.add_spring(pin, body, 0.0, &t);
    assert!(
        matches!(refused, Err(Error::ExceedsNetworkLimit { limit, .. }) if (limit - (2.0 + 2.0 * (-0.5f64).exp() * 0.9)).abs() < 1e-6),
        "{refused:?}"
    );
    // Without drag it is accepted; a drag added later is refused with the largest one
    // that keeps it: r > (3.5 − 2)/(2·0.9), c < −ln(0.833)/dt = 18.2 per second.
    s.set_linear_damping(body, 0.0).unwrap();
    s.add_spring(pin, body, 0.0, &t).unwrap();
    match s.set_linear_damping(body, 50.0) {
        Err(Error::OutOfRange {
            parameter: stiffspring::Parameter::LinearDamping,
            bound: stiffspring::Bound::Below { max },
            ..
        }) => assert!((max - (-(1.5f64 / 1.8).ln() / DT)).abs() < 1e-6, "{max}"),
        other => panic!("{other:?}"),
    }
    assert_eq!(s.linear_damping(body).unwrap(), 0.0);
    s.set_linear_damping(body, 18.0).unwrap();
}

/// The tunings a value takes near the edge of Jury's region, where a rounding of the
/// scene's test would refuse what a value accepts: raw coefficients `C_k` within
/// `10⁻¹²` to `30 %` of `4 − 2·C_d`, and exact maps up to `f·dt = 0.499` with `ζ` from
/// 0 to 10, at 60 Hz, 1 kHz and 10 kHz.
fn edge_tuning() -> impl Strategy<Value = Tuning> {
    let raw = (
        0.0f64..1.999,
        0.5f64..12.0,
        prop::sample::select(vec![1.0 / 60.0, 1e-3, 1e-4]),
    )
        .prop_filter_map("outside Jury's region", |(cd, digits, dt)| {
            let ck = (4.0 - 2.0 * cd) * (1.0 - 10f64.powf(-digits));
            Tuning::from_coefficients_extended(ck, cd, dt).ok()
        });
    let exact = (
        0.001f64..0.499,
        0.0f64..10.0,
        prop::sample::select(vec![1.0 / 60.0, 1e-3, 1e-4]),
    )
        .prop_filter_map("not a tuning", |(f_dt, zeta, dt)| {
            Tuning::from_frequency(f_dt / dt, zeta, dt).ok()
        });
    prop_oneof![raw, exact]
}

/// Every way a spring is lone: to a pin (1-D, and 2-D with a point spring or a rest
/// length, the pin holding a second body on its own spring), and between two free bodies
/// (masses 3 and 1). Each must be accepted when a value accepts the tuning, and stay
/// within the value's transient bound (`Tuning::growth`) for 400 steps.
fn lone_in_every_geometry<S: Scalar>(t: &Tuning) -> Result<(), TestCaseError> {
    if stiffspring::SpringValue::<S>::new([S::ZERO], t).is_err() {
        return Ok(()); // a gain the backend cannot hold: refused alike, not this test's subject
    }
    let bound = 2.0 * t.growth() + 1.0;
    for free_pair in [false, true] {
        let mut s = Scene::<S, 1, 2, 1>::new(SceneConfig::new(t.dt()).unwrap().no_sleep());
        let a = if free_pair {
            s.add_particle([S::ZERO], S::from_f64(3.0)).unwrap()
        } else {
            s.add_pinned([S::ZERO]).unwrap()
        };
        let b = s.add_particle([S::ONE], S::ONE).unwrap();
        let added = s.add_spring(a, b, S::ZERO, t);
        prop_assert!(
            added.is_ok(),
            "{} 1-D {t:?} free pair {free_pair}: {added:?}",
            S::NAME
        );
        for _ in 0..400 {
            let _ = s.step();
            let d = s.position(b).unwrap()[0].to_f64() - s.position(a).unwrap()[0].to_f64();
            prop_assert!(d.abs() <= bound, "{} 1-D {t:?}: {d} > {bound}", S::NAME);
        }
    }
    for rest in [0.0, 1.0] {
        let mut s = Scene::<S, 2, 3, 2>::new(SceneConfig::new(t.dt()).unwrap().no_sleep());
        let pin = s.add_pinned([S::ZERO, S::ZERO]).unwrap();
        let other = s.add_particle([S::ONE, S::ZERO], S::ONE).unwrap();
        s.add_spring(
            pin,
            other,
            S::ZERO,
            &Tuning::from_coefficients(0.5, 0.5, t.dt()).unwrap(),
        )
        .unwrap();
        let body = s
            .add_particle([S::from_f64(1.2), S::from_f64(1.6)], S::from_f64(2.0))
            .unwrap();
        let added = s.add_spring(pin, body, S::from_f64(rest), t);
        prop_assert!(
            added.is_ok(),
            "{} 2-D rest {rest} {t:?}: {added:?}",
            S::NAME
        );
        // The stretch is 2 − rest along (0.6, 0.8).
        let amplitude = 2.0 - rest;
        for _ in 0..400 {
            let _ = s.step();
            let p = s.position(body).unwrap();
            let x = p[0].to_f64().hypot(p[1].to_f64()) - rest;
            prop_assert!(
                x.abs() <= bound * amplitude,
                "{} 2-D rest {rest} {t:?}: {x}",
                S::NAME
            );
        }
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(200))]

    /// At the edge of the region too, in every backend: a lone spring is refused only
    /// where a value is.
    #[test]
    fn a_lone_spring_at_the_edge_of_the_region_is_accepted_as_a_value_is(t in edge_tuning()) {
        lone_in_every_geometry::<f64>(&t)?;
        lone_in_every_geometry::<f32>(&t)?;
        lone_in_every_geometry::<I32F32>(&t)?;
        lone_in_every_geometry::<I16F16>(&t)?;
    }
}
