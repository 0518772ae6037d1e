//! Bad input to every public constructor and setter: each gives its documented, typed
//! [`Error`] (exact variant and [`Parameter`]), and a setter that fails leaves its object
//! exactly as it was.
//!
//! Only one argument is bad at a time, so no test depends on the order in which a
//! function checks its arguments. "`t`" is a valid tuning, "`dt`" a valid time step.
//! `±Inf` means both infinities, `≤ 0` means `0.0`, `-0.0` and a negative value.
//!
//! | call | bad input | result |
//! |---|---|---|
//! | `Tuning::from_coefficients(ck, cd)` | `ck` NaN / ±Inf | `NotFinite(Stiffness)` |
//! | | `cd` NaN / ±Inf | `NotFinite(Damping)` |
//! | | `ck < 0`, `ck > 1` | `OutOfRange(Stiffness)` |
//! | | `cd < 0`, `cd > 1` | `OutOfRange(Damping)` |
//! | | the closed square `[0, 1]²` (corners included) | `Ok` |
//! | `Tuning::from_coefficients_extended(ck, cd)` | NaN / ±Inf | `NotFinite(Stiffness / Damping)` |
//! | | on the Jury edge `ck + 2·cd = 4` (`(3, 0.5)`, `(2, 1)`, `(0.5, 1.75)`, `(1.5, 1.25)`) or one ULP of `ck` past it | `OutOfRange(Stiffness)` |
//! | | the closest f64 points inside that edge (`ck + 2·cd = 4 − 2⁻⁵¹`) | `Ok` |
//! | | `cd = 2`, `cd > 2`, `cd < 0` | `OutOfRange(Damping)` |
//! | | `ck = 0` with `1 < cd < 2`; `ck < 0`; `ck ≥ 4`; `cd = 0` with `ck > 1` (undamped) | `OutOfRange(Stiffness)` |
//! | `Tuning::from_frequency(f, ζ, dt)`, `Oscillator::new(f, ζ)` | `f` NaN / ±Inf | `NotFinite(Frequency)` |
//! | | `f ≤ 0` | `NotPositive(Frequency)` |
//! | | `ζ` NaN / ±Inf | `NotFinite(DampingRatio)` |
//! | | `ζ < 0` | `Negative(DampingRatio)` |
//! | | `dt` NaN / ±Inf | `NotFinite(TimeStep)` |
//! | | `dt ≤ 0` | `NotPositive(TimeStep)` |
//! | | `ζ = 0` and `f·dt = 0.5`, `1.5`, `2.5` | `Aliased` |
//! | | `ζ = 0` and `f·dt = 1.0`, `2.0` | `Aliased` |
//! | | `ζ = 0` and `f·dt = 0.5 − 1e−6`, or `0.7` (undersampled) | `Ok` |
//! | | `ζ < 1` and `ω·dt` overflows (`f = 1e300`, `dt = 1e10`) | `OutOfRange(Frequency)` |
//! | | `ζ = 1e200` (finite, heavily overdamped) | `Ok` |
//! | | `f = 1e−300` with `ζ > 0` (`C_k` underflows) | `OutOfRange(Frequency)` |
//! | `Oscillator::from_angular_frequency(ω, ζ)` | `ω` NaN / Inf, `ω ≤ 0` | `NotFinite / NotPositive(Frequency)` |
//! | `Tuning::from_physical(k, c, m, dt)`, `Oscillator::from_physical` | `k` NaN / Inf, `k ≤ 0` | `NotFinite / NotPositive(SpringConstant)` |
//! | | `c` NaN / Inf, `c < 0` | `NotFinite / Negative(DampingConstant)` |
//! | | `m` NaN / Inf, `m ≤ 0` | `NotFinite / NotPositive(Mass)` |
//! | | `dt` | as `from_frequency` |
//! | `Tuning::swiftui(duration, bounce, dt)`, `Oscillator::swiftui` | `duration` NaN / Inf, `duration ≤ 0` | `NotFinite / NotPositive(Duration)` |
//! | | `bounce` NaN / ±Inf | `NotFinite(Bounce)` |
//! | | `bounce ≤ −1`, `bounce > 1` | `OutOfRange(Bounce)` |
//! | | `bounce = 1` (undamped) with `dt = duration/2` | `Aliased` |
//! | | `bounce = 1`, `bounce` one ULP above `−1` | `Ok` |
//! | `Oscillator::swiftui_response(response, fraction)` | `response` NaN / `≤ 0` | `NotFinite / NotPositive(Duration)` |
//! | | `fraction < 0`, NaN | `Negative / NotFinite(DampingRatio)` |
//! | `Tuning::android(stiffness, ζ, dt)`, `Oscillator::android` | `stiffness` NaN / Inf, `≤ 0` | `NotFinite / NotPositive(SpringConstant)` |
//! | | `ζ` NaN, `ζ < 0` | `NotFinite / Negative(DampingRatio)` |
//! | `Tuning::react_spring(tension, friction, dt)`, `Oscillator::react_spring` | `tension` NaN / Inf, `≤ 0` | `NotFinite / NotPositive(SpringConstant)` |
//! | | `friction` NaN / Inf, `< 0` | `NotFinite / Negative(DampingConstant)` |
//! | `Oscillator::tuning(dt)` | `dt` NaN / ±Inf, `≤ 0` | `NotFinite / NotPositive(TimeStep)` |
//! | `Tuning::oscillator(dt)` | `Tuning::rigid()` | `NoContinuousEquivalent` |
//! | | `C_k = 0`; `C_d = 1`; `1 < C_d < 2`; negative real poles `(2.95, 0.5)` | `NoContinuousEquivalent` |
//! | | `dt` NaN / ±Inf, `≤ 0` | `NotFinite / NotPositive(TimeStep)` |
//! | `RestThreshold::new(position, velocity)` | either NaN / ±Inf | `NotFinite(Threshold)` |
//! | | either `≤ 0` | `NotPositive(Threshold)` |
//! | `RestThreshold::from_min_visible_change(c)` | NaN / ±Inf, `≤ 0` | `NotFinite / NotPositive(Threshold)` |
//! | `kernel::BodyWeights::from_inverse_masses(a, b)` | both `0` | `NotPositive(Mass)` |
//! | | either `< 0` | `Negative(Mass)` |
//! | | either NaN / ±Inf | `NotFinite(Mass)` |
//! | `SpringValue::<f32 / f64>::new(p, t, dt)` | any component NaN / ±Inf | `NotFinite(Position)` |
//! | | any component beyond `Scalar::SAFE_MAGNITUDE` (`2¹⁰⁰` / `2¹⁰⁰⁰`), `±MAX` | `OutOfRange(Position)` |
//! | | exactly `±SAFE_MAGNITUDE` | `Ok` |
//! | `SpringValue::<I16F16 / I32F32>::new(p, t, dt)` | `MIN`, `MAX` (the whole range is accepted) | `Ok` |
//! | `SpringValue::new`, any backend | `dt` NaN / ±Inf, `≤ 0` | `NotFinite / NotPositive(TimeStep)` |
//! | `SpringValue::set_target`, `set_position` | as the position of `new` | same error, value unchanged |
//! | `SpringValue::fling(v)` | NaN / ±Inf | `NotFinite(Velocity)`, unchanged |
//! | | beyond `SAFE_MAGNITUDE` (floats) | `OutOfRange(Velocity)`, unchanged |
//! | | `u₀ = v·dt` beyond the range: `f32` `v = 2⁹⁹`, `dt = 4`; `I16F16` `v = 30000`, `dt = 2` | `OutOfRange(Velocity)`, unchanged (no saturation) |
//! | `SpringValue::set_tuning(t)` | new tuning needs `u` beyond the range (`I16F16`, `v = 20000`, `Q = e`) | `OutOfRange(Velocity)`, unchanged |
//! | `SpringValue::set_dt(dt)` | NaN / ±Inf, `≤ 0` | `NotFinite / NotPositive(TimeStep)`, unchanged |
//! | | exact map of `ζ = 0`, 30 Hz, from 240 Hz to 60 Hz | `Aliased`, unchanged |
//! | | new `u` beyond the range (`I16F16`, `v = 20000`, 60 Hz → `dt = 2`) | `OutOfRange(Velocity)`, unchanged |
//! | `SpringBatch::new(dt)` | NaN / ±Inf, `≤ 0` | `NotFinite / NotPositive(TimeStep)` |
//! | `SpringBatch::push`, `push_with_threshold` | batch full | `CapacityFull`, nothing added, `len` unchanged |
//! | | position NaN / beyond `SAFE_MAGNITUDE` | `NotFinite / OutOfRange(Position)`, nothing added |
//! | `SpringBatch::{set_target, fling, set_tuning, position, target, step_velocity, is_at_rest}` | index `len`, `usize::MAX`, any index of an empty batch | `OutOfRange(Index)`, batch unchanged |
//! | `SpringBatch::set_target`, `fling` | NaN / `u₀` beyond the range | as `SpringValue`, batch unchanged |
//! | `SpringBatch::set_tuning` | new `u` beyond the range | `OutOfRange(Velocity)`, batch unchanged |

