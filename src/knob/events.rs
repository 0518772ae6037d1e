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
        self.detent_step != 0 || self.endstop_hit.is_some() || self.magnet_captured.is_some()
    }
}
