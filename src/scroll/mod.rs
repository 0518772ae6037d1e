//! A scroll offset driven by a finger or a knob: a throw under friction, bounds with a
//! rubber band and a spring back, snap points, and steps from one snap point to the next.
//!
//! Every motion is one of the crate's exactly sampled ones, so that each frame lies on a
//! continuous trajectory:
//!
//! | phase | motion | from |
//! |---|---|---|
//! | gliding | [`Decay`]: `x₀ + (v₀/c)(1 − e^{−ct})` | a release inside the bounds, no snap points |
//! | bouncing | a spring to the bound ([`Scroll::with_bounce`]) | a glide that crosses a bound, a release past one |
//! | snapping | the spring with poles `−c` and `−4c` to the snap point nearest to `x₀ + v₀/c` | a release with snap points |
//! | stepping | a spring to a snap point or a position ([`Scroll::with_step_spring`]) | [`Scroll::step_by`], [`Scroll::scroll_to`] |
//!
//! Each hand-over keeps the velocity: a spring starts with the velocity the motion before
//! had at that instant (through the exact start of [`SpringValue::fling`]), and a glide
//! that crosses a bound hands over at the instant of the crossing, not at the next frame
//! (see `handover.rs`). Each motion comes to rest exactly on the point
//! [`Scroll::resting_point`] names.

mod drag;
mod handover;

use crate::bounds::Bounds;
use crate::decay::Decay;
use crate::error::Error;
use crate::friction::Friction;
use crate::motion::Motion;
use crate::rest::RestThreshold;
use crate::rubber_band::RubberBand;
use crate::scalar::Scalar;
use crate::snap::Snap;
use crate::tuning::{Oscillator, Tuning, presets};
use crate::value::SpringValue;

/// What a [`Scroll`] is doing.
///
/// ```
/// use stiffspring::{Bounds, Friction, Scroll, ScrollPhase};
/// let mut s = Scroll::<f32>::new(0.0, Bounds::new(0.0, 500.0)?, &Friction::IOS_NORMAL, 1.0 / 60.0)?;
/// assert_eq!(s.phase(), ScrollPhase::Resting);
/// s.drag_by(-30.0);
/// assert_eq!(s.phase(), ScrollPhase::Dragging);
/// # Ok::<(), stiffspring::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum ScrollPhase {
    /// At rest: stepping costs nothing.
    Resting,
    /// A finger holds the content.
    Dragging,
    /// Thrown, slowing by friction.
    Gliding,
    /// Springing back to a bound it passed.
    Bouncing,
    /// Springing to the snap point a release chose.
    Snapping,
    /// Springing to the point a step or `scroll_to` chose.
    Stepping,
}

/// A one-dimensional scroll offset in backend `S`: dragged and thrown by a finger, or
/// stepped by a knob's detents; held within [`Bounds`] by a rubber band and a spring
/// back, and resting on [`Snap`] points when it has them.
///
/// **The UI path cannot fail.** [`drag_by`](Scroll::drag_by),
/// [`release`](Scroll::release), [`set_bounds`](Scroll::set_bounds),
/// [`scroll_to`](Scroll::scroll_to) and [`step_by`](Scroll::step_by) ignore NaN and
/// saturate what is out of range; their `try_` twins report it.
///
/// ```
/// use stiffspring::{Bounds, Friction, Motion, RestThreshold, RubberBand, Scroll, Snap};
///
/// // 200 rows of 24 px in a 160 px view: offsets 0 to 200·24 − 160.
/// let mut list = Scroll::<f32>::new(0.0, Bounds::new(0.0, 4640.0)?, &Friction::IOS_NORMAL, 1.0 / 60.0)?
///     .with_rubber_band(RubberBand::new(160.0)?)
///     .with_snap(Snap::spacing(24.0, 0.0)?)
///     .with_rest_threshold(RestThreshold::PIXELS);
/// for _ in 0..5 {
///     list.drag_by(12.0); // the finger moves the content 12 px a frame
///     let _ = list.step();
/// }
/// list.release(900.0); // and lets go at 900 px/s
/// let rest = list.resting_point(); // known now: a row near 60 + 900/c
/// assert_eq!(rest % 24.0, 0.0);
/// while list.step() != Motion::Settled {}
/// assert_eq!(list.position(), rest); // on the row, exactly
/// # Ok::<(), stiffspring::Error>(())
/// ```
#[derive(Clone, Debug)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Scroll<'a, S: Scalar> {
    phase: ScrollPhase,
    /// The content's position while resting or dragging (the motions keep their own).
    held: S,
    /// While dragging: where the finger has taken the content, before the rubber band.
    finger: f64,
    /// Set by a drag, cleared by the step that reports it.
    dragged: bool,
    /// Where the current motion comes to rest.
    rest: S,
    /// While gliding: the bound the throw will cross, if its resting point lies beyond,
    /// and whether it is the upper one.
    crossing: Option<(S, bool)>,
    glide: Decay<S, 1>,
    bounce: SpringValue<S, 1>,
    snap_spring: SpringValue<S, 1>,
    step_spring: SpringValue<S, 1>,
    /// The bounce spring's oscillator, for the hand-over at the crossing instant.
    bounce_oscillator: Oscillator,
    bounds: Bounds<S>,
    snap: Snap<'a, S>,
    band: Option<RubberBand>,
    friction: Friction,
    dt: f64,
}

