//! Bad input to values and batches. The rows of `docs/bad-input.md` for them, one by one.
//!
//! The UI path (`set_target`, `set_position`, `fling`) cannot fail: it ignores NaN and
//! saturates the rest; its `try_` twins report the same cases as errors, and a call that
//! fails changes nothing. Set-up refuses a position out of range and a tuning the backend
//! cannot hold; a batch index that names no live value is ignored, `None` or
//! `Error::Stale`, never another value.

use stiffspring::{
    Bound, Error, I16F16, I32F32, Parameter, Remedy, Scalar, SpringBatch, SpringValue, Tuning,
};

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

// ---------------------------------------------------------------------------
// Values
// ---------------------------------------------------------------------------

/// Everything a value shows, for "nothing changed".
fn show<S: Scalar, const D: usize>(v: &SpringValue<S, D>) -> String {
    format!(
        "{:?} {:?} {:?} {:?} {:?} {}",
        v.position(),
        v.target(),
        v.offset(),
        v.velocity(),
        v.step_velocity(),
        v.is_at_rest()
    )
}

/// A value in flight: three components, retargeted and moving.
fn in_flight<S: Scalar>() -> SpringValue<S, 3> {
    let t = Tuning::from_frequency(2.0, 0.3, DT).expect("valid");
    let mut v = SpringValue::new([S::ZERO; 3], &t).expect("valid");
    v.set_target([S::ONE, S::ONE.neg(), S::ZERO]);
    for _ in 0..5 {
        let _ = v.step();
    }
    v
}

/// In floats: NaN and ±∞ (not finite) and ±2·MAX (out of range) for each component.
fn bad_floats<S: Scalar>(parameter: Parameter) -> Vec<(S, Error)> {
    let big = S::from_f64(f64::MAX);
    let inf = big.add(big);
    let twice = S::from_f64(2.0 * S::MAX);
    let beyond = out(
        parameter,
        2.0 * S::MAX,
        Bound::MagnitudeAtMost { max: S::MAX },
    );
    vec![
        (inf.sub(inf), not_finite(parameter)),
        (inf, not_finite(parameter)),
        (inf.neg(), not_finite(parameter)),
        (twice, beyond),
        (
            twice.neg(),
            Error::OutOfRange {
                parameter,
                value: -2.0 * S::MAX,
                bound: Bound::MagnitudeAtMost { max: S::MAX },
            },
        ),
    ]
}

fn float_values<S: Scalar>() {
    let t = Tuning::from_frequency(2.0, 0.3, DT).expect("valid");
    for (bad, e) in bad_floats::<S>(P::Position) {
        for k in 0..3 {
            let mut p = [S::ZERO; 3];
            p[k] = bad;
            assert_eq!(SpringValue::new(p, &t).map(|_| ()), Err(e), "{}", S::NAME);
            let mut v = in_flight::<S>();
            let before = show(&v);
            assert_eq!(v.try_set_target(p), Err(e));
            assert_eq!(v.try_set_position(p), Err(e));
            assert_eq!(show(&v), before, "{}: a failed try_ changed it", S::NAME);
            // The infallible twins: NaN does nothing, the rest saturates at ±MAX.
            v.set_target(p);
            v.set_position(p);
            if bad.to_f64().is_nan() {
                assert_eq!(show(&v), before, "{}: NaN changed it", S::NAME);
            } else {
                let max = S::from_f64(S::MAX);
                let sat = if bad > S::ZERO { max } else { max.neg() };
                assert_eq!(v.target()[k], sat);
                assert_eq!(v.position()[k], sat);
            }
        }
    }
    for (bad, e) in bad_floats::<S>(P::Velocity) {
        let mut v = in_flight::<S>();
        let before = show(&v);
        assert_eq!(v.try_fling([S::ZERO, bad, S::ZERO]), Err(e));
        assert_eq!(show(&v), before);
        v.fling([S::ZERO, bad, S::ZERO]);
        assert_eq!(show(&v) == before, bad.to_f64().is_nan(), "{}", S::NAME);
        assert!(v.velocity().iter().all(|c| c.to_f64().is_finite()));
    }
}

#[test]
fn float_values_refuse_non_finite_and_out_of_range_input_and_the_ui_path_saturates() {
    float_values::<f32>();
    float_values::<f64>();
}

