//! What a spring is tuned to: a validated `(C_k, C_d)` pair *sampled at a time step*, and
//! the ways to get one.
//!
//! A [`Tuning`] carries its `dt`. A value or a batch takes its time step from its tuning,
//! so the two cannot disagree; a scene checks every spring's tuning against its own `dt`
//! and rejects a mismatch ([`Error::TimeStepMismatch`]).
//!
//! | constructor | input |
//! |---|---|
//! | [`Tuning::rigid`] | `dt`: `C_k = C_d = 1`, at rest in two steps |
//! | [`Tuning::from_coefficients`] | `C_k, C_d ∈ [0, 1]`, the article's range, and `dt` |
//! | [`Tuning::from_coefficients_extended`] | up to the exact single-spring stability limit |
//! | [`Tuning::from_frequency`] | natural frequency, damping ratio, `dt` (exact map) |
//! | [`Tuning::from_physical`] | `k`, `c`, `m`, `dt` (exact map) |
//! | [`Oscillator::tuning`] | any [`Oscillator`], the presets among them ([`presets`]) |
//!
//! Every constructor is a `const fn`, so a tuning can be computed at compile time: a
//! firmware then carries two coefficients and no maths library. The [`tuning!`] macro
//! does it and turns an invalid tuning into a compile error:
//!
//! ```
//! use stiffspring::{tuning, Tuning};
//!
//! const CARD: Tuning = tuning!(Tuning::from_frequency(2.0, 0.7, 1.0 / 60.0));
//! assert_eq!(CARD.dt(), 1.0 / 60.0);
//! ```
//!
//! [`Error::TimeStepMismatch`]: crate::Error::TimeStepMismatch
//! [`tuning!`]: crate::tuning!

mod exact;
pub mod presets;
mod rope;
mod settling;
mod tuned;

pub use exact::Oscillator;
pub use settling::MAX_SETTLING_STEPS;
pub use tuned::Tuned;

use crate::error::{Bound, Error, Parameter, check, positive, tri};
use crate::friction::Friction;
use crate::math;

/// A validated pair of spring coefficients `C_k` (stiffness) and `C_d` (damping),
/// sampled every `dt` seconds.
///
/// The position-level step of a spring is (eq. 27/28 with `u = v·dt`)
///
/// ```text
/// u ← u − (C_k·x + C_d·u)        x ← x + u
/// ```
///
/// Every constructor checks its input; a `Tuning` that exists is stable (or, for an
/// undamped oscillator, marginally stable with distinct poles on the unit circle).
///
/// A tuning remembers where it came from:
///
/// - **Raw coefficients** keep the article's discrete meaning: a velocity `v` is the
///   step velocity `v·dt`, and [`Tuning::with_dt`] keeps the coefficients (the article's
///   claim that behaviour per step does not depend on `dt`).
/// - **The exact map** (frequency, physical constants, presets) samples a continuous
///   [`Oscillator`]: values keep the continuous position and velocity across retargets,
///   flings and retunes, and [`Tuning::with_dt`] resamples the same oscillator.
///
/// ```
/// use stiffspring::Tuning;
///
/// let t = Tuning::from_coefficients(0.2, 0.5, 0.01)?;
/// assert_eq!((t.stiffness(), t.damping(), t.dt()), (0.2, 0.5, 0.01));
/// # Ok::<(), stiffspring::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Tuning {
    stiffness: f64,
    damping: f64,
    /// `1 − C_d`, accurate where `C_d` rounds to 1 (the exact map computes it directly).
    retention: f64,
    dt: f64,
    /// `P̃` and `Q̃` of the kept step velocity `ũ = (1 − C_d)·u = P̃·x + Q̃·v`.
    start: (f64, f64),
    oscillator: Option<Oscillator>,
    /// `√C_k` and [`Tuning::growth`], derived once when the tuning is made (see
    /// [`Tuning::derived`]): a tuning computed at compile time carries them, and a
    /// firmware that sets a value up from it runs no square root nor division in `f64`.
    root_stiffness: f64,
    growth: f64,
}

