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
//! u ← u − (C_k·x + C_d·u)        x ← x + u
//! ```
//!
//! and no mass or time step appears in the loop. This crate adds what the article does
//! not have: the **exact map** from a continuous oscillator (frequency, damping ratio) to
//! `(C_k, C_d)`, which makes the discrete spring hit the continuous trajectory exactly at
//! every sample, for two multiply-adds per step, and fixed-point backends that keep
//! following it at 10 kHz.
//!
//! ```
//! use stiffspring::{Motion, SpringValue, Tuning};
//!
//! let tuning = Tuning::from_frequency(2.0, 0.3, 1.0 / 60.0)?; // 2 Hz, ζ = 0.3, at 60 Hz
//! let mut x = SpringValue::<f32>::new([0.0], &tuning)?;
//! x.set_target([1.0]);
//! assert_eq!(x.step(), Motion::Moving);
//! assert!(x.position()[0] > 0.0);
//! # Ok::<(), stiffspring::Error>(())
//! ```
//!
//! ## Map of the crate
//!
//! - [`Scalar`]: the arithmetic backends (`f32`, `f64`, `I16F16`, `I32F32`).
//! - [`Tuning`]: validated coefficients sampled at a `dt`, and every way to obtain them,
//!   at compile time too ([`tuning!`]); [`Oscillator`]: the continuous description;
//!   [`presets`]: the UI platforms' named springs.
//! - [`SpringValue`], [`SpringBatch`]: values that spring toward targets and report
//!   ([`Motion`], [`BatchMotion`]) when they settle; [`RestThreshold`]: when they count as
//!   settled.
//! - [`Decay`], [`Friction`]: a value thrown without a target, slowed by friction as the
//!   platforms give it, with its resting point known at release.
//! - [`Scroll`]: a scroll offset thrown and dragged by a finger or stepped by a knob,
//!   within [`Bounds`] (a [`RubberBand`] past the ends, a spring back), resting on
//!   [`Snap`] points.
//! - [`Error`]: what set-up can reject, with the parameter, its value and the bound.
//!   Stepping never fails.
//!
//! ## Features
//!
//! | feature | default | what it adds |
//! |---|---|---|
//! | `fixed` | no | the `I16F16` and `I32F32` backends |
//! | `micromath` | no | fast approximate roots for the length kernels |
//! | `hw-sqrt` | no | the `vsqrt.f32` length kernel on Cortex-M4F/M7/M33 (its module is the crate's only `unsafe`) |
//! | `defmt` | no | `defmt::Format` for every public type |
#![no_std]
#![cfg_attr(not(feature = "hw-sqrt"), forbid(unsafe_code))]
#![cfg_attr(feature = "hw-sqrt", deny(unsafe_code))]
#![deny(missing_docs)]
#![warn(clippy::unwrap_used, clippy::expect_used, clippy::panic)]
#![cfg_attr(test, allow(clippy::unwrap_used, clippy::expect_used, clippy::panic))]
// Component loops `for k in 0..D` index several arrays of the same length D at once (a
// position, a velocity, an axis); zipping three or four iterators reads worse.
#![allow(clippy::needless_range_loop)]

mod batch;
mod bounds;
mod decay;
mod error;
mod friction;
mod input;
pub mod kernel;
pub mod knob;
pub mod length;
mod math;
mod motion;
mod rest;
mod rubber_band;
pub mod scalar;
pub mod scene;
mod scroll;
mod snap;
mod start;
mod tuning;
mod value;

pub use batch::{BatchIndex, BatchMotion, Moved, SpringBatch, Stagger, Trail, TuningSlot};
pub use bounds::Bounds;
pub use decay::Decay;
pub use error::{Bound, Error, Parameter, Remedy};
pub use friction::Friction;
pub use knob::{Knob, KnobConfig, KnobOutput};
pub use motion::Motion;
pub use rest::RestThreshold;
pub use rubber_band::RubberBand;
pub use scalar::Scalar;
pub use scroll::{Scroll, ScrollPhase};
pub use snap::Snap;
pub use tuning::{MAX_SETTLING_STEPS, Oscillator, Tuned, Tuning, presets};
pub use value::SpringValue;

/// Re-export of the fixed-point types the backends are implemented for.
#[cfg(feature = "fixed")]
pub use fixed::types::{I16F16, I32F32};

/// The README's examples run as doctests.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
struct ReadmeDoctests;
