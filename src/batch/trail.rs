//! A trail: values that follow one another, each chasing where the one before it is
//! (react-spring's `useTrail`).

use super::{BatchIndex, BatchMotion, SpringBatch};
use crate::scalar::Scalar;
use heapless::Vec;

/// A chain of a [`SpringBatch`]'s values: the first is the leader, which the user moves
/// ([`Trail::set_target`]); on every [`Trail::step`] each follower's target becomes its
/// predecessor's position plus the spacing the two had when the trail was made, so that
/// the chain ripples after the leader and comes to rest in its original shape around the
/// leader's target.
///
/// Each follower is one step and one spring behind the value before it: a follower sees
/// its predecessor's position from before the step. The batch is untouched otherwise.
///
/// ```
/// use stiffspring::{SpringBatch, Trail, Tuning};
///
/// let tuning = Tuning::from_frequency(4.0, 1.0, 1.0 / 60.0)?;
/// let mut dots = SpringBatch::<f32, 2, 5>::new(&tuning)?;
/// let ids: Vec<_> = (0..5).map(|i| dots.push([i as f32 * 10.0, 0.0])).collect::<Result<_, _>>()?;
/// let mut trail = Trail::new(&dots, ids.iter().copied());
/// trail.set_target(&mut dots, [100.0, 50.0]);
/// while trail.step(&mut dots).any() {}
/// // At rest in the original shape, around the leader's target.
/// assert_eq!(dots.position(ids[4]), Some([140.0, 50.0]));
/// # Ok::<(), stiffspring::Error>(())
/// ```
#[derive(Clone, Debug)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Trail<S: Scalar, const D: usize, const N: usize> {
    /// The chain, leader first, and each value's spacing from the one before it.
    chain: Vec<(BatchIndex, [S; D]), N>,
}

impl<S: Scalar, const D: usize, const N: usize> Trail<S, D, N> {
    /// The values of `order` that `batch` holds, leader first, with the spacing each has
    /// from the one before it now (a stale index is left out).
    ///
    /// ```
    /// use stiffspring::{SpringBatch, Trail, Tuning};
    /// let mut b = SpringBatch::<f32, 1, 3>::new(&Tuning::rigid(0.01)?)?;
    /// let (a, c) = (b.push([0.0])?, b.push([5.0])?);
    /// assert_eq!(Trail::new(&b, [a, c]).len(), 2);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn new<const T: usize>(
        batch: &SpringBatch<S, D, N, T>,
        order: impl IntoIterator<Item = BatchIndex>,
    ) -> Self {
        let mut chain: Vec<(BatchIndex, [S; D]), N> = Vec::new();
        let mut before: Option<[S; D]> = None;
        for index in order {
            let Some(position) = batch.position(index) else {
                continue;
            };
            let mut spacing = [S::ZERO; D];
            if let Some(p) = before {
                for k in 0..D {
                    spacing[k] = position[k].sub(p[k]);
                }
            }
            // The chain holds at most N values, as many as the batch.
            if chain.push((index, spacing)).is_err() {
                break;
            }
            before = Some(position);
        }
        Trail { chain }
    }

    /// The values in the chain.
    ///
    /// ```
    /// use stiffspring::{SpringBatch, Trail, Tuning};
    /// let b = SpringBatch::<f32, 1, 3>::new(&Tuning::rigid(0.01)?)?;
    /// assert!(Trail::new(&b, []).is_empty());
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn len(&self) -> usize {
        self.chain.len()
    }

    /// True for a chain of no value.
    ///
    /// ```
    /// use stiffspring::{SpringBatch, Trail, Tuning};
    /// let b = SpringBatch::<f32, 1, 3>::new(&Tuning::rigid(0.01)?)?;
    /// assert_eq!(Trail::new(&b, []).len(), 0);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn is_empty(&self) -> bool {
        self.chain.is_empty()
    }

    /// Moves the leader's target (as [`SpringBatch::set_target`]: NaN ignored, out of
    /// range saturated); the followers take it up on the next steps.
    ///
    /// ```
    /// use stiffspring::{SpringBatch, Trail, Tuning};
    /// let mut b = SpringBatch::<f32, 1, 3>::new(&Tuning::rigid(0.01)?)?;
    /// let (a, c) = (b.push([0.0])?, b.push([5.0])?);
    /// let mut t = Trail::new(&b, [a, c]);
    /// t.set_target(&mut b, [1.0]);
    /// assert_eq!((b.target(a), b.target(c)), (Some([1.0]), Some([5.0])));
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn set_target<const T: usize>(&self, batch: &mut SpringBatch<S, D, N, T>, target: [S; D]) {
        if let Some(&(leader, _)) = self.chain.first() {
            batch.set_target(leader, target);
        }
    }

    /// One frame: each follower's target becomes its predecessor's position plus its
    /// spacing, then the batch steps; returns what the batch reports. A follower whose
    /// target does not change stays asleep ([`SpringBatch::set_target`]).
    ///
    /// ```
    /// use stiffspring::{SpringBatch, Trail, Tuning};
    /// let mut b = SpringBatch::<f32, 1, 3>::new(&Tuning::from_coefficients(0.5, 0.5, 0.01)?)?;
    /// let (a, c) = (b.push([0.0])?, b.push([5.0])?);
    /// let mut t = Trail::new(&b, [a, c]);
    /// t.set_target(&mut b, [1.0]);
    /// let _ = t.step(&mut b); // the leader moves; the follower still sees it at 0
    /// assert_eq!(b.position(c), Some([5.0]));
    /// let _ = t.step(&mut b); // now it follows
    /// assert!(b.position(c).unwrap()[0] > 5.0);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub fn step<const T: usize>(&mut self, batch: &mut SpringBatch<S, D, N, T>) -> BatchMotion {
        let mut before: Option<[S; D]> = None;
        for &(index, spacing) in self.chain.iter() {
            let position = batch.position(index);
            if let Some(p) = before {
                let mut target = p;
                for k in 0..D {
                    target[k] = target[k].add(spacing[k]);
                }
                batch.set_target(index, target);
            }
            // A value removed from the batch breaks the chain there: the next follows the
            // last one still held.
            if position.is_some() {
                before = position;
            }
        }
        batch.step()
    }
}