use stiffspring::kernel::BodyWeights;
use stiffspring::{
    Error, I16F16, I32F32, Oscillator, Parameter, RestThreshold, Scalar, SpringBatch, SpringValue,
    Tuning,
};

use Error::OutOfRange;
use Error::{Aliased, CapacityFull, Negative, NoContinuousEquivalent, NotFinite, NotPositive};
use Parameter::*;

const DT: f64 = 1.0 / 60.0;
const NON_FINITE: [f64; 3] = [f64::NAN, f64::INFINITY, f64::NEG_INFINITY];
const NOT_POSITIVE: [f64; 4] = [0.0, -0.0, -1.0, -f64::MAX];
const NEGATIVE: [f64; 3] = [-1e-300, -0.5, -f64::MAX];

/// A valid tuning from the exact map.
fn sampled() -> Tuning {
    Tuning::from_frequency(2.0, 0.3, DT).unwrap()
}

/// A valid tuning from raw coefficients.
fn raw() -> Tuning {
    Tuning::from_coefficients(0.1, 0.3).unwrap()
}

/// Checks that `call` gives `expected` for each input of `inputs`.
fn each<T: std::fmt::Debug>(
    inputs: &[f64],
    expected: Error,
    call: impl Fn(f64) -> Result<T, Error>,
) {
    for &x in inputs {
        let got = call(x);
        assert!(
            matches!(&got, Err(e) if *e == expected),
            "input {x:e}: expected Err({expected:?}), got {got:?}"
        );
    }
}

// ---------------------------------------------------------------------------
// Tuning from raw coefficients
// ---------------------------------------------------------------------------

#[test]
fn from_coefficients_rejects_non_finite() {
    each(&NON_FINITE, NotFinite(Stiffness), |x| {
        Tuning::from_coefficients(x, 0.5)
    });
    each(&NON_FINITE, NotFinite(Damping), |x| {
        Tuning::from_coefficients(0.5, x)
    });
}

#[test]
fn from_coefficients_rejects_outside_the_unit_square() {
    let outside = [-1e-300, -0.1, 1.0f64.next_up(), 1.5, f64::MAX, -f64::MAX];
    each(&outside, OutOfRange(Stiffness), |x| {
        Tuning::from_coefficients(x, 0.5)
    });
    each(&outside, OutOfRange(Damping), |x| {
        Tuning::from_coefficients(0.5, x)
    });
}

#[test]
fn from_coefficients_accepts_the_closed_unit_square() {
    for (ck, cd) in [
        (0.0, 0.0),
        (1.0, 1.0),
        (0.0, 1.0),
        (1.0, 0.0),
        (1e-300, 0.5),
    ] {
        let t = Tuning::from_coefficients(ck, cd).unwrap();
        assert_eq!((t.stiffness(), t.damping()), (ck, cd));
        assert!(!t.samples_oscillator());
    }
}

#[test]
fn from_coefficients_extended_rejects_non_finite() {
    each(&NON_FINITE, NotFinite(Stiffness), |x| {
        Tuning::from_coefficients_extended(x, 0.5)
    });
    each(&NON_FINITE, NotFinite(Damping), |x| {
        Tuning::from_coefficients_extended(0.5, x)
    });
}

#[test]
fn from_coefficients_extended_stops_exactly_at_the_jury_edge() {
    // Points with C_k + 2·C_d = 4 exactly (all operands and sums are exact in f64), and
    // the point one ULP past them.
    for (ck, cd) in [(3.0, 0.5), (2.0, 1.0), (0.5, 1.75), (1.5, 1.25)] {
        assert_eq!(ck + 2.0 * cd, 4.0);
        assert_eq!(
            Tuning::from_coefficients_extended(ck, cd),
            Err(OutOfRange(Stiffness)),
            "on the edge: ({ck}, {cd})"
        );
        assert_eq!(
            Tuning::from_coefficients_extended(ck.next_up(), cd),
            Err(OutOfRange(Stiffness)),
            "one ULP outside: ({ck}, {cd})"
        );
    }
    // The closest points inside whose C_k + 2·C_d is still below 4 in f64 (for C_k < 2
    // one ULP of C_k is below half an ULP of 4, so the step is taken in C_d).
    let eps = f64::EPSILON; // 2⁻⁵²
    for (ck, cd) in [
        (3.0f64.next_down(), 0.5),
        (2.0, 1.0 - eps),
        (0.5, 1.75f64.next_down()),
        (1.5, 1.25f64.next_down()),
    ] {
        assert_eq!(ck + 2.0 * cd, 4.0 - 2.0 * eps, "({ck}, {cd})");
        let t = Tuning::from_coefficients_extended(ck, cd).unwrap();
        assert_eq!((t.stiffness(), t.damping()), (ck, cd));
    }
}

