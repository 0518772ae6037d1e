//! Long runs: a million steps of an undamped spring and of free networks, in every
//! backend.
//!
//! **The undamped spring's invariant.** With `C_d = 0` the step is
//! `u' = u − k·x`, `x' = x + u'` (`k = C_k`). It keeps
//!
//! ```text
//! H(x, u) = u² − k·x·u + k·x²  =  u² + k·x·x₋₁        (x₋₁ = x − u, the previous position)
//! ```
//!
//! exactly. With `x' = (1 − k)·x + u` and `u' = u − k·x`, the new value
//! `k·x'² − k·x'·u' + u'²` expands to
//! `x²·[k(1−k)² + k²(1−k) + k²] + x·u·[2k(1−k) − k(1−2k) − 2k] + u²`, which is
//! `k·x² − k·x·u + u²`. It is the discrete map's energy (the naive `u² + k·x²`
//! oscillates by a factor `1 ± k/2` within every period, which says nothing about drift);
//! `H > 0` for `0 < k < 4`. [`invariant_is_exact_in_f64_on_random_states`] checks the
//! algebra numerically.
//!
//! - **Floats**: `H` stays within a band of rounding size around its start over 10⁶ steps
//!   (no secular drift): measured below.
//! - **Fixed point** rounds the spring term `k·x` toward zero and adds it to `u` exactly:
//!   each half of the step (`u ← u − round(k·x)`, then `x ← x + u`) is a shear of the
//!   integer lattice, a bijection, so nothing drags the spring (the old step, which
//!   rounded `u − k·x` as a whole, lost about `2/C_k` last bits of amplitude per cycle like
//!   Coulomb friction). `H` wanders by the rounding of the state (24 or 32 guard bits
//!   below a position's last bit) and does not drift: measured and bounded below.
//!
//! **Momentum.** Internal springs conserve the total momentum `Σ m·v` of free particles:
//! exactly (to the bit) for equal masses in fixed point, and to a drift measured and
//! bounded below for unequal ones and in floats.
//!
//! `cargo test --release --test long_runs -- --nocapture` prints the measurements.

use lab::linear::{Masses, Topology};
use lab::rng::Rng;
use stiffspring::scene::{Scene, SceneConfig, Stepper};
use stiffspring::{I16F16, I32F32, Scalar, SpringValue, Tuning};

const MILLION: usize = 1_000_000;

fn invariant(k: f64, x: f64, u: f64) -> f64 {
    u * u - k * x * u + k * x * x
}

#[test]
fn invariant_is_exact_in_f64_on_random_states() {
    let mut rng = Rng::seeded(11);
    for _ in 0..10_000 {
        let (k, x, u) = (
            rng.range(0.0, 4.0),
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
        );
        let h = invariant(k, x, u);
        let u2 = u - k * x;
        let x2 = x + u2;
        let h2 = invariant(k, x2, u2);
        // Rounding of terms up to about 4·(|x| + |u|)².
        let tol = 1e-14 * (1.0 + 4.0 * (x.abs() + u.abs()).powi(2));
        assert!((h2 - h).abs() <= tol, "{k} {x} {u}: {h} → {h2}");
        // u² + k·x·x₋₁ is the same number.
        assert!((h2 - (u2 * u2 + k * x2 * (x2 - u2))).abs() <= tol);
    }
}

