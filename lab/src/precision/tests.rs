//! The reference cannot be wrong silently: the analytic solution against RK4, the exact map against the poles, the models against each other.

use super::*;
use crate::rng::Rng;

const ZETAS: [f64; 7] = [0.0, 0.1, 0.3, 0.7, 1.0, 2.0, 10.0];

/// RK4 on x'' = −2ζθx' − θ²x with `sub` sub-steps per step.
fn rk4(fdt: f64, zeta: f64, x0: f64, v0: f64, steps: usize, sub: usize) -> Vec<f64> {
    let w = 2.0 * PI * fdt;
    let acc = |x: f64, v: f64| -2.0 * zeta * w * v - w * w * x;
    let h = 1.0 / sub as f64;
    let (mut x, mut v) = (x0, v0);
    let mut out = vec![x];
    for _ in 0..steps {
        for _ in 0..sub {
            let (k1x, k1v) = (v, acc(x, v));
            let (k2x, k2v) = (v + 0.5 * h * k1v, acc(x + 0.5 * h * k1x, v + 0.5 * h * k1v));
            let (k3x, k3v) = (v + 0.5 * h * k2v, acc(x + 0.5 * h * k2x, v + 0.5 * h * k2v));
            let (k4x, k4v) = (v + h * k3v, acc(x + h * k3x, v + h * k3v));
            x += h / 6.0 * (k1x + 2.0 * k2x + 2.0 * k3x + k4x);
            v += h / 6.0 * (k1v + 2.0 * k2v + 2.0 * k3v + k4v);
        }
        out.push(x);
    }
    out
}

#[test]
fn analytic_solution_matches_rk4() {
    for fdt in [1e-3, 2e-2, 0.2] {
        for zeta in ZETAS {
            for (x0, v0) in [(1.0, 0.0), (0.0, 1.0), (-0.5, 0.3)] {
                let an = Analytic::new(fdt, zeta, x0, v0);
                // Sub-steps so that the fastest pole moves at most 0.01 rad per sub-step.
                let fastest = 2.0 * PI * fdt * (zeta + (zeta * zeta - 1.0).abs().sqrt()).max(1.0);
                let sub = ((fastest / 0.002).ceil() as usize).max(1);
                let steps = (3.0 / fdt) as usize; // three periods
                let r = rk4(fdt, zeta, x0, v0, steps, sub);
                let scale = x0.abs().max(v0.abs() / (2.0 * PI * fdt));
                for (n, rn) in r.iter().enumerate() {
                    let d = (an.sample(n as i64) - rn).abs() / scale;
                    assert!(
                        d < 1e-9,
                        "fdt {fdt} ζ {zeta} start ({x0}, {v0}) n {n}: {d:e}"
                    );
                }
            }
        }
    }
}

#[test]
fn fling_peaks_at_the_amplitude_and_starts_at_rest_position() {
    for fdt in [1e-4, 1e-2, 0.2] {
        for zeta in ZETAS {
            let an = Analytic::fling(fdt, zeta, 3.0);
            assert_eq!(an.x0(), 0.0);
            let peak = (0..200_000)
                .map(|i| an.at(i as f64 * 1e-5 / fdt))
                .fold(0.0, f64::max);
            assert!(
                (peak - 3.0).abs() < 1e-6 && peak <= 3.0 + 1e-12,
                "fdt {fdt} ζ {zeta}: {peak}"
            );
        }
    }
}

#[test]
fn coefficients_are_the_products_of_the_poles() {
    for fdt in [1e-3, 1e-2, 0.2, 0.4] {
        for zeta in ZETAS {
            let c = Coefs::exact(fdt, zeta);
            let w = 2.0 * PI * fdt;
            // z₁z₂ and z₁ + z₂ straight from the poles.
            let (prod, sum) = if zeta < 1.0 {
                let r = (-zeta * w).exp();
                (r * r, 2.0 * r * (w * (1.0 - zeta * zeta).sqrt()).cos())
            } else {
                let q = (zeta * zeta - 1.0).sqrt();
                let (z1, z2) = ((-w * (zeta - q)).exp(), (-w * (zeta + q)).exp());
                (z1 * z2, z1 + z2)
            };
            assert!((c.cd - (1.0 - prod)).abs() < 1e-14);
            assert!((c.ck - (1.0 - sum + prod)).abs() < 1e-13 * (1.0 + 1.0 / c.ck.max(1e-3)));
            // inside the Jury region
            assert!(c.ck > 0.0 && c.cd >= 0.0 && c.ck + 2.0 * c.cd < 4.0);
        }
    }
}