#[test]
fn from_coefficients_extended_rejects_damping_outside_zero_two() {
    each(
        &[2.0, 2.0f64.next_up(), 3.0, f64::MAX],
        OutOfRange(Damping),
        |cd| Tuning::from_coefficients_extended(0.01, cd),
    );
    each(&[-1e-300, -0.5], OutOfRange(Damping), |cd| {
        Tuning::from_coefficients_extended(1.5, cd)
    });
}

#[test]
fn from_coefficients_extended_rejects_stiffness_outside_its_region() {
    // No stiffness at all beyond the square: a double pole at z = 1 (Jury's C_k > 0).
    each(
        &[1.0f64.next_up(), 1.5, 1.99],
        OutOfRange(Stiffness),
        |cd| Tuning::from_coefficients_extended(0.0, cd),
    );
    // Negative stiffness, and stiffness at or beyond 4 (where C_k + 2·C_d ≥ 4 for C_d ≥ 0).
    each(
        &[-1e-300, -0.5, 4.0, 5.0, f64::MAX],
        OutOfRange(Stiffness),
        |ck| Tuning::from_coefficients_extended(ck, 0.5),
    );
    // Undamped beyond the square is only marginally stable: the region is open.
    each(&[1.0f64.next_up(), 2.0, 3.9], OutOfRange(Stiffness), |ck| {
        Tuning::from_coefficients_extended(ck, 0.0)
    });
}

#[test]
fn from_coefficients_extended_accepts_the_square_and_the_open_region() {
    for (ck, cd) in [
        (0.0, 0.0),
        (1.0, 1.0),
        (0.0, 1.0),
        (1.5, 0.5),
        (0.5, 1.5),
        (3.9, 0.03125),
    ] {
        // (C_d values whose 1 − C_d is exact, so that `damping()` reads them back.)
        let t = Tuning::from_coefficients_extended(ck, cd).unwrap();
        assert_eq!((t.stiffness(), t.damping()), (ck, cd));
    }
}

// ---------------------------------------------------------------------------
// Tuning from an oscillator (exact map) and the UI platforms
// ---------------------------------------------------------------------------

#[test]
fn from_frequency_rejects_bad_frequency() {
    each(&NON_FINITE, NotFinite(Frequency), |f| {
        Tuning::from_frequency(f, 0.5, DT)
    });
    each(&NOT_POSITIVE, NotPositive(Frequency), |f| {
        Tuning::from_frequency(f, 0.5, DT)
    });
    each(&NON_FINITE, NotFinite(Frequency), |f| {
        Oscillator::new(f, 0.5)
    });
    each(&NOT_POSITIVE, NotPositive(Frequency), |f| {
        Oscillator::new(f, 0.5)
    });
    each(&NON_FINITE, NotFinite(Frequency), |w| {
        Oscillator::from_angular_frequency(w, 0.5)
    });
    each(&NOT_POSITIVE, NotPositive(Frequency), |w| {
        Oscillator::from_angular_frequency(w, 0.5)
    });
}

#[test]
fn from_frequency_rejects_bad_damping_ratio() {
    each(&NON_FINITE, NotFinite(DampingRatio), |z| {
        Tuning::from_frequency(2.0, z, DT)
    });
    each(&NEGATIVE, Negative(DampingRatio), |z| {
        Tuning::from_frequency(2.0, z, DT)
    });
    each(&NON_FINITE, NotFinite(DampingRatio), |z| {
        Oscillator::new(2.0, z)
    });
    each(&NEGATIVE, Negative(DampingRatio), |z| {
        Oscillator::new(2.0, z)
    });
    // −0.0 is not negative.
    assert!(Tuning::from_frequency(2.0, -0.0, DT).is_ok());
}

#[test]
fn from_frequency_and_oscillator_tuning_reject_bad_dt() {
    each(&NON_FINITE, NotFinite(TimeStep), |dt| {
        Tuning::from_frequency(2.0, 0.5, dt)
    });
    each(&NOT_POSITIVE, NotPositive(TimeStep), |dt| {
        Tuning::from_frequency(2.0, 0.5, dt)
    });
    let osc = Oscillator::new(2.0, 0.5).unwrap();
    each(&NON_FINITE, NotFinite(TimeStep), |dt| osc.tuning(dt));
    each(&NOT_POSITIVE, NotPositive(TimeStep), |dt| osc.tuning(dt));
}

#[test]
fn undamped_at_odd_multiples_of_half_the_sample_rate_is_aliased() {
    // f·dt = k/2: the sampled poles e^{±iπk} meet at z = ±1 (a double pole).
    for (f, dt) in [
        (50.0, 0.01),
        (30.0, 1.0 / 60.0),
        (60.0, 1.0 / 120.0),
        (500.0, 1e-3),
        (0.5, 1.0),
        (1.5, 1.0),
        (2.5, 1.0),
    ] {
        assert_eq!(
            Tuning::from_frequency(f, 0.0, dt),
            Err(Aliased),
            "f = {f}, dt = {dt}"
        );
    }
}

#[test]
fn undamped_at_the_sample_rate_is_aliased() {
    // Error::Aliased's documentation: "an undamped oscillator whose frequency is a
    // multiple of half the sample rate (f·dt = k/2)". For even k the two poles meet at
    // z = +1, and u never decays: x drifts without bound.
    for (f, dt) in [
        (1.0, 1.0),
        (60.0, 1.0 / 60.0),
        (120.0, 1.0 / 120.0),
        (2.0, 1.0),
    ] {
        assert_eq!(
            Tuning::from_frequency(f, 0.0, dt),
            Err(Aliased),
            "f = {f}, dt = {dt}"
        );
    }
}

#[test]
fn undamped_off_the_alias_points_is_accepted() {
    // Just below half the rate: C_k = 4·sin²(π·f·dt) < 4 (distinct poles near −1).
    let t = Tuning::from_frequency(0.5 - 1e-6, 0.0, 1.0).unwrap();
    assert!(t.stiffness() < 4.0 && t.stiffness() > 3.9);
    assert_eq!(t.damping(), 0.0);
    // Undersampled but not aliased onto ±1: accepted, as documented.
    let t = Tuning::from_frequency(0.7, 0.0, 1.0).unwrap();
    let expected = 4.0 * (std::f64::consts::PI * 0.7).sin().powi(2);
    assert!((t.stiffness() - expected).abs() < 1e-12);
}

#[test]
fn from_frequency_rejects_an_overflowing_omega_dt() {
    assert_eq!(
        Tuning::from_frequency(1e300, 0.5, 1e10),
        Err(OutOfRange(Frequency))
    );
    assert_eq!(
        Tuning::from_frequency(1e300, 0.0, 1e10),
        Err(OutOfRange(Frequency))
    );
}

