//! The two-body kernel: the impulse of eq. 27/28 in position-level form.
//!
//! Everything that springs in this crate (a UI value chasing its target, a distance or
//! angular spring in a network, the haptic knob) ends in the two functions here.
//!
//! With the step velocity `u = v·dt` and the *reduced* quantities of eq. 17–20, the
//! corrected eq. 27 (`j = −(m_red/dt)·C_k·x − m_red·C_d·v`) changes the relative step
//! velocity of the two ends by
//!
//! ```text
//! Δu_rel = −(C_k·x + C_d·u_rel)        so        u_rel' = (1 − C_d)·u_rel − C_k·x
//! ```
//!
//! ([`Coefficients::respond`]), and conservation of momentum splits it between the bodies
//! in proportion to their inverse masses ([`BodyWeights::split`]):
//!
//! ```text
//! Δu_a = −w_a·Δu_rel    Δu_b = +w_b·Δu_rel    w_a = m_red/m_a = inv_m_a/(inv_m_a + inv_m_b)
//! ```
//!
//! No `m`, `dt` or `dt²` appears: each factor is a dimensionless fraction precomputed at
//! set-up, which is what makes fixed point safe. A pinned body has inverse mass 0, so its
//! weight is 0 and the other body takes the whole change; a spring to a fixed target needs
//! no weights at all.

use crate::error::{Error, Parameter};
use crate::scalar::Scalar;
use crate::tuning::Tuning;

/// `C_k` and `1 − C_d` of one spring, in the backend's coefficient format.
///
/// ```
/// use stiffspring::{kernel::Coefficients, Tuning};
///
/// let c = Coefficients::<f32>::new(&Tuning::from_coefficients(0.25, 0.5)?);
/// // u' = (1 − 0.5)·2 − 0.25·4
/// assert_eq!(c.respond(4.0, 2.0), 0.0);
/// # Ok::<(), stiffspring::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Default)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Coefficients<S: Scalar> {
    stiffness: S::Coef,
    retention: S::Coef,
}

impl<S: Scalar> Coefficients<S> {
    /// Converts a tuning to the backend's format (set-up only).
    ///
    /// ```
    /// use stiffspring::{kernel::Coefficients, Tuning};
    ///
    /// let c = Coefficients::<f64>::new(&Tuning::rigid());
    /// assert_eq!(c.tuning(), Tuning::rigid());
    /// ```
    pub fn new(tuning: &Tuning) -> Self {
        Coefficients {
            stiffness: S::coef(tuning.stiffness()),
            retention: S::coef(tuning.retention()),
        }
    }

    /// The tuning these coefficients actually implement, after rounding to the backend's
    /// coefficient format, as raw coefficients (see [`Tuning::samples_oscillator`]).
    ///
    /// ```
    /// use stiffspring::{kernel::Coefficients, Tuning};
    ///
    /// let t = Tuning::from_coefficients(0.1, 0.2)?;
    /// let back = Coefficients::<f32>::new(&t).tuning();
    /// assert!((back.stiffness() - 0.1).abs() < 1e-8);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn tuning(&self) -> Tuning {
        // A validated tuning rounded to ≥ 24 significant bits stays inside the validated
        // region or on its closed edge; `from_parts` keeps it without re-checking.
        Tuning::from_parts(
            S::coef_to_f64(self.stiffness),
            S::coef_to_f64(self.retention),
            false,
        )
    }

    /// `C_k` in the backend's format.
    ///
    /// ```
    /// use stiffspring::{kernel::Coefficients, Tuning};
    /// assert_eq!(Coefficients::<f32>::new(&Tuning::rigid()).stiffness(), 1.0);
    /// ```
    #[inline(always)]
    pub fn stiffness(&self) -> S::Coef {
        self.stiffness
    }

    /// `1 − C_d` in the backend's format.
    ///
    /// ```
    /// use stiffspring::{kernel::Coefficients, Tuning};
    /// assert_eq!(Coefficients::<f32>::new(&Tuning::rigid()).retention(), 0.0);
    /// ```
    #[inline(always)]
    pub fn retention(&self) -> S::Coef {
        self.retention
    }

    /// The spring's new relative step velocity `(1 − C_d)·u_rel − C_k·x` for extension
    /// `x` and relative step velocity `u_rel`, rounded once (eq. 27/28 in position form).
    ///
    /// For a body on a fixed anchor this is the body's new step velocity; for two bodies
    /// hand `respond(x, u_rel) − u_rel` to [`BodyWeights::split`].
    ///
    /// ```
    /// use stiffspring::{kernel::Coefficients, Tuning};
    ///
    /// // The rigid spring cancels any offset in one step: u' = −x.
    /// let c = Coefficients::<f64>::new(&Tuning::rigid());
    /// assert_eq!(c.respond(3.0, 7.0), -3.0);
    /// ```
    #[inline(always)]
    pub fn respond(&self, extension: S, relative_step_velocity: S) -> S {
        S::mul_coef_diff(
            relative_step_velocity,
            self.retention,
            extension,
            self.stiffness,
        )
    }
}

