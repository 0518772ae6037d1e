//! Bad input to set-up: tunings, oscillators, presets, rest thresholds, body weights, the
//! network limit and the knob's configuration, and what the errors say. The rows of
//! `docs/bad-input.md`, one by one (values and batches are in `tests/value_bad_input.rs`,
//! scenes in `tests/scene_bad_input.rs`).
//!
//! Set-up either succeeds or returns the typed `Error` of the row, which names the
//! parameter, the value and the bound it broke.

use stiffspring::kernel::BodyWeights;
use stiffspring::knob::{KnobError, Limit, MAX_MAGNETS, Zone};
use stiffspring::presets::{android, react_spring, swiftui};
use stiffspring::scene::{Stepper, network_limit};
use stiffspring::{
    Bound, Error, I16F16, I32F32, Knob, KnobConfig, Oscillator, Parameter, RestThreshold, Scalar,
    SpringValue, Tuning,
};

const NAN: f64 = f64::NAN;
const INF: f64 = f64::INFINITY;
const DT: f64 = 1.0 / 60.0;

use Parameter as P;

fn not_finite(parameter: Parameter) -> Error {
    Error::NotFinite { parameter }
}

fn out(parameter: Parameter, value: f64, bound: Bound) -> Error {
    Error::OutOfRange {
        parameter,
        value,
        bound,
    }
}

/// The same error for NaN and both infinities of one argument.
#[track_caller]
fn non_finite<T: std::fmt::Debug>(parameter: Parameter, call: impl Fn(f64) -> Result<T, Error>) {
    for v in [NAN, INF, -INF] {
        assert_eq!(call(v).map(|_| ()), Err(not_finite(parameter)), "{v}");
    }
}

const UNIT: Bound = Bound::Within { min: 0.0, max: 1.0 };

// ---------------------------------------------------------------------------
// Tunings
// ---------------------------------------------------------------------------

#[test]
fn tunings_refuse_bad_coefficients_and_time_steps() {
    // dt, in every constructor.
    non_finite(P::TimeStep, Tuning::rigid);
    non_finite(P::TimeStep, |dt| Tuning::from_coefficients(0.1, 0.1, dt));
    non_finite(P::TimeStep, |dt| Tuning::from_frequency(2.0, 0.5, dt));
    for dt in [0.0, -0.0, -1e-3] {
        let e = Err(out(P::TimeStep, dt, Bound::Positive));
        assert_eq!(Tuning::rigid(dt), e);
        assert_eq!(Tuning::from_coefficients(0.1, 0.1, dt), e);
        assert_eq!(Tuning::from_coefficients_extended(1.5, 0.5, dt), e);
        assert_eq!(Tuning::from_frequency(2.0, 0.5, dt), e);
        assert_eq!(Tuning::from_physical(4.0, 1.0, 1.0, dt), e);
        assert_eq!(Oscillator::new(2.0, 0.5).expect("valid").tuning(dt), e);
        assert_eq!(Tuning::rigid(0.01).expect("dt").with_dt(dt), e);
    }
    // Raw coefficients: the article's square, less its origin.
    non_finite(P::Stiffness, |k| Tuning::from_coefficients(k, 0.1, DT));
    non_finite(P::Damping, |d| Tuning::from_coefficients(0.1, d, DT));
    for v in [-0.1, 1.0 + 1e-12, 2.0] {
        assert_eq!(
            Tuning::from_coefficients(v, 0.5, DT),
            Err(out(P::Stiffness, v, UNIT))
        );
        assert_eq!(
            Tuning::from_coefficients(0.5, v, DT),
            Err(out(P::Damping, v, UNIT))
        );
    }
    assert_eq!(
        Tuning::from_coefficients(0.0, 0.0, DT),
        Err(out(P::Stiffness, 0.0, Bound::Positive))
    );
    for (k, d) in [(0.0, 1.0), (1.0, 0.0), (1.0, 1.0), (1e-9, 0.0)] {
        assert!(Tuning::from_coefficients(k, d, DT).is_ok(), "({k}, {d})");
    }
    // Beyond the square: Jury's open region.
    non_finite(P::Stiffness, |k| {
        Tuning::from_coefficients_extended(k, 0.1, DT)
    });
    non_finite(P::Damping, |d| {
        Tuning::from_coefficients_extended(0.1, d, DT)
    });
    let ext = Tuning::from_coefficients_extended;
    assert_eq!(
        ext(-0.1, 0.5, DT),
        Err(out(P::Stiffness, -0.1, Bound::NonNegative))
    );
    assert_eq!(
        ext(0.5, -0.1, DT),
        Err(out(P::Damping, -0.1, Bound::NonNegative))
    );
    assert_eq!(
        ext(0.5, 2.0, DT),
        Err(out(P::Damping, 2.0, Bound::Below { max: 2.0 }))
    );
    assert_eq!(
        ext(3.0, 0.5, DT),
        Err(out(P::Stiffness, 3.0, Bound::Below { max: 3.0 }))
    );
    assert_eq!(
        ext(1.5, 0.0, DT),
        Err(out(P::Stiffness, 1.5, Bound::Below { max: 4.0 }))
    );
    assert_eq!(
        ext(0.0, 1.5, DT),
        Err(out(P::Stiffness, 0.0, Bound::Below { max: 1.0 }))
    );
    assert!(ext(2.999, 0.5, DT).is_ok() && ext(1.5, 0.5, DT).is_ok());
}

