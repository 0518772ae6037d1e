//! The `value` scene: UI values springing to their targets at 60 Hz, retargeted
//! mid-flight and flung, as a script of events.
//!
//! Shared, as data only, by `examples/check_value.rs` (which plays it on the library, on the
//! host and on the microcontrollers) and by `tests/golden.rs` (which plays it on the
//! analytic solution of the f64 reference model and writes `firmware/src/golden/value.rs`).
//! Change it, then regenerate the golden values:
//! `STIFFSPRING_BLESS=1 cargo test --test golden`.

/// The display's frame time, in seconds.
pub const DT: f64 = 1.0 / 60.0;

/// The number of frames played; golden sample `k` is the position after `k` frames.
pub const FRAMES: usize = 240;

/// Something that happens to a value, after `frame` frames and before the next one.
#[derive(Clone, Copy, Debug)]
pub enum Event {
    /// The target moves; position and velocity are kept.
    Target {
        /// Frames played before the event.
        frame: usize,
        /// The new target.
        to: f64,
    },
    /// A finger lets go: the velocity becomes `velocity` (units per second).
    Fling {
        /// Frames played before the event.
        frame: usize,
        /// The new velocity.
        velocity: f64,
    },
}

/// One animated value: a continuous oscillator, where it starts (at rest) and what
/// happens to it.
#[derive(Clone, Copy, Debug)]
pub struct Track {
    /// A short name for reports.
    pub name: &'static str,
    /// Natural frequency, in hertz.
    pub frequency: f64,
    /// Damping ratio ζ.
    pub damping_ratio: f64,
    /// The position at rest before the first event.
    pub start: f64,
    /// The events, in order of frame.
    pub events: &'static [Event],
}

/// The values of the scene, in the order of the golden arrays.
pub const TRACKS: [Track; 3] = [
    // A card sliding in with SwiftUI-like bounce, sent elsewhere before it arrives, then
    // flung back by a finger.
    Track {
        name: "card_x",
        frequency: 2.0,
        damping_ratio: 0.3,
        start: 0.0,
        events: &[
            Event::Target {
                frame: 0,
                to: 100.0,
            },
            Event::Target {
                frame: 30,
                to: 40.0,
            },
            Event::Fling {
                frame: 90,
                velocity: -300.0,
            },
        ],
    },
    // A scroll offset settling critically damped on a snap point, then on the next one.
    Track {
        name: "scroll",
        frequency: 1.0,
        damping_ratio: 1.0,
        start: 0.0,
        events: &[
            Event::Target {
                frame: 0,
                to: -120.0,
            },
            Event::Target {
                frame: 100,
                to: -240.0,
            },
        ],
    },
    // An overdamped slider knob chasing a target that a drag moves every few frames.
    Track {
        name: "slider",
        frequency: 3.0,
        damping_ratio: 1.5,
        start: 50.0,
        events: &[
            Event::Target { frame: 0, to: 60.0 },
            Event::Target { frame: 4, to: 70.0 },
            Event::Target { frame: 8, to: 85.0 },
            Event::Target {
                frame: 12,
                to: 90.0,
            },
            Event::Fling {
                frame: 60,
                velocity: 120.0,
            },
        ],
    },
];
