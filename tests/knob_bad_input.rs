//! Bad input to the knob: every configuration error is a typed [`KnobError`] that names
//! the parameter (the crate's [`Error`]), the [`Limit`] it broke, the value and the
//! bound's limit; and no angle or velocity, however wild, makes the per-period call panic
//! or return a torque outside `[−1, 1]` (or NaN).

use lab::rng::Rng;
use stiffspring::knob::{KnobError, Latency, Limit, Zone};
use stiffspring::{Error, I16F16, I32F32, Knob, KnobConfig, Parameter, Scalar};

const NAN: f64 = f64::NAN;
const INF: f64 = f64::INFINITY;

fn base() -> KnobConfig {
    KnobConfig::new(1_000.0, 1e-5, 0.05, 16384)
}

fn err(config: KnobConfig) -> KnobError {
    Knob::<f32>::new(&config, 0.0).unwrap_err()
}

/// A rejection of `parameter` with bound `limit` and value `value` (NaN: any non-finite
/// value), whose crate-wide error says the same: `NotFinite` for [`Limit::Finite`],
/// `CapacityFull` for [`Limit::Capacity`], else `OutOfRange` with the same value and a
/// range that excludes it. `Display` names the parameter and the value.
fn check(e: KnobError, parameter: Parameter, limit: Limit, value: f64) {
    assert_eq!(e.bound, limit, "{e:?}");
    if value.is_finite() {
        assert_eq!(e.value, value, "{e:?}");
    } else {
        assert!(!e.value.is_finite(), "{e:?}");
    }
    match (limit, e.error) {
        (Limit::Finite, Error::NotFinite { parameter: p }) => assert_eq!(p, parameter),
        (Limit::Capacity, Error::CapacityFull { capacity }) => {
            assert_eq!(capacity as f64, e.limit, "{e:?}");
        }
        (Limit::NeedsEndstops, Error::NeedsEndstops) => {
            assert_eq!(e.error.parameter(), Some(parameter), "{e:?}");
        }
        (
            _,
            Error::OutOfRange {
                parameter: p,
                value: v,
                bound,
            },
        ) => {
            assert_eq!(p, parameter, "{e:?}");
            assert_eq!(v, e.value, "{e:?}");
            assert!(!bound.contains(v), "{e:?}: the range contains the value");
        }
        _ => panic!("{e:?}: the crate's error does not match the bound"),
    }
    let text = e.to_string();
    // A full capacity names what is full (the magnets).
    let name = match limit {
        Limit::Capacity => "magnets".to_string(),
        Limit::NeedsEndstops => "endstops".to_string(),
        _ => format!("{parameter:?}"),
    };
    assert!(text.contains(&name), "{text}");
    if value.is_finite() {
        assert!(text.contains(&format!("{value}")), "{text}");
    }
}

