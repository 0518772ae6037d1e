//! What a spring is tuned to: a validated `(C_k, C_d)` pair, and the ways to get one.
//!
//! A [`Tuning`] is dimensionless. The article's point (eq. 13) is that `C_k` and `C_d` are
//! fractions of the stiffest and most damped spring a step can express,
//! `k_max = m/dt²` and `d_max = m/dt`, so the same pair behaves the same for any mass
//! and any `dt`. Physical units only enter through the constructors that take a `dt`:
//!
//! | constructor | input |
//! |---|---|
//! | [`Tuning::rigid`] | nothing: `C_k = C_d = 1`, at rest in two steps |
//! | [`Tuning::from_coefficients`] | `C_k, C_d ∈ [0, 1]`, the article's range |
//! | [`Tuning::from_coefficients_extended`] | up to the exact single-spring stability limit |
//! | [`Tuning::from_frequency`] | natural frequency, damping ratio, `dt` (exact map) |
//! | [`Tuning::from_physical`] | `k`, `c`, `m`, `dt` (exact map) |
//! | [`Tuning::swiftui`], [`Tuning::android`], [`Tuning::react_spring`] | the UI platforms' parameters and presets |
//!
//! and [`Tuning::oscillator`] goes back from a tuning to its frequency and damping ratio.

#[cfg(feature = "libm")]
mod exact;
#[cfg(feature = "libm")]
mod presets;

#[cfg(feature = "libm")]
pub use exact::Oscillator;
#[cfg(feature = "libm")]
pub use presets::{AndroidDamping, AndroidStiffness, ReactSpringPreset, SwiftUiPreset};

use crate::error::{Error, Parameter};

/// A validated pair of spring coefficients `C_k` (stiffness) and `C_d` (damping).
///
/// Besides `C_k` and `C_d` the tuning keeps the *retention* `1 − C_d`, the fraction of the
/// relative velocity a step keeps. The position-level step of a spring is
///
/// ```text
/// u ← (1 − C_d)·u − C_k·x        x ← x + u        (u = v·dt)
/// ```
///
/// Both are stored because each is the accurate one somewhere: the exact map computes
/// `C_d = −expm1(−2ζω·dt)` and `1 − C_d = e^{−2ζω·dt}` separately, and a heavily damped
/// spring needs the retention where `C_d` rounds to 1, while a raw `C_d` reads back exactly.
///
/// Every constructor checks its input; a `Tuning` that exists is stable (or, for the
/// undamped exact map, marginally stable with distinct poles on the unit circle).
///
/// A tuning remembers where it came from ([`Tuning::samples_oscillator`]):
///
/// - **Raw coefficients** keep the article's discrete meaning. The step velocity is
///   `v·dt`, a retarget keeps it, and a new `dt` keeps the coefficients (the article's
///   claim that behaviour per step does not depend on `dt`).
/// - **The exact map** (frequency, physical constants, presets) samples a continuous
///   oscillator. Values keep the *continuous* position and velocity across retargets,
///   flings and changes of `dt`, and a new `dt` resamples the same oscillator.
///
/// ```
/// use stiffspring::Tuning;
///
/// let t = Tuning::from_coefficients(0.2, 0.5)?;
/// assert_eq!((t.stiffness(), t.damping()), (0.2, 0.5));
/// assert_eq!(Tuning::rigid().stiffness(), 1.0);
/// # Ok::<(), stiffspring::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Tuning {
    stiffness: f64,
    damping: f64,
    retention: f64,
    sampled: bool,
}

impl Tuning {
    /// The article's stiffest spring, `C_k = C_d = 1` (eq. 12).
    ///
    /// The position reaches rest in one step for any offset, velocity, mass and `dt`, but
    /// the step velocity is then `−x₀` (the article calls the body at rest after one step;
    /// its velocity, `−x₀/dt`, is not zero): it is fully at rest only after the **second**
    /// step.
    ///
    /// ```
    /// use stiffspring::{SpringValue, Tuning};
    ///
    /// let mut v = SpringValue::<f32, 1>::new([5.0], Tuning::rigid(), 0.01)?;
    /// v.set_target([0.0])?;
    /// v.step();
    /// assert_eq!(v.position(), [0.0]); // position at rest after one step...
    /// assert_eq!(v.step_velocity(), [-5.0]); // ...but still moving
    /// v.step();
    /// assert_eq!((v.position(), v.step_velocity()), ([0.0], [0.0]));
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub const fn rigid() -> Self {
        Tuning {
            stiffness: 1.0,
            damping: 1.0,
            retention: 0.0,
            sampled: false,
        }
    }

