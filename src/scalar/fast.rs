//! The fixed-point step's fast path: gains prepared at set-up so that a step in the
//! common case (kHz-rate and UI springs, states well inside their range) is two long
//! multiplies per product and no saturation test. Bit for bit the same results as the
//! general path in the `wide` module, which the cases outside it take in `I32F32`. In
//! `I16F16` they take the lifted step, which scales the state up by a power of two so
//! that a gain of up to 4 has the fast form, and scales a state beyond `2^16` units
//! down into that range: `I16F16` links no general product.

use super::raw_state::narrow_takes;

/// A gain prepared at set-up for the fast path of the step, [`narrow_step::product`].
///
/// It stands for `C = mantissa / 2^(32 + k)` with `0 < mantissa < 2³¹` and
/// `2 ≤ k ≤ 31` (`2⁻³³ ≤ C < 2⁻³`), or `C = 0`: the gains of a spring stepped at a
/// kilohertz rate and of most UI springs. `bias = 2^k − 1`; `scale = 2^(32 − k)` ends
/// the shift by `k` with a long multiply where that is cheaper than a 64-bit shift (ARM
/// with `umull`), `k` and `32 − k` end it with two 32-bit shifts elsewhere.
#[derive(Clone, Copy, Debug, PartialEq, Default)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub(crate) struct FastFactor<M> {
    pub(crate) mantissa: M,
    pub(crate) bias: M,
    pub(crate) scale: M,
    pub(crate) k: Shift,
    pub(crate) complement: Shift,
    /// The mantissa's 16-bit halves, for the products on a Cortex-M0.
    pub(crate) halves: [u16; 2],
}

/// A shift amount below 32. As an enum its loads carry their range, so a shift by it
/// needs no `& 31` (a Cortex-M0 would spend two instructions on each). Two bytes wide,
/// so that a [`FastFactor<i32>`] is 20 bytes of fields and no padding: with one byte
/// each, moving a factor at run-time set-up copied its 18 bytes with `memcpy` (730
/// bytes of flash on the Cortex-M4F, `scripts/capi-size`).
#[derive(Clone, Copy, Debug, PartialEq, Default)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[repr(u16)]
#[rustfmt::skip]
pub(crate) enum Shift {
    #[default]
    S0 = 0, S1, S2, S3, S4, S5, S6, S7, S8, S9, S10, S11, S12, S13, S14, S15, S16, S17,
    S18, S19, S20, S21, S22, S23, S24, S25, S26, S27, S28, S29, S30, S31,
}

impl Shift {
    /// `n` as a `Shift`, for `n < 32`.
    fn new(n: u32) -> Shift {
        use Shift::*;
        #[rustfmt::skip]
        const ALL: [Shift; 32] = [
            S0, S1, S2, S3, S4, S5, S6, S7, S8, S9, S10, S11, S12, S13, S14, S15, S16, S17,
            S18, S19, S20, S21, S22, S23, S24, S25, S26, S27, S28, S29, S30, S31,
        ];
        ALL[n as usize & 31]
    }

    #[inline(always)]
    pub(crate) fn get(self) -> u32 {
        self as u32
    }
}

/// Both gains of a spring prepared for the fast path, and the bound on the state under
/// which that path cannot overflow: in `I16F16` it is `2²⁵` (states of `−2^56 ≤ s <
/// 2^56`, as the lifted step's) when both gains have the fast form without a lift, and 0
/// (no state passes) otherwise; in `I32F32`, `2⁶²` or 0.
#[derive(Clone, Copy, Debug, PartialEq, Default)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub(crate) struct FastGains<M> {
    pub(crate) stiffness: FastFactor<M>,
    pub(crate) damping: FastFactor<M>,
    pub(crate) headroom: M,
}

/// How the fast path multiplies and shifts, chosen per target (every mode computes the
/// same values, and the tests run all of them on the host):
/// - `NATIVE`: 64-bit multiplies and shifts (64-bit machines);
/// - `SCALE`: ARM with a long multiply (`umull`/`smlal`: all but ARMv6-M and ARMv8-M
///   Baseline), where the shift by `k` is cheaper as a multiply by `2^(32−k)`;
/// - `SMALL`: a multiplier of 32×32 → 32 bits only (Cortex-M0): long products from
///   16-bit halves, the shift as two 32-bit shifts.
pub(crate) mod mode {
    pub(crate) const NATIVE: u8 = 0;
    pub(crate) const SCALE: u8 = 1;
    pub(crate) const SMALL: u8 = 2;
    pub(crate) const TARGET: u8 = if cfg!(no_long_multiply) {
        SMALL
    } else if cfg!(target_arch = "arm") {
        SCALE
    } else {
        NATIVE
    };
}