#[test]
fn set_up_in_physical_units_is_checked() {
    use Parameter::*;
    for (v, l) in [
        (NAN, Limit::Finite),
        (INF, Limit::Finite),
        (0.0, Limit::Positive),
        (-1e3, Limit::Positive),
    ] {
        check(err(KnobConfig::new(v, 1e-5, 0.05, 16384)), LoopRate, l, v);
    }
    for (v, l) in [
        (NAN, Limit::Finite),
        (0.0, Limit::Positive),
        (-1.0, Limit::Positive),
    ] {
        check(err(KnobConfig::new(1e3, v, 0.05, 16384)), Inertia, l, v);
    }
    for (v, l) in [(INF, Limit::Finite), (0.0, Limit::Positive)] {
        check(err(KnobConfig::new(1e3, 1e-5, v, 16384)), TorqueLimit, l, v);
    }
    check(
        err(KnobConfig::new(1e3, 1e-5, 0.05, 0)),
        CountsPerTurn,
        Limit::Positive,
        0.0,
    );
    // Finer than an I16F16 LSB per count: I16F16 cannot tell counts apart.
    let fine = KnobConfig::new(1e3, 1e-5, 0.05, 1 << 20);
    let e = Knob::<I16F16>::new(&fine, I16F16::ZERO).unwrap_err();
    check(e, CountsPerTurn, Limit::AtMost, f64::from(1u32 << 20));
    assert_eq!(e.limit, (std::f64::consts::TAU * 65536.0).floor());
    assert!(Knob::<f32>::new(&fine, 0.0).is_ok());
    // A float's spacing grows with the angle: between stops at ±135° an f32 step is
    // 2.4e−7 rad (2⁻²² at 2.36), so a count must span four of them: 2π/(4·2⁻²²) counts per
    // turn at most. A 32-bit encoder is refused there, a 22-bit one is not.
    let stops = |counts: u32| KnobConfig::new(1e3, 1e-5, 0.05, counts).endstops(-2.356, 2.356);
    let e = Knob::<f32>::new(&stops(u32::MAX), 0.0).unwrap_err();
    check(e, CountsPerTurn, Limit::AtMost, f64::from(u32::MAX));
    let most = (std::f64::consts::TAU / (4.0 * 2f64.powi(-22))).floor();
    assert!(e.limit == most || e.limit == (2.0 * most).floor(), "{e:?}");
    assert!(Knob::<f32>::new(&stops(1 << 22), 0.0).is_ok());
    assert!(Knob::<f64>::new(&stops(u32::MAX), 0.0).is_ok());

    // Damping.
    check(
        err(base().damping_ratio(NAN)),
        DampingRatio,
        Limit::Finite,
        NAN,
    );
    let e = err(base().damping_ratio(0.19));
    check(e, DampingRatio, Limit::AtLeast, 0.19);
    assert_eq!(e.limit, 0.2);
    let e = err(base().damping_ratio(2.01));
    check(e, DampingRatio, Limit::AtMost, 2.01);
    assert_eq!(e.limit, 2.0);
    check(
        err(base().damping(-1e-3)),
        DampingConstant,
        Limit::NotNegative,
        -1e-3,
    );
    // A damper too strong for the loop (its velocity loop rings at twice the gain); the
    // limit is the most that passes.
    let e = err(base().damping(0.05));
    check(e, DampingConstant, Limit::LoopDamping, 0.05);
    assert!(e.limit > 0.0 && e.limit < 0.05);
    assert!(Knob::<f32>::new(&base().damping(0.99 * e.limit), 0.0).is_ok());
    assert!(Knob::<f32>::new(&base().damping(1.01 * e.limit), 0.0).is_err());
}