/// The second pole of the snap spring, as a multiple of the friction's rate `c`.
///
/// A release with snap points springs to the snap point `s` on the overdamped spring
/// whose poles are `−c` and `−p`: `x(t) − s = A·e^{−ct} + B·e^{−pt}`. Started with the
/// release's velocity, it is the friction's own glide when `s` is the throw's resting
/// point (`B = 0`), and otherwise corrects the difference `δ` with `B = c·δ/(p − c)`, a
/// motion that fades in `1/p`. At `p = 4c` that correction is a third of `δ` and done in
/// a quarter of the glide's time constant, so the glide keeps its feel; the spring is
/// `ω = √(c·p) = 2c`, `ζ = (c + p)/(2ω) = 1.25`.
const SNAP_POLE: f64 = 4.0;

/// Flutter's scroll spring (`ScrollPhysics.spring`: `SpringDescription.withDampingRatio(
/// mass: 0.5, stiffness: 100, ratio: 1.1)`), which brings an overscrolled list back to its
/// end: `ω = √(100/0.5) = 14.1 rad/s` (2.25 Hz), `ζ = 1.1`, back within a pixel in about
/// 0.6 s from 100 px.
const DEFAULT_BOUNCE: Oscillator = Oscillator::from_parts(14.142_135_623_730_951, 1.1);

impl<'a, S: Scalar> Scroll<'a, S> {
    /// A scroll at rest at `position` (limited to `bounds`), thrown under `friction`,
    /// stepped every `dt` seconds; no snap points, no rubber band (a drag stops at the
    /// ends), Flutter's scroll spring back from an overshoot ([`Scroll::with_bounce`]),
    /// SwiftUI's `.snappy` for steps ([`Scroll::with_step_spring`]), the default
    /// [`RestThreshold`].
    ///
    /// # Errors
    ///
    /// As [`Decay::new`] for the position, the friction and `dt`, and as
    /// [`SpringValue::new`] for the springs at this `dt` in this backend.
    ///
    /// ```
    /// use stiffspring::{Bounds, Friction, I16F16, Scroll};
    /// let b = Bounds::new(I16F16::ZERO, I16F16::from_num(3000))?;
    /// let s = Scroll::<I16F16>::new(I16F16::ZERO, b, &Friction::IOS_NORMAL, 1.0 / 60.0)?;
    /// assert!(s.is_at_rest());
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn new(
        position: S,
        bounds: Bounds<S>,
        friction: &Friction,
        dt: f64,
    ) -> Result<Self, Error> {
        let at = bounds.clamp(crate::input::check_position(
            position,
            crate::error::Parameter::Position,
        )?);
        let c = friction.rate();
        let snap = Oscillator::from_angular_frequency(
            libm::sqrt(c * SNAP_POLE * c),
            (1.0 + SNAP_POLE) / (2.0 * libm::sqrt(SNAP_POLE)),
        )?;
        let spring = |o: &Oscillator| -> Result<SpringValue<S, 1>, Error> {
            SpringValue::new([at], &o.tuning(dt)?)
        };
        Ok(Scroll {
            phase: ScrollPhase::Resting,
            held: at,
            finger: at.to_f64(),
            dragged: false,
            rest: at,
            crossing: None,
            glide: Decay::new([at], friction, dt)?,
            bounce: spring(&DEFAULT_BOUNCE)?,
            snap_spring: spring(&snap)?,
            step_spring: spring(&presets::swiftui::SNAPPY)?,
            bounce_oscillator: DEFAULT_BOUNCE,
            bounds,
            snap: Snap::NONE,
            band: None,
            friction: *friction,
            dt,
        })
    }