#[test]
fn heavily_overdamped_oscillator_is_not_aliased() {
    // ζ = 1e200 is a valid damping ratio (Oscillator::new accepts it). Its tuning is
    // C_k ≈ ω·dt/(2ζ) > 0 (the slow pole), C_d = 1: well inside the stable region, and
    // none of Oscillator::tuning's documented errors applies.
    let t = Tuning::from_frequency(1.0, 1e200, 0.01);
    assert!(matches!(t, Ok(t) if t.stiffness() > 0.0), "{t:?}");
}

#[test]
fn a_frequency_too_low_for_f64_at_this_dt_is_out_of_range() {
    // C_k ≈ (ω·dt)² underflows to 0 while C_d does not: not representable.
    assert_eq!(
        Tuning::from_frequency(1e-300, 0.5, 1.0),
        Err(OutOfRange(Frequency))
    );
}

#[test]
fn from_physical_rejects_bad_constants() {
    each(&NON_FINITE, NotFinite(SpringConstant), |k| {
        Tuning::from_physical(k, 1.0, 1.0, DT)
    });
    each(&NOT_POSITIVE, NotPositive(SpringConstant), |k| {
        Tuning::from_physical(k, 1.0, 1.0, DT)
    });
    each(&NON_FINITE, NotFinite(DampingConstant), |c| {
        Tuning::from_physical(100.0, c, 1.0, DT)
    });
    each(&NEGATIVE, Negative(DampingConstant), |c| {
        Tuning::from_physical(100.0, c, 1.0, DT)
    });
    each(&NON_FINITE, NotFinite(Mass), |m| {
        Tuning::from_physical(100.0, 1.0, m, DT)
    });
    each(&NOT_POSITIVE, NotPositive(Mass), |m| {
        Tuning::from_physical(100.0, 1.0, m, DT)
    });
    each(&NON_FINITE, NotFinite(TimeStep), |dt| {
        Tuning::from_physical(100.0, 1.0, 1.0, dt)
    });
    each(&NOT_POSITIVE, NotPositive(TimeStep), |dt| {
        Tuning::from_physical(100.0, 1.0, 1.0, dt)
    });
    each(&NON_FINITE, NotFinite(SpringConstant), |k| {
        Oscillator::from_physical(k, 1.0, 1.0)
    });
    each(&NEGATIVE, Negative(DampingConstant), |c| {
        Oscillator::from_physical(100.0, c, 1.0)
    });
    each(&NOT_POSITIVE, NotPositive(Mass), |m| {
        Oscillator::from_physical(100.0, 1.0, m)
    });
    // c = 0 is an undamped spring, not an error.
    assert!(Tuning::from_physical(100.0, 0.0, 1.0, DT).is_ok());
}

#[test]
fn swiftui_rejects_bad_duration_and_bounce() {
    each(&NON_FINITE, NotFinite(Duration), |d| {
        Tuning::swiftui(d, 0.2, DT)
    });
    each(&NOT_POSITIVE, NotPositive(Duration), |d| {
        Tuning::swiftui(d, 0.2, DT)
    });
    each(&NON_FINITE, NotFinite(Bounce), |b| {
        Tuning::swiftui(0.5, b, DT)
    });
    let outside = [
        -1.0,
        (-1.0f64).next_down(),
        -2.0,
        1.0f64.next_up(),
        1.5,
        f64::MAX,
    ];
    each(&outside, OutOfRange(Bounce), |b| {
        Tuning::swiftui(0.5, b, DT)
    });
    each(&outside, OutOfRange(Bounce), |b| {
        Oscillator::swiftui(0.5, b)
    });
    each(&NOT_POSITIVE, NotPositive(Duration), |d| {
        Oscillator::swiftui(d, 0.2)
    });
    each(&NON_FINITE, NotFinite(TimeStep), |dt| {
        Tuning::swiftui(0.5, 0.2, dt)
    });
    each(&NOT_POSITIVE, NotPositive(TimeStep), |dt| {
        Tuning::swiftui(0.5, 0.2, dt)
    });
}

#[test]
fn swiftui_bounce_range_is_half_open() {
    // bounce = 1 is SwiftUI's undamped spring: ζ = 0.
    let o = Oscillator::swiftui(0.5, 1.0).unwrap();
    assert_eq!(o.damping_ratio(), 0.0);
    assert!(Tuning::swiftui(0.5, 1.0, DT).is_ok());
    // Just above −1: ζ = 1/(1 + bounce) is huge but finite.
    let b = (-1.0f64).next_up();
    let o = Oscillator::swiftui(0.5, b).unwrap();
    assert_eq!(o.damping_ratio(), 1.0 / (1.0 + b));
    assert!(Tuning::swiftui(0.5, b, DT).is_ok());
    // Undamped at dt = duration/2, i.e. f·dt = 1/2: aliased.
    assert_eq!(Tuning::swiftui(0.5, 1.0, 0.25), Err(Aliased));
}

#[test]
fn swiftui_response_rejects_bad_input() {
    each(&[f64::NAN, f64::INFINITY], NotFinite(Duration), |r| {
        Oscillator::swiftui_response(r, 0.8)
    });
    each(&NOT_POSITIVE, NotPositive(Duration), |r| {
        Oscillator::swiftui_response(r, 0.8)
    });
    each(&NEGATIVE, Negative(DampingRatio), |z| {
        Oscillator::swiftui_response(0.5, z)
    });
    each(&NON_FINITE, NotFinite(DampingRatio), |z| {
        Oscillator::swiftui_response(0.5, z)
    });
}

#[test]
fn android_rejects_bad_input() {
    each(&NON_FINITE, NotFinite(SpringConstant), |k| {
        Tuning::android(k, 0.5, DT)
    });
    each(&NOT_POSITIVE, NotPositive(SpringConstant), |k| {
        Tuning::android(k, 0.5, DT)
    });
    each(&NON_FINITE, NotFinite(DampingRatio), |z| {
        Tuning::android(1500.0, z, DT)
    });
    each(&NEGATIVE, Negative(DampingRatio), |z| {
        Tuning::android(1500.0, z, DT)
    });
    each(&NOT_POSITIVE, NotPositive(TimeStep), |dt| {
        Tuning::android(1500.0, 0.5, dt)
    });
    each(&NON_FINITE, NotFinite(TimeStep), |dt| {
        Tuning::android(1500.0, 0.5, dt)
    });
    each(&NOT_POSITIVE, NotPositive(SpringConstant), |k| {
        Oscillator::android(k, 0.5)
    });
    each(&NEGATIVE, Negative(DampingRatio), |z| {
        Oscillator::android(1500.0, z)
    });
}

