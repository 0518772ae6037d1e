//! A value thrown with a velocity and slowed by friction: a fling without a target.
//!
//! Friction `dv/dt = −c·v` sampled every `dt` is the crate's spring step with no
//! stiffness. With `C_k = 0` the kept form (see [`Scalar`]) reads
//!
//! ```text
//! u ← ũ        x ← x + u        ũ ← u − C_d·u,        C_d = 1 − e^{−c·dt}
//! ```
//!
//! so every step moves the kept step velocity `ũ` and keeps `1 − C_d = e^{−c·dt}` of it:
//! the continuous throw `x(t) = x₀ + (v₀/c)·(1 − e^{−c·t})` at every sample, in every
//! backend, when the throw starts with `ũ₀ = (1 − C_d)·(x(0) − x(−dt)) = (C_d/c)·v₀`.
//!
//! **The resting point is known at release.** The steps after the throw move `ũ₀`,
//! `(1 − C_d)·ũ₀`, `(1 − C_d)²·ũ₀`, …, a geometric series whose sum is `ũ₀/C_d`; the value
//! comes to rest at
//!
//! ```text
//! x∞ = x₀ + ũ₀/C_d = x₀ + v₀/c
//! ```
//!
//! the continuous throw's own resting point. (Started the obvious way, with a step
//! velocity `u₀ = v₀·dt` kept as `ũ₀ = (1 − C_d)·v₀·dt`, it would stop at
//! `x₀ + v₀·dt·e^{−c·dt}/(1 − e^{−c·dt})`, short of `v₀/c` by about `c·dt/2` of the
//! throw.) A [`Decay`] keeps its state as the offset from that resting point, as a
//! [`SpringValue`](crate::SpringValue) keeps it from its target, with `ũ = −C_d·offset`
//! at the throw: it comes to rest exactly on the point [`Decay::resting_point`] gave at
//! the release, to the last bit, and then costs nothing.

use crate::error::{Error, Parameter, Remedy};
use crate::friction::Friction;
use crate::input::{check_position, gains_of, saturate};
use crate::motion::Motion;
use crate::rest::{RestBand, RestThreshold};
use crate::scalar::Scalar;
use crate::start::Start;
use crate::tuning::Tuning;

/// A `D`-dimensional value in backend `S`, thrown with a velocity and slowed by a
/// [`Friction`] until it rests where the throw takes it.
///
/// **The UI path cannot fail.** [`fling`](Decay::fling) and
/// [`set_position`](Decay::set_position) ignore NaN and saturate what is out of range;
/// their `try_` twins report it.
///
/// ```
/// use stiffspring::{Decay, Friction, Motion, RestThreshold};
///
/// let mut card = Decay::<f32, 2>::new([0.0, 0.0], &Friction::IOS_NORMAL, 1.0 / 60.0)?
///     .with_rest_threshold(RestThreshold::PIXELS);
/// card.fling([1200.0, -300.0]); // px/s, as a finger lets go
/// let rest = card.resting_point(); // known now: 1200/c and −300/c away
/// assert!((rest[0] - 1200.0 / Friction::IOS_NORMAL.rate() as f32).abs() < 1e-3);
/// while card.step() != Motion::Settled {}
/// assert_eq!(card.position(), rest); // where it said, to the bit
/// # Ok::<(), stiffspring::Error>(())
/// ```
#[derive(Clone, Debug)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Decay<S: Scalar, const D: usize = 1> {
    /// `position − resting point`, in the state format.
    offset: [S::State; D],
    /// The kept step velocity `ũ = −C_d·offset` (see the module docs).
    kept: [S::State; D],
    rest: [S; D],
    gains: S::Gains,
    /// Reads the velocity: `v = ũ·c/C_d`.
    start: Start<S>,
    /// `C_d`, which turns the offset from the resting point into `ũ`.
    damping: S::Factor,
    /// `1/c`: the travel of a throw per unit of velocity.
    travel: S::Factor,
    band: RestBand<S>,
    at_rest: bool,
    friction: Friction,
    dt: f64,
    threshold: RestThreshold,
}