macro_rules! no_fast_path {
    ($M:ty) => {
        impl FastGains<$M> {
            /// Gains the fast path does not take (headroom 0): written out, so that a
            /// `const` tuning off the fast path stores zeros in place (its `Default`, built
            /// as a temporary, was copied in with `memcpy`, 742 bytes of flash on the
            /// Cortex-M4F).
            const NONE: Self = FastGains {
                stiffness: FastFactor::<$M>::NONE,
                damping: FastFactor::<$M>::NONE,
                headroom: 0,
            };
        }
        impl FastFactor<$M> {
            /// A factor of no fast form. Its shifts are unused (the headroom of 0 keeps
            /// the fast path off) but not zero (`k = 2` and `32 − 2`, the narrow form of
            /// `C = 0`'s), so that the gains hold no long run of zeros, which LLVM
            /// clears with `__aeabi_memclr8` (174 bytes on the Cortex-M4F).
            const NONE: Self = FastFactor {
                mantissa: 0,
                bias: 0,
                scale: 0,
                k: Shift::S2,
                complement: Shift::S30,
                halves: [0, 0],
            };
        }
    };
}
no_fast_path!(i32);
no_fast_path!(i64);

impl FastGains<i32> {
    /// The fast form of the narrow gains `(mantissa, shift)`, or none (headroom 0).
    ///
    /// A gain `C = m/2^(32 + k)` of `k ≥ 2` is in the form of the fast step, which
    /// then runs wherever the state is within its headroom. A gain of `k < 2`
    /// (`C ≥ 2⁻³`: the damping of a UI spring at 60 Hz) is stored in the form of `k = 2`
    /// and the gains' headroom is 0: the lifted step ([`narrow_step::advance_lifted`]),
    /// which multiplies the state by `2^(2 − k)` first ([`narrow_step::lift`]), takes
    /// it. Gains that [`narrow_takes`] refuses (`C_k ≥ 4`, `C_d ≥ 2`, negative, or below
    /// `2⁻³³`) have no form; set-up refuses them too.
    pub(crate) fn narrow(stiffness: (i32, i32), damping: (i32, i32)) -> Self {
        if !narrow_takes(
            (stiffness.0 as i64, stiffness.1),
            (damping.0 as i64, damping.1),
        ) {
            return Self::NONE;
        }
        // The factor (`narrow_takes` bounds its `k` to 31 and, lifted, to 2) and whether
        // it is lifted.
        let factor = |(m, shift): (i32, i32)| -> (FastFactor<i32>, bool) {
            // C = 0: any form gives 0; take k = 2.
            let k = if m == 0 { 2 } else { shift - 32 };
            let lifted = k < 2;
            // The lifted step multiplies the state by 2^(2 − k) first (`narrow_step::lift`).
            let k = k.max(2) as u32;
            (
                FastFactor {
                    mantissa: m,
                    bias: ((1u32 << k) - 1) as i32,
                    scale: 1i32 << (32 - k),
                    k: Shift::new(k),
                    complement: Shift::new(32 - k),
                    halves: [m as u16, (m >> 16) as u16],
                },
                lifted,
            )
        };
        let ((stiffness, lifted_k), (damping, lifted_d)) = (factor(stiffness), factor(damping));
        FastGains {
            stiffness,
            damping,
            headroom: if lifted_k || lifted_d {
                0
            } else {
                narrow_step::RANGE
            },
        }
    }
}

impl FastGains<i64> {
    /// The fast form of the broad gains `(mantissa, shift)`: as [`FastGains::narrow`]
    /// with 64-bit words, `C = mantissa / 2^(64 + k)`, `2 ≤ k ≤ 63`. The 128-bit shift
    /// by `k` is one shift: `k` holds `k mod 32` and `complement` holds `⌊k/32⌋`, which
    /// tells the compiler that the amount is below 64 (no masking); `scale` is unused.
    pub(crate) fn broad(stiffness: (i64, i32), damping: (i64, i32)) -> Self {
        let factor = |(m, shift): (i64, i32)| -> Option<FastFactor<i64>> {
            let (m, k) = if m == 0 { (0, 2) } else { (m, shift - 64) };
            if m < 0 || !(2..=63).contains(&k) {
                return None;
            }
            let k = k as u32;
            Some(FastFactor {
                mantissa: m,
                bias: ((1u64 << k) - 1) as i64,
                scale: 0,
                k: Shift::new(k & 31),
                complement: Shift::new(k >> 5),
                halves: [0, 0],
            })
        };
        match (factor(stiffness), factor(damping)) {
            (Some(stiffness), Some(damping)) => FastGains {
                stiffness,
                damping,
                headroom: 1 << 62,
            },
            _ => Self::NONE,
        }
    }
}

