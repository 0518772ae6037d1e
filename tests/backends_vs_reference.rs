//! Every backend against the independent f64 reference model of the article.
//!
//! - A value with raw coefficients is the article's body on a fixed anchor: its positions
//!   and step velocities must follow the reference's impulse form (the corrected eq. 27)
//!   and its force form with symplectic Euler (the same map for one spring).
//! - The two-body kernel (`kernel::respond` + `BodyWeights::split`) applied to a pair of
//!   free bodies must follow the reference's reduced-mass pair (eq. 17–21, 27), and
//!   conserve momentum.
//!
//! `cargo test --release --test backends_vs_reference -- --nocapture` prints the measured
//! worst errors per backend.

use lab::reference;
use lab::rng::Rng;

use stiffspring::kernel::{self, BodyWeights};
use stiffspring::{I16F16, I32F32, RestThreshold, Scalar, SpringValue, Tuning};

const STEPS: usize = 2_000;

/// Worst |x_lib − x_ref| and |u_lib − u_ref| relative to the amplitude (max |x_ref|), over
/// random raw tunings in [0, 1]², random masses and time steps, starting offset `scale`.
fn single_body_error<S: Scalar>(scale: f64, force_form: bool) -> f64 {
    let mut rng = Rng::seeded(3);
    let never = RestThreshold::new(1e-300, 1e-300).expect("positive");
    let mut worst = 0.0f64;
    for _ in 0..200 {
        let (ck, cd) = (rng.unit(), 0.02 + 0.98 * rng.unit());
        let m = 10f64.powf(6.0 * rng.unit() - 3.0);
        let dt = 10f64.powf(-4.0 * rng.unit());
        // An offset and a velocity exactly representable in the backend (a velocity beyond
        // its range saturates), so that both start from the same state.
        let x0 = S::from_f64(scale * rng.sym(1.0));
        let v0 = S::from_f64(0.1 * scale * rng.sym(1.0) / dt);
        let tuning = Tuning::from_coefficients(ck, cd, dt).expect("in the square");
        let mut value = SpringValue::<S>::new([x0], &tuning)
            .expect("representable")
            .with_rest_threshold(never);
        value.set_target([S::ZERO]);
        // Raw coefficients: a fling is the article's u = v·dt (kept as (1 − C_d)·u).
        value.fling([v0]);
        let mut body = reference::Particle1::new(x0.to_f64(), v0.to_f64(), m);
        let mut amplitude = body.x.abs();
        let mut err = 0.0f64;
        for _ in 0..STEPS {
            value.advance();
            if force_form {
                body.force_step(ck, cd, dt);
            } else {
                body.impulse_step(ck, cd, dt);
            }
            amplitude = amplitude.max(body.x.abs());
            err = err.max((value.position()[0].to_f64() - body.x).abs());
            err = err.max((value.step_velocity()[0].to_f64() - body.v * dt).abs());
        }
        worst = worst.max(err / amplitude);
    }
    worst
}