/// How two bodies share a change of their relative velocity: `w_a`, `w_b` with
/// `w_a + w_b = 1`, precomputed from the inverse masses (or inverse moments of inertia).
///
/// ```
/// use stiffspring::kernel::BodyWeights;
///
/// // Body a is three times heavier than body b: it takes a quarter of the change.
/// let w = BodyWeights::<f64>::from_inverse_masses(1.0 / 3.0, 1.0)?;
/// assert_eq!(w.split(-4.0), (1.0, -3.0));
/// # Ok::<(), stiffspring::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Default)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct BodyWeights<S: Scalar> {
    a: S::Coef,
    b: S::Coef,
}

impl<S: Scalar> BodyWeights<S> {
    /// The weights `w_a = inv_a/(inv_a + inv_b)` and `w_b = inv_b/(inv_a + inv_b)`; an
    /// inverse mass of 0 is a pinned body (it takes nothing).
    ///
    /// # Errors
    ///
    /// [`Error::NotFinite`] or [`Error::Negative`] for an inverse mass;
    /// [`Error::NotPositive`] when both are 0 (a spring between two pinned bodies moves
    /// nothing).
    ///
    /// ```
    /// use stiffspring::kernel::BodyWeights;
    ///
    /// let pinned_a = BodyWeights::<f32>::from_inverse_masses(0.0, 2.0)?;
    /// assert_eq!(pinned_a.split(1.0), (0.0, 1.0));
    /// assert!(BodyWeights::<f32>::from_inverse_masses(0.0, 0.0).is_err());
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn from_inverse_masses(inv_a: f64, inv_b: f64) -> Result<Self, Error> {
        let inv_a = crate::error::non_negative(inv_a, Parameter::Mass)?;
        let inv_b = crate::error::non_negative(inv_b, Parameter::Mass)?;
        let largest = inv_a.max(inv_b);
        if largest <= 0.0 {
            return Err(Error::NotPositive(Parameter::Mass));
        }
        // Scaled by the larger one, so the sum lies in [1, 2] and cannot overflow.
        let (inv_a, inv_b) = (inv_a / largest, inv_b / largest);
        let sum = inv_a + inv_b;
        // Each weight is formed from its own quotient, not as 1 − the other: for a mass
        // ratio of 1e6 the light body's weight is 1 − 1e−6 and the heavy body's 1e−6,
        // and forming it as a difference would cost it its precision.
        Ok(BodyWeights {
            a: S::coef(inv_a / sum),
            b: S::coef(inv_b / sum),
        })
    }

    /// The changes of the two bodies' step velocities along the axis from `a` to `b`,
    /// for a change `delta_relative` of their relative step velocity:
    /// `(−w_a·Δ, +w_b·Δ)`, each rounded once.
    ///
    /// With equal weights the two changes are exact negatives of each other in every
    /// backend, so momentum is conserved to the bit.
    ///
    /// ```
    /// use stiffspring::kernel::BodyWeights;
    ///
    /// let w = BodyWeights::<f32>::from_inverse_masses(1.0, 1.0)?;
    /// assert_eq!(w.split(2.0), (-1.0, 1.0));
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    #[inline(always)]
    pub fn split(&self, delta_relative: S) -> (S, S) {
        (
            delta_relative.mul_coef(self.a).neg(),
            delta_relative.mul_coef(self.b),
        )
    }
}