#[test]
fn geometry_is_checked() {
    use Parameter::*;
    // Endstops.
    check(err(base().endstops(NAN, 1.0)), Endstops, Limit::Finite, NAN);
    check(err(base().endstops(1.0, 1.0)), Endstops, Limit::Below, 1.0);
    check(err(base().endstops(2.0, 1.0)), Endstops, Limit::Below, 2.0);
    let e = Knob::<I16F16>::new(&base().endstops(0.0, 20_000.0), I16F16::ZERO).unwrap_err();
    check(e, Endstops, Limit::BackendRange, 20_000.0);
    assert_eq!(e.limit, 16_384.0);

    // Detents.
    check(
        err(base().detent_count(5)),
        DetentCount,
        Limit::NeedsEndstops,
        5.0,
    );
    check(
        err(base().endstops(0.0, 1.0).detent_count(1)),
        DetentCount,
        Limit::AtLeast,
        1.0,
    );
    // More detents than fit at four counts each: the most that fit.
    let e = err(base().endstops(0.0, 1.0).detent_count(1000));
    check(e, DetentCount, Limit::AtMost, 1000.0);
    assert_eq!(
        e.limit,
        (16384.0 / (4.0 * std::f64::consts::TAU)).floor() + 1.0
    );
    let most = e.limit as u32;
    assert!(Knob::<f32>::new(&base().endstops(0.0, 1.0).detent_count(most), 0.0).is_ok());
    check(
        err(base().detent_width(0.1).detent_origin(NAN)),
        DetentOrigin,
        Limit::Finite,
        NAN,
    );
    check(
        err(base().detent_width(0.0)),
        DetentWidth,
        Limit::Positive,
        0.0,
    );
    check(
        err(base().detent_width(NAN)),
        DetentWidth,
        Limit::Finite,
        NAN,
    );
    // At least four counts wide.
    let e = err(base().detent_width(1e-3));
    check(e, DetentWidth, Limit::AtLeast, 1e-3);
    assert!((e.limit - 4.0 * std::f64::consts::TAU / 16384.0).abs() < 1e-15);
    let e = err(base().detent_width(0.1).snap_point(0.49));
    check(e, SnapPoint, Limit::AtLeast, 0.49);
    check(
        err(base().detent_width(0.1).snap_point(1.0)),
        SnapPoint,
        Limit::Below,
        1.0,
    );
    check(
        err(base().detent_width(0.1).snap_point(NAN)),
        SnapPoint,
        Limit::Finite,
        NAN,
    );
    check(
        err(base().detent_width(0.1).hysteresis(-1e-3)),
        Hysteresis,
        Limit::NotNegative,
        -1e-3,
    );
    let e = err(base().detent_width(0.1).hysteresis(0.05));
    check(e, Hysteresis, Limit::Below, 0.05);
    assert_eq!(e.limit, 0.05);
    assert!(Knob::<f32>::new(&base().detent_width(0.1).hysteresis(0.049), 0.0).is_ok());

    // Magnets.
    let e = err(base().magnets(&[0.0; 9]));
    check(e, Magnets, Limit::Capacity, 9.0);
    assert_eq!(e.limit, 8.0);
    check(err(base().magnets(&[NAN])), Magnets, Limit::Finite, NAN);
    check(
        err(base().endstops(0.0, 1.0).magnets(&[1.5])),
        Magnets,
        Limit::AtMost,
        1.5,
    );
    check(
        err(base().magnets(&[0.0]).magnet_radius(0.0)),
        CaptureRadius,
        Limit::Positive,
        0.0,
    );
    let e = err(base().magnets(&[0.0, 0.3]).magnet_radius(0.16));
    check(e, CaptureRadius, Limit::AtMost, 0.16);
    assert!(Knob::<f32>::new(&base().magnets(&[0.3, 0.0]).magnet_radius(0.14), 0.0).is_ok());

    // The initial angle.
    let e = Knob::<f32>::new(&base(), f32::NAN).unwrap_err();
    check(e, Position, Limit::Finite, NAN);
    let e = Knob::<f64>::new(&base(), 1e300).unwrap_err();
    check(e, Position, Limit::BackendRange, 1e300);
}

