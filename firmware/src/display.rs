//! The simulated display of the starter examples (`examples/card.rs`, `examples/list.rs`,
//! `examples/rope.rs`): a framebuffer that embedded-graphics draws on, as it draws on a
//! real panel's driver, and that records what it shows as an animated GIF under
//! `target/tour/`. Host only; it needs no system library (no SDL, no window).
//!
//! ```ignore
//! let mut display = firmware::display::Display::new(); // your panel's driver here
//! loop {
//!     display.clear(Rgb565::BLACK)?;
//!     // …draw with embedded-graphics…
//!     display.show(); // a driver flushes here; this one records the frame
//! }
//! display.save_gif("card")?; // target/tour/card.gif
//! ```

use core::convert::Infallible;
use embedded_graphics_core::pixelcolor::{Rgb565, RgbColor};
use embedded_graphics_core::prelude::{DrawTarget, OriginDimensions, Pixel, Size};
use std::path::{Path, PathBuf};
use std::vec::Vec;

/// The panel's width in pixels (a 240×160 TFT, in landscape).
pub const WIDTH: u32 = 240;
/// The panel's height in pixels.
pub const HEIGHT: u32 = 160;
/// The display's frame rate, in hertz: the UI starters step their springs once a frame.
pub const FRAME_RATE: f64 = 60.0;
/// Every how many shown frames one is recorded: the GIF plays at 30 frames per second,
/// in real time (a GIF's delay is counted in hundredths of a second, and players stretch
/// delays under 2/100 s).
const RECORD_EVERY: u32 = 2;

/// A 240×160 `Rgb565` framebuffer that records the frames it shows.
pub struct Display {
    pixels: Vec<Rgb565>,
    /// The recorded frames, as indices into `palette`.
    frames: Vec<Vec<u8>>,
    palette: Vec<Rgb565>,
    shown: u32,
}

impl Default for Display {
    fn default() -> Self {
        Self::new()
    }
}

impl Display {
    /// A black display with no frame recorded.
    pub fn new() -> Self {
        Display {
            pixels: std::vec![Rgb565::BLACK; (WIDTH * HEIGHT) as usize],
            frames: Vec::new(),
            palette: std::vec![Rgb565::BLACK],
            shown: 0,
        }
    }

    /// Ends a frame: a panel's driver would flush the framebuffer here. Every second
    /// frame is recorded for the GIF.
    pub fn show(&mut self) {
        if self.shown.is_multiple_of(RECORD_EVERY) {
            let mut last = (Rgb565::BLACK, 0u8);
            let mut frame = Vec::with_capacity(self.pixels.len());
            for &p in &self.pixels {
                if p != last.0 {
                    last = (p, index_of(&mut self.palette, p));
                }
                frame.push(last.1);
            }
            self.frames.push(frame);
        }
        self.shown += 1;
    }

    /// The frames shown so far.
    pub fn frames_shown(&self) -> u32 {
        self.shown
    }

    /// The colour at `(x, y)` (black outside the panel), for tests of what was drawn.
    pub fn pixel(&self, x: u32, y: u32) -> Rgb565 {
        if x < WIDTH && y < HEIGHT {
            self.pixels[(y * WIDTH + x) as usize]
        } else {
            Rgb565::BLACK
        }
    }

