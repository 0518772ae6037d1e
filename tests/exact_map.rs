//! Every backend against the analytic damped oscillator, through the public API: the
//! exact map, the exact start of a release and of a fling, and the state each backend
//! keeps, over the grid of springs and rates a display or a haptic loop uses.
//!
//! The measure is `max |x_n − x(t_n)|` over 10 000 steps, relative to the amplitude. The
//! grid here is a short one (`cargo test --release --test exact_map -- --nocapture`
//! prints the worst case of every test); `STIFFSPRING_FULL_GRID=1` runs the whole one
//! (every spring from 1 to 50 Hz at every rate from 60 Hz to 10 kHz with `f·dt ≤ 0.2`,
//! ζ from 0 to 10).

use core::f64::consts::PI;
use lab::reference::analytic;
use stiffspring::{I16F16, I32F32, Scalar, SpringValue, Tuning};

const STEPS: usize = 10_000;

/// One spring of the grid.
#[derive(Clone, Copy, Debug)]
struct Case {
    frequency: f64,
    zeta: f64,
    rate: f64,
    amplitude: f64,
    fling: bool,
}

fn full_grid() -> bool {
    std::env::var_os("STIFFSPRING_FULL_GRID").is_some()
}

/// Springs 1–50 Hz stepped at 60 Hz to 10 kHz with `f·dt ≤ 0.2`; released from an
/// offset of `amplitude` or flung from the target with a peak of about `amplitude`.
fn grid(zetas: &[f64], amplitudes: &[f64]) -> Vec<Case> {
    let (frequencies, rates): (&[f64], &[f64]) = if full_grid() {
        (
            &[1.0, 1.37, 2.0, 3.3, 5.0, 7.7, 12.0, 20.0, 37.1, 50.0],
            &[60.0, 120.0, 240.0, 500.0, 1000.0, 2000.0, 4000.0, 10_000.0],
        )
    } else {
        (&[1.0, 3.3, 12.0, 50.0], &[60.0, 1000.0, 10_000.0])
    };
    let mut cases = Vec::new();
    for &rate in rates {
        for &frequency in frequencies {
            if frequency / rate > 0.2 {
                continue;
            }
            for &zeta in zetas {
                for &amplitude in amplitudes {
                    for fling in [false, true] {
                        cases.push(Case {
                            frequency,
                            zeta,
                            rate,
                            amplitude,
                            fling,
                        });
                    }
                }
            }
        }
    }
    cases
}

/// The worst `|x_n − x(t_n)|/amplitude` of one case in backend `S`, through the public
/// API: a release is a retarget from rest (`set_target`), a fling a `fling` at rest.
fn worst_error<S: Scalar>(case: &Case) -> f64 {
    let dt = 1.0 / case.rate;
    let omega = 2.0 * PI * case.frequency;
    let tuning = Tuning::from_frequency(case.frequency, case.zeta, dt).expect("a valid tuning");
    let (x0, v0) = if case.fling {
        (0.0, case.amplitude * omega)
    } else {
        (case.amplitude, 0.0)
    };
    let mut value = SpringValue::<S>::new([S::from_f64(x0)], &tuning).expect("representable");
    if case.fling {
        value
            .try_fling([S::from_f64(v0)])
            .expect("a representable fling");
    } else {
        value.set_target([S::ZERO]);
    }
    let mut worst: f64 = 0.0;
    for n in 1..=STEPS {
        value.advance();
        let (exact, _) = analytic(x0, v0, omega, case.zeta, n as f64 * dt);
        worst = worst.max((value.position()[0].to_f64() - exact).abs());
    }
    worst / case.amplitude
}

/// The worst error over the cases, and the case it came from.
fn worst_over<S: Scalar>(cases: &[Case]) -> (f64, Case) {
    cases
        .iter()
        .map(|c| (worst_error::<S>(c), *c))
        .fold((0.0, cases[0]), |a, b| if b.0 > a.0 { b } else { a })
}

const DAMPED: [f64; 6] = [0.1, 0.3, 0.7, 1.0, 2.0, 10.0];

#[test]
fn i16f16_follows_the_continuous_spring_to_a_thousandth() {
    for zetas in [&DAMPED[..], &[0.0]] {
        for amplitude in [1.0, 100.0] {
            let (worst, case) = worst_over::<I16F16>(&grid(zetas, &[amplitude]));
            println!("I16F16, ζ {zetas:?}, A = {amplitude}: {worst:.2e} at {case:?}");
            assert!(worst <= 1e-3, "{worst} at {case:?}");
        }
    }
}

