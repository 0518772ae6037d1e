//! The scenes the dual-target examples play, shared with `tests/golden.rs`, which plays
//! them on the f64 reference model (or, for the knob, the library's `f64` knob) and
//! writes their golden values into [`crate::golden`].

pub mod knob;
pub mod knob_menu;
pub mod rope;
pub mod value;

/// Where a knob comes to rest, in encoder counts, for the closed-loop examples' checks
/// (`knob_rtic`, `knob_embassy`): a rotor drifts without torque inside the law's rest zone,
/// so its swing at rest is at most the zone's width plus the count it toggles by, and it
/// rests within the zone and the knee of its rest point.
pub mod knob_rest {
    use stiffspring::knob::{KNEE_COUNTS, REST_COUNTS};

    /// The most a rotor at rest swings, counts peak to peak.
    pub const SWING: i32 = 2 * REST_COUNTS as i32 + 1;
    /// The farthest a rotor at rest is from its rest point, counts.
    pub const OFFSET: i32 = (REST_COUNTS + KNEE_COUNTS) as i32;
}
