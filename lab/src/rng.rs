//! Seeded random inputs for the tests: the same sequence from the same seed on every
//! machine and every run, so that a failing case reproduces.
//!
//! The generator is rand's [`Xoshiro256PlusPlus`], chosen over the alternatives because:
//!
//! - it is a named algorithm (Blackman and Vigna's xoshiro256++), seeded from a `u64` by
//!   SplitMix64 inside the type, so no release of rand may swap it for another one, as
//!   it may for `SmallRng`, whose documentation calls it non-portable (it is xoshiro128++
//!   on 32-bit hosts and may change between versions);
//! - it uses only 64-bit integer arithmetic, so its output does not depend on the host;
//! - it comes with rand itself, which the tests already build for proptest: no further
//!   crate, and no OS entropy (rand without default features builds no getrandom).
//!
//! The conversions to `f64` are written here, from the top 53 bits of a draw, rather
//! than taken from rand's distributions, whose value stability rand promises only within
//! a minor version; the unit test `the_sequence_is_pinned` checks the first draws.

use rand::rngs::Xoshiro256PlusPlus;
use rand::{Rng as _, SeedableRng as _};

/// A seeded generator with the draws the tests use.
#[derive(Clone, Debug)]
pub struct Rng(Xoshiro256PlusPlus);

impl Rng {
    /// The generator for `seed`.
    pub fn seeded(seed: u64) -> Self {
        Rng(Xoshiro256PlusPlus::seed_from_u64(seed))
    }

    /// 64 random bits.
    pub fn next_u64(&mut self) -> u64 {
        self.0.next_u64()
    }

    /// Uniform in `[0, 1)`: the top 53 bits of a draw, scaled by 2⁻⁵³ (exact).
    pub fn unit(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
    }

    /// Uniform in `[lo, hi)`.
    pub fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.unit()
    }

    /// Uniform in `[−a, a)`.
    pub fn sym(&mut self, a: f64) -> f64 {
        self.range(-a, a)
    }

    /// Log-uniform in `[lo, hi)`, both positive.
    pub fn log_range(&mut self, lo: f64, hi: f64) -> f64 {
        self.range(lo.ln(), hi.ln()).exp()
    }

    /// A random unit vector in `D` dimensions (uniform on the sphere: rejection from the
    /// cube, keeping lengths in `(0.1, 1]`).
    pub fn unit_vector<const D: usize>(&mut self) -> [f64; D] {
        loop {
            let v: [f64; D] = std::array::from_fn(|_| self.sym(1.0));
            let n = v.iter().map(|c| c * c).sum::<f64>().sqrt();
            if n > 0.1 && n <= 1.0 {
                return v.map(|c| c / n);
            }
        }
    }

    /// Uniform in `0..n` (`n > 0`), without modulo bias: the high half of the 128-bit
    /// product of a draw and `n`, redrawn in the rare case that lands in the biased part.
    pub fn below(&mut self, n: usize) -> usize {
        assert!(n > 0, "below(0)");
        let n = n as u64;
        // Lemire's method: accept unless the low half falls below 2⁶⁴ mod n.
        let threshold = n.wrapping_neg() % n;
        loop {
            let product = u128::from(self.next_u64()) * u128::from(n);
            if (product as u64) >= threshold {
                return (product >> 64) as usize;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::Rng;

    /// The first draws from seed 1, as Blackman and Vigna's reference xoshiro256++ gives
    /// them from the state SplitMix64 makes of the seed (recomputed independently when
    /// this test was written). A change here means every seeded test now runs on other
    /// inputs: a release of rand that changed the generator or its seeding, or a change
    /// to this module.
    #[test]
    fn the_sequence_is_pinned() {
        let mut rng = Rng::seeded(1);
        let draws: Vec<u64> = (0..3).map(|_| rng.next_u64()).collect();
        assert_eq!(draws, PINNED);
    }

    const PINNED: [u64; 3] = [
        14971601782005023387,
        13781649495232077965,
        1847458086238483744,
    ];

    #[test]
    fn draws_fall_in_their_ranges() {
        let mut rng = Rng::seeded(7);
        let mut counts = [0usize; 5];
        for _ in 0..10_000 {
            let u = rng.unit();
            assert!((0.0..1.0).contains(&u));
            let r = rng.range(-2.0, 3.0);
            assert!((-2.0..3.0).contains(&r));
            let l = rng.log_range(1e-3, 1e3);
            assert!((1e-3..1e3 * (1.0 + 1e-12)).contains(&l));
            counts[rng.below(5)] += 1;
        }
        // Each of five bins gets 2000 ± a few standard deviations (40).
        for c in counts {
            assert!((1800..2200).contains(&c), "{counts:?}");
        }
    }
}
