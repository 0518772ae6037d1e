//! A [`Tuning`] converted to one backend's numbers when the firmware is built.

use crate::error::Error;
use crate::input::gains_error;
use crate::rest::{RestBandParts, RestThreshold};
use crate::scalar::{RawGains, Scalar};
use crate::start::StartParts;
use crate::tuning::Tuning;

/// A [`Tuning`] converted to backend `S`: the gains as `S` stores them (in fixed point a
/// mantissa and a shift), the start weights and the default rest band, computed by a
/// `const fn`. Made by [`tuning!`](crate::tuning!) with a backend, a `Tuned` is computed
/// by the compiler, and [`SpringValue::from_tuned`](crate::SpringValue::from_tuned) takes
/// its numbers as they are (in fixed point it derives the fast step's form of the gains,
/// in integers): an `I16F16` firmware links no `f64` arithmetic and no float-to-fixed
/// conversion for its values' set-up (`docs/firmware.md`, the flash table).
///
/// The value it starts is the one [`SpringValue::new`](crate::SpringValue::new) builds
/// from the same tuning at run time, to the bit: both run the same conversions.
///
/// ```
/// use stiffspring::{I16F16, Motion, SpringValue, Tuned, Tuning, tuning};
///
/// const SNAPPY: Tuned<I16F16> = tuning!(Tuning::from_coefficients(0.05, 0.3, 1.0 / 60.0), I16F16);
/// let mut v = SpringValue::from_tuned([I16F16::ZERO], &SNAPPY)?;
/// v.set_target([I16F16::from_num(100)]);
/// while v.step() == Motion::Moving {}
/// assert_eq!(v.position(), [I16F16::from_num(100)]);
/// # Ok::<(), stiffspring::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Tuned<S: Scalar> {
    tuning: Tuning,
    gains: RawGains<S>,
    start: StartParts<S>,
    band: RestBandParts<S>,
}

impl<S: Scalar> Tuned<S> {
    /// `tuning` in backend `S`.
    ///
    /// # Errors
    ///
    /// What [`SpringValue::new`](crate::SpringValue::new) refuses the tuning with in
    /// backend `S`: [`Error::Unrepresentable`] for a gain the backend cannot hold, or a
    /// float's transient growth that leaves no room for its positions.
    ///
    /// ```
    /// use stiffspring::{I16F16, Tuned, Tuning};
    ///
    /// // A 0.1 Hz spring at 10 kHz: C_k = 3.9e−9 is below the least gain I16F16 holds,
    /// // 2⁻²⁴ (its state's last bit over a position's).
    /// let slow = Tuning::from_frequency(0.1, 0.5, 1e-4)?;
    /// assert!(Tuned::<I16F16>::new(&slow).is_err());
    /// assert!(Tuned::<f32>::new(&slow).is_ok());
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    #[inline]
    pub const fn new(tuning: &Tuning) -> Result<Self, Error> {
        let gains = match RawGains::new(tuning.stiffness(), tuning.damping()) {
            Some(gains) => gains,
            None => return Err(gains_error::<S>(tuning)),
        };
        let start = match StartParts::new(tuning) {
            Ok(start) => start,
            Err(e) => return Err(e),
        };
        Ok(Tuned {
            tuning: *tuning,
            gains,
            start,
            band: RestBandParts::scaled(
                &RestThreshold::DEFAULT,
                tuning.root_stiffness(),
                tuning.dt(),
            ),
        })
    }

