//! Bad input to the knob: every configuration error is a typed [`KnobError`] that names
//! the parameter (the crate's [`Error`]), the [`Limit`] it broke, the value and the
//! bound's limit; and no angle or velocity, however wild, makes the per-period call panic
//! or return a torque outside `[−1, 1]` (or NaN).

use lab::rng::Rng;
use stiffspring::knob::{KnobError, Latency, Limit, Zone};
use stiffspring::{Bound, Error, I16F16, I32F32, Knob, KnobConfig, Parameter, Scalar};

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
        EncoderResolution,
        Limit::Positive,
        0.0,
    );
    // Finer than an I16F16 LSB per count: I16F16 cannot tell counts apart.
    let fine = KnobConfig::new(1e3, 1e-5, 0.05, 1 << 20);
    let e = Knob::<I16F16>::new(&fine, I16F16::ZERO).unwrap_err();
    check(e, EncoderResolution, Limit::AtMost, f64::from(1u32 << 20));
    assert!((e.limit - std::f64::consts::TAU * 65536.0).abs() < 1e-6);
    assert!(Knob::<f32>::new(&fine, 0.0).is_ok());
    // A float's spacing grows with the angle: between stops at ±135° an f32 step is
    // 2.4e−7 rad (2⁻²² at 2.36), so a count must span four of them: 2π/(4·2⁻²²) counts per
    // turn at most. A 32-bit encoder is refused there, a 22-bit one is not.
    let stops = |counts: u32| KnobConfig::new(1e3, 1e-5, 0.05, counts).endstops(-2.356, 2.356);
    let e = Knob::<f32>::new(&stops(u32::MAX), 0.0).unwrap_err();
    check(e, EncoderResolution, Limit::AtMost, f64::from(u32::MAX));
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
    check(err(base().endstops(NAN, 1.0)), Position, Limit::Finite, NAN);
    check(err(base().endstops(1.0, 1.0)), Position, Limit::Below, 1.0);
    check(err(base().endstops(2.0, 1.0)), Position, Limit::Below, 2.0);
    let e = Knob::<I16F16>::new(&base().endstops(0.0, 20_000.0), I16F16::ZERO).unwrap_err();
    check(e, Position, Limit::BackendRange, 20_000.0);
    assert_eq!(e.limit, 16_384.0);

    // Detents.
    check(
        err(base().detent_count(5)),
        DetentWidth,
        Limit::NeedsEndstops,
        5.0,
    );
    check(
        err(base().endstops(0.0, 1.0).detent_count(1)),
        DetentWidth,
        Limit::AtLeast,
        1.0,
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
    check(e, CaptureRadius, Limit::Capacity, 9.0);
    assert_eq!(e.limit, 8.0);
    check(err(base().magnets(&[NAN])), Position, Limit::Finite, NAN);
    check(
        err(base().endstops(0.0, 1.0).magnets(&[1.5])),
        Position,
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
            SpringConstant,
            l,
            s,
        );
        check(err(base().return_to_centre(0.0, s)), SpringConstant, l, s);
        check(
            err(base().magnets(&[0.0]).magnet_stiffness(s)),
            SpringConstant,
            l,
            s,
        );
        check(
            err(base().endstops(0.0, 1.0).endstop_stiffness(s)),
            SpringConstant,
            l,
            s,
        );
    }
    // A detent whose peak torque the motor cannot give: a relay. The peak is at the
    // switching point, 0.55 of the width.
    let e = err(base().detent_width(1.0).detent_stiffness(0.2));
    check(e, SpringConstant, Limit::PeakTorque, 0.2 * 0.55);
    assert_eq!(e.limit, 0.05);
    let e = err(base()
        .magnets(&[0.0])
        .magnet_radius(0.4)
        .magnet_stiffness(0.2));
    assert_eq!(e.bound, Limit::PeakTorque);
    // Beyond the loop guarantee, in each zone: the limit is the stiffest that passes.
    let e = err(base().detent_width(0.1).detent_stiffness(0.45));
    check(e, SpringConstant, Limit::LoopStiffness(Zone::Free), 0.45);
    assert!(e.limit > 0.2 && e.limit < 0.45, "{e:?}");
    let ok = base().detent_width(0.1).detent_stiffness(0.99 * e.limit);
    assert!(Knob::<f32>::new(&ok, 0.0).is_ok());
    let e = err(base()
        .detent_width(0.2)
        .detent_stiffness(0.05)
        .endstops(-1.0, 1.0)
        .endstop_stiffness(5.0));
    check(e, SpringConstant, Limit::LoopStiffness(Zone::Beyond), 5.05);
    let e = err(base()
        .damping(2e-4)
        .magnets(&[0.0])
        .magnet_radius(0.05)
        .magnet_stiffness(0.9));
    assert_eq!(e.bound, Limit::LoopStiffness(Zone::Magnet), "{e:?}");
    // A 10-bit encoder at 1 kHz and a detent near the loop's bound: one count would command
    // more than an eighth of the limit (a buzz at rest).
    let coarse = KnobConfig::new(1_000.0, 1e-5, 0.05, 1024).detent_width(0.2);
    let e = err(coarse.detent_stiffness(0.3));
    assert_eq!(e.bound, Limit::CountTorque(Zone::Free), "{e:?}");
    assert!(e.value > e.limit && e.limit == 0.05 / 8.0, "{e:?}");
    // The crate-wide error names the encoder, and the resolution that would pass; that
    // resolution is accepted (a count's torque scales with the count).
    let Error::OutOfRange {
        parameter: EncoderResolution,
        value,
        bound: Bound::AtLeast { min },
    } = e.error
    else {
        panic!("{e:?}");
    };
    assert!(value == 1024.0 && min > value, "{e:?}");
    let finer = KnobConfig::new(1_000.0, 1e-5, 0.05, (1.01 * min).ceil() as u32).detent_width(0.2);
    assert!(Knob::<f32>::new(&finer.detent_stiffness(0.3), 0.0).is_ok());
    assert!(
        e.error
            .to_string()
            .starts_with("EncoderResolution = 1024 is outside"),
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

#[test]
fn nothing_configured_is_lost() {
    // A rejection leaves the config as it was, and fixing the one bad argument is enough.
    let bad = base()
        .endstops(-1.0, 1.0)
        .detent_count(9)
        .detent_stiffness(0.45)
        .latency(Latency::SameStep);
    let e = Knob::<f32>::new(&bad, 0.0).unwrap_err();
    assert_eq!(e.error.parameter(), Some(Parameter::SpringConstant));
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
