//! A batch of values sharing a tuning (`SpringBatch<S, 1, STIFFSPRING_BATCH_CAPACITY>`), in
//! `f32` and Q16.16: one loop steps them all.
//!
//! A value of the batch is named by a `uint32_t` index: its slot in the low 16 bits and, in
//! the high 16, a count of the values that slot held before, so that the index of a removed
//! value never names the value that took its slot (it is `STALE_INDEX`, as the Rust API's
//! `BatchIndex`). It is the Rust `BatchIndex` itself, as `BatchIndex::to_bits` gives it.

use crate::error::{StiffspringError, code};
use crate::handle::{self, Tag};
use crate::q16;
use crate::tuning::{self, StiffspringTuning};
use core::mem::MaybeUninit;
use stiffspring::{BatchIndex, I16F16, Scalar, SpringBatch};

/// How many values a batch holds.
pub const STIFFSPRING_BATCH_CAPACITY: usize = 16;

/// 64-bit words of a [`StiffspringBatchF32`].
pub const STIFFSPRING_BATCH_F32_WORDS: usize = 81;
/// Bytes of a [`StiffspringBatchF32`], for a buffer of one's own.
pub const STIFFSPRING_BATCH_F32_SIZE: usize = STIFFSPRING_BATCH_F32_WORDS * 8;
/// 64-bit words of a [`StiffspringBatchQ16`].
pub const STIFFSPRING_BATCH_Q16_WORDS: usize = 109;
/// Bytes of a [`StiffspringBatchQ16`].
pub const STIFFSPRING_BATCH_Q16_SIZE: usize = STIFFSPRING_BATCH_Q16_WORDS * 8;

const N: usize = STIFFSPRING_BATCH_CAPACITY;

const _: () = assert!(handle::fits::<Batch<f32>>(STIFFSPRING_BATCH_F32_SIZE));
const _: () = assert!(handle::fits::<Batch<I16F16>>(STIFFSPRING_BATCH_Q16_SIZE));

const TAG_F32: Tag = Tag::new(4);
const TAG_Q16: Tag = Tag::new(5);

/// Storage for an `f32` batch; `stiffspring_batch_f32_init` fills it.
///
/// ```c
/// static StiffspringBatchF32 rows;
/// ```
#[repr(C)]
pub struct StiffspringBatchF32 {
    opaque: [MaybeUninit<u64>; STIFFSPRING_BATCH_F32_WORDS],
}

/// Storage for a Q16.16 batch; `stiffspring_batch_q16_init` fills it.
///
/// ```c
/// static StiffspringBatchQ16 rows;
/// ```
#[repr(C)]
pub struct StiffspringBatchQ16 {
    opaque: [MaybeUninit<u64>; STIFFSPRING_BATCH_Q16_WORDS],
}

/// What one batch step did.
///
/// ```c
/// StiffspringBatchMotion m;
/// stiffspring_batch_f32_step(&rows, &m);
/// if (m.moving + m.settled > 0) redraw();
/// ```
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct StiffspringBatchMotion {
    /// Values that moved and are still moving.
    pub moving: u32,
    /// Values that came to rest in this step.
    pub settled: u32,
}

/// The batch, built in place ([`init`]).
type Batch<S> = SpringBatch<S, 1, N>;

/// The Rust index a C index names, if it names a live value of `batch`: for the setters,
/// which ignore a stale index (the getters and `try_set_target` report one themselves).
fn live<S: Scalar>(batch: &Batch<S>, c: u32) -> Result<BatchIndex, StiffspringError> {
    let index = BatchIndex::from_bits(c);
    if batch.contains(index) {
        Ok(index)
    } else {
        Err(StiffspringError::StaleIndex)
    }
}

/// Removes the value a C index names; its position.
fn remove<S: Scalar>(batch: &mut Batch<S>, c: u32) -> Result<S, StiffspringError> {
    let [position] = batch
        .remove(BatchIndex::from_bits(c))
        .ok_or(StiffspringError::StaleIndex)?;
    Ok(position)
}