/// `H` over a run of an undamped value: (largest `|H − H₀|/H₀`, relative change of the
/// mean of `H` from the first to the last tenth of the run). The value is released from
/// `x0` with raw coefficients, so it starts from `(x0, 0)`; with `C_d = 0` the velocity it
/// keeps is the step velocity `u` itself.
fn undamped_run<S: Scalar>(k: f64, x0: f64, steps: usize) -> (f64, f64) {
    // Beyond the square the undamped edge is reached only by the exact map (ζ = 0):
    // C_k = 4·sin²(π·f·dt), whose release starts from u₀ = P·x₀, not 0.
    let tuning = if k <= 1.0 {
        Tuning::from_coefficients(k, 0.0, 1.0).expect("in the square")
    } else {
        let fdt = (k.sqrt() / 2.0).asin() / std::f64::consts::PI;
        Tuning::from_frequency(fdt, 0.0, 1.0).expect("not aliased")
    };
    let mut v = SpringValue::<S>::new([S::from_f64(x0)], &tuning).expect("representable");
    v.set_target([S::ZERO]);
    // The coefficient the backend runs, and the state it starts from.
    let (k, _) = S::gains_to_f64(&S::gains(tuning.stiffness(), 0.0).expect("representable"));
    let h0 = invariant(k, v.offset()[0].to_f64(), v.step_velocity()[0].to_f64());
    let (mut worst, mut first, mut last) = (0.0f64, 0.0, 0.0);
    let tenth = steps / 10;
    for n in 0..steps {
        v.advance();
        let (x, u) = (v.offset()[0].to_f64(), v.step_velocity()[0].to_f64());
        let h = invariant(k, x, u);
        worst = worst.max((h - h0).abs() / h0);
        if n < tenth {
            first += h / tenth as f64;
        } else if n >= steps - tenth {
            last += h / tenth as f64;
        }
    }
    (worst, (last - first) / h0)
}

/// The stiffnesses `C_k` of the undamped runs, from a UI spring at 60 Hz to a knob at
/// 1 kHz, in increasing order.
const STIFFNESSES: [f64; 6] = [1e-3, 0.01, 0.1, 0.5, 1.0, 2.5];

/// Undamped values in every backend: [`STIFFNESSES`], amplitude 100.
fn undamped_table(steps: usize) -> Vec<(String, f64, f64, f64)> {
    let mut rows = Vec::new();
    for k in STIFFNESSES {
        let run = |name: &str, (w, d): (f64, f64)| (name.to_string(), k, w, d);
        rows.push(run("f64", undamped_run::<f64>(k, 100.0, steps)));
        rows.push(run("f32", undamped_run::<f32>(k, 100.0, steps)));
        rows.push(run("I32F32", undamped_run::<I32F32>(k, 100.0, steps)));
        rows.push(run("I16F16", undamped_run::<I16F16>(k, 100.0, steps)));
    }
    rows
}

/// Checks [`undamped_table`]'s rows and returns them.
fn check_undamped(steps: usize) -> Vec<(String, f64, f64, f64)> {
    println!("backend  C_k     max |H−H₀|/H₀   drift of mean H over {steps} steps");
    let rows = undamped_table(steps);
    for (name, k, worst, drift) in rows.iter().cloned() {
        println!("{name:<8} {k:<7} {worst:>12.2e}   {drift:>+12.2e}");
        // Floats: a band of rounding size, and no drift beyond it (f32's is a random walk
        // of either sign). Fixed point: the reads of the state (half a last bit of x and u,
        // |u| ≈ 100·√C_k) and its own rounding, with no drift.
        let (band, most) = match name.as_str() {
            "f64" => (1e-11, 1e-11),
            "f32" => (1e-3, 1e-3),
            "I32F32" => (1e-8, 1e-9),
            _ => (3e-4, 3e-5),
        };
        assert!(
            worst <= band && drift.abs() <= most,
            "{name} C_k = {k}: H strays {worst:e}, drifts {drift:e}"
        );
    }
    rows
}

/// `v > 0` rounded up to two significant figures, strictly above it: `4.99e-14` is
/// `5.0e-14`, `5e-14` is `5.1e-14` (the figure a "below" states).
fn sci_above(v: f64) -> String {
    let shortest = format!("{v:e}");
    let (mantissa, exponent) = shortest.split_once('e').expect("`{:e}` has an exponent");
    let (mantissa, exponent): (f64, i32) = (
        mantissa.parse().expect("a mantissa"),
        exponent.parse().expect("an exponent"),
    );
    let tenths = (mantissa * 10.0).floor() + 1.0;
    if tenths >= 100.0 {
        format!("1.0e{}", exponent + 1)
    } else {
        format!("{:.1}e{exponent}", tenths / 10.0)
    }
}

