//! The [`AngularScene`] against the independent f64 reference of angular networks in
//! `lab/src/reference/network.rs` (the article's eq. 22–26 and 28), in every backend and
//! with both steppers: bodies wound by whole turns unwind, an unwrapped spring all the
//! way, a [`WrappedAngle`] spring the short way.
//!
//! As in `tests/scene_vs_reference.rs`: both models start from the state the scene holds
//! (angles and inertias rounded to the backend, the stored step velocity), the reference
//! runs the coefficients and rest angles the scene stores, in the library's spring order;
//! the error is the largest `|θ_lib − θ_ref|` over bodies and steps, and the same for the
//! step `θ(t) − θ(t − dt)`, relative to the winding (6π); the library's angle is the one
//! it holds ([`Scene::precise_position`]). Bounds are about 3× the measured worst.
//!
//! `cargo test --release --test angular_vs_reference -- --nocapture --test-threads=1`
//! prints the tables and each run's final angular momentum.

use lab::reference::network::AngularNetwork;
use std::f64::consts::{PI, TAU};
use std::fmt::Write as _;
use stiffspring::length::LengthKernel;
use stiffspring::scene::{Angle, AngularScene, ParticleId, SceneConfig, Stepper, WrappedAngle};
use stiffspring::{I16F16, I32F32, Scalar, Tuning};

const STEPPERS: [Stepper; 2] = [Stepper::GaussSeidel, Stepper::Jacobi];

fn stepper_name(stepper: Stepper) -> &'static str {
    match stepper {
        Stepper::GaussSeidel => "Gauss-Seidel",
        Stepper::Jacobi => "Jacobi",
    }
}

/// The spring order the library runs: springs with exactly one pinned end first, then
/// the two-sided ones, each group in insertion order.
fn library_order(net: &mut AngularNetwork) {
    let pinned = |i: usize| net.bodies[i].is_pinned();
    let rank = |a: usize, b: usize| match (pinned(a), pinned(b)) {
        (true, true) => 2,
        (false, false) => 1,
        _ => 0,
    };
    let mut springs = net.springs.clone();
    springs.sort_by_key(|s| rank(s.a, s.b));
    net.springs = springs;
}

/// Largest error of one run, relative to the winding.
#[derive(Clone, Copy, Debug, Default)]
struct Errors {
    angle: f64,
    velocity: f64,
}

/// An angular scene built from a reference network, and the reference on its grid.
struct Pair<S: Scalar, L: LengthKernel<S>> {
    scene: AngularScene<S, 8, 8, L>,
    ids: Vec<ParticleId>,
    net: AngularNetwork,
}

fn build<S: Scalar, L: LengthKernel<S>>(
    net0: &AngularNetwork,
    dt: f64,
    stepper: Stepper,
) -> Pair<S, L> {
    let mut net = net0.clone();
    library_order(&mut net);
    let config = SceneConfig::<S, 1>::new(dt)
        .unwrap()
        .stepper(stepper)
        .no_sleep();
    let mut scene = AngularScene::<S, 8, 8, L>::new(config);
    let mut ids = Vec::new();
    for b in net.bodies.iter_mut() {
        let angle = S::from_f64(b.angle);
        b.angle = angle.to_f64();
        let id = if b.is_pinned() {
            scene.add_pinned([angle]).unwrap()
        } else {
            let inertia = S::from_f64(b.inertia);
            b.inertia = inertia.to_f64();
            let id = scene.add_particle([angle], inertia).unwrap();
            let omega = S::from_f64(b.omega);
            scene.set_velocity(id, [omega]).unwrap();
            b.omega = S::state_to_f64(S::scale(omega.widen(), S::factor(dt))) / dt;
            id
        };
        ids.push(id);
    }
    for s in net.springs.iter_mut() {
        let tuning = Tuning::from_coefficients(s.ck, s.cd, dt).unwrap();
        let added = scene
            .add_spring(ids[s.a], ids[s.b], S::from_f64(s.rest_angle), &tuning)
            .unwrap();
        assert_eq!(added.clamped, 0);
        let tuning = scene.tuning(added.spring).unwrap();
        (s.ck, s.cd) = (tuning.stiffness(), tuning.damping());
        s.rest_angle = scene.rest_length(added.spring).unwrap().to_f64();
    }
    // The scene keeps each body's next step, its springs' pull included; the reference
    // starts the same way, from its own pull.
    net.pull(dt);
    Pair { scene, ids, net }
}