/// Builds the batch in `storage` itself (`SpringBatch::new_in`): returned and moved there,
/// it cost a `memcpy` of the whole batch, and the `memcpy`.
///
/// # Safety
///
/// As [`handle::init_in_place`] and [`handle::get_ref`].
unsafe fn init<S: Scalar>(
    storage: *mut u8,
    size: usize,
    tag: Tag,
    tuning: *const StiffspringTuning,
) -> StiffspringError {
    // SAFETY: the caller's contract; `SpringBatch::new_in` writes its slot only when it
    // returns `Ok` (its documentation), as `init_in_place` asks of `make`.
    code(unsafe {
        handle::init_in_place(storage, size, tag, |slot| {
            let tuning = tuning::read(tuning)?;
            Ok(SpringBatch::<S, 1, N>::new_in(slot, tuning)?)
        })
    })
}

/// Runs `f` on the live batch in `storage`.
///
/// # Safety
///
/// As [`handle::get`].
unsafe fn with<S: Scalar>(
    storage: *mut u8,
    tag: Tag,
    f: impl FnOnce(&mut Batch<S>) -> Result<(), StiffspringError>,
) -> StiffspringError {
    // SAFETY: the caller's contract.
    code(unsafe { handle::get::<Batch<S>>(storage, tag) }.and_then(f))
}

/// Runs `f` on the live batch in `storage`, shared.
///
/// # Safety
///
/// As [`handle::get_ref`].
unsafe fn with_ref<S: Scalar>(
    storage: *const u8,
    tag: Tag,
    f: impl FnOnce(&Batch<S>) -> Result<(), StiffspringError>,
) -> StiffspringError {
    // SAFETY: the caller's contract.
    code(unsafe { handle::get_ref::<Batch<S>>(storage, tag) }.and_then(f))
}

/// The count of a `usize` the batch reports, as `uint32_t` (at most its capacity).
fn count(n: usize) -> u32 {
    n as u32
}

/// # Safety
///
/// As [`handle::get`], [`handle::write_optional`] and, for each of the `capacity`
/// elements of `settled`, [`handle::write_out`].
unsafe fn step<S: Scalar>(
    storage: *mut u8,
    tag: Tag,
    motion: *mut StiffspringBatchMotion,
) -> StiffspringError {
    // SAFETY: the caller's contract.
    unsafe {
        with::<S>(storage, tag, |b| {
            let m = b.step();
            let m = StiffspringBatchMotion {
                moving: count(m.moving),
                settled: count(m.settled),
            };
            handle::write_optional(motion, m)
        })
    }
}

/// # Safety
///
/// As [`handle::get_ref`]; `indices` is null or valid for writes of `capacity` indices.
unsafe fn just_settled<S: Scalar>(
    storage: *const u8,
    tag: Tag,
    indices: *mut u32,
    capacity: usize,
    written: *mut usize,
) -> StiffspringError {
    // SAFETY: the caller's contract.
    unsafe {
        with_ref::<S>(storage, tag, |b| {
            let mut n = 0;
            for index in b.just_settled() {
                if n < capacity {
                    // `n < capacity`: within the caller's array.
                    handle::write_out(indices.wrapping_add(n), index.to_bits())?;
                    n += 1;
                }
            }
            handle::write_optional(written, n)
        })
    }
}

/// A batch with no values yet, tuned by `tuning` (which sets its time step), written into
/// `storage` of `size` bytes.
///
/// Errors: `UNREPRESENTABLE` when the backend cannot hold the tuning; `NULL_POINTER`,
/// `BUFFER_TOO_SMALL`, `MISALIGNED` for the storage, `NOT_INITIALISED` or `DROPPED` for
/// the tuning. On an error the storage is unchanged.
///
/// ```c
/// StiffspringBatchF32 rows;
/// stiffspring_batch_f32_init(&rows, sizeof rows, &tuning);
/// ```
///
/// # Safety
///
/// `storage` is null or points to `size` bytes the caller owns; `tuning` is null or points
/// to a `StiffspringTuning`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn stiffspring_batch_f32_init(
    storage: *mut StiffspringBatchF32,
    size: usize,
    tuning: *const StiffspringTuning,
) -> StiffspringError {
    // SAFETY: this function's contract.
    unsafe { init::<f32>(storage.cast(), size, TAG_F32, tuning) }
}

