//! The Cortex-M4F/M7/M33 hardware square root, `vsqrt.f32`.
//!
//! `f32::sqrt` is not in `core` on stable Rust, and LLVM only emits `vsqrt` for it, so the
//! instruction is reached through a two-instruction function in `global_asm!`. Calling
//! it is the crate's only `unsafe`, confined to this module and to builds with the
//! `hw-sqrt` feature on a hard-float ARM target.
#![allow(unsafe_code)]

use super::{LengthKernel, Sealed};
use crate::scalar::Scalar;

core::arch::global_asm!(
    ".section .text.stiffspring_vsqrt,\"ax\",%progbits",
    ".global stiffspring_vsqrt",
    ".type stiffspring_vsqrt,%function",
    // The block is assembled with the FPU of the Cortex-M4F; M7 and M33 are supersets.
    ".fpu fpv4-sp-d16",
    ".thumb_func",
    "stiffspring_vsqrt:",
    "vsqrt.f32 s0, s0",
    "bx lr",
    ".size stiffspring_vsqrt, . - stiffspring_vsqrt",
);

unsafe extern "C" {
    /// `√x` by `vsqrt.f32` (eabihf: argument and result in `s0`).
    fn stiffspring_vsqrt(x: f32) -> f32;
}

/// The correctly rounded square root by the FPU.
#[inline(always)]
fn vsqrt(x: f32) -> f32 {
    // SAFETY: the function reads s0 and writes s0, touches no memory, and is defined
    // above for exactly this signature under the hard-float calling convention.
    unsafe { stiffspring_vsqrt(x) }
}

/// [`Exact`](super::Exact) for `f32` with the root from `vsqrt.f32` instead of `libm`.
///
/// Only on hard-float ARM targets with the `hw-sqrt` feature, so the example is not run
/// on the host:
///
/// ```ignore
/// use stiffspring::length::HardwareSqrt;
/// use stiffspring::scene::{Scene, SceneConfig};
/// let rope = Scene::<f32, 2, 16, 15, HardwareSqrt>::new(SceneConfig::new(1.0 / 240.0)?);
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct HardwareSqrt;

impl Sealed for HardwareSqrt {}

impl LengthKernel<f32> for HardwareSqrt {
    type Rest = f32;
    const NAME: &'static str = "vsqrt";

    fn rest(length: f32) -> Self::Rest {
        length
    }

    fn rest_length(rest: &Self::Rest) -> f32 {
        *rest
    }

    #[inline(always)]
    fn measure<const D: usize>(d: &[f32; D], rest: &Self::Rest) -> (f32, [f32; D]) {
        let length = vsqrt(<f32 as Scalar>::dot(d, d));
        let inverse = if length > 0.0 { 1.0 / length } else { 0.0 };
        (length - rest, d.map(|d| d * inverse))
    }
}
