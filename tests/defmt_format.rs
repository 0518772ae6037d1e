//! With the `defmt` feature, every public type of the crate is `defmt::Format`, so that a
//! firmware can log any of them.
//!
//! ```text
//! cargo test --features defmt --test defmt_format
//! ```
//!
//! The list below is checked at compile time (a type without `Format` does not compile).
//! `scripts/check-defmt-types` checks that it names every struct and enum of the public
//! API (the pages of `cargo doc`), so a type added later without `Format` fails CI.
#![cfg(feature = "defmt")]

use stiffspring::kernel::BodyWeights;
use stiffspring::knob::{
    Anchor, Endstop, KnobDesign, KnobError, KnobEvents, Latency, Limit, LoopCoefficients,
    SensorFault, Zone,
};
use stiffspring::length::{Approximate, ApproximateNewton, Exact, Linearised, LinearisedRest};
use stiffspring::scalar::{FixedFactor, FixedGains, FloatGains};
use stiffspring::scene::{
    Added, Angle, LimitPolicy, ParticleId, Scene, SceneConfig, SceneMotion, SleepThreshold,
    SpringId, Stepper, WrappedAngle,
};
use stiffspring::{
    BatchIndex, BatchMotion, Bound, Bounds, Decay, Error, Friction, I16F16, I32F32, Knob,
    KnobConfig, KnobOutput, Motion, Moved, Oscillator, Parameter, Remedy, RestThreshold,
    RubberBand, Scroll, ScrollPhase, Snap, SpringBatch, SpringValue, Stagger, Trail, Tuned, Tuning,
    TuningSlot,
};

/// Compiles only for `T: defmt::Format`.
const fn is_format<T: defmt::Format + ?Sized>() {}

/// Generic types are checked in every backend.
macro_rules! in_every_backend {
    ($($t:ident),* $(,)?) => {
        $(
            is_format::<$t<f32>>();
            is_format::<$t<f64>>();
            is_format::<$t<I16F16>>();
            is_format::<$t<I32F32>>();
        )*
    };
}

// A `const` item: the assertion holds at compile time, without running anything.
const _: () = {
    // Set-up.
    is_format::<Tuning>();
    is_format::<Oscillator>();
    is_format::<RestThreshold>();
    in_every_backend!(Tuned);
    is_format::<Error>();
    is_format::<Parameter>();
    is_format::<Bound>();
    is_format::<Remedy>();
    // Values and batches.
    is_format::<SpringValue<f32, 2>>();
    is_format::<SpringValue<I16F16, 1>>();
    is_format::<SpringValue<I32F32, 3>>();
    is_format::<SpringBatch<f32, 2, 4>>();
    is_format::<SpringBatch<I16F16, 1, 4>>();
    is_format::<BatchIndex>();
    is_format::<Stagger<f32, 2, 4>>();
    is_format::<Moved<f32, 2>>();
    is_format::<TuningSlot>();
    is_format::<SpringBatch<I16F16, 1, 4, 3>>();
    is_format::<Trail<I16F16, 1, 4>>();
    is_format::<BatchMotion>();
    is_format::<Motion>();
    // Throws.
    is_format::<Friction>();
    is_format::<Decay<f32, 2>>();
    is_format::<Decay<I16F16, 1>>();
    // Scrolls.
    is_format::<Bounds<f32>>();
    is_format::<Snap<'static, I16F16>>();
    is_format::<RubberBand>();
    is_format::<Scroll<'static, f32>>();
    is_format::<Scroll<'static, I16F16>>();
    is_format::<ScrollPhase>();
    // The kernel and the backends' formats.
    in_every_backend!(BodyWeights, LinearisedRest);
    is_format::<FloatGains<f32>>();
    is_format::<FixedGains<i32>>();
    is_format::<FixedFactor<i64>>();
    // Length kernels.
    is_format::<Exact>();
    is_format::<Linearised>();
    is_format::<Approximate>();
    is_format::<ApproximateNewton>();
    // `length::HardwareSqrt` exists only on hard-float ARM targets: the firmware build
    // of `examples/cost.rs` asserts it there.
    // Scenes (`scene::AngularScene` is an alias of `Scene` with an angle kernel).
    is_format::<Scene<f32, 2, 8, 7>>();
    is_format::<Scene<I16F16, 2, 8, 7, Linearised>>();
    is_format::<Scene<f32, 1, 4, 3, Angle>>();
    is_format::<Scene<I16F16, 1, 4, 3, WrappedAngle>>();
    is_format::<SceneConfig<f32, 2>>();
    is_format::<SceneConfig<I16F16, 3>>();
    is_format::<SceneMotion>();
    is_format::<Stepper>();
    is_format::<LimitPolicy>();
    is_format::<SleepThreshold>();
    is_format::<ParticleId>();
    is_format::<SpringId>();
    is_format::<Added>();
    is_format::<Angle>();
    is_format::<WrappedAngle>();
    // The knob.
    in_every_backend!(Knob, KnobOutput, KnobDesign);
    is_format::<KnobConfig>();
    is_format::<KnobError>();
    is_format::<KnobEvents>();
    is_format::<Endstop>();
    is_format::<SensorFault>();
    is_format::<Anchor>();
    is_format::<Zone>();
    is_format::<Limit>();
    is_format::<Latency>();
    is_format::<LoopCoefficients>();
};

#[test]
fn every_public_type_is_defmt_format() {
    // The assertions are the `const` item above; reaching this line means they compiled.
}