/// The f64 map with the exact coefficients, started with u₀ = x(0) − x(−dt), stays on
/// the analytic samples to 1e-12 of the amplitude over 10,000 steps, on the
/// fixed-point grid (f·dt ≤ 0.2), releases and flings — to 1e-12·|u₀| where the start
/// is ill-conditioned (|u₀| > A: overdamped at large f·dt, where the first step cancels
/// the fast mode that u₀ carries; 3e-11 for a fling at f·dt = 0.1, ζ = 10).
#[test]
fn exact_f64_map_reproduces_the_analytic_samples() {
    let mut worst: f64 = 0.0;
    for fdt in [1e-4, 2e-4, 1e-3, 1.0 / 60.0, 0.05, 0.1, 0.2] {
        for zeta in ZETAS {
            for kind in [Kind::Release, Kind::Fling] {
                let an = kind.analytic(fdt, zeta, 1.0);
                let reference: Vec<f64> = (0..=10_000).map(|n| an.sample(n)).collect();
                let kappa = an.u0().abs().max(1.0);
                for rform in [false, true] {
                    let s = F64::new(rform, Coefs::exact(fdt, zeta), an.x0(), an.u0());
                    let (e, _) = Track {
                        reference: &reference,
                    }
                    .run(s);
                    if !rform {
                        assert!(
                            e < 1e-12 * kappa,
                            "fdt {fdt} ζ {zeta} {}: {e:e}",
                            kind.name()
                        );
                    }
                    worst = worst.max(e / kappa);
                }
            }
        }
    }
    // The r-form in f64 only loses 1 − C_d's last bits.
    assert!(worst < 1e-10, "{worst:e}");
}

#[test]
fn wide_arithmetic_agrees_with_i128() {
    let mut rng = Rng::seeded(7);
    for _ in 0..10_000 {
        let x = (rng.next_u64() as i128) >> (rng.next_u64() % 64) as u32; // |x| < 2^63
        let y = (rng.next_u64() as i128) >> (rng.next_u64() % 64) as u32;
        let (m, n) = (rng.next_u64() >> 33, rng.next_u64() >> 33); // < 2^31
        let p = I256::mul(x, m).add(I256::mul(y, n));
        let exact = x * m as i128 + y * n as i128;
        for s in [1, 29, 40, 61, 90] {
            for mode in [Round::Zero, Round::Nearest, Round::Floor, Round::Away] {
                assert_eq!(p.shr_round(s, mode), shr_round(exact, s, mode));
            }
            assert_eq!(p.low_bits(s), exact & ((1i128 << s) - 1));
        }
    }
    // beyond i128: (2^100 + 1)·(2^63 − 1) = 2^163 − 2^100 + 2^63 − 1, shifted back by 63
    let x = (1i128 << 100) + 1;
    let m = (1u64 << 63) - 1;
    let q = (1i128 << 100) - (1i128 << 37); // the quotient, remainder 2^63 − 1
    assert_eq!(I256::mul(x, m).shr_round(63, Round::Floor), q);
    assert_eq!(I256::mul(x, m).shr_round(63, Round::Zero), q);
    assert_eq!(I256::mul(x, m).shr_round(63, Round::Nearest), q + 1);
    assert_eq!(I256::mul(-x, m).shr_round(63, Round::Floor), -q - 1);
    assert_eq!(I256::mul(-x, m).shr_round(63, Round::Zero), -q);
    assert_eq!(I256::mul(-x, m).shr_round(63, Round::Nearest), -q - 1);
}

#[test]
fn rounding_modes() {
    assert_eq!(shr_round(-1, 4, Round::Zero), 0);
    assert_eq!(shr_round(-1, 4, Round::Floor), -1);
    assert_eq!(shr_round(-8, 4, Round::Nearest), 0);
    assert_eq!(shr_round(-9, 4, Round::Nearest), -1);
    assert_eq!(shr_round(8, 4, Round::Nearest), 1);
    assert_eq!(shr_round(-17, 4, Round::Zero), -1);
    assert_eq!(shr_round(17, 4, Round::Zero), 1);
    assert_eq!(shr_round(-1, 4, Round::Away), -1);
    assert_eq!(shr_round(1, 4, Round::Away), 1);
    assert_eq!(shr_round(0, 4, Round::Away), 0);
    assert_eq!(shr_round(16, 4, Round::Away), 1);
    assert_eq!(shr_round(-16, 4, Round::Away), -1);
    assert_eq!(shr_round(17, 4, Round::Away), 2);
    assert_eq!(shr_round(-17, 4, Round::Away), -2);
    for mode in [Round::Zero, Round::Nearest, Round::Floor, Round::Away] {
        for p in [-70i128, -33, -32, -31, -1, 0, 1, 31, 32, 33, 70] {
            let v = I256::from_i128(p).shr_round(4, mode);
            assert_eq!(v, shr_round(p, 4, mode), "{p} {mode:?}");
        }
    }
}

