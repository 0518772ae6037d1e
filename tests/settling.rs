//! `Tuning::settling_steps` against the analytic oscillator: a value tuned by the exact
//! map lies on the continuous trajectory at every step, so the step on which it comes to
//! rest is the first sample `n` at which the analytic offset `x(n·dt)` and the kept step
//! velocity `(1 − C_d)·(x(n·dt) − x((n − 1)·dt))` are both inside the rest band
//! (`RestThreshold`'s definition: `|x| ≤ p/√2`, `|ũ| ≤ min(p·√C_k/√2, v·dt)`).

use stiffspring::{RestThreshold, Tuning};

/// The damped oscillator `x'' + 2ζω·x' + ω²·x = 0` from `x(0) = x0`, `x'(0) = v0`.
fn analytic(omega: f64, zeta: f64, x0: f64, v0: f64, t: f64) -> f64 {
    if zeta < 1.0 {
        let wd = omega * (1.0 - zeta * zeta).sqrt();
        let a = x0;
        let b = (v0 + zeta * omega * x0) / wd;
        (-zeta * omega * t).exp() * (a * (wd * t).cos() + b * (wd * t).sin())
    } else if zeta == 1.0 {
        (x0 + (v0 + omega * x0) * t) * (-omega * t).exp()
    } else {
        let s = omega * (zeta * zeta - 1.0).sqrt();
        let (r1, r2) = (-zeta * omega + s, -zeta * omega - s);
        let c1 = (v0 - r2 * x0) / (r1 - r2);
        let c2 = x0 - c1;
        c1 * (r1 * t).exp() + c2 * (r2 * t).exp()
    }
}

/// The first step at which the analytic samples are inside the rest band.
fn reference(tuning: &Tuning, omega: f64, zeta: f64, x0: f64, v0: f64, rest: RestThreshold) -> u32 {
    let dt = tuning.dt();
    let p = rest.position() * std::f64::consts::FRAC_1_SQRT_2;
    let u_band = (p * tuning.stiffness().sqrt()).min(rest.velocity() * dt);
    let keep = 1.0 - tuning.damping();
    let mut previous = analytic(omega, zeta, x0, v0, -dt);
    for n in 0..10_000_000u32 {
        let x = analytic(omega, zeta, x0, v0, f64::from(n) * dt);
        let u = keep * (x - previous);
        if x.abs() <= p && u.abs() <= u_band {
            return n;
        }
        previous = x;
    }
    panic!("the analytic oscillator did not settle");
}

#[test]
fn settling_steps_is_the_step_the_analytic_trajectory_enters_the_rest_band() {
    let mut checked = 0;
    for rate in [60.0, 120.0, 240.0] {
        for frequency in [0.5, 2.0, 5.0] {
            for zeta in [0.2, 0.5, 0.7, 1.0, 1.5, 3.0] {
                let tuning = Tuning::from_frequency(frequency, zeta, 1.0 / rate).unwrap();
                let omega = std::f64::consts::TAU * frequency;
                for (x0, v0) in [
                    (300.0, 0.0),
                    (-40.0, 0.0),
                    (300.0, -2000.0),
                    (0.0, 5000.0),
                    (12.5, 800.0),
                ] {
                    for rest in [
                        RestThreshold::PIXELS,
                        RestThreshold::new(0.01, 1.0).unwrap(),
                    ] {
                        let got = tuning.settling_steps(x0, v0, rest).expect("settles");
                        let want = reference(&tuning, omega, zeta, x0, v0, rest);
                        // The value's rounding moves the crossing of the band by a step at
                        // most (a sample within a last bit of its edge).
                        assert!(
                            got.abs_diff(want) <= 1,
                            "{frequency} Hz, ζ {zeta}, {rate} Hz, ({x0}, {v0}): {got} steps, the analytic {want}"
                        );
                        let seconds = tuning.settling_time(x0, v0, rest).unwrap();
                        assert_eq!(seconds, f64::from(got) * tuning.dt());
                        checked += 1;
                    }
                }
            }
        }
    }
    assert_eq!(checked, 3 * 3 * 6 * 5 * 2);
}

#[test]
fn a_spring_without_damping_never_settles_and_bad_input_is_none() {
    let undamped = Tuning::from_frequency(2.0, 0.0, 1.0 / 60.0).unwrap();
    assert_eq!(
        undamped.settling_steps(100.0, 0.0, RestThreshold::PIXELS),
        None
    );
    let t = Tuning::from_frequency(2.0, 0.7, 1.0 / 60.0).unwrap();
    assert_eq!(t.settling_steps(f64::NAN, 0.0, RestThreshold::PIXELS), None);
    assert_eq!(
        t.settling_steps(1.0, f64::INFINITY, RestThreshold::PIXELS),
        None
    );
    assert_eq!(t.settling_steps(0.0, 0.0, RestThreshold::PIXELS), Some(0));
}
