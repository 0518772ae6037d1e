//! What the value and batch tests share: their two frame rates, a loop over every
//! backend, and a conversion into the backend under test. A module in a folder, so that
//! cargo does not build it as a test of its own.

#![allow(dead_code)] // each test file uses its own part of it

use proptest::prelude::*;
use stiffspring::Scalar;

/// 60 Hz, a display's frame.
pub const DT60: f64 = 1.0 / 60.0;
/// 120 Hz, a fast display's frame.
pub const DT120: f64 = 1.0 / 120.0;

/// Calls `f::<S>(args…)` for every backend: `f32`, `f64`, `I16F16`, `I32F32`.
#[macro_export]
macro_rules! each_backend {
    ($f:ident $(, $arg:expr)*) => {{
        $f::<f32>($($arg),*);
        $f::<f64>($($arg),*);
        $f::<stiffspring::I16F16>($($arg),*);
        $f::<stiffspring::I32F32>($($arg),*);
    }};
}

/// `x` in backend `S`.
pub fn s<S: Scalar>(x: f64) -> S {
    S::from_f64(x)
}

/// `x` in backend `S` as it is: NaN and infinities kept in floats (where `from_f64` maps
/// NaN to 0 and saturates infinity), saturated in fixed point, which holds neither. For
/// feeding bad input through the API.
pub fn from<S: Scalar>(x: f64) -> S {
    if S::RESOLUTION == 0.0 && !x.is_finite() {
        // Built by arithmetic, the only way to make a float backend's NaN or infinity.
        let big = S::from_f64(f64::MAX);
        let inf = big.add(big);
        if x.is_nan() {
            inf.sub(inf)
        } else if x > 0.0 {
            inf
        } else {
            inf.neg()
        }
    } else {
        S::from_f64(x)
    }
}

/// A number that is usually valid (in `[lo, hi]`) and sometimes not: NaN, ±∞, 0, −1,
/// ±10³⁰⁰.
pub fn number(lo: f64, hi: f64) -> impl Strategy<Value = f64> {
    prop_oneof![
        40 => lo..=hi,
        1 => Just(f64::NAN),
        1 => Just(f64::INFINITY),
        1 => Just(f64::NEG_INFINITY),
        1 => Just(0.0),
        1 => Just(-1.0),
        1 => Just(1e300),
        1 => Just(-1e300),
    ]
}