#[test]
fn i32f32_follows_the_continuous_spring_to_a_ten_millionth() {
    let zetas = [0.0, 0.1, 0.3, 0.7, 1.0, 2.0, 10.0];
    for amplitude in [1.0, 100.0] {
        let (worst, case) = worst_over::<I32F32>(&grid(&zetas, &[amplitude]));
        println!("I32F32, A = {amplitude}: {worst:.2e} at {case:?}");
        assert!(worst <= 1e-7, "{worst} at {case:?}");
    }
}

#[test]
fn f32_follows_a_damped_spring_to_a_hundred_thousandth() {
    for amplitude in [1.0, 100.0] {
        let (worst, case) = worst_over::<f32>(&grid(&DAMPED, &[amplitude]));
        println!("f32, damped, A = {amplitude}: {worst:.2e} at {case:?}");
        assert!(worst <= 1e-5, "{worst} at {case:?}");
    }
}

/// An undamped `f32` spring drifts in phase: its `C_k` carries 24 bits, and an error `ε`
/// in it turns the map by `tan(θ/2)·ε/2` more per step (`θ = ω·dt`), which adds up over
/// the run. The bound below is that drift for half an ulp of `C_k`, plus the `1e−5` of
/// the damped case; it is what an `f32` user of an undamped spring gets, and why the
/// README points them to `I32F32` (or `f64`).
#[test]
fn f32_undamped_drifts_no_more_than_the_precision_of_its_coefficient() {
    let mut overall = (0.0, None);
    let mut at_a_fifth: f64 = 0.0;
    for case in grid(&[0.0], &[1.0]) {
        let bound = drift_bound(case.frequency / case.rate);
        let worst = worst_error::<f32>(&case);
        if worst > overall.0 {
            overall = (worst, Some(case));
        }
        if case.frequency / case.rate == 0.2 {
            at_a_fifth = at_a_fifth.max(worst);
        }
        assert!(worst <= bound, "{worst} > {bound} at {case:?}");
    }
    let (worst, case) = overall;
    let case = case.expect("a grid of cases");
    println!("f32, undamped: {worst:.2e} at {case:?}");
    println!("f32, undamped, f·dt = 0.2 exactly: {at_a_fifth:.2e}");
}

/// The bound of the test above at `f·dt`: half an ulp of `C_k` over the run, plus the
/// damped case's `1e−5`.
fn drift_bound(frequency_times_dt: f64) -> f64 {
    let theta = 2.0 * PI * frequency_times_dt;
    1e-5 + STEPS as f64 * (theta / 2.0).tan() * 2f64.powi(-24)
}

/// The same drift over every `f·dt` from `10⁻⁴` to 0.2 in steps of `10⁻⁴` (springs of
/// 0.1 to 200 Hz at 1 kHz, released and flung): the bound holds everywhere, and the
/// worst case comes close to it, so the bound is the right size.
#[test]
fn f32_undamped_drift_over_a_dense_sweep_of_f_dt() {
    let rate = 1000.0;
    let (mut worst, mut worst_at, mut closest, mut closest_at) = (0.0, 0.0, 0.0, 0.0);
    for k in 1..=2000 {
        let frequency_times_dt = k as f64 * 1e-4;
        let bound = drift_bound(frequency_times_dt);
        for fling in [false, true] {
            let case = Case {
                frequency: frequency_times_dt * rate,
                zeta: 0.0,
                rate,
                amplitude: 1.0,
                fling,
            };
            let error = worst_error::<f32>(&case);
            assert!(error <= bound, "{error} > {bound} at {case:?}");
            if error > worst {
                (worst, worst_at) = (error, frequency_times_dt);
            }
            if error / bound > closest {
                (closest, closest_at) = (error / bound, frequency_times_dt);
            }
        }
    }
    println!(
        "f32, undamped, f·dt 1e-4..0.2 at 1 kHz: worst {worst:.2e} at f·dt {worst_at:.4}, \
         {:.2} of the bound there; closest to the bound: {closest:.2} at f·dt {closest_at:.4}",
        worst / drift_bound(worst_at)
    );
}