/// Ends the batch: later calls on it return `DROPPED` until it is initialised again.
///
/// ```c
/// stiffspring_batch_f32_drop(&rows);
/// ```
///
/// # Safety
///
/// `batch` is null or points to a `StiffspringBatchF32` the caller owns.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn stiffspring_batch_f32_drop(
    batch: *mut StiffspringBatchF32,
) -> StiffspringError {
    // SAFETY: this function's contract.
    code(unsafe { handle::drop::<Batch<f32>>(batch.cast(), TAG_F32) })
}

/// Adds a value at rest at `position`; `index` receives its name.
///
/// Errors: `CAPACITY_FULL`, `NOT_FINITE` or `OUT_OF_RANGE` for the position; the batch is
/// then unchanged.
///
/// ```c
/// uint32_t row;
/// stiffspring_batch_f32_push(&rows, 0.0f, &row);
/// ```
///
/// # Safety
///
/// As [`stiffspring_batch_f32_drop`]; `index` is null or valid for a write.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn stiffspring_batch_f32_push(
    batch: *mut StiffspringBatchF32,
    position: f32,
    index: *mut u32,
) -> StiffspringError {
    if index.is_null() {
        return StiffspringError::NullPointer;
    }
    // SAFETY: this function's contract.
    unsafe {
        with::<f32>(batch.cast(), TAG_F32, |b| {
            handle::write_out(index, b.push([position])?.to_bits())
        })
    }
}

/// Removes the value `index` names; `position` (optional) receives where it was.
///
/// ```c
/// stiffspring_batch_f32_remove(&rows, row, NULL);
/// ```
///
/// # Safety
///
/// As [`stiffspring_batch_f32_drop`]; `position` is null or valid for a write.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn stiffspring_batch_f32_remove(
    batch: *mut StiffspringBatchF32,
    index: u32,
    position: *mut f32,
) -> StiffspringError {
    // SAFETY: this function's contract.
    unsafe {
        with::<f32>(batch.cast(), TAG_F32, |b| {
            handle::write_optional(position, remove(b, index)?)
        })
    }
}

/// Springs the value `index` names toward `target`. Cannot fail on the target (NaN is
/// ignored, out-of-range input saturates); `STALE_INDEX` for an index that names no value.
///
/// ```c
/// stiffspring_batch_f32_set_target(&rows, row, 24.0f);
/// ```
///
/// # Safety
///
/// As [`stiffspring_batch_f32_drop`].
#[unsafe(no_mangle)]
pub unsafe extern "C" fn stiffspring_batch_f32_set_target(
    batch: *mut StiffspringBatchF32,
    index: u32,
    target: f32,
) -> StiffspringError {
    // SAFETY: this function's contract.
    unsafe {
        with::<f32>(batch.cast(), TAG_F32, |b| {
            let i = live(b, index)?;
            b.set_target(i, [target]);
            Ok(())
        })
    }
}

/// [`stiffspring_batch_f32_set_target`], reporting instead of saturating: `NOT_FINITE`,
/// `OUT_OF_RANGE` or `UNREPRESENTABLE`, and the value is unchanged.
///
/// ```c
/// stiffspring_batch_f32_try_set_target(&rows, row, 24.0f);
/// ```
///
/// # Safety
///
/// As [`stiffspring_batch_f32_drop`].
#[unsafe(no_mangle)]
pub unsafe extern "C" fn stiffspring_batch_f32_try_set_target(
    batch: *mut StiffspringBatchF32,
    index: u32,
    target: f32,
) -> StiffspringError {
    // SAFETY: this function's contract.
    unsafe {
        with::<f32>(batch.cast(), TAG_F32, |b| {
            Ok(b.try_set_target(BatchIndex::from_bits(index), [target])?)
        })
    }
}

/// Moves the value `index` names to `position` at once (its target stays), keeping its
/// velocity. Cannot fail on the position; `STALE_INDEX` for an index that names no value.
///
/// ```c
/// stiffspring_batch_f32_set_position(&rows, row, finger_y);
/// ```
///
/// # Safety
///
/// As [`stiffspring_batch_f32_drop`].
#[unsafe(no_mangle)]
pub unsafe extern "C" fn stiffspring_batch_f32_set_position(
    batch: *mut StiffspringBatchF32,
    index: u32,
    position: f32,
) -> StiffspringError {
    // SAFETY: this function's contract.
    unsafe {
        with::<f32>(batch.cast(), TAG_F32, |b| {
            let i = live(b, index)?;
            b.set_position(i, [position]);
            Ok(())
        })
    }
}

