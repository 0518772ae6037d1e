//! Integer helpers: rounded shifts, a 256-bit accumulator, mantissas.

use super::*;

/// How a wide sum is brought down by a right shift.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Round {
    /// Toward zero.
    Zero,
    /// To nearest, half up (`(p + 2^(s−1)) >> s`).
    Nearest,
    /// Toward −∞ (a plain arithmetic shift).
    Floor,
    /// Away from zero (ceiling for `p > 0`, floor for `p < 0`).
    Away,
}

/// `p / 2^s` rounded as asked; `1 ≤ s < 127`.
#[inline(always)]
pub fn shr_round(p: i128, s: u32, mode: Round) -> i128 {
    match mode {
        Round::Floor => p >> s,
        Round::Zero => (p + ((p >> 127) & ((1i128 << s) - 1))) >> s,
        Round::Nearest => (p + (1i128 << (s - 1))) >> s,
        Round::Away => (p + (!(p >> 127) & ((1i128 << s) - 1))) >> s,
    }
}

/// A signed 256-bit accumulator `hi·2¹²⁸ + lo`, two's complement: just enough for the sum of
/// two `i128 × u64` products and a rounded right shift.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct I256 {
    hi: i128,
    lo: u128,
}

impl I256 {
    /// Sign-extends an `i128`.
    #[inline(always)]
    pub fn from_i128(v: i128) -> I256 {
        I256 {
            hi: v >> 127,
            lo: v as u128,
        }
    }

    /// `self + o` (wrapping at 2²⁵⁶, which the study never reaches).
    #[inline(always)]
    #[allow(clippy::should_implement_trait)]
    pub fn add(self, o: I256) -> I256 {
        let (lo, c) = self.lo.overflowing_add(o.lo);
        I256 {
            hi: self.hi.wrapping_add(o.hi).wrapping_add(c as i128),
            lo,
        }
    }

    /// The exact product `x·m`.
    #[inline(always)]
    pub fn mul(x: i128, m: u64) -> I256 {
        let xh = x >> 64; // in i64 range
        let xl = x as u64 as u128;
        let ph = xh * m as i128; // |ph| < 2^127
        let pl = xl * m as u128; // < 2^128
        I256 {
            hi: ph >> 64,
            lo: (ph as u128) << 64,
        }
        .add(I256 { hi: 0, lo: pl })
    }

    /// `self / 2^s` rounded as asked, as an `i128` (the caller keeps it in range);
    /// `1 ≤ s < 127`.
    #[inline(always)]
    pub fn shr_round(self, s: u32, mode: Round) -> i128 {
        let v = match mode {
            Round::Floor => self,
            Round::Zero => {
                if self.hi < 0 {
                    self.add(I256::from_i128((1i128 << s) - 1))
                } else {
                    self
                }
            }
            Round::Nearest => self.add(I256::from_i128(1i128 << (s - 1))),
            Round::Away => {
                if self.hi >= 0 {
                    self.add(I256::from_i128((1i128 << s) - 1))
                } else {
                    self
                }
            }
        };
        v.hi.wrapping_shl(128 - s).wrapping_add((v.lo >> s) as i128)
    }

    /// `self − (q << s)`, the remainder of a floor shift, as an `i128`.
    #[inline(always)]
    pub fn low_bits(self, s: u32) -> i128 {
        (self.lo & ((1u128 << s) - 1)) as i128
    }
}

/// Mantissas `round(C·2^s)` with one shared shift `s`: the largest `s` for which the larger
/// coefficient's mantissa has at most `bits` bits.
pub fn mantissas(c: Coefs, bits: u32) -> (i128, i128, u32) {
    let limit = ((1u128 << bits) - 1) as f64;
    let cmax = c.ck.max(c.cd);
    let fits = |s: i32| (cmax * 2f64.powi(s)).round() <= limit;
    let mut s = (limit / cmax).log2().floor() as i32;
    while fits(s + 1) {
        s += 1;
    }
    while !fits(s) {
        s -= 1;
    }
    assert!((1..126).contains(&s), "shift {s} out of range");
    let m = |v: f64| (v * 2f64.powi(s)).round() as i128;
    (m(c.ck), m(c.cd), s as u32)
}

pub(super) fn quantise(v: f64, frac: u32) -> i128 {
    (v * 2f64.powi(frac as i32)).round() as i128
}