/// The step's fast path for the broad state (`I32F32`): [`narrow_step`] with every word
/// twice as wide.
pub(crate) mod broad_step {
    use super::{FastFactor, FastGains};

    /// `x·C` rounded toward zero or away from it, for a gain in fast form: the value of
    /// `broad::mul_shift::<AWAY>(x, m, 64 + k)`, as `narrow_step::product`.
    #[inline(always)]
    pub(crate) fn product<const AWAY: bool>(x: i128, f: &FastFactor<i64>) -> i128 {
        let (xh, xl) = ((x >> 64) as i64, x as u64);
        let negative = (xh >> 63) as u64;
        let up = if AWAY { !negative } else { negative };
        let bias = ((((f.bias as u64) & up) as u128) << 64) | up as u128;
        let low = xl as u128 * f.mantissa as u64 as u128 + bias;
        let t = xh as i128 * f.mantissa as i128 + (low >> 64) as i128;
        t >> (f.k.get() + 32 * f.complement.get())
    }

    /// One step in the fast form, or `false` (nothing changed): as
    /// `narrow_step::advance`, with `|x|, |ũ| < 2^125`.
    #[inline(always)]
    pub(crate) fn advance(g: &FastGains<i64>, x: &mut i128, v: &mut i128) -> bool {
        let (x0, v0) = (*x, *v);
        let probe =
            ((x0 >> 64) as u64).wrapping_add(1 << 61) | ((v0 >> 64) as u64).wrapping_add(1 << 61);
        if probe >= g.headroom as u64 {
            return false;
        }
        let u = v0.wrapping_sub(product::<false>(x0, &g.stiffness));
        *x = x0.wrapping_add(u);
        *v = u.wrapping_sub(product::<true>(u, &g.damping));
        true
    }
}

/// The step's fast path for the narrow state (`I16F16`).
pub(crate) mod narrow_step {
    use super::{FastFactor, FastGains, mode};

    /// `a·m` for `0 ≤ m < 2³¹`, exactly, on a Cortex-M0, which multiplies 32×32 → 32
    /// bits only: four products of 16-bit halves, each placed with one 64-bit add
    /// (`__aeabi_lmul` would take all 64×64 bits).
    #[inline(always)]
    fn umul_small(a: u32, [m0, m1]: [u16; 2]) -> u64 {
        let (m0, m1) = (m0 as u32, m1 as u32);
        let (a0, a1) = (a & 0xffff, a >> 16);
        let ends = ((a1 * m1) as u64) << 32 | (a0 * m0) as u64;
        ends + (((a1 * m0) as u64) << 16) + (((a0 * m1) as u64) << 16)
    }

    /// `a·m` for a signed `a` and `0 ≤ m < 2³¹`, as [`umul_small`].
    #[inline(always)]
    fn smul_small(a: i32, [m0, m1]: [u16; 2]) -> i64 {
        let (m0, m1) = (m0 as u32, m1 as u32);
        // `a1` keeps the sign; |a1·m0| < 2^31.
        let (a0, a1) = (a as u32 & 0xffff, a >> 16);
        let ends = (((a1 * m1 as i32) as i64) << 32) | (a0 * m0) as i64;
        ends + (((a1 * m0 as i32) as i64) << 16) + (((a0 * m1) as i64) << 16)
    }

    /// `x·C` rounded toward zero (`AWAY = false`) or away from zero (`AWAY = true`),
    /// for a gain `C = m/2^(32+k)` in fast form: the same value as
    /// `narrow::mul_shift::<AWAY>(x, m, 32 + k)`.
    ///
    /// With `p = x·m` and `s = 32 + k`, the rounded quotient is `⌊(p + B)/2^s⌋` with
    /// `B = 2^s − 1` when it rounds up (`p < 0` toward zero, `p ≥ 0` away from it;
    /// `m ≥ 0`, so the sign of `p` is the sign of `x` where `p ≠ 0`) and `B = 0`
    /// otherwise. `B`'s low word is the sign mask and its high word `2^k − 1` masked,
    /// so `t = ⌊(p + B)/2^32⌋ = xₕ·m + ⌊(xₗ·m + B)/2^32⌋` takes one `umlal` and one
    /// `smlal` on a Cortex-M4, and the result is `⌊t/2^k⌋`.
    #[inline(always)]
    pub(crate) fn product<const AWAY: bool>(x: i64, f: &FastFactor<i32>) -> i64 {
        product_in::<AWAY, { mode::TARGET }>(x, f)
    }