/// Gives the value `index` names a velocity (units per second). Cannot fail on the
/// velocity; `STALE_INDEX` for an index that names no value.
///
/// ```c
/// stiffspring_batch_f32_fling(&rows, row, 600.0f);
/// ```
///
/// # Safety
///
/// As [`stiffspring_batch_f32_drop`].
#[unsafe(no_mangle)]
pub unsafe extern "C" fn stiffspring_batch_f32_fling(
    batch: *mut StiffspringBatchF32,
    index: u32,
    velocity: f32,
) -> StiffspringError {
    // SAFETY: this function's contract.
    unsafe {
        with::<f32>(batch.cast(), TAG_F32, |b| {
            let i = live(b, index)?;
            b.fling(i, [velocity]);
            Ok(())
        })
    }
}

/// One time step of every value; `motion` (optional) receives what it did.
///
/// ```c
/// StiffspringBatchMotion m;
/// stiffspring_batch_f32_step(&rows, &m);
/// ```
///
/// # Safety
///
/// As [`stiffspring_batch_f32_drop`]; `motion` is null or valid for a write.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn stiffspring_batch_f32_step(
    batch: *mut StiffspringBatchF32,
    motion: *mut StiffspringBatchMotion,
) -> StiffspringError {
    // SAFETY: this function's contract.
    unsafe { step::<f32>(batch.cast(), TAG_F32, motion) }
}

/// The indices of the values that came to rest in the last step: up to `capacity` of them
/// into `indices`, and how many into `written` (optional).
///
/// ```c
/// uint32_t done[STIFFSPRING_BATCH_CAPACITY];
/// size_t n;
/// stiffspring_batch_f32_just_settled(&rows, done, STIFFSPRING_BATCH_CAPACITY, &n);
/// ```
///
/// # Safety
///
/// As [`stiffspring_batch_f32_drop`]; `indices` is null or valid for writes of `capacity`
/// indices, `written` null or valid for a write.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn stiffspring_batch_f32_just_settled(
    batch: *const StiffspringBatchF32,
    indices: *mut u32,
    capacity: usize,
    written: *mut usize,
) -> StiffspringError {
    // SAFETY: this function's contract.
    unsafe { just_settled::<f32>(batch.cast(), TAG_F32, indices, capacity, written) }
}

/// The position of the value `index` names, into `out`.
///
/// ```c
/// float y;
/// stiffspring_batch_f32_position(&rows, row, &y);
/// ```
///
/// # Safety
///
/// As [`stiffspring_batch_f32_drop`]; `out` is null or valid for a write.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn stiffspring_batch_f32_position(
    batch: *const StiffspringBatchF32,
    index: u32,
    out: *mut f32,
) -> StiffspringError {
    // SAFETY: this function's contract.
    unsafe {
        with_ref::<f32>(batch.cast(), TAG_F32, |b| {
            let p = b
                .position(BatchIndex::from_bits(index))
                .ok_or(StiffspringError::StaleIndex)?;
            handle::write_out(out, p[0])
        })
    }
}

/// Whether the value `index` names rests on its target, into `out`.
///
/// ```c
/// bool resting;
/// stiffspring_batch_f32_is_at_rest(&rows, row, &resting);
/// ```
///
/// # Safety
///
/// As [`stiffspring_batch_f32_position`].
#[unsafe(no_mangle)]
pub unsafe extern "C" fn stiffspring_batch_f32_is_at_rest(
    batch: *const StiffspringBatchF32,
    index: u32,
    out: *mut bool,
) -> StiffspringError {
    // SAFETY: this function's contract.
    unsafe {
        with_ref::<f32>(batch.cast(), TAG_F32, |b| {
            let r = b
                .is_at_rest(BatchIndex::from_bits(index))
                .ok_or(StiffspringError::StaleIndex)?;
            handle::write_out(out, r)
        })
    }
}

