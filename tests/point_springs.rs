//! Point springs (a zero rest length: a drag handle, a mouse spring) and the exact
//! release, against independent references, in every backend.
//!
//! - **A body on a handle, released.** A free body `A` units from a pinned handle, on a
//!   point spring tuned by [`Tuning::from_frequency`], released with [`Scene::release`]
//!   and stepped 10 000 times: every component must follow the continuous damped
//!   oscillator `lab::reference::analytic` from rest, over a grid of springs (1, 5 and
//!   20 Hz; ζ = 0, 0.3, 1 and 3) and rates (60 Hz, 1 kHz, 10 kHz; `f·dt ≤ 0.2`), at
//!   amplitudes 1 and 100. The error is the largest `|x − x(t)|/A` of the state the scene
//!   holds ([`Scene::precise_position`]).
//! - **Two free bodies on a point spring** (masses 1 and 3) have the same relative motion
//!   (the coefficients are fractions of the reduced mass), and their centre of mass does
//!   not move.
//! - **Any start.** With a velocity of its own (a body flung past its handle), each axis
//!   of a point spring is the article's single-spring map `lab::reference::map_step` on
//!   that component: the spring pulls and damps along every axis, so the body spirals in
//!   instead of orbiting.
//!
//! `cargo test --release --test point_springs -- --nocapture` prints the grid.

use lab::reference::{analytic, map_step};
use std::f64::consts::TAU;
use std::fmt::Write as _;
use stiffspring::scene::{ParticleId, Scene, SceneConfig, Stepper};
use stiffspring::{I16F16, I32F32, Scalar, Tuning};

/// Steps of every run.
const STEPS: usize = 10_000;
/// Where the handle is.
const HANDLE: [f64; 2] = [0.5, -0.25];
/// The direction of the displacement from the handle.
const DIRECTION: [f64; 2] = [0.8, -0.6];

/// The springs and rates of the grid: `(f, ζ, rate)` with `f·dt ≤ 0.2`.
fn grid() -> Vec<(f64, f64, f64)> {
    let mut out = Vec::new();
    for f in [1.0, 5.0, 20.0] {
        for zeta in [0.0, 0.3, 1.0, 3.0] {
            for rate in [60.0, 1000.0, 10_000.0] {
                if f / rate <= 0.2 {
                    out.push((f, zeta, rate));
                }
            }
        }
    }
    out
}

/// A body `amplitude` from the handle, released; the largest `|x − x(t)|/A` over the
/// run, both components.
fn released_from_a_handle<S: Scalar>(
    f: f64,
    zeta: f64,
    rate: f64,
    amplitude: f64,
    stepper: Stepper,
) -> f64 {
    let dt = 1.0 / rate;
    let config = SceneConfig::<S, 2>::new(dt)
        .unwrap()
        .stepper(stepper)
        .no_sleep();
    let mut scene = Scene::<S, 2, 2, 1>::new(config);
    let start = [
        HANDLE[0] + amplitude * DIRECTION[0],
        HANDLE[1] + amplitude * DIRECTION[1],
    ];
    let body = scene.add_particle(start.map(S::from_f64), S::ONE).unwrap();
    let tuning = Tuning::from_frequency(f, zeta, dt).unwrap();
    let (handle, _) = scene
        .add_anchor(HANDLE.map(S::from_f64), body, S::ZERO, &tuning)
        .unwrap();
    scene.release().unwrap();
    // The displacement as the backend holds it.
    let (b, h) = (
        scene.precise_position(body).unwrap(),
        scene.precise_position(handle).unwrap(),
    );
    let x0 = [b[0] - h[0], b[1] - h[1]];
    let omega = TAU * f;
    let mut worst = 0.0f64;
    for n in 1..=STEPS {
        let _ = scene.step();
        let x = scene.precise_position(body).unwrap();
        for k in 0..2 {
            let (exact, _) = analytic(x0[k], 0.0, omega, zeta, n as f64 * dt);
            worst = worst.max((x[k] - h[k] - exact).abs() / amplitude);
        }
    }
    worst
}

