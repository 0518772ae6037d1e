//! The spring parameters UI people already know, and their platforms' named springs.
//!
//! Every preset, of every platform, is an [`Oscillator`] constant, and every platform's
//! parameters map onto an [`Oscillator`] through a `const fn`; the exact map then samples
//! it at the caller's `dt`, the same way for all of them:
//!
//! ```
//! use stiffspring::presets::{android, react_spring, swiftui};
//!
//! let dt = 1.0 / 60.0;
//! let a = swiftui::BOUNCY.tuning(dt)?;
//! let b = android::DEFAULT.tuning(dt)?;
//! let c = react_spring::WOBBLY.tuning(dt)?;
//! let d = android::spring_force(android::STIFFNESS_LOW, android::DAMPING_RATIO_NO_BOUNCY)?
//!     .tuning(dt)?;
//! # let _ = (a, b, c, d);
//! # Ok::<(), stiffspring::Error>(())
//! ```
//!
//! Each platform describes a continuous mass–spring–damper with mass 1:
//!
//! | platform | parameters | `ω` | `ζ` |
//! |---|---|---|---|
//! | SwiftUI `Spring(duration:bounce:)` | duration, bounce ∈ (−1, 1] | `2π/duration` | `1 − bounce` (bounce ≥ 0), `1/(1 + bounce)` (bounce < 0) |
//! | SwiftUI `.spring(response:dampingFraction:)` | response, damping fraction | `2π/response` | damping fraction |
//! | Android `SpringForce` | stiffness, dampingRatio | `√stiffness` | dampingRatio |
//! | react-spring `config` | tension, friction (mass 1) | `√tension` | `friction/(2·√tension)` |
//!
//! Sources: Apple's `Spring` documentation (its worked example, duration 0.5 and bounce
//! 0.3, gives stiffness 157.9 and damping 17.6); androidx `SpringForce`; react-spring's
//! `config` presets.

use super::Oscillator;
use crate::error::{Error, Parameter, positive, tri};
use crate::math::sqrt;
use core::f64::consts::TAU;

/// SwiftUI's springs.
pub mod swiftui {
    use super::*;

    /// `.smooth`, which is also `Spring()`: duration 0.5, bounce 0 (critically damped).
    ///
    /// ```
    /// let o = stiffspring::presets::swiftui::SMOOTH;
    /// assert_eq!((o.frequency(), o.damping_ratio()), (2.0, 1.0));
    /// ```
    pub const SMOOTH: Oscillator = Oscillator::from_parts(TAU / 0.5, 1.0);
    /// `.snappy`: duration 0.5, bounce 0.15.
    ///
    /// ```
    /// assert_eq!(stiffspring::presets::swiftui::SNAPPY.damping_ratio(), 0.85);
    /// ```
    pub const SNAPPY: Oscillator = Oscillator::from_parts(TAU / 0.5, 1.0 - 0.15);
    /// `.bouncy`: duration 0.5, bounce 0.3.
    ///
    /// ```
    /// assert_eq!(stiffspring::presets::swiftui::BOUNCY.damping_ratio(), 0.7);
    /// ```
    pub const BOUNCY: Oscillator = Oscillator::from_parts(TAU / 0.5, 1.0 - 0.3);
    /// `.spring()`: response 0.5, damping fraction 0.825.
    ///
    /// ```
    /// assert_eq!(stiffspring::presets::swiftui::SPRING.damping_ratio(), 0.825);
    /// ```
    pub const SPRING: Oscillator = Oscillator::from_parts(TAU / 0.5, 0.825);
    /// `.interactiveSpring()`: response 0.15, damping fraction 0.86.
    ///
    /// ```
    /// assert_eq!(stiffspring::presets::swiftui::INTERACTIVE_SPRING.damping_ratio(), 0.86);
    /// ```
    pub const INTERACTIVE_SPRING: Oscillator = Oscillator::from_parts(TAU / 0.15, 0.86);

    /// Every named preset with its SwiftUI name, for tables and tests.
    ///
    /// ```
    /// assert_eq!(stiffspring::presets::swiftui::ALL.len(), 5);
    /// ```
    pub const ALL: [(&str, Oscillator); 5] = [
        ("smooth", SMOOTH),
        ("snappy", SNAPPY),
        ("bouncy", BOUNCY),
        ("spring", SPRING),
        ("interactiveSpring", INTERACTIVE_SPRING),
    ];

