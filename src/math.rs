//! The few `f64` functions the exact map needs, as `const fn`.
//!
//! `core` has no `exp` or `sin`, and `libm`'s are not `const`, so a tuning could not be
//! computed at compile time. These are written for the arguments the exact map passes,
//! which keeps them short and small in flash when they run at set-up instead:
//!
//! - [`exp`] and [`expm1`]: Cody–Waite reduction `x = k·ln 2 + r`, `|r| ≤ ½ ln 2`, and the
//!   Taylor series of `e^r − 1` to degree 14 (the first term left out,
//!   `(½ ln 2)^15/15!`, is below `1e−19`, far under half an ulp of the result);
//! - [`sin`] for `|x| ≤ π` (the map's arguments are at most `ω_d·dt/2 < π/2` where it is
//!   not aliased), by `sin x = sin(π − x)` and the Taylor series to degree 23; larger
//!   arguments (an undersampled oscillator) are first reduced by the nearest multiple
//!   of `2π`;
//! - [`sqrt`]: Newton's iteration from a halved exponent, then one correction step;
//! - [`ln`]: the mantissa's `2·atanh((m − 1)/(m + 1))` by its series, for a friction given
//!   as a deceleration rate.
//!
//! Each is checked against `libm` to within a few units in the last place over its
//! range (`cargo test --lib math`), and the exact map built from them reproduces the
//! analytic oscillator to `1e−12` (`tests/exact_map.rs`).

use core::f64::consts::{LN_2, PI};

/// `ln 2` split so that `k·LN2_HI` is exact for `|k| < 2^11` (the low 32 bits of its
/// mantissa are zero), and `LN2_LO` the next 53 bits of the true `ln 2` (not of its
/// rounded `f64`, which is off by 2.3e−17: times `k = 1000` that alone would be 200 ulp):
/// the Cody–Waite reduction, with fdlibm's constants.
const LN2_HI: f64 = f64::from_bits(0x3fe6_2e42_fee0_0000);
const LN2_LO: f64 = f64::from_bits(0x3dea_39ef_3579_3c76);
/// `π − PI`: the part of π that its `f64` misses.
const PI_LO: f64 = 1.224_646_799_147_353_2e-16;
/// `2⁵⁰`: above it `sin` has no phase left to reduce.
const TWO_POW_50: f64 = 1_125_899_906_842_624.0;

/// `e^r − 1` for `|r| ≤ ½ ln 2 + ε`, by its Taylor series in Horner form.
const fn expm1_reduced(r: f64) -> f64 {
    // 1/n! for n = 14 down to 2.
    const C: [f64; 13] = [
        1.0 / 87_178_291_200.0,
        1.0 / 6_227_020_800.0,
        1.0 / 479_001_600.0,
        1.0 / 39_916_800.0,
        1.0 / 3_628_800.0,
        1.0 / 362_880.0,
        1.0 / 40_320.0,
        1.0 / 5_040.0,
        1.0 / 720.0,
        1.0 / 120.0,
        1.0 / 24.0,
        1.0 / 6.0,
        0.5,
    ];
    let mut p = 0.0;
    let mut i = 0;
    while i < C.len() {
        p = p * r + C[i];
        i += 1;
    }
    // r + r²·(½ + r/6 + …): the leading term exact, the rest a small correction.
    r + r * r * p
}

/// `2^k` for an integer `k` in the normal range.
const fn pow2(k: i64) -> f64 {
    f64::from_bits(((k + 1023) as u64) << 52)
}

/// `(k, r)` with `x = k·ln 2 + r`, `|r| ≤ ½ ln 2` (to rounding).
const fn reduce(x: f64) -> (i64, f64) {
    let kf = x / LN_2;
    // Round to nearest without `round` (not `const` in `core`): `as` truncates.
    let k = if kf >= 0.0 {
        (kf + 0.5) as i64
    } else {
        (kf - 0.5) as i64
    };
    let kf = k as f64;
    (k, (x - kf * LN2_HI) - kf * LN2_LO)
}