#[test]
fn oscillators_refuse_bad_frequencies_damping_ratios_and_aliased_rates() {
    non_finite(P::Frequency, |f| Tuning::from_frequency(f, 0.5, DT));
    non_finite(P::Frequency, |f| Oscillator::new(f, 0.5));
    non_finite(P::Frequency, |w| Oscillator::from_angular_frequency(w, 0.5));
    non_finite(P::DampingRatio, |z| Tuning::from_frequency(2.0, z, DT));
    for f in [0.0, -2.0] {
        assert_eq!(
            Oscillator::new(f, 0.5),
            Err(out(P::Frequency, f, Bound::Positive))
        );
    }
    assert_eq!(
        Oscillator::new(2.0, -0.1),
        Err(out(P::DampingRatio, -0.1, Bound::NonNegative))
    );
    // An undamped oscillator at a multiple of half the sample rate: a double pole at ±1.
    for (f, fdt) in [(30.0, 0.5), (60.0, 1.0), (90.0, 1.5)] {
        let t = Tuning::from_frequency(f, 0.0, DT / 4.0).expect("below the alias");
        for got in [Tuning::from_frequency(f, 0.0, DT), t.with_dt(DT)] {
            match got {
                Err(Error::Aliased { frequency_times_dt }) => {
                    assert!(
                        (frequency_times_dt - fdt).abs() < 1e-12,
                        "{frequency_times_dt}"
                    )
                }
                other => panic!("{f} Hz: {other:?}"),
            }
        }
    }
    assert!(Tuning::from_frequency(29.0, 0.0, DT).is_ok());
    assert!(Tuning::from_frequency(30.0, 1e-3, DT).is_ok()); // damped: no alias
    // ω·dt beyond f64, and a C_k below f64's range.
    let fast = Oscillator::from_angular_frequency(1e308, 0.5).expect("finite");
    let below = Bound::Below {
        max: f64::MAX / std::f64::consts::TAU / 10.0,
    };
    assert_eq!(
        fast.tuning(10.0),
        Err(out(P::Frequency, fast.frequency(), below))
    );
    let slow = Oscillator::new(1e-200, 0.5).expect("positive");
    assert_eq!(
        slow.tuning(1e-200),
        Err(out(P::Frequency, 1e-200, Bound::Positive))
    );
    // Documented: an astronomically overdamped spring is a valid (very slow) tuning.
    assert!(Tuning::from_frequency(1.0, 1e200, DT).is_ok_and(|t| t.stiffness() > 0.0));
}