/// How many values the batch holds, and how many of them move, into `len` and `awake`
/// (each optional).
///
/// ```c
/// uint32_t len, awake;
/// stiffspring_batch_f32_counts(&rows, &len, &awake);
/// ```
///
/// # Safety
///
/// As [`stiffspring_batch_f32_drop`]; `len` and `awake` are null or valid for a write.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn stiffspring_batch_f32_counts(
    batch: *const StiffspringBatchF32,
    len: *mut u32,
    awake: *mut u32,
) -> StiffspringError {
    // SAFETY: this function's contract.
    unsafe {
        with_ref::<f32>(batch.cast(), TAG_F32, |b| {
            handle::write_optional(len, count(b.len()))?;
            handle::write_optional(awake, count(b.awake()))
        })
    }
}

/// A Q16.16 batch with no values yet, tuned by `tuning` (which sets its time step), written into
/// `storage` of `size` bytes.
///
/// Errors: `UNREPRESENTABLE` when the backend cannot hold the tuning; `NULL_POINTER`,
/// `BUFFER_TOO_SMALL`, `MISALIGNED` for the storage, `NOT_INITIALISED` or `DROPPED` for
/// the tuning. On an error the storage is unchanged.
///
/// ```c
/// StiffspringBatchQ16 rows;
/// stiffspring_batch_q16_init(&rows, sizeof rows, &tuning);
/// ```
///
/// # Safety
///
/// `storage` is null or points to `size` bytes the caller owns; `tuning` is null or points
/// to a `StiffspringTuning`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn stiffspring_batch_q16_init(
    storage: *mut StiffspringBatchQ16,
    size: usize,
    tuning: *const StiffspringTuning,
) -> StiffspringError {
    // SAFETY: this function's contract.
    unsafe { init::<I16F16>(storage.cast(), size, TAG_Q16, tuning) }
}

/// Ends the batch: later calls on it return `DROPPED` until it is initialised again.
///
/// ```c
/// stiffspring_batch_q16_drop(&rows);
/// ```
///
/// # Safety
///
/// `batch` is null or points to a `StiffspringBatchQ16` the caller owns.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn stiffspring_batch_q16_drop(
    batch: *mut StiffspringBatchQ16,
) -> StiffspringError {
    // SAFETY: this function's contract.
    code(unsafe { handle::drop::<Batch<I16F16>>(batch.cast(), TAG_Q16) })
}

/// Adds a value at rest at `position`; `index` receives its name.
///
/// Errors: `CAPACITY_FULL`, `NOT_FINITE` or `OUT_OF_RANGE` for the position; the batch is
/// then unchanged.
///
/// ```c
/// uint32_t row;
/// stiffspring_batch_q16_push(&rows, 0, &row);
/// ```
///
/// # Safety
///
/// As [`stiffspring_batch_q16_drop`]; `index` is null or valid for a write.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn stiffspring_batch_q16_push(
    batch: *mut StiffspringBatchQ16,
    position: i32,
    index: *mut u32,
) -> StiffspringError {
    if index.is_null() {
        return StiffspringError::NullPointer;
    }
    // SAFETY: this function's contract.
    unsafe {
        with::<I16F16>(batch.cast(), TAG_Q16, |b| {
            handle::write_out(index, b.push([q16::from_bits(position)])?.to_bits())
        })
    }
}

/// Removes the value `index` names; `position` (optional) receives where it was.
///
/// ```c
/// stiffspring_batch_q16_remove(&rows, row, NULL);
/// ```
///
/// # Safety
///
/// As [`stiffspring_batch_q16_drop`]; `position` is null or valid for a write.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn stiffspring_batch_q16_remove(
    batch: *mut StiffspringBatchQ16,
    index: u32,
    position: *mut i32,
) -> StiffspringError {
    // SAFETY: this function's contract.
    unsafe {
        with::<I16F16>(batch.cast(), TAG_Q16, |b| {
            handle::write_optional(position, q16::to_bits(remove(b, index)?))
        })
    }
}

/// Springs the value `index` names toward `target`. Cannot fail on the target (NaN is
/// ignored, out-of-range input saturates); `STALE_INDEX` for an index that names no value.
///
/// ```c
/// stiffspring_batch_q16_set_target(&rows, row, 24 * STIFFSPRING_Q16_ONE);
/// ```
///
/// # Safety
///
/// As [`stiffspring_batch_q16_drop`].
#[unsafe(no_mangle)]
pub unsafe extern "C" fn stiffspring_batch_q16_set_target(
    batch: *mut StiffspringBatchQ16,
    index: u32,
    target: i32,
) -> StiffspringError {
    // SAFETY: this function's contract.
    unsafe {
        with::<I16F16>(batch.cast(), TAG_Q16, |b| {
            let i = live(b, index)?;
            b.set_target(i, [q16::from_bits(target)]);
            Ok(())
        })
    }
}