/// Steps both `steps` times; the largest deviations relative to `size`.
fn run<S: Scalar, L: LengthKernel<S>>(
    pair: &mut Pair<S, L>,
    dt: f64,
    steps: usize,
    size: f64,
    stepper: Stepper,
) -> Errors {
    let held = |pair: &Pair<S, L>| -> Vec<f64> {
        pair.ids
            .iter()
            .map(|&id| pair.scene.precise_position(id).unwrap()[0])
            .collect()
    };
    let mut errors = Errors::default();
    let mut before = held(pair);
    let mut before_ref: Vec<f64> = pair.net.bodies.iter().map(|b| b.angle).collect();
    for _ in 0..steps {
        let _ = pair.scene.step();
        match stepper {
            Stepper::GaussSeidel => pair.net.step_gauss_seidel_kept(dt),
            Stepper::Jacobi => pair.net.step_jacobi_kept(dt),
        }
        let now = held(pair);
        for (i, b) in pair.net.bodies.iter().enumerate() {
            let d = (now[i] - b.angle).abs() / size;
            let du = ((now[i] - before[i]) - (b.angle - before_ref[i])).abs() / size;
            errors.angle = errors.angle.max(d);
            errors.velocity = errors.velocity.max(du);
        }
        before = now;
        before_ref = pair.net.bodies.iter().map(|b| b.angle).collect();
    }
    errors
}

/// One backend and stepper: the errors relative to the winding, after checking that the
/// first spring unwound to its rest angle within `tolerance` (radians), and the final
/// angular momentum `Σ I·ω`.
fn unwind<S: Scalar>(
    net: &AngularNetwork,
    dt: f64,
    steps: usize,
    stepper: Stepper,
    tolerance: f64,
) -> (Errors, f64) {
    let mut pair = build::<S, Angle>(net, dt, stepper);
    let errors = run(&mut pair, dt, steps, 3.0 * TAU, stepper);
    let scene = &pair.scene;
    let (spring, a, b) = scene.springs().next().unwrap();
    let angle = |p| scene.precise_position(p).unwrap()[0];
    let displacement = angle(b) - angle(a) - scene.rest_length(spring).unwrap().to_f64();
    assert!(
        displacement.abs() < tolerance,
        "{} {stepper:?}: displacement {displacement} after unwinding",
        S::NAME
    );
    (errors, scene.momentum()[0])
}

/// Every backend and stepper against `bounds` (f64, f32, I32F32, I16F16) on both
/// errors; prints the table and the final angular momenta.
fn check(title: &str, net: &AngularNetwork, steps: usize, bounds: [f64; 4]) {
    let dt = 1e-3;
    let mut out = format!(
        "\n{title}\n| stepper | backend | max |Δθ|/6π | max |Δu|/6π | bound | final Σ I·ω |\n|---|---|---|---|---|---|\n"
    );
    let mut failures = Vec::new();
    for stepper in STEPPERS {
        let results = [
            ("f64", unwind::<f64>(net, dt, steps, stepper, 1e-9)),
            ("f32", unwind::<f32>(net, dt, steps, stepper, 1e-4)),
            ("I32F32", unwind::<I32F32>(net, dt, steps, stepper, 1e-9)),
            ("I16F16", unwind::<I16F16>(net, dt, steps, stepper, 1e-6)),
        ];
        for ((name, (e, momentum)), bound) in results.into_iter().zip(bounds) {
            let _ = writeln!(
                out,
                "| {} | {name} | {:.2e} | {:.2e} | {bound:.0e} | {momentum:.1e} |",
                stepper_name(stepper),
                e.angle,
                e.velocity
            );
            if !(e.angle <= bound && e.velocity <= bound) {
                failures.push(format!("{name} {stepper:?}: {e:?} > {bound:e}"));
            }
        }
    }
    println!("{out}");
    assert!(failures.is_empty(), "{title}: {failures:#?}");
}