/// docs/stability.md's table of the undamped runs: per backend, the range of the largest
/// `|H − H₀|/H₀` over the stiffnesses (but `C_k = 1`, whose four exact states lose
/// nothing) and a bound on the drift of the mean.
fn undamped_doc_table(rows: &[(String, f64, f64, f64)]) -> String {
    let mut out = Vec::new();
    for backend in ["f64", "f32", "I32F32", "I16F16"] {
        let mine = rows.iter().filter(|r| r.0 == backend);
        let (mut lo, mut hi, mut drift) = (f64::INFINITY, 0.0f64, 0.0f64);
        for (_, k, worst, d) in mine {
            if *k == 1.0 {
                assert_eq!((*worst, *d), (0.0, 0.0), "{backend}: C_k = 1 is exact");
                continue;
            }
            (lo, hi, drift) = (lo.min(*worst), hi.max(*worst), drift.max(d.abs()));
        }
        out.push(vec![
            format!("`{backend}`"),
            format!("{} to {}", lab::table::sci(lo), lab::table::sci(hi)),
            if drift == 0.0 {
                "0".to_string()
            } else {
                format!("below {}", sci_above(drift))
            },
        ]);
    }
    let (k_lo, k_hi) = (STIFFNESSES[0], STIFFNESSES[STIFFNESSES.len() - 1]);
    let header = [
        "backend".to_string(),
        format!("largest `\\|H − H₀\\|/H₀`, `C_k` from {k_lo} to {k_hi}"),
        "drift of the mean of `H`".to_string(),
    ];
    let header: Vec<&str> = header.iter().map(String::as_str).collect();
    lab::table::markdown(&header, &out)
}

/// Writes docs/stability.md's table (`target/figures/stability/long-runs.md`).
#[test]
fn undamped_spring_keeps_its_invariant_over_1e5_steps() {
    let rows = check_undamped(100_000);
    let path = lab::table::write_figures("stability/long-runs.md", &undamped_doc_table(&rows));
    println!("wrote {}", path.display());
}

#[test]
#[ignore = "10⁶ steps per row: `cargo test --release --test long_runs -- --ignored --nocapture`"]
fn undamped_spring_keeps_its_invariant_over_1e6_steps() {
    let _ = check_undamped(MILLION);
}

// ---------------------------------------------------------------------------
// Momentum of free networks
// ---------------------------------------------------------------------------

const P: usize = 16;
const K: usize = 32;

/// A free network (no pinned particle, no gravity) with random initial velocities, in
/// backend `S`: the largest drift of `Σ m·v` over `steps`, relative to `Σ m·|v|` at the
/// start, and whether it was exactly constant.
fn momentum_drift<S: Scalar>(top: &Topology, stepper: Stepper, steps: usize) -> (f64, bool) {
    let dt = 1.0 / 60.0;
    let config = SceneConfig::new(dt)
        .expect("dt > 0")
        .stepper(stepper)
        .no_sleep();
    let mut scene = Scene::<S, 2, P, K>::new(config);
    let ids: Vec<_> = top
        .positions
        .iter()
        .enumerate()
        .map(|(i, p)| {
            let p = [S::from_f64(p[0]), S::from_f64(p[1])];
            let mass = S::from_f64(1.0 / top.inverse_masses[i]);
            scene.add_particle(p, mass).expect("room")
        })
        .collect();
    // One tuning for all, within every spring's limit (the limit of the busiest).
    let c = stiffspring::scene::network_limit(top.share_count(), stepper) * 0.5;
    let tuning = Tuning::from_coefficients(c, c, dt).expect("in the square");
    for &(a, b) in &top.springs {
        scene
            .add_spring_at_rest(ids[a], ids[b], &tuning)
            .expect("within the limit");
    }
    let mut rng = Rng::seeded(3);
    let mut scale = 0.0;
    for (i, &id) in ids.iter().enumerate() {
        let v = [rng.range(-1.0, 1.0), rng.range(-1.0, 1.0)];
        let v = [S::from_f64(v[0]), S::from_f64(v[1])];
        scene.set_velocity(id, v).expect("free");
        let m = 1.0 / top.inverse_masses[i];
        scale += m * v[0].to_f64().hypot(v[1].to_f64());
    }
    let p0 = scene.momentum();
    let mut worst = 0.0f64;
    let mut exact = true;
    for _ in 0..steps {
        let _ = scene.step();
        let p = scene.momentum();
        for k in 0..2 {
            worst = worst.max((p[k] - p0[k]).abs() / scale);
            exact &= p[k] == p0[k];
        }
    }
    (worst, exact)
}