    /// Writes the recorded frames to `target/tour/NAME.gif` under the workspace, looping,
    /// and returns the path.
    ///
    /// # Errors
    ///
    /// The file system's, or the encoder's as an `InvalidData` error.
    pub fn save_gif(&self, name: &str) -> std::io::Result<PathBuf> {
        let firmware = Path::new(env!("CARGO_MANIFEST_DIR"));
        let dir = firmware
            .parent()
            .unwrap_or(firmware)
            .join("target")
            .join("tour");
        std::fs::create_dir_all(&dir)?;
        let path = dir.join(std::format!("{name}.gif"));
        let mut rgb = Vec::with_capacity(3 * self.palette.len());
        for c in &self.palette {
            // 5- and 6-bit channels widened to 8 bits.
            rgb.extend([
                c.r() << 3 | c.r() >> 2,
                c.g() << 2 | c.g() >> 4,
                c.b() << 3 | c.b() >> 2,
            ]);
        }
        let invalid =
            |e: gif::EncodingError| std::io::Error::new(std::io::ErrorKind::InvalidData, e);
        let file = std::io::BufWriter::new(std::fs::File::create(&path)?);
        let mut encoder =
            gif::Encoder::new(file, WIDTH as u16, HEIGHT as u16, &rgb).map_err(invalid)?;
        encoder.set_repeat(gif::Repeat::Infinite).map_err(invalid)?;
        for (k, pixels) in self.frames.iter().enumerate() {
            let mut frame = gif::Frame::from_indexed_pixels(
                WIDTH as u16,
                HEIGHT as u16,
                pixels.as_slice(),
                None,
            );
            frame.delay = gif_delay(k);
            encoder.write_frame(&frame).map_err(invalid)?;
        }
        Ok(path)
    }
}

/// The delay of recorded frame `k`, in the GIF's centiseconds: the time from its start to
/// the next one's, each rounded to the centisecond from the start of the animation, so
/// that the GIF plays at the rate the frames were stepped (two 60 Hz frames are 3.33 cs:
/// 3, 3, 4, 3, 3, 4, … rather than 3 every time, which played 10 % fast).
fn gif_delay(k: usize) -> u16 {
    let at = |k: usize| (100.0 * (k as f64) * f64::from(RECORD_EVERY) / FRAME_RATE).round();
    (at(k + 1) - at(k)) as u16
}

impl OriginDimensions for Display {
    fn size(&self) -> Size {
        Size::new(WIDTH, HEIGHT)
    }
}

impl DrawTarget for Display {
    type Color = Rgb565;
    type Error = Infallible;

    fn draw_iter<I>(&mut self, pixels: I) -> Result<(), Self::Error>
    where
        I: IntoIterator<Item = Pixel<Self::Color>>,
    {
        for Pixel(point, colour) in pixels {
            // Pixels outside the panel are dropped, as a driver clips them.
            if let (Ok(x), Ok(y)) = (u32::try_from(point.x), u32::try_from(point.y))
                && x < WIDTH
                && y < HEIGHT
            {
                self.pixels[(y * WIDTH + x) as usize] = colour;
            }
        }
        Ok(())
    }

    fn clear(&mut self, colour: Self::Color) -> Result<(), Self::Error> {
        self.pixels.fill(colour);
        Ok(())
    }
}

/// The palette index of `colour`, added if new; the nearest entry once the palette
/// holds 256 colours (the starters draw with a handful).
fn index_of(palette: &mut Vec<Rgb565>, colour: Rgb565) -> u8 {
    if let Some(i) = palette.iter().position(|c| *c == colour) {
        return i as u8;
    }
    if palette.len() < 256 {
        palette.push(colour);
        return (palette.len() - 1) as u8;
    }
    let distance = |c: &Rgb565| {
        let d = |a: u8, b: u8| (i32::from(a) - i32::from(b)).pow(2);
        d(c.r(), colour.r()) + d(c.g(), colour.g()) + d(c.b(), colour.b())
    };
    (0..palette.len())
        .min_by_key(|&i| distance(&palette[i]))
        .unwrap_or(0) as u8
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_gif_plays_at_the_rate_the_frames_were_stepped() {
        // 300 recorded frames of two 60 Hz frames: 10 s, to the centisecond, and never
        // more than half a centisecond off at any frame.
        let mut total = 0u32;
        for k in 0..300 {
            total += u32::from(gif_delay(k));
            let exact = 100.0 * (k + 1) as f64 * 2.0 / 60.0;
            assert!(
                (f64::from(total) - exact).abs() <= 0.5,
                "frame {k}: {total} cs"
            );
        }
        assert_eq!(total, 1000);
    }
}