    /// `Spring(duration:bounce:)`.
    ///
    /// # Errors
    ///
    /// [`Error::NotFinite`] or [`Error::OutOfRange`] for a duration `≤ 0` or a bounce
    /// outside `(−1, 1]`.
    ///
    /// ```
    /// use stiffspring::presets::swiftui;
    /// assert_eq!(swiftui::spring(0.5, 0.3)?, swiftui::BOUNCY);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub const fn spring(duration: f64, bounce: f64) -> Result<Oscillator, Error> {
        let duration = tri!(positive(duration, Parameter::Duration));
        // (−1, 1]: −1 itself would be an infinite damping ratio.
        let bounce = tri!(super::super::exact::within(
            bounce,
            Parameter::Bounce,
            -1.0 + f64::EPSILON,
            1.0
        ));
        let zeta = if bounce >= 0.0 {
            1.0 - bounce
        } else {
            1.0 / (1.0 + bounce)
        };
        Oscillator::from_angular_frequency(TAU / duration, zeta)
    }

    /// `.spring(response:dampingFraction:)`.
    ///
    /// # Errors
    ///
    /// [`Error::NotFinite`] or [`Error::OutOfRange`] for a response `≤ 0` or a negative
    /// damping fraction.
    ///
    /// ```
    /// use stiffspring::presets::swiftui;
    /// assert_eq!(swiftui::response(0.15, 0.86)?, swiftui::INTERACTIVE_SPRING);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub const fn response(response: f64, damping_fraction: f64) -> Result<Oscillator, Error> {
        let response = tri!(positive(response, Parameter::Duration));
        Oscillator::from_angular_frequency(TAU / response, damping_fraction)
    }
}

/// Android's `SpringForce` (and Compose's `spring()`).
pub mod android {
    use super::*;

    /// `STIFFNESS_HIGH`.
    pub const STIFFNESS_HIGH: f64 = 10_000.0;
    /// `STIFFNESS_MEDIUM`, the default of a new `SpringForce`.
    pub const STIFFNESS_MEDIUM: f64 = 1500.0;
    /// Compose's `Spring.StiffnessMediumLow`.
    pub const STIFFNESS_MEDIUM_LOW: f64 = 400.0;
    /// `STIFFNESS_LOW`.
    pub const STIFFNESS_LOW: f64 = 200.0;
    /// `STIFFNESS_VERY_LOW`.
    pub const STIFFNESS_VERY_LOW: f64 = 50.0;
    /// `DAMPING_RATIO_HIGH_BOUNCY`.
    pub const DAMPING_RATIO_HIGH_BOUNCY: f64 = 0.2;
    /// `DAMPING_RATIO_MEDIUM_BOUNCY`, the default.
    pub const DAMPING_RATIO_MEDIUM_BOUNCY: f64 = 0.5;
    /// `DAMPING_RATIO_LOW_BOUNCY`.
    pub const DAMPING_RATIO_LOW_BOUNCY: f64 = 0.75;
    /// `DAMPING_RATIO_NO_BOUNCY`.
    pub const DAMPING_RATIO_NO_BOUNCY: f64 = 1.0;

    /// Every stiffness constant with its Android name, for tables and tests.
    ///
    /// ```
    /// assert_eq!(stiffspring::presets::android::STIFFNESSES.len(), 5);
    /// ```
    pub const STIFFNESSES: [(&str, f64); 5] = [
        ("high", STIFFNESS_HIGH),
        ("medium", STIFFNESS_MEDIUM),
        ("mediumLow", STIFFNESS_MEDIUM_LOW),
        ("low", STIFFNESS_LOW),
        ("veryLow", STIFFNESS_VERY_LOW),
    ];

    /// Every damping-ratio constant with its Android name, for tables and tests.
    ///
    /// ```
    /// assert_eq!(stiffspring::presets::android::DAMPING_RATIOS.len(), 4);
    /// ```
    pub const DAMPING_RATIOS: [(&str, f64); 4] = [
        ("highBouncy", DAMPING_RATIO_HIGH_BOUNCY),
        ("mediumBouncy", DAMPING_RATIO_MEDIUM_BOUNCY),
        ("lowBouncy", DAMPING_RATIO_LOW_BOUNCY),
        ("noBouncy", DAMPING_RATIO_NO_BOUNCY),
    ];

