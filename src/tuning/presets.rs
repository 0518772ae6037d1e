//! The spring parameters UI people already know, and their platforms' presets by name.
//!
//! Each platform describes a continuous mass–spring–damper with mass 1; each maps onto an
//! [`Oscillator`], which the exact map then samples at the caller's `dt`:
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

use super::{Oscillator, Tuning};
use crate::error::{Error, Parameter, positive};
use core::f64::consts::TAU;

/// SwiftUI's named springs.
///
/// ```
/// use stiffspring::{SwiftUiPreset, Tuning};
///
/// let bouncy = SwiftUiPreset::Bouncy.oscillator();
/// assert!((bouncy.damping_ratio() - 0.7).abs() < 1e-12);
/// let t: Tuning = bouncy.tuning(1.0 / 120.0)?;
/// # Ok::<(), stiffspring::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum SwiftUiPreset {
    /// `.smooth`, which is also `Spring()`: duration 0.5, bounce 0 (critically damped).
    Smooth,
    /// `.snappy`: duration 0.5, bounce 0.15.
    Snappy,
    /// `.bouncy`: duration 0.5, bounce 0.3.
    Bouncy,
    /// `.spring()`: response 0.5, damping fraction 0.825.
    Spring,
    /// `.interactiveSpring()`: response 0.15, damping fraction 0.86.
    InteractiveSpring,
}

impl SwiftUiPreset {
    /// Every preset, for tables and tests.
    ///
    /// ```
    /// assert_eq!(stiffspring::SwiftUiPreset::ALL.len(), 5);
    /// ```
    pub const ALL: [SwiftUiPreset; 5] = [
        SwiftUiPreset::Smooth,
        SwiftUiPreset::Snappy,
        SwiftUiPreset::Bouncy,
        SwiftUiPreset::Spring,
        SwiftUiPreset::InteractiveSpring,
    ];

    /// The continuous oscillator of the preset.
    ///
    /// ```
    /// let o = stiffspring::SwiftUiPreset::Smooth.oscillator();
    /// assert_eq!((o.frequency(), o.damping_ratio()), (2.0, 1.0));
    /// ```
    pub const fn oscillator(self) -> Oscillator {
        // (duration or response, ζ); with bounce ≥ 0, ζ = 1 − bounce.
        let (period, zeta) = match self {
            SwiftUiPreset::Smooth => (0.5, 1.0),
            SwiftUiPreset::Snappy => (0.5, 1.0 - 0.15),
            SwiftUiPreset::Bouncy => (0.5, 1.0 - 0.3),
            SwiftUiPreset::Spring => (0.5, 0.825),
            SwiftUiPreset::InteractiveSpring => (0.15, 0.86),
        };
        Oscillator::from_parts(TAU / period, zeta)
    }
}

/// Android `SpringForce` stiffness constants (and Compose's `StiffnessMediumLow`).
///
/// ```
/// assert_eq!(stiffspring::AndroidStiffness::Medium.value(), 1500.0);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum AndroidStiffness {
    /// `STIFFNESS_HIGH` = 10 000.
    High,
    /// `STIFFNESS_MEDIUM` = 1500, the default of a new `SpringForce`.
    Medium,
    /// Compose's `Spring.StiffnessMediumLow` = 400.
    MediumLow,
    /// `STIFFNESS_LOW` = 200.
    Low,
    /// `STIFFNESS_VERY_LOW` = 50.
    VeryLow,
}

impl AndroidStiffness {
    /// Every constant, for tables and tests.
    ///
    /// ```
    /// assert_eq!(stiffspring::AndroidStiffness::ALL.len(), 5);
    /// ```
    pub const ALL: [AndroidStiffness; 5] = [
        AndroidStiffness::High,
        AndroidStiffness::Medium,
        AndroidStiffness::MediumLow,
        AndroidStiffness::Low,
        AndroidStiffness::VeryLow,
    ];

    /// The stiffness value (mass 1, so `ω = √stiffness`).
    ///
    /// ```
    /// assert_eq!(stiffspring::AndroidStiffness::VeryLow.value(), 50.0);
    /// ```
    pub const fn value(self) -> f64 {
        match self {
            AndroidStiffness::High => 10_000.0,
            AndroidStiffness::Medium => 1500.0,
            AndroidStiffness::MediumLow => 400.0,
            AndroidStiffness::Low => 200.0,
            AndroidStiffness::VeryLow => 50.0,
        }
    }
}

