//! Exponential friction, as UI platforms give it: what slows a thrown value down.
//!
//! A value thrown with velocity `v₀` under friction `dv/dt = −c·v` moves as
//!
//! ```text
//! v(t) = v₀·e^{−c·t}        x(t) = x₀ + (v₀/c)·(1 − e^{−c·t})
//! ```
//!
//! and comes to rest `v₀/c` from where it was thrown. Sampled every `dt`, this is exactly
//! the crate's spring step with no stiffness, `C_k = 0` and `C_d = 1 − e^{−c·dt}` (see
//! [`Decay`](crate::Decay)).
//!
//! | platform | parameter | rate `c` |
//! |---|---|---|
//! | iOS `UIScrollView.decelerationRate` | `d` per millisecond: `.normal` 0.998, `.fast` 0.99 | `−ln(d) / 1 ms` |
//! | Android `FlingAnimation.setFriction` | friction scalar `f > 0`, default 1 | `4.2·f` per second |
//!
//! Sources: UIKit's `UIScrollView.DecelerationRate` constants, a velocity kept in the
//! fraction `d` per millisecond (`v(t) = v₀·d^{t/1 ms}`); androidx `dynamicanimation`'s
//! `FlingAnimation.DragForce`, whose `setFrictionScalar(f)` sets the friction to
//! `f·DEFAULT_FRICTION` with `DEFAULT_FRICTION = −4.2` and steps the velocity as
//! `v·exp(Δt·friction)` (Δt in seconds), so `c = 4.2·f`.

use crate::error::{Bound, Error, Parameter, check, positive, tri};
use crate::math::{exp, expm1, ln};
use crate::rest::RestThreshold;

/// An exponential friction `dv/dt = −c·v`, with its rate `c` in 1/s.
///
/// Every constructor is a `const fn`; a friction that exists has a finite rate `c > 0`.
///
/// ```
/// use stiffspring::Friction;
///
/// // iOS's normal deceleration: the velocity keeps 0.998 of itself every millisecond.
/// let ios = Friction::IOS_NORMAL;
/// assert!((ios.rate() - 2.002).abs() < 1e-3);
/// // A throw at 1,000 px/s comes to rest 499.5 px further on.
/// assert!((ios.distance(1000.0) - 499.5).abs() < 0.1);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Friction {
    rate: f64,
}

/// Android's friction per unit of its friction scalar, in 1/s (`FlingAnimation`'s
/// `DEFAULT_FRICTION = −4.2`, applied as `v·exp(Δt·friction)`).
const ANDROID_RATE_PER_SCALAR: f64 = 4.2;

impl Friction {
    /// iOS `UIScrollView.DecelerationRate.normal`: 0.998 per millisecond, `c = 2.002/s`.
    ///
    /// ```
    /// let f = stiffspring::Friction::IOS_NORMAL;
    /// assert!((f.deceleration_rate() - 0.998).abs() < 1e-15);
    /// ```
    pub const IOS_NORMAL: Friction = Friction {
        rate: -1000.0 * ln(0.998),
    };
    /// iOS `UIScrollView.DecelerationRate.fast`: 0.99 per millisecond, `c = 10.05/s`.
    ///
    /// ```
    /// let f = stiffspring::Friction::IOS_FAST;
    /// assert!((f.rate() - 10.050).abs() < 1e-3);
    /// ```
    pub const IOS_FAST: Friction = Friction {
        rate: -1000.0 * ln(0.99),
    };
    /// Android `FlingAnimation`'s default friction (scalar 1): `c = 4.2/s`.
    ///
    /// ```
    /// assert_eq!(stiffspring::Friction::ANDROID_DEFAULT.rate(), 4.2);
    /// ```
    pub const ANDROID_DEFAULT: Friction = Friction {
        rate: ANDROID_RATE_PER_SCALAR,
    };

    /// A friction of rate `rate` per second: the velocity falls to `1/e` of itself in
    /// `1/rate` seconds.
    ///
    /// # Errors
    ///
    /// [`Error::NotFinite`] or [`Error::OutOfRange`] with [`Parameter::Friction`] for a
    /// rate that is NaN, infinite or `≤ 0`.
    ///
    /// ```
    /// use stiffspring::{Error, Friction, Parameter};
    ///
    /// assert_eq!(Friction::new(3.0)?.rate(), 3.0);
    /// assert_eq!(
    ///     Friction::new(f64::NAN),
    ///     Err(Error::NotFinite { parameter: Parameter::Friction })
    /// );
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub const fn new(rate: f64) -> Result<Self, Error> {
        let rate = tri!(positive(rate, Parameter::Friction));
        Ok(Friction { rate })
    }