impl<S: Scalar, const D: usize> Decay<S, D> {
    /// A value at rest at `position`, slowed by `friction` and stepped every `dt` seconds,
    /// with the default [`RestThreshold`].
    ///
    /// # Errors
    ///
    /// [`Error::NotFinite`] or [`Error::OutOfRange`] for a position or for `dt`;
    /// [`Error::OutOfRange`] with [`Parameter::Friction`] when `c·dt` is so small that
    /// `1 − e^{−c·dt}` underflows `f64`; [`Error::Unrepresentable`] when the backend
    /// cannot hold `C_d`.
    ///
    /// ```
    /// use stiffspring::{Decay, Friction, I16F16};
    ///
    /// let d = Decay::<I16F16>::new([I16F16::ZERO], &Friction::ANDROID_DEFAULT, 1.0 / 120.0)?;
    /// assert!(d.is_at_rest());
    /// assert!(Decay::<f32>::new([0.0], &Friction::IOS_FAST, 0.0).is_err());
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn new(position: [S; D], friction: &Friction, dt: f64) -> Result<Self, Error> {
        for p in position {
            check_position(p, Parameter::Position)?;
        }
        let tuning = Tuning::friction(friction, dt)?;
        let threshold = RestThreshold::default();
        Ok(Decay {
            offset: [S::STATE_ZERO; D],
            kept: [S::STATE_ZERO; D],
            rest: position,
            gains: gains_of::<S>(&tuning)?,
            start: Start::new(&tuning)?,
            damping: S::factor(tuning.damping()),
            travel: S::factor(1.0 / friction.rate()),
            band: RestBand::decay(&threshold, tuning.damping(), friction.rate()),
            at_rest: true,
            friction: *friction,
            dt,
            threshold,
        })
    }