/// docs/accuracy.md's table of this file's worst cases, written for
/// `scripts/check-figures`: `target/figures/exact-map-short.md`, or
/// `exact-map-full.md` with `STIFFSPRING_FULL_GRID`.
#[test]
fn accuracy_table() {
    let row = |backend: &str, cases: &str, (worst, case): (f64, Case), bound: &str| {
        vec![
            format!("`{backend}`"),
            cases.to_string(),
            format!("{worst:.2e}"),
            format!(
                "{} Hz at {} Hz, ζ {}, {}, A = {}",
                case.frequency,
                case.rate,
                case.zeta,
                if case.fling { "fling" } else { "release" },
                case.amplitude
            ),
            bound.to_string(),
        ]
    };
    let all = [0.0, 0.1, 0.3, 0.7, 1.0, 2.0, 10.0];
    let rows = vec![
        row(
            "I16F16",
            "ζ 0.1–10, A = 1 and 100",
            worst_over::<I16F16>(&grid(&DAMPED, &[1.0, 100.0])),
            "1e−3",
        ),
        row(
            "I16F16",
            "ζ = 0, A = 1 and 100",
            worst_over::<I16F16>(&grid(&[0.0], &[1.0, 100.0])),
            "1e−3",
        ),
        row(
            "I32F32",
            "ζ 0–10, A = 1 and 100",
            worst_over::<I32F32>(&grid(&all, &[1.0, 100.0])),
            "1e−7",
        ),
        row(
            "f32",
            "ζ 0.1–10, A = 1 and 100",
            worst_over::<f32>(&grid(&DAMPED, &[1.0, 100.0])),
            "1e−5",
        ),
        row(
            "f32",
            "ζ = 0, A = 1",
            worst_over::<f32>(&grid(&[0.0], &[1.0])),
            "`1e−5 + N·tan(θ/2)·2⁻²⁴`",
        ),
        row(
            "f64",
            "ζ 0, 0.1, 1, 10, A = 1",
            worst_over::<f64>(&grid(&[0.0, 0.1, 1.0, 10.0], &[1.0])),
            "1e−9",
        ),
    ];
    let header = [
        "backend",
        "cases",
        "worst error / amplitude",
        "where",
        "bound asserted",
    ];
    let name = if full_grid() {
        "exact-map-full.md"
    } else {
        "exact-map-short.md"
    };
    let path = lab::table::write_figures(name, &lab::table::markdown(&header, &rows));
    println!("wrote {}", path.display());
}

#[test]
fn f64_is_exact_to_rounding() {
    let zetas = [0.0, 0.1, 1.0, 10.0];
    let (worst, case) = worst_over::<f64>(&grid(&zetas, &[1.0]));
    println!("f64: {worst:.2e} at {case:?}");
    assert!(worst <= 1e-9, "{worst} at {case:?}");
}

/// Heavily overdamped springs at a low rate (ζ = 10 at 12 Hz and 60 Hz: `ζω·dt` = 12.6)
/// extrapolate one step back to a start `u₀ = x(0) − x(−dt)` of 7·10¹⁰ times the
/// offset; the kept velocity `(1 − C_d)·u₀` of the values does not, in any backend.
#[test]
fn heavily_overdamped_starts_are_exact_in_every_backend() {
    for fling in [false, true] {
        let case = Case {
            frequency: 12.0,
            zeta: 10.0,
            rate: 60.0,
            amplitude: 1.0,
            fling,
        };
        let errors = [
            worst_error::<f64>(&case),
            worst_error::<f32>(&case),
            worst_error::<I32F32>(&case),
            worst_error::<I16F16>(&case),
        ];
        println!(
            "ζ = 10, 12 Hz at 60 Hz, {}: f64 {:.1e}, f32 {:.1e}, I32F32 {:.1e}, I16F16 {:.1e}",
            if fling { "fling" } else { "release" },
            errors[0],
            errors[1],
            errors[2],
            errors[3]
        );
        assert!(errors[0] < 1e-12);
        assert!(errors[1] < 1e-6);
        assert!(errors[2] < 1e-9);
        assert!(errors[3] < 1e-4);
    }
}

/// Undamped fixed point keeps its amplitude: the spring term is rounded toward zero and
/// each half of a step is a shear of the integer lattice, so nothing drags it.
#[test]
fn undamped_i16f16_keeps_its_amplitude_for_a_million_steps() {
    for frequency_times_dt in [1e-3, 1e-2] {
        let dt = 1e-3;
        let tuning = Tuning::from_frequency(frequency_times_dt / dt, 0.0, dt).expect("valid");
        let mut value = SpringValue::<I16F16>::new([I16F16::ONE], &tuning).expect("representable");
        value.set_target([I16F16::ZERO]);
        let period = (1.0 / frequency_times_dt).ceil() as usize;
        for _ in 0..1_000_000 - period {
            value.advance();
        }
        let mut amplitude: f64 = 0.0;
        for _ in 0..period {
            value.advance();
            amplitude = amplitude.max(value.position()[0].to_f64().abs());
        }
        println!("I16F16, undamped, f·dt {frequency_times_dt}: last period's peak {amplitude:.7}");
        assert!(amplitude >= 0.99, "f·dt {frequency_times_dt}: {amplitude}");
        assert!(amplitude <= 1.01, "f·dt {frequency_times_dt}: {amplitude}");
    }
}
