//! The exact sampled-response map between a continuous damped oscillator and a tuning.
//!
//! A continuous oscillator `ẍ + 2ζω·ẋ + ω²·x = 0` has poles `s₁, s₂`. Put
//! `zᵢ = e^{sᵢ·dt}`. The discrete spring `u ← u − C_k·x − C_d·u, x ← x + u` has the
//! characteristic polynomial `z² − (2 − C_k − C_d)·z + (1 − C_d)`, so choosing
//!
//! ```text
//! 1 − C_d = z₁·z₂ = e^{−2ζω·dt}        C_k = (1 − z₁)(1 − z₂)
//! ```
//!
//! gives it the same poles: started on two samples of a continuous trajectory, it hits
//! that trajectory exactly at every later sample. The naive `C_k = k·dt²/m`,
//! `C_d = c·dt/m` is only first-order accurate.
//!
//! The products are evaluated without cancellation, with `a = ζω·dt`:
//!
//! | case | `C_k` |
//! |---|---|
//! | ζ < 1 | `expm1(−a)² + 4·e^{−a}·sin²(ω_d·dt/2)`, `ω_d = ω·√((1−ζ)(1+ζ))` |
//! | ζ = 1 | `expm1(−ω·dt)²` |
//! | ζ > 1 | `expm1(−ω·dt·r₁)·expm1(−ω·dt·r₂)`, `r₂ = ζ + √((ζ−1)(ζ+1))`, `r₁ = 1/r₂` |
//!
//! Everything here is a `const fn` on the crate's own `exp`, `expm1`, `sin` and `sqrt`
//! (`src/math.rs`), so a tuning can be computed at compile time.

use super::Tuning;
use crate::error::{Bound, Error, Parameter, check, non_negative, positive, tri};
use crate::math::{exp, expm1, sin, sqrt};
use core::f64::consts::TAU;

/// A continuous damped harmonic oscillator: natural frequency and damping ratio.
///
/// It is the physical description that UI platforms and physics use;
/// [`Oscillator::tuning`] turns it into the coefficients that reproduce it exactly at a
/// given `dt`. The UI platforms' named springs are `Oscillator` constants in
/// [`presets`](crate::presets).
///
/// ```
/// use stiffspring::Oscillator;
///
/// let osc = Oscillator::new(2.0, 0.3)?; // 2 Hz, ζ = 0.3
/// let at_60 = osc.tuning(1.0 / 60.0)?;
/// assert_eq!(at_60.oscillator(), Some(osc));
/// # Ok::<(), stiffspring::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Oscillator {
    omega: f64,
    zeta: f64,
}

impl Oscillator {
    /// An oscillator of natural frequency `frequency` (Hz) and damping ratio
    /// `damping_ratio` (0 undamped, 1 critical, above 1 overdamped).
    ///
    /// # Errors
    ///
    /// [`Error::NotFinite`] or [`Error::OutOfRange`] for either.
    ///
    /// ```
    /// assert!(stiffspring::Oscillator::new(1.5, 1.0).is_ok());
    /// assert!(stiffspring::Oscillator::new(1.5, -0.1).is_err());
    /// ```
    pub const fn new(frequency: f64, damping_ratio: f64) -> Result<Self, Error> {
        let f = tri!(positive(frequency, Parameter::Frequency));
        Self::from_angular_frequency(TAU * f, damping_ratio)
    }