    /// iOS's form: the fraction `rate` of its velocity a value keeps every millisecond
    /// (`UIScrollView.decelerationRate`), `c = −ln(rate) / 1 ms`.
    ///
    /// # Errors
    ///
    /// [`Error::NotFinite`] or [`Error::OutOfRange`] with [`Parameter::Friction`] for a
    /// rate outside the open interval `(0, 1)` (1 keeps all the velocity: no friction).
    ///
    /// ```
    /// use stiffspring::Friction;
    ///
    /// assert_eq!(Friction::from_deceleration_rate(0.998)?, Friction::IOS_NORMAL);
    /// assert!(Friction::from_deceleration_rate(1.0).is_err());
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub const fn from_deceleration_rate(rate: f64) -> Result<Self, Error> {
        let rate = tri!(check(
            rate,
            Parameter::Friction,
            Bound::Within { min: 0.0, max: 1.0 }
        ));
        if rate == 0.0 || rate == 1.0 {
            return Err(Error::OutOfRange {
                parameter: Parameter::Friction,
                value: rate,
                bound: Bound::Within { min: 0.0, max: 1.0 },
            });
        }
        // A rate just below 1 whose logarithm is below f64's range is no friction either.
        Friction::new(-1000.0 * ln(rate))
    }

    /// Android's form: `FlingAnimation.setFriction(friction)`, `c = 4.2·friction` per
    /// second (the default friction is 1).
    ///
    /// # Errors
    ///
    /// [`Error::NotFinite`] or [`Error::OutOfRange`] with [`Parameter::Friction`] for a
    /// friction that is NaN, infinite or `≤ 0` (Android refuses `≤ 0` too).
    ///
    /// ```
    /// use stiffspring::Friction;
    ///
    /// assert_eq!(Friction::android(1.0)?, Friction::ANDROID_DEFAULT);
    /// assert!(Friction::android(0.0).is_err());
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub const fn android(friction: f64) -> Result<Self, Error> {
        let f = tri!(positive(friction, Parameter::Friction));
        Friction::new(ANDROID_RATE_PER_SCALAR * f)
    }

    /// The rate `c`, per second.
    ///
    /// ```
    /// assert_eq!(stiffspring::Friction::new(2.0)?.rate(), 2.0);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub const fn rate(&self) -> f64 {
        self.rate
    }

    /// The fraction of its velocity a value keeps every millisecond, `e^{−c·1 ms}`
    /// (iOS's `decelerationRate`).
    ///
    /// ```
    /// let f = stiffspring::Friction::IOS_FAST;
    /// assert!((f.deceleration_rate() - 0.99).abs() < 1e-15);
    /// ```
    pub const fn deceleration_rate(&self) -> f64 {
        exp(-self.rate * 1e-3)
    }

    /// How far a value thrown at `velocity` travels before it stops: `velocity / c`.
    ///
    /// (WWDC 2018's "Designing Fluid Interfaces" projects a throw with the sum of the
    /// per-millisecond decay, `v/1000·d/(1 − d)`; the continuous friction gives
    /// `v/(−1000·ln d)`, 0.5 ms of travel more for iOS's normal rate.)
    ///
    /// ```
    /// let f = stiffspring::Friction::new(4.0)?;
    /// assert_eq!(f.distance(-800.0), -200.0);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub const fn distance(&self, velocity: f64) -> f64 {
        velocity / self.rate
    }

    /// How long a value thrown at `velocity` takes until the motion it has left is within
    /// `threshold`: its remaining travel `|v|/c·e^{−c·t}` below the position threshold and
    /// its velocity `|v|·e^{−c·t}` below the velocity threshold; 0 when it already is.
    /// This is the continuous friction's time; a [`Decay`](crate::Decay) settles on the
    /// first step after it.
    ///
    /// ```
    /// use stiffspring::{Friction, RestThreshold};
    ///
    /// let f = Friction::IOS_NORMAL;
    /// // 2,000 px/s until less than 0.75 px is left to go (and under 46.9 px/s).
    /// let t = f.settling_time(2000.0, &RestThreshold::PIXELS);
    /// assert!((t - (2000.0 / (f.rate() * 0.75)).ln() / f.rate()).abs() < 1e-12);
    /// ```
    pub fn settling_time(&self, velocity: f64, threshold: &RestThreshold) -> f64 {
        let v = if velocity < 0.0 { -velocity } else { velocity };
        // e^{−ct} ≤ p·c/|v| and e^{−ct} ≤ v_thr/|v|: the smaller fraction decides.
        let by_travel = threshold.position() * self.rate / v;
        let by_speed = threshold.velocity() / v;
        let fraction = if by_travel < by_speed {
            by_travel
        } else {
            by_speed
        };
        if fraction >= 1.0 || fraction.is_nan() {
            0.0
        } else {
            -ln(fraction) / self.rate
        }
    }

    /// `C_d = 1 − e^{−c·dt}`, the damping coefficient that samples the friction exactly
    /// every `dt`, computed without cancellation.
    pub(crate) const fn damping(&self, dt: f64) -> f64 {
        -expm1(-self.rate * dt)
    }
}
