//! Properties of a value over its whole input range: floats never produce NaN or infinity,
//! and fixed point steps exactly as the study's integer model of its step
//! (`lab::precision::Kept`: Q24.40 / Q64.64 state, spring term toward zero, damping term
//! away from it), saturating, never wrapping, from any start in its range.
//!
//! `cargo test --release --test value_properties` runs 256 cases per property;
//! `PROPTEST_CASES=20000 cargo test --release --test value_properties` is a longer run.

use lab::precision::{Coefs, Fixed, KRound, Kept, Stepper};
use proptest::prelude::*;
use stiffspring::{I16F16, I32F32, Scalar, SpringValue, Tuning};

const DT60: f64 = 1.0 / 60.0;

/// Raw access to the fixed-point backends, for the exact-arithmetic check.
trait FixedBits: Scalar {
    const FIXED: Fixed;
    const MIN_BITS: i128;
    const MAX_BITS: i128;
    fn bits(self) -> i128;
    fn from_raw(bits: i128) -> Self;
}

impl FixedBits for I16F16 {
    const FIXED: Fixed = Fixed::I16F16;
    const MIN_BITS: i128 = i32::MIN as i128;
    const MAX_BITS: i128 = i32::MAX as i128;
    fn bits(self) -> i128 {
        self.to_bits() as i128
    }
    fn from_raw(bits: i128) -> Self {
        I16F16::from_bits(bits as i32)
    }
}

impl FixedBits for I32F32 {
    const FIXED: Fixed = Fixed::I32F32;
    const MIN_BITS: i128 = i64::MIN as i128;
    const MAX_BITS: i128 = i64::MAX as i128;
    fn bits(self) -> i128 {
        self.to_bits() as i128
    }
    fn from_raw(bits: i128) -> Self {
        I32F32::from_bits(bits as i64)
    }
}

/// A value released from `from` toward `to` with raw coefficients `(ck, cd)` (whose release
/// starts from a kept velocity of 0) steps as the model from the same state, read for read,
/// for `steps` steps. `None` when set-up refuses the tuning (a `C_k` below the backend's
/// resolution).
fn follows_the_model<S: FixedBits>(ck: f64, cd: f64, from: S, to: S, steps: usize) -> Option<()> {
    let tuning = Tuning::from_coefficients_extended(ck, cd, DT60).ok()?;
    let mut v = SpringValue::<S>::new([from], &tuning).ok()?;
    v.try_set_target([to]).expect("the state holds any offset");
    assert_eq!(v.position(), [from], "{}: the retarget moved it", S::NAME);
    let x = (from.bits() - to.bits()) << Kept::guard(S::FIXED);
    let mut model = Kept::from_state(S::FIXED, KRound::Lead, Coefs { ck, cd }, x, 0);
    for n in 0..steps {
        v.advance();
        model.step();
        assert_eq!(
            v.offset()[0].bits(),
            model.visible_lsb(),
            "{} ({ck}, {cd}) from {from:?} to {to:?}, step {n}",
            S::NAME
        );
    }
    Some(())
}

/// From the ends of the range to the other end, to zero and back, a fixed-point value's
/// first step moves toward its target (exact map and raw coefficients), and with raw
/// coefficients every step is the model's.
fn extremes<S: FixedBits>() {
    let (min, max) = (S::from_raw(S::MIN_BITS), S::from_raw(S::MAX_BITS));
    let pairs = [
        (max, min),
        (min, max),
        (max, S::ZERO),
        (min, S::ZERO),
        (S::ZERO, max),
    ];
    let exact = [
        Tuning::from_frequency(2.0, 0.3, DT60),
        Tuning::from_frequency(100.0, 0.2, DT60),
    ];
    for tuning in exact.map(|t| t.expect("valid")) {
        for (from, to) in pairs {
            let mut v = SpringValue::<S>::new([from], &tuning).expect("representable");
            v.set_target([to]);
            assert_eq!(v.position(), [from]);
            v.advance();
            let after = v.position()[0];
            assert!(
                if to > from {
                    after > from
                } else {
                    after < from
                },
                "{}",
                S::NAME
            );
        }
    }
    for (ck, cd) in [(0.05, 0.2), (1.0, 0.0), (1.0, 1.0), (2.5, 0.1), (0.3, 1.6)] {
        for (from, to) in pairs {
            follows_the_model(ck, cd, from, to, 5000).expect("representable");
        }
    }
}

#[test]
fn fixed_point_extremes_saturate_and_move_toward_the_target() {
    extremes::<I16F16>();
    extremes::<I32F32>();
}