fn momentum_topologies() -> Vec<Topology> {
    let mut unequal = Topology::mesh(3, 3, true, false);
    let mut rng = Rng::seeded(8);
    for m in unequal.inverse_masses.iter_mut() {
        *m = 1.0 / 10f64.powf(rng.range(-1.0, 1.0));
    }
    unequal.name = "mesh 3×3 diag, masses 0.1 to 10".into();
    vec![
        Topology::rope(2, false, Masses::Equal),
        Topology::rope(8, false, Masses::Equal),
        Topology::rope(2, false, Masses::Alternating(7.0)),
        Topology::rope(8, false, Masses::Alternating(100.0)),
        unequal,
    ]
}

fn check_momentum(steps: usize) {
    println!(
        "network                              stepper       backend  drift of Σm·v / Σm·|v₀|  exact"
    );
    for top in momentum_topologies() {
        let equal = top
            .inverse_masses
            .iter()
            .all(|&m| m == top.inverse_masses[0]);
        for stepper in [Stepper::GaussSeidel, Stepper::Jacobi] {
            let rows = [
                ("f64", momentum_drift::<f64>(&top, stepper, steps)),
                ("f32", momentum_drift::<f32>(&top, stepper, steps)),
                ("I32F32", momentum_drift::<I32F32>(&top, stepper, steps)),
                ("I16F16", momentum_drift::<I16F16>(&top, stepper, steps)),
            ];
            for (backend, (drift, exact)) in rows {
                println!(
                    "{:<36} {:<13} {backend:<8} {drift:>12.2e}               {exact}",
                    top.name,
                    format!("{stepper:?}")
                );
                // Equal masses: the two halves of every impulse are exact negatives, so
                // momentum is constant to the bit in fixed point (`I16F16`'s Q24.40 state
                // converts to f64 exactly; `I32F32`'s Q64.64 state rounds to f64's 53 bits
                // in `Scene::momentum`, half an ulp per particle).
                if equal && backend == "I16F16" {
                    assert!(exact, "{} {stepper:?} {backend}: {drift:e}", top.name);
                }
                // Measured: floats round-off only; fixed point drifts by the rounding of the
                // weights' shares when the masses differ (the old narrow state drifted by
                // 0.48 to 0.74 of the momentum scale in I16F16 after 10⁵ steps).
                let bound = match backend {
                    _ if equal && backend == "I32F32" => 1e-15,
                    "f64" => 1e-12,
                    "f32" => 1e-4,
                    "I32F32" => 1e-13,
                    _ => 1e-11 * steps as f64,
                };
                assert!(
                    drift <= bound,
                    "{} {stepper:?} {backend}: {drift:e}",
                    top.name
                );
            }
        }
    }
}

#[test]
fn free_networks_conserve_momentum_over_1e5_steps() {
    check_momentum(100_000);
}

#[test]
#[ignore = "10⁶ steps per row: `cargo test --release --test long_runs -- --ignored --nocapture`"]
fn free_networks_conserve_momentum_over_1e6_steps() {
    check_momentum(MILLION);
}