#[test]
fn physical_constants_and_presets_refuse_bad_input() {
    non_finite(P::SpringConstant, |k| {
        Oscillator::from_physical(k, 1.0, 1.0)
    });
    non_finite(P::DampingConstant, |c| {
        Oscillator::from_physical(4.0, c, 1.0)
    });
    non_finite(P::Mass, |m| Oscillator::from_physical(4.0, 1.0, m));
    let phys = Oscillator::from_physical;
    assert_eq!(
        phys(0.0, 1.0, 1.0),
        Err(out(P::SpringConstant, 0.0, Bound::Positive))
    );
    assert_eq!(
        phys(4.0, -1.0, 1.0),
        Err(out(P::DampingConstant, -1.0, Bound::NonNegative))
    );
    assert_eq!(
        phys(4.0, 1.0, -2.0),
        Err(out(P::Mass, -2.0, Bound::Positive))
    );
    // √(k/m) that underflows or overflows f64.
    assert_eq!(
        phys(1e-300, 0.0, 1e300),
        Err(out(P::SpringConstant, 1e-300, Bound::Positive))
    );
    assert_eq!(
        phys(1e300, 0.0, 1e-300),
        Err(out(P::SpringConstant, 1e300, Bound::Positive))
    );
    // ζ = c/(2·m·ω) beyond f64.
    assert_eq!(phys(1e-300, 1e300, 1.0), Err(not_finite(P::DampingRatio)));
    assert_eq!(
        Tuning::from_physical(0.0, 1.0, 1.0, DT),
        Err(out(P::SpringConstant, 0.0, Bound::Positive))
    );

    // SwiftUI: duration > 0, bounce in (−1, 1]; response > 0, damping fraction ≥ 0.
    non_finite(P::Duration, |d| swiftui::spring(d, 0.3));
    non_finite(P::Bounce, |b| swiftui::spring(0.5, b));
    assert_eq!(
        swiftui::spring(0.0, 0.3),
        Err(out(P::Duration, 0.0, Bound::Positive))
    );
    let bounce = Bound::Within {
        min: -1.0 + f64::EPSILON,
        max: 1.0,
    };
    for b in [-1.0, 1.0 + 1e-9, -2.0] {
        assert_eq!(swiftui::spring(0.5, b), Err(out(P::Bounce, b, bounce)));
    }
    assert!(swiftui::spring(0.5, 1.0).is_ok() && swiftui::spring(0.5, -0.99).is_ok());
    non_finite(P::Duration, |r| swiftui::response(r, 0.86));
    assert_eq!(
        swiftui::response(-0.1, 0.86),
        Err(out(P::Duration, -0.1, Bound::Positive))
    );
    assert_eq!(
        swiftui::response(0.15, -0.5),
        Err(out(P::DampingRatio, -0.5, Bound::NonNegative))
    );
    // Android: stiffness > 0, damping ratio ≥ 0.
    non_finite(P::SpringConstant, |k| android::spring_force(k, 0.5));
    non_finite(P::DampingRatio, |z| android::spring_force(1500.0, z));
    assert_eq!(
        android::spring_force(0.0, 0.5),
        Err(out(P::SpringConstant, 0.0, Bound::Positive))
    );
    assert_eq!(
        android::spring_force(1500.0, -0.5),
        Err(out(P::DampingRatio, -0.5, Bound::NonNegative))
    );
    // react-spring: tension and friction are k and c with mass 1.
    assert_eq!(react_spring::config(-170.0, 26.0), phys(-170.0, 26.0, 1.0));
    assert_eq!(react_spring::config(170.0, -26.0), phys(170.0, -26.0, 1.0));
    non_finite(P::SpringConstant, |k| react_spring::config(k, 26.0));
}

#[test]
fn the_inverse_map_refuses_a_tuning_without_a_continuous_oscillator() {
    for t in [
        Tuning::rigid(DT),
        Tuning::from_coefficients(0.0, 0.5, DT),
        Tuning::from_coefficients(0.5, 1.0, DT),
        Tuning::from_coefficients_extended(1.5, 1.2, DT),
    ] {
        let t = t.expect("valid");
        assert_eq!(
            t.equivalent_oscillator(),
            Err(Error::NoContinuousEquivalent),
            "{t:?}"
        );
    }
    let t = Tuning::from_coefficients(0.04, 0.1, DT).expect("valid");
    assert!(t.equivalent_oscillator().is_ok());
}

