//! Which detent the rotor is in, with hysteresis, and the magnetic detents.
//!
//! A detent pulls the rotor toward its centre over its whole cell, so its torque is a
//! sawtooth that changes sign where the rotor passes from one cell to the next. If that
//! boundary sits on an encoder count, the quantised angle toggles across it and the torque
//! would flip sign every period: the knob buzzes. The index therefore switches only when
//! the rotor is past the **snap point** (a fraction of the width from the current centre,
//! SmartKnob's `snap_point`) and at least the **hysteresis** (a few encoder counts) past
//! the midpoint; coming back, the same distance is measured from the new centre, so the
//! band in which a toggling count could switch back and forth is never crossed by one
//! count (`tests/knob_hysteresis.rs`).

use super::config::MAX_MAGNETS;
use super::validate::floor;
use crate::scalar::Scalar;

/// How many detents the index may move in one period. At 1 kHz that is 4 000 detents per
/// second, beyond a flick of a 1° knob (about 3 turns/s); a rotor moving faster catches up
/// over the next periods instead of stalling the loop.
pub(crate) const MAX_WALK: usize = 4;

/// The most detents one [`Ladder::seek`] walks; a knob taken up farther away than this
/// walks the rest at [`MAX_WALK`] detents a period.
pub(crate) const MAX_SEEK: usize = 4096;

/// The detent grid: the current index and centre, and the switching threshold.
///
/// # Centres far from the origin
///
/// A float backend computes the centre as `origin + index·width`, rounded once. A fixed
/// backend cannot: the index of an endless knob outgrows its range (`I16F16` holds
/// ±32,767, a 100-detent knob at 1000 rad is at detent 15,915; at 32,000 rad, 509,000), and a width rounded to
/// the LSB puts detent `i` `i·½` LSB off. So in fixed point the centre is carried from
/// detent to detent, exactly: the width is a whole number of LSB plus a remainder kept to
/// 2⁻³² LSB over two fractional accumulators, so that the centre stays the nearest LSB to
/// `origin + i·width` anywhere in the backend's range (`tests/knob_fixed.rs`).
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub(crate) struct Ladder<S: Scalar> {
    origin: S,
    width: S,
    threshold: S,
    neg_threshold: S,
    min_index: i32,
    max_index: i32,
    index: i32,
    /// Floats: the index as a number (exact below 2²⁴ in `f32`).
    index_value: S,
    centre: S,
    /// Fixed point: `origin + index·width + LSB/2 = centre + (frac1 + frac2·LSB)·LSB`.
    frac1: S,
    frac2: S,
    /// The width's remainder below one LSB: `step1 + step2·LSB` (in LSB).
    step1: S,
    step2: S,
    /// One LSB (fixed point), zero for floats.
    lsb: S,
    /// The exact grid, for resets.
    exact_origin: f64,
    exact_width: f64,
}

/// `x − floor(x)` split into a value on the backend's grid and the rest, scaled up:
/// `(floor(x·2^F)/2^F, frac(x·2^F))` with `2^F = 1/LSB`.
fn split<S: Scalar>(x: f64) -> (S, S) {
    let scale = 1.0 / S::RESOLUTION;
    let high = floor(x * scale);
    (S::from_f64(high / scale), S::from_f64(x * scale - high))
}

impl<S: Scalar> Ladder<S> {
    /// Detents at `origin + i·width` for `i ∈ [min_index, max_index]`, switching `threshold`
    /// past the centre, starting at `index`. Set-up only; the arguments are validated.
    pub(crate) fn new(
        origin: f64,
        width: f64,
        threshold: f64,
        (min_index, max_index): (i32, i32),
        index: i32,
    ) -> Self {
        let fixed = S::RESOLUTION > 0.0;
        let (width_s, step1, step2, lsb) = if fixed {
            let lsb = S::RESOLUTION;
            let units = width / lsb;
            let whole = floor(units);
            let (s1, s2) = split::<S>(units - whole);
            (S::from_f64(whole * lsb), s1, s2, S::from_f64(lsb))
        } else {
            (S::from_f64(width), S::ZERO, S::ZERO, S::ZERO)
        };
        let mut ladder = Ladder {
            origin: S::from_f64(origin),
            width: width_s,
            threshold: S::from_f64(threshold),
            neg_threshold: S::from_f64(-threshold),
            min_index,
            max_index,
            index,
            index_value: S::ZERO,
            centre: S::ZERO,
            frac1: S::ZERO,
            frac2: S::ZERO,
            step1,
            step2,
            lsb,
            exact_origin: origin,
            exact_width: width,
        };
        ladder.set_index(index);
        ladder
    }

