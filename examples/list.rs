//! Starter: a list of 200 rows in one `SpringBatch`. A row is deleted and the rows below
//! close the gap, then the list scrolls by three rows; each step says how many rows
//! moved and settled, so only they need redrawing. `cargo run --example list` draws it on
//! a simulated display and writes `target/tour/list.gif`; `draw` runs on any
//! embedded-graphics `DrawTarget`, your panel's driver.
use embedded_graphics::mono_font::{MonoTextStyle, ascii::FONT_6X10};
use embedded_graphics::pixelcolor::Rgb565;
use embedded_graphics::prelude::*;
use embedded_graphics::primitives::{PrimitiveStyle, Rectangle};
use embedded_graphics::text::Text;
use firmware::display::Display;
use stiffspring::{BatchIndex, SpringBatch, Tuning};

const ROW: f32 = 24.0; // pixels per row

pub fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut display = Display::new(); // the simulated 240×160 panel: your driver goes here
    let tuning = Tuning::from_frequency(3.0, 0.8, 1.0 / 60.0)?; // every row shares one tuning
    let mut list = SpringBatch::<f32, 1, 200>::new(&tuning)?;
    let mut rows = Vec::new(); // (label, index into the batch)
    for i in 0..200 {
        rows.push((i, list.push([i as f32 * ROW])?));
    }
    for frame in 0..150 {
        if frame == 10 {
            let (_, deleted) = rows.remove(1); // delete the second row: the rows below close the gap
            list.remove(deleted);
        }
        if frame == 10 || frame == 70 {
            let scroll = if frame == 70 { 3.0 * ROW } else { 0.0 }; // then scroll by three rows
            for (slot, (_, index)) in rows.iter().enumerate() {
                list.set_target(*index, [slot as f32 * ROW - scroll]);
            }
        }
        let motion = list.step(); // how many rows moved and settled: what to redraw
        if motion.settled > 0 {
            println!(
                "list: frame {frame}: {} rows settled, {} moving",
                motion.settled, motion.moving
            );
        }
        draw(&mut display, &rows, &list)?;
        display.show();
    }
    println!("list: wrote {}", display.save_gif("list")?.display());
    Ok(())
}

/// One frame on any embedded-graphics display: the rows on screen, at their positions.
fn draw<D: DrawTarget<Color = Rgb565>>(
    d: &mut D,
    rows: &[(usize, BatchIndex)],
    list: &SpringBatch<f32, 1, 200>,
) -> Result<(), D::Error> {
    d.clear(Rgb565::BLACK)?;
    for (label, index) in rows {
        let y = list.position(*index).map_or(-ROW, |[y]| y);
        if (-ROW + 1.0..160.0).contains(&y) {
            let top = Point::new(8, y.round() as i32 + 2);
            Rectangle::new(top, Size::new(224, ROW as u32 - 4))
                .into_styled(PrimitiveStyle::with_fill(Rgb565::CSS_STEEL_BLUE))
                .draw(d)?;
            let style = MonoTextStyle::new(&FONT_6X10, Rgb565::WHITE);
            Text::new(&format!("row {label}"), top + Point::new(8, 13), style).draw(d)?;
        }
    }
    Ok(())
}