#[test]
fn stiffness_beyond_what_the_loop_guarantees_is_refused_with_the_bound() {
    use Parameter::*;
    for (s, l) in [(NAN, Limit::Finite), (-0.1, Limit::NotNegative)] {
        check(
            err(base().detent_width(0.1).detent_stiffness(s)),
            DetentStiffness,
            l,
            s,
        );
        check(
            err(base().detent_width(0.1).detent_torque(s)),
            DetentTorque,
            l,
            s,
        );
        check(err(base().return_to_centre(0.0, s)), ReturnStiffness, l, s);
        check(
            err(base().magnets(&[0.0]).magnet_stiffness(s)),
            MagnetStiffness,
            l,
            s,
        );
        check(
            err(base().endstops(0.0, 1.0).endstop_stiffness(s)),
            EndstopStiffness,
            l,
            s,
        );
    }
    check(
        err(base().return_to_centre(NAN, 0.01)),
        ReturnCentre,
        Limit::Finite,
        NAN,
    );
    // A detent whose peak torque the motor cannot give: a relay. The peak is at the
    // switching point, 0.55 of the width; the error gives the stiffness the user set and
    // the stiffest whose peak the motor gives.
    let e = err(base().detent_width(1.0).detent_stiffness(0.2));
    check(e, DetentStiffness, Limit::PeakTorque, 0.2);
    assert!((e.limit - 0.05 / 0.55).abs() < 1e-15, "{e:?}");
    // As a peak torque: against the torque limit.
    let e = err(base().detent_width(1.0).detent_torque(0.06));
    check(e, DetentTorque, Limit::PeakTorque, 0.06);
    assert_eq!(e.limit, 0.05);
    let e = err(base()
        .magnets(&[0.0])
        .magnet_radius(0.4)
        .magnet_stiffness(0.2));
    check(e, MagnetStiffness, Limit::PeakTorque, 0.2);
    assert!(e.limit < 0.2 && e.limit * (0.4 + 2.0 * base().count()) <= 0.05 * (1.0 + 1e-15));
    // Beyond the loop guarantee, in each zone: the limit is the stiffest of what the user
    // set that passes, `detent_stiffness_limit` for a detent.
    let c = base().detent_width(0.1).detent_stiffness(0.45);
    let e = err(c);
    check(e, DetentStiffness, Limit::LoopStiffness(Zone::Free), 0.45);
    assert_eq!(e.limit, c.detent_stiffness_limit::<f32>().unwrap());
    assert!(e.limit > 0.2 && e.limit < 0.45, "{e:?}");
    assert!(Knob::<f32>::new(&c.detent_stiffness(e.limit), 0.0).is_ok());
    assert!(Knob::<f32>::new(&c.detent_stiffness(e.limit * (1.0 + 1e-12)), 0.0).is_err());
    let e = err(base()
        .detent_width(0.2)
        .detent_stiffness(0.05)
        .endstops(-1.0, 1.0)
        .endstop_stiffness(5.0));
    check(e, EndstopStiffness, Limit::LoopStiffness(Zone::Beyond), 5.0);
    assert!(e.limit > 0.05 && e.limit < 5.0, "{e:?}");
    let e = err(base()
        .damping(2e-4)
        .magnets(&[0.0])
        .magnet_radius(0.05)
        .magnet_stiffness(0.9));
    check(e, MagnetStiffness, Limit::LoopStiffness(Zone::Magnet), 0.9);
    // A 10-bit encoder at 1 kHz and a detent near the loop's bound: one count would command
    // more than an eighth of the limit (a buzz at rest). The error names the encoder, and
    // the counts per turn that would pass; that resolution is accepted.
    let coarse = KnobConfig::new(1_000.0, 1e-5, 0.05, 1024).detent_width(0.2);
    let e = err(coarse.detent_stiffness(0.3));
    check(e, CountsPerTurn, Limit::CountTorque(Zone::Free), 1024.0);
    assert!(e.limit > 1024.0, "{e:?}");
    let finer = KnobConfig::new(1_000.0, 1e-5, 0.05, e.limit as u32).detent_width(0.2);
    assert!(Knob::<f32>::new(&finer.detent_stiffness(0.3), 0.0).is_ok());
    assert!(
        e.to_string().starts_with("CountsPerTurn = 1024 is outside"),
        "{e}"
    );
    assert!(Knob::<f32>::new(&coarse.detent_stiffness(0.02), 0.0).is_ok());
    // The same stiffness at 10 kHz is accepted: the bound grows with the rate.
    let fast = KnobConfig::new(10_000.0, 1e-5, 0.05, 16384)
        .detent_width(0.1)
        .detent_stiffness(0.45);
    assert!(Knob::<f32>::new(&fast, 0.0).is_ok());
    // The error says by how much: the ratio of value to limit.
    let e = err(base().detent_width(0.1).detent_stiffness(0.45));
    assert!(
        e.to_string()
            .contains(&format!("{:.3}×", e.value / e.limit)),
        "{e}"
    );
}

/// The cases of issue 17: each error names what the user set, in its units, with the
/// value that would pass.
mod issue_17 {
    use super::*;
    use std::f64::consts::TAU;

    /// 24 detents between endstops at ±135°.
    fn layout(c: KnobConfig) -> KnobConfig {
        c.endstops(-0.375 * TAU, 0.375 * TAU).detent_count(24)
    }

    #[test]
    fn a_detent_too_strong_for_the_motor_reports_its_stiffness() {
        // Was "SpringConstant = 0.1126875625744165 is outside (−∞, 0.02]": a peak torque.
        let c = layout(KnobConfig::new(1_000.0, 1e-5, 0.02, 16384)).detent_stiffness(1.0);
        let e = err(c);
        check(e, Parameter::DetentStiffness, Limit::PeakTorque, 1.0);
        // The peak is at 0.55 of the width, 0.75 turn / 23: the stiffest that fits is
        // 0.02 N·m over that.
        let peak_at = 0.55 * 0.75 * TAU / 23.0;
        assert!((e.limit - 0.02 / peak_at).abs() < 1e-12 * e.limit, "{e:?}");
        assert!(
            e.to_string().starts_with("DetentStiffness = 1 is outside"),
            "{e}"
        );
        assert!(Knob::<f32>::new(&c.detent_stiffness(e.limit), 0.0).is_ok());
    }

