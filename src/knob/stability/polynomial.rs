//! The polynomial tests behind the guarantee: Schur–Cohn in the z-plane, Routh–Hurwitz
//! in the Tustin plane, and the damping-ratio sector.

use super::*;

/// Schur–Cohn on a real polynomial: every root strictly inside the unit circle.
pub(super) const fn schur(coefficients: &Poly, degree: usize) -> bool {
    let mut p = *coefficients;
    let mut n = degree;
    while n > 0 {
        if !(p[0].abs() < p[n].abs()) {
            return false;
        }
        let mut q = [0.0; 6];
        let mut scale = 0.0f64;
        let mut j = 0;
        while j < n {
            q[j] = p[n] * p[j + 1] - p[0] * p[n - 1 - j];
            scale = scale.max(q[j].abs());
            j += 1;
        }
        if !(scale > 0.0) || !scale.is_finite() {
            return false;
        }
        let mut j = 0;
        while j < 6 {
            q[j] /= scale;
            j += 1;
        }
        p = q;
        n -= 1;
    }
    true
}

/// Polynomial product (coefficients from `w⁰` up; the result must fit).
pub(super) const fn pmul<const N: usize>(a: &[f64], b: &[f64]) -> [f64; N] {
    let mut r = [0.0; N];
    let mut i = 0;
    while i < a.len() {
        let mut k = 0;
        while k < b.len() {
            if i + k < N {
                r[i + k] += a[i] * b[k];
            }
            k += 1;
        }
        i += 1;
    }
    r
}

/// The characteristic polynomial in the Tustin plane `w = (z' − 1)/(z' + 1)` of the loop
/// scaled by `r` (`z = r·z'`; roots inside `|z| < r` ⇔ roots of this in the open left
/// half-plane), given `r − 1` so that a small decay loses no digits. Built from the loop's
/// factors (`z − 1 = ((r−1) + (r+1)w)/(1 − w)`, …) rather than from the coefficients in
/// `z`, so that the gains of a soft spring, down to `C_k ≈ 1e−16`, are not lost against
/// the `O(1)` coefficients of the double pole at `z = 1`. Without stiffness the factor of
/// the rest position is divided out. Coefficients from `w⁰` up, and the degree.
pub(super) const fn tustin_polynomial(
    c: LoopCoefficients,
    delay: usize,
    r_minus_1: f64,
) -> (Poly, usize) {
    let (ck, cd, a) = (c.stiffness, c.damping, c.filter);
    let rm = r_minus_1;
    let r = 1.0 + rm;
    let d = if delay > 1 { 1 } else { delay };
    let l = [rm, 2.0 + rm]; // (z − 1)(1 − w)
    let m = [rm + a, 2.0 + rm - a]; // (z − β)(1 − w)
    let p = [2.0 + rm, rm]; // (z + 1)(1 − w)
    let zd: [f64; 2] = if d == 1 { [r, r] } else { [1.0, 0.0] }; // z^d (1 − w)^d
    let one_minus: [f64; 3] = if d == 1 {
        [1.0, -2.0, 1.0]
    } else {
        [1.0, -1.0, 0.0]
    }; // (1 − w)^(1+d)
    let n = 3 + d;
    if ck == 0.0 {
        // q/L = 2·L·M·z^d + P·C_d·α·(1 − w)^(1+d)
        let lm: [f64; 3] = pmul(&l, &m);
        let a_part: [f64; 6] = pmul(&lm, &zd);
        let b_part: [f64; 6] = pmul(&p, &one_minus);
        let mut q = [0.0; 6];
        let mut k = 0;
        while k < 6 {
            q[k] = 2.0 * a_part[k] + cd * a * b_part[k];
            k += 1;
        }
        return (q, n - 1);
    }
    // q = 2·L²·M·z^d + P·(C_k·M + C_d·α·L)·(1 − w)^(1+d)
    let ll: [f64; 3] = pmul(&l, &l);
    let llm: [f64; 4] = pmul(&ll, &m);
    let a_part: [f64; 6] = pmul(&llm, &zd);
    let ctrl = [ck * m[0] + cd * a * l[0], ck * m[1] + cd * a * l[1]];
    let pc: [f64; 3] = pmul(&p, &ctrl);
    let b_part: [f64; 6] = pmul(&pc, &one_minus);
    let mut q = [0.0; 6];
    let mut k = 0;
    while k < 6 {
        q[k] = 2.0 * a_part[k] + b_part[k];
        k += 1;
    }
    (q, n)
}