/// Android `SpringForce` damping-ratio constants.
///
/// ```
/// assert_eq!(stiffspring::AndroidDamping::MediumBouncy.value(), 0.5);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum AndroidDamping {
    /// `DAMPING_RATIO_HIGH_BOUNCY` = 0.2.
    HighBouncy,
    /// `DAMPING_RATIO_MEDIUM_BOUNCY` = 0.5, the default of a new `SpringForce`.
    MediumBouncy,
    /// `DAMPING_RATIO_LOW_BOUNCY` = 0.75.
    LowBouncy,
    /// `DAMPING_RATIO_NO_BOUNCY` = 1.
    NoBouncy,
}

impl AndroidDamping {
    /// Every constant, for tables and tests.
    ///
    /// ```
    /// assert_eq!(stiffspring::AndroidDamping::ALL.len(), 4);
    /// ```
    pub const ALL: [AndroidDamping; 4] = [
        AndroidDamping::HighBouncy,
        AndroidDamping::MediumBouncy,
        AndroidDamping::LowBouncy,
        AndroidDamping::NoBouncy,
    ];

    /// The damping ratio.
    ///
    /// ```
    /// assert_eq!(stiffspring::AndroidDamping::NoBouncy.value(), 1.0);
    /// ```
    pub const fn value(self) -> f64 {
        match self {
            AndroidDamping::HighBouncy => 0.2,
            AndroidDamping::MediumBouncy => 0.5,
            AndroidDamping::LowBouncy => 0.75,
            AndroidDamping::NoBouncy => 1.0,
        }
    }
}

/// react-spring's `config` presets (tension, friction, mass 1).
///
/// ```
/// use stiffspring::ReactSpringPreset;
/// assert_eq!(ReactSpringPreset::Default.tension_friction(), (170.0, 26.0));
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum ReactSpringPreset {
    /// `config.default`: tension 170, friction 26.
    Default,
    /// `config.gentle`: tension 120, friction 14.
    Gentle,
    /// `config.wobbly`: tension 180, friction 12.
    Wobbly,
    /// `config.stiff`: tension 210, friction 20.
    Stiff,
    /// `config.slow`: tension 280, friction 60.
    Slow,
    /// `config.molasses`: tension 280, friction 120.
    Molasses,
}

impl ReactSpringPreset {
    /// Every preset, for tables and tests.
    ///
    /// ```
    /// assert_eq!(stiffspring::ReactSpringPreset::ALL.len(), 6);
    /// ```
    pub const ALL: [ReactSpringPreset; 6] = [
        ReactSpringPreset::Default,
        ReactSpringPreset::Gentle,
        ReactSpringPreset::Wobbly,
        ReactSpringPreset::Stiff,
        ReactSpringPreset::Slow,
        ReactSpringPreset::Molasses,
    ];

    /// `(tension, friction)` of the preset.
    ///
    /// ```
    /// use stiffspring::ReactSpringPreset;
    /// assert_eq!(ReactSpringPreset::Molasses.tension_friction(), (280.0, 120.0));
    /// ```
    pub const fn tension_friction(self) -> (f64, f64) {
        match self {
            ReactSpringPreset::Default => (170.0, 26.0),
            ReactSpringPreset::Gentle => (120.0, 14.0),
            ReactSpringPreset::Wobbly => (180.0, 12.0),
            ReactSpringPreset::Stiff => (210.0, 20.0),
            ReactSpringPreset::Slow => (280.0, 60.0),
            ReactSpringPreset::Molasses => (280.0, 120.0),
        }
    }

    /// The continuous oscillator of the preset.
    ///
    /// ```
    /// let o = stiffspring::ReactSpringPreset::Molasses.oscillator();
    /// assert!(o.damping_ratio() > 1.0); // overdamped
    /// ```
    pub fn oscillator(self) -> Oscillator {
        let (tension, friction) = self.tension_friction();
        let omega = libm::sqrt(tension);
        Oscillator::from_parts(omega, friction / (2.0 * omega))
    }
}