    /// A tuning from raw coefficients in the article's range `0 ≤ C_k, C_d ≤ 1` (eq. 13).
    ///
    /// Soft, bouncy springs have values around `1e−3` to `1e−5`; `0.01` to `0.1` already
    /// looks rigid. Values above 1 are stable up to a limit but *less* stiff, see
    /// [`Tuning::from_coefficients_extended`].
    ///
    /// # Errors
    ///
    /// [`Error::NotFinite`] for NaN or infinity, [`Error::OutOfRange`] outside `[0, 1]`.
    ///
    /// ```
    /// use stiffspring::{Error, Parameter, Tuning};
    ///
    /// assert!(Tuning::from_coefficients(0.01, 0.1).is_ok());
    /// assert_eq!(
    ///     Tuning::from_coefficients(0.5, -0.1),
    ///     Err(Error::OutOfRange(Parameter::Damping))
    /// );
    /// ```
    pub fn from_coefficients(stiffness: f64, damping: f64) -> Result<Self, Error> {
        let (ck, cd) = finite_pair(stiffness, damping)?;
        if !(0.0..=1.0).contains(&ck) {
            return Err(Error::OutOfRange(Parameter::Stiffness));
        }
        if !(0.0..=1.0).contains(&cd) {
            return Err(Error::OutOfRange(Parameter::Damping));
        }
        Ok(Tuning::raw(ck, cd))
    }

    /// A tuning from raw coefficients, allowing values above 1 up to the exact
    /// single-spring stability limit.
    ///
    /// Accepts the article's square `[0, 1]²` and, beyond it, the open region where the
    /// map on `(x, u)` has both eigenvalues strictly inside the unit circle (Jury's test on
    /// `trace = 2 − C_k − C_d`, `det = 1 − C_d`):
    ///
    /// ```text
    /// C_k > 0,    0 < C_d < 2,    C_k + 2·C_d < 4
    /// ```
    ///
    /// The article warns that such springs get *less* rigid, not more; they exist because
    /// the exact map produces them for undersampled oscillators, and because a tuning near
    /// the limit is a useful stress test. Springs that share a particle have a much lower
    /// limit.
    ///
    /// # Errors
    ///
    /// [`Error::NotFinite`] for NaN or infinity, [`Error::OutOfRange`] outside both regions.
    ///
    /// ```
    /// use stiffspring::Tuning;
    ///
    /// assert!(Tuning::from_coefficients(1.5, 0.5).is_err());
    /// assert!(Tuning::from_coefficients_extended(1.5, 0.5).is_ok());
    /// assert!(Tuning::from_coefficients_extended(3.0, 0.5).is_err()); // 3 + 2·0.5 = 4
    /// ```
    pub fn from_coefficients_extended(stiffness: f64, damping: f64) -> Result<Self, Error> {
        let (ck, cd) = finite_pair(stiffness, damping)?;
        let in_square = (0.0..=1.0).contains(&ck) && (0.0..=1.0).contains(&cd);
        if in_square || is_strictly_stable(ck, cd) {
            return Ok(Tuning::raw(ck, cd));
        }
        // Name the coefficient that is out of its own range first, else blame C_k.
        if !(0.0..2.0).contains(&cd) {
            Err(Error::OutOfRange(Parameter::Damping))
        } else {
            Err(Error::OutOfRange(Parameter::Stiffness))
        }
    }

    fn raw(stiffness: f64, damping: f64) -> Self {
        Tuning {
            stiffness,
            damping,
            retention: 1.0 - damping,
            sampled: false,
        }
    }

    /// Builds a tuning from `C_k`, `C_d` and `1 − C_d`, each already computed accurately by
    /// the exact map. Accepts the stable region and its undamped edge `C_d = 0`,
    /// `0 < C_k < 4` (distinct poles on the unit circle). An undamped oscillator whose
    /// poles sit on `z = ±1` to within rounding (`C_k·(4 − C_k) = 16·sin²(ω·dt)` below
    /// `16ε`, at `f·dt = k/2`) aliases; a `C_k` that underflowed to 0 is a frequency too
    /// low for `f64` at this `dt`.
    #[cfg(feature = "libm")]
    pub(crate) fn from_map(stiffness: f64, damping: f64, retention: f64) -> Result<Self, Error> {
        let ck = stiffness;
        if ck == 0.0 && damping > 0.0 {
            return Err(Error::OutOfRange(Parameter::Frequency));
        }
        let undamped_edge = damping == 0.0 && ck * (4.0 - ck) > 16.0 * f64::EPSILON;
        if undamped_edge || is_strictly_stable(ck, damping) {
            Ok(Tuning {
                stiffness: ck,
                damping,
                retention,
                sampled: true,
            })
        } else {
            Err(Error::Aliased)
        }
    }