/// A coefficient in [0, 1], with the corners drawn often.
fn unit() -> impl Strategy<Value = f64> {
    prop_oneof![1 => Just(0.0), 1 => Just(1.0), 6 => 0.0..=1.0f64]
}

/// Valid tunings at 60 Hz: raw coefficients over [0, 1]² less the origin, and the exact
/// map over f·dt ∈ [1e−3, 0.45], ζ ∈ [0, 5].
fn tunings() -> impl Strategy<Value = Tuning> {
    prop_oneof![
        (unit(), unit()).prop_filter_map("a spring", |(k, d)| {
            Tuning::from_coefficients(k, d, DT60).ok()
        }),
        (
            1e-3..=0.45f64,
            prop_oneof![1 => Just(0.0), 1 => Just(1.0), 6 => 0.0..=5.0f64]
        )
            .prop_filter_map("valid", |(fdt, z)| {
                Tuning::from_frequency(fdt / DT60, z, DT60).ok()
            }),
    ]
}

/// The stable region of raw coefficients: the square less the origin, and Jury's region.
fn region() -> impl Strategy<Value = (f64, f64)> {
    prop_oneof![
        (unit(), unit()),
        (0.0..4.0f64, 0.0..2.0f64),
        (0.0..2.0f64, 1e-6..0.1f64).prop_map(|(cd, gap)| (4.0 - 2.0 * cd - gap, cd)),
    ]
    .prop_filter("stable", |&(k, d)| {
        Tuning::from_coefficients_extended(k, d, DT60).is_ok()
    })
}

/// A fraction in [−1, 1] of a magnitude, with 0 and ±1 drawn often.
fn fraction() -> impl Strategy<Value = f64> {
    prop_oneof![1 => Just(0.0), 1 => Just(1.0), 1 => Just(-1.0), 6 => -1.0..=1.0f64]
}

/// Raw bits of a fixed-point value: anywhere, near the ends, or near zero.
fn bits(min: i128, max: i128) -> impl Strategy<Value = i128> {
    prop_oneof![
        4 => min..=max,
        1 => Just(min),
        1 => Just(max),
        1 => (0i128..4096).prop_map(move |d| min + d),
        1 => (0i128..4096).prop_map(move |d| max - d),
        2 => -1_000_000i128..1_000_000,
    ]
}

/// Positions, targets and flings anywhere in the accepted range (`±Scalar::MAX`), through
/// the infallible setters (which saturate what the state cannot hold): never NaN, never
/// infinite. A tuning whose transient growth leaves the float no room is refused at
/// set-up (`Error::Unrepresentable`), documented.
fn floats_stay_finite<S: Scalar>(
    tuning: Tuning,
    (p, t, v): (f64, f64, f64),
) -> Result<(), TestCaseError> {
    let lim = S::MAX;
    let Ok(mut value) = SpringValue::<S>::new([S::from_f64(p * lim)], &tuning) else {
        prop_assert!(tuning.growth() > 1e6, "{tuning:?} refused");
        return Ok(());
    };
    value.set_target([S::from_f64(t * lim)]);
    value.fling([S::from_f64(v * lim)]);
    for n in 0..2000 {
        let _ = value.step();
        let all = [
            value.position()[0],
            value.offset()[0],
            value.step_velocity()[0],
            value.velocity()[0],
        ];
        prop_assert!(
            all.iter().all(|x| x.to_f64().is_finite()),
            "{} step {n}: {all:?} ({tuning:?})",
            S::NAME
        );
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    #[test]
    fn f32_never_produces_nan_or_inf(t in tunings(), x in (fraction(), fraction(), fraction())) {
        floats_stay_finite::<f32>(t, x)?;
    }

    #[test]
    fn f64_never_produces_nan_or_inf(t in tunings(), x in (fraction(), fraction(), fraction())) {
        floats_stay_finite::<f64>(t, x)?;
    }

    #[test]
    fn i16f16_steps_are_the_model_and_saturate(
        (ck, cd) in region(),
        p in bits(i32::MIN as i128, i32::MAX as i128),
        g in bits(i32::MIN as i128, i32::MAX as i128),
    ) {
        let _ = follows_the_model(ck, cd, I16F16::from_raw(p), I16F16::from_raw(g), 2000);
    }

    #[test]
    fn i32f32_steps_are_the_model_and_saturate(
        (ck, cd) in region(),
        p in bits(i64::MIN as i128, i64::MAX as i128),
        g in bits(i64::MIN as i128, i64::MAX as i128),
    ) {
        let _ = follows_the_model(ck, cd, I32F32::from_raw(p), I32F32::from_raw(g), 2000);
    }
}
