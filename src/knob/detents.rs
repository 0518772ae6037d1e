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
use crate::scalar::{Raw, Scalar};

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
const fn split<S: Scalar>(x: f64) -> (Raw<S>, Raw<S>) {
    let scale = 1.0 / S::RESOLUTION;
    let high = floor(x * scale);
    (Raw::new(high / scale), Raw::new(x * scale - high))
}

/// A [`Ladder`] computed by the set-up (a `const fn`, so at compile time for a knob
/// designed there): its numbers as the backend's bits, turned into the ladder at run time
/// by [`Ladder::from_parts`] with no `f64` arithmetic.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub(crate) struct LadderParts<S> {
    origin: Raw<S>,
    width: Raw<S>,
    threshold: Raw<S>,
    neg_threshold: Raw<S>,
    min_index: i32,
    max_index: i32,
    index: i32,
    index_value: Raw<S>,
    centre: Raw<S>,
    frac1: Raw<S>,
    frac2: Raw<S>,
    step1: Raw<S>,
    step2: Raw<S>,
    lsb: Raw<S>,
    exact_origin: f64,
    exact_width: f64,
}

/// The centre of detent `index` of the exact grid `origin + i·width`, and the state
/// that carries it from detent to detent: `(centre, frac1, frac2, index_value)`.
const fn centre_of<S: Scalar>(
    origin: f64,
    width: f64,
    index: i32,
) -> (Raw<S>, Raw<S>, Raw<S>, Raw<S>) {
    let exact = origin + index as f64 * width;
    if S::RESOLUTION > 0.0 {
        let units = exact / S::RESOLUTION + 0.5;
        let whole = floor(units);
        let (f1, f2) = split::<S>(units - whole);
        (Raw::new(whole * S::RESOLUTION), f1, f2, Raw::new(0.0))
    } else {
        // A float backend: `origin + index·width`, rounded once, as `Ladder::up` computes
        // it.
        let o = Raw::<S>::new(origin);
        let w = Raw::<S>::new(width);
        let i = Raw::<S>::new(index as f64);
        (Raw::float_mul_add(o, i, w), Raw::new(0.0), Raw::new(0.0), i)
    }
}

impl<S: Scalar> LadderParts<S> {
    /// Detents at `origin + i·width` for `i ∈ [min_index, max_index]`, switching
    /// `threshold` past the centre, starting at `index`. The arguments are validated.
    pub(crate) const fn new(
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
            (Raw::new(whole * lsb), s1, s2, Raw::new(lsb))
        } else {
            (Raw::new(width), Raw::new(0.0), Raw::new(0.0), Raw::new(0.0))
        };
        let index = if index < min_index {
            min_index
        } else if index > max_index {
            max_index
        } else {
            index
        };
        let (centre, frac1, frac2, index_value) = centre_of::<S>(origin, width, index);
        LadderParts {
            origin: Raw::new(origin),
            width: width_s,
            threshold: Raw::new(threshold),
            neg_threshold: Raw::new(-threshold),
            min_index,
            max_index,
            index,
            index_value,
            centre,
            frac1,
            frac2,
            step1,
            step2,
            lsb,
            exact_origin: origin,
            exact_width: width,
        }
    }

    /// A grid that never switches: index 0 at `origin` (a knob without detents).
    pub(crate) const fn fixed(origin: f64) -> Self {
        LadderParts {
            origin: Raw::new(origin),
            width: Raw::new(0.0),
            threshold: Raw::new(S::MAX),
            neg_threshold: Raw::new(-S::MAX),
            min_index: 0,
            max_index: 0,
            index: 0,
            index_value: Raw::new(0.0),
            centre: Raw::new(origin),
            frac1: Raw::new(0.0),
            frac2: Raw::new(0.0),
            step1: Raw::new(0.0),
            step2: Raw::new(0.0),
            lsb: Raw::new(0.0),
            exact_origin: origin,
            exact_width: 0.0,
        }
    }
}

