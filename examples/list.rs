//! Starter: a list of 200 rows in one `SpringBatch`. A row is deleted and the rows below
//! close the gap, then the list scrolls by three rows; each step says how many rows
//! moved and settled, so only they need redrawing. `cargo run --example list` draws it on
//! a simulated display and writes `target/tour/list.gif`.
use embedded_graphics::mono_font::{MonoTextStyle, ascii::FONT_6X10};
use embedded_graphics::pixelcolor::Rgb565;
use embedded_graphics::prelude::*;
use embedded_graphics::primitives::{PrimitiveStyle, Rectangle};
use embedded_graphics::text::Text;
use firmware::display::Display;
use stiffspring::{SpringBatch, Tuning};

const ROW: f32 = 24.0; // pixels per row

pub fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut display = Display::new(); // the simulated 240×160 panel: your driver goes here
    let tuning = Tuning::from_frequency(3.0, 0.8, 1.0 / 60.0)?; // every row shares one tuning
    let mut list = SpringBatch::<f32, 1, 200>::new(&tuning)?;
    let mut rows = Vec::new(); // (label, index into the batch)
    for i in 0..200 {
        rows.push((i, list.push([i as f32 * ROW])?));
    }
    let mut scroll = 0.0;
    for frame in 0..150 {
        if frame == 10 {
            let (_, deleted) = rows.remove(1); // delete the second row: the rest move up
            list.remove(deleted);
        }
        if frame == 70 {
            scroll = 3.0 * ROW; // scroll down by three rows
        }
        if frame == 10 || frame == 70 {
            for (slot, (_, index)) in rows.iter().enumerate() {
                list.set_target(*index, [slot as f32 * ROW - scroll]);
            }
        }
        let motion = list.step();
        if motion.settled > 0 {
            println!(
                "list: frame {frame}: {} rows settled, {} moving",
                motion.settled, motion.moving
            );
        }
        display.clear(Rgb565::BLACK)?;
        for (label, index) in &rows {
            let Some([y]) = list.position(*index) else {
                continue;
            };
            if (-ROW..160.0).contains(&y) {
                let top = Point::new(8, y.round() as i32 + 2);
                Rectangle::new(top, Size::new(224, ROW as u32 - 4))
                    .into_styled(PrimitiveStyle::with_fill(Rgb565::CSS_STEEL_BLUE))
                    .draw(&mut display)?;
                let style = MonoTextStyle::new(&FONT_6X10, Rgb565::WHITE);
                Text::new(&format!("row {label}"), top + Point::new(8, 13), style)
                    .draw(&mut display)?;
            }
        }
        display.show();
    }
    println!("list: wrote {}", display.save_gif("list")?.display());
    Ok(())
}