    /// An oscillator of angular natural frequency `omega` (rad/s).
    ///
    /// # Errors
    ///
    /// As [`Oscillator::new`].
    ///
    /// ```
    /// let o = stiffspring::Oscillator::from_angular_frequency(10.0, 0.5)?;
    /// assert_eq!(o.angular_frequency(), 10.0);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub const fn from_angular_frequency(omega: f64, damping_ratio: f64) -> Result<Self, Error> {
        let omega = tri!(positive(omega, Parameter::Frequency));
        let zeta = tri!(non_negative(damping_ratio, Parameter::DampingRatio));
        Ok(Oscillator { omega, zeta })
    }

    /// The oscillator of a mass `m` on a spring `k` with a damper `c`:
    /// `ω = √(k/m)`, `ζ = c / (2·√(k·m))`.
    ///
    /// # Errors
    ///
    /// [`Error::NotFinite`] or [`Error::OutOfRange`] for `k`, `c` and `m`, or when `√(k/m)`
    /// or `ζ` is not a finite positive `f64`.
    ///
    /// ```
    /// let o = stiffspring::Oscillator::from_physical(100.0, 2.0, 1.0)?;
    /// assert_eq!((o.angular_frequency(), o.damping_ratio()), (10.0, 0.1));
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub const fn from_physical(k: f64, c: f64, m: f64) -> Result<Self, Error> {
        let k = tri!(positive(k, Parameter::SpringConstant));
        let c = tri!(non_negative(c, Parameter::DampingConstant));
        let m = tri!(positive(m, Parameter::Mass));
        // ω = √(k/m) and ζ = c/(2√(km)) = c/(2mω); each quotient is formed once.
        let omega = sqrt(k / m);
        let zeta = c / (2.0 * m * omega);
        if !(omega > 0.0 && omega.is_finite()) {
            return Err(Error::OutOfRange {
                parameter: Parameter::SpringConstant,
                value: k,
                bound: Bound::Positive,
            });
        }
        Self::from_angular_frequency(omega, zeta)
    }

    /// An oscillator from values known to be valid (positive `omega`, non-negative `zeta`).
    pub(crate) const fn from_parts(omega: f64, zeta: f64) -> Self {
        Oscillator { omega, zeta }
    }

    /// The natural frequency in hertz.
    ///
    /// ```
    /// assert_eq!(stiffspring::Oscillator::new(3.0, 0.0)?.frequency(), 3.0);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub const fn frequency(&self) -> f64 {
        self.omega / TAU
    }

    /// The angular natural frequency `ω`, in rad/s.
    ///
    /// ```
    /// let o = stiffspring::Oscillator::new(1.0, 0.0)?;
    /// assert_eq!(o.angular_frequency(), core::f64::consts::TAU);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub const fn angular_frequency(&self) -> f64 {
        self.omega
    }

    /// The damping ratio `ζ`.
    ///
    /// ```
    /// assert_eq!(stiffspring::Oscillator::new(1.0, 0.7)?.damping_ratio(), 0.7);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub const fn damping_ratio(&self) -> f64 {
        self.zeta
    }

    /// The tuning whose discrete spring samples this oscillator exactly every `dt`.
    ///
    /// Works undersampled too: above `f·dt = 1/6` (for ζ = 0) `C_k` exceeds 1, and above
    /// `f·dt = 1/2` the samples alias, as any sampled signal does.
    ///
    /// # Errors
    ///
    /// - [`Error::NotFinite`] or [`Error::OutOfRange`] for `dt`;
    /// - [`Error::Aliased`] for an undamped oscillator at a multiple of half the sample
    ///   rate;
    /// - [`Error::OutOfRange`] with [`Parameter::Frequency`] when `ω·dt` overflows or
    ///   `C_k` underflows (a frequency too high or too low for `f64` at this `dt`);
    ///
    /// ```
    /// use stiffspring::Oscillator;
    ///
    /// let t = Oscillator::new(1.0, 1.0)?.tuning(1e-3)?;
    /// // C_d = 1 − e^{−2ωdt} ≈ 2ωdt, and C_k ≈ (ωdt)² for a well-sampled spring.
    /// assert!((t.damping() - 0.012_488).abs() < 1e-6);
    /// assert!((t.stiffness() - 3.9232e-5).abs() < 1e-8);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub const fn tuning(&self, dt: f64) -> Result<Tuning, Error> {
        let dt = tri!(positive(dt, Parameter::TimeStep));
        let wh = self.omega * dt;
        if !wh.is_finite() {
            return Err(Error::OutOfRange {
                parameter: Parameter::Frequency,
                value: self.omega / TAU,
                bound: Bound::Below {
                    max: f64::MAX / TAU / dt,
                },
            });
        }
        let z = self.zeta;
        let a = z * wh;
        let damping = -expm1(-2.0 * a);
        let stiffness = if z < 1.0 {
            let half_wdh = 0.5 * wh * sqrt((1.0 - z) * (1.0 + z));
            let decay = expm1(-a);
            let s = sin(half_wdh);
            decay * decay + 4.0 * exp(-a) * s * s
        } else if z == 1.0 {
            let decay = expm1(-wh);
            decay * decay
        } else {
            // √(ζ−1)·√(ζ+1) rather than √((ζ−1)(ζ+1)): the product overflows above 1e154.
            let r2 = z + sqrt(z - 1.0) * sqrt(z + 1.0);
            expm1(-wh / r2) * expm1(-wh * r2)
        };
        if !(stiffness > 0.0 && stiffness.is_finite()) {
            return Err(Error::OutOfRange {
                parameter: Parameter::Frequency,
                value: self.omega / TAU,
                bound: Bound::Positive,
            });
        }
        // Undamped: the poles are on the unit circle, distinct unless they meet at
        // z = ±1 (C_k·(4 − C_k) = 16·sin²(ω·dt) is then below rounding, f·dt = k/2).
        let undamped_edge = damping == 0.0 && stiffness * (4.0 - stiffness) > 16.0 * f64::EPSILON;
        if !(undamped_edge || super::is_strictly_stable(stiffness, damping)) {
            return Err(Error::Aliased {
                frequency_times_dt: wh / TAU,
            });
        }
        Ok(Tuning {
            stiffness,
            damping,
            retention: exp(-2.0 * a),
            dt,
            start: self.kept_start_weights(dt),
            oscillator: Some(*self),
            root_stiffness: 0.0,
            growth: 0.0,
        }
        .derived())
    }

    /// `(P̃, Q̃) = (1 − C_d)·(P, Q)` of [`Oscillator::start_weights`], formed so that they
    /// never overflow: `ũ₀ = e^{−2a}·(x(0) − x(−h))` with `a = ζω·h` is
    /// `x₀·(e^{−2a} − e^{−a}·C(h) + e^{−a}·S(h)·ζω) + v₀·e^{−a}·S(h)`, and `e^{−a}·C(h)`,
    /// `e^{−a}·S(h)` stay below 1 because `C` and `S` grow at most as `e^{a}`. Every
    /// difference of nearly equal terms is taken through `expm1`.
    const fn kept_start_weights(&self, dt: f64) -> (f64, f64) {
        let (w, z, h) = (self.omega, self.zeta, dt);
        let a = z * w * h;
        if z < 1.0 {
            // C = cos b, S = sin(b)/ω_d:
            // e^{−2a} − e^{−a}·cos b = expm1(−2a) − expm1(−a) + 2e^{−a}·sin²(b/2).
            let wd = w * sqrt((1.0 - z) * (1.0 + z));
            let b = wd * h;
            let s = sin(0.5 * b);
            let decay = exp(-a);
            let q = decay * sin(b) / wd;
            (
                expm1(-2.0 * a) - expm1(-a) + 2.0 * decay * s * s + q * z * w,
                q,
            )
        } else if z == 1.0 {
            // C = 1, S = h.
            let decay = exp(-a);
            let q = decay * h;
            (expm1(-2.0 * a) - expm1(-a) + q * w, q)
        } else {
            // C = cosh g, S = sinh(g)/γ, γ = ω√(ζ² − 1) < ζω:
            // e^{−a}·cosh g − 1 = ½(expm1(g − a) + expm1(−g − a)),
            // e^{−a}·sinh g = ½(expm1(g − a) − expm1(−g − a)).
            let gamma = w * sqrt((z - 1.0) * (z + 1.0));
            let g = gamma * h;
            let (up, down) = (expm1(g - a), expm1(-g - a));
            let q = 0.5 * (up - down) / gamma;
            (expm1(-2.0 * a) - 0.5 * (up + down) + q * z * w, q)
        }
    }

    /// The offset and velocity `(x(t), v(t))` of the continuous oscillator `t ≥ 0` seconds
    /// after it was at offset `offset` (from its rest position) with velocity `velocity`.
    ///
    /// The state-transition matrix of `ẍ + 2ζω·ẋ + ω²·x = 0`:
    ///
    /// ```text
    /// x(t) = e^{−ζωt}·[(C + ζω·S)·x₀ + S·v₀]        v(t) = e^{−ζωt}·[−ω²·S·x₀ + (C − ζω·S)·v₀]
    /// ```
    ///
    /// with `C = cos(ω_d·t)`, `S = sin(ω_d·t)/ω_d` (ζ < 1), `C = 1`, `S = t` (ζ = 1), and
    /// `C = cosh(γt)`, `S = sinh(γt)/γ`, `γ = ω√(ζ² − 1)` (ζ > 1; the products with
    /// `e^{−ζωt}` are formed as exponentials of `(±γ − ζω)·t`, which never overflow).
    /// Set-up and hand-over arithmetic in `f64` (libm), not a step: a
    /// [`Scroll`](crate::Scroll) uses it once per throw, to start its spring at the
    /// instant the throw crossed a bound rather than at the next frame.
    ///
    /// ```
    /// use stiffspring::Oscillator;
    ///
    /// // Undamped, 1 Hz: a quarter period after release from 1, it passes 0 at −2π.
    /// let (x, v) = Oscillator::new(1.0, 0.0)?.state_after(1.0, 0.0, 0.25);
    /// assert!(x.abs() < 1e-15 && (v + core::f64::consts::TAU).abs() < 1e-14);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn state_after(&self, offset: f64, velocity: f64, t: f64) -> (f64, f64) {
        use libm::{cos, exp, sin, sqrt};
        let (w, z) = (self.omega, self.zeta);
        let a = z * w;
        // (e^{−at}·C, e^{−at}·S)
        let (c, s) = if z < 1.0 {
            let wd = w * sqrt((1.0 - z) * (1.0 + z));
            let e = exp(-a * t);
            (e * cos(wd * t), e * sin(wd * t) / wd)
        } else if z == 1.0 {
            let e = exp(-a * t);
            (e, e * t)
        } else {
            let gamma = w * sqrt(z - 1.0) * sqrt(z + 1.0);
            let (up, down) = (exp((gamma - a) * t), exp(-(gamma + a) * t));
            (0.5 * (up + down), 0.5 * (up - down) / gamma)
        };
        (
            (c + a * s) * offset + s * velocity,
            -w * w * s * offset + (c - a * s) * velocity,
        )
    }

    /// The weights `(P, Q)` of the step velocity `u₀ = P·x₀ + Q·v₀ = x(0) − x(−dt)` that
    /// starts the discrete spring on the continuous trajectory through offset `x₀` (from
    /// the rest position) with velocity `v₀`.
    ///
    /// `v₀·dt` would be the obvious choice and is only first-order right (and a value
    /// released from rest with `u₀ = 0` is off by about `C_k/2·x₀` per step). With these
    /// weights and [`Oscillator::tuning`], every later sample is exact. Both are infinite
    /// when the backward extrapolation `x(−dt)` overflows `f64`, which takes a heavily
    /// overdamped oscillator with `ζω·dt` in the hundreds; values never need them, they
    /// keep `(1 − C_d)·u₀`, which stays finite (see [`Scalar`](crate::Scalar)).
    ///
    /// ```
    /// let (p, q) = stiffspring::Oscillator::new(1.0, 0.0)?.start_weights(1e-3);
    /// // Released from rest: x(−h) = x0·cos(ωh), so P = 1 − cos(ωh) ≈ (ωh)²/2.
    /// assert!((p - (1.0 - (core::f64::consts::TAU * 1e-3).cos())).abs() < 1e-15);
    /// assert!((q - 1e-3).abs() < 1e-8); // sin(ωh)/ω
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub const fn start_weights(&self, dt: f64) -> (f64, f64) {
        // x(t) = e^{−ζωt}·[x0·C(t) + (v0 + ζω·x0)·S(t)], with C even and S odd, so
        // x(−h) = e^{a}·[x0·C(h) − (v0 + ζω·x0)·S(h)] and
        // u0 = x0·(1 − e^{a}·C(h) + e^{a}·S(h)·ζω) + v0·e^{a}·S(h).
        let (w, z, h) = (self.omega, self.zeta, dt);
        let a = z * w * h;
        let grow = exp(a);
        let (one_minus_grow_c, s_h) = if z < 1.0 {
            // C = cos(ω_d t), S = sin(ω_d t)/ω_d; 1 − e^a·cos b = −expm1(a) + 2e^a·sin²(b/2).
            let wd = w * sqrt((1.0 - z) * (1.0 + z));
            let b = wd * h;
            let s = sin(0.5 * b);
            (-expm1(a) + 2.0 * grow * s * s, sin(b) / wd)
        } else if z == 1.0 {
            (-expm1(a), h)
        } else {
            // C = cosh(γt), S = sinh(γt)/γ with γ = ω√(ζ²−1) < ζω, so both expm1 are > 0.
            let gamma = w * sqrt((z - 1.0) * (z + 1.0));
            let g = gamma * h;
            let sinh = 0.5 * (expm1(g) - expm1(-g));
            (-0.5 * (expm1(a + g) + expm1(a - g)), sinh / gamma)
        };
        let q = grow * s_h;
        (one_minus_grow_c + q * z * w, q)
    }
}

