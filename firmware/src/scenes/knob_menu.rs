//! The `knob_menu` scene: a menu of [`ITEMS`] items on a haptic knob with as many
//! detents between its endstops, the knob's loop at 1.2 kHz and the menu's frames at
//! 60 Hz. Shared by `examples/knob_menu.rs` (the starter: host and firmware) and by
//! `tests/knob_menu_golden.rs`, which plays the same rotor and hand with the library's
//! `f64` knob and the menu on the analytic solution of its step spring, and writes
//! `firmware/src/golden/knob_menu.rs`. Change it, then regenerate the golden values:
//! `STIFFSPRING_BLESS=1 cargo test --release --test knob_menu_golden`.
//!
//! The hand turns the knob up through every item into the upper endstop and pushes
//! there, lets go, turns it back down three items, lets go, then turns it down into the
//! lower endstop and lets go again.

use crate::Tally;
use crate::golden::knob_menu as golden;
use stiffspring::{Knob, KnobConfig, Scalar, Scroll};

/// The knob's control rate, Hz: 20 periods per 60 Hz frame.
pub const RATE: f64 = 1_200.0;
/// The knob's control period, s.
pub const DT: f64 = 1.0 / RATE;
/// The knob's periods in one frame of the menu.
pub const PERIODS: usize = 20;
/// The menu's frame time, s.
pub const FRAME: f64 = PERIODS as f64 * DT;
/// The frames played: 5.5 s.
pub const FRAMES: usize = 330;
/// The rotor and knob cap, kg·m².
pub const INERTIA: f64 = 1e-5;
/// The motor's torque limit, N·m.
pub const LIMIT: f64 = 0.05;
/// One count of a 14-bit encoder, rad.
pub const COUNT: f64 = core::f64::consts::TAU / 16_384.0;
/// The menu's items, one per detent.
pub const ITEMS: u32 = 8;
/// One detent: 30°.
pub const WIDTH: f64 = core::f64::consts::PI / 6.0;
/// The knob's range, from the first item's detent to the last one's: 210°.
pub const RANGE: f64 = (ITEMS - 1) as f64 * WIDTH;
/// The height of one item, px: the menu's offset is `item · ROW` at rest.
pub const ROW: f32 = 32.0;

/// The knob: a detent for each item, the first and the last at the endstops, so that the
/// detent index is the item and cannot leave the list. Detents of 0.1 N·m/rad (a click of
/// 29 mN·m at the snap point); a `const`, so the firmware designs it when it is built
/// (`stiffspring::knob!(CONFIG)`).
pub const CONFIG: KnobConfig = KnobConfig::new(RATE, INERTIA, LIMIT, 16_384)
    .endstops(0.0, RANGE)
    .detent_count(ITEMS)
    .detent_stiffness(0.1);

/// Where the hand pushes the knob at time `t` (s), and whether it touches it.
pub fn hand_target(t: f64) -> Option<f64> {
    // Straight lines between (time, angle) points: up through every item and 0.35 rad
    // into the upper stop; from the last item down three and a half; from the fourth item
    // 0.35 rad past the lower stop. The times are nudged off the 60 Hz grid
    // (by 2.5 ms, 5 ms and −5 ms) so that no detent click falls on a frame's first or last
    // period, where another backend's click a period apart would land in another frame
    // (`tests/knob_menu_golden.rs` checks it).
    let ramp = |t: f64, t0: f64, t1: f64, a0: f64, a1: f64| a0 + (a1 - a0) * (t - t0) / (t1 - t0);
    const UP: f64 = 0.3025; // s: the turn up, for 2 s
    const DOWN: f64 = 3.305; // the turn down three items, for 0.4 s
    const LOW: f64 = 4.195; // the turn into the lower stop, for 0.4 s
    match t {
        t if t < UP => None,
        t if t < UP + 2.0 => Some(ramp(t, UP, UP + 2.0, 0.0, RANGE + 0.35)),
        t if t < 2.8 => Some(RANGE + 0.35),
        t if t < DOWN => None,
        t if t < DOWN + 0.4 => Some(ramp(t, DOWN, DOWN + 0.4, RANGE, RANGE - 3.5 * WIDTH)),
        t if t < LOW => None,
        t if t < LOW + 0.4 => Some(ramp(t, LOW, LOW + 0.4, 4.0 * WIDTH, -0.35)),
        t if t < 4.9 => Some(-0.35),
        _ => None,
    }
}

