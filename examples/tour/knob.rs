//! The haptic knob: against SmartKnob-style PD detents, and a hand turning it.

use lab::knob::pd::{DETENTS, INERTIA, KnobLaw, LIMIT, compare};
use lab::knob::{COUNT, Plant};
use lab::plot::{Grid, Plot, Series};
use lab::table::print;
use std::f64::consts::TAU;
use std::path::Path;
use stiffspring::{Knob, KnobConfig};

/// The library's knob for [`compare`]: detents `width` apart with small-signal stiffness
/// `kp` (N·m/rad) at period `dt`, damping ratio 0.7 (the default), two counts of
/// hysteresis, a 14-bit encoder, in `f32`.
fn knob_law(dt: f64, width: f64, kp: f64) -> KnobLaw {
    let config = KnobConfig::new(1.0 / dt, INERTIA, LIMIT, 16384)
        .detent_width(width)
        .hysteresis(2.0 * COUNT)
        .detent_stiffness(kp);
    let mut knob = Knob::<f32>::new(&config, 0.0).expect("accepted stiffness");
    let cd = knob.loop_coefficients()[0].map_or(0.0, |c| c.damping);
    let law = move |angle: f64| {
        let out = knob.update(angle as f32);
        (f64::from(out.torque) * LIMIT, out.detent)
    };
    (Box::new(law), cd)
}

pub fn against_pd() {
    println!(
        "The knob against SmartKnob-style PD detents: {DETENTS} detents, rotor 1e-5 kg·m², \
         a 20 rad/s flick, 14-bit encoder, one period of delay"
    );
    let mut rows = Vec::new();
    for rate in [1_000.0, 10_000.0] {
        for kp in [0.02, 0.1, 0.25] {
            let c = compare(rate, kp, knob_law);
            for (law, zeta, r) in [
                ("SmartKnob PD", c.pd_zeta, &c.pd),
                ("stiffspring", c.knob_zeta, &c.knob),
            ] {
                rows.push(vec![
                    format!("{} kHz, k_p {kp}", rate / 1e3),
                    law.into(),
                    format!("{zeta:.2}"),
                    format!("{:.0} ms", r.settle_ms),
                    format!("{:.0} %", r.overshoot_pct),
                    format!("{:.2} mN·m", r.ripple_mnm),
                ]);
            }
        }
    }
    print(
        &["case", "law", "ζ", "settle", "overshoot", "ripple at rest"],
        &rows,
    );
    println!(
        "(same rotor, stiffness, detent logic and torque limit; \
         cargo test --release --test knob_vs_pd -- --nocapture prints the full table)\n"
    );
}

/// A finger turns the knob slowly through five detents and lets go between two.
pub fn trace(dir: &Path) {
    let dt = 1e-3;
    let width = TAU / DETENTS;
    let config = KnobConfig::new(1.0 / dt, INERTIA, LIMIT, 16384)
        .detent_width(width)
        .hysteresis(2.0 * COUNT)
        .detent_stiffness(0.05);
    let mut knob = Knob::<f32>::new(&config, 0.0).expect("valid");
    let mut plant = Plant::new(INERTIA, dt, 1.0);
    // The finger drags the knob at 0.5 rad/s for 1.2 s (through about two and a half
    // detents), then lets go halfway between two.
    let mut hand = |theta: f64, omega: f64, t: f64| {
        if t < 1.2 {
            -0.3 * (theta - 0.5 * t) - 0.003 * omega
        } else {
            0.0
        }
    };
    let (mut angle, mut torque, mut detent) = (Vec::new(), Vec::new(), Vec::new());
    for n in 0..2000 {
        let out = knob.update(plant.read() as f32);
        let t = n as f64 * dt;
        angle.push((t, plant.theta / width));
        torque.push((t, f64::from(out.torque) * LIMIT * 1e3));
        detent.push((t, f64::from(out.detent)));
        plant.step(f64::from(out.torque) * LIMIT, &mut hand);
    }
    let grid = Grid::new("A finger drags the knob through detents, then lets go (f32, 1 kHz)")
        .columns(1)
        .plot(
            Plot::new("angle")
                .y_label("angle [detent widths]")
                .series(Series::line("rotor", angle))
                .series(Series::line("detent index", detent).dashed())
                .size(720, 260),
        )
        .plot(
            Plot::new("torque")
                .x_label("time [s]")
                .y_label("torque [mN·m]")
                .series(Series::line("commanded", torque))
                .size(720, 260),
        );
    let path = dir.join("knob_drag.svg");
    grid.write(&path).expect("write knob_drag.svg");
    println!(
        "  wrote {} (cargo run --example check_knob draws a longer scene)\n",
        path.display()
    );
}