impl Tuning {
    /// The exact tuning for natural frequency `frequency` (Hz) and damping ratio
    /// `damping_ratio`, stepped every `dt` seconds. See [`Oscillator::tuning`].
    ///
    /// # Errors
    ///
    /// As [`Oscillator::new`] and [`Oscillator::tuning`].
    ///
    /// ```
    /// let t = stiffspring::Tuning::from_frequency(2.0, 0.3, 1.0 / 60.0)?;
    /// assert!(t.stiffness() > 0.0 && t.stiffness() < 0.05);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub const fn from_frequency(
        frequency: f64,
        damping_ratio: f64,
        dt: f64,
    ) -> Result<Self, Error> {
        tri!(Oscillator::new(frequency, damping_ratio)).tuning(dt)
    }

    /// The exact tuning for a mass `m` on a spring `k` with damper `c`, stepped every
    /// `dt`. See [`Oscillator::from_physical`] and [`Oscillator::tuning`].
    ///
    /// # Errors
    ///
    /// As [`Oscillator::from_physical`] and [`Oscillator::tuning`].
    ///
    /// ```
    /// let t = stiffspring::Tuning::from_physical(400.0, 4.0, 1.0, 1e-3)?;
    /// assert!((t.stiffness() - 400.0 * 1e-6).abs() < 1e-6);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub const fn from_physical(k: f64, c: f64, m: f64, dt: f64) -> Result<Self, Error> {
        tri!(Oscillator::from_physical(k, c, m)).tuning(dt)
    }

    /// The continuous oscillator this tuning samples exactly: the stored one for a tuning
    /// from the exact map, else the inverse of the map.
    ///
    /// # Errors
    ///
    /// [`Error::NoContinuousEquivalent`] when a pole of the map is zero or negative real
    /// (any `C_d ≥ 1`, including [`Tuning::rigid`]) or `C_k = 0`.
    ///
    /// ```
    /// use stiffspring::{Error, Tuning};
    ///
    /// let t = Tuning::from_coefficients(0.04, 0.1, 1.0 / 60.0)?;
    /// let o = t.equivalent_oscillator()?;
    /// assert!((o.frequency() - 1.97).abs() < 0.01);
    /// assert_eq!(
    ///     Tuning::rigid(0.01)?.equivalent_oscillator(),
    ///     Err(Error::NoContinuousEquivalent)
    /// );
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn equivalent_oscillator(&self) -> Result<Oscillator, Error> {
        use libm::{atan2, hypot, log, log1p};
        if let Some(o) = self.oscillator {
            return Ok(o);
        }
        let h = self.dt;
        let ck = self.stiffness;
        let cd = self.damping;
        let keep = 1.0 - cd;
        if ck <= 0.0 || keep <= 0.0 {
            return Err(Error::NoContinuousEquivalent);
        }
        let sum = ck + cd;
        // 4·det − trace² = 4·C_k − (C_k + C_d)², formed without the 4 − 4 cancellation.
        let neg_disc = 4.0 * ck - sum * sum;
        let ln_keep = if keep > 0.5 { log1p(-cd) } else { log(keep) };
        let (omega, zeta) = if neg_disc > 0.0 {
            // Complex pair: |z|² = 1 − C_d, arg z = θ.
            let decay_rate = -0.5 * ln_keep / h; // ζω
            let theta = atan2(libm::sqrt(neg_disc), 1.0 + keep - ck);
            let omega = hypot(decay_rate, theta / h);
            (omega, decay_rate / omega)
        } else {
            // Real pair; both poles positive exactly when trace = 1 + keep − C_k > 0.
            // With mᵢ = 1 − zᵢ, m₁·m₂ = C_k and m₁ + m₂ = C_k + C_d.
            if 1.0 + keep - ck <= 0.0 {
                return Err(Error::NoContinuousEquivalent);
            }
            let m2 = 0.5 * (sum + libm::sqrt(-neg_disc));
            let ln_z1 = log1p(-ck / m2);
            let s1 = ln_z1 / h;
            let s2 = (ln_keep - ln_z1) / h;
            let omega = libm::sqrt(s1 * s2);
            (omega, -0.5 * (s1 + s2) / omega)
        };
        Oscillator::from_angular_frequency(omega, zeta).map_err(|_| Error::NoContinuousEquivalent)
    }
}

