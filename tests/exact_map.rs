//! The exact sampled-response map reproduces the continuous oscillator.
//!
//! A value tuned with `Tuning::from_frequency`, started with `set_target` and `fling`,
//! is stepped 10 000 times and compared at every sample with the analytic solution of
//! `ẍ + 2ζω·ẋ + ω²·x = 0` from the independent reference model (`lab::reference`).
//! Error = max |x_n − x(n·dt)| / amplitude, amplitude = max(|x0|, max |x(t)|).
//!
//! The grid: f·dt from 1e−4 to 0.4, ζ from 0 to 10, two starts (released from rest, and
//! flung through the target). Run with `--nocapture` for the table of every backend.

use lab::reference;

use stiffspring::{I16F16, I32F32, RestThreshold, Scalar, SpringValue, Tuning};

const STEPS: usize = 10_000;
const DT: f64 = 1e-3;
const FDTS: [f64; 10] = [1e-4, 3e-4, 1e-3, 3e-3, 1e-2, 3e-2, 0.1, 0.2, 0.3, 0.4];
const ZETAS: [f64; 11] = [0.0, 0.01, 0.1, 0.3, 0.7, 0.99, 1.0, 1.01, 2.0, 5.0, 10.0];

/// A threshold no trajectory reaches before the end, so nothing snaps early (fixed point
/// still widens it to its dead band, which is part of what is measured).
fn never() -> RestThreshold {
    RestThreshold::new(1e-300, 1e-300).unwrap()
}

/// The two starts, for amplitude `a` and angular frequency `w`: released from rest at
/// `a`, and flung from `a/2` toward the target at `a·w`.
fn starts(a: f64, w: f64) -> [(f64, f64); 2] {
    [(a, 0.0), (0.5 * a, -a * w)]
}

/// Max relative error over the run, or `None` when the start does not fit the backend:
/// a velocity beyond the fixed-point range, or a heavily overdamped, undersampled
/// oscillator, which extrapolates back to a huge `x(−dt)` so that its starting step
/// velocity `x(0) − x(−dt)` leaves the range.
fn run<S: Scalar>(fdt: f64, zeta: f64, x0: f64, v0: f64) -> Option<f64> {
    let f = fdt / DT;
    let w = core::f64::consts::TAU * f;
    let u0 = reference::u0_from_analytic(x0, v0, w, zeta, DT);
    if u0.abs().max(v0.abs()) > 0.5 * S::SAFE_MAGNITUDE {
        return None;
    }
    let tuning = Tuning::from_frequency(f, zeta, DT).unwrap();
    let mut value = SpringValue::<S, 1>::new([S::from_f64(x0)], tuning, DT)
        .unwrap()
        .with_rest_threshold(never());
    value.set_target([S::ZERO]).unwrap();
    value.fling([S::from_f64(v0)]).ok()?;
    let mut amplitude = x0.abs();
    let mut worst = 0.0f64;
    for n in 1..=STEPS {
        value.step();
        let (xa, _) = reference::analytic(x0, v0, w, zeta, n as f64 * DT);
        amplitude = amplitude.max(xa.abs());
        worst = worst.max((value.position()[0].to_f64() - xa).abs());
    }
    Some(worst / amplitude)
}

/// The worst error per f·dt (over ζ and both starts) for a backend at amplitude `a`;
/// cells where every start was rejected are `None`.
fn table<S: Scalar>(a: f64) -> Vec<(f64, Option<f64>)> {
    FDTS.iter()
        .map(|&fdt| {
            let w = core::f64::consts::TAU * fdt / DT;
            let mut worst: Option<f64> = None;
            for &z in &ZETAS {
                for (x0, v0) in starts(a, w) {
                    if let Some(e) = run::<S>(fdt, z, x0, v0) {
                        worst = Some(worst.map_or(e, |w| w.max(e)));
                    }
                }
            }
            (fdt, worst)
        })
        .collect()
}

fn print(name: &str, a: f64, rows: &[(f64, Option<f64>)]) {
    println!("{name} (amplitude {a}): worst max|x − x_analytic|/amplitude over ζ ∈ [0, 10]");
    for (fdt, e) in rows {
        match e {
            Some(e) => println!("  f·dt = {fdt:<7} {e:.2e}"),
            None => println!("  f·dt = {fdt:<7} start out of range"),
        }
    }
}