    /// A grid that never switches: index 0 at `origin` (a knob without detents).
    pub(crate) fn fixed(origin: f64) -> Self {
        let never = S::from_f64(S::MAX);
        Ladder {
            origin: S::from_f64(origin),
            width: S::ZERO,
            threshold: never,
            neg_threshold: never.neg(),
            min_index: 0,
            max_index: 0,
            index: 0,
            index_value: S::ZERO,
            centre: S::from_f64(origin),
            frac1: S::ZERO,
            frac2: S::ZERO,
            step1: S::ZERO,
            step2: S::ZERO,
            lsb: S::ZERO,
            exact_origin: origin,
            exact_width: 0.0,
        }
    }

    /// One detent up.
    #[inline(always)]
    fn up(&mut self) {
        self.index += 1;
        if S::RESOLUTION > 0.0 {
            self.centre = self.centre.add(self.width);
            self.frac2 = self.frac2.add(self.step2);
            if self.frac2 >= S::ONE {
                self.frac2 = self.frac2.sub(S::ONE);
                self.frac1 = self.frac1.add(self.lsb);
            }
            self.frac1 = self.frac1.add(self.step1);
            if self.frac1 >= S::ONE {
                self.frac1 = self.frac1.sub(S::ONE);
                self.centre = self.centre.add(self.lsb);
            }
        } else {
            self.index_value = self.index_value.add(S::ONE);
            self.centre = self.origin.add(self.index_value.mul(self.width));
        }
    }

    /// One detent down: exactly the inverse of [`Self::up`].
    #[inline(always)]
    fn down(&mut self) {
        self.index -= 1;
        if S::RESOLUTION > 0.0 {
            self.centre = self.centre.sub(self.width);
            self.frac2 = self.frac2.sub(self.step2);
            if self.frac2 < S::ZERO {
                self.frac2 = self.frac2.add(S::ONE);
                self.frac1 = self.frac1.sub(self.lsb);
            }
            self.frac1 = self.frac1.sub(self.step1);
            if self.frac1 < S::ZERO {
                self.frac1 = self.frac1.add(S::ONE);
                self.centre = self.centre.sub(self.lsb);
            }
        } else {
            self.index_value = self.index_value.sub(S::ONE);
            self.centre = self.origin.add(self.index_value.mul(self.width));
        }
    }

    /// Moves the index toward `angle` (at most [`MAX_WALK`] detents) and returns the
    /// number of detents it moved, signed.
    #[inline]
    pub(crate) fn update(&mut self, angle: S) -> i8 {
        // At most MAX_WALK (4) detents: the sum fits an i8.
        self.walk::<MAX_WALK>(angle) as i8
    }

    /// Walks the index toward `angle`, at most `LIMIT` detents; returns how many it
    /// moved. The walk is monotone (a switching point lies at least half a width from its
    /// centre), so it ends.
    #[inline(always)]
    fn walk<const LIMIT: usize>(&mut self, angle: S) -> i32 {
        let mut moved = 0i32;
        for _ in 0..LIMIT {
            let e = angle.sub(self.centre);
            if e > self.threshold && self.index < self.max_index {
                self.up();
                moved += 1;
            } else if e < self.neg_threshold && self.index > self.min_index {
                self.down();
                moved -= 1;
            } else {
                break;
            }
        }
        moved
    }

    /// The current detent index.
    #[inline(always)]
    pub(crate) fn index(&self) -> i32 {
        self.index
    }

    /// Walks the index to `angle` as [`Ladder::update`] does, without its limit of
    /// [`MAX_WALK`] detents, up to [`MAX_SEEK`] (reset, and taking up the readings after a
    /// sensor fault); returns how many detents it moved.
    pub(crate) fn seek(&mut self, angle: S) -> i32 {
        self.walk::<MAX_SEEK>(angle)
    }

