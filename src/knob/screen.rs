//! What the knob does with a reading that cannot be physical: the state of the screen
//! between the encoder and the law.
//!
//! A good reading moves the rotor by less than the configured maximum speed allows in
//! one period (`max_step`), and changes its movement per period by less than the motor
//! and a hand can (`jolt`: four times the torque limit on half the configured inertia,
//! plus six counts of quantisation and noise over the three readings a change of
//! movement spans). The hot path tests both with two comparisons; a knob holding or lost
//! fails them by construction (its gate is negative), so that those cases run in the cold
//! path, `Knob::recover`. A knob fading in ([`Mode::Fading`]) or blending a
//! reconfiguration ([`Mode::Blending`]) takes the hot path, and only its torque goes
//! through the cold `Knob::ease`.
//!
//! After a bad reading the knob holds the last torque for [`HOLD_PERIODS`] periods, then
//! commands none. If the next reading continues the motion from before the bad one, the
//! knob goes on as if nothing happened. Otherwise it waits for [`AGREE_STEPS`] steps that
//! agree with each other (each within the jolt of the one before, and within the
//! maximum speed), takes up the angle, velocity and detent they give, and fades its
//! torque back in over [`FADE_PERIODS`] periods.

/// How many periods a bad reading holds the last torque before the knob lets go.
pub const HOLD_PERIODS: u8 = 2;

/// How many consecutive steps between readings must agree before the knob takes up the
/// readings again.
pub const AGREE_STEPS: u8 = 3;

/// How many periods the torque takes to fade back in after the knob took up the readings
/// again.
pub const FADE_PERIODS: u8 = 16;

/// The change of movement per period the screen allows is this many times what the
/// torque limit alone gives the rotor: the motor plus a hand up to three times as strong.
pub(crate) const JOLT_TORQUES: f64 = 4.0;

/// Encoder counts added to the jolt: a second difference of three floored readings is
/// off by less than 4 counts, and by 2 more with one count of noise on one of them.
pub(crate) const JOLT_COUNTS: f64 = 6.0;

/// Where the screen is.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub(crate) enum Mode {
    /// Every reading goes to the law.
    #[default]
    Tracking,
    /// The last `missed` readings were bad; the last torque is held while `missed ≤
    /// HOLD_PERIODS`.
    Holding { missed: u8 },
    /// The readings are not trusted; `agree` readings in a row agree so far.
    Lost { agree: u8 },
    /// Taken up again: the torque is multiplied by the fade (`Knob::fade`), which rises by
    /// `1/FADE_PERIODS` a period and ends the fade at 1 (exactly: `1/FADE_PERIODS` is a
    /// power of two, whose sums every backend holds without rounding).
    Fading,
    /// Reconfigured: the torque carries an offset from the old layout's, which moves to
    /// zero by at most one count's torque per period.
    Blending,
}