    /// A new `SpringForce`: medium stiffness, medium bouncy.
    ///
    /// ```
    /// let o = stiffspring::presets::android::DEFAULT;
    /// assert!((o.angular_frequency() - 1500f64.sqrt()).abs() < 1e-12);
    /// ```
    pub const DEFAULT: Oscillator =
        Oscillator::from_parts(sqrt(STIFFNESS_MEDIUM), DAMPING_RATIO_MEDIUM_BOUNCY);

    /// `SpringForce().setStiffness(stiffness).setDampingRatio(damping_ratio)`.
    ///
    /// # Errors
    ///
    /// [`Error::NotFinite`] or [`Error::OutOfRange`] for a stiffness `≤ 0` or a negative
    /// damping ratio.
    ///
    /// ```
    /// use stiffspring::presets::android;
    /// let o = android::spring_force(android::STIFFNESS_MEDIUM, 0.5)?;
    /// assert_eq!(o, android::DEFAULT);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub const fn spring_force(stiffness: f64, damping_ratio: f64) -> Result<Oscillator, Error> {
        let k = tri!(positive(stiffness, Parameter::SpringConstant));
        Oscillator::from_angular_frequency(sqrt(k), damping_ratio)
    }
}

/// react-spring's `config`.
pub mod react_spring {
    use super::*;

    /// `config.default`: tension 170, friction 26.
    ///
    /// ```
    /// let o = stiffspring::presets::react_spring::DEFAULT;
    /// assert!((o.damping_ratio() - 26.0 / (2.0 * 170f64.sqrt())).abs() < 1e-15);
    /// ```
    pub const DEFAULT: Oscillator = from_config(170.0, 26.0);
    /// `config.gentle`: tension 120, friction 14.
    ///
    /// ```
    /// assert!(stiffspring::presets::react_spring::GENTLE.damping_ratio() < 1.0);
    /// ```
    pub const GENTLE: Oscillator = from_config(120.0, 14.0);
    /// `config.wobbly`: tension 180, friction 12.
    ///
    /// ```
    /// assert!(stiffspring::presets::react_spring::WOBBLY.damping_ratio() < 0.5);
    /// ```
    pub const WOBBLY: Oscillator = from_config(180.0, 12.0);
    /// `config.stiff`: tension 210, friction 20.
    ///
    /// ```
    /// assert!(stiffspring::presets::react_spring::STIFF.frequency() > 2.0);
    /// ```
    pub const STIFF: Oscillator = from_config(210.0, 20.0);
    /// `config.slow`: tension 280, friction 60.
    ///
    /// ```
    /// assert!(stiffspring::presets::react_spring::SLOW.damping_ratio() > 1.0);
    /// ```
    pub const SLOW: Oscillator = from_config(280.0, 60.0);
    /// `config.molasses`: tension 280, friction 120.
    ///
    /// ```
    /// assert!(stiffspring::presets::react_spring::MOLASSES.damping_ratio() > 3.0);
    /// ```
    pub const MOLASSES: Oscillator = from_config(280.0, 120.0);

    /// Every named preset with its react-spring name, for tables and tests.
    ///
    /// ```
    /// assert_eq!(stiffspring::presets::react_spring::ALL.len(), 6);
    /// ```
    pub const ALL: [(&str, Oscillator); 6] = [
        ("default", DEFAULT),
        ("gentle", GENTLE),
        ("wobbly", WOBBLY),
        ("stiff", STIFF),
        ("slow", SLOW),
        ("molasses", MOLASSES),
    ];

    /// A config's oscillator from valid constants.
    const fn from_config(tension: f64, friction: f64) -> Oscillator {
        let omega = sqrt(tension);
        Oscillator::from_parts(omega, friction / (2.0 * omega))
    }

    /// `{ tension, friction }` with mass 1.
    ///
    /// # Errors
    ///
    /// As [`Oscillator::from_physical`] with `k = tension`, `c = friction`, `m = 1`.
    ///
    /// ```
    /// use stiffspring::presets::react_spring;
    /// assert_eq!(react_spring::config(180.0, 12.0)?, react_spring::WOBBLY);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub const fn config(tension: f64, friction: f64) -> Result<Oscillator, Error> {
        Oscillator::from_physical(tension, friction, 1.0)
    }
}
