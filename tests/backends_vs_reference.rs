//! Every backend against the independent f64 reference model of the article.
//!
//! - A value with raw coefficients is the article's body on a fixed anchor: its positions
//!   and step velocities must follow the reference's impulse form (the corrected eq. 27)
//!   and its force form with symplectic Euler (the same map for one spring).
//! - The two-body kernel (`Coefficients::respond` + `BodyWeights::split`) applied to a
//!   pair of free bodies must follow the reference's reduced-mass pair (eq. 17–21, 27).
//!
//! `cargo test --release --test backends_vs_reference -- --nocapture` prints the measured
//! worst errors per backend, which the README quotes.

use lab::reference;
use lab::rng::Rng;

use stiffspring::kernel::{BodyWeights, Coefficients};
use stiffspring::{I16F16, I32F32, RestThreshold, Scalar, SpringValue, Tuning};

const STEPS: usize = 2_000;

/// Worst |x_lib − x_ref| relative to the amplitude (max |x_ref|), over random raw
/// tunings in [0, 1]², random masses and time steps, starting offset `scale`.
fn single_body_error<S: Scalar>(scale: f64, force_form: bool) -> f64 {
    let mut rng = Rng::seeded(3);
    let never = RestThreshold::new(1e-300, 1e-300).unwrap();
    let mut worst = 0.0f64;
    for _ in 0..200 {
        let (ck, cd) = (rng.unit(), 0.02 + 0.98 * rng.unit());
        let m = 10f64.powf(6.0 * rng.unit() - 3.0);
        let dt = 10f64.powf(-4.0 * rng.unit());
        // Offsets and step velocities exactly representable in the backend, so the
        // comparison starts from the same state.
        let x0 = S::from_f64(scale * (2.0 * rng.unit() - 1.0)).to_f64();
        let u0 = S::from_f64(0.1 * scale * (2.0 * rng.unit() - 1.0)).to_f64();
        let tuning = Tuning::from_coefficients(ck, cd).unwrap();
        let mut value = SpringValue::<S, 1>::new([S::from_f64(x0)], tuning, dt)
            .unwrap()
            .with_rest_threshold(never);
        value.set_target([S::ZERO]).unwrap();
        // Raw coefficients: fling sets u = v·dt. The reference starts from the step
        // velocity the backend actually holds, so both start from the same state.
        value.fling([S::from_f64(u0 / dt)]).unwrap();
        let u_start = value.step_velocity()[0].to_f64();
        let mut body = reference::Particle1::new(x0, u_start / dt, m);
        let mut amplitude = x0.abs();
        let mut err = 0.0f64;
        for _ in 0..STEPS {
            value.step();
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
    for _ in 0..200 {
        let (ck, cd) = (rng.unit(), 0.02 + 0.98 * rng.unit());
        let (ma, mb) = (
            10f64.powf(4.0 * rng.unit() - 2.0),
            10f64.powf(4.0 * rng.unit() - 2.0),
        );
        let dt = 1e-3;
        let rest = 0.5 * scale;
        let xa = S::from_f64(0.0);
        let xb = S::from_f64(rest + scale * (rng.unit() - 0.5));
        let (ua, ub) = (
            S::from_f64(0.05 * scale * (rng.unit() - 0.5)),
            S::from_f64(0.05 * scale * (rng.unit() - 0.5)),
        );
        let coefficients = Coefficients::<S>::new(&Tuning::from_coefficients(ck, cd).unwrap());
        let weights = BodyWeights::<S>::from_inverse_masses(1.0 / ma, 1.0 / mb).unwrap();
        let rest_s = S::from_f64(rest);
        let (mut xa, mut xb, mut ua, mut ub) = (xa, xb, ua, ub);
        let mut pair = reference::Pair1::new(
            xa.to_f64(),
            ua.to_f64() / dt,
            ma,
            xb.to_f64(),
            ub.to_f64() / dt,
            mb,
        );
        let p0 = ma * ua.to_f64() + mb * ub.to_f64();
        // The extension is what the spring acts on; the pair also drifts as a whole, and
        // that absolute position is compared relative to the distance travelled.
        let (mut ext_err, mut ext_amp) = (0.0f64, 1e-3 * scale);
        let (mut pos_err, mut pos_amp) = (0.0f64, scale);
        for _ in 0..STEPS {
            // The kernel in its 1-D form: extension, relative step velocity, response,
            // split, then both positions advance.
            let extension = xb.sub(xa).sub(rest_s);
            let u_rel = ub.sub(ua);
            let delta = coefficients.respond(extension, u_rel).sub(u_rel);
            let (da, db) = weights.split(delta);
            ua = ua.add(da);
            ub = ub.add(db);
            xa = xa.add(ua);
            xb = xb.add(ub);
            pair.impulse_step(ck, cd, rest, dt);
            let ext = xb.to_f64() - xa.to_f64() - rest;
            ext_amp = ext_amp.max(pair.extension(rest).abs());
            ext_err = ext_err.max((ext - pair.extension(rest)).abs());
            pos_amp = pos_amp.max(pair.xa.abs()).max(pair.xb.abs());
            pos_err = pos_err.max(
                (xa.to_f64() - pair.xa)
                    .abs()
                    .max((xb.to_f64() - pair.xb).abs()),
            );
        }
        worst = worst.max(ext_err / ext_amp).max(pos_err / pos_amp);
        let p = ma * ua.to_f64() + mb * ub.to_f64();
        drift = drift.max((p - p0).abs() / (ma.max(mb) * scale));
    }
    (worst, drift)
}

/// Bounds are about 3× the measured worst case. The two-body column is dominated by the
/// pair drifting as a whole: its extension is a difference of growing absolute positions,
/// which f32 and I16F16 hold to their own resolution.
#[test]
fn every_backend_follows_the_reference() {
    println!("backend  impulse form  force form  two-body kernel  momentum drift");
    let rows: [(&str, [f64; 4], [f64; 4]); 4] = [
        ("f64", measure::<f64>(1.0), [1e-12, 1e-12, 1e-10, 1e-12]),
        ("f32", measure::<f32>(1.0), [2e-6, 2e-6, 6e-3, 5e-7]),
        ("I32F32", measure::<I32F32>(1.0), [1e-6, 1e-6, 1e-4, 1e-6]),
        ("I16F16", measure::<I16F16>(100.0), [3e-4, 3e-4, 3e-2, 1e-4]),
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
