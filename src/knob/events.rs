//! What happened during one control period: the knob's events.

/// Which endstop.
///
/// ```
/// use stiffspring::knob::Endstop;
/// assert_ne!(Endstop::Min, Endstop::Max);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Endstop {
    /// The lower end of the range.
    Min,
    /// The upper end of the range.
    Max,
}

/// The events of one call to [`Knob::update`](crate::Knob::update).
///
/// Each is reported once, on the period it happens, with hysteresis so that encoder
/// noise at a boundary does not repeat it: a detent change needs the snap point plus the
/// hysteresis, an endstop hit needs the rotor to come back inside by the hysteresis
/// before it counts again, and a magnet captures inside its radius and releases only
/// beyond its radius plus the hysteresis.
///
/// ```
/// use stiffspring::knob::KnobEvents;
///
/// let none = KnobEvents::default();
/// assert!(!none.any());
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct KnobEvents {
    /// The detent index changed this period (the new index is in
    /// [`KnobOutput::detent`](crate::KnobOutput::detent)); its sign says which way.
    pub detent_step: i8,
    /// The rotor went past an endstop this period.
    pub endstop_hit: Option<Endstop>,
    /// A magnetic detent captured the rotor this period (its index in the sorted list).
    pub magnet_captured: Option<u8>,
    /// This period's reading was not used: it cannot be physical (see [`SensorFault`]).
    /// The knob held its last torque (for two periods, then none) and waits for readings
    /// that agree again.
    pub sensor: Option<SensorFault>,
    /// The knob took up the readings again after a fault: its angle, velocity and
    /// detent jumped to what the encoder reads, and the torque fades back in.
    pub resynced: bool,
}

/// Why a reading was not used.
///
/// ```
/// use stiffspring::{Knob, KnobConfig};
/// use stiffspring::knob::SensorFault;
///
/// let config = KnobConfig::new(1_000.0, 1e-5, 0.05, 16384).detent_width(0.2).detent_stiffness(0.05);
/// let mut knob = Knob::<f32>::new(&config, 0.0)?;
/// let out = knob.update(f32::NAN);
/// assert_eq!(out.events.sensor, Some(SensorFault::NotANumber));
/// assert_eq!(out.torque, 0.0); // the torque of the last good reading, held
/// # Ok::<(), stiffspring::knob::KnobError>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum SensorFault {
    /// A NaN (float backends).
    NotANumber,
    /// An infinite angle, or one beyond the range the knob's arithmetic holds
    /// ([`Knob::reach`](crate::Knob::reach)).
    OutOfRange,
    /// A reading too far from where the rotor can be: its change of velocity since the
    /// last reading is more than the motor and a hand can give the rotor in one period
    /// ([`Knob::max_jolt`](crate::Knob::max_jolt)), or it moved farther than the
    /// configured [`max_speed`](crate::KnobConfig::max_speed) allows in one period
    /// after a reading that did not.
    Jump,
    /// Readings that agree with each other, of a rotor turning faster than the configured
    /// [`max_speed`](crate::KnobConfig::max_speed): the torque stays off until it slows
    /// down.
    TooFast,
}

impl KnobEvents {
    /// True when anything happened.
    ///
    /// ```
    /// use stiffspring::knob::{Endstop, KnobEvents};
    ///
    /// let hit = KnobEvents { endstop_hit: Some(Endstop::Max), ..KnobEvents::default() };
    /// assert!(hit.any());
    /// ```
    pub fn any(&self) -> bool {
        self.detent_step != 0
            || self.endstop_hit.is_some()
            || self.magnet_captured.is_some()
            || self.sensor.is_some()
            || self.resynced
    }
}
