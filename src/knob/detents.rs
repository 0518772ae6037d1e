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

use crate::scalar::Scalar;

/// How many detents the index may move in one period. At 1 kHz that is 4 000 detents per
/// second, beyond a flick of a 1° knob (about 3 turns/s); a rotor moving faster catches up
/// over the next periods instead of stalling the loop.
pub(crate) const MAX_WALK: usize = 4;

/// The detent grid: the current index and centre, and the switching threshold.
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
    index_value: S,
    centre: S,
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
        let mut ladder = Ladder {
            origin: S::from_f64(origin),
            width: S::from_f64(width),
            threshold: S::from_f64(threshold),
            neg_threshold: S::from_f64(-threshold),
            min_index,
            max_index,
            index,
            index_value: S::from_f64(index as f64),
            centre: S::ZERO,
        };
        ladder.centre = ladder.centre_of_index();
        ladder
    }

    /// A grid that never switches: index 0 at `origin` (a knob without detents).
    pub(crate) fn fixed(origin: f64) -> Self {
        let never = S::from_f64(S::SAFE_MAGNITUDE);
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
        }
    }

    /// `origin + i·width`, rounded once: computed from the index rather than accumulated,
    /// so that a float backend's centres do not drift over many turns.
    #[inline(always)]
    fn centre_of_index(&self) -> S {
        self.origin.add(self.index_value.mul(self.width))
    }

    /// Moves the index toward `angle` (at most [`MAX_WALK`] detents) and returns the
    /// number of detents it moved, signed.
    #[inline]
    pub(crate) fn update(&mut self, angle: S) -> i8 {
        let mut moved = 0i8;
        for _ in 0..MAX_WALK {
            let e = angle.sub(self.centre);
            if e > self.threshold && self.index < self.max_index {
                self.index += 1;
                self.index_value = self.index_value.add(S::ONE);
                moved += 1;
            } else if e < self.neg_threshold && self.index > self.min_index {
                self.index -= 1;
                self.index_value = self.index_value.sub(S::ONE);
                moved -= 1;
            } else {
                break;
            }
            self.centre = self.centre_of_index();
        }
        moved
    }

    /// The current detent index.
    #[inline(always)]
    pub(crate) fn index(&self) -> i32 {
        self.index
    }

    /// The current detent centre.
    #[inline(always)]
    pub(crate) fn centre(&self) -> S {
        self.centre
    }

    /// Puts the index back on `index` (set-up and reset only).
    pub(crate) fn set_index(&mut self, index: i32) {
        self.index = index.clamp(self.min_index, self.max_index);
        self.index_value = S::from_f64(self.index as f64);
        self.centre = self.centre_of_index();
    }
}

/// The most magnetic detents a knob holds.
///
/// ```
/// use stiffspring::knob::MAX_MAGNETS;
/// assert_eq!(MAX_MAGNETS, 8);
/// ```
pub const MAX_MAGNETS: usize = 8;

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
