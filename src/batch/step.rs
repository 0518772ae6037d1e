//! The hot loop of a batch, and what a step reports.

use super::{BatchIndex, BatchMotion, BatchTuning, SpringBatch};
use crate::scalar::Scalar;

/// Whether the target steps a batch several values at a time (SIMD), which a branch per
/// value would prevent: not the microcontrollers, whose scalar loop is cheapest with a
/// branch on the first rest test that fails.
const VECTOR_UNITS: bool = cfg!(any(
    target_arch = "x86_64",
    target_arch = "x86",
    target_arch = "aarch64",
    target_arch = "wasm32"
));

impl<S: Scalar, const D: usize, const N: usize, const T: usize> SpringBatch<S, D, N, T> {
    /// Advances every awake value by one time step, settles those whose motion left is
    /// inside the rest band (every [`with_rest_check_every`](Self::with_rest_check_every)
    /// steps), and reports what moved.
    ///
    /// ```
    /// use stiffspring::{SpringBatch, Tuning};
    /// let mut b = SpringBatch::<f32, 1, 2>::new(&Tuning::from_coefficients(0.5, 0.5, 0.01)?)?;
    /// let i = b.push([0.0])?;
    /// b.set_target(i, [1.0]);
    /// assert_eq!(b.step().moving, 1);
    /// assert_eq!(b.position(i), Some([0.5]));
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn step(&mut self) -> BatchMotion {
        self.settled.clear();
        let awake = self.awake.len();
        if awake == 0 {
            return BatchMotion::default();
        }
        let check = self.until_check == 0;
        self.until_check = if check {
            self.check_every - 1
        } else {
            self.until_check - 1
        };
        if !check {
            self.advance_awake();
            return BatchMotion {
                moving: awake,
                settled: 0,
            };
        }
        if T > 1 {
            // Values of several tunings: each steps with its own, through the awake list.
            self.step_each_tuned();
        } else if awake == self.len {
            // Everything live is awake: one straight pass over the used slots. Removed
            // slots hold a zero state, which a step leaves at zero.
            let (gains, band) = (self.tunings[0].gains, self.tunings[0].band);
            let used = self.used;
            let (offsets, velocities) = (&mut self.offset[..used], &mut self.step_velocity[..used]);
            let live = &self.live[..used];
            let settled = &mut self.settled;
            let mut settle = |slot: usize, x: &mut [S::State; D], u: &mut [S::State; D]| {
                // A removed slot keeps a zero state, inside every band.
                if live[slot] {
                    *x = [S::STATE_ZERO; D];
                    *u = [S::STATE_ZERO; D];
                    // Cannot fail: at most N slots settle.
                    let _ = settled.push(slot as u16);
                }
            };
            if VECTOR_UNITS {
                // A machine with vector units steps the values several at a time: the
                // first pass has no branch, only an `or` of the tests, and a second
                // pass settles, in the rare step where some value is inside its band.
                let mut any = false;
                for (x, u) in offsets.iter_mut().zip(velocities.iter_mut()) {
                    let mut inside = true;
                    for k in 0..D {
                        S::advance(&gains, &mut x[k], &mut u[k]);
                        inside &= band.contains_all(x[k], u[k]);
                    }
                    any |= inside;
                }
                if any {
                    core::hint::cold_path();
                    for (slot, (x, u)) in offsets.iter_mut().zip(velocities.iter_mut()).enumerate()
                    {
                        if (0..D).all(|k| band.contains(x[k], u[k])) {
                            settle(slot, x, u);
                        }
                    }
                }
            } else {
                // A microcontroller steps one value at a time: a branch on the first
                // test that fails is the cheapest test.
                for (slot, (x, u)) in offsets.iter_mut().zip(velocities.iter_mut()).enumerate() {
                    for k in 0..D {
                        S::advance(&gains, &mut x[k], &mut u[k]);
                    }
                    if (0..D).all(|k| band.contains(x[k], u[k])) {
                        core::hint::cold_path();
                        settle(slot, x, u);
                    }
                }
            }
        } else {
            let (gains, band) = (self.tunings[0].gains, self.tunings[0].band);
            for &slot in self.awake.iter() {
                let slot = slot as usize;
                let (x, u) = (&mut self.offset[slot], &mut self.step_velocity[slot]);
                for k in 0..D {
                    S::advance(&gains, &mut x[k], &mut u[k]);
                }
                if (0..D).all(|k| band.contains(x[k], u[k])) {
                    *x = [S::STATE_ZERO; D];
                    *u = [S::STATE_ZERO; D];
                    let _ = self.settled.push(slot as u16);
                }
            }
        }
        // The awake list changes only when something settled: a step in which nothing
        // did pays nothing for the bookkeeping.
        if !self.settled.is_empty() {
            for &slot in self.settled.iter() {
                self.is_awake[slot as usize] = false;
            }
            let is_awake = &self.is_awake;
            self.awake.retain(|&s| is_awake[s as usize]);
        }
        BatchMotion {
            moving: self.awake.len(),
            settled: self.settled.len(),
        }
    }