impl<S: Scalar> Ladder<S> {
    /// The ladder the set-up computed.
    pub(crate) fn from_parts(p: &LadderParts<S>) -> Self {
        Ladder {
            origin: p.origin.get(),
            width: p.width.get(),
            threshold: p.threshold.get(),
            neg_threshold: p.neg_threshold.get(),
            min_index: p.min_index,
            max_index: p.max_index,
            index: p.index,
            index_value: p.index_value.get(),
            centre: p.centre.get(),
            frac1: p.frac1.get(),
            frac2: p.frac2.get(),
            step1: p.step1.get(),
            step2: p.step2.get(),
            lsb: p.lsb.get(),
            exact_origin: p.exact_origin,
            exact_width: p.exact_width,
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
    ///
    /// The test for a move is inline, and the walk itself out of line: most periods do
    /// not move, and one copy of the walk serves this, [`Self::seek`] and
    /// [`Self::settle`] (an inlined walk of four unrolled steps was 300 bytes of
    /// `Knob::update` on the Cortex-M4F, `scripts/size-report`).
    #[inline(always)]
    pub(crate) fn update(&mut self, angle: S) -> i8 {
        if self.direction(angle) != 0 {
            // At most MAX_WALK (4) detents: the sum fits an i8.
            self.walk(angle, MAX_WALK) as i8
        } else {
            0
        }
    }

    /// Which way `angle` takes the index: 1 up, −1 down, 0 for none (within the
    /// switching threshold of the centre, or at the end of the range).
    #[inline(always)]
    fn direction(&self, angle: S) -> i32 {
        // The switching points as angles (`centre ± threshold`), not the extension
        // against the threshold: the knob's quiet window is made of the same points, so
        // the two tests agree to the last bit.
        // (Written out rather than through `switching_points`'s options, which cost the
        // detent walk 160 bytes on the Cortex-M0 and 2 instructions a swept period.)
        if angle > self.centre.add(self.threshold) && self.index < self.max_index {
            1
        } else if angle < self.centre.add(self.neg_threshold) && self.index > self.min_index {
            -1
        } else {
            0
        }
    }

    /// The angles past which [`Self::update`] moves the index, `(down, up)`:
    /// `centre ± threshold`, and none at the ends of the range, where the index moves no
    /// further that way.
    pub(crate) fn switching_points(&self) -> (Option<S>, Option<S>) {
        let down = (self.index > self.min_index).then(|| self.centre.add(self.neg_threshold));
        let up = (self.index < self.max_index).then(|| self.centre.add(self.threshold));
        (down, up)
    }

    /// Walks the index toward `angle`, at most `limit` detents; returns how many it
    /// moved. The walk is monotone (a switching point lies at least half a width from its
    /// centre), so it ends.
    #[inline(never)]
    fn walk(&mut self, angle: S, limit: usize) -> i32 {
        let mut moved = 0i32;
        for _ in 0..limit {
            let d = self.direction(angle);
            match d {
                1 => self.up(),
                -1 => self.down(),
                _ => break,
            }
            moved += d;
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
        self.walk(angle, MAX_SEEK)
    }

    /// Puts the index on the detent whose centre is nearest `angle` (ties to the higher),
    /// walking from where it is: set-up only, as many detents as that takes.
    pub(crate) fn settle(&mut self, angle: S) {
        while self.walk(angle, MAX_SEEK) != 0 {}
        // The walk stops within the switching threshold (at least half a width) of a
        // centre: the nearest is this one or a neighbour.
        let here = angle.sub(self.centre).abs();
        if self.index < self.max_index {
            self.up();
            if angle.sub(self.centre).abs() <= here {
                return;
            }
            self.down();
        }
        if self.index > self.min_index {
            self.down();
            if angle.sub(self.centre).abs() < here {
                return;
            }
            self.up();
        }
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
        let (centre, frac1, frac2, index_value) =
            centre_of::<S>(self.exact_origin, self.exact_width, self.index);
        self.centre = centre.get();
        self.frac1 = frac1.get();
        self.frac2 = frac2.get();
        if S::RESOLUTION == 0.0 {
            self.index_value = index_value.get();
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
// `repr(C)`, in this order, so that a nonzero field parts the two arrays: a knob without
// magnets clears each array by itself, in stores inline, where the compiler cleared the
// two arrays and the count as one 68-byte block with a call to `__aeabi_memclr8` (174
// bytes of `knob_f32_const` on the Cortex-M4F, `scripts/size-report`).
#[repr(C)]
pub(crate) struct Magnets<S: Scalar> {
    centres: [S; MAX_MAGNETS],
    radius: S,
    midpoints: [S; MAX_MAGNETS],
    release: S,
    count: usize,
    nearest: usize,
    captured: bool,
    tracker: Tracker<S>,
}

/// What [`Magnets::update`] calls: [`Magnets::track`] when there are magnets, nothing
/// when there are none. A pointer rather than a test of the count, so that a firmware
/// whose knob is designed without magnets at compile time never names `track`, and the
/// linker drops it (736 bytes on the Cortex-M4F, `scripts/size-report`'s
/// `knob_f32_const`): the set-up's constant count folds the pointer to `None`.
#[derive(Clone, Copy)]
struct Tracker<S: Scalar>(Option<Track<S>>);

/// [`Magnets::track`]'s type.
type Track<S> = fn(&mut Magnets<S>, S) -> MagnetUpdate<S>;

/// What a magnets' update returns: the extension from the capturing magnet's centre,
/// whether the rotor is captured, and the magnet that captured it in this period.
type MagnetUpdate<S> = (S, bool, Option<u8>);

impl<S: Scalar> PartialEq for Tracker<S> {
    /// Two trackers are equal when both track or neither does: the pointer is
    /// `Magnets::track` whenever it is set, so its address says nothing more.
    fn eq(&self, other: &Self) -> bool {
        self.0.is_some() == other.0.is_some()
    }
}

impl<S: Scalar> core::fmt::Debug for Tracker<S> {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.write_str(if self.0.is_some() { "Tracking" } else { "None" })
    }
}

#[cfg(feature = "defmt")]
impl<S: Scalar> defmt::Format for Tracker<S> {
    fn format(&self, f: defmt::Formatter<'_>) {
        defmt::write!(
            f,
            "{=str}",
            if self.0.is_some() { "Tracking" } else { "None" }
        )
    }
}

/// [`Magnets`] computed by the set-up, as the backend's bits ([`LadderParts`]).
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub(crate) struct MagnetParts<S> {
    centres: [Raw<S>; MAX_MAGNETS],
    midpoints: [Raw<S>; MAX_MAGNETS],
    count: usize,
    radius: Raw<S>,
    release: Raw<S>,
}

impl<S: Scalar> MagnetParts<S> {
    /// The first `count` of `sorted` (validated centres); `release = radius + hysteresis`.
    pub(crate) const fn new(
        sorted: &[f64; MAX_MAGNETS],
        count: usize,
        radius: f64,
        release: f64,
    ) -> Self {
        let mut centres = [Raw::new(0.0); MAX_MAGNETS];
        let mut midpoints = [Raw::new(0.0); MAX_MAGNETS];
        let count = if count < MAX_MAGNETS {
            count
        } else {
            MAX_MAGNETS
        };
        let mut k = 0;
        while k < count {
            centres[k] = Raw::new(sorted[k]);
            if k + 1 < count {
                midpoints[k] = Raw::new(0.5 * (sorted[k] + sorted[k + 1]));
            }
            k += 1;
        }
        MagnetParts {
            centres,
            midpoints,
            count,
            radius: Raw::new(radius),
            release: Raw::new(release),
        }
    }
}

impl<S: Scalar> Magnets<S> {
    /// The magnets the set-up computed. Inlined, so that a constant count of zero leaves
    /// no reference to [`Self::track`] (see [`Tracker`]).
    #[inline(always)]
    pub(crate) fn from_parts(p: &MagnetParts<S>) -> Self {
        let track: Track<S> = Self::track;
        Magnets {
            tracker: Tracker(if p.count > 0 { Some(track) } else { None }),
            centres: p.centres.map(Raw::get),
            midpoints: p.midpoints.map(Raw::get),
            count: p.count,
            radius: p.radius.get(),
            release: p.release.get(),
            nearest: 0,
            captured: false,
        }
    }

    /// Whether there are magnets.
    pub(crate) fn any(&self) -> bool {
        self.count > 0
    }

    /// Updates the nearest magnet and the capture for `angle`. Returns the extension
    /// `angle − centre` of the capturing magnet (zero when free), whether the rotor is
    /// captured, and the magnet that captured it this period, if any.
    #[inline(always)]
    pub(crate) fn update(&mut self, angle: S) -> MagnetUpdate<S> {
        // Inlined: a knob without magnets pays a test, not a call.
        match self.tracker.0 {
            Some(track) => track(self, angle),
            None => (S::ZERO, false, None),
        }
    }

    /// [`Self::update`] with magnets, out of line.
    #[inline(never)]
    fn track(&mut self, angle: S) -> MagnetUpdate<S> {
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
