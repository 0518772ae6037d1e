//! The wide arithmetic of the fixed-point state: a state times a mantissa, shifted by
//! an exponent and rounded, without an integer three halves wide.
//!
//! A state `x` of `2H` bits is split into a signed high half `xₕ` and an unsigned low
//! half `xₗ`, so `x·m = xₕ·m·2^H + xₗ·m`. Both partial products fit the state type when
//! `|m| < 2^(H−1)`; `T = xₕm + ⌊xₗm / 2^H⌋` and `R = xₗm mod 2^H` then hold the exact
//! product `p = T·2^H + R` of up to `3H − 1` bits. The shift and the rounding need only
//! `T` and whether `R`'s low bits are zero. On a Cortex-M4 each partial product is one
//! `smull`/`umull`; on a Cortex-M0 four 32-bit multiplies of 16-bit halves
//! (`src/scalar/widening.rs`).

macro_rules! wide_arithmetic {
    (
        $module:ident, $Half:ty, $HalfU:ty, $Full:ty, $FullU:ty, $mul:path, $mul_unsigned:path
    ) => {
        pub(crate) mod $module {
            /// Half the state width, in bits.
            pub(crate) const H: u32 = <$Half>::BITS;

            /// `x·m / 2^shift`, rounded toward zero (`AWAY = false`) or away from zero
            /// (`AWAY = true`), saturated to the state type. `shift` may be negative (a
            /// left shift, exact).
            #[inline(always)]
            pub(crate) fn mul_shift<const AWAY: bool>(x: $Full, m: $Half, shift: i32) -> $Full {
                mul_shift_rounding(x, m, shift, AWAY)
            }

            /// [`mul_shift`] with the rounding chosen at run time: one copy of the code
            /// serves both roundings where it is not inlined (the step's cold path).
            #[inline(always)]
            pub(crate) fn mul_shift_rounding(x: $Full, m: $Half, shift: i32, away: bool) -> $Full {
                #[allow(non_snake_case)]
                let AWAY = away;
                let (xh, xl) = ((x >> H) as $Half, x as $HalfU);
                let high = $mul(xh, m);
                let low = $mul_unsigned(xl, m);
                let t = high + (low >> H);
                let r = (low as $FullU) & (<$HalfU>::MAX as $FullU);
                let negative = t < 0;
                // Round up (toward +∞) for negative products toward zero, for positive
                // ones away from zero; a zero product has t = r = 0 and stays 0 either way.
                let up = negative != AWAY;
                if shift >= H as i32 {
                    let k = (shift - H as i32) as u32;
                    if k >= 2 * H - 1 {
                        // |p| < 2^(3H − 2) ≤ 2^shift: 0 toward zero, ±1 away from it.
                        let zero = t == 0 && r == 0;
                        return if !AWAY || zero {
                            0
                        } else if negative {
                            -1
                        } else {
                            1
                        };
                    }
                    if up {
                        // ⌈p/2^s⌉ = ⌊(T + 2^k − 1 + [R ≠ 0]) / 2^k⌋.
                        let bias = ((1 as $Full) << k) - 1 + (r != 0) as $Full;
                        (t + bias) >> k
                    } else {
                        t >> k
                    }
                } else if shift >= 0 {
                    let s = shift as u32;
                    // ⌊p/2^s⌋ = T·2^(H−s) + ⌊R/2^s⌋, saturating.
                    let lift = H - s;
                    let head = t << lift;
                    if head >> lift != t {
                        return if negative { <$Full>::MIN } else { <$Full>::MAX };
                    }
                    let floor = head + (r >> s) as $Full;
                    let inexact = s > 0 && r & (((1 as $FullU) << s) - 1) != 0;
                    floor + (up && inexact) as $Full
                } else {
                    // A factor of 2^(H−1) or more: p·2^(−shift), exact or saturating.
                    let lift = (-shift) as u32;
                    let p = t
                        .checked_mul((1 as $Full) << H)
                        .and_then(|v| v.checked_add(r as $Full));
                    let lifted = match p {
                        Some(0) => Some(0),
                        Some(p) if lift < <$Full>::BITS - 1 => p.checked_mul((1 as $Full) << lift),
                        _ => None,
                    };
                    lifted.unwrap_or(if negative { <$Full>::MIN } else { <$Full>::MAX })
                }
            }

            /// `mantissa / 2^shift` as `f64`.
            pub(crate) fn decode(mantissa: $Half, shift: i32) -> f64 {
                mantissa as f64 * pow2(-shift)
            }

            /// `2^k` as `f64`, for `k` in the normal range.
            fn pow2(k: i32) -> f64 {
                f64::from_bits(((k + 1023) as u64) << 52)
            }
        }
    };
}