#[test]
fn react_spring_rejects_bad_input() {
    each(&NON_FINITE, NotFinite(SpringConstant), |k| {
        Tuning::react_spring(k, 26.0, DT)
    });
    each(&NOT_POSITIVE, NotPositive(SpringConstant), |k| {
        Tuning::react_spring(k, 26.0, DT)
    });
    each(&NON_FINITE, NotFinite(DampingConstant), |c| {
        Tuning::react_spring(170.0, c, DT)
    });
    each(&NEGATIVE, Negative(DampingConstant), |c| {
        Tuning::react_spring(170.0, c, DT)
    });
    each(&NON_FINITE, NotFinite(TimeStep), |dt| {
        Tuning::react_spring(170.0, 26.0, dt)
    });
    each(&NOT_POSITIVE, NotPositive(TimeStep), |dt| {
        Tuning::react_spring(170.0, 26.0, dt)
    });
    each(&NOT_POSITIVE, NotPositive(SpringConstant), |k| {
        Oscillator::react_spring(k, 26.0)
    });
    each(&NEGATIVE, Negative(DampingConstant), |c| {
        Oscillator::react_spring(170.0, c)
    });
}

// ---------------------------------------------------------------------------
// Tuning::oscillator (the inverse map)
// ---------------------------------------------------------------------------

#[test]
fn oscillator_of_a_tuning_without_continuous_equivalent() {
    let no_equivalent = [
        Tuning::rigid(),
        // C_k = 0: a pole at z = 1 that is not a decaying mode.
        Tuning::from_coefficients(0.0, 0.5).unwrap(),
        // C_d = 1: a pole at z = 0.
        Tuning::from_coefficients(0.5, 1.0).unwrap(),
        // 1 < C_d < 2: det = 1 − C_d < 0, one pole is negative real.
        Tuning::from_coefficients_extended(0.5, 1.5).unwrap(),
        // trace = −1.45, det = 0.5: both poles negative real (trace² > 4·det).
        Tuning::from_coefficients_extended(2.95, 0.5).unwrap(),
    ];
    for t in no_equivalent {
        assert_eq!(t.oscillator(DT), Err(NoContinuousEquivalent), "{t:?}");
    }
    // The undamped edge of the square does have one: ζ = 0.
    let o = Tuning::from_coefficients(0.5, 0.0)
        .unwrap()
        .oscillator(DT)
        .unwrap();
    assert_eq!(o.damping_ratio(), 0.0);
}

#[test]
fn oscillator_rejects_bad_dt() {
    let t = Tuning::from_coefficients(0.04, 0.1).unwrap();
    each(&NON_FINITE, NotFinite(TimeStep), |dt| t.oscillator(dt));
    each(&NOT_POSITIVE, NotPositive(TimeStep), |dt| t.oscillator(dt));
}

// ---------------------------------------------------------------------------
// Rest thresholds and body weights
// ---------------------------------------------------------------------------

#[test]
fn rest_threshold_rejects_bad_input() {
    each(&NON_FINITE, NotFinite(Threshold), |p| {
        RestThreshold::new(p, 1.0)
    });
    each(&NON_FINITE, NotFinite(Threshold), |v| {
        RestThreshold::new(0.1, v)
    });
    each(&NOT_POSITIVE, NotPositive(Threshold), |p| {
        RestThreshold::new(p, 1.0)
    });
    each(&NOT_POSITIVE, NotPositive(Threshold), |v| {
        RestThreshold::new(0.1, v)
    });
    each(&NON_FINITE, NotFinite(Threshold), |c| {
        RestThreshold::from_min_visible_change(c)
    });
    each(&NOT_POSITIVE, NotPositive(Threshold), |c| {
        RestThreshold::from_min_visible_change(c)
    });
}

fn body_weights_reject_bad_input<S: Scalar>() {
    assert_eq!(
        BodyWeights::<S>::from_inverse_masses(0.0, 0.0),
        Err(NotPositive(Mass)),
        "{}",
        S::NAME
    );
    assert_eq!(
        BodyWeights::<S>::from_inverse_masses(-0.0, 0.0),
        Err(NotPositive(Mass))
    );
    each(&NEGATIVE, Negative(Mass), |a| {
        BodyWeights::<S>::from_inverse_masses(a, 1.0)
    });
    each(&NEGATIVE, Negative(Mass), |b| {
        BodyWeights::<S>::from_inverse_masses(1.0, b)
    });
    each(&NON_FINITE, NotFinite(Mass), |a| {
        BodyWeights::<S>::from_inverse_masses(a, 1.0)
    });
    each(&NON_FINITE, NotFinite(Mass), |b| {
        BodyWeights::<S>::from_inverse_masses(1.0, b)
    });
    // One pinned body is fine: it takes nothing, the other takes everything.
    let w = BodyWeights::<S>::from_inverse_masses(0.0, 2.0).unwrap();
    let one = S::from_f64(1.0);
    assert_eq!(w.split(one), (S::ZERO, one));
}

#[test]
fn body_weights_reject_bad_input_in_every_backend() {
    body_weights_reject_bad_input::<f32>();
    body_weights_reject_bad_input::<f64>();
    body_weights_reject_bad_input::<I16F16>();
    body_weights_reject_bad_input::<I32F32>();
}

// ---------------------------------------------------------------------------
// SpringValue
// ---------------------------------------------------------------------------

/// Everything observable about a value, to check that a failed setter changed nothing.
#[derive(Debug, PartialEq)]
struct Snapshot<S, const D: usize> {
    position: [S; D],
    target: [S; D],
    offset: [S; D],
    step_velocity: [S; D],
    velocity: [S; D],
    dt: f64,
    tuning: Tuning,
    rest_threshold: RestThreshold,
    rest_offset: S,
    at_rest: bool,
}

fn snapshot<S: Scalar, const D: usize>(v: &SpringValue<S, D>) -> Snapshot<S, D> {
    Snapshot {
        position: v.position(),
        target: v.target(),
        offset: v.offset(),
        step_velocity: v.step_velocity(),
        velocity: v.velocity(),
        dt: v.dt(),
        tuning: v.tuning(),
        rest_threshold: v.rest_threshold(),
        rest_offset: v.rest_offset(),
        at_rest: v.is_at_rest(),
    }
}

fn s<S: Scalar>(x: f64) -> S {
    S::from_f64(x)
}

/// A 3-D value in mid-flight (awake, with non-zero offset and velocity), so that "nothing
/// changed" after a failed setter is a real check.
fn in_flight<S: Scalar>(tuning: Tuning) -> SpringValue<S, 3> {
    let mut v = SpringValue::new([s(1.0), s(-2.0), s(3.0)], tuning, DT).unwrap();
    v.set_target([s(10.0), s(5.0), s(-4.0)]).unwrap();
    for _ in 0..3 {
        v.step();
    }
    assert!(!v.is_at_rest());
    assert!(v.step_velocity().iter().all(|u| *u != S::ZERO));
    v
}

