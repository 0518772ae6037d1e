//! The 2D rope: 12 particles pinned at one end swing down under gravity.
//!
//! On the host: `cargo run --example rope` prints the tip's path and the final shape.
#![cfg_attr(target_os = "none", no_std, no_main)]

#[path = "scenes/rope.rs"]
mod scene;

#[cfg(not(target_os = "none"))]
fn main() -> Result<(), stiffspring::Error> {
    use stiffspring::length::Exact;
    let (mut rope, ids) = scene::build::<f32, Exact>()?;
    let tip = ids[scene::PARTICLES - 1];
    println!(
        "A rope of {} particles, {} s at {} Hz (f32, exact lengths)",
        scene::PARTICLES,
        scene::STEPS as f64 * scene::DT,
        1.0 / scene::DT
    );
    println!("   t [s]   tip x [m]   tip y [m]");
    for n in 0..=scene::STEPS {
        if n % 60 == 0 {
            let p = rope.position(tip)?;
            println!("{:8.3} {:11.4} {:11.4}", n as f64 * scene::DT, p[0], p[1]);
        }
        if n < scene::STEPS {
            rope.step();
        }
    }
    println!("final shape:");
    for (i, id) in ids.iter().enumerate() {
        let p = rope.position(*id)?;
        println!("  particle {i:2}: ({:+.4}, {:+.4})", p[0], p[1]);
    }
    Ok(())
}