wide_arithmetic!(
    narrow,
    i32,
    u32,
    i64,
    u64,
    crate::scalar::widening::mul_i32,
    crate::scalar::widening::mul_u32_i32
);
wide_arithmetic!(
    broad,
    i64,
    u64,
    i128,
    u128,
    crate::scalar::widening::mul_i64,
    crate::scalar::widening::mul_u64_i64
);

#[cfg(test)]
mod tests {
    use super::super::fast::{FastGains, broad_step, mode, narrow_step};
    use super::super::raw_state::encode_mantissa;
    use super::*;

    /// The exact quotient, toward zero or away from it, on i128 (the products fit).
    fn reference(x: i64, m: i32, shift: i32, away: bool) -> i64 {
        let p = x as i128 * m as i128;
        let q = if shift >= 0 {
            if shift >= 127 {
                if away { p.signum() } else { 0 }
            } else {
                let d = 1i128 << shift;
                let t = p / d; // toward zero
                if away && t * d != p {
                    t + p.signum()
                } else {
                    t
                }
            }
        } else {
            p.saturating_mul(1i128 << (-shift))
        };
        q.clamp(i64::MIN as i128, i64::MAX as i128) as i64
    }

    #[test]
    fn narrow_matches_exact_arithmetic() {
        let mut seed = 0x9e37_79b9_7f4a_7c15u64;
        let mut next = || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            seed
        };
        for _ in 0..200_000 {
            let x = next() as i64 >> (next() % 64);
            let m = (next() as i32) >> (next() % 32);
            let m = if m == i32::MIN { 0 } else { m };
            let shift = (next() % 110) as i32 - 12;
            assert_eq!(
                narrow::mul_shift::<false>(x, m, shift),
                reference(x, m, shift, false)
            );
            assert_eq!(
                narrow::mul_shift::<true>(x, m, shift),
                reference(x, m, shift, true)
            );
        }
        for &x in &[i64::MIN, i64::MAX, -1, 1, 0] {
            for &m in &[-i32::MAX, i32::MAX, 1, -1, 0] {
                for shift in [-40, -5, 0, 1, 31, 32, 33, 60, 93, 94, 95, 200] {
                    for away in [false, true] {
                        let got = if away {
                            narrow::mul_shift::<true>(x, m, shift)
                        } else {
                            narrow::mul_shift::<false>(x, m, shift)
                        };
                        assert_eq!(got, reference(x, m, shift, away), "{x} {m} {shift} {away}");
                    }
                }
            }
        }
    }

    /// xorshift64: reproducible inputs without a dependency.
    fn rng(mut seed: u64) -> impl FnMut() -> u64 {
        move || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            seed
        }
    }

    #[test]
    fn fast_product_matches_mul_shift() {
        let mut next = rng(0x2545_f491_4f6c_dd1d);
        let mut checked = 0;
        for i in 0..400_000u32 {
            let x = next() as i64 >> (next() % 64);
            let x = if i % 7 == 0 {
                [i64::MIN, i64::MAX, -1, 0, 1][i as usize % 5]
            } else {
                x
            };
            let shift = 34 + (next() % 30) as i32; // 34..=63
            let m = if i % 11 == 0 {
                0
            } else {
                (1 << 30) | (next() as i32 & 0x3fff_ffff)
            };
            let m = if i % 13 == 0 { i32::MAX } else { m };
            let fast = FastGains::narrow((m, shift), (m, shift));
            assert_eq!(fast.headroom, narrow_step::RANGE, "{m} {shift}");
            let f = fast.stiffness;
            let (down, up) = (
                narrow::mul_shift::<false>(x, m, shift),
                narrow::mul_shift::<true>(x, m, shift),
            );
            use narrow_step::product_in;
            assert_eq!(product_in::<false, { mode::NATIVE }>(x, &f), down);
            assert_eq!(product_in::<true, { mode::NATIVE }>(x, &f), up);
            assert_eq!(product_in::<false, { mode::SCALE }>(x, &f), down);
            assert_eq!(product_in::<true, { mode::SCALE }>(x, &f), up);
            assert_eq!(
                product_in::<false, { mode::SMALL }>(x, &f),
                down,
                "{x} {m} {shift}"
            );
            assert_eq!(product_in::<true, { mode::SMALL }>(x, &f), up);
            checked += 1;
        }
        assert_eq!(checked, 400_000);
    }

    #[test]
    fn fast_step_is_the_saturating_step_where_it_runs() {
        let general = |(km, ks): (i32, i32), (dm, ds): (i32, i32), x: &mut i64, v: &mut i64| {
            let u = v.saturating_sub(narrow::mul_shift::<false>(*x, km, ks));
            *x = x.saturating_add(u);
            *v = u.saturating_sub(narrow::mul_shift::<true>(u, dm, ds));
        };
        let mut next = rng(0x9e37_79b9_7f4a_7c15);
        let (mut fast_runs, mut refusals) = (0, 0);
        for i in 0..400_000u32 {
            let gain = |next: &mut dyn FnMut() -> u64| {
                let r = next();
                if r.is_multiple_of(9) {
                    (0, 0)
                } else {
                    (
                        (1 << 30) | (r as i32 & 0x3fff_ffff),
                        28 + (r >> 40) as i32 % 40,
                    )
                }
            };
            let (k, d) = (gain(&mut next), gain(&mut next));
            let fast = FastGains::narrow(k, d);
            let x0 = next() as i64 >> (next() % 64);
            let v0 = next() as i64 >> (next() % 64);
            let (x0, v0) = if i % 17 == 0 {
                (i64::MAX, i64::MIN)
            } else {
                (x0, v0)
            };
            let (mut x, mut v) = (x0, v0);
            let (mut gx, mut gv) = (x0, v0);
            general(k, d, &mut gx, &mut gv);
            if narrow_step::advance(&fast, &mut x, &mut v) {
                fast_runs += 1;
                assert_eq!((x, v), (gx, gv), "{k:?} {d:?} {x0} {v0}");
            } else {
                refusals += 1;
                assert_eq!((x, v), (x0, v0));
            }
        }
        assert!(
            fast_runs > 100_000 && refusals > 10_000,
            "{fast_runs} {refusals}"
        );
    }

    #[test]
    fn lifted_step_is_the_saturating_step_of_the_scaled_state() {
        use super::super::fast::narrow_step::advance_lifted_in;
        const MAX: i64 = (1 << 56) - 1;
        // The state halved together until both are 57-bit integers.
        let held = |(mut x, mut v): (i64, i64)| {
            while !(-MAX - 1..=MAX).contains(&x) || !(-MAX - 1..=MAX).contains(&v) {
                (x, v) = (x >> 1, v >> 1);
            }
            (x, v)
        };
        use super::super::raw_state::narrow_takes;
        let general = |(km, ks): (i32, i32), (dm, ds): (i32, i32), x: &mut i64, v: &mut i64| {
            let u = v.saturating_sub(narrow::mul_shift::<false>(*x, km, ks));
            *x = x.saturating_add(u);
            *v = u.saturating_sub(narrow::mul_shift::<true>(u, dm, ds));
        };
        let mut next = rng(0x5851_f42d_4c95_7f2d);
        let (mut within, mut outside) = (0, 0);
        for i in 0..300_000u32 {
            // Every gain the narrow step takes: stiffness shifts 29..=63, damping 30..=63
            // (C_k < 4, C_d < 2, both at least 2^−33), zeros, and the lifts' ends.
            let gain = |next: &mut dyn FnMut() -> u64, least: i32| {
                let r = next();
                if r.is_multiple_of(9) {
                    (0, 0)
                } else {
                    let m = if r % 7 == 1 {
                        i32::MAX - 1
                    } else {
                        (1 << 30) | (r as i32 & 0x3fff_ffff)
                    };
                    (m, least + (r >> 40) as i32 % (64 - least))
                }
            };
            let (k, d) = (gain(&mut next, 29), gain(&mut next, 30));
            assert!(narrow_takes((k.0 as i64, k.1), (d.0 as i64, d.1)));
            let fast = FastGains::narrow(k, d);
            let x0 = next() as i64 >> (next() % 64);
            let v0 = next() as i64 >> (next() % 64);
            let (x0, v0) = match i % 23 {
                0 => (i64::MAX, i64::MIN),
                1 => (MAX, -MAX - 1),
                2 => (MAX + 1, -MAX - 2),
                _ => (x0, v0),
            };
            let (mut gx, mut gv) = held((x0, v0));
            if (gx, gv) == (x0, v0) {
                within += 1;
            } else {
                outside += 1;
            }
            general(k, d, &mut gx, &mut gv);
            let mut modes = [(x0, v0); 3];
            advance_lifted_in::<{ mode::NATIVE }>(
                &fast,
                (k.1, d.1),
                &mut modes[0].0,
                &mut modes[0].1,
            );
            advance_lifted_in::<{ mode::SCALE }>(
                &fast,
                (k.1, d.1),
                &mut modes[1].0,
                &mut modes[1].1,
            );
            advance_lifted_in::<{ mode::SMALL }>(
                &fast,
                (k.1, d.1),
                &mut modes[2].0,
                &mut modes[2].1,
            );
            for (n, got) in modes.iter().enumerate() {
                assert_eq!(*got, (gx, gv), "mode {n}: {k:?} {d:?} {x0} {v0}");
            }
        }
        assert!(within > 150_000 && outside > 30_000, "{within} {outside}");
    }

    #[test]
    fn broad_fast_product_matches_mul_shift() {
        let mut next = rng(0x1234_5678_9abc_def1);
        for i in 0..200_000u32 {
            let x = ((next() as i128) << 64 | next() as i128) >> (next() % 128);
            let x = if i % 7 == 0 {
                [i128::MIN, i128::MAX, -1, 0, 1][i as usize % 5]
            } else {
                x
            };
            let shift = 66 + (next() % 62) as i32; // 66..=127
            let m = if i % 11 == 0 {
                0
            } else {
                (1 << 62) | (next() as i64 & 0x3fff_ffff_ffff_ffff)
            };
            let m = if i % 13 == 0 { i64::MAX } else { m };
            let fast = FastGains::broad((m, shift), (m, shift));
            assert_eq!(fast.headroom, 1 << 62, "{m} {shift}");
            let f = fast.stiffness;
            assert_eq!(
                broad_step::product::<false>(x, &f),
                broad::mul_shift::<false>(x, m, shift)
            );
            assert_eq!(
                broad_step::product::<true>(x, &f),
                broad::mul_shift::<true>(x, m, shift)
            );
        }
    }

    #[test]
    fn broad_fast_step_is_the_saturating_step_where_it_runs() {
        let mut next = rng(0x0bad_cafe_f00d_1234);
        let (mut fast_runs, mut refusals) = (0, 0);
        for i in 0..200_000u32 {
            let gain = |next: &mut dyn FnMut() -> u64| {
                let r = next();
                if r.is_multiple_of(9) {
                    (0i64, 0)
                } else {
                    (
                        (1 << 62) | (r as i64 & 0x3fff_ffff_ffff_ffff),
                        60 + (r >> 40) as i32 % 72,
                    )
                }
            };
            let (k, d) = (gain(&mut next), gain(&mut next));
            let fast = FastGains::broad(k, d);
            let wide = |next: &mut dyn FnMut() -> u64| {
                ((next() as i128) << 64 | next() as i128) >> (next() % 128)
            };
            let (x0, v0) = if i % 17 == 0 {
                (i128::MAX, i128::MIN)
            } else {
                (wide(&mut next), wide(&mut next))
            };
            let (mut x, mut v) = (x0, v0);
            let u = v0.saturating_sub(broad::mul_shift::<false>(x0, k.0, k.1));
            let gx = x0.saturating_add(u);
            let gv = u.saturating_sub(broad::mul_shift::<true>(u, d.0, d.1));
            if broad_step::advance(&fast, &mut x, &mut v) {
                fast_runs += 1;
                assert_eq!((x, v), (gx, gv), "{k:?} {d:?} {x0} {v0}");
            } else {
                refusals += 1;
                assert_eq!((x, v), (x0, v0));
            }
        }
        assert!(
            fast_runs > 30_000 && refusals > 10_000,
            "{fast_runs} {refusals}"
        );
    }

    #[test]
    fn broad_agrees_with_narrow_scaled_up() {
        // The same values in the upper halves of the wide words give the same quotient.
        for (x, m, s) in [
            (12345i64, 1 << 20, 40),
            (-98765, 3, 2),
            (-1, 1, 0),
            (7, -5, 1),
        ] {
            let n = narrow::mul_shift::<false>(x, m, s) as i128;
            let b = broad::mul_shift::<false>((x as i128) << 32, m as i64, s + 32);
            assert_eq!(n, b, "{x} {m} {s}");
            let n = narrow::mul_shift::<true>(x, m, s) as i128;
            let b = broad::mul_shift::<true>((x as i128) << 32, m as i64, s + 32);
            assert_eq!(n, b, "{x} {m} {s}");
        }
    }

    #[test]
    fn encoding_keeps_thirty_one_bits() {
        for v in [3.9e-7, 1.0, 3.999, 0.1, 1e-12, 2.5e6, -0.75] {
            let (m, s) = encode_mantissa(v, 32);
            let m = m as i32;
            assert!(
                ((narrow::decode(m, s) - v) / v).abs() <= 2.0f64.powi(-30),
                "{v}"
            );
            let (m, s) = encode_mantissa(v, 64);
            assert!(
                ((broad::decode(m, s) - v) / v).abs() <= 2.0f64.powi(-62),
                "{v}"
            );
        }
        assert_eq!(encode_mantissa(0.0, 32), (0, 0));
        assert_eq!(encode_mantissa(f64::NAN, 32), (0, 0));
    }
}