#[test]
fn rest_thresholds_body_weights_and_the_network_limit() {
    non_finite(P::Threshold, |p| RestThreshold::new(p, 1.0));
    non_finite(P::Threshold, |v| RestThreshold::new(1.0, v));
    non_finite(P::Threshold, RestThreshold::from_min_visible_change);
    for v in [0.0, -1.0] {
        let e = Err(out(P::Threshold, v, Bound::Positive));
        assert_eq!(RestThreshold::new(v, 1.0), e);
        assert_eq!(RestThreshold::new(1.0, v), e);
        assert_eq!(RestThreshold::from_min_visible_change(v), e);
    }
    fn weights<S: Scalar>() {
        let w = BodyWeights::<S>::from_inverse_masses;
        for v in [NAN, INF] {
            assert_eq!(w(v, 1.0), Err(not_finite(P::Mass)), "{}", S::NAME);
            assert_eq!(w(1.0, v), Err(not_finite(P::Mass)));
        }
        assert_eq!(w(-1.0, 1.0), Err(out(P::Mass, -1.0, Bound::NonNegative)));
        assert_eq!(w(0.0, 0.0), Err(out(P::Mass, 0.0, Bound::Positive)));
        assert!(w(0.0, 1.0).is_ok() && w(1e-300, 1e300).is_ok());
    }
    weights::<f32>();
    weights::<f64>();
    weights::<I16F16>();
    weights::<I32F32>();
    // The network limit never fails: 1 for a spring alone, decreasing, never negative.
    for stepper in [Stepper::GaussSeidel, Stepper::Jacobi] {
        assert_eq!(
            (network_limit(0, stepper), network_limit(1, stepper)),
            (1.0, 1.0)
        );
        let mut last = 1.0;
        for n in [2, 3, 8, 1000, usize::MAX] {
            let l = network_limit(n, stepper);
            assert!((0.0..=last).contains(&l), "{stepper:?} {n}: {l}");
            last = l;
        }
    }
}

// ---------------------------------------------------------------------------
// The knob's configuration
// ---------------------------------------------------------------------------

/// 1 kHz, 10⁻⁵ kg·m², 50 mN·m, a 14-bit encoder.
fn knob() -> KnobConfig {
    KnobConfig::new(1_000.0, 1e-5, 0.05, 16_384)
}

/// `Knob::new`'s error, checked field by field; `value` and `limit` NaN mean "not
/// compared" (a NaN argument, or a limit of the loop design).
#[track_caller]
fn knob_refuses<S: Scalar>(
    config: KnobConfig,
    parameter: Parameter,
    bound: Limit,
    value: f64,
    limit: f64,
) {
    let e: KnobError = Knob::<S>::new(&config, S::ZERO).expect_err("refused");
    // (A full list of magnets is `CapacityFull`, which names no parameter.)
    let named = (bound != Limit::Capacity).then_some(parameter);
    assert_eq!((e.error.parameter(), e.bound), (named, bound), "{e:?}");
    if !value.is_nan() {
        assert_eq!(e.value, value, "{e:?}");
    }
    if !limit.is_nan() {
        assert!(
            (e.limit - limit).abs() <= 1e-12 * limit.abs(),
            "{e:?}: limit {limit}"
        );
    }
    // The crate-wide error says the same: not finite, full, or out of its range.
    let kind_agrees = match bound {
        Limit::Finite => e.error == not_finite(parameter),
        Limit::Capacity => matches!(e.error, Error::CapacityFull { .. }),
        Limit::NeedsEndstops => e.error == Error::NeedsEndstops,
        // One count's torque: the crate-wide error names the encoder resolution, below
        // the resolution that would pass.
        Limit::CountTorque(_) => matches!(
            e.error,
            Error::OutOfRange { value: v, bound, .. } if !bound.contains(v)
        ),
        _ => matches!(e.error, Error::OutOfRange { value: v, .. } if v == e.value),
    };
    assert!(kind_agrees, "{e:?}");
}