/// `ũ₀ = P̃·x₀ + Q̃·v₀` is `(1 − C_d)·u₀` where that is well conditioned, and
/// `x(1) − x(0) + C_k·x(0)` everywhere (the first step of the kept form lands on `x(1)`).
#[test]
fn kept_start_is_the_damped_step_velocity() {
    for fdt in [1e-4, 1e-3, 1.0 / 60.0, 0.1, 0.2, 0.3, 0.4] {
        for zeta in ZETAS {
            let c = Coefs::exact(fdt, zeta);
            for kind in [Kind::Release, Kind::Fling] {
                let an = kind.analytic(fdt, zeta, 1.0);
                let k = an.kept0();
                let first = an.sample(1) - an.x0() + c.ck * an.x0();
                assert!(
                    (k - first).abs() < 1e-13,
                    "fdt {fdt} ζ {zeta} {}: {k:e} {first:e}",
                    kind.name()
                );
                if an.u0().abs() < 10.0 {
                    let direct = (1.0 - c.cd) * an.u0();
                    assert!(
                        (k - direct).abs() < 1e-13,
                        "fdt {fdt} ζ {zeta} {}: {k:e} {direct:e}",
                        kind.name()
                    );
                }
            }
        }
    }
}

/// The f64 kept map from `ũ₀` stays on the analytic samples, ill-conditioned starts
/// included, with no step ahead.
#[test]
fn kept_f64_reproduces_the_analytic_samples() {
    for fdt in [1e-4, 1e-3, 1.0 / 60.0, 0.1, 0.2, 0.4] {
        for zeta in ZETAS {
            for kind in [Kind::Release, Kind::Fling] {
                let an = kind.analytic(fdt, zeta, 1.0);
                let reference: Vec<f64> = (0..=10_000).map(|n| an.sample(n)).collect();
                let s = KeptF64::new(Coefs::exact(fdt, zeta), Start::analytic(&an));
                let (e, _) = Track {
                    reference: &reference,
                }
                .run(s);
                assert!(e < 1e-11, "fdt {fdt} ζ {zeta} {}: {e:e}", kind.name());
            }
        }
    }
}

/// The I16F16 kept model against a firmware-style model in `i64`/`u64` only: the
/// 64×32 split product `m·x = m·x_hi·2³² + m·x_lo`, rounded from its parts.
#[test]
fn kept_matches_a_64_bit_split_product_model() {
    /// `round(m·y / 2^s)` with `y` in `i64`, `m < 2^31`, from two 64-bit products.
    fn term(m: i64, y: i64, s: u32, away: bool) -> i64 {
        let hi = y >> 32; // [−2^31, 2^31)
        let lo = (y as u64) & 0xffff_ffff;
        let p_hi = m * hi; // < 2^62
        let p_lo = m as u64 * lo; // < 2^63
        let t = p_hi + (p_lo >> 32) as i64; // m·y = t·2^32 + (p_lo mod 2^32)
        let low = p_lo & 0xffff_ffff;
        let (floor, inexact) = if s >= 32 {
            let k = s - 32;
            (t >> k, low != 0 || t & ((1i64 << k) - 1) != 0)
        } else {
            let k = 32 - s;
            ((t << k) | (low >> s) as i64, low & ((1u64 << s) - 1) != 0)
        };
        let neg = t < 0;
        match (away, neg, inexact) {
            (false, true, true) => floor + 1, // toward zero
            (true, false, true) => floor + 1, // away from zero
            _ => floor,
        }
    }
    for (fdt, zeta) in [
        (1e-4, 0.05),
        (2e-3, 0.3),
        (0.02, 1.0),
        (0.1, 10.0),
        (0.2, 0.1),
    ] {
        let c = Coefs::exact(fdt, zeta);
        for kind in [Kind::Release, Kind::Fling] {
            let st = Start::analytic(&kind.analytic(fdt, zeta, 1.0));
            let mut k = Kept::new(Fixed::I16F16, KRound::Lead, c, st);
            let (mk, sk) = mantissa(c.ck, 31);
            let (md, sd) = mantissa(c.cd, 31);
            let (mut x, mut v) = (k.state().0 as i64, k.state().1 as i64);
            for n in 0..20_000 {
                let u = v - term(mk as i64, x, sk, false);
                x += u;
                v = u - term(md as i64, u, sd, true);
                k.step();
                assert_eq!(
                    k.state(),
                    (x as i128, v as i128),
                    "fdt {fdt} ζ {zeta} step {n}"
                );
            }
        }
    }
}