/// The float backends, with the non-finite values `Scalar::from_f64` cannot produce (it
/// maps NaN to zero and clamps infinities to `±MAX`, by design).
trait Float: Scalar {
    const NAN: Self;
    const INF: Self;
    const MAX: Self;
}

impl Float for f32 {
    const NAN: Self = f32::NAN;
    const INF: Self = f32::INFINITY;
    const MAX: Self = f32::MAX;
}

impl Float for f64 {
    const NAN: Self = f64::NAN;
    const INF: Self = f64::INFINITY;
    const MAX: Self = f64::MAX;
}

/// Positions every float backend must reject, with the error they must give.
fn bad_float_positions<S: Float>() -> Vec<(S, Error)> {
    let beyond = s::<S>(2.0 * S::SAFE_MAGNITUDE);
    assert!(beyond.to_f64() > S::SAFE_MAGNITUDE);
    vec![
        (S::NAN, NotFinite(Position)),
        (S::INF, NotFinite(Position)),
        (S::INF.neg(), NotFinite(Position)),
        (beyond, OutOfRange(Position)),
        (beyond.neg(), OutOfRange(Position)),
        (S::MAX, OutOfRange(Position)),
        (S::MAX.neg(), OutOfRange(Position)),
    ]
}

fn value_new_rejects_bad_float_positions<S: Float>() {
    for (bad, expected) in bad_float_positions::<S>() {
        for k in 0..3 {
            let mut p = [s::<S>(1.0); 3];
            p[k] = bad;
            let got = SpringValue::new(p, sampled(), DT);
            assert!(
                matches!(&got, Err(e) if *e == expected),
                "{}: component {k} = {bad:?}: expected {expected:?}, got {:?}",
                S::NAME,
                got.map(|v| v.position())
            );
        }
    }
    // Exactly the safe magnitude is accepted.
    let edge = S::SAFE_MAGNITUDE;
    let v = SpringValue::<S, 2>::new([s(edge), s(-edge)], sampled(), DT).unwrap();
    assert_eq!(v.position(), [s(edge), s(-edge)]);
}

#[test]
fn value_new_rejects_non_finite_and_unsafe_float_positions() {
    value_new_rejects_bad_float_positions::<f32>();
    value_new_rejects_bad_float_positions::<f64>();
    assert_eq!(f32::SAFE_MAGNITUDE, 2f64.powi(100));
    assert_eq!(f64::SAFE_MAGNITUDE, 2f64.powi(1000));
}

#[test]
fn value_new_accepts_the_whole_fixed_point_range() {
    let v = SpringValue::<I16F16, 2>::new([I16F16::MIN, I16F16::MAX], sampled(), DT).unwrap();
    assert_eq!(v.position(), [I16F16::MIN, I16F16::MAX]);
    let v = SpringValue::<I32F32, 2>::new([I32F32::MIN, I32F32::MAX], sampled(), DT).unwrap();
    assert_eq!(v.position(), [I32F32::MIN, I32F32::MAX]);
}

fn value_new_rejects_bad_dt<S: Scalar>() {
    let p = [s::<S>(1.0)];
    each(&NON_FINITE, NotFinite(TimeStep), |dt| {
        SpringValue::<S, 1>::new(p, sampled(), dt).map(|v| v.position())
    });
    each(&NOT_POSITIVE, NotPositive(TimeStep), |dt| {
        SpringValue::<S, 1>::new(p, sampled(), dt).map(|v| v.position())
    });
}

#[test]
fn value_new_rejects_bad_dt_in_every_backend() {
    value_new_rejects_bad_dt::<f32>();
    value_new_rejects_bad_dt::<f64>();
    value_new_rejects_bad_dt::<I16F16>();
    value_new_rejects_bad_dt::<I32F32>();
}

fn value_set_target_and_position_reject_bad_floats<S: Float>() {
    for tuning in [sampled(), raw()] {
        for (bad, expected) in bad_float_positions::<S>() {
            for k in 0..3 {
                let mut v = in_flight::<S>(tuning);
                let before = snapshot(&v);
                let mut p = [s::<S>(7.0); 3];
                p[k] = bad;
                assert_eq!(v.set_target(p), Err(expected), "{} {bad:?}", S::NAME);
                assert_eq!(snapshot(&v), before, "set_target changed the value");
                assert_eq!(v.set_position(p), Err(expected), "{} {bad:?}", S::NAME);
                assert_eq!(snapshot(&v), before, "set_position changed the value");
            }
        }
    }
}

#[test]
fn value_set_target_and_set_position_reject_bad_floats_and_change_nothing() {
    value_set_target_and_position_reject_bad_floats::<f32>();
    value_set_target_and_position_reject_bad_floats::<f64>();
}

fn value_fling_rejects_bad_floats<S: Float>() {
    for tuning in [sampled(), raw()] {
        for (bad, expected) in bad_float_positions::<S>() {
            let expected = match expected {
                NotFinite(_) => NotFinite(Velocity),
                _ => OutOfRange(Velocity),
            };
            for k in 0..3 {
                let mut v = in_flight::<S>(tuning);
                let before = snapshot(&v);
                let mut vel = [s::<S>(7.0); 3];
                vel[k] = bad;
                assert_eq!(v.fling(vel), Err(expected), "{} {bad:?}", S::NAME);
                assert_eq!(snapshot(&v), before, "fling changed the value");
            }
        }
    }
}

#[test]
fn value_fling_rejects_bad_float_velocities_and_changes_nothing() {
    value_fling_rejects_bad_floats::<f32>();
    value_fling_rejects_bad_floats::<f64>();
}

#[test]
fn fling_whose_step_velocity_leaves_the_range_is_rejected() {
    // Raw coefficients: u₀ = v·dt exactly (documented). Each velocity is valid on its
    // own, but u₀ is beyond the backend's range.
    let t = Tuning::rigid();

    // f32: v = 2⁹⁹ ≤ 2¹⁰⁰, dt = 4 → u₀ = 2¹⁰¹ > SAFE_MAGNITUDE.
    let mut v = SpringValue::<f32, 1>::new([0.0], t, 4.0).unwrap();
    let before = snapshot(&v);
    assert_eq!(v.fling([2f32.powi(99)]), Err(OutOfRange(Velocity)));
    assert_eq!(snapshot(&v), before);
    // ... while 2⁹⁸·4 = 2¹⁰⁰ is still accepted.
    v.fling([2f32.powi(98)]).unwrap();
    assert_eq!(v.step_velocity(), [2f32.powi(100)]);

    // I16F16: v = 30000, dt = 2 → u₀ = 60000 does not fit in ±32768: an error, not a
    // silent saturation to 32767.99998.
    let mut v = SpringValue::<I16F16, 1>::new([I16F16::ZERO], t, 2.0).unwrap();
    let before = snapshot(&v);
    assert_eq!(
        v.fling([I16F16::from_num(30000)]),
        Err(OutOfRange(Velocity))
    );
    assert_eq!(snapshot(&v), before);
    // In the middle of a 3-D fling: the first components were fine, nothing is kept.
    let mut v = SpringValue::<I16F16, 3>::new([I16F16::ZERO; 3], t, 2.0).unwrap();
    let before = snapshot(&v);
    let vel = [1.0, 2.0, 30000.0].map(I16F16::from_num);
    assert_eq!(v.fling(vel), Err(OutOfRange(Velocity)));
    assert_eq!(snapshot(&v), before);
    // 16000·2 = 32000 fits.
    v.fling([16000.0, 0.0, -16000.0].map(I16F16::from_num))
        .unwrap();
    assert_eq!(
        v.step_velocity(),
        [32000.0, 0.0, -32000.0].map(I16F16::from_num)
    );
}

