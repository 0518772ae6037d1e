//! Energy of a free, undamped rope over long runs, in every backend.
//!
//! **The rope.** 10 particles of mass 1 in 2D, spacing 1, nine springs at rest length 1,
//! nothing pinned, no gravity, `C_d = 0`; random velocities in `[−v, v]²` (seed 7) with
//! their mean removed, and optionally a drift `w` along `(1, 1)/√2` on top, which carries
//! the rope thousands of units from the origin.
//!
//! **The energy.** In step units (× dt²), with `u = v·dt` and `k·dt² = C_k·m_red`
//! (eq. 27): kinetic `Σ ½·m·|u − ū|²` (in the frame of the centre of mass, whose motion
//! momentum conservation keeps), potential `Σ ½·C_k·m_red·x·x₊₁` with `x₊₁` the extension
//! at the next positions `p + u` (a scene's velocity is the step it moves next). That staggered potential is the shadow energy of
//! the scheme: for a linear network stepped by Jacobi, `|u|² + pᵀK·p₊₁` is exactly
//! invariant, and undamped Gauss-Seidel is the same map (each impulse `−C_k·x` depends on
//! positions only). The naive `½·C_k·m_red·x²` swings by `±C_k/2` within every period and
//! hides a drift. For the nonlinear (rotating, crumpling) rope the staggered form is
//! first-order: in `f64` it stays within ±0.1 % at `C_k = 0.01` and wanders by ±1 % at
//! `0.1`. So each backend's band along the run is checked against the `f64` run's band,
//! widened by the target (what rounding adds), and the end value against the target
//! where the measure is exact (`C_k = 0.01`).
//!
//! What keeps it: the undamped integer step is a bijection (the kick depends on positions
//! only, and the state is wide enough that its rounding noise stays far below the
//! motion), and `f32` positions carry their rounding remainder
//! ([`stiffspring::Scalar::Remainder`]).
//!
//! `cargo test --release --test network_energy -- --nocapture` runs 10⁵ steps per row;
//! `-- --ignored --nocapture one_million` the 10⁶ of the target.

use lab::rng::Rng;
use stiffspring::scene::{ParticleId, Scene, SceneConfig, Stepper};
use stiffspring::{I16F16, I32F32, Scalar, Tuning};

const N: usize = 10;

/// How the rope starts.
#[derive(Clone, Copy, Debug)]
enum Start {
    /// Random velocities, total momentum removed.
    Still(f64),
    /// Random velocities in [−v, v]², mean removed, plus a drift `w` along (1, 1)/√2.
    Moving(f64, f64),
}

#[derive(Clone, Copy, Debug)]
struct Case {
    dt: f64,
    ck: f64,
    stepper: Stepper,
    start: Start,
    steps: usize,
}

/// The shadow energy (see the module docs), in step units.
fn shadow_energy<S: Scalar>(
    scene: &Scene<S, 2, N, { N - 1 }>,
    ids: &[ParticleId],
    case: &Case,
) -> f64 {
    let p: Vec<[f64; 2]> = ids
        .iter()
        .map(|&i| scene.precise_position(i).expect("live"))
        .collect();
    let u: Vec<[f64; 2]> = ids
        .iter()
        .map(|&i| {
            scene
                .velocity(i)
                .expect("live")
                .map(|v| v.to_f64() * case.dt)
        })
        .collect();
    let mut centre = [0.0; 2];
    for u in &u {
        for k in 0..2 {
            centre[k] += u[k] / N as f64;
        }
    }
    let mut energy = 0.0;
    for u in &u {
        let (a, b) = (u[0] - centre[0], u[1] - centre[1]);
        energy += 0.5 * (a * a + b * b);
    }
    let m_red = 0.5;
    for i in 0..N - 1 {
        let (a, b) = (i, i + 1);
        let x = (p[b][0] - p[a][0]).hypot(p[b][1] - p[a][1]) - 1.0;
        let next = (p[b][0] + u[b][0] - p[a][0] - u[a][0])
            .hypot(p[b][1] + u[b][1] - p[a][1] - u[a][1])
            - 1.0;
        energy += 0.5 * case.ck * m_red * x * next;
    }
    energy
}