    /// [`product`] computed the way `MODE` says.
    #[inline(always)]
    pub(crate) fn product_in<const AWAY: bool, const MODE: u8>(x: i64, f: &FastFactor<i32>) -> i64 {
        let (xh, xl) = ((x >> 32) as i32, x as u32);
        // The sign mask from the whole word: it lets LLVM fold `!negative` into `mvn`
        // and `bic` on the Cortex-M4 (from `xh` it builds a compare and an `it` block,
        // 3 instructions more per step); from `xh` on the Cortex-M0 (6 fewer there).
        let negative = if MODE == mode::SMALL {
            (xh >> 31) as u32
        } else {
            (x >> 63) as u32
        };
        let up = if AWAY { !negative } else { negative };
        if MODE == mode::SMALL {
            let bias = ((((f.bias as u32) & up) as u64) << 32) | up as u64;
            let low = umul_small(xl, f.halves) + bias;
            let t = smul_small(xh, f.halves) + (low >> 32) as i64;
            let (th, tl) = ((t >> 32) as i32, t as u32);
            // ⌊t/2^k⌋ in two 32-bit shifts and an `or`: no call to `__aeabi_lasr`.
            let ql = (tl >> f.k.get()) | ((th as u32) << f.complement.get());
            let qh = th >> f.k.get();
            return ((qh as i64) << 32) | ql as i64;
        }
        // B as a 64-bit word; xₗ·m < 2^63 and B < 2^63 (k ≤ 31): the sum fits (`umlal`).
        let bias = ((((f.bias as u32) & up) as u64) << 32) | up as u64;
        let low = xl as u64 * f.mantissa as u32 as u64 + bias;
        let t = xh as i64 * f.mantissa as i64 + (low >> 32) as i64;
        if MODE == mode::SCALE {
            // ⌊t/2^k⌋ = tₕ·2^(32−k) + ⌊tₗ·2^(32−k)/2^32⌋ (2^(32−k) ≤ 2^30): `umull` and
            // `smlal`, cheaper than a 64-bit shift by a variable amount.
            let (th, tl) = ((t >> 32) as i32, t as u32);
            th as i64 * f.scale as i64 + ((tl as u64 * f.scale as u32 as u64) >> 32) as i64
        } else {
            t >> f.k.get()
        }
    }

    /// The lift `j` of a gain of shift `shift` (`C = m/2^shift`): the power of two the
    /// lifted step multiplies the state by, so that `shift + j ≥ 34` (the fast form's
    /// `k ≥ 2`). At most 5, for a stiffness just below 4 (`shift = 29`); 0 from `k = 2`
    /// up. A zero gain (shift 0) gets 5, harmlessly: its product is 0 whatever the
    /// state, wrapped or not.
    #[inline(always)]
    pub(crate) fn lift(shift: i32) -> u32 {
        (34 - shift).clamp(0, 5) as u32
    }

    /// `x·2^j` (`j ≤ 5`; wrapping), computed the way `MODE` says.
    #[inline(always)]
    pub(crate) fn lift_in<const MODE: u8>(x: i64, j: u32) -> i64 {
        if MODE == mode::NATIVE {
            x.wrapping_shl(j)
        } else {
            // Two 32-bit shifts per word, `(l >> 1) >> (31 − j)` being `l >> (32 − j)`
            // with both amounts below 32, also for `j = 0`: six instructions on a
            // Cortex-M4, where LLVM's 64-bit shift by a register takes nine (it also
            // covers `j ≥ 32`), and turns a multiply by `2^j` back into that shift.
            let (h, l) = ((x >> 32) as u32, x as u32);
            let high = (h << j) | ((l >> 1) >> (31 - j));
            ((high as i64) << 32) | (l << j) as i64
        }
    }

    /// [`product`] of a gain of lift `j`, for `|x| < 2^58`: `x·C = (x·2^j)·m/2^(shift + j)`
    /// rounded the same way, since both quotients are the same rational number.
    #[inline(always)]
    pub(crate) fn lifted_product_in<const AWAY: bool, const MODE: u8>(
        x: i64,
        j: u32,
        f: &FastFactor<i32>,
    ) -> i64 {
        product_in::<AWAY, MODE>(lift_in::<MODE>(x, j), f)
    }

    /// The bound of [`range_probe`] for the states every `I16F16` step takes: both
    /// `x` and `ũ` 57-bit integers, `−2^56 ≤ s < 2^56` (`2^16` units of an `I16F16`
    /// position, which the offset between two positions stays within). The fast
    /// step's headroom where it takes the gains.
    pub(crate) const RANGE: i32 = 1 << 25;