/// Just outside the dead band, `ũ = 0` and `⌊C_k·x⌋ = 1`: the lead's rounding moves `x`
/// one state LSB per step (`u = −1`, then the damping takes it all back), until
/// `|x| < 1/C_k`.
#[test]
fn kept_creeps_one_lsb_per_step_to_the_dead_band() {
    let c = Coefs::exact(1e-3, 0.1);
    let probe = Kept::from_state(Fixed::I16F16, KRound::Lead, c, 0, 0);
    let edge = probe.dead_band().ceil() as i128; // the first x with ⌊C_k·x⌋ = 1
    let x0 = edge + 5000;
    let end = kept_settle(
        Kept::from_state(Fixed::I16F16, KRound::Lead, c, x0, 0),
        1 << 20,
    );
    assert_eq!(end.period, 1);
    assert_eq!(end.state, (edge - 1, 0));
    assert_eq!(end.steps, Some(5002)); // 5001 creep steps and the one that sees the rest
    assert_eq!(end.creep, 5001);
}

/// The counterexample: with a quantised C_k in [1.5, 2) and C_d ≤ 1/3 the lead's rounding
/// has the period-4 cycle (2, 0) → (−1, −2) → (−2, 0) → (1, 2); below C_k = 1.5 the same
/// start rests.
#[test]
fn kept_lead_rounding_cycles_at_ck_from_1_5() {
    let cycle = [(-1, -2), (-2, 0), (1, 2), (2, 0)];
    for (fdt, zeta) in [(0.21, 0.001), (0.25, 0.02), (0.25, 0.1)] {
        let c = Coefs::exact(fdt, zeta);
        let mut k = Kept::from_state(Fixed::I16F16, KRound::Lead, c, 2, 0);
        assert!((1.5..2.0).contains(&(1.0 / k.dead_band())), "{fdt} {zeta}");
        for want in cycle.iter().cycle().take(40) {
            k.step();
            assert_eq!(k.state(), *want, "fdt {fdt} ζ {zeta}");
        }
        let end = kept_settle(Kept::from_state(Fixed::I32F32, KRound::Lead, c, 2, 0), 100);
        assert_eq!(end.period, 4, "I32F32 fdt {fdt} ζ {zeta}");
    }
    let c = Coefs::exact(0.2, 0.001);
    let end = kept_settle(Kept::from_state(Fixed::I16F16, KRound::Lead, c, 2, 0), 100);
    assert!(1.0 / Kept::from_state(Fixed::I16F16, KRound::Lead, c, 0, 0).dead_band() < 1.5);
    assert_eq!((end.period, end.state), (1, (0, 0)));
}

#[test]
fn mantissas_use_all_bits_of_the_larger_coefficient() {
    for (ck, cd) in [(3.9e-7, 0.0), (3.9e-7, 0.0125), (1.5, 0.3), (0.25, 0.999)] {
        let (mk, md, s) = mantissas(Coefs { ck, cd }, 31);
        let m = mk.max(md);
        assert!((1 << 30..1 << 31).contains(&m), "{ck} {cd}: {m} {s}");
        assert!((mk as f64 / 2f64.powi(s as i32) - ck).abs() <= 0.5 / 2f64.powi(s as i32));
    }
}

#[test]
fn approximate_low_products_are_below_the_exact_one() {
    let mut rng = Rng::seeded(11);
    for _ in 0..10_000 {
        let x = (rng.next_u64() as i64 >> (rng.next_u64() % 40)) as i128;
        let m = (rng.next_u64() >> 33) as i128;
        let d = m * x - Wide::approx(m, x);
        assert!((0..1i128 << 49).contains(&d), "{x} {m} {d}");
        let d = m * x - Wide::approx2(m, x);
        assert!((0..1i128 << 47).contains(&d), "{x} {m} {d}");
    }
}

#[test]
fn truncate_is_todays_narrowing() {
    // 2 Hz at 1 kHz from 1 at rest: the first steps by hand, Q3.29 coefficients rounded
    // to nearest and `(1−C_d)·u − C_k·x` truncated toward zero.
    let c = Coefs::exact(0.002, 0.3);
    let mut s = RForm::new(Fixed::I16F16, RMode::Truncate, c, 1.0, 0.0);
    let k = (c.ck * 2f64.powi(29)).round() as i128;
    let r = ((1.0 - c.cd) * 2f64.powi(29)).round() as i128;
    let (mut x, mut u) = (65536i128, 0i128);
    for _ in 0..100 {
        let p = u * r - x * k;
        u = if p < 0 { -((-p) >> 29) } else { p >> 29 };
        x += u;
        s.step();
        assert_eq!(s.key(), [x, u, 0]);
    }
}
