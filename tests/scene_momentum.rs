//! Momentum of free networks: a spinning, drifting 4×4 jelly with diagonals (nothing
//! pinned, no gravity, lightly damped so that it keeps moving), 10 000 steps, in every
//! backend with both steppers.
//!
//! - **Equal masses.** A spring's two velocity changes are the same computation negated
//!   (`BodyWeights::split` with equal weights), and fixed-point additions are exact, so
//!   the total momentum does not change by a single bit in fixed point: checked in
//!   `I16F16`, whose Q24.40 state `f64` reads exactly; `I32F32`'s Q64.64 state has more
//!   bits than an `f64`, so there the check is to the reading. (`f32` and `f64` round the
//!   sum of a particle's changes; their drift is the rounding of those sums.)
//! - **Unequal masses** (random in [0.25, 4]). Each body's share of an impulse is rounded
//!   on its own, so the total momentum drifts by the rounding of the weights and shares:
//!   in `I16F16` 0.13 to 0.15 of a Q24.40 last bit (times a kilogram) per step.
//! - **Angular momentum** about the origin, `Σ m·(x × u)/dt`, is conserved by a spring's
//!   central impulse up to the same rounding and to the step's own error (symplectic
//!   Euler does not conserve it exactly for a rotating, deforming body): its drift is
//!   measured against `Σ m·|x|·|v|`.
//!
//! `Scene::momentum` reads the state exactly (`dt = 1/128` is a power of two); positions
//! are read as the scene holds them ([`Scene::precise_position`]) and step velocities as
//! their steps.
//!
//! `cargo test --release --test scene_momentum -- --nocapture` prints the table.

use lab::rng::Rng;
use std::fmt::Write as _;
use stiffspring::scene::{ParticleId, Scene, SceneConfig, Stepper};
use stiffspring::{I16F16, I32F32, Scalar, Tuning};

const W: usize = 4;
const DT: f64 = 1.0 / 128.0;
const STEPS: usize = 10_000;

/// The jelly: particles (position, velocity, mass) and springs (ends, rest length).
struct Jelly {
    particles: Vec<([f64; 2], [f64; 2], f64)>,
    springs: Vec<(usize, usize, f64)>,
}

/// A 4×4 mesh with diagonals, spacing 0.25, jittered, spinning at 2 rad/s about its
/// centre and drifting at (0.3, −0.1); masses 1, or log-uniform in [0.25, 4].
fn drifting_jelly(equal: bool) -> Jelly {
    let mut rng = Rng::seeded(if equal { 21 } else { 22 });
    let spacing = 0.25;
    let c = 0.375;
    let mut particles = Vec::new();
    for r in 0..W {
        for col in 0..W {
            let (x, y) = (col as f64 * spacing, r as f64 * spacing);
            let position = [x + rng.sym(0.03), y + rng.sym(0.03)];
            let velocity = [
                -2.0 * (y - c) + 0.3 + rng.sym(0.2),
                2.0 * (x - c) - 0.1 + rng.sym(0.2),
            ];
            let mass = if equal { 1.0 } else { rng.log_range(0.25, 4.0) };
            particles.push((position, velocity, mass));
        }
    }
    let mut springs = Vec::new();
    for r in 0..W {
        for col in 0..W {
            let i = r * W + col;
            if col + 1 < W {
                springs.push((i, i + 1, spacing));
            }
            if r + 1 < W {
                springs.push((i, i + W, spacing));
            }
        }
    }
    for r in 0..W - 1 {
        for col in 0..W - 1 {
            let i = r * W + col;
            let diagonal = spacing * std::f64::consts::SQRT_2;
            springs.push((i, i + W + 1, diagonal));
            springs.push((i + 1, i + W, diagonal));
        }
    }
    Jelly { particles, springs }
}

/// Positions as the scene holds them.
fn held<S: Scalar>(scene: &Scene<S, 2, 16, 42>, ids: &[ParticleId]) -> Vec<[f64; 2]> {
    ids.iter()
        .map(|&id| scene.precise_position(id).unwrap())
        .collect()
}

/// `Σ m·(x × u)/dt` and `Σ m·|x|·|u|/dt`.
fn angular(x: &[[f64; 2]], u: &[[f64; 2]], masses: &[f64]) -> (f64, f64) {
    let mut l = 0.0;
    let mut scale = 0.0;
    for ((x, u), m) in x.iter().zip(u).zip(masses) {
        l += m * (x[0] * u[1] - x[1] * u[0]) / DT;
        scale += m * x[0].hypot(x[1]) * u[0].hypot(u[1]) / DT;
    }
    (l, scale)
}