/// Worst error of the kernel on a free pair (the extension relative to its amplitude, and
/// the drifting positions relative to their magnitude), and the worst momentum drift
/// relative to the momentum scale `m·|u|`.
fn pair_error<S: Scalar>(scale: f64) -> (f64, f64) {
    let mut rng = Rng::seeded(5);
    let (mut worst, mut drift) = (0.0f64, 0.0f64);
    let f = S::state_to_f64;
    for _ in 0..200 {
        let (ck, cd) = (rng.unit(), 0.02 + 0.98 * rng.unit());
        let (ma, mb) = (
            10f64.powf(4.0 * rng.unit() - 2.0),
            10f64.powf(4.0 * rng.unit() - 2.0),
        );
        let dt = 1e-3;
        let rest = 0.5 * scale;
        let gains = S::gains(ck, cd).expect("representable");
        let weights = BodyWeights::<S>::from_inverse_masses(1.0 / ma, 1.0 / mb).expect("masses");
        let state = |v: f64| S::from_f64(v).widen();
        let rest_s = state(rest);
        let (mut xa, mut xb) = (state(0.0), state(rest + scale * (rng.unit() - 0.5)));
        let mut ua = state(0.05 * scale * (rng.unit() - 0.5));
        let mut ub = state(0.05 * scale * (rng.unit() - 0.5));
        let mut pair = reference::Pair1::new(f(xa), f(ua) / dt, ma, f(xb), f(ub) / dt, mb);
        let p0 = ma * f(ua) + mb * f(ub);
        // The extension is what the spring acts on; the pair also drifts as a whole, and
        // that absolute position is compared relative to the distance travelled.
        let (mut ext_err, mut ext_amp) = (0.0f64, 1e-3 * scale);
        let (mut pos_err, mut pos_amp) = (0.0f64, scale);
        for _ in 0..STEPS {
            // The kernel in its 1-D form: extension and relative step velocity, the change
            // Δ of the relative step velocity, split by the weights, then both positions.
            let extension = S::state_sub(S::state_sub(xb, xa), rest_s);
            let delta = kernel::respond::<S>(&gains, extension, S::state_sub(ub, ua));
            let (da, db) = weights.split(delta);
            ua = S::state_add(ua, da);
            ub = S::state_add(ub, db);
            xa = S::state_add(xa, ua);
            xb = S::state_add(xb, ub);
            pair.impulse_step(ck, cd, rest, dt);
            let ext = f(xb) - f(xa) - rest;
            ext_amp = ext_amp.max(pair.extension(rest).abs());
            ext_err = ext_err.max((ext - pair.extension(rest)).abs());
            pos_amp = pos_amp.max(pair.xa.abs()).max(pair.xb.abs());
            pos_err = pos_err.max((f(xa) - pair.xa).abs().max((f(xb) - pair.xb).abs()));
        }
        worst = worst.max(ext_err / ext_amp).max(pos_err / pos_amp);
        let p = ma * f(ua) + mb * f(ub);
        drift = drift.max((p - p0).abs() / (ma.max(mb) * scale));
    }
    (worst, drift)
}

fn measure<S: Scalar>(scale: f64) -> [f64; 4] {
    let (pair, drift) = pair_error::<S>(scale);
    [
        single_body_error::<S>(scale, false),
        single_body_error::<S>(scale, true),
        pair,
        drift,
    ]
}

/// Bounds are about 3× the measured worst case (printed with `--nocapture`). The value's
/// columns are dominated by reading the state rounded to a position (half a last bit of
/// a small amplitude); the kernel's by the state it keeps (Q24.40 for `I16F16`, Q64.64
/// for `I32F32`), which is what it steps, read here without rounding.
#[test]
fn every_backend_follows_the_reference() {
    println!("backend  impulse form  force form  two-body kernel  momentum drift");
    let rows: [(&str, [f64; 4], [f64; 4]); 4] = [
        ("f64", measure::<f64>(1.0), [1e-14, 1e-14, 1e-12, 2e-16]),
        ("f32", measure::<f32>(1.0), [5e-6, 5e-6, 2e-3, 2e-7]),
        ("I32F32", measure::<I32F32>(1.0), [1e-7, 1e-7, 1e-11, 2e-16]),
        (
            "I16F16",
            measure::<I16F16>(100.0),
            [6e-5, 6e-5, 2e-8, 3e-11],
        ),
    ];
    for (name, got, _) in &rows {
        println!(
            "{name:<8} {:>12.1e} {:>11.1e} {:>16.1e} {:>15.1e}",
            got[0], got[1], got[2], got[3]
        );
    }
    for (name, got, bound) in rows {
        for k in 0..4 {
            assert!(
                got[k] < bound[k],
                "{name} column {k}: {:e} ≥ {:e}",
                got[k],
                bound[k]
            );
        }
    }
    // docs/accuracy.md's table.
    let table: Vec<Vec<String>> = rows
        .iter()
        .map(|(name, got, bound)| {
            let mut row = vec![format!("`{name}`")];
            row.extend(got.iter().map(|&v| lab::table::sci(v)));
            row.push(
                bound
                    .iter()
                    .map(|b| format!("{b:.0e}"))
                    .collect::<Vec<_>>()
                    .join(", "),
            );
            row
        })
        .collect();
    let header = [
        "backend",
        "impulse form",
        "force form",
        "two-body kernel",
        "momentum drift",
        "bounds asserted",
    ];
    let path = lab::table::write_figures(
        "accuracy/backends-vs-reference.md",
        &lab::table::markdown(&header, &table),
    );
    println!("wrote {}", path.display());
}