impl Oscillator {
    /// SwiftUI's `Spring(duration:bounce:)`: `ω = 2π/duration`; `ζ = 1 − bounce` for
    /// `bounce ≥ 0` and `1/(1 + bounce)` for `bounce < 0`.
    ///
    /// # Errors
    ///
    /// [`Error::NotFinite`], [`Error::NotPositive`] for the duration,
    /// [`Error::OutOfRange`] for a bounce outside SwiftUI's `(−1, 1]`.
    ///
    /// ```
    /// // Apple's example: duration 0.5, bounce 0.3 → stiffness 157.9, damping 17.6.
    /// let o = stiffspring::Oscillator::swiftui(0.5, 0.3)?;
    /// let w = o.angular_frequency();
    /// assert!((w * w - 157.91).abs() < 0.01);
    /// assert!((2.0 * o.damping_ratio() * w - 17.59).abs() < 0.01);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn swiftui(duration: f64, bounce: f64) -> Result<Self, Error> {
        let duration = positive(duration, Parameter::Duration)?;
        if !bounce.is_finite() {
            return Err(Error::NotFinite(Parameter::Bounce));
        }
        if bounce <= -1.0 || bounce > 1.0 {
            return Err(Error::OutOfRange(Parameter::Bounce));
        }
        let zeta = if bounce >= 0.0 {
            1.0 - bounce
        } else {
            1.0 / (1.0 + bounce)
        };
        Oscillator::from_angular_frequency(TAU / duration, zeta)
    }

    /// SwiftUI's `.spring(response:dampingFraction:)`: `ω = 2π/response`,
    /// `ζ = dampingFraction`.
    ///
    /// # Errors
    ///
    /// As [`Oscillator::from_angular_frequency`], with the response as
    /// [`Parameter::Duration`].
    ///
    /// ```
    /// let o = stiffspring::Oscillator::swiftui_response(0.5, 0.825)?;
    /// assert_eq!(o.frequency(), 2.0);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn swiftui_response(response: f64, damping_fraction: f64) -> Result<Self, Error> {
        let response = positive(response, Parameter::Duration)?;
        Oscillator::from_angular_frequency(TAU / response, damping_fraction)
    }

    /// Android `SpringForce(stiffness, dampingRatio)` with its implicit mass of 1.
    ///
    /// # Errors
    ///
    /// As [`Oscillator::from_physical`].
    ///
    /// ```
    /// use stiffspring::{AndroidDamping, AndroidStiffness, Oscillator};
    ///
    /// let o = Oscillator::android(AndroidStiffness::Medium.value(), AndroidDamping::MediumBouncy.value())?;
    /// assert!((o.angular_frequency() - 1500f64.sqrt()).abs() < 1e-12);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn android(stiffness: f64, damping_ratio: f64) -> Result<Self, Error> {
        let k = positive(stiffness, Parameter::SpringConstant)?;
        Oscillator::from_angular_frequency(libm::sqrt(k), damping_ratio)
    }

    /// react-spring's `{ tension, friction }` with its default mass of 1: tension is the
    /// spring constant and friction the damping constant.
    ///
    /// # Errors
    ///
    /// As [`Oscillator::from_physical`].
    ///
    /// ```
    /// let o = stiffspring::Oscillator::react_spring(170.0, 26.0)?;
    /// assert!((o.damping_ratio() - 26.0 / (2.0 * 170f64.sqrt())).abs() < 1e-12);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn react_spring(tension: f64, friction: f64) -> Result<Self, Error> {
        Oscillator::from_physical(tension, friction, 1.0)
    }
}

impl Tuning {
    /// The exact tuning of SwiftUI's `Spring(duration:bounce:)` at `dt`.
    ///
    /// # Errors
    ///
    /// As [`Oscillator::swiftui`] and [`Oscillator::tuning`].
    ///
    /// ```
    /// let t = stiffspring::Tuning::swiftui(0.5, 0.15, 1.0 / 120.0)?;
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn swiftui(duration: f64, bounce: f64, dt: f64) -> Result<Self, Error> {
        Oscillator::swiftui(duration, bounce)?.tuning(dt)
    }

    /// The exact tuning of Android's `SpringForce(stiffness, dampingRatio)` at `dt`.
    ///
    /// # Errors
    ///
    /// As [`Oscillator::android`] and [`Oscillator::tuning`].
    ///
    /// ```
    /// use stiffspring::{AndroidDamping, AndroidStiffness, Tuning};
    /// let t = Tuning::android(AndroidStiffness::Low.value(), AndroidDamping::NoBouncy.value(), 1.0 / 60.0)?;
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn android(stiffness: f64, damping_ratio: f64, dt: f64) -> Result<Self, Error> {
        Oscillator::android(stiffness, damping_ratio)?.tuning(dt)
    }

    /// The exact tuning of react-spring's `{ tension, friction }` at `dt`.
    ///
    /// # Errors
    ///
    /// As [`Oscillator::react_spring`] and [`Oscillator::tuning`].
    ///
    /// ```
    /// let t = stiffspring::Tuning::react_spring(170.0, 26.0, 1.0 / 60.0)?;
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn react_spring(tension: f64, friction: f64, dt: f64) -> Result<Self, Error> {
        Oscillator::react_spring(tension, friction)?.tuning(dt)
    }
}
