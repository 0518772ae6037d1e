//! Starter: a list of 200 rows scrolled by a finger. A drag moves it, a release flings it
//! and it glides to rest on a row (`Snap`), and a drag past the top stretches less than
//! the finger (`RubberBand`) and springs back. `cargo run --example scroll` draws it on a
//! simulated display and writes `target/tour/scroll.gif`; `draw` runs on any
//! embedded-graphics `DrawTarget`, your panel's driver.
use embedded_graphics::pixelcolor::Rgb565;
use embedded_graphics::prelude::*;
use embedded_graphics::primitives::{PrimitiveStyle, Rectangle};
use firmware::display::Display;
use stiffspring::{Bounds, Friction, Motion, RestThreshold, RubberBand, Scroll, Snap};

const ROW: f32 = 24.0; // pixels per row; the screen is 160 px tall

pub fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut display = Display::new(); // the simulated 240×160 panel: your driver goes here
    let bounds = Bounds::new(0.0, 200.0 * ROW - 160.0)?; // the content offset's range
    let mut list = Scroll::<f32>::new(0.0, bounds, &Friction::IOS_FAST, 1.0 / 60.0)?
        .with_snap(Snap::spacing(ROW, 0.0)?) // come to rest on a row
        .with_rubber_band(RubberBand::new(160.0)?) // overscroll like iOS, on a 160 px view
        .with_rest_threshold(RestThreshold::PIXELS); // at rest: under a pixel to go
    for frame in 0..240 {
        match frame {
            0 | 130 => list.grab(),           // a finger touches the screen
            1..=20 => list.drag_by(12.0),     // and pushes the list up 240 px
            21 => list.release(3000.0),       // then lets go at 3000 px/s
            131..=155 => list.drag_by(-30.0), // drags it down past the top: it stretches less
            156 => list.release(0.0),         // let go: it springs back
            _ => {}
        }
        let (at, to) = (list.position(), list.resting_point());
        if frame == 21 || frame == 156 {
            println!("scroll: released at {at:.0} px, to rest on {to:.0} px");
        }
        if list.step() == Motion::Settled {
            println!(
                "scroll: frame {frame}: at rest on {to:.0} px, row {}",
                to / ROW
            );
        }
        draw(&mut display, list.position())?;
        display.show();
    }
    println!("scroll: wrote {}", display.save_gif("scroll")?.display());
    Ok(())
}

/// One frame on any embedded-graphics display: the rows the offset puts on screen.
fn draw<D: DrawTarget<Color = Rgb565>>(d: &mut D, offset: f32) -> Result<(), D::Error> {
    d.clear(Rgb565::BLACK)?;
    let first = (offset / ROW).floor().max(0.0) as i32;
    for row in first..first + 8 {
        let top = Point::new(8, (row as f32 * ROW - offset).round() as i32 + 2);
        let shade = [Rgb565::CSS_STEEL_BLUE, Rgb565::CSS_SLATE_GRAY][row as usize % 2];
        Rectangle::new(top, Size::new(224, ROW as u32 - 4))
            .into_styled(PrimitiveStyle::with_fill(shade))
            .draw(d)?;
    }
    Ok(())
}
