//! Bad input to the knob: every configuration error is the documented typed [`Error`],
//! and no angle or velocity, however wild, makes the per-period call panic or return a
//! torque outside `[−1, 1]` (or NaN).

use stiffspring::knob::{Latency, StrengthMap};
use stiffspring::{Error, I16F16, I32F32, Knob, KnobConfig, Parameter, Scalar};

const NAN: f64 = f64::NAN;
const INF: f64 = f64::INFINITY;

fn base() -> KnobConfig {
    KnobConfig::new(1e-3, 1e-5, 0.05)
}

fn err(config: KnobConfig) -> Error {
    Knob::<f32>::new(&config, 0.0).unwrap_err()
}

#[test]
fn configuration_errors_name_the_argument() {
    use Error::*;
    use Parameter::*;
    for (v, e) in [
        (NAN, NotFinite(TimeStep)),
        (INF, NotFinite(TimeStep)),
        (0.0, NotPositive(TimeStep)),
        (-1e-3, NotPositive(TimeStep)),
    ] {
        assert_eq!(err(KnobConfig::new(v, 1e-5, 0.05)), e);
    }
    for (v, e) in [
        (NAN, NotFinite(Inertia)),
        (0.0, NotPositive(Inertia)),
        (-1.0, NotPositive(Inertia)),
    ] {
        assert_eq!(err(KnobConfig::new(1e-3, v, 0.05)), e);
    }
    for (v, e) in [
        (INF, NotFinite(TorqueLimit)),
        (0.0, NotPositive(TorqueLimit)),
    ] {
        assert_eq!(err(KnobConfig::new(1e-3, 1e-5, v)), e);
    }
    for (z, e) in [
        (NAN, NotFinite(DampingRatio)),
        (0.19, OutOfRange(DampingRatio)),
        (2.01, OutOfRange(DampingRatio)),
        (-1.0, OutOfRange(DampingRatio)),
    ] {
        assert_eq!(err(base().damping_ratio(z)), e);
    }
    assert!(Knob::<f32>::new(&base().damping_ratio(0.2), 0.0).is_ok());
    assert!(Knob::<f32>::new(&base().damping_ratio(2.0), 0.0).is_ok());
    // I/(dt²·τ_max) that I16F16 cannot hold (in radians: too small at 1 kHz, too large
    // for a heavy rotor at 10 kHz); f32 holds both.
    let tiny = KnobConfig::new(1e-3, 1e-10, 0.05);
    let huge = KnobConfig::new(1e-4, 1e-2, 0.05);
    for c in [tiny, huge] {
        assert_eq!(
            Knob::<I16F16>::new(&c, 0.0).unwrap_err(),
            OutOfRange(Inertia)
        );
        assert!(Knob::<f32>::new(&c, 0.0).is_ok());
    }
    // Endstops.
    assert_eq!(err(base().endstops(NAN, 1.0)), NotFinite(Position));
    assert_eq!(err(base().endstops(1.0, 1.0)), OutOfRange(Position));
    assert_eq!(err(base().endstops(2.0, 1.0)), OutOfRange(Position));
    assert_eq!(
        Knob::<I16F16>::new(&base().endstops(0.0, 20_000.0), 0.0).unwrap_err(),
        OutOfRange(Position)
    );
    // Detents.
    assert_eq!(err(base().detent_count(5)), OutOfRange(DetentWidth)); // no endstops
    assert_eq!(
        err(base().endstops(0.0, 1.0).detent_count(1)),
        OutOfRange(DetentWidth)
    );
    assert_eq!(err(base().detent_width(0.0)), NotPositive(DetentWidth));
    assert_eq!(err(base().detent_width(NAN)), NotFinite(DetentWidth));
    assert_eq!(
        Knob::<I16F16>::new(&base().detent_width(1e-3), 0.0).unwrap_err(),
        OutOfRange(DetentWidth)
    );
    for snap in [0.49, 1.0, NAN] {
        let e = err(base().detent_width(0.1).snap_point(snap));
        assert!(
            matches!(e, OutOfRange(SnapPoint) | NotFinite(SnapPoint)),
            "{snap}: {e:?}"
        );
    }
    assert_eq!(
        err(base().detent_width(0.1).hysteresis(-1e-3)),
        Negative(Hysteresis)
    );
    assert_eq!(
        err(base().detent_width(0.1).hysteresis(0.05)),
        OutOfRange(Hysteresis)
    );
    assert!(Knob::<f32>::new(&base().detent_width(0.1).hysteresis(0.049), 0.0).is_ok());
    // Strengths, each and summed.
    for (s, e) in [
        (NAN, NotFinite(Strength)),
        (-0.1, Negative(Strength)),
        (1.1, OutOfRange(Strength)),
    ] {
        assert_eq!(err(base().detent_width(0.1).detent_strength(s)), e);
        assert_eq!(err(base().return_to_centre(0.0, s)), e);
        assert_eq!(err(base().magnets(&[0.0]).magnet_strength(s)), e);
        assert_eq!(err(base().endstops(0.0, 1.0).endstop_strength(s)), e);
    }
    assert_eq!(
        err(base()
            .detent_width(0.1)
            .detent_strength(0.6)
            .magnets(&[0.0])
            .magnet_strength(0.5)),
        OutOfRange(Strength)
    );
    assert_eq!(
        err(base()
            .endstops(-1.0, 1.0)
            .endstop_strength(0.9)
            .return_to_centre(0.0, 0.2)),
        OutOfRange(Strength)
    );
    assert!(
        Knob::<f32>::new(
            &base()
                .detent_width(0.1)
                .detent_strength(0.7)
                .return_to_centre(0.0, 0.3),
            0.0
        )
        .is_ok()
    );
    // The default endstop strength takes what the return spring leaves.
    assert!(Knob::<f32>::new(&base().endstops(-1.0, 1.0).return_to_centre(0.0, 0.4), 0.0).is_ok());
    // Magnets.
    assert_eq!(err(base().magnets(&[0.0; 9])), CapacityFull);
    assert_eq!(err(base().magnets(&[NAN])), NotFinite(Position));
    assert_eq!(
        err(base().endstops(0.0, 1.0).magnets(&[1.5])),
        OutOfRange(Position)
    );
    assert_eq!(
        err(base().magnets(&[0.0]).magnet_radius(0.0)),
        NotPositive(CaptureRadius)
    );
    assert_eq!(
        err(base().magnets(&[0.0, 0.3]).magnet_radius(0.16)),
        OutOfRange(CaptureRadius)
    );
    assert_eq!(
        err(base()
            .magnets(&[0.0, 0.3])
            .magnet_radius(0.14)
            .hysteresis(0.02)),
        OutOfRange(CaptureRadius)
    );
    assert!(Knob::<f32>::new(&base().magnets(&[0.3, 0.0]).magnet_radius(0.14), 0.0).is_ok());
    // The encoder resolution, and strengths too stiff for it.
    assert_eq!(
        err(base().encoder_resolution(NAN)),
        NotFinite(EncoderResolution)
    );
    assert_eq!(
        err(base().encoder_resolution(0.0)),
        NotPositive(EncoderResolution)
    );
    let stiff = KnobConfig::new(1e-4, 1e-5, 0.05)
        .detent_width(0.2)
        .detent_strength(1.0);
    assert_eq!(
        err(stiff.encoder_resolution(std::f64::consts::TAU / 16384.0)),
        OutOfRange(Strength)
    );
    assert!(
        Knob::<f32>::new(
            &stiff
                .detent_strength(0.2)
                .encoder_resolution(std::f64::consts::TAU / 16384.0),
            0.0
        )
        .is_ok()
    );
    // The initial angle.
    assert_eq!(
        Knob::<f32>::new(&base(), NAN).unwrap_err(),
        NotFinite(Position)
    );
    assert_eq!(
        Knob::<f32>::new(&base(), 1e300).unwrap_err(),
        OutOfRange(Position)
    );
    // The strength map on its own.
    assert_eq!(
        StrengthMap::new(NAN, Latency::OneStep).unwrap_err(),
        NotFinite(DampingRatio)
    );
    let map = StrengthMap::new(0.7, Latency::SameStep).unwrap();
    assert_eq!(map.coefficients(INF).unwrap_err(), NotFinite(Strength));
}

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
    v.extend((0..200).map(|k| ((k * 7919) % 201) as f64 * 0.05 - 5.0));
    v.into_iter().map(S::from_f64).collect()
}

fn never_misbehaves<S: Scalar>() {
    let configs = [
        base(),
        base().detent_width(0.1).detent_strength(1.0),
        base()
            .endstops(-1.0, 1.0)
            .detent_count(9)
            .detent_strength(0.5)
            .return_to_centre(0.0, 0.5),
        base().magnets(&[-0.5, 0.5]).magnet_strength(1.0),
        KnobConfig::new(1e-4, 1e-5, 0.05)
            .endstops(0.0, 3.0)
            .endstop_strength(1.0),
    ];
    let one = S::from_f64(1.0);
    for config in &configs {
        let mut knob = Knob::<S>::new(config, 0.0).unwrap();
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