/// `e^x − 1`, accurate to a few ulp for every `x`, and exact in sign and to full
/// relative precision near 0 (where `exp(x) − 1` would cancel).
///
/// Below `−40` the result is `−1` to the last bit; above `709.78` it is `+∞`.
pub const fn expm1(x: f64) -> f64 {
    if x.is_nan() {
        return x;
    }
    if x < -40.0 {
        return -1.0;
    }
    let (k, r) = reduce(x);
    if k == 0 {
        return expm1_reduced(r);
    }
    if k > 1000 {
        return exp(x);
    }
    // e^x − 1 = 2^k·(expm1(r) + (1 − 2^−k)): the constant is exact and the sum does not
    // cancel, where exp(x) − 1 would lose the last bits of e^x near x = ±ln 2.
    pow2(k) * (expm1_reduced(r) + (1.0 - pow2(-k)))
}

/// `e^x`, accurate to a few ulp; `0` below `−745.2` and `+∞` above `709.78`.
pub const fn exp(x: f64) -> f64 {
    if x.is_nan() {
        return x;
    }
    if x > 709.782_712_893_384 {
        return f64::INFINITY;
    }
    if x < -745.2 {
        return 0.0;
    }
    let (k, r) = reduce(x);
    let m = 1.0 + expm1_reduced(r);
    // 2^k in two factors, so that results in the subnormal range (k < −1022) are formed
    // by one final, correctly rounded multiplication instead of an out-of-range exponent.
    if k < -1000 {
        m * pow2(k + 1000) * pow2(-1000)
    } else if k > 1000 {
        m * pow2(k - 1000) * pow2(1000)
    } else {
        m * pow2(k)
    }
}

/// `sin x`: accurate to a few ulp for `|x| ≤ π`. Larger arguments (an undersampled
/// oscillator's half step angle) are reduced by the nearest multiple `k` of `2π`, whose
/// product rounds once: the absolute error grows as `|k|·2⁻⁵⁰` (1e−13 at `k = 100`).
/// Beyond `2⁵⁰` no phase is left in an `f64`, and the result is 0.
pub const fn sin(x: f64) -> f64 {
    let mut x = x;
    if x > PI || x < -PI {
        if x.abs() >= TWO_POW_50 {
            return 0.0;
        }
        let turns = x / (2.0 * PI);
        let k = (turns + if turns < 0.0 { -0.5 } else { 0.5 }) as i64 as f64;
        x = (x - k * (2.0 * PI)) - k * (2.0 * PI_LO);
    }
    // Fold into [−π/2, π/2]: sin(x) = sin(π − x). `PI − x` is exact (Sterbenz) and the
    // part of π that `PI` misses is added back.
    if x > 0.5 * PI {
        x = (PI - x) + PI_LO;
    } else if x < -0.5 * PI {
        x = (-PI - x) - PI_LO;
    }
    // 1/n! with alternating signs for n = 23 down to 3; the term after, (π/2)^25/25!,
    // is 1.2e−20.
    const C: [f64; 11] = [
        -1.0 / 25_852_016_738_884_976_640_000.0,
        1.0 / 51_090_942_171_709_440_000.0,
        -1.0 / 121_645_100_408_832_000.0,
        1.0 / 355_687_428_096_000.0,
        -1.0 / 1_307_674_368_000.0,
        1.0 / 6_227_020_800.0,
        -1.0 / 39_916_800.0,
        1.0 / 362_880.0,
        -1.0 / 5_040.0,
        1.0 / 120.0,
        -1.0 / 6.0,
    ];
    let x2 = x * x;
    let mut p = 0.0;
    let mut i = 0;
    while i < C.len() {
        p = p * x2 + C[i];
        i += 1;
    }
    x + x * x2 * p
}