/// Fixed point takes its whole range; a retarget across all of it keeps the position.
fn fixed_values<S: Scalar>() {
    let t = Tuning::from_frequency(2.0, 0.3, DT).expect("valid");
    let (lo, hi) = (S::from_f64(-S::MAX), S::from_f64(S::MAX));
    for p in [lo, hi] {
        let mut v = SpringValue::<S>::new([p], &t).expect("the whole range");
        let q = if p == lo { hi } else { lo };
        v.try_set_target([q]).expect("the state holds any offset");
        assert_eq!(v.position(), [p]);
        v.try_fling([q]).expect("the state holds any fling");
    }
}

#[test]
fn fixed_point_values_take_their_whole_range() {
    fixed_values::<I16F16>();
    fixed_values::<I32F32>();
    // And so do floats, within ±MAX.
    fixed_values::<f32>();
    fixed_values::<f64>();
}

/// A tuning the backend cannot hold: a gain below its resolution (fixed point: `C_k`
/// below 2⁻²⁴ or 2⁻³², a dead band wider than a position's last bit; floats: a gain that
/// would be subnormal), or a transient growth that leaves a float no room.
#[test]
fn values_and_batches_refuse_a_tuning_the_backend_cannot_hold() {
    let slow = Tuning::from_frequency(0.1, 0.5, 1e-4).expect("valid"); // C_k = 3.9e−9
    let e = Error::Unrepresentable {
        parameter: P::Stiffness,
        backend: "I16F16",
        value: slow.stiffness(),
        limit: 2f64.powi(-24),
        remedy: Remedy::LowerRate,
    };
    assert_eq!(
        SpringValue::<I16F16>::new([I16F16::ZERO], &slow).map(|_| ()),
        Err(e)
    );
    assert_eq!(SpringBatch::<I16F16, 1, 4>::new(&slow).map(|_| ()), Err(e));
    assert!(SpringValue::<I32F32>::new([I32F32::ZERO], &slow).is_ok());
    let slower = Tuning::from_coefficients(1e-10, 0.5, DT).expect("in the square");
    assert!(matches!(
        SpringValue::<I32F32>::new([I32F32::ZERO], &slower),
        Err(Error::Unrepresentable { parameter: P::Stiffness, limit, .. }) if limit == 2f64.powi(-32)
    ));
    let tiny = Tuning::from_coefficients(0.5, 1e-40, DT).expect("in the square");
    assert!(matches!(
        SpringValue::<f32>::new([0.0], &tiny),
        Err(Error::Unrepresentable {
            parameter: P::Damping,
            backend: "f32",
            remedy: Remedy::WiderBackend,
            ..
        })
    ));
    // An undamped spring so slow that its state may swing 10¹⁸ times its start.
    let wide = Tuning::from_coefficients(1e-36, 0.0, DT).expect("in the square");
    let got = SpringValue::<f32>::new([0.0], &wide);
    assert!(
        matches!(got, Err(Error::Unrepresentable { parameter: P::Stiffness, value, .. }) if value == wide.growth()),
        "{got:?}"
    );
    // A failed retune changes nothing.
    let mut v = in_flight::<I16F16>();
    let before = show(&v);
    assert_eq!(v.set_tuning(&slow), Err(e));
    assert_eq!(show(&v), before);
    let t = Tuning::from_frequency(2.0, 0.3, DT).expect("valid");
    let mut b = SpringBatch::<I16F16, 1, 2>::new(&t).expect("valid");
    let i = b.push([I16F16::ONE]).expect("room");
    b.set_target(i, [I16F16::ZERO]);
    let _ = b.step();
    let state = |b: &SpringBatch<I16F16, 1, 2>| {
        b.iter()
            .map(|(i, p)| (i, p, b.velocity(i)))
            .collect::<Vec<_>>()
    };
    let before = state(&b);
    assert_eq!(b.set_tuning(&slow), Err(e));
    assert_eq!((b.tuning(), state(&b)), (t, before));
}