    /// The same scroll resting on `snap` points.
    ///
    /// ```
    /// use stiffspring::{Bounds, Friction, Scroll, Snap};
    /// let s = Scroll::<f32>::new(0.0, Bounds::new(0.0, 960.0)?, &Friction::IOS_FAST, 1.0 / 60.0)?
    ///     .with_snap(Snap::spacing(240.0, 0.0)?); // pages of 240 px
    /// assert!(s.snap().snaps());
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn with_snap(mut self, snap: Snap<'a, S>) -> Self {
        self.snap = snap;
        self
    }

    /// The same scroll with a rubber band: a drag past an end moves the content less than
    /// the finger (see [`RubberBand`]). Without one a drag stops at the ends.
    ///
    /// ```
    /// use stiffspring::{Bounds, Friction, RubberBand, Scroll};
    /// let mut s = Scroll::<f32>::new(0.0, Bounds::new(0.0, 500.0)?, &Friction::IOS_NORMAL, 1.0 / 60.0)?
    ///     .with_rubber_band(RubberBand::new(160.0)?);
    /// s.drag_by(-40.0); // 40 px past the top
    /// assert!(s.position() < 0.0 && s.position() > -40.0 * 0.55);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn with_rubber_band(mut self, band: RubberBand) -> Self {
        self.band = Some(band);
        self
    }

    /// The same scroll springing back from an overshoot with `oscillator` (Flutter's
    /// scroll spring by default: 2.25 Hz, ζ = 1.1).
    ///
    /// # Errors
    ///
    /// As [`Oscillator::tuning`] and [`SpringValue::new`] at the scroll's `dt`.
    ///
    /// ```
    /// use stiffspring::{Bounds, Friction, Oscillator, Scroll};
    /// let s = Scroll::<f32>::new(0.0, Bounds::new(0.0, 500.0)?, &Friction::IOS_NORMAL, 1.0 / 60.0)?
    ///     .with_bounce(&Oscillator::new(3.0, 1.0)?)?;
    /// # let _ = s;
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn with_bounce(mut self, oscillator: &Oscillator) -> Result<Self, Error> {
        self.bounce = self.spring_of(&oscillator.tuning(self.dt)?)?;
        self.bounce_oscillator = *oscillator;
        Ok(self)
    }

    /// The same scroll moving between snap points, on [`Scroll::step_by`] and
    /// [`Scroll::scroll_to`], with `oscillator` (SwiftUI's `.snappy` by default).
    ///
    /// # Errors
    ///
    /// As [`Oscillator::tuning`] and [`SpringValue::new`] at the scroll's `dt`.
    ///
    /// ```
    /// use stiffspring::{Bounds, Friction, Scroll, presets};
    /// let s = Scroll::<f32>::new(0.0, Bounds::new(0.0, 500.0)?, &Friction::IOS_NORMAL, 1.0 / 60.0)?
    ///     .with_step_spring(&presets::swiftui::SMOOTH)?;
    /// # let _ = s;
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn with_step_spring(mut self, oscillator: &Oscillator) -> Result<Self, Error> {
        self.step_spring = self.spring_of(&oscillator.tuning(self.dt)?)?;
        Ok(self)
    }

    /// The same scroll with another rest threshold, for every motion.
    ///
    /// ```
    /// use stiffspring::{Bounds, Friction, RestThreshold, Scroll};
    /// let s = Scroll::<f32>::new(0.0, Bounds::new(0.0, 500.0)?, &Friction::IOS_NORMAL, 1.0 / 60.0)?
    ///     .with_rest_threshold(RestThreshold::PIXELS);
    /// assert_eq!(s.rest_threshold(), RestThreshold::PIXELS);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn with_rest_threshold(mut self, threshold: RestThreshold) -> Self {
        self.glide = self.glide.with_rest_threshold(threshold);
        self.bounce = self.bounce.with_rest_threshold(threshold);
        self.snap_spring = self.snap_spring.with_rest_threshold(threshold);
        self.step_spring = self.step_spring.with_rest_threshold(threshold);
        self
    }

    fn spring_of(&self, tuning: &Tuning) -> Result<SpringValue<S, 1>, Error> {
        Ok(SpringValue::new([self.held], tuning)?.with_rest_threshold(self.rest_threshold()))
    }

    /// Advances the scroll by one time step and reports what happened: `Moving` while it
    /// moves (and in a step after a drag moved it), `Settled` in the step it comes to
    /// rest, exactly on [`Scroll::resting_point`], and `Resting` when nothing moved.
    ///
    /// ```
    /// use stiffspring::{Bounds, Friction, Motion, Scroll};
    /// let mut s = Scroll::<f64>::new(0.0, Bounds::new(0.0, 500.0)?, &Friction::new(4.0)?, 0.01)?;
    /// assert_eq!(s.step(), Motion::Resting);
    /// s.release(400.0); // rests 100 px on
    /// assert_eq!(s.step(), Motion::Moving);
    /// while s.step() == Motion::Moving {}
    /// assert_eq!(s.position(), 100.0);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn step(&mut self) -> Motion {
        let motion = match self.phase {
            ScrollPhase::Resting => Motion::Resting,
            ScrollPhase::Dragging => {
                let moved = self.dragged;
                self.dragged = false;
                return if moved {
                    Motion::Moving
                } else {
                    Motion::Resting
                };
            }
            ScrollPhase::Gliding => {
                let motion = self.glide.step();
                if let Some((bound, upper)) = self.crossing
                    && passed(self.glide.position()[0], bound, upper)
                {
                    self.hand_over(bound);
                    return Motion::Moving;
                }
                motion
            }
            ScrollPhase::Bouncing => self.bounce.step(),
            ScrollPhase::Snapping => self.snap_spring.step(),
            ScrollPhase::Stepping => self.step_spring.step(),
        };
        if motion == Motion::Settled {
            self.held = self.rest;
            self.phase = ScrollPhase::Resting;
        }
        motion
    }

    /// The content's position (the scroll offset).
    ///
    /// ```
    /// use stiffspring::{Bounds, Friction, Scroll};
    /// let s = Scroll::<f32>::new(120.0, Bounds::new(0.0, 500.0)?, &Friction::IOS_NORMAL, 0.01)?;
    /// assert_eq!(s.position(), 120.0);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn position(&self) -> S {
        match self.phase {
            ScrollPhase::Resting | ScrollPhase::Dragging => self.held,
            ScrollPhase::Gliding => self.glide.position()[0],
            ScrollPhase::Bouncing => self.bounce.position()[0],
            ScrollPhase::Snapping => self.snap_spring.position()[0],
            ScrollPhase::Stepping => self.step_spring.position()[0],
        }
    }

    /// The content's velocity in units per second: the current motion's (0 at rest and
    /// while a finger holds it; the finger's velocity is the caller's, given at
    /// [`Scroll::release`]).
    ///
    /// ```
    /// use stiffspring::{Bounds, Friction, Scroll};
    /// let mut s = Scroll::<f64>::new(0.0, Bounds::new(0.0, 500.0)?, &Friction::new(2.0)?, 0.01)?;
    /// s.release(300.0);
    /// assert!((s.velocity() - 300.0).abs() < 1e-9);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn velocity(&self) -> S {
        match self.phase {
            ScrollPhase::Resting | ScrollPhase::Dragging => S::ZERO,
            ScrollPhase::Gliding => self.glide.velocity()[0],
            ScrollPhase::Bouncing => self.bounce.velocity()[0],
            ScrollPhase::Snapping => self.snap_spring.velocity()[0],
            ScrollPhase::Stepping => self.step_spring.velocity()[0],
        }
    }

    /// Where the scroll will come to rest, known when the motion starts (at a release, a
    /// step, a hand-over): the throw's `x₀ + v₀/c`, the bound it passes, or the snap
    /// point. It stops exactly there. While a finger holds it, where it is.
    ///
    /// ```
    /// use stiffspring::{Bounds, Friction, Motion, Scroll};
    /// let mut s = Scroll::<f32>::new(0.0, Bounds::new(0.0, 500.0)?, &Friction::new(2.0)?, 1.0 / 60.0)?;
    /// s.release(2000.0); // would rest at 1,000: it stops at the end, 500
    /// assert_eq!(s.resting_point(), 500.0);
    /// while s.step() != Motion::Settled {}
    /// assert_eq!(s.position(), 500.0);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn resting_point(&self) -> S {
        match self.phase {
            ScrollPhase::Dragging => self.held,
            _ => self.rest,
        }
    }

    /// What the scroll is doing.
    ///
    /// ```
    /// use stiffspring::{Bounds, Friction, Scroll, ScrollPhase};
    /// let mut s = Scroll::<f32>::new(0.0, Bounds::new(0.0, 500.0)?, &Friction::new(2.0)?, 0.01)?;
    /// s.release(100.0);
    /// assert_eq!(s.phase(), ScrollPhase::Gliding);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn phase(&self) -> ScrollPhase {
        self.phase
    }

    /// True when nothing moves and no finger holds it: the display can sleep.
    ///
    /// ```
    /// use stiffspring::{Bounds, Friction, Scroll};
    /// let s = Scroll::<f32>::new(0.0, Bounds::new(0.0, 500.0)?, &Friction::new(2.0)?, 0.01)?;
    /// assert!(s.is_at_rest());
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn is_at_rest(&self) -> bool {
        self.phase == ScrollPhase::Resting
    }

    /// The bounds.
    ///
    /// ```
    /// use stiffspring::{Bounds, Friction, Scroll};
    /// let b = Bounds::new(0.0, 500.0)?;
    /// let s = Scroll::<f32>::new(0.0, b, &Friction::new(2.0)?, 0.01)?;
    /// assert_eq!(s.bounds(), b);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn bounds(&self) -> Bounds<S> {
        self.bounds
    }

    /// The snap points.
    ///
    /// ```
    /// use stiffspring::{Bounds, Friction, Scroll};
    /// let s = Scroll::<f32>::new(0.0, Bounds::new(0.0, 500.0)?, &Friction::new(2.0)?, 0.01)?;
    /// assert!(!s.snap().snaps());
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn snap(&self) -> Snap<'a, S> {
        self.snap
    }

    /// The friction of a throw.
    ///
    /// ```
    /// use stiffspring::{Bounds, Friction, Scroll};
    /// let s = Scroll::<f32>::new(0.0, Bounds::new(0.0, 500.0)?, &Friction::IOS_FAST, 0.01)?;
    /// assert_eq!(s.friction(), Friction::IOS_FAST);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn friction(&self) -> Friction {
        self.friction
    }

    /// The rest threshold.
    ///
    /// ```
    /// use stiffspring::{Bounds, Friction, RestThreshold, Scroll};
    /// let s = Scroll::<f32>::new(0.0, Bounds::new(0.0, 500.0)?, &Friction::IOS_FAST, 0.01)?;
    /// assert_eq!(s.rest_threshold(), RestThreshold::default());
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn rest_threshold(&self) -> RestThreshold {
        self.glide.rest_threshold()
    }

    /// Starts `spring` toward `target` from the current position and velocity (kept
    /// exactly, through the spring's exact start), in `phase`.
    fn spring_to(&mut self, phase: ScrollPhase, target: S, position: S, velocity: S) {
        let same = phase == self.phase;
        let spring = match phase {
            ScrollPhase::Bouncing => &mut self.bounce,
            ScrollPhase::Snapping => &mut self.snap_spring,
            _ => &mut self.step_spring,
        };
        spring.set_target([target]);
        // The spring that moves already keeps its position and velocity through a new
        // target exactly; another one starts from them.
        if !same {
            spring.set_position([position]);
            spring.fling([velocity]);
        }
        self.rest = target;
        self.crossing = None;
        self.phase = phase;
    }
}

/// True when `position` lies beyond `bound`: above it for the upper bound, below it for
/// the lower one.
fn passed<S: Scalar>(position: S, bound: S, upper: bool) -> bool {
    if upper {
        position > bound
    } else {
        position < bound
    }
}
