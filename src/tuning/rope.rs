//! A rope's links tuned from what a designer asks for: how far the rope stretches under
//! its own weight when it hangs at rest.

use super::Tuning;
use crate::error::{Bound, Error, Parameter, check, positive, tri};

impl Tuning {
    /// The tuning of a rope's links that makes it hang `stretch` longer than its rest
    /// length under its own weight: `particles` equal particles in a chain below a pinned
    /// point, springs of rest length `link` between them (the first one to the pin),
    /// gravity `gravity` (units per second², its magnitude), stretch damping `damping`
    /// (`C_d`), at `dt`:
    ///
    /// ```text
    /// C_k = N·g·dt² / (stretch·link)
    /// ```
    ///
    /// At rest every link carries the weight of the particles below it. A spring's
    /// stiffness is `C_k·μ/dt²` with `μ` its two ends' reduced mass (eq. 20 of the
    /// article): `m` for the link to the pin, `m/2` between two particles of mass `m`. So
    /// link 1 (to the pin) stretches by `N·m·g/(C_k·m/dt²) = N·g·dt²/C_k`, link `i ≥ 2`
    /// (counted from the pin) by `2·(N − i + 1)·g·dt²/C_k`, and the whole rope by
    /// `N²·g·dt²/C_k`: a
    /// fraction `N·g·dt²/(C_k·link)` of its length `N·link`, whatever the mass.
    ///
    /// A scene's rope at rest hangs exactly so (`tests/rope_stretch.rs`, against the
    /// statics link by link, in `f64` and `f32`) with the force form
    /// ([`Stepper::Jacobi`](crate::scene::Stepper::Jacobi)), and with the default
    /// Gauss–Seidel stepper when the links have no stretch damping (`damping = 0`: damp
    /// the swing with the scene's
    /// [`linear_damping`](crate::scene::SceneConfig::linear_damping), which does nothing
    /// at rest). Gauss–Seidel with stretch damping damps, in place, the step velocity the
    /// links above each one left in the same step, and the links below the pin hang
    /// shorter: the 12-link rope of the example below stretches 4.7 %, 4.2 % and 3.7 %
    /// at `C_d` 0.1, 0.3 and 0.5 for the 5 % asked (`cargo test --release --test
    /// rope_stretch -- --nocapture`).
    ///
    /// The rope's stiffness is bounded by the rate, as every spring's is: the least
    /// stretch at `C_k = 1` is `N·g·dt²/link`, and a scene refuses links above its network
    /// limit for a chain (`scene::network_limit`). Halving `dt` quarters the least
    /// stretch.
    ///
    /// # Errors
    ///
    /// [`Error::NotFinite`] or [`Error::OutOfRange`] for `link`, `gravity`, `stretch`
    /// ([`Parameter::RestLength`], [`Parameter::Acceleration`], [`Parameter::Stretch`]:
    /// each must be positive), a `particles` of 0 ([`Parameter::ParticleCount`]), a
    /// `damping` outside `[0, 1]` or a `dt` that [`Tuning::from_coefficients`] refuses; a
    /// stretch below the least one the rate allows is [`Error::OutOfRange`] with
    /// [`Parameter::Stretch`] and that least stretch as the bound.
    ///
    /// ```
    /// use stiffspring::{Error, Parameter, Tuning};
    ///
    /// // 12 links of 0.1 m hanging 5 % long at 240 Hz.
    /// let t = Tuning::from_rope_stretch(12, 0.1, 9.81, 0.05, 0.3, 1.0 / 240.0)?;
    /// assert!((t.stiffness() - 12.0 * 9.81 / 240.0f64.powi(2) / (0.05 * 0.1)).abs() < 1e-12);
    /// // 0.1 % is stiffer than one step at 240 Hz can hold:
    /// assert!(matches!(
    ///     Tuning::from_rope_stretch(12, 0.1, 9.81, 0.001, 0.3, 1.0 / 240.0),
    ///     Err(Error::OutOfRange { parameter: Parameter::Stretch, .. })
    /// ));
    /// # Ok::<(), Error>(())
    /// ```
    pub const fn from_rope_stretch(
        particles: u32,
        link: f64,
        gravity: f64,
        stretch: f64,
        damping: f64,
        dt: f64,
    ) -> Result<Self, Error> {
        if particles == 0 {
            return Err(Error::OutOfRange {
                parameter: Parameter::ParticleCount,
                value: 0.0,
                bound: Bound::Positive,
            });
        }
        let link = tri!(positive(link, Parameter::RestLength));
        let gravity = tri!(positive(gravity, Parameter::Acceleration));
        let stretch = tri!(positive(stretch, Parameter::Stretch));
        let dt = tri!(positive(dt, Parameter::TimeStep));
        // The stretch at C_k = 1: the stiffest link one step holds.
        let least = particles as f64 * gravity * dt * dt / link;
        let stretch = tri!(check(
            stretch,
            Parameter::Stretch,
            Bound::AtLeast { min: least }
        ));
        Tuning::from_coefficients(least / stretch, damping, dt)
    }
}