/// The simulated rotor and encoder of the scene, in `f64` (no `std` needed): a rotor of
/// [`INERTIA`] under the motor's torque, held over each period, and a hand (a spring of
/// 0.2 N·m/rad and 1 mN·m·s/rad toward [`hand_target`]), integrated exactly for a
/// constant torque over four sub-steps of each period; the encoder floors the angle to a
/// count.
#[derive(Clone, Copy, Debug, Default)]
pub struct Rotor {
    angle: f64,
    speed: f64,
    period: usize,
}

impl Rotor {
    /// At rest at angle 0, the first item.
    pub const fn new() -> Self {
        Rotor {
            angle: 0.0,
            speed: 0.0,
            period: 0,
        }
    }

    /// The encoder's reading, rad: the angle floored to a count.
    pub fn encoder(&self) -> f64 {
        let counts = self.angle / COUNT;
        // Floor without `std`: truncate, then step down for negative fractions.
        let whole = counts as i64 as f64;
        let floor = if whole > counts { whole - 1.0 } else { whole };
        floor * COUNT
    }

    /// One period under the motor's `torque` (a fraction of [`LIMIT`]) and the hand.
    pub fn turn(&mut self, torque: f64) {
        const SUB: usize = 4;
        let h = DT / SUB as f64;
        for k in 0..SUB {
            let t = self.period as f64 * DT + k as f64 * h;
            let hand = match hand_target(t) {
                Some(target) => 0.2 * (target - self.angle) - 1e-3 * self.speed,
                None => 0.0,
            };
            let a = (torque * LIMIT + hand) / INERTIA;
            self.angle += self.speed * h + 0.5 * a * h * h;
            self.speed += a * h;
        }
        self.period += 1;
    }

    /// The rotor's angle, rad.
    pub fn angle(&self) -> f64 {
        self.angle
    }
}

/// The menu offset may differ from the golden run by this much, px: the default rest
/// threshold (0.75e−3 px), by which a spring at rest snaps onto its item where the
/// analytic reference goes on, plus the `f32` rounding of offsets up to 224 px
/// (1.5e−5 px an ulp).
pub const OFFSET_TOLERANCE: f64 = 1e-3;

/// The example's check of each frame against the golden run
/// (`firmware/src/golden/knob_menu.rs`): the item (the knob's detent) must be the same,
/// the menu's resting point that item's offset, and its offset within
/// [`OFFSET_TOLERANCE`].
#[derive(Clone, Copy, Debug)]
pub struct Check {
    /// The offsets against the golden ones, px.
    pub offsets: Tally,
    /// Frames whose item differs from the golden one.
    pub item_mismatches: usize,
    /// Frames whose resting point is not the item's offset.
    pub unsynced: usize,
    /// Whether everything [`Check::require`] was given held.
    pub required: bool,
    frame: usize,
}

impl Default for Check {
    fn default() -> Self {
        Self::new()
    }
}

impl Check {
    /// Nothing checked yet.
    pub const fn new() -> Self {
        Check {
            offsets: Tally::new(),
            item_mismatches: 0,
            unsynced: 0,
            required: true,
            frame: 0,
        }
    }

    /// The next frame: the item is the `knob`'s detent, the `menu` rests on its offset
    /// and is where the golden run is.
    pub fn frame<S: Scalar>(&mut self, knob: &Knob<S>, menu: &Scroll<S>) {
        let [items, offsets] = golden::RUN;
        let (k, item) = (self.frame, knob.detent());
        self.frame += 1;
        if k >= items.len() || f64::from(item) != items[k] {
            self.item_mismatches += 1;
        }
        if menu.resting_point().to_f64() != f64::from(item) * f64::from(ROW) {
            self.unsynced += 1;
        }
        let golden = offsets.get(k).copied().unwrap_or(f64::NAN);
        let offset = menu.position().to_f64();
        self.offsets.check(k, offset, golden, OFFSET_TOLERANCE);
    }

    /// Fails the run unless `ok`: what the example needs besides the frames (on the
    /// host, that it wrote its GIF).
    pub fn require(&mut self, ok: bool) {
        self.required &= ok;
    }

    /// True when every frame of the scene was checked and matched.
    pub fn passed(&self) -> bool {
        self.frame == FRAMES
            && self.required
            && self.offsets.passed()
            && self.item_mismatches == 0
            && self.unsynced == 0
    }
}