    /// `sₕ + 2^24` of `x` and of `ũ` (unsigned) at once, with an `or`: below [`RANGE`]
    /// exactly when both are within `−2^56 ≤ s < 2^56`.
    #[inline(always)]
    fn range_probe(x: i64, v: i64) -> u32 {
        ((x >> 32) as u32).wrapping_add(1 << 24) | ((v >> 32) as u32).wrapping_add(1 << 24)
    }

    /// Whether the lifted step takes `(x, ũ)` as it is ([`RANGE`]).
    #[inline(always)]
    pub(crate) fn liftable(x: i64, v: i64) -> bool {
        range_probe(x, v) < RANGE as u32
    }

    /// `(x, ũ)` halved together (rounded toward −∞) until [`liftable`]: the same
    /// spring's motion from a smaller start, in the same direction. A stable spring's
    /// orbit decays, and each halving halves the largest state that orbit reaches after
    /// it, so a spring that grows past `2^16` units (a tuning beyond the article's square
    /// started near an end of the range) still comes to rest; clipping each component
    /// on its own turned such a spring into a limit cycle (`C_k = 3.45`, `C_d = 0.23`,
    /// `tests/single_spring_stability.rs`).
    #[inline(always)]
    pub(crate) fn scale_into_range(mut x: i64, mut v: i64) -> (i64, i64) {
        while !liftable(x, v) {
            (x, v) = (x >> 1, v >> 1);
        }
        (x, v)
    }

    /// One step of any gains [`narrow_takes`](super::super::raw_state::narrow_takes)
    /// takes, of shifts `shifts` (stiffness, damping), from any state: a state outside
    /// `[−2^56, 2^56)` is first scaled into it ([`scale_into_range`]), which is how the
    /// `I16F16` step saturates.
    ///
    /// With `|x|, |ũ| ≤ 2^56`, `C_k < 4` and `C_d < 2`: `|x·2^j| < 2^61` (`j ≤ 5`),
    /// `|C_k·x| < 2^58`, `|u| < 2^59`, `|x + u| < 2^60`, `|u·2^j| < 2^63` (`j ≤ 4` for a
    /// damping below 2), and `C_d·u` rounded away from zero is at most `2|u| + 1`, so
    /// that `|u − C_d·u| ≤ |u| + 1`: nothing overflows.
    #[inline(always)]
    pub(crate) fn advance_lifted(g: &FastGains<i32>, shifts: (i32, i32), x: &mut i64, v: &mut i64) {
        advance_lifted_in::<{ mode::TARGET }>(g, shifts, x, v)
    }

    /// [`advance_lifted`] computed the way `MODE` says.
    #[inline(always)]
    pub(crate) fn advance_lifted_in<const MODE: u8>(
        g: &FastGains<i32>,
        (stiffness_shift, damping_shift): (i32, i32),
        x: &mut i64,
        v: &mut i64,
    ) {
        let (x0, v0) = scale_into_range(*x, *v);
        let (jk, jd) = (lift(stiffness_shift), lift(damping_shift));
        let u = v0.wrapping_sub(lifted_product_in::<false, MODE>(x0, jk, &g.stiffness));
        *x = x0.wrapping_add(u);
        *v = u.wrapping_sub(lifted_product_in::<true, MODE>(u, jd, &g.damping));
    }

    /// One step `u = ũ − C_k·x; x += u; ũ = u − C_d·u` in the fast form, or `false`
    /// (nothing changed) when the gains have none or the state is outside the
    /// headroom.
    ///
    /// The headroom is the lifted step's range, `−2^56 ≤ x, ũ < 2^56` (2¹⁶ units), so
    /// that every `I16F16` step scales a state beyond it the same way, whatever its gains
    /// ([`scale_into_range`]). There, with both gains below 2⁻³: `|C_k·x| < 2^53`,
    /// `|u| < 2^57`, `|x + u| < 2^58`, and `C_d·u` rounded away from zero lies between 0
    /// and `u`: nothing can overflow, so plain adds give the saturating ones' results
    /// without their tests.
    #[inline(always)]
    pub(crate) fn advance(g: &FastGains<i32>, x: &mut i64, v: &mut i64) -> bool {
        let (x0, v0) = (*x, *v);
        if range_probe(x0, v0) >= g.headroom as u32 {
            return false;
        }
        let u = v0.wrapping_sub(product::<false>(x0, &g.stiffness));
        *x = x0.wrapping_add(u);
        *v = u.wrapping_sub(product::<true>(u, &g.damping));
        true
    }
}
