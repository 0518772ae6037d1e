//! How far content follows a finger that drags it past an end: iOS's rubber band.

use crate::error::{Error, Parameter, positive, tri};

/// A drag past an end moves the content less than the finger, the more so the farther it
/// pulls, and never by more than the view's `dimension`: the rubber band of iOS's
/// `UIScrollView`,
///
/// ```text
/// b(x) = (1 − 1/(x·c/d + 1))·d = x·c·d / (x·c + d)
/// ```
///
/// for a finger `x` past the end, the content `b` past it, the view's dimension `d` along
/// the scroll and `c = 0.55` (the constant and the formula as Grant Paul reverse-engineered
/// them from iOS in 2013; the same function underlies every "iOS-like" overscroll). Near
/// the end the content follows the finger at the rate `c` (`b'(0) = c`), and a finger that
/// pulls a whole view past it moves the content `c/(c + 1)` of a view, 35 %.
///
/// It is evaluated in `f64` on each drag event (a touch panel's rate, not the display's
/// step); the stepping code never runs it.
///
/// ```
/// use stiffspring::RubberBand;
///
/// let band = RubberBand::new(160.0)?; // a 160 px tall view
/// let b = band.stretch(100.0); // the finger is 100 px past the top
/// assert!((b - 100.0 * 0.55 * 160.0 / (100.0 * 0.55 + 160.0)).abs() < 1e-12);
/// assert!(b < 100.0 * 0.55 && b < 160.0);
/// assert!((band.finger(b) - 100.0).abs() < 1e-12); // and back
/// # Ok::<(), stiffspring::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct RubberBand {
    dimension: f64,
    constant: f64,
}

impl RubberBand {
    /// UIScrollView's constant `c = 0.55`.
    ///
    /// ```
    /// assert_eq!(stiffspring::RubberBand::IOS_CONSTANT, 0.55);
    /// ```
    pub const IOS_CONSTANT: f64 = 0.55;

    /// iOS's rubber band over a view `dimension` long along the scroll (the user's unit,
    /// pixels say).
    ///
    /// # Errors
    ///
    /// [`Error::NotFinite`] or [`Error::OutOfRange`] with [`Parameter::RubberBand`] for a
    /// dimension that is not finite and positive.
    ///
    /// ```
    /// use stiffspring::{Error, Parameter, RubberBand};
    /// assert!(RubberBand::new(0.0).is_err());
    /// assert_eq!(
    ///     RubberBand::new(f64::NAN),
    ///     Err(Error::NotFinite { parameter: Parameter::RubberBand })
    /// );
    /// ```
    pub const fn new(dimension: f64) -> Result<Self, Error> {
        let dimension = tri!(positive(dimension, Parameter::RubberBand));
        Ok(RubberBand {
            dimension,
            constant: Self::IOS_CONSTANT,
        })
    }

    /// The same band with another constant `c > 0` (stiffer below 0.55, looser above).
    ///
    /// # Errors
    ///
    /// [`Error::NotFinite`] or [`Error::OutOfRange`] with [`Parameter::RubberBand`] for a
    /// constant that is not finite and positive.
    ///
    /// ```
    /// let band = stiffspring::RubberBand::new(100.0)?.with_constant(0.3)?;
    /// assert_eq!(band.constant(), 0.3);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub const fn with_constant(self, constant: f64) -> Result<Self, Error> {
        let constant = tri!(positive(constant, Parameter::RubberBand));
        Ok(RubberBand {
            dimension: self.dimension,
            constant,
        })
    }

    /// The view's dimension `d`.
    ///
    /// ```
    /// assert_eq!(stiffspring::RubberBand::new(160.0)?.dimension(), 160.0);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub const fn dimension(&self) -> f64 {
        self.dimension
    }

    /// The constant `c`.
    ///
    /// ```
    /// assert_eq!(stiffspring::RubberBand::new(160.0)?.constant(), 0.55);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub const fn constant(&self) -> f64 {
        self.constant
    }

    /// How far the content goes past the end, `b(x)`, for a finger `past` beyond it (odd:
    /// a negative `past` gives a negative `b`). Always `|b| < d` and `|b| ≤ c·|past|`.
    ///
    /// ```
    /// let band = stiffspring::RubberBand::new(200.0)?;
    /// assert_eq!(band.stretch(-50.0), -band.stretch(50.0));
    /// assert!(band.stretch(1e12) < 200.0);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn stretch(&self, past: f64) -> f64 {
        let (c, d) = (self.constant, self.dimension);
        let x = if past.is_nan() { 0.0 } else { past };
        // x·c·d/(|x|·c + d): no cancellation, and beyond f64 the content is a view past.
        let b = x * c * d / (x.abs() * c + d);
        if b.is_nan() { d.copysign(x) } else { b }
    }

    /// The finger distance past the end that puts the content `stretched` past it: the
    /// inverse of [`RubberBand::stretch`], `x = b·d / (c·(d − |b|))`. A `|stretched| ≥ d`
    /// (which no drag reaches) gives `±f64::MAX`.
    ///
    /// ```
    /// let band = stiffspring::RubberBand::new(200.0)?;
    /// assert!((band.finger(band.stretch(37.0)) - 37.0).abs() < 1e-12);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn finger(&self, stretched: f64) -> f64 {
        let (c, d) = (self.constant, self.dimension);
        let b = if stretched.is_nan() { 0.0 } else { stretched };
        let room = d - b.abs();
        if room <= 0.0 {
            return f64::MAX.copysign(b);
        }
        let x = b * d / (c * room);
        if x.is_finite() {
            x
        } else {
            f64::MAX.copysign(b)
        }
    }

    /// How fast the content follows the finger at `past` beyond the end, `b'(x) =
    /// c·d²/(|x|·c + d)²`: `c` at the end, falling as the finger pulls farther. A
    /// finger's velocity times this is the content's velocity, with which a release past
    /// an end starts its spring back.
    ///
    /// ```
    /// let band = stiffspring::RubberBand::new(200.0)?;
    /// assert_eq!(band.slope(0.0), 0.55);
    /// assert!(band.slope(100.0) < 0.55);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn slope(&self, past: f64) -> f64 {
        let (c, d) = (self.constant, self.dimension);
        let x = if past.is_nan() { 0.0 } else { past.abs() };
        let r = d / (x * c + d);
        c * r * r
    }
}