    /// The tuning it was made from.
    ///
    /// ```
    /// use stiffspring::{Tuned, Tuning};
    /// let t = Tuning::rigid(0.01)?;
    /// assert_eq!(Tuned::<f32>::new(&t)?.tuning(), &t);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub const fn tuning(&self) -> &Tuning {
        &self.tuning
    }

    /// Its gains, start weights and default rest band (set-up only).
    #[inline]
    pub(crate) fn parts(&self) -> (S::Gains, crate::start::Start<S>, crate::rest::RestBand<S>) {
        (self.gains.get(), self.start.get(), self.band.get())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::presets;
    use fixed::types::{I16F16, I32F32};

    /// `tuning!` with a backend (evaluated by the compiler) against `Tuned::new` at run
    /// time, in every backend: the compiler's `f64` arithmetic is IEEE's, so the two are
    /// equal to the bit.
    macro_rules! compiled_as_run {
        ($tuning:expr) => {{
            const F32: Tuned<f32> = crate::tuning!($tuning, f32);
            const F64: Tuned<f64> = crate::tuning!($tuning, f64);
            const Q16: Tuned<I16F16> = crate::tuning!($tuning, I16F16);
            const Q32: Tuned<I32F32> = crate::tuning!($tuning, I32F32);
            let t = core::hint::black_box($tuning.unwrap());
            assert_eq!(F32, Tuned::new(&t).unwrap());
            assert_eq!(F64, Tuned::new(&t).unwrap());
            assert_eq!(Q16, Tuned::new(&t).unwrap());
            assert_eq!(Q32, Tuned::new(&t).unwrap());
        }};
    }

    #[test]
    fn the_compilers_conversion_is_the_run_times() {
        compiled_as_run!(Tuning::from_coefficients(0.05, 0.3, 1.0 / 60.0));
        compiled_as_run!(Tuning::from_coefficients(1.0, 1.0, 1e-3));
        compiled_as_run!(Tuning::from_frequency(2.0, 0.7, 1.0 / 120.0));
        compiled_as_run!(Tuning::from_frequency(40.0, 0.2, 1e-4));
        compiled_as_run!(Tuning::from_frequency(12.0, 10.0, 1.0 / 60.0));
        compiled_as_run!(presets::swiftui::BOUNCY.tuning(1.0 / 120.0));
    }

    /// A value from a `Tuned` is the value `SpringValue::new` builds at run time (which
    /// runs `gains_of`, `Start::new` and `RestBand::new`, not `Tuned::new`), field by
    /// field: their `Debug` prints every field, bits included.
    #[test]
    fn a_value_from_a_tuned_is_new_s_value() {
        fn same<S: Scalar>(t: &Tuning, at: f64) {
            let p = [S::from_f64(at)];
            let new = crate::SpringValue::<S, 1>::new(p, t).unwrap();
            let tuned = crate::SpringValue::<S, 1>::from_tuned(p, &Tuned::new(t).unwrap()).unwrap();
            let print = |v: &crate::SpringValue<S, 1>| {
                let mut text = heapless::String::<4096>::new();
                core::fmt::Write::write_fmt(&mut text, format_args!("{v:?}")).unwrap();
                text
            };
            assert_eq!(print(&new), print(&tuned), "{}", S::NAME);
        }
        for t in [
            Tuning::from_coefficients(0.05, 0.3, 1.0 / 60.0).unwrap(),
            Tuning::from_frequency(2.0, 0.7, 1.0 / 120.0).unwrap(),
            Tuning::from_frequency(40.0, 0.2, 1e-4).unwrap(),
            Tuning::from_frequency(12.0, 10.0, 1.0 / 60.0).unwrap(),
        ] {
            same::<f32>(&t, 3.25);
            same::<f64>(&t, 3.25);
            same::<I16F16>(&t, 3.25);
            same::<I32F32>(&t, -7.5);
        }
    }

    /// What a backend refuses, `Tuned::new` refuses with the error `SpringValue::new`
    /// gives.
    #[test]
    fn a_refused_tuning_is_the_values_error() {
        let slow = Tuning::from_frequency(0.1, 0.5, 1e-4).unwrap();
        let value = crate::SpringValue::<I16F16>::new([I16F16::ZERO], &slow).unwrap_err();
        assert_eq!(Tuned::<I16F16>::new(&slow).unwrap_err(), value);
        assert!(matches!(value, Error::Unrepresentable { limit, .. } if limit == 2f64.powi(-24)));
    }
}