#[test]
fn set_tuning_whose_step_velocity_leaves_the_range_is_rejected() {
    // I16F16 at dt = 1 s with raw coefficients: fling 20000 units/s gives u = 20000.
    let mut v = SpringValue::<I16F16, 1>::new([I16F16::ZERO], raw(), 1.0).unwrap();
    v.fling([I16F16::from_num(20000)]).unwrap();
    assert_eq!(v.step_velocity(), [I16F16::from_num(20000)]);
    let before = snapshot(&v);
    // A critically damped oscillator with ω·dt = 1: at offset 0, u = Q·v with
    // Q = e^{ωdt}·dt = e ≈ 2.718 (x(t) = v·t·e^{−ωt}, so x(−dt) = −v·dt·e^{ωdt}),
    // and 20000·e ≈ 54366 does not fit.
    let critical = Tuning::from_frequency(1.0 / std::f64::consts::TAU, 1.0, 1.0).unwrap();
    assert_eq!(v.set_tuning(critical), Err(OutOfRange(Velocity)));
    assert_eq!(snapshot(&v), before);
    // Half the velocity fits (≈ 27183), and then the velocity is kept.
    let mut w = SpringValue::<I16F16, 1>::new([I16F16::ZERO], raw(), 1.0).unwrap();
    w.fling([I16F16::from_num(10000)]).unwrap();
    w.set_tuning(critical).unwrap();
    let u = w.step_velocity()[0].to_f64();
    assert!((u - 10000.0 * std::f64::consts::E).abs() < 1e-3, "{u}");
}

fn value_set_dt_rejects_bad_dt<S: Scalar>() {
    for tuning in [sampled(), raw()] {
        let mut v = in_flight::<S>(tuning);
        let before = snapshot(&v);
        for dt in NON_FINITE {
            assert_eq!(v.set_dt(dt), Err(NotFinite(TimeStep)), "{}", S::NAME);
        }
        for dt in NOT_POSITIVE {
            assert_eq!(v.set_dt(dt), Err(NotPositive(TimeStep)), "{}", S::NAME);
        }
        assert_eq!(snapshot(&v), before);
    }
}

#[test]
fn value_set_dt_rejects_bad_dt_and_changes_nothing() {
    value_set_dt_rejects_bad_dt::<f32>();
    value_set_dt_rejects_bad_dt::<f64>();
    value_set_dt_rejects_bad_dt::<I16F16>();
    value_set_dt_rejects_bad_dt::<I32F32>();
}

#[test]
fn set_dt_onto_an_aliased_rate_is_rejected() {
    // Undamped 30 Hz sampled at 240 Hz is fine; at 60 Hz it sits exactly on half the
    // sample rate.
    let t = Tuning::from_frequency(30.0, 0.0, 1.0 / 240.0).unwrap();
    let mut v = SpringValue::<f64, 1>::new([0.0], t, 1.0 / 240.0).unwrap();
    v.set_target([1.0]).unwrap();
    v.step();
    let before = snapshot(&v);
    assert_eq!(v.set_dt(1.0 / 60.0), Err(Aliased));
    assert_eq!(snapshot(&v), before);
}

#[test]
fn set_dt_whose_step_velocity_leaves_the_range_is_rejected() {
    // 0.1 Hz, ζ = 0.5 sampled at 60 Hz, flung at 20000 units/s: u ≈ 333 fits. At dt = 2 s,
    // u = Q·v with Q = e^{ζωdt}·sin(ω_d·dt)/ω_d ≈ 3.05 (see Oscillator::start_weights),
    // and 61 000 does not.
    let t = Tuning::from_frequency(0.1, 0.5, DT).unwrap();
    let mut v = SpringValue::<I16F16, 1>::new([I16F16::ZERO], t, DT).unwrap();
    v.fling([I16F16::from_num(20000)]).unwrap();
    let before = snapshot(&v);
    assert_eq!(v.set_dt(2.0), Err(OutOfRange(Velocity)));
    assert_eq!(snapshot(&v), before);
}

// ---------------------------------------------------------------------------
// SpringBatch
// ---------------------------------------------------------------------------

type Member<S, const D: usize> = ([S; D], [S; D], [S; D], bool);

/// Everything observable about a batch.
fn batch_snapshot<S: Scalar, const N: usize, const D: usize>(
    b: &SpringBatch<S, N, D>,
) -> (usize, usize, Vec<Member<S, D>>) {
    let members = (0..b.len())
        .map(|i| {
            (
                b.position(i).unwrap(),
                b.target(i).unwrap(),
                b.step_velocity(i).unwrap(),
                b.is_at_rest(i).unwrap(),
            )
        })
        .collect();
    (b.len(), b.awake(), members)
}

fn batch_new_rejects_bad_dt<S: Scalar>() {
    each(&NON_FINITE, NotFinite(TimeStep), |dt| {
        SpringBatch::<S, 4, 2>::new(dt).map(|b| b.len())
    });
    each(&NOT_POSITIVE, NotPositive(TimeStep), |dt| {
        SpringBatch::<S, 4, 2>::new(dt).map(|b| b.len())
    });
}

#[test]
fn batch_new_rejects_bad_dt_in_every_backend() {
    batch_new_rejects_bad_dt::<f32>();
    batch_new_rejects_bad_dt::<f64>();
    batch_new_rejects_bad_dt::<I16F16>();
    batch_new_rejects_bad_dt::<I32F32>();
}

fn batch_push_beyond_capacity<S: Scalar>() {
    let mut b = SpringBatch::<S, 3>::new(DT).unwrap();
    for k in 0..3 {
        assert_eq!(b.push([s(k as f64)], sampled()), Ok(k));
    }
    b.set_target(1, [s(50.0)]).unwrap();
    b.step();
    let before = batch_snapshot(&b);
    assert_eq!(
        b.push([s(9.0)], sampled()),
        Err(CapacityFull),
        "{}",
        S::NAME
    );
    assert_eq!(
        b.push_with_threshold([s(9.0)], raw(), RestThreshold::PIXELS),
        Err(CapacityFull)
    );
    assert_eq!(b.len(), 3);
    assert_eq!(batch_snapshot(&b), before);
    // Still full after stepping: capacity is not freed by values coming to rest.
    for _ in 0..1000 {
        b.step();
    }
    assert_eq!(b.awake(), 0);
    assert_eq!(b.push([s(9.0)], sampled()), Err(CapacityFull));
    assert_eq!(b.len(), 3);
}