#[test]
fn knob_configuration_errors_name_the_parameter_value_and_limit() {
    let count = std::f64::consts::TAU / 16_384.0;
    let hysteresis = KnobConfig::DEFAULT_HYSTERESIS_COUNTS * count;
    let k = knob_refuses::<f32>;
    // The loop, the rotor, the motor, the encoder.
    k(
        KnobConfig::new(NAN, 1e-5, 0.05, 16_384),
        P::LoopRate,
        Limit::Finite,
        NAN,
        NAN,
    );
    k(
        KnobConfig::new(0.0, 1e-5, 0.05, 16_384),
        P::LoopRate,
        Limit::Positive,
        0.0,
        0.0,
    );
    k(
        KnobConfig::new(1e3, -1.0, 0.05, 16_384),
        P::Inertia,
        Limit::Positive,
        -1.0,
        0.0,
    );
    k(
        KnobConfig::new(1e3, 1e-5, INF, 16_384),
        P::TorqueLimit,
        Limit::Finite,
        NAN,
        NAN,
    );
    k(
        KnobConfig::new(1e3, 1e-5, 0.05, 0),
        P::CountsPerTurn,
        Limit::Positive,
        0.0,
        0.0,
    );
    let fine = KnobConfig::new(1e3, 1e-5, 0.05, 1_000_000);
    let most = (std::f64::consts::TAU / I16F16::RESOLUTION).floor();
    knob_refuses::<I16F16>(fine, P::CountsPerTurn, Limit::AtMost, 1e6, most);
    assert!(Knob::<f32>::new(&fine, 0.0).is_ok());
    // Damping.
    k(
        knob().damping_ratio(NAN),
        P::DampingRatio,
        Limit::Finite,
        NAN,
        NAN,
    );
    k(
        knob().damping_ratio(0.1),
        P::DampingRatio,
        Limit::AtLeast,
        0.1,
        0.2,
    );
    k(
        knob().damping_ratio(3.0),
        P::DampingRatio,
        Limit::AtMost,
        3.0,
        2.0,
    );
    k(
        knob().damping(-1.0),
        P::DampingConstant,
        Limit::NotNegative,
        -1.0,
        0.0,
    );
    // Endstops.
    k(
        knob().endstops(NAN, 1.0),
        P::Endstops,
        Limit::Finite,
        NAN,
        NAN,
    );
    k(
        knob().endstops(1.0, 1.0),
        P::Endstops,
        Limit::Below,
        1.0,
        1.0,
    );
    let far = knob().endstops(0.0, 20_000.0);
    knob_refuses::<I16F16>(
        far,
        P::Endstops,
        Limit::BackendRange,
        20_000.0,
        <I16F16 as Scalar>::MAX / 2.0,
    );
    // Detents.
    k(
        knob().snap_point(NAN),
        P::SnapPoint,
        Limit::Finite,
        NAN,
        NAN,
    );
    k(
        knob().snap_point(0.4),
        P::SnapPoint,
        Limit::AtLeast,
        0.4,
        0.5,
    );
    k(knob().snap_point(1.0), P::SnapPoint, Limit::Below, 1.0, 1.0);
    k(
        knob().detent_count(5),
        P::DetentCount,
        Limit::NeedsEndstops,
        5.0,
        NAN,
    );
    k(
        knob().endstops(0.0, 1.0).detent_count(1),
        P::DetentCount,
        Limit::AtLeast,
        1.0,
        2.0,
    );
    k(
        knob().detent_width(0.0),
        P::DetentWidth,
        Limit::Positive,
        0.0,
        0.0,
    );
    k(
        knob().detent_width(1e-3),
        P::DetentWidth,
        Limit::AtLeast,
        1e-3,
        4.0 * count,
    );
    let narrow = knob().detent_width(0.1).hysteresis(-1e-3);
    k(narrow, P::Hysteresis, Limit::NotNegative, -1e-3, 0.0);
    k(
        knob().detent_width(0.1).hysteresis(0.05),
        P::Hysteresis,
        Limit::Below,
        0.05,
        0.05,
    );
    // Layer stiffnesses, the return spring's centre.
    k(
        knob().detent_width(0.1).detent_stiffness(-1.0),
        P::DetentStiffness,
        Limit::NotNegative,
        -1.0,
        0.0,
    );
    k(
        knob().return_to_centre(0.0, -1.0),
        P::ReturnStiffness,
        Limit::NotNegative,
        -1.0,
        0.0,
    );
    k(
        knob().return_to_centre(NAN, 0.01),
        P::ReturnCentre,
        Limit::Finite,
        NAN,
        NAN,
    );
    // Magnets: how many, where, how wide.
    let nine: Vec<f64> = (0..=MAX_MAGNETS).map(|i| i as f64).collect();
    let many = MAX_MAGNETS as f64;
    k(
        knob().magnets(&nine),
        P::Magnets,
        Limit::Capacity,
        many + 1.0,
        many,
    );
    k(knob().magnets(&[NAN]), P::Magnets, Limit::Finite, NAN, NAN);
    k(
        knob().endstops(0.0, 1.0).magnets(&[2.0]),
        P::Magnets,
        Limit::AtMost,
        2.0,
        1.0,
    );
    k(
        knob().magnets(&[0.0]).magnet_radius(0.0),
        P::CaptureRadius,
        Limit::Positive,
        0.0,
        0.0,
    );
    let tiny = knob().magnets(&[0.0]).magnet_radius(1e-4);
    k(tiny, P::CaptureRadius, Limit::AtLeast, 1e-4, 2.0 * count);
    let wide = knob().magnets(&[0.0, 0.1]).magnet_radius(0.0499);
    k(
        wide,
        P::CaptureRadius,
        Limit::AtMost,
        0.0499,
        0.05 - hysteresis,
    );
    // A detent the motor cannot render unclipped: its peak torque is the stiffness times
    // the switching point, 0.55 of the width (the default snap point); the limit is the
    // stiffest whose peak the motor gives.
    let strong = knob().detent_width(0.1).detent_stiffness(5.0);
    k(
        strong,
        P::DetentStiffness,
        Limit::PeakTorque,
        5.0,
        0.05 / 0.055,
    );
    // A detent the loop cannot hold at 1 kHz (with a motor that can).
    let stiff = KnobConfig::new(1_000.0, 1e-5, 2.0, 16_384)
        .detent_width(0.1)
        .detent_stiffness(5.0);
    k(
        stiff,
        P::DetentStiffness,
        Limit::LoopStiffness(Zone::Free),
        5.0,
        stiff
            .detent_stiffness_limit::<f32>()
            .expect("a soft detent passes"),
    );
    // A rate below the least a knob runs at (a period passed where the rate goes).
    k(
        KnobConfig::new(1e-3, 1e-5, 0.05, 16_384),
        P::LoopRate,
        Limit::AtLeast,
        1e-3,
        stiffspring::knob::MIN_LOOP_RATE,
    );
}