    /// The current detent centre.
    #[inline(always)]
    pub(crate) fn centre(&self) -> S {
        self.centre
    }

    /// Puts the index on `index` (set-up and reset only), with the centre from the exact
    /// grid.
    pub(crate) fn set_index(&mut self, index: i32) {
        if self.exact_width == 0.0 {
            return;
        }
        self.index = index.clamp(self.min_index, self.max_index);
        let exact = self.exact_origin + f64::from(self.index) * self.exact_width;
        if S::RESOLUTION > 0.0 {
            let units = exact / S::RESOLUTION + 0.5;
            let whole = floor(units);
            let (f1, f2) = split::<S>(units - whole);
            self.centre = S::from_f64(whole * S::RESOLUTION);
            self.frac1 = f1;
            self.frac2 = f2;
        } else {
            self.index_value = S::from_f64(f64::from(self.index));
            self.centre = self.origin.add(self.index_value.mul(self.width));
        }
    }
}

/// Magnetic detents: centres at arbitrary angles that pull the rotor only within a
/// capture radius; between them the knob turns freely (apart from the other layers).
///
/// Their capture zones, widened by the hysteresis, do not overlap (checked at set-up), so
/// switching the nearest magnet at the midpoints never changes the torque, and only the
/// capture edge needs hysteresis.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub(crate) struct Magnets<S: Scalar> {
    centres: [S; MAX_MAGNETS],
    midpoints: [S; MAX_MAGNETS],
    count: usize,
    radius: S,
    release: S,
    nearest: usize,
    captured: bool,
}

impl<S: Scalar> Magnets<S> {
    /// Sorted, validated centres; `release = radius + hysteresis`.
    pub(crate) fn new(sorted: &[f64], radius: f64, release: f64) -> Self {
        let mut centres = [S::ZERO; MAX_MAGNETS];
        let mut midpoints = [S::ZERO; MAX_MAGNETS];
        let count = sorted.len().min(MAX_MAGNETS);
        for k in 0..count {
            centres[k] = S::from_f64(sorted[k]);
            if k + 1 < count {
                midpoints[k] = S::from_f64(0.5 * (sorted[k] + sorted[k + 1]));
            }
        }
        Magnets {
            centres,
            midpoints,
            count,
            radius: S::from_f64(radius),
            release: S::from_f64(release),
            nearest: 0,
            captured: false,
        }
    }

    /// Updates the nearest magnet and the capture for `angle`. Returns the extension
    /// `angle − centre` of the capturing magnet (zero when free), whether the rotor is
    /// captured, and the magnet that captured it this period, if any.
    #[inline]
    pub(crate) fn update(&mut self, angle: S) -> (S, bool, Option<u8>) {
        if self.count == 0 {
            return (S::ZERO, false, None);
        }
        let before = self.nearest;
        // At most `count` moves in total: the midpoints are sorted.
        for _ in 0..MAX_MAGNETS {
            match self.midpoints.get(self.nearest) {
                Some(&mid) if self.nearest + 1 < self.count && angle > mid => self.nearest += 1,
                _ => break,
            }
        }
        for _ in 0..MAX_MAGNETS {
            match self
                .nearest
                .checked_sub(1)
                .and_then(|k| self.midpoints.get(k))
            {
                Some(&mid) if angle < mid => self.nearest -= 1,
                _ => break,
            }
        }
        if self.nearest != before {
            self.captured = false;
        }
        let centre = self.centres.get(self.nearest).copied().unwrap_or(S::ZERO);
        let e = angle.sub(centre);
        let distance = e.abs();
        let mut newly = None;
        if self.captured {
            if distance > self.release {
                self.captured = false;
            }
        } else if distance <= self.radius {
            self.captured = true;
            newly = Some(self.nearest as u8);
        }
        if self.captured {
            (e, true, newly)
        } else {
            (S::ZERO, false, None)
        }
    }

    /// Forgets the capture (reset).
    pub(crate) fn reset(&mut self) {
        self.captured = false;
    }
}