/// [`stiffspring_batch_q16_set_target`], reporting instead of saturating: `NOT_FINITE`,
/// `OUT_OF_RANGE` or `UNREPRESENTABLE`, and the value is unchanged.
///
/// ```c
/// stiffspring_batch_q16_try_set_target(&rows, row, 24 * STIFFSPRING_Q16_ONE);
/// ```
///
/// # Safety
///
/// As [`stiffspring_batch_q16_drop`].
#[unsafe(no_mangle)]
pub unsafe extern "C" fn stiffspring_batch_q16_try_set_target(
    batch: *mut StiffspringBatchQ16,
    index: u32,
    target: i32,
) -> StiffspringError {
    // SAFETY: this function's contract.
    unsafe {
        with::<I16F16>(batch.cast(), TAG_Q16, |b| {
            Ok(b.try_set_target(BatchIndex::from_bits(index), [q16::from_bits(target)])?)
        })
    }
}

/// Moves the value `index` names to `position` at once (its target stays), keeping its
/// velocity. Cannot fail on the position; `STALE_INDEX` for an index that names no value.
///
/// ```c
/// stiffspring_batch_q16_set_position(&rows, row, finger_y);
/// ```
///
/// # Safety
///
/// As [`stiffspring_batch_q16_drop`].
#[unsafe(no_mangle)]
pub unsafe extern "C" fn stiffspring_batch_q16_set_position(
    batch: *mut StiffspringBatchQ16,
    index: u32,
    position: i32,
) -> StiffspringError {
    // SAFETY: this function's contract.
    unsafe {
        with::<I16F16>(batch.cast(), TAG_Q16, |b| {
            let i = live(b, index)?;
            b.set_position(i, [q16::from_bits(position)]);
            Ok(())
        })
    }
}

/// Gives the value `index` names a velocity (units per second). Cannot fail on the
/// velocity; `STALE_INDEX` for an index that names no value.
///
/// ```c
/// stiffspring_batch_q16_fling(&rows, row, 600 * STIFFSPRING_Q16_ONE);
/// ```
///
/// # Safety
///
/// As [`stiffspring_batch_q16_drop`].
#[unsafe(no_mangle)]
pub unsafe extern "C" fn stiffspring_batch_q16_fling(
    batch: *mut StiffspringBatchQ16,
    index: u32,
    velocity: i32,
) -> StiffspringError {
    // SAFETY: this function's contract.
    unsafe {
        with::<I16F16>(batch.cast(), TAG_Q16, |b| {
            let i = live(b, index)?;
            b.fling(i, [q16::from_bits(velocity)]);
            Ok(())
        })
    }
}

/// One time step of every value; `motion` (optional) receives what it did.
///
/// ```c
/// StiffspringBatchMotion m;
/// stiffspring_batch_q16_step(&rows, &m);
/// ```
///
/// # Safety
///
/// As [`stiffspring_batch_q16_drop`]; `motion` is null or valid for a write.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn stiffspring_batch_q16_step(
    batch: *mut StiffspringBatchQ16,
    motion: *mut StiffspringBatchMotion,
) -> StiffspringError {
    // SAFETY: this function's contract.
    unsafe { step::<I16F16>(batch.cast(), TAG_Q16, motion) }
}

/// The indices of the values that came to rest in the last step: up to `capacity` of them
/// into `indices`, and how many into `written` (optional).
///
/// ```c
/// uint32_t done[STIFFSPRING_BATCH_CAPACITY];
/// size_t n;
/// stiffspring_batch_q16_just_settled(&rows, done, STIFFSPRING_BATCH_CAPACITY, &n);
/// ```
///
/// # Safety
///
/// As [`stiffspring_batch_q16_drop`]; `indices` is null or valid for writes of `capacity`
/// indices, `written` null or valid for a write.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn stiffspring_batch_q16_just_settled(
    batch: *const StiffspringBatchQ16,
    indices: *mut u32,
    capacity: usize,
    written: *mut usize,
) -> StiffspringError {
    // SAFETY: this function's contract.
    unsafe { just_settled::<I16F16>(batch.cast(), TAG_Q16, indices, capacity, written) }
}