/// `value` if it lies in `[min, max]`, for the preset constructors.
pub(crate) const fn within(
    value: f64,
    parameter: Parameter,
    min: f64,
    max: f64,
) -> Result<f64, Error> {
    check(value, parameter, Bound::Within { min, max })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn map_round_trips_through_its_inverse() -> Result<(), Error> {
        for &f in &[0.1, 1.0, 5.0, 40.0] {
            for &z in &[0.0, 0.05, 0.5, 0.999_999, 1.0, 1.000_001, 2.0, 10.0] {
                for &dt in &[1e-4, 1e-3, 1.0 / 60.0] {
                    if f * dt >= 0.5 {
                        continue; // aliased: the inverse finds the alias, by design
                    }
                    let t = Oscillator::new(f, z)?.tuning(dt)?;
                    let raw = Tuning::from_coefficients_extended(t.stiffness(), t.damping(), dt)?;
                    let back = raw.equivalent_oscillator()?;
                    let fe = (back.frequency() - f).abs() / f;
                    let ze = (back.damping_ratio() - z).abs();
                    assert!(fe < 1e-6, "f {f} z {z} dt {dt}: {fe}");
                    assert!(ze < 1e-5, "f {f} z {z} dt {dt}: {ze}");
                }
            }
        }
        Ok(())
    }

    #[test]
    fn undamped_multiples_of_half_the_rate_alias() -> Result<(), Error> {
        let osc = Oscillator::new(50.0, 0.0)?;
        assert!(matches!(osc.tuning(0.01), Err(Error::Aliased { .. })));
        assert!(osc.tuning(0.0099).is_ok());
        Ok(())
    }

    /// An undersampled damped spring (a 503 Hz segment of a stiff rope, ζ = 0.07, at
    /// 60 Hz: `f·dt = 8.4`) is sampled exactly too: `C_k = (1 − z₁)(1 − z₂)` of its poles,
    /// computed here with libm.
    #[test]
    fn undersampled_damped_oscillators_are_sampled_exactly() -> Result<(), Error> {
        for (k, c, m, dt) in [
            (1e5, 0.0707, 0.01, 1.0 / 60.0),
            (1e5, 0.1, 0.005, 1.0 / 240.0),
            (5e3, 0.1, 0.005, 1.0 / 60.0),
        ] {
            let t = Tuning::from_physical(k, c, m, dt)?;
            let (w, z) = (libm::sqrt(k / m), c / (2.0 * libm::sqrt(k * m)));
            let a = z * w * dt;
            let b = w * libm::sqrt(1.0 - z * z) * dt;
            let s = libm::sin(0.5 * b);
            let ck = libm::expm1(-a) * libm::expm1(-a) + 4.0 * libm::exp(-a) * s * s;
            assert!((t.stiffness() - ck).abs() <= 1e-12 * ck, "{k} {c} {m} {dt}");
            let (p, q) = t.start_weights();
            let keep = libm::exp(-2.0 * a);
            let q_libm = keep * libm::exp(a) * libm::sin(b) / (w * libm::sqrt(1.0 - z * z));
            assert!((q - q_libm).abs() <= 1e-12 * dt, "{k} {c} {m} {dt}: {q}");
            assert!(p.is_finite());
        }
        Ok(())
    }

    #[test]
    fn kept_start_weights_are_the_retention_times_the_start_weights() -> Result<(), Error> {
        for (f, z, dt) in [
            (1.0, 0.1, 1e-3),
            (2.0, 1.0, 0.01),
            (3.0, 2.5, 0.02),
            (1.0, 0.0, 0.1),
        ] {
            let o = Oscillator::new(f, z)?;
            let t = o.tuning(dt)?;
            let (p, q) = o.start_weights(dt);
            let (pk, qk) = t.start_weights();
            let keep = t.retention();
            assert!(
                (pk - keep * p).abs() <= 1e-14 * (1.0 + (keep * p).abs()),
                "{f} {z} {dt}"
            );
            assert!(
                (qk - keep * q).abs() <= 1e-14 * (keep * q).abs(),
                "{f} {z} {dt}"
            );
        }
        // ζ = 300 at f·dt = 0.2: x(−dt) grows as e^{2ζω·dt} = e^{754}, beyond f64; the
        // kept weights do not.
        let t = Tuning::from_frequency(1.0, 300.0, 0.2)?;
        let (pk, qk) = t.start_weights();
        assert!(pk.is_finite() && qk.is_finite() && qk > 0.0);
        Ok(())
    }
}
