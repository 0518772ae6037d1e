//! The precision study of issue 10: one spring, `u ← u − a, x ← x + u`, started on an analytic
//! damped-oscillator trajectory and measured against it.
//!
//! Everything works in *step units*: time is counted in steps (`dt = 1`), so the map and the
//! reference depend only on `θ = 2π·f·dt` and `ζ`. Two grid points with the same `f·dt` give
//! the same numbers.
//!
//! - The reference is the analytic solution of `x'' + 2ζω·x' + ω²·x = 0` with `ω = θ` per
//!   step ([`Analytic`]).
//! - The exact sampled map ([`Coefs::exact`]) has `C_d = 1 − z₁z₂`, `C_k = (1 − z₁)(1 − z₂)`,
//!   `z_i = e^{s_i}`, in cancellation-free forms. Started with `u₀ = x(0) − x(−1)` it
//!   reproduces the analytic samples (tested to 1e-12 below).
//! - The fixed-point models are bit-exact integer models (`i128`, and a 256-bit accumulator
//!   for the I32F32 wide state); the float models use `f32`/`f64` with no fused operations.
//!
//! Candidates (names as published):
//!
//! | name | backend | state | coefficients | step |
//! |---|---|---|---|---|
//! | `truncate` | I16F16 / I32F32 | Q16.16 / Q32.32 | Q3.29 / Q3.61 of `C_k`, `1 − C_d` | `u ← (1−C_d)u − C_k x`, rounded once toward zero |
//! | `remainder-floor` | " | " | " | same sum plus the last remainder, floored; the remainder (in `[0, 1)` LSB) carried |
//! | `remainder-centred` | " | " | " | same, rounded to nearest; remainder in `[−½, ½)` LSB carried |
//! | `wide-G` | " | G guard bits | 31-/63-bit mantissas, one shared shift | `a = C_k x + C_d u` rounded toward zero, `u ← u − a` |
//! | `wide-G-nearest`, `wide-G-floor` | " | " | " | `a` rounded half up / toward −∞ |
//! | `wide-G-utrunc` | " | " | " | the new `u` (not `a`) rounded toward zero: the r-form's rounding, in delta form |
//! | `wide-24-approx-lo` | I16F16 | Q24.40 | " | as `wide-24`, with `m·x_lo ≈ (x_lo >> 16)·(m >> 16)·2¹⁶` |
//! | `r-form`, `delta` | f32, f64 | float | float | `u ← r·u − k·x` / `u ← u − (k·x + d·u)` |
//! | `delta+comp-x` | f32 | `x` + Fast2Sum error term | f32 | delta, `x ← x + u` compensated |
//! | `delta+split-k` | f32 | f32 | `C_k = k_hi + k_lo` | `a = k_hi·x + (k_lo·x + d·u)` |
//! | `delta+comp-x+split-k` | f32 | both | both | both |
//! | `kept` | I16F16 / I32F32 | `x` and the kept step velocity `ũ = (1−C_d)u`, Q24.40 in `i64` / Q64.64 in `i128` | `C_k`, `C_d` each its own 31-/63-bit mantissa and shift | `u ← ũ − round_k(C_k x)`, `x ← x + u`, `ũ ← u − round_d(C_d u)`; spring toward zero, damping away from zero |
//! | `kept-zero`, `kept-nearest` | " | " | " | both terms toward zero / both to nearest (half up) |
//! | `kept` | f32, f64 | float | float | the same with IEEE rounding |
//!
//! `kept` starts from `ũ₀ = P̃·x₀ + Q̃·v₀` ([`kept_pq`]), never from `u₀`: the tracking grids run it
//! exactly like the others; the ill-conditioned table shows it needs no step ahead; and
//! [`claim_search`] asks whether every damped start ends at rest.
//!
//! The user reads a wide state through round-half-up to the visible format.

//!
//! `cargo run --release -p stiffspring-lab --bin precision` prints the tables of the full
//! grid (`--quick` the short one) and writes their CSV files to `target/precision/`.
//!
//! | module | what it holds |
//! |---|---|
//! | `reference` | [`Coefs`], [`Analytic`], [`kept_pq`], [`Start`] |
//! | `int` | [`Round`], [`shr_round`], [`I256`], [`mantissa`], [`mantissas`] |
//! | `steppers` | [`Stepper`] and the candidates' models: [`RForm`], [`Wide`], [`F32`], [`F64`], [`Kept`], [`KeptF32`], [`KeptF64`] |
//! | `candidates` | [`Backend`], [`Cand`], [`candidates`], [`dispatch`] |
//! | `measure` | [`Track`], [`Amplitude`], [`Settle`] |
//! | `grid` | [`Grid`], [`fixed_grid`], [`float_grid`], [`undamped`], [`limit_cycles`] |
//! | `claim` | [`kept_settle`], [`claim_search`] |
//! | `report` | [`Study`], [`study`] |

use std::f64::consts::PI;

mod candidates;
mod claim;
mod grid;
mod int;
mod measure;
mod reference;
mod report;
mod steppers;
#[cfg(test)]
mod tests;

pub use candidates::*;
pub use claim::*;
pub use grid::*;
pub use int::*;
pub use measure::*;
pub use reference::*;
pub use report::*;
pub use steppers::*;
