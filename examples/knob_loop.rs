//! Starter: the control loop of a haptic knob at 4 kHz, with 24 detents between endstops
//! at ±135°, set up in physical units (rotor inertia, motor torque, encoder counts). A
//! simulated rotor stands in for the motor and the encoder: a finger turns it through a
//! few detents into the endstop, then lets go. `cargo run --example knob_loop`.
use stiffspring::{Knob, KnobConfig};

pub fn main() -> Result<(), stiffspring::knob::KnobError> {
    const RATE: f64 = 4_000.0; // Hz: the loop runs once per encoder reading
    const LIMIT: f64 = 0.05; // N·m: the motor's torque at full current
    let config = KnobConfig::new(RATE, 1e-5, LIMIT, 16_384) // 1e−5 kg·m² rotor, 14-bit encoder
        .endstops(-135f64.to_radians(), 135f64.to_radians())
        .detent_count(24)
        .detent_stiffness(0.1); // N·m/rad
    let mut knob = Knob::<f32>::new(&config, 0.0)?; // refuses what it cannot keep stable
    // The simulated rotor: replace with your encoder read and your FOC torque command.
    let (mut angle, mut speed, dt) = (0.0f64, 0.0f64, 1.0 / RATE);
    let count = std::f64::consts::TAU / 16_384.0;
    for n in 0..8_000 {
        let encoder = ((angle / count).round() * count) as f32; // read the encoder (radians)
        let out = knob.update(encoder);
        if out.events.detent_step != 0 {
            println!("knob: t = {:4} ms: detent {}", n / 4, out.detent);
        }
        if let Some(stop) = out.events.endstop_hit {
            println!("knob: t = {:4} ms: endstop {stop:?}", n / 4);
        }
        // Command out.torque (a fraction of LIMIT). A finger turns the knob toward 2.6 rad,
        // past the endstop, for the first second, then lets go.
        let finger = if n < 4_000 {
            0.05 * (2.6 - angle) - 5e-4 * speed
        } else {
            0.0
        };
        speed += (f64::from(out.torque) * LIMIT + finger) / 1e-5 * dt;
        angle += speed * dt;
    }
    println!(
        "knob: at rest on detent {} ({:.1}°)",
        knob.detent(),
        angle.to_degrees()
    );
    Ok(())
}