/// `H/H₀` along the run: at its end, and the least and the largest of the samples taken
/// every 997 steps (a period prime to the rope's, so that the samples fall on every phase).
#[derive(Clone, Copy, Debug)]
struct Band {
    end: f64,
    least: f64,
    largest: f64,
}

fn run<S: Scalar>(case: &Case) -> Band {
    let config = SceneConfig::new(case.dt)
        .expect("a positive dt")
        .stepper(case.stepper)
        .no_sleep();
    let mut scene = Scene::<S, 2, N, { N - 1 }>::new(config);
    let ids: Vec<_> = (0..N)
        .map(|i| {
            scene
                .add_particle([S::from_f64(i as f64), S::ZERO], S::ONE)
                .expect("room")
        })
        .collect();
    let tuning = Tuning::from_coefficients(case.ck, 0.0, case.dt).expect("valid");
    for i in 0..N - 1 {
        scene
            .add_spring(ids[i], ids[i + 1], S::ONE, &tuning)
            .expect("within the limit");
    }
    let mut rng = Rng::seeded(7);
    let (v, w) = match case.start {
        Start::Still(v) => (v, 0.0),
        Start::Moving(v, w) => (v, w / 2f64.sqrt()),
    };
    let mut velocities: Vec<[f64; 2]> = (0..N).map(|_| [rng.sym(v), rng.sym(v)]).collect();
    let mean = [
        velocities.iter().map(|v| v[0]).sum::<f64>() / N as f64,
        velocities.iter().map(|v| v[1]).sum::<f64>() / N as f64,
    ];
    for v in velocities.iter_mut() {
        v[0] += w - mean[0];
        v[1] += w - mean[1];
    }
    for (id, v) in ids.iter().zip(&velocities) {
        scene
            .set_velocity(*id, [S::from_f64(v[0]), S::from_f64(v[1])])
            .expect("a free particle");
    }
    let h0 = shadow_energy(&scene, &ids, case);
    let mut band = Band {
        end: 1.0,
        least: 1.0,
        largest: 1.0,
    };
    for n in 1..=case.steps {
        let _ = scene.step();
        if n % 997 == 0 || n == case.steps {
            let h = shadow_energy(&scene, &ids, case) / h0;
            band.least = band.least.min(h);
            band.largest = band.largest.max(h);
            band.end = h;
        }
    }
    band
}

/// What a backend did over the 16 cases: the least and the largest end value, and the
/// least and the largest value along the runs.
#[derive(Clone, Copy, Debug)]
struct Spread {
    end: (f64, f64),
    band: (f64, f64),
}

impl Spread {
    const EMPTY: Spread = Spread {
        end: (f64::INFINITY, f64::NEG_INFINITY),
        band: (f64::INFINITY, f64::NEG_INFINITY),
    };

    fn add(&mut self, band: &Band) {
        self.end = (self.end.0.min(band.end), self.end.1.max(band.end));
        self.band = (self.band.0.min(band.least), self.band.1.max(band.largest));
    }
}

/// The backends of [`check`]'s [`Spread`]s, and the target each is held to.
const BACKENDS: [(&str, f64); 4] = [
    ("f64", 0.0),
    ("f32", 0.01),
    ("I32F32", 0.01),
    ("I16F16", 0.05),
];

