//! Angular springs between rotating bodies (eq. 22–26, 28).
//!
//! A rotating body has an angle, an angular velocity and a moment of inertia; an angular
//! spring holds two bodies at a rest angle with opposite torques. The mathematics is the
//! distance spring's in one dimension with the angle difference as the extension, the
//! reduced moment of inertia (eq. 22/23) in place of the reduced mass, and the same
//! precomputed weights. So an [`AngularScene`] is a one-dimensional [`Scene`] whose
//! "length" kernel is the signed angle difference: the same steppers, pinned bodies,
//! sleeping and network limits, and a hot loop with no square root.
//!
//! The angle difference is **not** wrapped: a spring wound by three turns unwinds three
//! turns, like the coil spring of a clock, as the article says. Use [`WrappedAngle`] for
//! a spring that should take the short way round.
//!
//! In an angular scene, "mass" is the moment of inertia, positions are angles (radians)
//! and velocities angular velocities.

use super::Scene;
use crate::length::{LengthKernel, Sealed};
use crate::scalar::Scalar;

/// The signed angle difference `θ_b − θ_a − θ_rest`, unwrapped. For one-dimensional
/// scenes only (the axis is the first coordinate).
///
/// ```
/// use stiffspring::length::LengthKernel;
/// use stiffspring::scene::Angle;
///
/// let rest = <Angle as LengthKernel<f32>>::rest(0.5);
/// assert_eq!(<Angle as LengthKernel<f32>>::measure(&[20.0], &rest), (19.5, [1.0]));
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Angle;

impl Sealed for Angle {}

impl<S: Scalar> LengthKernel<S> for Angle {
    type Rest = S::State;
    const NAME: &'static str = "angle";
    const SIGNED_REST: bool = true;

    fn rest(angle: S) -> Self::Rest {
        angle.widen()
    }

    fn rest_length(rest: &Self::Rest) -> S {
        S::narrow(*rest)
    }

    fn flipped(rest: &Self::Rest) -> Self::Rest {
        S::state_sub(S::STATE_ZERO, *rest)
    }

    #[inline(always)]
    fn measure<const D: usize>(d: &[S::State; D], rest: &Self::Rest) -> (S::State, [S::Coef; D]) {
        let mut axis = [S::coef(0.0); D];
        if let Some(first) = axis.first_mut() {
            *first = S::coef(1.0);
        }
        let first = d.first().copied().unwrap_or(S::STATE_ZERO);
        (S::state_sub(first, *rest), axis)
    }
}

/// [`Angle`] wrapped into `[−π, π)`: the spring takes the short way round.
///
/// ```
/// use stiffspring::length::LengthKernel;
/// use stiffspring::scene::WrappedAngle;
///
/// let rest = <WrappedAngle as LengthKernel<f64>>::rest(0.0);
/// let (x, _) = <WrappedAngle as LengthKernel<f64>>::measure(&[7.0], &rest);
/// assert!((x - (7.0 - core::f64::consts::TAU)).abs() < 1e-12);
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct WrappedAngle;

impl Sealed for WrappedAngle {}

/// `x − 2π·⌊(x + π)/2π⌋`, the representative of `x` in `[−π, π)`, on the state.
trait Wrap: Scalar {
    fn wrap(state: Self::State) -> Self::State;
}

impl Wrap for f32 {
    #[inline(always)]
    fn wrap(x: f32) -> f32 {
        use core::f32::consts::{PI, TAU};
        x - TAU * libm::floorf((x + PI) * (1.0 / TAU))
    }
}

impl Wrap for f64 {
    #[inline(always)]
    fn wrap(x: f64) -> f64 {
        use core::f64::consts::{PI, TAU};
        x - TAU * libm::floor((x + PI) * (1.0 / TAU))
    }
}

#[cfg(feature = "fixed")]
macro_rules! fixed_wrap {
    ($S:ty) => {
        impl Wrap for $S {
            #[inline(always)]
            fn wrap(x: Self::State) -> Self::State {
                // On the raw state integers: the period is 2π rounded to the state's
                // format, so the wrap is exact arithmetic modulo that period.
                let period = <$S>::state_from_f64(core::f64::consts::TAU);
                let half = period / 2;
                x.saturating_add(half).rem_euclid(period) - half
            }
        }
    };
}

#[cfg(feature = "fixed")]
fixed_wrap!(fixed::types::I16F16);
#[cfg(feature = "fixed")]
fixed_wrap!(fixed::types::I32F32);

#[allow(private_bounds)]
impl<S: Wrap> LengthKernel<S> for WrappedAngle {
    type Rest = S::State;
    const NAME: &'static str = "wrapped angle";
    const SIGNED_REST: bool = true;

    fn rest(angle: S) -> Self::Rest {
        <Angle as LengthKernel<S>>::rest(angle)
    }

    fn rest_length(rest: &Self::Rest) -> S {
        <Angle as LengthKernel<S>>::rest_length(rest)
    }

    fn flipped(rest: &Self::Rest) -> Self::Rest {
        <Angle as LengthKernel<S>>::flipped(rest)
    }

    #[inline(always)]
    fn measure<const D: usize>(d: &[S::State; D], rest: &Self::Rest) -> (S::State, [S::Coef; D]) {
        let (x, axis) = <Angle as LengthKernel<S>>::measure(d, rest);
        (S::wrap(x), axis)
    }
}

/// Up to `B` rotating bodies and `K` angular springs: a one-dimensional [`Scene`] with
/// the [`Angle`] kernel. Masses are moments of inertia, positions are angles.
///
/// ```
/// use core::f64::consts::TAU;
/// use stiffspring::scene::{AngularScene, SceneConfig};
/// use stiffspring::Tuning;
///
/// // A clock spring: a flywheel on a pinned arbor, wound by three turns.
/// let dt = 1e-3;
/// let mut clock = AngularScene::<f64, 2, 1>::new(SceneConfig::new(dt)?);
/// let arbor = clock.add_pinned([0.0])?;
/// let wheel = clock.add_particle([3.0 * TAU], 0.01)?; // inertia 0.01 kg·m²
/// clock.add_spring(arbor, wheel, 0.0, &Tuning::from_frequency(2.0, 0.7, dt)?)?;
/// for _ in 0..3000 {
///     let _ = clock.step();
/// }
/// assert!(clock.position(wheel)?[0].abs() < 1e-3); // unwound all three turns
/// # Ok::<(), stiffspring::Error>(())
/// ```
pub type AngularScene<S, const B: usize, const K: usize, L = Angle> = Scene<S, 1, B, K, L>;