/// `√x` to within one ulp; `0` for `x ≤ 0` or NaN, `+∞` for `+∞`.
pub const fn sqrt(x: f64) -> f64 {
    if x.is_nan() || x <= 0.0 {
        return 0.0;
    }
    if x == f64::INFINITY {
        return x;
    }
    // Scale subnormals up so that the exponent halving below sees a normal number.
    let (x, scale) = if x < f64::MIN_POSITIVE {
        (x * pow2(108), pow2(-54))
    } else {
        (x, 1.0)
    };
    // Halve the exponent for a first guess within a factor of √2 of the root; Newton's
    // iteration then doubles the correct bits each time: 6 steps give 64.
    let mut r = f64::from_bits((x.to_bits() >> 1) + (1023u64 << 51));
    let mut i = 0;
    while i < 6 {
        r = 0.5 * (r + x / r);
        i += 1;
    }
    r * scale
}

/// `ln x` for finite `x > 0`, to a few ulp (`NaN` for `x ≤ 0` or NaN, `+∞` for `+∞`): a
/// friction given as a deceleration rate per millisecond (`−ln(rate)`) at compile time.
///
/// `x = m·2^e` with `m ∈ [√½, √2)`, then `ln m = 2·atanh(s)`, `s = (m − 1)/(m + 1)`,
/// `|s| ≤ 0.1716`, by its series to `s²³` (the first term left out, `s²⁵/25 < 2⁻⁶⁴·s`,
/// is far below half an ulp), and `e·ln 2` in the two parts of the Cody–Waite constant.
/// Near 1 (`0.998`, iOS's normal rate) `m − 1` is exact, so the result keeps its full
/// relative precision.
pub const fn ln(x: f64) -> f64 {
    if x.is_nan() || x <= 0.0 {
        return f64::NAN;
    }
    if x.is_infinite() {
        return x;
    }
    // Subnormals: scaled into the normal range first.
    let (x, bias) = if x < f64::MIN_POSITIVE {
        (x * pow2(54), -54)
    } else {
        (x, 0)
    };
    let bits = x.to_bits();
    let mut e = ((bits >> 52) & 0x7ff) as i64 - 1023 + bias;
    // The mantissa with the exponent of 1: m ∈ [1, 2).
    let mut m = f64::from_bits((bits & 0x000f_ffff_ffff_ffff) | 0x3ff0_0000_0000_0000);
    if m > core::f64::consts::SQRT_2 {
        m *= 0.5;
        e += 1;
    }
    let s = (m - 1.0) / (m + 1.0);
    let s2 = s * s;
    // 1/(2k + 1) for k = 11 down to 1.
    const C: [f64; 11] = [
        1.0 / 23.0,
        1.0 / 21.0,
        1.0 / 19.0,
        1.0 / 17.0,
        1.0 / 15.0,
        1.0 / 13.0,
        1.0 / 11.0,
        1.0 / 9.0,
        1.0 / 7.0,
        1.0 / 5.0,
        1.0 / 3.0,
    ];
    let mut p = 0.0;
    let mut i = 0;
    while i < C.len() {
        p = p * s2 + C[i];
        i += 1;
    }
    // 2s + 2s·s²·(1/3 + s²/5 + …): the leading term exact, the rest a small correction.
    let ln_m = 2.0 * s + 2.0 * s * s2 * p;
    let ef = e as f64;
    (ef * LN2_HI + ln_m) + ef * LN2_LO
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Distance in units in the last place.
    fn ulps(a: f64, b: f64) -> u64 {
        if a == b {
            return 0;
        }
        let (a, b) = (a.to_bits() as i64, b.to_bits() as i64);
        a.abs_diff(b)
    }

    fn grid(lo: f64, hi: f64, n: usize) -> impl Iterator<Item = f64> {
        (0..=n).map(move |i| lo + (hi - lo) * i as f64 / n as f64)
    }

    #[test]
    fn exp_and_expm1_agree_with_libm() {
        let mut worst = (0, 0);
        for x in grid(-745.0, 709.0, 200_000).chain(grid(-1.0, 1.0, 100_000)) {
            worst.0 = worst.0.max(ulps(exp(x), libm::exp(x)));
            worst.1 = worst.1.max(ulps(expm1(x), libm::expm1(x)));
        }
        for e in -300..0 {
            let x = 1.37f64 * 10f64.powi(e);
            worst.1 = worst.1.max(ulps(expm1(x), libm::expm1(x)));
            worst.1 = worst.1.max(ulps(expm1(-x), libm::expm1(-x)));
        }
        assert!(worst.0 <= 2 && worst.1 <= 2, "{worst:?}");
        assert_eq!(exp(710.0), f64::INFINITY);
        assert_eq!(exp(-800.0), 0.0);
        assert_eq!(expm1(-50.0), -1.0);
    }

    #[test]
    fn sin_agrees_with_libm_on_its_range() {
        let mut worst = 0;
        for x in grid(-PI, PI, 200_000) {
            let (a, b) = (sin(x), libm::sin(x));
            // Near the zeros at ±π the relative ulp distance is meaningless; compare the
            // absolute error there.
            if x.abs() > 3.0 {
                assert!((a - b).abs() < 1e-15, "{x}");
            } else {
                worst = worst.max(ulps(a, b));
            }
        }
        for e in -300..0 {
            let x = 1.37f64 * 10f64.powi(e);
            worst = worst.max(ulps(sin(x), libm::sin(x)));
        }
        assert!(worst <= 2, "{worst}");
    }

    /// Beyond ±π (an undersampled oscillator's half step angle): reduced by the nearest
    /// multiple of 2π, to within `|k|·2⁻⁵⁰` of libm.
    #[test]
    fn sin_reduces_large_arguments() {
        for x in grid(-2000.0, 2000.0, 200_001) {
            let k = (x / (2.0 * PI)).abs().round().max(1.0);
            let (a, b) = (sin(x), libm::sin(x));
            assert!((a - b).abs() <= k * 2f64.powi(-50), "{x}: {a} against {b}");
        }
        assert_eq!(sin(f64::INFINITY), 0.0);
        assert_eq!(sin(1e300), 0.0);
    }

    #[test]
    fn sqrt_is_within_an_ulp() {
        for x in grid(0.0, 4.0, 10_000)
            .chain((-1074..1024).map(|e| 1.3 * 2f64.powi(e)))
            .chain([f64::MIN_POSITIVE, 5e-324, f64::MAX])
        {
            assert!(ulps(sqrt(x), libm::sqrt(x)) <= 1, "{x}");
        }
        assert_eq!(sqrt(-1.0), 0.0);
        assert_eq!(sqrt(f64::NAN), 0.0);
        assert_eq!(sqrt(f64::INFINITY), f64::INFINITY);
    }

    #[test]
    fn ln_agrees_with_libm() {
        let mut worst = 0;
        for x in grid(1e-3, 4.0, 200_000)
            .chain(grid(0.98, 1.02, 100_000))
            .chain((-1074..1024).map(|e| 1.37 * 2f64.powi(e)))
            .chain([0.998, 0.99, f64::MIN_POSITIVE, 5e-324, f64::MAX])
            .filter(|&x| x > 0.0)
        {
            let (a, b) = (ln(x), libm::log(x));
            // Near x = 1 the result is near 0: compare the absolute error there.
            if (x - 1.0).abs() < 1e-3 {
                assert!(
                    (a - b).abs() <= 2.0 * f64::EPSILON * b.abs().max(1e-300),
                    "{x}"
                );
            } else {
                assert!(ulps(a, b) <= 2, "{x}: {a} against {b}");
                worst = worst.max(ulps(a, b));
            }
        }
        assert!(worst <= 2, "{worst}");
        assert!(ln(0.0).is_nan() && ln(-1.0).is_nan() && ln(f64::NAN).is_nan());
        assert_eq!(ln(f64::INFINITY), f64::INFINITY);
        assert_eq!(ln(1.0), 0.0);
    }
}