/// Runs the 16 cases `steps` steps in every backend, asserts them, and returns each
/// backend's [`Spread`] (in the order of [`BACKENDS`]).
fn check(steps: usize) -> [Spread; 4] {
    let mut failures = Vec::new();
    let mut spreads = [Spread::EMPTY; 4];
    for start in [Start::Still(0.5), Start::Moving(0.5, 1.0)] {
        for rate in [60.0, 1000.0] {
            for ck in [0.01, 0.1] {
                for stepper in [Stepper::GaussSeidel, Stepper::Jacobi] {
                    let case = Case {
                        dt: 1.0 / rate,
                        ck,
                        stepper,
                        start,
                        steps,
                    };
                    let exact = run::<f64>(&case);
                    spreads[0].add(&exact);
                    println!(
                        "{:<7} {stepper:<11?} {rate:>5} Hz C_k {ck:<5} {start:?}: H/H₀ = {:.5} (band {:.5} to {:.5})",
                        "f64", exact.end, exact.least, exact.largest
                    );
                    for (i, band) in [
                        (1, run::<f32>(&case)),
                        (2, run::<I32F32>(&case)),
                        (3, run::<I16F16>(&case)),
                    ] {
                        let (name, allowed) = BACKENDS[i];
                        spreads[i].add(&band);
                        println!(
                            "{name:<7} {stepper:<11?} {rate:>5} Hz C_k {ck:<5} {start:?}: H/H₀ = {:.5} (band {:.5} to {:.5})",
                            band.end, band.least, band.largest
                        );
                        // Rounding must not heat or cool the rope beyond what the scheme
                        // does in f64: the backend's band lies within the f64 run's,
                        // widened by the target. Where the measure is exact to 0.1 % in
                        // f64 (C_k = 0.01, see the module docs) the end value must also
                        // lie within the target of 1.
                        let beyond = band.least < exact.least - allowed
                            || band.largest > exact.largest + allowed
                            || (ck == 0.01 && (band.end - 1.0).abs() > allowed);
                        if beyond {
                            failures
                                .push(format!("{name} {case:?}: {band:?} against f64 {exact:?}"));
                        }
                    }
                }
            }
        }
    }
    assert!(failures.is_empty(), "{failures:#?}");
    spreads
}

/// Writes the docs' tables of a run: docs/networks.md's (`networks/energy-NAME.md`: the
/// end values and, in brackets, the band along the runs) and docs/accuracy.md's
/// (`accuracy/energy-NAME.md`: the end values, in bold where one lies outside its
/// backend's target of 1).
fn write_tables(name: &str, spreads: &[Spread; 4], labels: [&str; 2], command: &str) {
    let range = |(lo, hi): (f64, f64)| format!("{lo:.4} to {hi:.4}");
    let marked = |v: f64, allowed: f64| {
        if allowed > 0.0 && (v - 1.0).abs() > allowed {
            format!("**{v:.4}**")
        } else {
            format!("{v:.4}")
        }
    };
    let header = ["steps", "f64", "f32", "I32F32", "I16F16", "command"];
    let command = format!("`{command}`");
    let mut networks = vec![labels[0].to_string()];
    let mut accuracy = vec![labels[1].to_string()];
    for (s, (_, allowed)) in spreads.iter().zip(BACKENDS) {
        networks.push(format!("{} ({})", range(s.end), range(s.band)));
        accuracy.push(format!(
            "{} to {}",
            marked(s.end.0, allowed),
            marked(s.end.1, allowed)
        ));
    }
    networks.push(command.clone());
    accuracy.push(command);
    for (doc, row) in [("networks", networks), ("accuracy", accuracy)] {
        let path = lab::table::write_figures(
            &format!("{doc}/energy-{name}.md"),
            &lab::table::markdown(&header, &[row]),
        );
        println!("wrote {}", path.display());
    }
}

#[test]
fn a_free_undamped_rope_keeps_its_energy_over_1e5_steps() {
    let spreads = check(100_000);
    write_tables(
        "1e5",
        &spreads,
        ["10⁵", "10⁵"],
        "cargo test --release --test network_energy -- --nocapture",
    );
}

#[test]
#[ignore = "10⁶ steps per row, a minute: `cargo test --release --test network_energy -- --ignored --nocapture one_million`"]
fn a_free_undamped_rope_keeps_its_energy_over_one_million_steps() {
    let spreads = check(1_000_000);
    write_tables(
        "1e6",
        &spreads,
        ["10⁶ (ignored)", "10⁶ (ignored by default)"],
        "cargo test --release --test network_energy -- --ignored --nocapture one_million",
    );
}
