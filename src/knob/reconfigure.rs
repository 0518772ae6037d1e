//! A new layout for a running knob: menus change their detents, and the rotor must not
//! feel the change as a kick.

use super::screen::Mode;
use super::{Knob, KnobConfig, KnobError};
use crate::scalar::Scalar;

/// Where a new layout's detents lie when a running knob takes it
/// ([`Knob::reconfigure`]).
///
/// ```
/// use stiffspring::knob::Anchor;
/// assert_ne!(Anchor::AsConfigured, Anchor::CurrentDetent);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Anchor {
    /// Where the configuration puts them: the knob takes the new layout's detent nearest
    /// its angle.
    AsConfigured,
    /// Shifted, endstops and all, so that the current detent keeps its index and its
    /// centre: a menu that grows or shrinks under a knob at rest stays where it is.
    CurrentDetent,
}

impl<S: Scalar> Knob<S> {
    /// Takes a new layout (detents, strengths, endstops, magnets, damping) in place. The
    /// angle, the velocity filter's state and the sensor screen carry over; with
    /// [`Anchor::CurrentDetent`] the detent index does too (the new layout's last, where it
    /// has fewer detents). The torque moves from the old
    /// layout's to the new one's by at most one count's torque (of the new detents; at
    /// least 1/256 of the limit) per period, so the change is not felt as a kick.
    ///
    /// # Errors
    ///
    /// Those of [`Knob::new`], for the new configuration at the current angle. The knob
    /// is then unchanged.
    ///
    /// ```
    /// use stiffspring::knob::Anchor;
    /// use stiffspring::{Knob, KnobConfig};
    ///
    /// let menu = |items: u32| {
    ///     KnobConfig::new(1_000.0, 1e-5, 0.05, 16384)
    ///         .endstops(0.0, 0.25 * f64::from(items - 1))
    ///         .detent_count(items)
    ///         .detent_stiffness(0.05)
    /// };
    /// let mut knob = Knob::<f32>::new(&menu(8), 0.75)?;
    /// assert_eq!(knob.detent(), 3);
    /// knob.reconfigure(&menu(4), Anchor::CurrentDetent)?;
    /// assert_eq!((knob.detent(), knob.detent_centre()), (3, 0.75));
    /// assert!(knob.reconfigure(&menu(1), Anchor::CurrentDetent).is_err());
    /// assert_eq!(knob.detent(), 3); // nothing lost
    /// # Ok::<(), stiffspring::knob::KnobError>(())
    /// ```
    pub fn reconfigure(&mut self, config: &KnobConfig, anchor: Anchor) -> Result<(), KnobError> {
        let angle = self.previous;
        let mut next = match anchor {
            Anchor::AsConfigured => Knob::new(config, angle)?,
            Anchor::CurrentDetent => {
                let shifted = config.shifted_to(self.detent(), self.detent_centre().to_f64());
                let mut k = Knob::new(&shifted, angle)?;
                k.ladder.set_index(self.detent());
                // The window `Knob::new` set is the detent it settled on, which need not
                // be this one: set it again, or the probe below takes the short path
                // about this detent's centre and skips the switch the long path makes.
                k.refresh_quiet();
                k
            }
        };
        // The damper's state is a torque times the state scale: rescaled to the new
        // gain, it is the same velocity.
        let ratio = next.damping_gain.to_f64() / self.damping_gain.to_f64();
        let state = if ratio.is_finite() {
            S::from_f64(self.damping_state.to_f64() * ratio)
        } else {
            S::ZERO
        };
        next.previous = self.previous;
        next.held = self.held;
        next.last_step = self.last_step;
        next.damping_state = state;
        // The new torque at this state, without advancing it: the offset starts as the
        // difference, and the blend takes it away.
        let mut probe = next.clone();
        let new_torque = probe.period(angle, S::ZERO).torque;
        next.mode = self.mode;
        next.fade = self.fade;
        next.candidate = self.candidate;
        next.candidate_step = self.candidate_step;
        next.last_torque = self.last_torque;
        if next.mode == Mode::Tracking || next.mode == Mode::Blending {
            next.offset = self.last_torque.sub(new_torque);
            if next.offset != S::ZERO {
                next.mode = Mode::Blending;
            }
        }
        next.gate = if matches!(next.mode, Mode::Tracking | Mode::Blending | Mode::Fading) {
            next.jolt
        } else {
            S::ONE.neg()
        };
        *self = next;
        // The mode may differ from the new knob's: the quiet window follows it.
        self.refresh_quiet();
        Ok(())
    }
}