#[test]
fn f64_matches_the_analytic_trajectory_within_1e_minus_9() {
    let rows = table::<f64>(1.0);
    print("f64", 1.0, &rows);
    for (fdt, e) in rows {
        let e = e.unwrap();
        assert!(e < 1e-9, "f·dt = {fdt}: {e:e}");
    }
}

/// f32 keeps its offset relative to the target, so the rounding error shrinks with the
/// trajectory. What remains is the rounding of `C_k` to 24 bits, a frequency error that
/// an undamped spring accumulates as phase: 8.6e−4 after 10 000 steps at f·dt = 0.4,
/// ζ = 0 (measured). The bound leaves a 3× margin.
#[test]
fn f32_matches_the_analytic_trajectory() {
    let rows = table::<f32>(1.0);
    print("f32", 1.0, &rows);
    for (fdt, e) in rows {
        let e = e.unwrap();
        assert!(e < F32_BOUND, "f·dt = {fdt}: {e:e}");
    }
}
const F32_BOUND: f64 = 3e-3;

/// The error model of fixed point, relative to the amplitude `A`, with `ωh = 2π·f·dt`,
/// the smallest `C_k` of the row (≈ `(ωh)²` when well sampled), position LSB `q`,
/// coefficient LSB `c` and `N` steps:
///
/// - **dead band**: the spring stops where `C_k·x` truncates to zero, `(1/C_k + 1)·q`
///   (tests/fixed_rounding.rs);
/// - **rounding noise**: each step rounds `u` by up to `q/2`, which an undamped spring
///   never forgets; as a random walk that is `√N·(q/2)/(ωh)` in position;
/// - **coefficient rounding**: `C_k` off by `c/2` detunes the frequency by `c/(4·C_k)`
///   relatively, a phase error of `N·ωh·c/(4·C_k)` after `N` steps;
/// - **truncation drag**: truncating `(1 − C_d)·u − C_k·x` toward zero shortens `u` by
///   half an LSB per step on average, a Coulomb friction of `q/2` per step² that takes
///   `2/C_k` LSB of amplitude per cycle, `2·N·f·dt/C_k·q` over the run (a bound: a damped
///   spring has lost its amplitude long before).
///
/// The bound is three times their sum plus a floor for the float parts of the test.
fn fixed_bound<S: Scalar>(fdt: f64, amplitude: f64, coef_lsb: f64) -> f64 {
    let wh = core::f64::consts::TAU * fdt;
    // The smallest C_k over the ζ grid, from the reference's pole formula.
    let ck = ZETAS
        .iter()
        .map(|&z| reference::exact_coefficients_from_poles(wh / DT, z, DT).0)
        .fold(f64::INFINITY, f64::min);
    let (q, n) = (S::RESOLUTION, STEPS as f64);
    let dead_band = (1.0 / ck + 1.0) * q / amplitude;
    let noise = n.sqrt() * 0.5 * q / wh / amplitude;
    let detuning = n * wh * coef_lsb / (4.0 * ck);
    let drag = 2.0 * n * fdt / ck * q / amplitude;
    3.0 * (dead_band + noise + detuning + drag) + 1e-9
}

fn check_fixed<S: Scalar>(amplitude: f64, coef_lsb: f64) {
    let rows = table::<S>(amplitude);
    print(S::NAME, amplitude, &rows);
    for (fdt, e) in rows {
        let bound = fixed_bound::<S>(fdt, amplitude, coef_lsb);
        if let Some(e) = e {
            assert!(e < bound, "f·dt = {fdt}: {e:e} ≥ {bound:e}");
        }
    }
}

/// Coefficients in Q3.61.
#[test]
fn i32f32_matches_the_analytic_trajectory() {
    check_fixed::<I32F32>(1.0, (2.0f64).powi(-61));
}

/// Amplitude 100 (a UI offset in pixels); coefficients in Q3.29.
#[test]
fn i16f16_matches_the_analytic_trajectory() {
    check_fixed::<I16F16>(100.0, (2.0f64).powi(-29));
}
