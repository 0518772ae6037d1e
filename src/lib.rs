//! # stiffspring
//!
//! Stiff, unconditionally stable springs for microcontrollers: the detents and endstops of
//! a haptic knob at a 1–10 kHz control loop, and UI values springing to their targets at
//! 60–120 Hz. `no_std`, no allocation, no `unsafe` (except the opt-in `hw-sqrt` kernel);
//! `f32`, `f64` or fixed point.
//!
//! The spring is the one of *Towards a simpler, stiffer, and more stable spring*: instead
//! of raw `k` and `d`, a spring has two coefficients `C_k, C_d ∈ [0, 1]` that are fractions
//! of the stiffest and most damped spring one time step can express,
//! `k_max = m/dt²` and `d_max = m/dt`. With the velocity stored per step, `u = v·dt`, one
//! step of a spring is
//!
//! ```text
//! u ← (1 − C_d)·u − C_k·x        x ← x + u
//! ```
//!
//! and no mass or time step appears in the loop. This crate adds what the article does
//! not have: the **exact map** from a continuous oscillator (frequency, damping ratio) to
//! `(C_k, C_d)`, which makes the discrete spring hit the continuous trajectory exactly at
//! every sample, for two multiply-adds per step.
//!
//! ```
//! use stiffspring::{SpringValue, Tuning};
//!
//! let dt = 1.0 / 60.0;
//! let tuning = Tuning::from_frequency(2.0, 0.3, dt)?; // 2 Hz, ζ = 0.3
//! let mut x = SpringValue::<f32, 1>::new([0.0], tuning, dt)?;
//! x.set_target([1.0])?;
//! x.step();
//! assert!(x.position()[0] > 0.0);
//! # Ok::<(), stiffspring::Error>(())
//! ```
//!
//! ## Map of the crate
//!
//! - [`Scalar`]: the arithmetic backends (`f32`, `f64`, `I16F16`, `I32F32`).
//! - [`Tuning`]: validated coefficients, and every way to obtain them; [`Oscillator`]: the
//!   continuous description (with `libm`).
//! - [`kernel`]: the two-body kernel every spring in the crate runs through.
//! - [`SpringValue`], [`SpringBatch`]: values that spring toward targets; [`RestThreshold`]:
//!   when they count as settled.
//! - [`Knob`], [`KnobConfig`]: a haptic knob (detents, endstops, magnetic detents, a
//!   return spring) run from the measured angle in a 1–10 kHz control loop, inside the
//!   closed-loop stability region of a sampled rotor ([`knob::stability`]).
//! - [`Error`]: what set-up can reject. Stepping never fails.
//!
//! ## Features
//!
//! | feature | default | what it adds |
//! |---|---|---|
//! | `libm` | yes | the exact map, presets, analytic fling ([`Oscillator`]) |
//! | `fixed` | no | the `I16F16` and `I32F32` backends |
//! | `micromath` | no | fast approximate roots for the length kernels |
//! | `hw-sqrt` | no | the `vsqrt.f32` length kernel on Cortex-M4F/M7/M33 (the only `unsafe`) |
//! | `defmt` | no | `defmt::Format` for every public type |
#![no_std]
// The only `unsafe` is the call into the `vsqrt.f32` routine of `length::hardware`,
// compiled only with the `hw-sqrt` feature; everywhere else it is forbidden outright.
#![cfg_attr(not(feature = "hw-sqrt"), forbid(unsafe_code))]
#![cfg_attr(feature = "hw-sqrt", deny(unsafe_code))]
#![deny(missing_docs)]
#![warn(clippy::unwrap_used, clippy::expect_used, clippy::panic)]
#![cfg_attr(test, allow(clippy::unwrap_used, clippy::expect_used, clippy::panic))]

mod batch;
mod error;
pub mod kernel;
pub mod knob;
pub mod length;
mod rest;
mod sampling;
mod scalar;
pub mod scene;
mod tuning;
mod value;

pub use batch::SpringBatch;
pub use error::{Error, Parameter};
pub use knob::{Knob, KnobConfig, KnobOutput};
pub use rest::RestThreshold;
pub use scalar::Scalar;
pub use tuning::Tuning;
#[cfg(feature = "libm")]
pub use tuning::{AndroidDamping, AndroidStiffness, Oscillator, ReactSpringPreset, SwiftUiPreset};
pub use value::{SpringValue, SpringValue1};

/// Re-export of the fixed-point types the backends are implemented for.
#[cfg(feature = "fixed")]
pub use fixed::types::{I16F16, I32F32};

/// The README's examples run as doctests.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
struct ReadmeDoctests;
