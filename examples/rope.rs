//! Starter: a rope pinned at one end, its other end dragged by a pointer through a drag
//! handle (a zero-length spring to a pinned point that follows the pointer), then let go.
//! `cargo run --example rope` draws it on a simulated display and writes
//! `target/tour/rope.gif`; `draw` runs on any embedded-graphics `DrawTarget`, your panel's
//! driver.
//!
//! On a chip without an FPU, make it `Scene::<I16F16, 2, 13, 12>` and write the numbers as
//! `I16F16` (`I16F16::from_num(0.02)`); `examples/check_rope.rs` runs the same kind of rope in both.
use embedded_graphics::pixelcolor::Rgb565;
use embedded_graphics::prelude::*;
use embedded_graphics::primitives::{Circle, Line, PrimitiveStyle};
use firmware::display::Display;
use stiffspring::Tuning;
use stiffspring::scene::{ParticleId, Scene, SceneConfig, SleepThreshold};

const DT: f64 = 1.0 / 240.0; // four physics steps per 60 Hz frame
fn pixel([x, y]: [f32; 2]) -> Point {
    Point::new((x * 100.0) as i32, 160 - (y * 100.0) as i32) // 100 px per metre, y up
}

pub fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut display = Display::new(); // the simulated 240×160 panel: your driver goes here
    // The drag and the sleep threshold the docs recommend for a rope of about a metre
    // (`SceneConfig::linear_damping`): near critical for its slowest swing, so that the
    // released rope comes to rest, and 1 cm/s for half a second, so that its island then
    // falls asleep and costs nothing. At rest the drag does nothing.
    let config = SceneConfig::new(DT)?
        .gravity([0.0, -9.81])?
        .linear_damping(6.0)?
        .sleep(SleepThreshold::new(0.01, 0.5)?);
    let mut rope = Scene::<f32, 2, 13, 12>::new(config);
    // Links that let the rope hang 5 % longer than its 1.1 m at rest, from what a designer
    // asks for (C_k = N·g·dt²/(stretch·link) = 0.375, within the network limit of ¾), with
    // no stretch damping: the drag damps the stretch too, and the rope hangs exactly as
    // long as asked (stretch damping would shorten it with the default stepper).
    let link = Tuning::from_rope_stretch(11, 0.1, 9.81, 0.05, 0.0, DT)?;
    let mut ids = vec![rope.add_pinned([0.5, 1.3])?];
    for i in 1..12 {
        ids.push(rope.add_particle([0.5 + 0.1 * i as f32, 1.3], 0.02)?); // 20 g each
        rope.add_spring(ids[i - 1], ids[i], 0.1, &link)?;
    }
    let tip = ids[11];
    let drag = Tuning::from_coefficients(0.5, 0.5, DT)?; // a firm grip, within the limit too
    let (handle, _) = rope.add_anchor(rope.position(tip)?, tip, 0.0, &drag)?;
    let mut asleep = None;
    for frame in 0..420 {
        let t = frame as f32 / 60.0;
        if t < 2.0 {
            let wiggle = 0.3 * (std::f32::consts::TAU * 1.5 * t).sin();
            rope.set_position(handle, [1.6 - 0.4 * t, 1.3 - 0.45 * t + wiggle])?; // the pointer
        } else if frame == 120 {
            rope.remove_particle(handle)?; // let go: the handle and its spring are gone
        }
        for _ in 0..4 {
            let motion = rope.step(); // what moved, and which islands fell asleep
            if frame >= 120 && motion.moving == 0 && asleep.is_none() {
                asleep = Some(t - 2.0);
            }
        }
        // Nothing moves once the rope sleeps: a firmware stops redrawing (and stepping).
        if asleep.is_none() || frame % 60 == 0 {
            draw(&mut display, &rope, &ids, (frame < 120).then_some(handle))?;
            display.show();
        }
    }
    let length = rope.position(ids[0])?[1] - rope.position(tip)?[1];
    println!(
        "rope: released at 2 s, asleep {} later, hanging {:.3} m ({:+.1} % of its 1.1 m); wrote {}",
        asleep.map_or("never".to_string(), |s| format!("{s:.2} s")),
        length,
        100.0 * (length / 1.1 - 1.0),
        display.save_gif("rope")?.display()
    );
    Ok(())
}

/// One frame on any embedded-graphics display: the rope's links, and the drag handle
/// while there is one.
fn draw<D: DrawTarget<Color = Rgb565>>(
    d: &mut D,
    rope: &Scene<f32, 2, 13, 12>,
    ids: &[ParticleId],
    handle: Option<ParticleId>,
) -> Result<(), D::Error> {
    d.clear(Rgb565::BLACK)?;
    for pair in ids.windows(2) {
        if let (Ok(a), Ok(b)) = (rope.position(pair[0]), rope.position(pair[1])) {
            Line::new(pixel(a), pixel(b))
                .into_styled(PrimitiveStyle::with_stroke(Rgb565::CSS_LIGHT_GREEN, 2))
                .draw(d)?;
        }
    }
    if let Some(Ok(at)) = handle.map(|h| rope.position(h)) {
        Circle::with_center(pixel(at), 9)
            .into_styled(PrimitiveStyle::with_stroke(Rgb565::WHITE, 1))
            .draw(d)?;
    }
    Ok(())
}