    #[test]
    fn a_coarse_encoder_is_blamed_not_an_endstop_nobody_set() {
        // Was the "Beyond" zone's stiffness "(by 1.000×)".
        let c = layout(KnobConfig::new(1_000.0, 1e-5, 0.05, 256)).detent_stiffness(0.1);
        let e = err(c);
        check(
            e,
            Parameter::CountsPerTurn,
            Limit::CountTorque(Zone::Beyond),
            256.0,
        );
        assert!(e.limit > 256.0, "{e:?}");
        let finer =
            layout(KnobConfig::new(1_000.0, 1e-5, 0.05, e.limit as u32)).detent_stiffness(0.1);
        assert!(Knob::<f32>::new(&finer, 0.0).is_ok(), "{e}");
        assert!(!e.to_string().contains("1.000×"), "{e}");
    }

    #[test]
    fn a_detent_too_stiff_with_default_endstops_reports_the_detent_limit() {
        // Was "Beyond zone 0.125 > 0.0863" while the stiffest detent that passes was 0.0188.
        // The default endstop now goes down to 1/16 of the detent before the detent is
        // refused: 0.125 passes, 0.4 does not.
        let c = layout(KnobConfig::new(1_000.0, 1e-5, 0.05, 16384)).detent_stiffness(0.125);
        assert!(Knob::<f32>::new(&c, 0.0).is_ok());
        let c = c.detent_stiffness(0.4);
        let e = err(c);
        assert_eq!(e.error.parameter(), Some(Parameter::DetentStiffness), "{e}");
        assert!(matches!(e.bound, Limit::LoopStiffness(_)), "{e:?}");
        assert_eq!(e.value, 0.4);
        assert_eq!(e.limit, c.detent_stiffness_limit::<f32>().unwrap());
        assert!(Knob::<f32>::new(&c.detent_stiffness(e.limit), 0.0).is_ok());
    }

    #[test]
    fn a_period_passed_as_the_rate_reports_the_rate() {
        // Was "above 0 N·m/rad … (by inf×)".
        let c = layout(KnobConfig::new(0.001, 1e-5, 0.05, 16384)).detent_stiffness(0.01);
        let e = err(c);
        check(e, Parameter::LoopRate, Limit::AtLeast, 0.001);
        assert_eq!(e.limit, stiffspring::knob::MIN_LOOP_RATE);
        assert!(!e.to_string().contains("inf"), "{e}");
    }

    #[test]
    fn a_rate_too_low_for_the_springs_reports_the_least_rate() {
        // 100 Hz holds no 0.05 N·m/rad detent on 1e−5 kg·m²: the error names the rate
        // with the least that holds it.
        let c = KnobConfig::new(100.0, 1e-5, 0.05, 16384)
            .detent_width(0.5)
            .detent_stiffness(0.05);
        let e = err(c);
        assert!(
            matches!(
                e.error.parameter(),
                Some(Parameter::DetentStiffness) | Some(Parameter::LoopRate)
            ),
            "{e}"
        );
        assert!(
            e.limit < e.value || e.error.parameter() == Some(Parameter::LoopRate),
            "{e:?}"
        );
    }