/// Two free bodies (inertia 0.02 and 0.05) on an angular spring of rest angle 0.3,
/// wound by three turns (6π). 4 s at 1 kHz.
#[test]
fn angular_pair_wound_three_turns_unwinds_like_the_reference() {
    let wound = 3.0 * TAU;
    // Bounds (f64, f32, I32F32, I16F16), about 3× the measured worst: 9.4e−17, 2.4e−6,
    // 1.9e−15, 5.5e−10 at (0.05, 0.3); 2.8e−16, 1.5e−5, 1.9e−16, 1.7e−10 at (1, 1). In
    // f32 each body's share of the first, huge impulse (the spring wound by 6π) is rounded
    // on its own: a kick of Σ I·ω ≈ 5e−6 that turns the pair as a whole.
    let cases = [
        ((0.05, 0.3), [5e-16, 1e-5, 1e-14, 2e-9]),
        ((1.0, 1.0), [1e-15, 5e-5, 1e-15, 1e-9]),
    ];
    for ((ck, cd), bounds) in cases {
        let mut net = AngularNetwork::new();
        net.add_body(0.0, 0.0, 0.02);
        net.add_body(0.3 + wound, 0.0, 0.05);
        net.add_spring(0, 1, 0.3, ck, cd);
        check(
            &format!(
                "angular pair wound by 3 turns (6π), C_k {ck}, C_d {cd}, 4000 steps (errors / 6π; Σ I·ω starts at 0)"
            ),
            &net,
            4000,
            bounds,
        );
    }
}

/// A chain of four free bodies on a pinned arbor, wound evenly by three turns in all.
#[test]
fn angular_chain_on_a_pinned_arbor_unwinds_like_the_reference() {
    let wound = 3.0 * TAU;
    let mut net = AngularNetwork::new();
    net.add_body(0.0, 0.0, f64::INFINITY);
    for (i, inertia) in [0.01, 0.02, 0.015, 0.03].into_iter().enumerate() {
        net.add_body(wound * (i + 1) as f64 / 4.0, 0.0, inertia);
    }
    for i in 0..4 {
        net.add_spring(i, i + 1, 0.0, 0.3, 0.3);
    }
    check(
        "angular chain of 4 on a pinned arbor, wound by 3 turns, C_k = C_d = 0.3, 4000 steps (errors / 6π)",
        &net,
        4000,
        // Measured 5.7e−16, 1.5e−7, 4.7e−16, 2.5e−10.
        [2e-15, 5e-7, 2e-15, 1e-9],
    );
}

