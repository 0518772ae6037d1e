//! What the value and batch tests share: their two frame rates, a loop over every
//! backend, and a conversion into the backend under test. A module in a folder, so that
//! cargo does not build it as a test of its own.

#![allow(dead_code)] // each test file uses its own part of it

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