    /// Rebuilds a tuning from coefficients that were validated before being rounded to a
    /// backend's format (see [`crate::kernel::Coefficients::tuning`]).
    pub(crate) const fn from_parts(stiffness: f64, retention: f64, sampled: bool) -> Self {
        Tuning {
            stiffness,
            damping: 1.0 - retention,
            retention,
            sampled,
        }
    }

    /// True when the tuning came from the exact map of a continuous [`Oscillator`]
    /// (frequency, physical constants, a preset) rather than from raw coefficients.
    ///
    /// [`Oscillator`]: crate::Oscillator
    ///
    /// ```
    /// use stiffspring::Tuning;
    ///
    /// assert!(!Tuning::rigid().samples_oscillator());
    /// # #[cfg(feature = "libm")]
    /// assert!(Tuning::from_frequency(1.0, 0.5, 0.01)?.samples_oscillator());
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub const fn samples_oscillator(&self) -> bool {
        self.sampled
    }

    /// The stiffness coefficient `C_k`, a fraction of `k_max = m/dt²`.
    ///
    /// ```
    /// assert_eq!(stiffspring::Tuning::rigid().stiffness(), 1.0);
    /// ```
    pub const fn stiffness(&self) -> f64 {
        self.stiffness
    }

    /// The damping coefficient `C_d`, a fraction of `d_max = m/dt`.
    ///
    /// ```
    /// assert_eq!(stiffspring::Tuning::rigid().damping(), 1.0);
    /// ```
    pub const fn damping(&self) -> f64 {
        self.damping
    }

    /// The retention `1 − C_d`: the fraction of its relative velocity a spring keeps per
    /// step, before the stiffness term. Exact where `C_d` itself would round to 1.
    ///
    /// ```
    /// assert_eq!(stiffspring::Tuning::rigid().retention(), 0.0);
    /// ```
    pub const fn retention(&self) -> f64 {
        self.retention
    }

    /// The spectral radius of the single-spring map on `(x, u)`: the factor by which the
    /// slowest mode shrinks per step (1 for an undamped spring, 0 for [`Tuning::rigid`]).
    ///
    /// Needs only a square root, so it is available without `libm`.
    ///
    /// ```
    /// use stiffspring::Tuning;
    ///
    /// assert_eq!(Tuning::rigid().spectral_radius(), 0.0);
    /// let t = Tuning::from_coefficients(0.01, 0.0)?;
    /// assert!((t.spectral_radius() - 1.0).abs() < 1e-12);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn spectral_radius(&self) -> f64 {
        let trace = 2.0 - self.stiffness - self.damping();
        let det = self.retention;
        let disc = trace * trace - 4.0 * det;
        if disc < 0.0 {
            // Complex pair: |z|² = det.
            sqrt_f64(det)
        } else {
            // Real pair (trace ± √disc)/2: the larger magnitude takes the sign of trace.
            (trace.abs() + sqrt_f64(disc)) * 0.5
        }
    }
}

/// Jury's conditions for a second-order map with `trace = 2 − C_k − C_d` and
/// `det = 1 − C_d`: `|det| < 1`, `1 − trace + det > 0` (i.e. `C_k > 0`) and
/// `1 + trace + det > 0` (i.e. `C_k + 2·C_d < 4`).
pub(crate) fn is_strictly_stable(ck: f64, cd: f64) -> bool {
    ck > 0.0 && cd > 0.0 && cd < 2.0 && ck + 2.0 * cd < 4.0
}

fn finite_pair(ck: f64, cd: f64) -> Result<(f64, f64), Error> {
    if !ck.is_finite() {
        return Err(Error::NotFinite(Parameter::Stiffness));
    }
    if !cd.is_finite() {
        return Err(Error::NotFinite(Parameter::Damping));
    }
    Ok((ck, cd))
}

/// Square root without `libm`, for the few set-up computations that must work in a
/// `--no-default-features` build. Newton's iteration from an exponent-halved guess
/// converges to the correctly rounded root or one ULP from it in at most 7 steps.
pub(crate) fn sqrt_f64(value: f64) -> f64 {
    #[cfg(feature = "libm")]
    {
        libm::sqrt(value)
    }
    #[cfg(not(feature = "libm"))]
    {
        if !(value > 0.0) || !value.is_finite() {
            return if value == 0.0 || value.is_infinite() {
                value
            } else {
                0.0
            };
        }
        // Halve the exponent for a guess within a factor of 2 of the root.
        let bits = value.to_bits();
        let mut x = f64::from_bits((bits >> 1) + (1023u64 << 51));
        for _ in 0..8 {
            x = 0.5 * (x + value / x);
        }
        x
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn newton_root_matches_exact_values() {
        for v in [0.0, 1.0, 4.0, 2.0, 1e-300, 1e300, 0.01] {
            let r = sqrt_f64(v);
            assert!((r * r - v).abs() <= 4.0 * f64::EPSILON * v, "{v}");
        }
    }
}
