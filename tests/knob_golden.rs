//! The golden values of the `knob` scene (`firmware/src/scenes/knob.rs`), which
//! `examples/check_knob.rs` checks its `f32` and `I16F16` knobs against on the host and on the
//! microcontrollers: the torque and the detent index after each period of the scene's
//! scripted encoder sweep.
//!
//! They come from a model of the knob's documented torque law written here in `f64`
//! (`τ = −K_zone·knee(dz(e)) − B·v`, `dz` the rest zone of two counts, `knee` the soft
//! knee of up to four counts, `v` the low-pass-filtered movement of a play of 1.25
//! counts on the angle, torques under 2⁻²⁴ of the limit sent as zero, the detent
//! index switching past the snap point and the hysteresis, the endstop adding to the
//! detent field; see the `knob` module docs), with the damping from the configured damping
//! ratio, `B = 2ζ·√(K·J)`. The one set-up output taken from the library is the velocity
//! filter's time constant, which its loop analysis chooses (`tests/knob_stability.rs`
//! checks that analysis). The library's `f64` knob must follow the model to rounding.
//!
//! This test recomputes them and fails when `firmware/src/golden/knob.rs` is missing or
//! stale. To regenerate:
//!
//! ```text
//! STIFFSPRING_BLESS=1 cargo test --release --test knob_golden
//! ```

use firmware::golden::knob as golden;
use firmware::scenes::knob as scene;
use lab::golden::{check_or_bless, f64_table};
use std::path::Path;
use stiffspring::Knob;

/// The scene's detent layout and springs, as `scene::config()` sets them.
const DETENTS: u32 = 20;
const DETENT_STIFFNESS: f64 = 0.1;
const ENDSTOP_STIFFNESS: f64 = 0.15;
const SNAP: f64 = 0.55;
const ZETA: f64 = 0.7;
const HYSTERESIS_COUNTS: f64 = 2.0;
/// The law's rest zone, knee and play, in counts (the `knob` module docs).
const REST_COUNTS: f64 = 2.0;
const KNEE_COUNTS: f64 = 4.0;
const PLAY_COUNTS: f64 = 1.25;

/// The knob's torque law, one period at a time, in `f64`.
struct Model {
    dt: f64,
    width: f64,
    threshold: f64,
    damping: f64,
    alpha: f64,
    knee: f64,
    index: i32,
    held: f64,
    velocity: f64,
}

impl Model {
    /// At rest at `angle`, in the nearest detent.
    fn new(angle: f64, filter_time_constant: f64) -> Self {
        let width = scene::MAX / f64::from(DETENTS - 1);
        let threshold = (SNAP * width).max(0.5 * width + HYSTERESIS_COUNTS * scene::COUNT);
        let rest = REST_COUNTS * scene::COUNT;
        Model {
            dt: scene::DT,
            width,
            threshold,
            // Four counts, or a quarter of the way from the rest zone to the switch.
            knee: (KNEE_COUNTS * scene::COUNT).min(0.25 * (threshold - rest)),
            damping: 2.0 * ZETA * (DETENT_STIFFNESS * scene::INERTIA).sqrt(),
            alpha: scene::DT / (filter_time_constant + scene::DT),
            index: ((angle / width).round() as i32).clamp(0, DETENTS as i32 - 1),
            held: angle,
            velocity: 0.0,
        }
    }