/// Steps the jelly; returns the largest momentum drift `max |p − p0|` (absolute, and
/// relative to `Σ m·|v₀|`) and the largest angular momentum drift relative to the
/// largest `Σ m·|x|·|v|` of the run (the jelly drifts away from the origin).
fn momentum_drift<S: Scalar>(equal: bool, stepper: Stepper) -> [f64; 3] {
    let jelly = drifting_jelly(equal);
    let config = SceneConfig::<S, 2>::new(DT)
        .unwrap()
        .stepper(stepper)
        .no_sleep();
    let mut scene = Scene::<S, 2, 16, 42>::new(config);
    let tuning = Tuning::from_coefficients(0.1, 0.02, DT).unwrap();
    let mut ids = Vec::new();
    let mut masses = Vec::new();
    let mut scale = 0.0;
    for &(x, v, m) in &jelly.particles {
        let mass = S::from_f64(m);
        let id = scene.add_particle(x.map(S::from_f64), mass).unwrap();
        scene.set_velocity(id, v.map(S::from_f64)).unwrap();
        ids.push(id);
        masses.push(mass.to_f64());
        scale += mass.to_f64() * v[0].hypot(v[1]);
    }
    for &(a, b, rest) in &jelly.springs {
        let added = scene
            .add_spring(ids[a], ids[b], S::from_f64(rest), &tuning)
            .unwrap();
        assert_eq!(added.clamped, 0);
    }
    let p0 = scene.momentum();
    let (mut dp, mut dl, mut angular_scale) = (0.0f64, 0.0f64, 0.0f64);
    let mut l0 = None;
    let mut before = held(&scene, &ids);
    for _ in 0..STEPS {
        let _ = scene.step();
        let p = scene.momentum();
        for k in 0..2 {
            dp = dp.max((p[k] - p0[k]).abs());
        }
        let now = held(&scene, &ids);
        let u: Vec<[f64; 2]> = now
            .iter()
            .zip(&before)
            .map(|(x, y)| [x[0] - y[0], x[1] - y[1]])
            .collect();
        let (l, s) = angular(&now, &u, &masses);
        let l0 = *l0.get_or_insert(l);
        dl = dl.max((l - l0).abs());
        angular_scale = angular_scale.max(s);
        before = now;
    }
    [dp, dp / scale, dl / angular_scale]
}

#[test]
fn free_networks_conserve_momentum_to_rounding() {
    let mut out = String::from(
        "\nFree 4×4 jelly, 10 000 steps at dt = 1/128, C_k 0.1, C_d 0.02 (exact kernel): momentum drift\n\
         | backend | stepper | masses | max |Δp| | max |Δp|/Σm|v| | max |ΔL|/Σm|x||v| | |Δp| in last bits of the state·kg per step |\n\
         |---|---|---|---|---|---|---|\n",
    );
    // (backend, the state's last bit where `f64` reads the state exactly, equal
    // masses?) → bounds on [|Δp|/Σm|v|, |ΔL|/Σm|x||v|], about 3× the measured worst over
    // both steppers. Equal masses in I16F16: not a bit (its Q24.40 step velocities, about
    // 10⁻², are exact in `f64`). I32F32's Q64.64 state has more bits than an `f64` holds,
    // so its sum is read to 2.9e−16 of the momentum, not to the bit.
    let bounds: [(&str, f64, bool, [f64; 2]); 8] = [
        ("f64", 0.0, true, [5e-15, 2e-13]),
        ("f64", 0.0, false, [1e-14, 2e-13]),
        ("f32", 0.0, true, [5e-6, 2e-6]),
        ("f32", 0.0, false, [5e-6, 2e-6]),
        ("I32F32", 0.0, true, [1e-15, 2e-13]),
        ("I32F32", 0.0, false, [5e-15, 5e-13]),
        ("I16F16", 2f64.powi(-40), true, [0.0, 2e-10]),
        ("I16F16", 2f64.powi(-40), false, [5e-8, 2e-8]),
    ];
    let mut failures = Vec::new();
    // (backend, equal masses?, |Δp|/Σm|v|, |Δp| in last bits per step) of every run.
    let mut measured: Vec<(&str, bool, f64, Option<f64>)> = Vec::new();
    for stepper in [Stepper::GaussSeidel, Stepper::Jacobi] {
        for equal in [true, false] {
            let results = [
                ("f64", momentum_drift::<f64>(equal, stepper)),
                ("f32", momentum_drift::<f32>(equal, stepper)),
                ("I32F32", momentum_drift::<I32F32>(equal, stepper)),
                ("I16F16", momentum_drift::<I16F16>(equal, stepper)),
            ];
            for (name, [dp, rel, ang]) in results {
                let (_, lsb, _, bound) =
                    *bounds.iter().find(|b| b.0 == name && b.2 == equal).unwrap();
                // One last bit of step velocity on a unit mass is lsb/dt of momentum.
                let bits = (lsb > 0.0).then(|| dp * DT / lsb / STEPS as f64);
                measured.push((name, equal, rel, bits));
                let per_step = bits.map_or("-".into(), |b| format!("{b:.3}"));
                let _ = writeln!(
                    out,
                    "| {name} | {stepper:?} | {} | {dp:.2e} | {rel:.2e} | {ang:.2e} | {per_step} |",
                    if equal { "equal" } else { "0.25–4" },
                );
                if !(rel <= bound[0] && ang <= bound[1]) {
                    failures.push(format!("{name} {stepper:?} equal={equal}: {rel:e} {ang:e}"));
                }
            }
        }
    }
    println!("{out}");
    assert!(failures.is_empty(), "{failures:#?}");
    write_tables(&measured, &bounds);
}

