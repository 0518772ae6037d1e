//! Starter: a menu on a haptic knob. Its 8 detents are the 8 items and its endstops the
//! list's ends: a click steps the menu (a `Scroll` on `Snap` points) to the next item, and
//! a turn into a stop cannot pass the first or last. A simulated rotor and scripted hand
//! stand in for the motor and encoder. `cargo run --example knob_menu` draws it (`draw`
//! takes any `DrawTarget`) to `target/tour/knob_menu.gif`; `--target thumbv7em-none-eabihf`
//! runs it on a Cortex-M4F in QEMU. Both check the run against golden values.
#![cfg_attr(target_os = "none", no_std, no_main)]
firmware::output!(text);

#[cfg(not(target_os = "none"))]
use embedded_graphics::{pixelcolor::Rgb565, prelude::*, primitives::*};
use firmware::scenes::knob_menu::{CONFIG, Check, FRAMES, ITEMS, PERIODS, ROW, Rotor};
use stiffspring::{Bounds, Error, Friction, Knob, Scroll, Snap, knob};

pub fn run() -> bool {
    play() == Ok(true)
}
firmware::main!(run); // on the host and the firmware: fails off the golden values

fn play() -> Result<bool, Error> {
    #[cfg(not(target_os = "none"))]
    let mut display = firmware::display::Display::new(); // your panel's driver goes here
    let mut knob = Knob::from_design(&knob!(CONFIG), 0.0)?; // designed when it is built
    let bounds = Bounds::new(0.0, (ITEMS - 1) as f32 * ROW)?; // the first item to the last
    let mut menu = Scroll::<f32>::new(0.0, bounds, &Friction::IOS_NORMAL, 1.0 / 60.0)?
        .with_snap(Snap::spacing(ROW, 0.0)?); // rests on an item
    let (mut rotor, mut check) = (Rotor::new(), Check::new()); // your motor; the golden run
    for _ in 0..FRAMES {
        for _ in 0..PERIODS {
            let out = knob.update(rotor.encoder() as f32); // the knob's loop, at 1.2 kHz
            if out.events.detent_step != 0 {
                menu.step_by(out.events.detent_step.into()); // a click moves the selection
                say!("knob_menu: item {}", out.detent);
            }
            rotor.turn(out.torque.into()); // command the torque
        }
        let _ = menu.step(); // a frame of the menu, at 60 Hz
        check.frame(&knob, &menu);
        #[cfg(not(target_os = "none"))] // the simulated display cannot fail
        let _ = draw(&mut display, menu.position(), knob.detent()).map(|()| display.show());
    }
    say!("knob_menu: golden run: worst {} px", check.offsets.worst);
    #[cfg(not(target_os = "none"))]
    check.require(display.save_gif("knob_menu").is_ok()); // target/tour/knob_menu.gif
    Ok(check.passed())
}

/// One frame on any embedded-graphics display: the items, the selected `item` in orange,
/// scrolled so that the item at `offset / ROW` is in the middle.
#[cfg(not(target_os = "none"))]
fn draw<D: DrawTarget<Color = Rgb565>>(d: &mut D, offset: f32, item: i32) -> Result<(), D::Error> {
    d.clear(Rgb565::BLACK)?;
    for i in 0..ITEMS as i32 {
        let y = (67.0 + i as f32 * ROW - offset).round() as i32;
        let row = Rectangle::new(Point::new(12, y), Size::new(96 + 16 * i as u32, 26));
        let colour = [Rgb565::CSS_STEEL_BLUE, Rgb565::CSS_ORANGE][usize::from(i == item)];
        row.into_styled(PrimitiveStyle::with_fill(colour)).draw(d)?;
    }
    Ok(())
}