/// The position of the value `index` names, into `out`.
///
/// ```c
/// int32_t y;
/// stiffspring_batch_q16_position(&rows, row, &y);
/// ```
///
/// # Safety
///
/// As [`stiffspring_batch_q16_drop`]; `out` is null or valid for a write.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn stiffspring_batch_q16_position(
    batch: *const StiffspringBatchQ16,
    index: u32,
    out: *mut i32,
) -> StiffspringError {
    // SAFETY: this function's contract.
    unsafe {
        with_ref::<I16F16>(batch.cast(), TAG_Q16, |b| {
            let p = b
                .position(BatchIndex::from_bits(index))
                .ok_or(StiffspringError::StaleIndex)?;
            handle::write_out(out, q16::to_bits(p[0]))
        })
    }
}

/// Whether the value `index` names rests on its target, into `out`.
///
/// ```c
/// bool resting;
/// stiffspring_batch_q16_is_at_rest(&rows, row, &resting);
/// ```
///
/// # Safety
///
/// As [`stiffspring_batch_q16_position`].
#[unsafe(no_mangle)]
pub unsafe extern "C" fn stiffspring_batch_q16_is_at_rest(
    batch: *const StiffspringBatchQ16,
    index: u32,
    out: *mut bool,
) -> StiffspringError {
    // SAFETY: this function's contract.
    unsafe {
        with_ref::<I16F16>(batch.cast(), TAG_Q16, |b| {
            let r = b
                .is_at_rest(BatchIndex::from_bits(index))
                .ok_or(StiffspringError::StaleIndex)?;
            handle::write_out(out, r)
        })
    }
}

/// How many values the batch holds, and how many of them move, into `len` and `awake`
/// (each optional).
///
/// ```c
/// uint32_t len, awake;
/// stiffspring_batch_q16_counts(&rows, &len, &awake);
/// ```
///
/// # Safety
///
/// As [`stiffspring_batch_q16_drop`]; `len` and `awake` are null or valid for a write.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn stiffspring_batch_q16_counts(
    batch: *const StiffspringBatchQ16,
    len: *mut u32,
    awake: *mut u32,
) -> StiffspringError {
    // SAFETY: this function's contract.
    unsafe {
        with_ref::<I16F16>(batch.cast(), TAG_Q16, |b| {
            handle::write_optional(len, count(b.len()))?;
            handle::write_optional(awake, count(b.awake()))
        })
    }
}