    /// The same value with another rest threshold: it settles when the travel it has
    /// left is within the position threshold and its velocity within the velocity one.
    ///
    /// ```
    /// use stiffspring::{Decay, Friction, RestThreshold};
    /// let d = Decay::<f32>::new([0.0], &Friction::IOS_NORMAL, 1.0 / 60.0)?
    ///     .with_rest_threshold(RestThreshold::PIXELS);
    /// assert_eq!(d.rest_threshold(), RestThreshold::PIXELS);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn with_rest_threshold(mut self, threshold: RestThreshold) -> Self {
        self.threshold = threshold;
        let damping = self.friction.damping(self.dt);
        self.band = RestBand::decay(&threshold, damping, self.friction.rate());
        self
    }

    /// Throws the value from where it is with `velocity` (units per second), as a finger
    /// lets go: its new resting point is `position + velocity/c`
    /// ([`Decay::resting_point`]).
    ///
    /// A NaN component is ignored (the whole call does nothing); a velocity beyond
    /// [`Scalar::MAX`] saturates, and so does a resting point beyond the position range
    /// (the throw then stops there, with the velocity that takes it there).
    /// [`Decay::try_fling`] reports these.
    ///
    /// ```
    /// use stiffspring::{Decay, Friction};
    ///
    /// let mut d = Decay::<f64>::new([10.0], &Friction::new(4.0)?, 1.0 / 60.0)?;
    /// d.fling([400.0]);
    /// assert_eq!(d.resting_point(), [110.0]);
    /// assert!((d.velocity()[0] - 400.0).abs() < 1e-9);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn fling(&mut self, velocity: [S; D]) {
        let mut v = velocity;
        for c in v.iter_mut() {
            match saturate(*c) {
                Some(s) => *c = s,
                None => return,
            }
        }
        for i in 0..D {
            let from = self.position_state(i);
            let to = S::state_add(from, S::scale(v[i].widen(), self.travel));
            // `saturate` clamps a float's resting point into the position range (fixed
            // point saturates in `narrow`); it is never NaN, the sum of two finite numbers.
            let rest = saturate(S::narrow(to)).unwrap_or(self.rest[i]);
            self.throw_to(i, from, rest);
        }
        self.at_rest = false;
    }

    /// [`Decay::fling`], reporting instead of saturating.
    ///
    /// # Errors
    ///
    /// [`Error::NotFinite`] or [`Error::OutOfRange`] for the velocity;
    /// [`Error::Unrepresentable`] with [`Parameter::Position`] when the resting point
    /// `position + velocity/c` lies beyond [`Scalar::MAX`]. The value is then unchanged.
    ///
    /// ```
    /// use stiffspring::{Decay, Friction, I16F16};
    ///
    /// let start = I16F16::from_num(20_000);
    /// let mut d = Decay::<I16F16>::new([start], &Friction::IOS_NORMAL, 1.0 / 60.0)?;
    /// // 30,000 px/s would rest 14,985 px on, at 34,985: beyond I16F16's 32,768.
    /// assert!(d.try_fling([I16F16::from_num(30_000)]).is_err());
    /// assert!(d.try_fling([I16F16::from_num(10_000)]).is_ok());
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn try_fling(&mut self, velocity: [S; D]) -> Result<(), Error> {
        let mut rests = self.rest;
        let max = S::from_f64(S::MAX).widen();
        for i in 0..D {
            let v = check_position(velocity[i], Parameter::Velocity)?;
            let to = S::state_add(self.position_state(i), S::scale(v.widen(), self.travel));
            if !S::within(to, max) {
                return Err(Error::Unrepresentable {
                    parameter: Parameter::Position,
                    backend: S::NAME,
                    value: S::state_to_f64(to),
                    limit: S::MAX,
                    remedy: Remedy::LargerUnit,
                });
            }
            rests[i] = S::narrow(to);
        }
        for i in 0..D {
            let from = self.position_state(i);
            self.throw_to(i, from, rests[i]);
        }
        self.at_rest = false;
        Ok(())
    }

    /// Moves the value to `position` at once, keeping its velocity: its resting point
    /// moves with it.
    ///
    /// NaN is ignored; out-of-range input saturates, as for [`Decay::fling`].
    ///
    /// ```
    /// use stiffspring::{Decay, Friction};
    ///
    /// let mut d = Decay::<f64>::new([0.0], &Friction::new(2.0)?, 0.01)?;
    /// d.fling([100.0]);
    /// d.set_position([-20.0]);
    /// assert_eq!(d.resting_point(), [30.0]);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn set_position(&mut self, position: [S; D]) {
        let mut p = position;
        for c in p.iter_mut() {
            match saturate(*c) {
                Some(s) => *c = s,
                None => return,
            }
        }
        let v = self.velocity();
        let moving = !self.at_rest;
        self.rest = p;
        self.offset = [S::STATE_ZERO; D];
        self.kept = [S::STATE_ZERO; D];
        if moving {
            self.fling(v);
        }
    }

    /// [`Decay::set_position`], reporting instead of saturating.
    ///
    /// # Errors
    ///
    /// [`Error::NotFinite`] or [`Error::OutOfRange`] for the position, and as
    /// [`Decay::try_fling`] for the resting point it moves to. The value is then
    /// unchanged.
    ///
    /// ```
    /// use stiffspring::{Decay, Friction};
    /// let mut d = Decay::<f32>::new([0.0], &Friction::IOS_NORMAL, 1.0 / 60.0)?;
    /// assert!(d.try_set_position([f32::NAN]).is_err());
    /// assert!(d.try_set_position([5.0]).is_ok());
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn try_set_position(&mut self, position: [S; D]) -> Result<(), Error> {
        for p in position {
            check_position(p, Parameter::Position)?;
        }
        let v = self.velocity();
        let saved = self.clone();
        self.rest = position;
        self.offset = [S::STATE_ZERO; D];
        self.kept = [S::STATE_ZERO; D];
        if !saved.at_rest
            && let Err(e) = self.try_fling(v)
        {
            *self = saved;
            return Err(e);
        }
        Ok(())
    }

    /// Stops the value where it is (a finger catching it).
    ///
    /// ```
    /// use stiffspring::{Decay, Friction, Motion};
    ///
    /// let mut d = Decay::<f32>::new([0.0], &Friction::IOS_NORMAL, 1.0 / 60.0)?;
    /// d.fling([500.0]);
    /// let _ = d.step();
    /// d.stop();
    /// assert_eq!(d.resting_point(), d.position());
    /// assert_eq!(d.step(), Motion::Resting);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn stop(&mut self) {
        self.rest = self.position();
        self.settle();
    }

    /// Advances the value by one time step and reports what happened: it settles (snaps
    /// exactly onto its resting point, then costs nothing) when the travel it has left
    /// and its velocity are inside its [`RestThreshold`].
    ///
    /// ```
    /// use stiffspring::{Decay, Friction, Motion};
    ///
    /// let mut d = Decay::<f64>::new([0.0], &Friction::new(1.0)?, 0.5)?;
    /// d.fling([10.0]);
    /// assert_eq!(d.step(), Motion::Moving);
    /// // x(0.5 s) = (v₀/c)·(1 − e^{−c·t}): the continuous throw.
    /// assert!((d.position()[0] - 10.0 * (1.0 - (-0.5f64).exp())).abs() < 1e-12);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    #[inline]
    pub fn step(&mut self) -> Motion {
        if self.at_rest {
            return Motion::Resting;
        }
        for i in 0..D {
            S::advance(&self.gains, &mut self.offset[i], &mut self.kept[i]);
        }
        let band = &self.band;
        if (0..D).all(|i| band.contains(self.offset[i], self.kept[i])) {
            self.settle();
            Motion::Settled
        } else {
            Motion::Moving
        }
    }

    /// The current position.
    ///
    /// ```
    /// use stiffspring::{Decay, Friction};
    /// let d = Decay::<f32, 2>::new([1.0, 2.0], &Friction::IOS_NORMAL, 0.01)?;
    /// assert_eq!(d.position(), [1.0, 2.0]);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn position(&self) -> [S; D] {
        let mut p = self.rest;
        for i in 0..D {
            p[i] = S::narrow(self.position_state(i));
        }
        p
    }

    /// The velocity in units per second: `ũ·c/C_d`, the continuous throw's velocity at
    /// this sample. It saturates at `±Scalar::MAX`.
    ///
    /// ```
    /// use stiffspring::{Decay, Friction};
    ///
    /// let f = Friction::new(3.0)?;
    /// let mut d = Decay::<f64>::new([0.0], &f, 0.01)?;
    /// d.fling([90.0]);
    /// for _ in 0..10 {
    ///     let _ = d.step();
    /// }
    /// assert!((d.velocity()[0] - 90.0 * (-3.0f64 * 0.1).exp()).abs() < 1e-9);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn velocity(&self) -> [S; D] {
        let mut v = [S::ZERO; D];
        for i in 0..D {
            v[i] = self.start.velocity(self.offset[i], self.kept[i]);
        }
        v
    }

    /// Where the value will come to rest: `x₀ + v₀/c` of the last throw, rounded once to a
    /// position. The value stops exactly there.
    ///
    /// ```
    /// use stiffspring::{Decay, Friction};
    /// let mut d = Decay::<f32>::new([100.0], &Friction::new(5.0)?, 1.0 / 60.0)?;
    /// d.fling([-250.0]);
    /// assert_eq!(d.resting_point(), [50.0]);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn resting_point(&self) -> [S; D] {
        self.rest
    }

    /// The friction that slows the value.
    ///
    /// ```
    /// use stiffspring::{Decay, Friction};
    /// let d = Decay::<f32>::new([0.0], &Friction::IOS_FAST, 0.01)?;
    /// assert_eq!(d.friction(), Friction::IOS_FAST);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn friction(&self) -> Friction {
        self.friction
    }

    /// The rest threshold.
    ///
    /// ```
    /// use stiffspring::{Decay, Friction, RestThreshold};
    /// let d = Decay::<f32>::new([0.0], &Friction::IOS_FAST, 0.01)?;
    /// assert_eq!(d.rest_threshold(), RestThreshold::default());
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn rest_threshold(&self) -> RestThreshold {
        self.threshold
    }

    /// True when the value sits on its resting point with no velocity, and stepping it
    /// costs nothing.
    ///
    /// ```
    /// use stiffspring::{Decay, Friction};
    /// let mut d = Decay::<f32>::new([0.0], &Friction::IOS_FAST, 0.01)?;
    /// d.fling([1.0]);
    /// assert!(!d.is_at_rest());
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn is_at_rest(&self) -> bool {
        self.at_rest
    }

    /// The position of component `i` in the state format.
    fn position_state(&self, i: usize) -> S::State {
        S::state_add(self.rest[i].widen(), self.offset[i])
    }

    /// Component `i`, at `from` (state format), thrown so that it rests on `rest`: the
    /// offset from the resting point, and `ũ = −C_d·offset`, whose geometric series of
    /// steps adds up to exactly that offset.
    fn throw_to(&mut self, i: usize, from: S::State, rest: S) {
        let offset = self.start.clamp(S::state_sub(from, rest.widen()));
        self.rest[i] = rest;
        self.offset[i] = offset;
        self.kept[i] = S::state_sub(S::STATE_ZERO, S::scale(offset, self.damping));
    }

    /// Exactly on the resting point, with no velocity.
    fn settle(&mut self) {
        for x in self.offset.iter_mut() {
            *x = S::STATE_ZERO;
        }
        self.at_rest = true;
        for u in self.kept.iter_mut() {
            *u = S::STATE_ZERO;
        }
    }
}
