//! Starter: a card on a 60 Hz display springs to where you tap, is retargeted mid-flight,
//! is flung, and says when it has settled. `cargo run --example card` draws it on a
//! simulated display and writes `target/tour/card.gif`; `draw` runs on any embedded-graphics
//! `DrawTarget`, your panel's driver.
use embedded_graphics::pixelcolor::Rgb565;
use embedded_graphics::prelude::*;
use embedded_graphics::primitives::{Circle, PrimitiveStyle, Rectangle, RoundedRectangle};
use firmware::display::Display;
use stiffspring::{Motion, RestThreshold, SpringValue, Tuning};

pub fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut display = Display::new(); // the simulated 240×160 panel: your driver goes here
    let tuning = Tuning::from_frequency(2.0, 0.5, 1.0 / 60.0)?; // 2 Hz, a little bounce, at 60 Hz
    let mut card = SpringValue::<f32, 2>::new([40.0, 40.0], &tuning)?
        .with_rest_threshold(RestThreshold::PIXELS); // settled: less than a pixel left to move
    let taps = [(0, [190.0, 110.0]), (25, [60.0, 120.0])]; // (frame, where the finger taps)
    let mut tap = [0.0, 0.0];
    for frame in 0..180 {
        if let Some((_, at)) = taps.iter().find(|(f, _)| *f == frame) {
            card.set_target(*at); // cannot fail: NaN is ignored, the rest saturates
            tap = *at;
        }
        if frame == 80 {
            card.fling([-600.0, -900.0]); // a finger lets go of it, flinging it up (px/s)
        }
        let motion = card.step();
        if motion == Motion::Settled {
            println!("card: settled on {:?} at frame {frame}", card.position());
        }
        if motion.moved() || frame == 0 {
            draw(&mut display, tap, card.position())?;
        }
        display.show(); // a frame: only frames that moved were redrawn
    }
    println!("card: wrote {}", display.save_gif("card")?.display());
    Ok(())
}

/// One frame on any embedded-graphics display: the tap's ring and the card.
fn draw<D: DrawTarget<Color = Rgb565>>(
    d: &mut D,
    tap: [f32; 2],
    at: [f32; 2],
) -> Result<(), D::Error> {
    let [x, y] = at.map(|c| c.round() as i32);
    d.clear(Rgb565::BLACK)?;
    Circle::with_center(Point::new(tap[0] as i32, tap[1] as i32), 9)
        .into_styled(PrimitiveStyle::with_stroke(Rgb565::CSS_GRAY, 1))
        .draw(d)?;
    RoundedRectangle::with_equal_corners(
        Rectangle::with_center(Point::new(x, y), Size::new(56, 36)),
        Size::new(8, 8),
    )
    .into_styled(PrimitiveStyle::with_fill(Rgb565::CSS_ORANGE))
    .draw(d)
}