/// Routh–Hurwitz on a real polynomial (coefficients from `w⁰` up, degree `n ≤ 10`): every
/// root strictly in the left half-plane.
pub(super) const fn hurwitz(q: &[f64], n: usize) -> bool {
    if n == 0 {
        return q[0] != 0.0;
    }
    let sign = if q[n] < 0.0 { -1.0 } else { 1.0 };
    // Rows of the Routh array: row0 = a_n, a_{n−2}, …; row1 = a_{n−1}, a_{n−3}, …
    let mut r0 = [0.0; 6];
    let mut r1 = [0.0; 6];
    let mut j = 0;
    while j < 6 {
        if n >= 2 * j {
            r0[j] = sign * q[n - 2 * j];
        }
        if n > 2 * j {
            r1[j] = sign * q[n - 2 * j - 1];
        }
        j += 1;
    }
    if !(r0[0] > 0.0) {
        return false;
    }
    let mut row = 0;
    while row < n {
        if !(r1[0] > 0.0) || !r1[0].is_finite() {
            return false;
        }
        let mut r2 = [0.0; 6];
        let mut j = 0;
        while j < 5 {
            r2[j] = r0[j + 1] - r0[0] * r1[j + 1] / r1[0];
            j += 1;
        }
        // Rescale (a positive factor keeps the signs).
        let mut scale = 0.0f64;
        let mut j = 0;
        while j < 6 {
            scale = scale.max(r1[j].abs()).max(r2[j].abs());
            j += 1;
        }
        if !(scale > 0.0) || !scale.is_finite() {
            return false;
        }
        let mut zero = true;
        let mut j = 0;
        while j < 6 {
            r1[j] /= scale;
            r2[j] /= scale;
            zero &= r2[j] == 0.0;
            j += 1;
        }
        r0 = r1;
        r1 = r2;
        if zero {
            // The last row: done when the array is exhausted.
            break;
        }
        row += 1;
    }
    true
}

/// Every root of `q` (Tustin plane, no scaling) has a damping ratio `−Re w/|w|` of at
/// least [`MIN_DAMPING_RATIO`] and `|w| < NYQUIST_GUARD`.
///
/// The sector: a root `w` is in it when both `w·e^{iψ}` and `w·e^{−iψ}` are in the left
/// half-plane (`ψ = asin ζ_min`); those are the roots of `q(v·e^{−iψ})` and `q(v·e^{iψ})`,
/// whose product is a real polynomial, `Q_m = Σ_{k+l=m} q_k·q_l·cos((k − l)·ψ)`, tested by
/// Routh–Hurwitz.
pub(super) const fn damped(q: &Poly, n: usize) -> bool {
    // No root at |w| ≥ guard: q(guard·u) has its roots inside the unit circle.
    let mut scaled = *q;
    let mut g = 1.0;
    let mut k = 0;
    while k <= n && k < 6 {
        scaled[k] *= g;
        g *= NYQUIST_GUARD;
        k += 1;
    }
    if !schur(&scaled, n) {
        return false;
    }
    // cos(kψ) for k = 0..=n by the recurrence cos((k+1)ψ) = 2cosψ·cos(kψ) − cos((k−1)ψ).
    let mut cos = [0.0; 6];
    cos[0] = 1.0;
    cos[1] = SECTOR_COS;
    let mut k = 2;
    while k <= n {
        cos[k] = 2.0 * SECTOR_COS * cos[k - 1] - cos[k - 2];
        k += 1;
    }
    let mut product = [0.0; 11];
    let mut k = 0;
    while k <= n {
        let mut l = 0;
        while l <= n {
            product[k + l] += q[k] * q[l] * cos[k.abs_diff(l)];
            l += 1;
        }
        k += 1;
    }
    hurwitz(&product, 2 * n)
}