/// With [`WrappedAngle`] a spring wound by three turns and a bit does not unwind: it
/// takes the short way to the nearest rest angle, exactly as the reference spring that
/// was never wound (shifted by the three turns); past half a turn it goes the other way.
/// Returns the largest `|Δθ|` (radians).
fn wrapped_takes_the_short_way<S: Scalar>(stepper: Stepper, tolerance: f64) -> f64
where
    WrappedAngle: LengthKernel<S>,
{
    let (rest, dt, steps) = (0.3, 1e-3, 4000);
    let mut worst = 0.0f64;
    // Offsets past the rest angle, and the turns the short way adds on top of 3 turns.
    for (offset, extra_turns) in [
        (0.5, 0.0),
        (-0.5, 0.0),
        (PI + 0.25, 1.0),
        (-PI - 0.25, -1.0),
    ] {
        let wound = 3.0 * TAU;
        let mut reference = AngularNetwork::new();
        reference.add_body(0.0, 0.0, f64::INFINITY);
        // The reference sees the wrapped displacement without any winding.
        let short = offset - extra_turns * TAU;
        reference.add_body(rest + short, 0.0, 0.05);
        reference.add_spring(0, 1, rest, 0.05, 0.3);
        let mut pair = build::<S, WrappedAngle>(&reference, dt, stepper);
        // Same set-up in the library, wound by three turns (and `extra_turns`); the
        // reference starts from the library's start less the whole turns, so that the
        // two differ by exactly those turns.
        let body = pair.ids[1];
        let start = S::from_f64(rest + short + wound + extra_turns * TAU);
        pair.scene.set_position(body, [start]).unwrap();
        let shift = wound + extra_turns * TAU;
        pair.net.bodies[1].angle = start.to_f64() - shift;
        // The pull from the moved start, as the scene repulls it.
        pair.net.bodies[1].omega = 0.0;
        pair.net.pull(dt);
        for _ in 0..steps {
            let _ = pair.scene.step();
            match stepper {
                Stepper::GaussSeidel => pair.net.step_gauss_seidel_kept(dt),
                Stepper::Jacobi => pair.net.step_jacobi_kept(dt),
            }
            let got = pair.scene.precise_position(body).unwrap()[0] - shift;
            worst = worst.max((got - pair.net.bodies[1].angle).abs());
        }
        // It settled at the rest angle plus whole turns: the nearest one.
        let end = pair.scene.precise_position(body).unwrap()[0];
        let turns = (end - rest) / TAU;
        assert!(
            (turns - (3.0 + extra_turns)).abs() < tolerance,
            "{} offset {offset}: ended {turns} turns from rest",
            S::NAME
        );
        // The unwrapped kernel unwinds everything instead.
        let mut plain = AngularScene::<S, 2, 1>::new(SceneConfig::new(dt).unwrap().no_sleep());
        let arbor = plain.add_pinned([S::ZERO]).unwrap();
        let wheel = plain.add_particle([start], S::from_f64(0.05)).unwrap();
        let tuning = Tuning::from_coefficients(0.05, 0.3, dt).unwrap();
        plain
            .add_spring(arbor, wheel, S::from_f64(rest), &tuning)
            .unwrap();
        for _ in 0..steps {
            let _ = plain.step();
        }
        let end = plain.precise_position(wheel).unwrap()[0];
        assert!(
            (end - rest).abs() < tolerance * TAU,
            "{} unwrapped: {end}",
            S::NAME
        );
    }
    worst
}

#[test]
fn wrapped_angle_takes_the_short_way() {
    let mut out = String::from(
        "\nWrappedAngle, wound 3 turns ± a bit, vs the unwound reference: max |Δθ| (rad)\n| stepper | f64 | f32 | I32F32 | I16F16 |\n|---|---|---|---|---|\n",
    );
    // About 3× the measured worst: 7.5e−15, 1.7e−6, 1.8e−15, 2.7e−11 (f32 and f64 wrap
    // at the wound angle, about 20 rad, to its last bit).
    let bounds = [5e-14, 1e-5, 1e-14, 1e-10];
    for stepper in STEPPERS {
        let e = [
            wrapped_takes_the_short_way::<f64>(stepper, 1e-9),
            wrapped_takes_the_short_way::<f32>(stepper, 1e-5),
            wrapped_takes_the_short_way::<I32F32>(stepper, 1e-7),
            wrapped_takes_the_short_way::<I16F16>(stepper, 1e-3),
        ];
        let _ = writeln!(
            out,
            "| {} | {:.1e} | {:.1e} | {:.1e} | {:.1e} |",
            stepper_name(stepper),
            e[0],
            e[1],
            e[2],
            e[3]
        );
        for (e, b) in e.iter().zip(bounds) {
            assert!(*e <= b, "{out}");
        }
    }
    println!("{out}");
}