    /// The torque (a fraction of the limit) and the detent index for the encoder `angle`.
    fn update(&mut self, angle: f64) -> (f64, i32) {
        // The play: the damper sees the angle's movement beyond ±1.25 counts.
        let play = PLAY_COUNTS * scene::COUNT;
        let held = self.held.clamp(angle - play, angle + play);
        let speed = (held - self.held) / self.dt;
        self.held = held;
        self.velocity += self.alpha * (speed - self.velocity);
        // The index moves at most four detents a period.
        for _ in 0..4 {
            let e = angle - f64::from(self.index) * self.width;
            if e > self.threshold && self.index < DETENTS as i32 - 1 {
                self.index += 1;
            } else if e < -self.threshold && self.index > 0 {
                self.index -= 1;
            } else {
                break;
            }
        }
        let detent = DETENT_STIFFNESS * (angle - f64::from(self.index) * self.width);
        // Beyond a stop the endstop's spring adds to the detent field.
        let (stiffness, spring) = if angle > scene::MAX {
            (
                DETENT_STIFFNESS + ENDSTOP_STIFFNESS,
                detent + ENDSTOP_STIFFNESS * (angle - scene::MAX),
            )
        } else if angle < 0.0 {
            (
                DETENT_STIFFNESS + ENDSTOP_STIFFNESS,
                detent + ENDSTOP_STIFFNESS * angle,
            )
        } else {
            (DETENT_STIFFNESS, detent)
        };
        // The rest zone: no spring within two counts of the rest point; then the knee,
        // quadratic up to its width, then the full stiffness.
        let rest = stiffness * REST_COUNTS * scene::COUNT;
        let knee = stiffness * self.knee;
        let over = spring.abs() - rest;
        let magnitude = if over <= 0.0 {
            0.0
        } else if over < knee {
            over * over / (2.0 * knee)
        } else {
            over - 0.5 * knee
        };
        let spring = magnitude.copysign(spring);
        let torque = (-(spring + self.damping * self.velocity) / scene::LIMIT).clamp(-1.0, 1.0);
        // A float's rounding noise is not sent to the motor.
        let torque = if torque.abs() < 1.0 / 16_777_216.0 {
            0.0
        } else {
            torque
        };
        (torque, self.index)
    }
}

#[test]
fn knob_golden_values_are_current() {
    // At rest where the sweep starts (a jump there would be a sensor fault).
    let start = scene::sweep_angle(0);
    let mut knob = Knob::<f64>::new(&scene::config(), start).unwrap();
    // The set-up the model assumes.
    assert_eq!(knob.torque_limit(), scene::LIMIT);
    assert_eq!(knob.rest_zone(), REST_COUNTS * scene::COUNT);
    let b = 2.0 * ZETA * (DETENT_STIFFNESS * scene::INERTIA).sqrt();
    assert!((knob.damping() - b).abs() < 1e-15, "{}", knob.damping());
    let stiffness = knob.zone_stiffness();
    assert!((stiffness[2] - (DETENT_STIFFNESS + ENDSTOP_STIFFNESS)).abs() < 1e-15);
    let mut model = Model::new(start, knob.filter_time_constant());
    assert_eq!(knob.knee(), model.knee);

    let (mut torques, mut detents) = (Vec::new(), Vec::new());
    let mut worst: f64 = 0.0;
    for n in 0..scene::SWEEP_STEPS {
        let angle = scene::sweep_angle(n);
        let (torque, detent) = model.update(angle);
        let out = knob.update(angle);
        assert_eq!(out.events.sensor, None, "period {n}, angle {angle}");
        assert_eq!(out.detent, detent, "period {n}, angle {angle}");
        worst = worst.max((out.torque - torque).abs());
        torques.push(torque);
        detents.push(f64::from(detent));
    }
    println!("the f64 knob against the model: worst torque difference {worst:.1e} of the limit");
    assert!(worst < 1e-12, "{worst}");
    // The sweep crosses every detent both ways, drives into both stops and saturates.
    let changes = detents.windows(2).filter(|w| w[0] != w[1]).count();
    assert!(changes >= 2 * 19, "{changes} detent changes");
    assert!(torques.contains(&1.0) && torques.contains(&-1.0));

    let source = format!(
        "//! Golden values of the `knob` scene (`firmware/src/scenes/knob.rs`):\n\
         //! the torque (a fraction of the limit) and the detent index of the knob's torque\n\
         //! law after each period of the scripted encoder sweep.\n\
         //!\n\
         //! @generated by `STIFFSPRING_BLESS=1 cargo test --release --test knob_golden` from\n\
         //! the f64 model of the torque law in tests/knob_golden.rs; do not edit.\n\n{}",
        f64_table(
            "SWEEP",
            "The torque, then the detent index; sample `k` is after period `k`.",
            &[
                ("torque".to_string(), torques.as_slice()),
                ("detent".to_string(), detents.as_slice()),
            ],
        )
    );
    check_or_bless(
        &Path::new(env!("CARGO_MANIFEST_DIR")).join("firmware/src/golden/knob.rs"),
        &source,
        &[torques, detents],
        &golden::SWEEP,
        1e-12,
        "regenerate with `STIFFSPRING_BLESS=1 cargo test --release --test knob_golden`",
    );
}