    /// Advances every awake value by one time step and nothing else: no rest test. The
    /// cheapest step; values advanced this way stay awake.
    ///
    /// ```
    /// use stiffspring::{SpringBatch, Tuning};
    /// let mut b = SpringBatch::<f32, 1, 2>::new(&Tuning::from_coefficients(0.5, 0.5, 0.01)?)?;
    /// let i = b.push([0.0])?;
    /// b.set_target(i, [1.0]);
    /// b.advance();
    /// assert_eq!(b.position(i), Some([0.5]));
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn advance(&mut self) {
        self.settled.clear();
        self.advance_awake();
    }

    fn advance_awake(&mut self) {
        if T > 1 {
            for &slot in self.awake.iter() {
                let slot = slot as usize;
                let gains = self.tuned(slot).gains;
                for k in 0..D {
                    S::advance(
                        &gains,
                        &mut self.offset[slot][k],
                        &mut self.step_velocity[slot][k],
                    );
                }
            }
            return;
        }
        let gains = self.tunings[0].gains;
        if self.awake.len() == self.len {
            let used = self.used;
            for (x, u) in self.offset[..used]
                .iter_mut()
                .zip(self.step_velocity[..used].iter_mut())
            {
                for k in 0..D {
                    S::advance(&gains, &mut x[k], &mut u[k]);
                }
            }
        } else {
            for &slot in self.awake.iter() {
                let slot = slot as usize;
                for k in 0..D {
                    S::advance(
                        &gains,
                        &mut self.offset[slot][k],
                        &mut self.step_velocity[slot][k],
                    );
                }
            }
        }
    }

    /// The rest-testing step of a batch with several tunings: each awake value with its
    /// own tuning's gains and rest band.
    fn step_each_tuned(&mut self) {
        for &slot in self.awake.iter() {
            let slot = slot as usize;
            let BatchTuning { gains, band, .. } = *self.tuned(slot);
            let (x, u) = (&mut self.offset[slot], &mut self.step_velocity[slot]);
            for k in 0..D {
                S::advance(&gains, &mut x[k], &mut u[k]);
            }
            if (0..D).all(|k| band.contains(x[k], u[k])) {
                *x = [S::STATE_ZERO; D];
                *u = [S::STATE_ZERO; D];
                let _ = self.settled.push(slot as u16);
            }
        }
    }

    /// The values that came to rest in the last [`SpringBatch::step`].
    ///
    /// ```
    /// use stiffspring::{SpringBatch, Tuning};
    /// let b = SpringBatch::<f32, 1, 2>::new(&Tuning::rigid(0.01)?)?;
    /// assert_eq!(b.just_settled().count(), 0);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn just_settled(&self) -> impl Iterator<Item = BatchIndex> + '_ {
        self.settled.iter().map(|&s| self.index_of(s as usize))
    }

    /// The awake values and their positions: what a redraw of the moving parts needs.
    ///
    /// ```
    /// use stiffspring::{SpringBatch, Tuning};
    /// let mut b = SpringBatch::<f32, 1, 4>::new(&Tuning::rigid(0.01)?)?;
    /// let (i, _j) = (b.push([0.0])?, b.push([1.0])?);
    /// b.set_target(i, [2.0]);
    /// assert_eq!(b.moving().map(|(k, _)| k).collect::<Vec<_>>(), [i]);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn moving(&self) -> impl Iterator<Item = (BatchIndex, [S; D])> + '_ {
        self.awake.iter().map(|&s| {
            let s = s as usize;
            (self.index_of(s), self.position_of(s))
        })
    }
}
