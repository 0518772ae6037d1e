//! The exact double-width product of two integers of the fixed-point backends.
//!
//! A Cortex-M4 has `smull` and `umull` (32×32 → 64 bits). A Cortex-M0 (ARMv6-M, and
//! ARMv8-M Baseline) multiplies 32×32 → 32 bits only, and for a 64-bit product LLVM calls
//! `__aeabi_lmul`, a full 64×64 multiply: 38 instructions, the call, and the sign
//! extension of both arguments. With four 32-bit multiplies of 16-bit halves the same
//! product is about 20 instructions inline. The results are exact either way, so every
//! target computes the same bits.

/// `a·b` for 32-bit signed `a` and `b`, exactly.
#[inline(always)]
pub(crate) fn mul_i32(a: i32, b: i32) -> i64 {
    if cfg!(no_long_multiply) {
        mul_i32_halves(a, b)
    } else {
        a as i64 * b as i64
    }
}

/// `a·b` for an unsigned 32-bit `a` and a signed 32-bit `b`, exactly.
#[inline(always)]
pub(crate) fn mul_u32_i32(a: u32, b: i32) -> i64 {
    if cfg!(no_long_multiply) {
        mul_u32_i32_halves(a, b)
    } else {
        a as i64 * b as i64
    }
}

/// [`mul_i32`] from 32-bit products: with `a = a₁·2¹⁶ + a₀` (`a₁` signed,
/// `0 ≤ a₀ < 2¹⁶`) and `b` alike, every partial product fits 32 bits: `|a₁·b₁| ≤ 2³⁰`,
/// `|a₁·b₀|, |a₀·b₁| < 2³¹`, `0 ≤ a₀·b₀ < 2³²`.
#[inline(always)]
fn mul_i32_halves(a: i32, b: i32) -> i64 {
    let (a1, a0) = (a >> 16, a & 0xffff);
    let (b1, b0) = (b >> 16, b & 0xffff);
    let ends = (((a1 * b1) as i64) << 32) | (a0 as u32 * b0 as u32) as i64;
    ends + (((a1 * b0) as i64) << 16) + (((a0 * b1) as i64) << 16)
}

/// [`mul_u32_i32`] from 32-bit products, as [`mul_i32_halves`] with `a₁` unsigned:
/// `|a₁·b₁|, |a₀·b₁| < 2³¹`, `0 ≤ a₁·b₀, a₀·b₀ < 2³²`.
#[inline(always)]
fn mul_u32_i32_halves(a: u32, b: i32) -> i64 {
    let (a1, a0) = ((a >> 16) as i32, (a & 0xffff) as i32);
    let (b1, b0) = (b >> 16, (b & 0xffff) as u32);
    let ends = (((a1 * b1) as i64) << 32) | (a0 as u32 * b0) as i64;
    ends + (((a1 as u32 * b0) as i64) << 16) + (((a0 * b1) as i64) << 16)
}

/// `a·b` for 64-bit signed `a` and `b` (`I32F32`), exactly: the compiler's 128-bit
/// product on every target.
#[inline(always)]
pub(crate) fn mul_i64(a: i64, b: i64) -> i128 {
    a as i128 * b as i128
}

/// `a·b` for an unsigned 64-bit `a` and a signed 64-bit `b`, exactly.
#[inline(always)]
pub(crate) fn mul_u64_i64(a: u64, b: i64) -> i128 {
    a as i128 * b as i128
}

#[cfg(test)]
mod tests {
    use super::{mul_i32_halves, mul_u32_i32_halves};

    fn samples() -> impl Iterator<Item = i32> {
        let corners = [i32::MIN, i32::MIN + 1, -65_537, -65_536, -65_535, -1, 0, 1];
        let more = [65_535, 65_536, 65_537, i32::MAX - 1, i32::MAX];
        // A multiplicative spread over every magnitude, both signs.
        let spread = (0..64u32).flat_map(|i| {
            let v = (0x9E37_79B9u32.wrapping_mul(i + 1) >> (i % 31)) as i32;
            [v, v.wrapping_neg()]
        });
        corners.into_iter().chain(more).chain(spread)
    }

    /// The Cortex-M0's arithmetic, run on the host: the plain 64-bit products, at the
    /// corners and over a spread of magnitudes.
    #[test]
    fn halves_give_the_exact_products() {
        for a in samples() {
            for b in samples() {
                assert_eq!(mul_i32_halves(a, b), a as i64 * b as i64, "{a}·{b}");
                let ua = a as u32;
                assert_eq!(mul_u32_i32_halves(ua, b), ua as i64 * b as i64, "{ua}·{b}");
            }
        }
    }
}