/// Computes a [`Tuning`] at compile time; an invalid one is a compile error.
///
/// Takes any expression of type `Result<Tuning, Error>` that can be evaluated in a
/// `const` context (every constructor of [`Tuning`] and [`Oscillator`] can).
///
/// ```
/// use stiffspring::{presets, tuning, Tuning};
///
/// const KNOB: Tuning = tuning!(Tuning::from_frequency(40.0, 0.7, 1e-4));
/// const BOUNCY: Tuning = tuning!(presets::swiftui::BOUNCY.tuning(1.0 / 120.0));
/// assert!(KNOB.stiffness() > 0.0 && BOUNCY.damping() > 0.0);
/// ```
///
/// ```compile_fail
/// use stiffspring::{tuning, Tuning};
/// const BAD: Tuning = tuning!(Tuning::from_coefficients(2.0, 0.5, 0.01)); // C_k > 1
/// ```
///
/// With a backend, `tuning!(expr, S)` also converts the tuning to that backend's numbers
/// ([`Tuned`]), for [`SpringValue::from_tuned`](crate::SpringValue::from_tuned); a tuning
/// the backend cannot hold is a compile error too.
///
/// ```
/// use stiffspring::{I16F16, SpringValue, Tuned, Tuning, tuning};
///
/// const UI: Tuned<I16F16> = tuning!(Tuning::from_frequency(3.0, 0.8, 1.0 / 60.0), I16F16);
/// let v = SpringValue::from_tuned([I16F16::from_num(12)], &UI)?;
/// assert_eq!(v.position(), [I16F16::from_num(12)]);
/// # Ok::<(), stiffspring::Error>(())
/// ```
///
/// ```compile_fail
/// use stiffspring::{I16F16, Tuned, Tuning, tuning};
/// // A 0.1 Hz spring at 10 kHz: C_k = 3.9e−9, below the least gain I16F16 holds.
/// const SLOW: Tuned<I16F16> = tuning!(Tuning::from_frequency(0.1, 0.5, 1e-4), I16F16);
/// ```
#[macro_export]
macro_rules! tuning {
    ($tuning:expr) => {
        const {
            match $tuning {
                ::core::result::Result::Ok(t) => t,
                ::core::result::Result::Err(_) => {
                    ::core::panic!("invalid tuning: evaluate it at run time to see the Error")
                }
            }
        }
    };
    ($tuning:expr, $backend:ty) => {
        const {
            match $crate::Tuned::<$backend>::new(&$crate::tuning!($tuning)) {
                ::core::result::Result::Ok(t) => t,
                ::core::result::Result::Err(_) => ::core::panic!(
                    "the backend cannot hold this tuning: evaluate Tuned::new at run time to see the Error"
                ),
            }
        }
    };
}