/// The largest error of each backend over the grid, at amplitude `amplitude`.
fn grid_worst(amplitude: f64, stepper: Stepper, out: &mut String) -> [f64; 4] {
    let mut worst = [0.0f64; 4];
    for (f, zeta, rate) in grid() {
        let e = [
            released_from_a_handle::<f64>(f, zeta, rate, amplitude, stepper),
            released_from_a_handle::<f32>(f, zeta, rate, amplitude, stepper),
            released_from_a_handle::<I32F32>(f, zeta, rate, amplitude, stepper),
            released_from_a_handle::<I16F16>(f, zeta, rate, amplitude, stepper),
        ];
        let _ = writeln!(
            out,
            "| {f} | {zeta} | {rate} | {amplitude} | {:.1e} | {:.1e} | {:.1e} | {:.1e} |",
            e[0], e[1], e[2], e[3]
        );
        for (w, e) in worst.iter_mut().zip(e) {
            *w = w.max(e);
        }
    }
    worst
}

#[test]
fn a_released_body_on_a_drag_handle_samples_its_continuous_oscillator() {
    let mut out = String::from(
        "\nA body on a point spring to a pinned handle, released, 10 000 steps: max |x − x(t)|/A\n\
         | f (Hz) | ζ | rate (Hz) | A | f64 | f32 | I32F32 | I16F16 |\n|---|---|---|---|---|---|---|---|\n",
    );
    // (amplitude, bounds for f64, f32, I32F32, I16F16), about 3× the measured worst:
    // 1.0e−12, 5.4e−6, 1.0e−12, 3.6e−6 at A = 1; 1.0e−12, 8.8e−6, 1.0e−12, 9.0e−7 at 100.
    let cases = [
        (1.0, [5e-12, 2e-5, 5e-12, 2e-5]),
        (100.0, [5e-12, 5e-5, 5e-12, 5e-6]),
    ];
    let mut failures = Vec::new();
    for (amplitude, bounds) in cases {
        // One spring: both steppers are the same map.
        let worst = grid_worst(amplitude, Stepper::GaussSeidel, &mut out);
        let _ = writeln!(
            out,
            "| worst | | | {amplitude} | {:.1e} | {:.1e} | {:.1e} | {:.1e} |",
            worst[0], worst[1], worst[2], worst[3]
        );
        for ((name, w), b) in ["f64", "f32", "I32F32", "I16F16"]
            .iter()
            .zip(worst)
            .zip(bounds)
        {
            if w > b {
                failures.push(format!("{name} at A = {amplitude}: {w:e} > {b:e}"));
            }
        }
    }
    println!("{out}");
    assert!(failures.is_empty(), "{failures:#?}");
}

/// Two free bodies (masses 1 and 3) on a point spring, released: the relative coordinate
/// follows the oscillator, the centre of mass stays where it was. Returns the largest
/// relative error and the largest move of the centre of mass, relative to the amplitude.
fn released_pair<S: Scalar>(stepper: Stepper) -> (f64, f64) {
    let (f, zeta, dt) = (2.0, 0.2, 1.0 / 120.0);
    let config = SceneConfig::<S, 2>::new(dt)
        .unwrap()
        .stepper(stepper)
        .no_sleep();
    let mut scene = Scene::<S, 2, 2, 1>::new(config);
    let masses = [1.0, 3.0];
    let ids: Vec<ParticleId> = [[-0.3, 0.2], [0.5, -0.4]]
        .iter()
        .zip(masses)
        .map(|(p, m)| {
            scene
                .add_particle(p.map(S::from_f64), S::from_f64(m))
                .unwrap()
        })
        .collect();
    let tuning = Tuning::from_frequency(f, zeta, dt).unwrap();
    scene.add_spring(ids[0], ids[1], S::ZERO, &tuning).unwrap();
    scene.release().unwrap();
    let held = |scene: &Scene<S, 2, 2, 1>| -> ([f64; 2], [f64; 2]) {
        let (a, b) = (
            scene.precise_position(ids[0]).unwrap(),
            scene.precise_position(ids[1]).unwrap(),
        );
        let centre = [
            (masses[0] * a[0] + masses[1] * b[0]) / 4.0,
            (masses[0] * a[1] + masses[1] * b[1]) / 4.0,
        ];
        ([b[0] - a[0], b[1] - a[1]], centre)
    };
    let (d0, c0) = held(&scene);
    let amplitude = d0[0].hypot(d0[1]);
    let (mut relative, mut centre) = (0.0f64, 0.0f64);
    for n in 1..=600 {
        let _ = scene.step();
        let (d, c) = held(&scene);
        for k in 0..2 {
            let (exact, _) = analytic(d0[k], 0.0, TAU * f, zeta, n as f64 * dt);
            relative = relative.max((d[k] - exact).abs() / amplitude);
            centre = centre.max((c[k] - c0[k]).abs() / amplitude);
        }
    }
    (relative, centre)
}