/// A fling or a retune whose step velocity leaves the state: an `I16F16` state holds
/// ±2²³ units, and a raw tuning at dt = 1000 s turns 32 767 units/s into a step of
/// 3.3·10⁷ units.
#[test]
fn a_step_velocity_beyond_the_state_is_refused_or_saturates() {
    let long = Tuning::from_coefficients(0.01, 0.1, 1000.0).expect("in the square");
    let fast = I16F16::from_num(32_767);
    let mut v = SpringValue::<I16F16>::new([I16F16::ZERO], &long).expect("valid");
    let before = show(&v);
    let got = v.try_fling([fast]);
    assert!(
        matches!(
            got,
            Err(Error::Unrepresentable {
                parameter: P::StepVelocity,
                backend: "I16F16",
                remedy: Remedy::LargerUnit,
                ..
            })
        ),
        "{got:?}"
    );
    assert_eq!(show(&v), before);
    v.fling([fast]); // saturates at the state's end
    assert!(!v.is_at_rest());
    // The same velocity taken to that tuning by a retune.
    let mut w = SpringValue::<I16F16>::new(
        [I16F16::ZERO],
        &Tuning::from_coefficients(0.01, 0.1, DT).expect("valid"),
    )
    .expect("valid");
    w.fling([fast]);
    let before = show(&w);
    assert!(matches!(
        w.set_tuning(&long),
        Err(Error::Unrepresentable {
            parameter: P::StepVelocity,
            ..
        })
    ));
    assert_eq!(show(&w), before);
}

// ---------------------------------------------------------------------------
// Batches
// ---------------------------------------------------------------------------

fn batches<S: Scalar>() {
    let t = Tuning::from_frequency(3.0, 0.8, DT).expect("valid");
    let mut b = SpringBatch::<S, 2, 2>::new(&t).expect("valid");
    let i = b.push([S::ZERO, S::ONE]).expect("room");
    let gone = b.push([S::ONE, S::ONE]).expect("room");
    b.remove(gone);
    if S::RESOLUTION == 0.0 {
        for (bad, e) in bad_floats::<S>(P::Position) {
            assert_eq!(b.push([S::ZERO, bad]), Err(e), "{}", S::NAME);
            assert_eq!(b.try_set_target(i, [bad, S::ZERO]), Err(e));
        }
    }
    b.push([S::ONE, S::ONE]).expect("the freed slot");
    assert_eq!(
        b.push([S::ZERO; 2]),
        Err(Error::CapacityFull { capacity: 2 })
    );
    assert_eq!(b.len(), 2);
    // A removed index names nothing: reads give None, the infallible setters ignore it,
    // the try_ setters say so, and remove does nothing.
    let stale = Err(Error::Stale {
        parameter: P::Index,
    });
    let before: Vec<_> = b.iter().collect();
    b.set_target(gone, [S::ONE; 2]);
    b.set_position(gone, [S::ONE; 2]);
    b.fling(gone, [S::ONE; 2]);
    assert_eq!(b.try_set_target(gone, [S::ONE; 2]), stale);
    assert_eq!(b.try_fling(gone, [S::ONE; 2]), stale);
    assert_eq!(b.remove(gone), None);
    assert_eq!(
        (
            b.position(gone),
            b.target(gone),
            b.velocity(gone),
            b.is_at_rest(gone)
        ),
        (None, None, None, None)
    );
    assert_eq!(b.iter().collect::<Vec<_>>(), before);
    // NaN is ignored by the infallible setters.
    if S::RESOLUTION == 0.0 {
        let big = S::from_f64(f64::MAX);
        let nan = big.add(big).sub(big.add(big));
        b.set_target(i, [nan, S::ONE]);
        b.fling(i, [nan, S::ONE]);
        assert_eq!(b.iter().collect::<Vec<_>>(), before);
    }
    // A sparse rest test of period 0 is a test every step.
    let mut c = SpringBatch::<S, 1, 1>::new(&t)
        .expect("valid")
        .with_rest_check_every(0);
    let mut every = SpringBatch::<S, 1, 1>::new(&t).expect("valid");
    for b in [&mut c, &mut every] {
        let k = b.push([S::ZERO]).expect("room");
        b.set_target(k, [S::ONE]);
    }
    loop {
        let (m, expected) = (c.step(), every.step());
        assert_eq!(m, expected, "{}", S::NAME);
        if !expected.any() {
            break;
        }
    }
}

#[test]
fn batches_refuse_bad_input_and_stale_indices() {
    batches::<f32>();
    batches::<f64>();
    batches::<I16F16>();
    batches::<I32F32>();
}