// ---------------------------------------------------------------------------
// What the errors say
// ---------------------------------------------------------------------------

/// Issue 11: an error says which parameter, what value, and the bound it broke (or the
/// backend, its limit and what would work).
#[test]
fn errors_say_which_parameter_what_value_and_the_bound() {
    let say = |e: Error| e.to_string();
    let e = Tuning::from_coefficients(1.5, 0.2, DT).expect_err("C_k > 1");
    assert_eq!(say(e), "Stiffness = 1.5 is outside [0, 1]");
    let e = Tuning::from_coefficients_extended(3.5, 0.5, DT).expect_err("beyond Jury");
    assert_eq!(say(e), "Stiffness = 3.5 is outside (−∞, 3)");
    let e = Tuning::from_frequency(2.0, 0.5, -1.0).expect_err("dt < 0");
    assert_eq!(say(e), "TimeStep = -1 is outside (0, ∞)");
    assert_eq!(say(not_finite(P::Velocity)), "Velocity is NaN or infinite");
    let slow = Tuning::from_frequency(0.1, 0.5, 1e-4).expect("valid");
    let e = SpringValue::<I16F16>::new([I16F16::ZERO], &slow)
        .map(|_| ())
        .expect_err("C_k");
    let expected = format!(
        "Stiffness = {} is beyond what I16F16 holds ({}): step at a lower rate",
        slow.stiffness(),
        2f64.powi(-24)
    );
    assert_eq!(say(e), expected);
    let stale = Error::Stale {
        parameter: P::Index,
    };
    assert_eq!(say(stale), "the Index id names nothing live");
    let mismatch = Error::TimeStepMismatch {
        expected: 0.01,
        found: 0.02,
    };
    assert_eq!(
        say(mismatch),
        "the tuning is sampled at dt = 0.02, the scene steps at dt = 0.01"
    );
    let full = Error::CapacityFull { capacity: 8 };
    assert_eq!(say(full), "capacity 8 is full");
    // The knob's errors add the bound in its own terms.
    let strong = knob().detent_width(0.1).detent_stiffness(5.0);
    let e = Knob::<f32>::new(&strong, 0.0)
        .expect_err("peak torque")
        .to_string();
    assert!(e.starts_with("DetentStiffness = 5 is outside"), "{e}");
    assert!(
        e.contains("the stiffest whose peak torque the motor gives"),
        "{e}"
    );
}