#[test]
fn batch_push_beyond_capacity_adds_nothing_in_every_backend() {
    batch_push_beyond_capacity::<f32>();
    batch_push_beyond_capacity::<f64>();
    batch_push_beyond_capacity::<I16F16>();
    batch_push_beyond_capacity::<I32F32>();
}

#[test]
fn batch_zero_capacity_is_always_full() {
    let mut b = SpringBatch::<f32, 0>::new(DT).unwrap();
    assert_eq!(b.push([0.0], raw()), Err(CapacityFull));
    assert!(b.is_empty());
}

fn batch_push_rejects_bad_floats<S: Float>() {
    let mut b = SpringBatch::<S, 4, 2>::new(DT).unwrap();
    b.push([s(1.0), s(2.0)], sampled()).unwrap();
    b.set_target(0, [s(3.0), s(4.0)]).unwrap();
    let before = batch_snapshot(&b);
    for (bad, expected) in bad_float_positions::<S>() {
        assert_eq!(
            b.push([s(1.0), bad], sampled()),
            Err(expected),
            "{}",
            S::NAME
        );
        assert_eq!(
            b.push_with_threshold([bad, s(1.0)], raw(), RestThreshold::PIXELS),
            Err(expected)
        );
        assert_eq!(batch_snapshot(&b), before);
    }
}

#[test]
fn batch_push_rejects_bad_float_positions_and_adds_nothing() {
    batch_push_rejects_bad_floats::<f32>();
    batch_push_rejects_bad_floats::<f64>();
}

/// Every indexed method of `b` rejects `index` and leaves the batch as it was.
fn rejects_index<S: Scalar>(b: &mut SpringBatch<S, 4>, index: usize) {
    let index_error = Err(OutOfRange(Index));
    let before = batch_snapshot(b);
    assert_eq!(b.set_target(index, [s(5.0)]), index_error, "{}", S::NAME);
    assert_eq!(b.fling(index, [s(5.0)]), index_error);
    assert_eq!(b.set_tuning(index, raw()), index_error);
    assert_eq!(b.position(index), index_error.map(|()| [S::ZERO]));
    assert_eq!(b.target(index), index_error.map(|()| [S::ZERO]));
    assert_eq!(b.step_velocity(index), index_error.map(|()| [S::ZERO]));
    assert_eq!(b.is_at_rest(index), index_error.map(|()| true));
    assert_eq!(batch_snapshot(b), before);
}

fn batch_unknown_index<S: Scalar>() {
    let mut b = SpringBatch::<S, 4>::new(DT).unwrap();
    // An empty batch knows no index at all.
    for index in [0, 1, 4, usize::MAX] {
        rejects_index(&mut b, index);
    }
    b.push([s(1.0)], sampled()).unwrap();
    b.push([s(2.0)], raw()).unwrap();
    b.set_target(0, [s(20.0)]).unwrap();
    b.step();
    // Beyond the length (also below the capacity 4), and far beyond.
    for index in [2, 3, 4, usize::MAX] {
        rejects_index(&mut b, index);
    }
}

#[test]
fn batch_unknown_index_is_rejected_by_every_indexed_method() {
    batch_unknown_index::<f32>();
    batch_unknown_index::<f64>();
    batch_unknown_index::<I16F16>();
    batch_unknown_index::<I32F32>();
}

fn batch_setters_reject_bad_floats<S: Float>() {
    let mut b = SpringBatch::<S, 4, 2>::new(DT).unwrap();
    b.push([s(1.0), s(2.0)], sampled()).unwrap();
    b.push([s(-1.0), s(0.5)], raw()).unwrap();
    b.set_target(0, [s(30.0), s(-4.0)]).unwrap();
    b.set_target(1, [s(3.0), s(4.0)]).unwrap();
    b.step();
    let before = batch_snapshot(&b);
    for (bad, expected) in bad_float_positions::<S>() {
        for i in 0..2 {
            assert_eq!(b.set_target(i, [s(1.0), bad]), Err(expected), "{}", S::NAME);
            let velocity_error = match expected {
                NotFinite(_) => NotFinite(Velocity),
                _ => OutOfRange(Velocity),
            };
            assert_eq!(b.fling(i, [bad, s(1.0)]), Err(velocity_error));
            assert_eq!(batch_snapshot(&b), before);
        }
    }
}

#[test]
fn batch_setters_reject_bad_float_input_and_change_nothing() {
    batch_setters_reject_bad_floats::<f32>();
    batch_setters_reject_bad_floats::<f64>();
}

#[test]
fn batch_fling_and_set_tuning_whose_step_velocity_leaves_the_range_are_rejected() {
    // As for SpringValue, in I16F16. At dt = 2 s with raw coefficients, u₀ = v·dt:
    // 20000 units/s needs u₀ = 40000, which does not fit in ±32768.
    let mut b = SpringBatch::<I16F16, 2>::new(2.0).unwrap();
    b.push([I16F16::ZERO], raw()).unwrap();
    b.push([I16F16::from_num(5)], raw()).unwrap();
    b.set_target(1, [I16F16::from_num(-5)]).unwrap();
    b.step();
    let before = batch_snapshot(&b);
    assert_eq!(
        b.fling(0, [I16F16::from_num(20000)]),
        Err(OutOfRange(Velocity))
    );
    assert_eq!(batch_snapshot(&b), before);
    b.fling(0, [I16F16::from_num(16000)]).unwrap();
    assert_eq!(b.step_velocity(0), Ok([I16F16::from_num(32000)]));

    // At dt = 1 s: set_tuning to the critically damped ω·dt = 1 oscillator needs
    // u = e·20000 ≈ 54366 (see set_tuning_whose_step_velocity_leaves_the_range_is_rejected).
    let mut b = SpringBatch::<I16F16, 2>::new(1.0).unwrap();
    b.push([I16F16::ZERO], raw()).unwrap();
    b.push([I16F16::ZERO], raw()).unwrap();
    b.fling(0, [I16F16::from_num(20000)]).unwrap();
    let before = batch_snapshot(&b);
    let critical = Tuning::from_frequency(1.0 / std::f64::consts::TAU, 1.0, 1.0).unwrap();
    assert_eq!(b.set_tuning(0, critical), Err(OutOfRange(Velocity)));
    assert_eq!(batch_snapshot(&b), before);
    // The resting member is retuned without trouble.
    b.set_tuning(1, critical).unwrap();
}