    /// Over a grid of refused configurations: no error gives a limit equal to its value,
    /// an infinite ratio, or a parameter the user did not set.
    #[test]
    fn no_error_gives_a_limit_equal_to_its_value() {
        let mut refused = 0;
        for rate in [1_000.0, 4_000.0, 10_000.0] {
            for counts in [256u32, 1024, 4096, 16384] {
                for k in [0.003, 0.01, 0.03, 0.1, 0.3, 1.0, 3.0] {
                    for stops in [false, true] {
                        let c = KnobConfig::new(rate, 1e-5, 0.05, counts);
                        let c = if stops {
                            layout(c)
                        } else {
                            c.detent_width(0.26)
                        };
                        let Err(e) = Knob::<f32>::new(&c.detent_stiffness(k), 0.0) else {
                            continue;
                        };
                        refused += 1;
                        assert_ne!(e.value, e.limit, "{e}");
                        assert!(e.limit.is_finite(), "{e}");
                        let text = e.to_string();
                        assert!(!text.contains("1.000×") && !text.contains("inf"), "{text}");
                        let p = e.error.parameter();
                        assert!(
                            p == Some(Parameter::DetentStiffness)
                                || p == Some(Parameter::CountsPerTurn),
                            "{text}"
                        );
                    }
                }
            }
        }
        assert!(refused > 10, "{refused}");
    }
}

#[test]
fn nothing_configured_is_lost() {
    // A rejection leaves the config as it was, and fixing the one bad argument is enough.
    let bad = base()
        .endstops(-1.0, 1.0)
        .detent_count(9)
        .detent_stiffness(0.45)
        .latency(Latency::SameStep);
    let e = Knob::<f32>::new(&bad, 0.0).unwrap_err();
    assert_eq!(e.error.parameter(), Some(Parameter::DetentStiffness));
    let fixed = bad.detent_stiffness(0.1);
    let knob = Knob::<f32>::new(&fixed, 0.9).unwrap();
    // The endstops and detents are still there: 9 detents over [−1, 1], 0.25 apart.
    assert_eq!(knob.detent(), 8);
    assert_eq!(knob.zone_stiffness()[0], 0.1);

    // `?` into the crate's error keeps the parameter and the value.
    fn build() -> Result<Knob<f32>, Error> {
        Ok(Knob::<f32>::new(&base().damping_ratio(5.0), 0.0)?)
    }
    let e = build().unwrap_err();
    assert_eq!(e.parameter(), Some(Parameter::DampingRatio));
    assert!(matches!(e, Error::OutOfRange { value: 5.0, .. }), "{e:?}");
}

/// Angles from everywhere: the extremes of every backend, infinities, NaN, and a seeded
/// spread around the range.
fn wild_angles<S: Scalar>() -> Vec<S> {
    let mut v: Vec<f64> = vec![
        0.0,
        1e-9,
        -1e-9,
        0.1,
        -0.1,
        3.0,
        -3.0,
        1e3,
        -1e3,
        3e4,
        -3e4,
        1e9,
        -1e9,
        1e30,
        -1e30,
        f64::MAX,
        f64::MIN,
        INF,
        -INF,
        NAN,
    ];
    let mut rng = Rng::seeded(0x6b6e_6f62);
    v.extend((0..200).map(|_| rng.sym(5.0)));
    v.into_iter().map(S::from_f64).collect()
}

fn never_misbehaves<S: Scalar>() {
    let configs = [
        base(),
        base().detent_width(0.1).detent_stiffness(0.2),
        base()
            .endstops(-1.0, 1.0)
            .detent_count(9)
            .detent_stiffness(0.1)
            .return_to_centre(0.0, 0.02),
        base().magnets(&[-0.5, 0.5]).magnet_stiffness(0.15),
        KnobConfig::new(10_000.0, 1e-5, 0.05, 16384)
            .endstops(0.0, 3.0)
            .endstop_stiffness(1.0),
    ];
    let one = S::from_f64(1.0);
    for config in &configs {
        let mut knob = Knob::<S>::new(config, S::ZERO).unwrap();
        for &a in &wild_angles::<S>() {
            for out in [knob.update(a), knob.update_with_velocity(a, a)] {
                assert!(out.torque.to_f64().is_finite(), "{} {a:?}", S::NAME);
                assert!(
                    out.torque <= one && out.torque >= one.neg(),
                    "{} {a:?}",
                    S::NAME
                );
            }
        }
        knob.reset(S::from_f64(NAN));
        assert!(knob.update(S::ZERO).torque.to_f64().is_finite());
    }
}

#[test]
fn no_angle_breaks_the_per_period_call() {
    never_misbehaves::<f32>();
    never_misbehaves::<f64>();
    never_misbehaves::<I16F16>();
    never_misbehaves::<I32F32>();
}