/// docs/networks.md's and docs/accuracy.md's tables (`networks/momentum.md`,
/// `accuracy/momentum.md`): per backend the largest `|Δp|/Σm|v|` of both steppers, with
/// equal and with unequal masses (and in accuracy.md the bounds asserted). An exact zero
/// is bold; `I32F32` with equal masses is the `f64` reading of its state; `I16F16`'s
/// unequal drift is also given in state last bits per step.
fn write_tables(
    measured: &[(&str, bool, f64, Option<f64>)],
    bounds: &[(&str, f64, bool, [f64; 2])],
) {
    let (mut networks, mut accuracy) = (Vec::new(), Vec::new());
    for name in ["f64", "f32", "I32F32", "I16F16"] {
        let (mut net_row, mut acc_row) = (vec![name.to_string()], vec![format!("`{name}`")]);
        for equal in [true, false] {
            let runs: Vec<_> = measured
                .iter()
                .filter(|m| m.0 == name && m.1 == equal)
                .collect();
            let worst = runs.iter().map(|m| m.2).fold(0.0, f64::max);
            let bits: Vec<f64> = runs.iter().filter_map(|m| m.3).collect();
            let (least, most) = bits
                .iter()
                .fold((f64::INFINITY, 0.0f64), |(l, h), &b| (l.min(b), h.max(b)));
            let (mut net, mut acc) = if worst == 0.0 {
                ("**0**".to_string(), "**0**, to the bit".to_string())
            } else {
                (lab::table::sci(worst), lab::table::sci(worst))
            };
            if name == "I32F32" && equal {
                net.push_str(" (the f64 reading of its Q64.64 state)");
                acc.push_str(" (the `f64` reading of its state)");
            }
            if worst > 0.0 && !bits.is_empty() {
                net.push_str(&format!(
                    " ({least:.2} to {most:.2} of a state's last bit per step)"
                ));
                acc.push_str(&format!(
                    " ({least:.2}–{most:.2} of a state's last bit per step)"
                ));
            }
            let (_, _, _, bound) = bounds
                .iter()
                .find(|b| b.0 == name && b.2 == equal)
                .expect("a bound for every run");
            net_row.push(net);
            acc_row.push(acc);
            acc_row.push(if bound[0] == 0.0 {
                "0".to_string()
            } else {
                format!("{:.0e}", bound[0])
            });
        }
        networks.push(net_row);
        accuracy.push(acc_row);
    }
    let path = lab::table::write_figures(
        "networks/momentum.md",
        &lab::table::markdown(&["backend", "equal masses", "masses 0.25 to 4"], &networks),
    );
    println!("wrote {}", path.display());
    let path = lab::table::write_figures(
        "accuracy/momentum.md",
        &lab::table::markdown(
            &["backend", "equal masses", "bound", "masses 0.25–4", "bound"],
            &accuracy,
        ),
    );
    println!("wrote {}", path.display());
}