#[test]
fn two_free_bodies_on_a_point_spring_oscillate_about_their_still_centre() {
    let mut out = String::from(
        "\nTwo free bodies (1 and 3 kg) on a point spring, 2 Hz, ζ = 0.2, 120 Hz, released, 600 steps\n\
         | stepper | backend | max relative error / A | max centre move / A |\n|---|---|---|---|\n",
    );
    // (backend, bound on the relative error, on the centre's move), about 3× measured.
    let bounds = [
        ("f64", 1e-15, 1e-14),
        ("f32", 5e-7, 5e-6),
        ("I32F32", 1e-15, 5e-16),
        ("I16F16", 2e-9, 1e-8),
    ];
    let mut failures = Vec::new();
    for stepper in [Stepper::GaussSeidel, Stepper::Jacobi] {
        let results = [
            released_pair::<f64>(stepper),
            released_pair::<f32>(stepper),
            released_pair::<I32F32>(stepper),
            released_pair::<I16F16>(stepper),
        ];
        for ((name, b_rel, b_centre), (rel, centre)) in bounds.iter().zip(results) {
            let _ = writeln!(out, "| {stepper:?} | {name} | {rel:.1e} | {centre:.1e} |");
            if rel > *b_rel || centre > *b_centre {
                failures.push(format!("{name} {stepper:?}: {rel:e} {centre:e}"));
            }
        }
    }
    println!("{out}");
    assert!(failures.is_empty(), "{failures:#?}");
}

/// A body flung past its handle with a velocity of its own: each component follows the
/// single-spring map from its own start. Returns the largest error relative to the
/// initial distance, and the distance left at the end relative to it.
fn flung_past_the_handle<S: Scalar>() -> (f64, f64) {
    let dt = 1.0 / 60.0;
    let config = SceneConfig::<S, 2>::new(dt).unwrap().no_sleep();
    let mut scene = Scene::<S, 2, 2, 1>::new(config);
    let body = scene
        .add_particle([1.0, 0.0].map(S::from_f64), S::ONE)
        .unwrap();
    // Flung at right angles to the spring: a distance spring of any length would let it
    // orbit; a point spring damps the swing on both axes.
    let velocity = [0.0, 6.0].map(S::from_f64);
    scene.set_velocity(body, velocity).unwrap();
    let tuning = Tuning::from_coefficients(0.05, 0.1, dt).unwrap();
    let (handle, added) = scene
        .add_anchor([0.0, 0.0].map(S::from_f64), body, S::ZERO, &tuning)
        .unwrap();
    let stored = scene.tuning(added.spring).unwrap();
    let (ck, cd) = (stored.stiffness(), stored.damping());
    let h = scene.precise_position(handle).unwrap();
    let b = scene.precise_position(body).unwrap();
    let mut x = [b[0] - h[0], b[1] - h[1]];
    // The scene's next step moves the body by `v·dt` plus its spring's pull
    // (`Scene::set_velocity`, then `add_anchor`): the map's step `(1 − C_d)·u − C_k·x`
    // from `u = v·dt/(1 − C_d)`.
    let mut u = velocity.map(|v| S::state_to_f64(S::scale(v.widen(), S::factor(dt))) / (1.0 - cd));
    let r0 = x[0].hypot(x[1]);
    let mut worst = 0.0f64;
    for _ in 0..600 {
        let _ = scene.step();
        let p = scene.precise_position(body).unwrap();
        for k in 0..2 {
            map_step(&mut x[k], &mut u[k], ck, cd);
            worst = worst.max((p[k] - h[k] - x[k]).abs() / r0);
        }
    }
    let p = scene.precise_position(body).unwrap();
    (worst, (p[0] - h[0]).hypot(p[1] - h[1]) / r0)
}

#[test]
fn a_body_flung_past_its_handle_follows_the_single_spring_map_on_each_axis() {
    // (backend, bound), about 3× the measured worst.
    let results = [
        ("f64", flung_past_the_handle::<f64>(), 1e-15),
        ("f32", flung_past_the_handle::<f32>(), 5e-7),
        ("I32F32", flung_past_the_handle::<I32F32>(), 5e-16),
        ("I16F16", flung_past_the_handle::<I16F16>(), 2e-10),
    ];
    for (name, (worst, left), bound) in results {
        println!(
            "{name}: max error {worst:.1e} of the start distance; {left:.1e} of it left after 10 s"
        );
        assert!(worst <= bound, "{name}: {worst:e}");
        // It spiralled in: e^{−ζω·10 s} of the start is left, not an orbit.
        assert!(left < 1e-3, "{name}: {left}");
    }
}
