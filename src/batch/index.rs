//! How a batch names its values and reports a step.

/// A value of a [`SpringBatch`](super::SpringBatch): a slot and the generation of the value in it, so that an
/// index of a removed value never names the value that took its slot.
///
/// The generation is 16 bits: an index kept across 65,536 removals from its slot names
/// the slot's value again. An index is one `u32` ([`BatchIndex::to_bits`]), so that a
/// caller can keep it where only an integer fits, a C handle or a UI widget's tag, and get
/// it back with [`BatchIndex::from_bits`].
///
/// ```
/// use stiffspring::{SpringBatch, Tuning};
///
/// let mut batch = SpringBatch::<f32, 1, 4>::new(&Tuning::rigid(0.01)?)?;
/// let a = batch.push([1.0])?;
/// batch.remove(a);
/// let b = batch.push([2.0])?;
/// assert_eq!(a.slot(), b.slot()); // the slot is reused...
/// assert_ne!(a, b); // ...the index is not
/// assert_eq!(batch.position(a), None);
/// assert_eq!(batch.position(b), Some([2.0]));
/// # Ok::<(), stiffspring::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct BatchIndex {
    pub(super) slot: u16,
    pub(super) generation: u16,
}

impl BatchIndex {
    /// The slot, for arrays parallel to the batch (`0..N`).
    ///
    /// ```
    /// use stiffspring::{SpringBatch, Tuning};
    /// let mut batch = SpringBatch::<f32, 1, 4>::new(&Tuning::rigid(0.01)?)?;
    /// assert_eq!(batch.push([0.0])?.slot(), 0);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub const fn slot(self) -> usize {
        self.slot as usize
    }

    /// The index as one integer: the slot in the low 16 bits, the generation in the high 16.
    ///
    /// ```
    /// use stiffspring::{BatchIndex, SpringBatch, Tuning};
    /// let mut batch = SpringBatch::<f32, 1, 4>::new(&Tuning::rigid(0.01)?)?;
    /// let a = batch.push([0.0])?;
    /// batch.remove(a);
    /// let b = batch.push([1.0])?;
    /// assert_eq!(b.to_bits(), 1 << 16); // slot 0, its second value
    /// assert_eq!(BatchIndex::from_bits(b.to_bits()), b);
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub const fn to_bits(self) -> u32 {
        (self.generation as u32) << 16 | self.slot as u32
    }

    /// The index whose [`BatchIndex::to_bits`] is `bits`. Every `u32` is an index; one that
    /// no batch gave names no value, and the batch treats it as stale (as
    /// [`SpringBatch::contains`](super::SpringBatch::contains) tells).
    ///
    /// ```
    /// use stiffspring::{BatchIndex, SpringBatch, Tuning};
    /// let mut batch = SpringBatch::<f32, 1, 4>::new(&Tuning::rigid(0.01)?)?;
    /// let a = batch.push([2.0])?;
    /// assert_eq!(batch.position(BatchIndex::from_bits(a.to_bits())), Some([2.0]));
    /// assert!(!batch.contains(BatchIndex::from_bits(u32::MAX)));
    /// # Ok::<(), stiffspring::Error>(())
    /// ```
    pub const fn from_bits(bits: u32) -> BatchIndex {
        BatchIndex {
            slot: bits as u16,
            generation: (bits >> 16) as u16,
        }
    }
}

/// What one [`SpringBatch::step`](super::SpringBatch::step) did.
///
/// ```
/// use stiffspring::{BatchMotion, SpringBatch, Tuning};
///
/// let mut batch = SpringBatch::<f32, 1, 8>::new(&Tuning::from_coefficients(0.5, 1.0, 0.01)?)?;
/// let i = batch.push([0.0])?;
/// batch.set_target(i, [1.0]);
/// assert_eq!(batch.step(), BatchMotion { moving: 1, settled: 0 });
/// while batch.step().settled == 0 {}
/// assert_eq!(batch.just_settled().collect::<Vec<_>>(), [i]);
/// # Ok::<(), stiffspring::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[must_use = "a step reports what to redraw; `let _ =` discards it"]
pub struct BatchMotion {
    /// Values that moved and are still moving.
    pub moving: usize,
    /// Values that came to rest in this step ([`SpringBatch::just_settled`](super::SpringBatch::just_settled) names them).
    pub settled: usize,
}

impl BatchMotion {
    /// True when any value moved in this step.
    ///
    /// ```
    /// assert!(!stiffspring::BatchMotion::default().any());
    /// ```
    pub const fn any(&self) -> bool {
        self.moving + self.settled > 0
    }
}
