//! What moves a scroll: a finger (grab, drag, release), a knob (steps), the program
//! (scroll to, new bounds). Infallible, with `try_` twins.

use super::{Scroll, ScrollPhase};
use crate::bounds::Bounds;
use crate::error::{Bound, Error, Parameter};
use crate::input::{check_position, saturate};
use crate::scalar::Scalar;

impl<S: Scalar> Scroll<'_, S> {
    /// A finger touches the content: whatever moved stops where it is, and the finger
    /// holds it. [`Scroll::drag_by`] grabs by itself; call this on touch-down to catch a
    /// gliding list before the finger moves.
    ///
    /// Past an end, the finger takes the content where it is: a later drag continues the
    /// rubber band from there. (Without a rubber band, the next drag puts it on the end.)
    ///
    /// ```
    /// use stiffspring::{Bounds, Friction, Motion, Scroll, ScrollPhase};
    /// let mut s = Scroll::<f32>::new(0.0, Bounds::new(0.0, 900.0)?, &Friction::IOS_NORMAL, 1.0 / 60.0)?;
    /// s.release(1500.0);
    /// let _ = s.step();
    /// s.grab();
    /// assert_eq!(s.phase(), ScrollPhase::Dragging);
    /// assert_eq!(s.step(), Motion::Resting); // held still
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn grab(&mut self) {
        let x = self.position();
        self.finger = self.unbanded(x);
        self.held = x;
        self.rest = x;
        self.crossing = None;
        self.dragged = false;
        self.phase = ScrollPhase::Dragging;
    }

    /// The finger moved the content by `delta` (the user's unit): the content follows it
    /// one to one inside the bounds, and by the rubber band past an end (without a rubber
    /// band, it stops at the end). The next [`Scroll::step`] reports it as moving.
    ///
    /// NaN is ignored; a delta, or a finger position, beyond [`Scalar::MAX`] saturates.
    /// [`Scroll::try_drag_by`] reports these.
    ///
    /// ```
    /// use stiffspring::{Bounds, Friction, RubberBand, Scroll};
    /// let band = RubberBand::new(160.0)?;
    /// let mut s = Scroll::<f64>::new(10.0, Bounds::new(0.0, 900.0)?, &Friction::IOS_NORMAL, 1.0 / 60.0)?
    ///     .with_rubber_band(band);
    /// s.drag_by(-50.0); // 10 px to the top, then 40 px past it
    /// assert_eq!(s.position(), band.stretch(-40.0));
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn drag_by(&mut self, delta: S) {
        let Some(delta) = saturate(delta) else {
            return;
        };
        if self.phase != ScrollPhase::Dragging {
            self.grab();
        }
        let max = S::MAX;
        self.finger = (self.finger + delta.to_f64()).clamp(-max, max);
        self.held = self.banded(self.finger);
        self.rest = self.held;
        self.dragged = true;
    }

    /// [`Scroll::drag_by`], reporting instead of ignoring or saturating.
    ///
    /// # Errors
    ///
    /// [`Error::NotFinite`] or [`Error::OutOfRange`] with [`Parameter::Position`] for a
    /// delta, or a finger position it leads to, that is not a position. The scroll is
    /// then unchanged.
    ///
    /// ```
    /// use stiffspring::{Bounds, Friction, Scroll};
    /// let mut s = Scroll::<f32>::new(0.0, Bounds::new(0.0, 900.0)?, &Friction::IOS_NORMAL, 0.01)?;
    /// assert!(s.try_drag_by(f32::NAN).is_err());
    /// assert!(s.try_drag_by(5.0).is_ok());
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn try_drag_by(&mut self, delta: S) -> Result<(), Error> {
        let delta = check_position(delta, Parameter::Position)?;
        let start = if self.phase == ScrollPhase::Dragging {
            self.finger
        } else {
            self.unbanded(self.position())
        };
        let to = start + delta.to_f64();
        if to.is_nan() || to.abs() > S::MAX {
            return Err(Error::OutOfRange {
                parameter: Parameter::Position,
                value: to,
                bound: Bound::MagnitudeAtMost { max: S::MAX },
            });
        }
        self.drag_by(delta);
        Ok(())
    }

    /// The finger lets go with `velocity` (units per second, the finger's): the content
    /// is thrown from where it is.
    ///
    /// - Inside the bounds, without snap points, it glides under the friction to
    ///   `x₀ + v₀/c`; if that lies beyond an end, it hands over to the bounce spring at
    ///   the instant it crosses the end, and rests on it.
    /// - With snap points, it springs to the snap point nearest to `x₀ + v₀/c`, keeping
    ///   its velocity (see [`Snap`](crate::Snap)).
    /// - Past an end (a rubber-band drag), it springs back to the end with the content's
    ///   velocity: the finger's times the band's [`slope`](crate::RubberBand::slope).
    ///
    /// NaN is ignored; a velocity beyond [`Scalar::MAX`] saturates, and so does a resting
    /// point beyond it. [`Scroll::try_release`] reports these.
    ///
    /// ```
    /// use stiffspring::{Bounds, Friction, Motion, Scroll, ScrollPhase};
    /// let mut s = Scroll::<f32>::new(400.0, Bounds::new(0.0, 900.0)?, &Friction::new(2.0)?, 1.0 / 60.0)?;
    /// s.release(-2000.0); // 1,000 px back: past the top
    /// assert_eq!((s.phase(), s.resting_point()), (ScrollPhase::Gliding, 0.0));
    /// while s.phase() == ScrollPhase::Gliding {
    ///     let _ = s.step();
    /// }
    /// assert_eq!(s.phase(), ScrollPhase::Bouncing); // crossed the top
    /// while s.step() != Motion::Settled {}
    /// assert_eq!(s.position(), 0.0);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn release(&mut self, velocity: S) {
        let Some(v) = saturate(velocity) else {
            return;
        };
        let x = self.position();
        if !self.bounds.contains(x) {
            self.spring_back(x, v);
        } else if self.snap.snaps() {
            let snapped = self.snap.nearest(self.throw_rest(x, v), &self.bounds);
            self.spring_to(ScrollPhase::Snapping, snapped.unwrap_or(x), x, v);
        } else {
            self.glide.stop();
            self.glide.set_position([x]);
            self.glide.fling([v]);
            self.start_glide();
        }
    }

    /// [`Scroll::release`], reporting instead of ignoring or saturating.
    ///
    /// # Errors
    ///
    /// [`Error::NotFinite`] or [`Error::OutOfRange`] with [`Parameter::Velocity`] for the
    /// velocity; as [`Decay::try_fling`](crate::Decay::try_fling) for a resting point
    /// beyond [`Scalar::MAX`]. The scroll is then unchanged.
    ///
    /// ```
    /// use stiffspring::{Bounds, Friction, Scroll};
    /// let mut s = Scroll::<f32>::new(0.0, Bounds::new(0.0, 900.0)?, &Friction::IOS_NORMAL, 0.01)?;
    /// assert!(s.try_release(f32::INFINITY).is_err());
    /// assert!(s.try_release(800.0).is_ok());
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn try_release(&mut self, velocity: S) -> Result<(), Error> {
        let v = check_position(velocity, Parameter::Velocity)?;
        let x = self.position();
        if self.bounds.contains(x) && !self.snap.snaps() {
            let saved = self.glide.clone();
            self.glide.stop();
            self.glide.set_position([x]);
            if let Err(e) = self.glide.try_fling([v]) {
                self.glide = saved;
                return Err(e);
            }
            self.start_glide();
            return Ok(());
        }
        self.release(v);
        Ok(())
    }

    /// The glide just thrown: where it rests, and the bound it crosses first if that lies
    /// beyond.
    fn start_glide(&mut self) {
        let rest = self.glide.resting_point()[0];
        self.rest = self.bounds.clamp(rest);
        self.crossing = (!self.bounds.contains(rest)).then(|| (self.rest, rest > self.rest));
        self.phase = ScrollPhase::Gliding;
    }

    /// From past an end back to it: with the content's velocity, which a rubber band
    /// makes the finger's times the band's slope there.
    fn spring_back(&mut self, x: S, velocity: S) {
        let end = self.bounds.clamp(x);
        let v = match (self.phase, self.band) {
            (ScrollPhase::Dragging, Some(band)) => {
                S::from_f64(velocity.to_f64() * band.slope(self.finger - end.to_f64()))
            }
            _ => velocity,
        };
        self.spring_to(ScrollPhase::Bouncing, end, x, v);
    }

    /// `x₀ + v₀/c` as a position (saturated).
    fn throw_rest(&self, x: S, v: S) -> S {
        S::from_f64(x.to_f64() + self.friction.distance(v.to_f64()))
    }

    /// Moves the resting point `steps` snap points on (back, when negative) from the one
    /// it rests on or springs to, and springs there with the step spring, keeping the
    /// velocity: a knob's detent steps, a menu's next and previous. The ends stop it.
    /// Without snap points nothing happens. [`Scroll::try_step_by`] reports both.
    ///
    /// ```
    /// use stiffspring::{Bounds, Friction, Motion, Scroll, Snap};
    /// let mut menu = Scroll::<f32>::new(0.0, Bounds::new(0.0, 7.0 * 24.0)?, &Friction::IOS_NORMAL, 1.0 / 60.0)?
    ///     .with_snap(Snap::spacing(24.0, 0.0)?);
    /// menu.step_by(1);
    /// menu.step_by(1); // before the first settles: the target moves on
    /// assert_eq!(menu.resting_point(), 48.0);
    /// menu.step_by(100); // stops at the last item
    /// assert_eq!(menu.resting_point(), 168.0);
    /// while menu.step() != Motion::Settled {}
    /// assert_eq!(menu.position(), 168.0);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn step_by(&mut self, steps: i32) {
        if let Some((to, _)) = self.snap.step(self.resting_point(), steps, &self.bounds) {
            self.move_to(to);
        }
    }

    /// [`Scroll::step_by`], reporting instead of stopping at an end.
    ///
    /// # Errors
    ///
    /// [`Error::OutOfRange`] with [`Parameter::Index`] when the step would pass an end
    /// (the bound is how many steps each way there are), and with
    /// [`Parameter::SnapPoints`] (`Bound::AtLeast { min: 1.0 }`) when there are no snap
    /// points. The scroll is then unchanged.
    ///
    /// ```
    /// use stiffspring::{Bound, Bounds, Error, Friction, Parameter, Scroll, Snap};
    /// let mut menu = Scroll::<f32>::new(0.0, Bounds::new(0.0, 72.0)?, &Friction::IOS_NORMAL, 0.01)?
    ///     .with_snap(Snap::spacing(24.0, 0.0)?);
    /// assert!(menu.try_step_by(3).is_ok());
    /// assert_eq!(
    ///     menu.try_step_by(1),
    ///     Err(Error::OutOfRange {
    ///         parameter: Parameter::Index,
    ///         value: 1.0,
    ///         bound: Bound::Within { min: -3.0, max: 0.0 }
    ///     })
    /// );
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn try_step_by(&mut self, steps: i32) -> Result<(), Error> {
        let none = Error::OutOfRange {
            parameter: Parameter::SnapPoints,
            value: 0.0,
            bound: Bound::AtLeast { min: 1.0 },
        };
        let (to, (back, on)) = self
            .snap
            .step(self.resting_point(), steps, &self.bounds)
            .ok_or(none)?;
        let wanted = i64::from(steps);
        if wanted < back || wanted > on {
            return Err(Error::OutOfRange {
                parameter: Parameter::Index,
                value: f64::from(steps),
                bound: Bound::Within {
                    min: back as f64,
                    max: on as f64,
                },
            });
        }
        self.move_to(to);
        Ok(())
    }

    /// Springs to `position` (limited to the bounds) with the step spring, keeping the
    /// velocity: a jump to an item that is not a throw. NaN is ignored.
    /// [`Scroll::try_scroll_to`] reports a position outside the bounds.
    ///
    /// ```
    /// use stiffspring::{Bounds, Friction, Motion, Scroll};
    /// let mut s = Scroll::<f32>::new(0.0, Bounds::new(0.0, 900.0)?, &Friction::IOS_NORMAL, 1.0 / 60.0)?;
    /// s.scroll_to(1200.0);
    /// assert_eq!(s.resting_point(), 900.0);
    /// while s.step() != Motion::Settled {}
    /// assert_eq!(s.position(), 900.0);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn scroll_to(&mut self, position: S) {
        if let Some(p) = saturate(position) {
            self.move_to(self.bounds.clamp(p));
        }
    }

    /// [`Scroll::scroll_to`], reporting instead of ignoring or limiting.
    ///
    /// # Errors
    ///
    /// [`Error::NotFinite`] with [`Parameter::Position`] for NaN or infinity;
    /// [`Error::OutOfRange`] with [`Parameter::Position`] and `Bound::Within` the bounds
    /// for a position outside them. The scroll is then unchanged.
    ///
    /// ```
    /// use stiffspring::{Bounds, Friction, Scroll};
    /// let mut s = Scroll::<f32>::new(0.0, Bounds::new(0.0, 900.0)?, &Friction::IOS_NORMAL, 0.01)?;
    /// assert!(s.try_scroll_to(1200.0).is_err());
    /// assert!(s.try_scroll_to(300.0).is_ok());
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn try_scroll_to(&mut self, position: S) -> Result<(), Error> {
        let p = check_position(position, Parameter::Position)?;
        if !self.bounds.contains(p) {
            return Err(Error::OutOfRange {
                parameter: Parameter::Position,
                value: p.to_f64(),
                bound: Bound::Within {
                    min: self.bounds.min().to_f64(),
                    max: self.bounds.max().to_f64(),
                },
            });
        }
        self.move_to(p);
        Ok(())
    }

    /// The step spring toward `to` from the current position and velocity.
    fn move_to(&mut self, to: S) {
        let (x, v) = (self.position(), self.velocity());
        self.spring_to(ScrollPhase::Stepping, to, x, v);
    }

    /// New bounds (the content grew or shrank), from the UI path: NaN is ignored, ends
    /// beyond [`Scalar::MAX`] saturate, and `min > max` becomes `[min, min]` (a content
    /// shorter than its view). A scroll that rests or springs outside the new bounds
    /// springs back inside; a glide now crossing an end hands over there.
    /// [`Scroll::try_set_bounds`] reports these.
    ///
    /// ```
    /// use stiffspring::{Bounds, Friction, Motion, Scroll, ScrollPhase};
    /// let mut s = Scroll::<f32>::new(800.0, Bounds::new(0.0, 900.0)?, &Friction::IOS_NORMAL, 1.0 / 60.0)?;
    /// s.set_bounds(0.0, 500.0); // rows were deleted
    /// assert_eq!(s.phase(), ScrollPhase::Bouncing);
    /// while s.step() != Motion::Settled {}
    /// assert_eq!(s.position(), 500.0);
    /// s.set_bounds(10.0, 0.0); // shorter than the view
    /// assert_eq!(s.bounds(), Bounds::new(10.0, 10.0)?);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn set_bounds(&mut self, min: S, max: S) {
        if let Some(bounds) = Bounds::saturating(min, max) {
            self.apply_bounds(bounds);
        }
    }

    /// [`Scroll::set_bounds`], reporting instead of ignoring or saturating.
    ///
    /// # Errors
    ///
    /// As [`Bounds::new`]: [`Parameter::Bounds`] for an end that is not a position, or
    /// `min > max`. The scroll is then unchanged.
    ///
    /// ```
    /// use stiffspring::{Bounds, Error, Friction, Parameter, Scroll};
    /// let mut s = Scroll::<f32>::new(0.0, Bounds::new(0.0, 900.0)?, &Friction::IOS_NORMAL, 0.01)?;
    /// assert_eq!(s.try_set_bounds(f32::NAN, 1.0).unwrap_err().parameter(), Some(Parameter::Bounds));
    /// assert!(s.try_set_bounds(5.0, 1.0).is_err());
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn try_set_bounds(&mut self, min: S, max: S) -> Result<(), Error> {
        let bounds = Bounds::new(min, max)?;
        self.apply_bounds(bounds);
        Ok(())
    }

    fn apply_bounds(&mut self, bounds: Bounds<S>) {
        self.bounds = bounds;
        match self.phase {
            ScrollPhase::Resting => {
                if !bounds.contains(self.held) {
                    self.spring_to(
                        ScrollPhase::Bouncing,
                        bounds.clamp(self.held),
                        self.held,
                        S::ZERO,
                    );
                }
            }
            ScrollPhase::Dragging => {
                self.held = self.banded(self.finger);
                self.rest = self.held;
            }
            ScrollPhase::Gliding => self.start_glide(),
            phase => {
                if !bounds.contains(self.rest) {
                    let (x, v) = (self.position(), self.velocity());
                    self.spring_to(phase, bounds.clamp(self.rest), x, v);
                }
            }
        }
    }

    /// The content's position for a finger at `finger`: itself inside the bounds, the
    /// rubber band's stretch past an end (the end without a band).
    fn banded(&self, finger: f64) -> S {
        let (lo, hi) = (self.bounds.min().to_f64(), self.bounds.max().to_f64());
        let stretch = |past: f64| self.band.map_or(0.0, |b| b.stretch(past));
        S::from_f64(if finger < lo {
            lo + stretch(finger - lo)
        } else if finger > hi {
            hi + stretch(finger - hi)
        } else {
            finger
        })
    }

    /// The finger position that puts the content at `x`: the inverse of
    /// [`Scroll::banded`] (itself without a band).
    fn unbanded(&self, x: S) -> f64 {
        let x = x.to_f64();
        let (lo, hi) = (self.bounds.min().to_f64(), self.bounds.max().to_f64());
        match self.band {
            Some(b) if x < lo => lo + b.finger(x - lo),
            Some(b) if x > hi => hi + b.finger(x - hi),
            _ => x,
        }
    }
}