impl Tuning {
    /// The article's stiffest spring, `C_k = C_d = 1` (eq. 12), at `dt`.
    ///
    /// The position reaches its target in one step for any offset, velocity, mass and
    /// `dt`, as the article says. The article also implies the body is then at rest; it
    /// is not quite: its velocity after that step is `−x₀/dt` (the step's displacement).
    /// `C_d = 1` removes all of it in the next step, so the second step does not move
    /// and a value keeps none of it ([`SpringValue::velocity`](crate::SpringValue::velocity)
    /// reads 0).
    ///
    /// # Errors
    ///
    /// [`Error::NotFinite`] or [`Error::OutOfRange`] for `dt`.
    ///
    /// ```
    /// use stiffspring::{Motion, SpringValue, Tuning};
    ///
    /// let mut v = SpringValue::<f32>::new([5.0], &Tuning::rigid(0.01)?)?;
    /// v.set_target([0.0]);
    /// assert_eq!(v.step(), Motion::Settled); // on target after one step
    /// assert_eq!(v.position(), [0.0]);
    /// assert_eq!(v.step(), Motion::Resting);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub const fn rigid(dt: f64) -> Result<Self, Error> {
        Tuning::from_coefficients(1.0, 1.0, dt)
    }

    /// A tuning from raw coefficients in the article's range `0 ≤ C_k, C_d ≤ 1` (eq. 13),
    /// stepped every `dt`.
    ///
    /// Soft, bouncy springs have values around `1e−3` to `1e−5`; `0.01` to `0.1` already
    /// looks rigid. Values above 1 are stable up to a limit but *less* stiff, see
    /// [`Tuning::from_coefficients_extended`]. `C_k = C_d = 0` (nothing pulls, nothing
    /// damps) is rejected: a value would drift for ever.
    ///
    /// # Errors
    ///
    /// [`Error::NotFinite`] for NaN or infinity, [`Error::OutOfRange`] outside `[0, 1]`
    /// or for `dt ≤ 0`.
    ///
    /// ```
    /// use stiffspring::{Bound, Error, Parameter, Tuning};
    ///
    /// assert!(Tuning::from_coefficients(0.01, 0.1, 0.01).is_ok());
    /// assert_eq!(
    ///     Tuning::from_coefficients(1.5, 0.1, 0.01),
    ///     Err(Error::OutOfRange {
    ///         parameter: Parameter::Stiffness,
    ///         value: 1.5,
    ///         bound: Bound::Within { min: 0.0, max: 1.0 }
    ///     })
    /// );
    /// ```
    pub const fn from_coefficients(stiffness: f64, damping: f64, dt: f64) -> Result<Self, Error> {
        let unit = Bound::Within { min: 0.0, max: 1.0 };
        let ck = tri!(check(stiffness, Parameter::Stiffness, unit));
        let cd = tri!(check(damping, Parameter::Damping, unit));
        if ck == 0.0 && cd == 0.0 {
            return Err(Error::OutOfRange {
                parameter: Parameter::Stiffness,
                value: 0.0,
                bound: Bound::Positive,
            });
        }
        Tuning::raw(ck, cd, dt)
    }

    /// A tuning from raw coefficients, allowing values above 1 up to the exact
    /// single-spring stability limit.
    ///
    /// Accepts the article's square `[0, 1]²` (less the origin) and, beyond it, the open
    /// region where the map on `(x, u)` has both eigenvalues strictly inside the unit
    /// circle (Jury's test on `trace = 2 − C_k − C_d`, `det = 1 − C_d`):
    ///
    /// ```text
    /// C_k > 0,    0 < C_d < 2,    C_k + 2·C_d < 4
    /// ```
    ///
    /// The article warns that such springs get *less* rigid, not more; they exist because
    /// the exact map produces them for undersampled oscillators, and because a tuning near
    /// the limit is a useful stress test.
    ///
    /// # Errors
    ///
    /// [`Error::NotFinite`] for NaN or infinity, [`Error::OutOfRange`] outside both regions
    /// (naming `C_d` when it is outside `[0, 2)`, else `C_k`, with `C_k`'s upper limit
    /// `4 − 2·C_d`).
    ///
    /// ```
    /// use stiffspring::Tuning;
    ///
    /// assert!(Tuning::from_coefficients(1.5, 0.5, 0.01).is_err());
    /// assert!(Tuning::from_coefficients_extended(1.5, 0.5, 0.01).is_ok());
    /// assert!(Tuning::from_coefficients_extended(3.0, 0.5, 0.01).is_err()); // 3 + 2·0.5 = 4
    /// ```
    pub const fn from_coefficients_extended(
        stiffness: f64,
        damping: f64,
        dt: f64,
    ) -> Result<Self, Error> {
        let ck = tri!(check(stiffness, Parameter::Stiffness, Bound::NonNegative));
        let cd = tri!(check(damping, Parameter::Damping, Bound::NonNegative));
        let in_square = ck <= 1.0 && cd <= 1.0;
        if in_square {
            return Tuning::from_coefficients(ck, cd, dt);
        }
        if is_strictly_stable(ck, cd) {
            return Tuning::raw(ck, cd, dt);
        }
        if cd >= 2.0 {
            Err(Error::OutOfRange {
                parameter: Parameter::Damping,
                value: cd,
                bound: Bound::Below { max: 2.0 },
            })
        } else {
            Err(Error::OutOfRange {
                parameter: Parameter::Stiffness,
                value: ck,
                bound: Bound::Below {
                    max: 4.0 - 2.0 * cd,
                },
            })
        }
    }

    const fn raw(stiffness: f64, damping: f64, dt: f64) -> Result<Self, Error> {
        let dt = tri!(positive(dt, Parameter::TimeStep));
        let retention = 1.0 - damping;
        Ok(Tuning {
            stiffness,
            damping,
            retention,
            dt,
            start: (0.0, retention * dt),
            oscillator: None,
            root_stiffness: 0.0,
            growth: 0.0,
        }
        .derived())
    }

    /// The step of a friction sampled every `dt`, in the kept form: `C_k = 0`,
    /// `C_d = 1 − e^{−c·dt}`, and the exact start `ũ₀ = (1 − C_d)·(x(0) − x(−dt))`.
    ///
    /// The continuous throw `x(t) = x₀ + (v₀/c)(1 − e^{−c·t})` has
    /// `x(0) − x(−dt) = (v₀/c)(e^{c·dt} − 1)`, so `ũ₀ = (v₀/c)(1 − e^{−c·dt}) = (C_d/c)·v₀`:
    /// `P̃ = 0`, `Q̃ = C_d/c`. Every later step moves `ũ` and keeps `1 − C_d = e^{−c·dt}`
    /// of it, which is the continuous throw at every sample.
    ///
    /// Not public: a value with this tuning has no pull toward its target, so a target
    /// that moved would never be reached ([`Decay`](crate::Decay) keeps its target on the
    /// resting point instead).
    pub(crate) const fn friction(friction: &Friction, dt: f64) -> Result<Self, Error> {
        let dt = tri!(positive(dt, Parameter::TimeStep));
        let rate = friction.rate();
        let damping = friction.damping(dt);
        // A friction so weak that `c·dt` underflows has no step that samples it.
        if damping <= 0.0 || damping.is_nan() {
            return Err(Error::OutOfRange {
                parameter: Parameter::Friction,
                value: rate,
                bound: Bound::Positive,
            });
        }
        Ok(Tuning {
            stiffness: 0.0,
            damping,
            retention: math::exp(-rate * dt),
            dt,
            start: (0.0, damping / rate),
            oscillator: None,
            root_stiffness: 0.0,
            growth: 0.0,
        }
        .derived())
    }

    /// The stiffness coefficient `C_k`, a fraction of `k_max = m/dt²`.
    ///
    /// ```
    /// assert_eq!(stiffspring::Tuning::rigid(0.01)?.stiffness(), 1.0);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub const fn stiffness(&self) -> f64 {
        self.stiffness
    }

    /// The damping coefficient `C_d`, a fraction of `d_max = m/dt`.
    ///
    /// ```
    /// assert_eq!(stiffspring::Tuning::rigid(0.01)?.damping(), 1.0);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub const fn damping(&self) -> f64 {
        self.damping
    }

    /// The time step the tuning is sampled at, in seconds.
    ///
    /// ```
    /// assert_eq!(stiffspring::Tuning::rigid(0.01)?.dt(), 0.01);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub const fn dt(&self) -> f64 {
        self.dt
    }

    /// The continuous oscillator the tuning samples, if it came from the exact map.
    ///
    /// ```
    /// use stiffspring::Tuning;
    ///
    /// assert_eq!(Tuning::rigid(0.01)?.oscillator(), None);
    /// let t = Tuning::from_frequency(1.0, 0.5, 0.01)?;
    /// assert_eq!(t.oscillator().map(|o| o.damping_ratio()), Some(0.5));
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub const fn oscillator(&self) -> Option<Oscillator> {
        self.oscillator
    }

    /// The retention `1 − C_d`: the fraction of its step velocity a spring keeps into
    /// the next step. For the exact map it is `e^{−2ζω·dt}`, exact where `C_d` itself
    /// rounds to 1.
    ///
    /// ```
    /// assert_eq!(stiffspring::Tuning::rigid(0.01)?.retention(), 0.0);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub const fn retention(&self) -> f64 {
        self.retention
    }

    /// The weights `(P̃, Q̃)` of the kept step velocity `ũ = (1 − C_d)·u = P̃·x + Q̃·v` that
    /// puts a spring at offset `x` with velocity `v`: for the exact map,
    /// `u = x(0) − x(−dt)` of the continuous trajectory through `(x, v)`; for raw
    /// coefficients `u = v·dt`, the article's meaning.
    pub(crate) const fn start_weights(&self) -> (f64, f64) {
        self.start
    }

    /// The same spring at another time step: the exact map resamples its oscillator; raw
    /// coefficients are kept (behaviour per step does not depend on `dt`).
    ///
    /// # Errors
    ///
    /// As the constructor the tuning came from, at `dt`.
    ///
    /// ```
    /// use stiffspring::Tuning;
    ///
    /// let t60 = Tuning::from_frequency(2.0, 0.5, 1.0 / 60.0)?;
    /// let t120 = t60.with_dt(1.0 / 120.0)?;
    /// assert_eq!(t120, Tuning::from_frequency(2.0, 0.5, 1.0 / 120.0)?);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub const fn with_dt(&self, dt: f64) -> Result<Self, Error> {
        match self.oscillator {
            Some(o) => o.tuning(dt),
            None => Tuning::raw(self.stiffness, self.damping, dt),
        }
    }

    /// The spectral radius of the single-spring map on `(x, u)`: the factor by which the
    /// slowest mode shrinks per step (1 for an undamped spring, 0 for [`Tuning::rigid`]).
    ///
    /// ```
    /// use stiffspring::Tuning;
    ///
    /// assert_eq!(Tuning::rigid(0.01)?.spectral_radius(), 0.0);
    /// let t = Tuning::from_coefficients(0.01, 0.0, 0.01)?;
    /// assert!((t.spectral_radius() - 1.0).abs() < 1e-12);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub const fn spectral_radius(&self) -> f64 {
        let (trace, det) = self.trace_det();
        let disc = trace * trace - 4.0 * det;
        if disc < 0.0 {
            // Complex pair: |z|² = det.
            math::sqrt(det)
        } else {
            // Real pair (trace ± √disc)/2: the larger magnitude takes the sign of trace.
            (trace.abs() + math::sqrt(disc)) * 0.5
        }
    }

    /// A bound on the transient growth of the spring: from any state `(x₀, ũ₀)`, every
    /// later `|x|` and `|ũ|` is at most `growth · max(|x₀|, |ũ₀|)`.
    ///
    /// Values use it to keep float states finite without a clamp in the step: set-up
    /// limits the state to [`Scalar::STATE_MAX`](crate::Scalar::STATE_MAX)` / growth`.
    /// The bound follows from `Mⁿ = sₙ·M − det·sₙ₋₁·I` (Cayley–Hamilton, with
    /// `sₙ = (λ₁ⁿ − λ₂ⁿ)/(λ₁ − λ₂)`) and `|sₙ| ≤ min(n·ρⁿ⁻¹, 2/|λ₁ − λ₂|)`.
    ///
    /// ```
    /// use stiffspring::Tuning;
    ///
    /// // Undamped at f·dt = 0.01: λ = e^{±iθ}, θ = 2π/100, growth ≈ 2/sin θ.
    /// let g = Tuning::from_frequency(1.0, 0.0, 0.01)?.growth();
    /// assert!(g > 20.0 && g < 60.0);
    /// assert!(Tuning::rigid(0.01)?.growth() <= 3.0);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub const fn growth(&self) -> f64 {
        self.growth
    }

    /// `√C_k`, for the rest band (see [`RestThreshold`](crate::RestThreshold)).
    pub(crate) const fn root_stiffness(&self) -> f64 {
        self.root_stiffness
    }

    /// The tuning with the quantities set-up derives from its coefficients filled in.
    /// Every constructor ends here, so that they are computed in the constructor's
    /// `const` context: `SpringValue::new` on a `const` tuning then folds to constants.
    pub(crate) const fn derived(mut self) -> Self {
        self.root_stiffness = math::sqrt(self.stiffness);
        self.growth = self.bound_growth();
        self
    }

    /// The bound [`Tuning::growth`] returns.
    const fn bound_growth(&self) -> f64 {
        let (trace, det) = self.trace_det();
        // ‖M‖∞ for M = [[1 − C_k, 1], [−det·C_k, det]] on (x, ũ), the state the values
        // keep (see `Scalar`); its trace and determinant are those of the map on (x, u).
        let a = (1.0 - self.stiffness).abs() + 1.0;
        let b = (det * self.stiffness).abs() + det.abs();
        let norm = if a > b { a } else { b };
        let rho = self.spectral_radius();
        // sup n·ρ^(n−1): 1 for ρ ≤ ½ (n = 1), else below 1/(e·ρ·ln(1/ρ)) ≤ 2/(e·(1 − ρ)).
        let by_radius = if rho <= 0.5 {
            1.0
        } else if rho < 1.0 {
            2.0 / (core::f64::consts::E * (1.0 - rho))
        } else {
            f64::INFINITY
        };
        let gap = math::sqrt((trace * trace - 4.0 * det).abs());
        let by_gap = if gap > 0.0 { 2.0 / gap } else { f64::INFINITY };
        let s = if by_radius < by_gap {
            by_radius
        } else {
            by_gap
        };
        s * (norm + det.abs())
    }

    /// `(trace, det)` of the map on `(x, u)`.
    const fn trace_det(&self) -> (f64, f64) {
        let det = self.retention;
        (1.0 + det - self.stiffness, det)
    }
}

/// Jury's conditions for a second-order map with `trace = 2 − C_k − C_d` and
/// `det = 1 − C_d`: `|det| < 1`, `1 − trace + det > 0` (i.e. `C_k > 0`) and
/// `1 + trace + det > 0` (i.e. `C_k + 2·C_d < 4`).
pub(crate) const fn is_strictly_stable(ck: f64, cd: f64) -> bool {
    ck > 0.0 && cd > 0.0 && cd < 2.0 && ck + 2.0 * cd < 4.0
}
