//! The two-body kernel of a network spring: the impulse of eq. 27/28 in position-level
//! form.
//!
//! With the step velocity `u = v·dt` and the *reduced* quantities of eq. 17–20, the
//! corrected eq. 27 (`j = −(m_red/dt)·C_k·x − m_red·C_d·v`; the article prints the
//! damping term without the mass) changes the relative step velocity of the two ends by
//!
//! ```text
//! Δ = −(C_k·x + C_d·u_rel)
//! ```
//!
//! ([`respond`]), and conservation of momentum splits it between the bodies in
//! proportion to their inverse masses ([`BodyWeights::split`]):
//!
//! ```text
//! Δu_a = −w_a·Δ    Δu_b = +w_b·Δ    w_a = m_red/m_a = inv_m_a/(inv_m_a + inv_m_b)
//! ```
//!
//! No `m`, `dt` or `dt²` appears: each factor is a dimensionless fraction precomputed at
//! set-up, which is what makes fixed point safe. A pinned body has inverse mass 0, so its
//! weight is 0 and the other body takes the whole change. A single value toward a target
//! is the same spring on a fixed anchor; it keeps its damped step velocity instead (see
//! [`Scalar`]), which only a spring with one velocity of its own can.

use crate::error::{Bound, Error, Parameter};
use crate::scalar::Scalar;

/// The change of relative step velocity `Δ = −(C_k·x + C_d·u_rel)` of a network spring
/// with extension `x` and relative step velocity `u_rel` along its axis, in the state
/// format. In fixed point the spring term is rounded toward zero and the damping term
/// away from it, as in [`Scalar::advance`].
///
/// ```
/// use stiffspring::{kernel, Scalar};
///
/// let g = f64::gains(0.25, 0.5).unwrap();
/// assert_eq!(kernel::respond::<f64>(&g, 4.0, 2.0), -2.0); // −(0.25·4 + 0.5·2)
/// ```
#[inline(always)]
pub fn respond<S: Scalar>(gains: &S::Gains, extension: S::State, relative: S::State) -> S::State {
    S::state_sub(
        S::STATE_ZERO,
        S::state_add(
            S::spring_term(gains, extension),
            S::damping_term(gains, relative),
        ),
    )
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
    a: S::Factor,
    b: S::Factor,
}

impl<S: Scalar> BodyWeights<S> {
    /// The weights `w_a = inv_a/(inv_a + inv_b)` and `w_b = inv_b/(inv_a + inv_b)`; an
    /// inverse mass of 0 is a pinned body (it takes nothing).
    ///
    /// # Errors
    ///
    /// [`Error::NotFinite`] or [`Error::OutOfRange`] for a negative inverse mass, or when
    /// both are 0 (a spring between two pinned bodies moves nothing).
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
            return Err(Error::OutOfRange {
                parameter: Parameter::Mass,
                value: 0.0,
                bound: Bound::Positive,
            });
        }
        // Scaled by the larger one, so the sum lies in [1, 2] and cannot overflow. Each
        // weight is formed from its own quotient, not as 1 − the other: for a mass ratio
        // of 1e6 the heavy body's weight is 1e−6, which a difference would lose.
        let (inv_a, inv_b) = (inv_a / largest, inv_b / largest);
        let sum = inv_a + inv_b;
        Ok(BodyWeights {
            a: S::factor(inv_a / sum),
            b: S::factor(inv_b / sum),
        })
    }

    /// The changes of the two bodies' step velocities along the axis from `a` to `b`, for
    /// a change `delta` of their relative step velocity: `(−w_a·Δ, +w_b·Δ)`, each rounded
    /// toward zero.
    ///
    /// With equal weights the two changes are the same computation, so they are exact
    /// negatives of each other in every backend and momentum is conserved to the bit.
    ///
    /// ```
    /// use stiffspring::kernel::BodyWeights;
    ///
    /// let w = BodyWeights::<f32>::from_inverse_masses(1.0, 1.0)?;
    /// assert_eq!(w.split(2.0), (-1.0, 1.0));
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    #[inline(always)]
    pub fn split(&self, delta: S::State) -> (S::State, S::State) {
        (
            S::state_sub(S::STATE_ZERO, S::scale(delta, self.a)),
            S::scale(delta, self.b),
        )
    }
}