/// The storage words a batch of backend `S` needs on this target.
#[cfg(test)]
pub(crate) fn words<S: Scalar>() -> usize {
    core::mem::size_of::<handle::Slot<Batch<S>>>().div_ceil(8)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::tuning::stiffspring_tuning_from_coefficients;
    use core::mem::size_of;
    use core::ptr::null_mut;

    fn tuning() -> StiffspringTuning {
        let mut t = StiffspringTuning::zeroed_for_tests();
        // SAFETY: our storage.
        let e = unsafe {
            stiffspring_tuning_from_coefficients(
                &mut t,
                size_of::<StiffspringTuning>(),
                0.1,
                0.4,
                0.01,
            )
        };
        assert_eq!(e, StiffspringError::Ok);
        t
    }

    #[test]
    fn indices_name_values_until_they_are_removed() {
        let t = tuning();
        let mut b = StiffspringBatchF32 {
            opaque: [handle::ZERO; STIFFSPRING_BATCH_F32_WORDS],
        };
        let size = size_of::<StiffspringBatchF32>();
        let (mut i, mut j, mut x) = (0u32, 0u32, 0.0f32);
        // SAFETY: our storage and out-pointers.
        unsafe {
            assert_eq!(
                stiffspring_batch_f32_init(&mut b, size, &t),
                StiffspringError::Ok
            );
            assert_eq!(
                stiffspring_batch_f32_push(&mut b, 1.0, &mut i),
                StiffspringError::Ok
            );
            assert_eq!(
                stiffspring_batch_f32_push(&mut b, f32::NAN, &mut j),
                StiffspringError::NotFinite
            );
            assert_eq!(
                stiffspring_batch_f32_push(&mut b, 2.0, null_mut()),
                StiffspringError::NullPointer
            );
            assert_eq!(
                stiffspring_batch_f32_remove(&mut b, i, &mut x),
                StiffspringError::Ok
            );
            assert_eq!(x, 1.0);
            assert_eq!(
                stiffspring_batch_f32_push(&mut b, 2.0, &mut j),
                StiffspringError::Ok
            );
            assert_eq!(i & 0xffff, j & 0xffff, "the slot is reused");
            assert_ne!(i, j, "the index is not");
            assert_eq!(
                stiffspring_batch_f32_set_target(&mut b, i, 5.0),
                StiffspringError::StaleIndex
            );
            assert_eq!(
                stiffspring_batch_f32_position(&b, i, &mut x),
                StiffspringError::StaleIndex
            );
            assert_eq!(
                stiffspring_batch_f32_remove(&mut b, i, null_mut()),
                StiffspringError::StaleIndex
            );
            assert_eq!(
                stiffspring_batch_f32_position(&b, 0xdead_beef, &mut x),
                StiffspringError::StaleIndex
            );
            // The UI path ignores NaN; the try_ twin reports it.
            assert_eq!(
                stiffspring_batch_f32_set_target(&mut b, j, f32::NAN),
                StiffspringError::Ok
            );
            assert_eq!(
                stiffspring_batch_f32_try_set_target(&mut b, j, f32::NAN),
                StiffspringError::NotFinite
            );
            assert_eq!(
                stiffspring_batch_f32_set_target(&mut b, j, 3.0),
                StiffspringError::Ok
            );
            let mut m = StiffspringBatchMotion::default();
            let mut steps = 0;
            while m.settled == 0 {
                assert_eq!(
                    stiffspring_batch_f32_step(&mut b, &mut m),
                    StiffspringError::Ok
                );
                steps += 1;
                assert!(steps < 10_000);
            }
            let (mut done, mut n) = ([0u32; 4], 0usize);
            assert_eq!(
                stiffspring_batch_f32_just_settled(&b, done.as_mut_ptr(), 4, &mut n),
                StiffspringError::Ok
            );
            assert_eq!((n, done[0]), (1, j));
            assert_eq!(
                stiffspring_batch_f32_just_settled(&b, null_mut(), 0, &mut n),
                StiffspringError::Ok
            );
            assert_eq!(n, 0, "no room: nothing written");
            stiffspring_batch_f32_position(&b, j, &mut x);
            assert_eq!(x, 3.0);
            let (mut len, mut awake) = (9, 9);
            stiffspring_batch_f32_counts(&b, &mut len, &mut awake);
            assert_eq!((len, awake), (1, 0));
            assert_eq!(stiffspring_batch_f32_drop(&mut b), StiffspringError::Ok);
            assert_eq!(
                stiffspring_batch_f32_step(&mut b, null_mut()),
                StiffspringError::Dropped
            );
        }
    }

    #[test]
    fn a_full_batch_refuses_a_push() {
        let t = tuning();
        let mut b = StiffspringBatchQ16 {
            opaque: [handle::ZERO; STIFFSPRING_BATCH_Q16_WORDS],
        };
        let mut i = 0;
        // SAFETY: our storage and out-pointers.
        unsafe {
            assert_eq!(
                stiffspring_batch_q16_init(&mut b, size_of::<StiffspringBatchQ16>(), &t),
                StiffspringError::Ok
            );
            for k in 0..STIFFSPRING_BATCH_CAPACITY as i32 {
                assert_eq!(
                    stiffspring_batch_q16_push(&mut b, k << 16, &mut i),
                    StiffspringError::Ok
                );
            }
            assert_eq!(
                stiffspring_batch_q16_push(&mut b, 0, &mut i),
                StiffspringError::CapacityFull
            );
            let mut x = 0;
            assert_eq!(
                stiffspring_batch_q16_position(&b, i, &mut x),
                StiffspringError::Ok
            );
            assert_eq!(x, (STIFFSPRING_BATCH_CAPACITY as i32 - 1) << 16);
        }
    }
}
