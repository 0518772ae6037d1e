//! A value that springs toward a target (`SpringValue<S, 1>`), in `f32` and Q16.16.
//!
//! Every function comes twice, `stiffspring_value_f32_*` on `float` and
//! `stiffspring_value_q16_*` on Q16.16 `int32_t`; both share the generic code below.

use crate::error::{StiffspringError, code};
use crate::handle::{self, Tag};
use crate::q16;
use crate::tuning::{self, StiffspringTuning};
use core::mem::MaybeUninit;
use stiffspring::{I16F16, Motion, RestThreshold, Scalar, SpringValue};

/// 64-bit words of a [`StiffspringValueF32`].
pub const STIFFSPRING_VALUE_F32_WORDS: usize = 12;
/// Bytes of a [`StiffspringValueF32`], for a buffer of one's own (aligned to
/// `STIFFSPRING_STORAGE_ALIGN`).
pub const STIFFSPRING_VALUE_F32_SIZE: usize = STIFFSPRING_VALUE_F32_WORDS * 8;
/// 64-bit words of a [`StiffspringValueQ16`]: its state is Q24.40 in 64 bits, so that it
/// follows the continuous spring to the last bit.
pub const STIFFSPRING_VALUE_Q16_WORDS: usize = 25;
/// Bytes of a [`StiffspringValueQ16`].
pub const STIFFSPRING_VALUE_Q16_SIZE: usize = STIFFSPRING_VALUE_Q16_WORDS * 8;

// The storage holds the object on every target this crate builds for (the one being built).
const _: () = assert!(handle::fits::<SpringValue<f32>>(STIFFSPRING_VALUE_F32_SIZE));
const _: () = assert!(handle::fits::<SpringValue<I16F16>>(
    STIFFSPRING_VALUE_Q16_SIZE
));

const TAG_F32: Tag = Tag::new(2);
const TAG_Q16: Tag = Tag::new(3);

/// Storage for an `f32` value; `stiffspring_value_f32_init` fills it.
///
/// ```c
/// static StiffspringValueF32 card; /* zeroed: "not initialised" until init */
/// ```
#[repr(C)]
pub struct StiffspringValueF32 {
    opaque: [MaybeUninit<u64>; STIFFSPRING_VALUE_F32_WORDS],
}

/// Storage for a Q16.16 value; `stiffspring_value_q16_init` fills it.
///
/// ```c
/// StiffspringValueQ16 slider;
/// ```
#[repr(C)]
pub struct StiffspringValueQ16 {
    opaque: [MaybeUninit<u64>; STIFFSPRING_VALUE_Q16_WORDS],
}

/// What a step did, as the Rust API's `Motion`.
///
/// ```c
/// StiffspringMotion m;
/// stiffspring_value_f32_step(&card, &m);
/// if (m != STIFFSPRING_MOTION_RESTING) redraw();
/// ```
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum StiffspringMotion {
    /// The value was at rest and the step did nothing.
    Resting = 0,
    /// The value moved and is still moving.
    Moving = 1,
    /// The value moved and came to rest on its target in this step: draw it once more.
    Settled = 2,
}

impl From<Motion> for StiffspringMotion {
    fn from(motion: Motion) -> Self {
        match motion {
            Motion::Resting => StiffspringMotion::Resting,
            Motion::Moving => StiffspringMotion::Moving,
            Motion::Settled => StiffspringMotion::Settled,
        }
    }
}

// The generic code: `storage` is the handle's storage, `tag` the backend's.

/// # Safety
///
/// `storage` and `tuning` as in [`handle::init`] and [`handle::get_ref`].
unsafe fn init<S: Scalar>(
    storage: *mut u8,
    size: usize,
    tag: Tag,
    tuning: *const StiffspringTuning,
    position: S,
) -> StiffspringError {
    // SAFETY: the caller's contract.
    code(unsafe {
        handle::init(storage, size, tag, || {
            let tuning = tuning::read(tuning)?;
            Ok(SpringValue::<S>::new([position], tuning)?)
        })
    })
}

/// Runs `f` on the live value in `storage`.
///
/// # Safety
///
/// As [`handle::get`].
unsafe fn with<S: Scalar, R>(
    storage: *mut u8,
    tag: Tag,
    f: impl FnOnce(&mut SpringValue<S>) -> R,
) -> Result<R, StiffspringError> {
    // SAFETY: the caller's contract.
    unsafe { handle::get::<SpringValue<S>>(storage, tag) }.map(f)
}

/// Reads one component of the live value in `storage` into `out`.
///
/// # Safety
///
/// As [`handle::get_ref`] and [`handle::write_out`].
unsafe fn read<S: Scalar, T>(
    storage: *const u8,
    tag: Tag,
    out: *mut T,
    f: impl FnOnce(&SpringValue<S>) -> T,
) -> StiffspringError {
    // SAFETY: the caller's contract.
    code(unsafe {
        handle::get_ref::<SpringValue<S>>(storage, tag).and_then(|v| handle::write_out(out, f(v)))
    })
}

/// # Safety
///
/// As [`handle::get`] and [`handle::write_optional`].
unsafe fn step<S: Scalar>(
    storage: *mut u8,
    tag: Tag,
    motion: *mut StiffspringMotion,
) -> StiffspringError {
    // SAFETY: the caller's contract.
    code(unsafe {
        with::<S, _>(storage, tag, |v| v.step())
            .and_then(|m| handle::write_optional(motion, m.into()))
    })
}

/// # Safety
///
/// As [`handle::get`].
unsafe fn set_rest_threshold<S: Scalar>(
    storage: *mut u8,
    tag: Tag,
    position: f64,
    velocity: f64,
) -> StiffspringError {
    let threshold = match RestThreshold::new(position, velocity) {
        Ok(t) => t,
        Err(e) => return e.into(),
    };
    // SAFETY: the caller's contract.
    code(unsafe {
        with::<S, _>(storage, tag, |v| {
            *v = v.clone().with_rest_threshold(threshold)
        })
    })
}

/// A value at rest at `position`, tuned by `tuning` (which sets its time step), written into
/// `storage` of `size` bytes. Re-initialising a live value replaces it.
///
/// Errors: `NOT_FINITE` for a NaN or infinite position; `UNREPRESENTABLE` when the backend
/// cannot hold the tuning; `NULL_POINTER`, `BUFFER_TOO_SMALL`, `MISALIGNED` for the
/// storage, `NOT_INITIALISED` or `DROPPED` for the tuning. On an error the storage is
/// unchanged.
///
/// ```c
/// StiffspringValueF32 card;
/// StiffspringError e = stiffspring_value_f32_init(&card, sizeof card, &tuning, 0.0f);
/// ```
///
/// # Safety
///
/// `storage` is null or points to `size` bytes the caller owns; `tuning` is null or points
/// to a `StiffspringTuning`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn stiffspring_value_f32_init(
    storage: *mut StiffspringValueF32,
    size: usize,
    tuning: *const StiffspringTuning,
    position: f32,
) -> StiffspringError {
    // SAFETY: this function's contract.
    unsafe { init::<f32>(storage.cast(), size, TAG_F32, tuning, position) }
}

/// Ends the value: later calls on it return `DROPPED` until it is initialised again.
///
/// ```c
/// stiffspring_value_f32_drop(&card);
/// ```
///
/// # Safety
///
/// `value` is null or points to a `StiffspringValueF32` the caller owns (the contract of
/// every function on a handle: see the header's introduction).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn stiffspring_value_f32_drop(
    value: *mut StiffspringValueF32,
) -> StiffspringError {
    // SAFETY: this function's contract.
    code(unsafe { handle::drop::<SpringValue<f32>>(value.cast(), TAG_F32) })
}

/// Springs toward `target` from where the value is, keeping its position and velocity.
/// Cannot fail on the target: NaN is ignored, a target beyond the state's range
/// saturates. Returns an error only for a bad handle.
///
/// ```c
/// stiffspring_value_f32_set_target(&card, 320.0f);
/// ```
///
/// # Safety
///
/// As [`stiffspring_value_f32_drop`].
#[unsafe(no_mangle)]
pub unsafe extern "C" fn stiffspring_value_f32_set_target(
    value: *mut StiffspringValueF32,
    target: f32,
) -> StiffspringError {
    // SAFETY: this function's contract.
    code(unsafe { with::<f32, _>(value.cast(), TAG_F32, |v| v.set_target([target])) })
}

/// [`stiffspring_value_f32_set_target`], reporting instead of saturating: `NOT_FINITE`,
/// `OUT_OF_RANGE` or `UNREPRESENTABLE`, and the value is unchanged.
///
/// ```c
/// assert(stiffspring_value_f32_try_set_target(&card, INFINITY) == STIFFSPRING_ERROR_NOT_FINITE);
/// ```
///
/// # Safety
///
/// As [`stiffspring_value_f32_drop`].
#[unsafe(no_mangle)]
pub unsafe extern "C" fn stiffspring_value_f32_try_set_target(
    value: *mut StiffspringValueF32,
    target: f32,
) -> StiffspringError {
    // SAFETY: this function's contract.
    code(
        unsafe { with::<f32, _>(value.cast(), TAG_F32, |v| v.try_set_target([target])) }
            .and_then(|r| r.map_err(Into::into)),
    )
}

/// Moves the value to `position` at once (its target stays), keeping its velocity: a drag.
/// Cannot fail on the position (NaN is ignored, out-of-range input saturates).
///
/// ```c
/// stiffspring_value_f32_set_position(&card, finger_x);
/// ```
///
/// # Safety
///
/// As [`stiffspring_value_f32_drop`].
#[unsafe(no_mangle)]
pub unsafe extern "C" fn stiffspring_value_f32_set_position(
    value: *mut StiffspringValueF32,
    position: f32,
) -> StiffspringError {
    // SAFETY: this function's contract.
    code(unsafe { with::<f32, _>(value.cast(), TAG_F32, |v| v.set_position([position])) })
}

/// [`stiffspring_value_f32_set_position`], reporting instead of saturating.
///
/// ```c
/// stiffspring_value_f32_try_set_position(&card, 10.0f);
/// ```
///
/// # Safety
///
/// As [`stiffspring_value_f32_drop`].
#[unsafe(no_mangle)]
pub unsafe extern "C" fn stiffspring_value_f32_try_set_position(
    value: *mut StiffspringValueF32,
    position: f32,
) -> StiffspringError {
    // SAFETY: this function's contract.
    code(
        unsafe { with::<f32, _>(value.cast(), TAG_F32, |v| v.try_set_position([position])) }
            .and_then(|r| r.map_err(Into::into)),
    )
}

/// Gives the value a velocity (units per second), as a finger releasing a fling does. Cannot
/// fail on the velocity (NaN is ignored, a step velocity beyond the state's range saturates).
///
/// ```c
/// stiffspring_value_f32_fling(&card, -800.0f);
/// ```
///
/// # Safety
///
/// As [`stiffspring_value_f32_drop`].
#[unsafe(no_mangle)]
pub unsafe extern "C" fn stiffspring_value_f32_fling(
    value: *mut StiffspringValueF32,
    velocity: f32,
) -> StiffspringError {
    // SAFETY: this function's contract.
    code(unsafe { with::<f32, _>(value.cast(), TAG_F32, |v| v.fling([velocity])) })
}

/// [`stiffspring_value_f32_fling`], reporting instead of saturating.
///
/// ```c
/// stiffspring_value_f32_try_fling(&card, -800.0f);
/// ```
///
/// # Safety
///
/// As [`stiffspring_value_f32_drop`].
#[unsafe(no_mangle)]
pub unsafe extern "C" fn stiffspring_value_f32_try_fling(
    value: *mut StiffspringValueF32,
    velocity: f32,
) -> StiffspringError {
    // SAFETY: this function's contract.
    code(
        unsafe { with::<f32, _>(value.cast(), TAG_F32, |v| v.try_fling([velocity])) }
            .and_then(|r| r.map_err(Into::into)),
    )
}

/// When the value counts as settled: within `position` units of its target and slower
/// than `velocity` units per second (the Rust API's `RestThreshold::new`).
///
/// ```c
/// stiffspring_value_f32_set_rest_threshold(&card, 0.5, 10.0); /* pixels */
/// ```
///
/// # Safety
///
/// As [`stiffspring_value_f32_drop`].
#[unsafe(no_mangle)]
pub unsafe extern "C" fn stiffspring_value_f32_set_rest_threshold(
    value: *mut StiffspringValueF32,
    position: f64,
    velocity: f64,
) -> StiffspringError {
    // SAFETY: this function's contract.
    unsafe { set_rest_threshold::<f32>(value.cast(), TAG_F32, position, velocity) }
}

/// One time step; `motion` (optional, may be null) receives what it did.
///
/// ```c
/// StiffspringMotion m;
/// do { stiffspring_value_f32_step(&card, &m); } while (m == STIFFSPRING_MOTION_MOVING);
/// ```
///
/// # Safety
///
/// As [`stiffspring_value_f32_drop`]; `motion` is null or valid for a write.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn stiffspring_value_f32_step(
    value: *mut StiffspringValueF32,
    motion: *mut StiffspringMotion,
) -> StiffspringError {
    // SAFETY: this function's contract.
    unsafe { step::<f32>(value.cast(), TAG_F32, motion) }
}

/// The value's position, into `out`.
///
/// ```c
/// float x;
/// stiffspring_value_f32_position(&card, &x);
/// ```
///
/// # Safety
///
/// As [`stiffspring_value_f32_drop`]; `out` is null or valid for a write.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn stiffspring_value_f32_position(
    value: *const StiffspringValueF32,
    out: *mut f32,
) -> StiffspringError {
    // SAFETY: this function's contract.
    unsafe { read::<f32, _>(value.cast(), TAG_F32, out, |v| v.position()[0]) }
}

/// The value's target, into `out`.
///
/// ```c
/// float t;
/// stiffspring_value_f32_target(&card, &t);
/// ```
///
/// # Safety
///
/// As [`stiffspring_value_f32_position`].
#[unsafe(no_mangle)]
pub unsafe extern "C" fn stiffspring_value_f32_target(
    value: *const StiffspringValueF32,
    out: *mut f32,
) -> StiffspringError {
    // SAFETY: this function's contract.
    unsafe { read::<f32, _>(value.cast(), TAG_F32, out, |v| v.target()[0]) }
}

/// The value's velocity (units per second), into `out`.
///
/// ```c
/// float v;
/// stiffspring_value_f32_velocity(&card, &v);
/// ```
///
/// # Safety
///
/// As [`stiffspring_value_f32_position`].
#[unsafe(no_mangle)]
pub unsafe extern "C" fn stiffspring_value_f32_velocity(
    value: *const StiffspringValueF32,
    out: *mut f32,
) -> StiffspringError {
    // SAFETY: this function's contract.
    unsafe { read::<f32, _>(value.cast(), TAG_F32, out, |v| v.velocity()[0]) }
}

/// Whether the value rests on its target, into `out`.
///
/// ```c
/// bool resting;
/// stiffspring_value_f32_is_at_rest(&card, &resting);
/// ```
///
/// # Safety
///
/// As [`stiffspring_value_f32_position`].
#[unsafe(no_mangle)]
pub unsafe extern "C" fn stiffspring_value_f32_is_at_rest(
    value: *const StiffspringValueF32,
    out: *mut bool,
) -> StiffspringError {
    // SAFETY: this function's contract.
    unsafe { read::<f32, _>(value.cast(), TAG_F32, out, |v| v.is_at_rest()) }
}

/// A Q16.16 value (`position` is Q16.16 bits) at rest at `position`, tuned by `tuning` (which sets its time step), written into
/// `storage` of `size` bytes. Re-initialising a live value replaces it.
///
/// Errors: `NOT_FINITE` for a NaN or infinite position; `UNREPRESENTABLE` when the backend
/// cannot hold the tuning; `NULL_POINTER`, `BUFFER_TOO_SMALL`, `MISALIGNED` for the
/// storage, `NOT_INITIALISED` or `DROPPED` for the tuning. On an error the storage is
/// unchanged.
///
/// ```c
/// StiffspringValueQ16 slider;
/// StiffspringError e = stiffspring_value_q16_init(&slider, sizeof card, &tuning, 0);
/// ```
///
/// # Safety
///
/// `storage` is null or points to `size` bytes the caller owns; `tuning` is null or points
/// to a `StiffspringTuning`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn stiffspring_value_q16_init(
    storage: *mut StiffspringValueQ16,
    size: usize,
    tuning: *const StiffspringTuning,
    position: i32,
) -> StiffspringError {
    // SAFETY: this function's contract.
    unsafe {
        init::<I16F16>(
            storage.cast(),
            size,
            TAG_Q16,
            tuning,
            q16::from_bits(position),
        )
    }
}

/// Ends the value: later calls on it return `DROPPED` until it is initialised again.
///
/// ```c
/// stiffspring_value_q16_drop(&slider);
/// ```
///
/// # Safety
///
/// `value` is null or points to a `StiffspringValueQ16` the caller owns (the contract of
/// every function on a handle: see the header's introduction).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn stiffspring_value_q16_drop(
    value: *mut StiffspringValueQ16,
) -> StiffspringError {
    // SAFETY: this function's contract.
    code(unsafe { handle::drop::<SpringValue<I16F16>>(value.cast(), TAG_Q16) })
}

/// Springs toward `target` from where the value is, keeping its position and velocity.
/// Cannot fail on the target: NaN is ignored, a target beyond the state's range
/// saturates. Returns an error only for a bad handle.
///
/// ```c
/// stiffspring_value_q16_set_target(&slider, 320);
/// ```
///
/// # Safety
///
/// As [`stiffspring_value_q16_drop`].
#[unsafe(no_mangle)]
pub unsafe extern "C" fn stiffspring_value_q16_set_target(
    value: *mut StiffspringValueQ16,
    target: i32,
) -> StiffspringError {
    // SAFETY: this function's contract.
    code(unsafe {
        with::<I16F16, _>(value.cast(), TAG_Q16, |v| {
            v.set_target([q16::from_bits(target)])
        })
    })
}

/// [`stiffspring_value_q16_set_target`], reporting instead of saturating: `NOT_FINITE`,
/// `OUT_OF_RANGE` or `UNREPRESENTABLE`, and the value is unchanged.
///
/// ```c
/// assert(stiffspring_value_q16_try_set_target(&slider, INT32_MAX) == STIFFSPRING_ERROR_OUT_OF_RANGE);
/// ```
///
/// # Safety
///
/// As [`stiffspring_value_q16_drop`].
#[unsafe(no_mangle)]
pub unsafe extern "C" fn stiffspring_value_q16_try_set_target(
    value: *mut StiffspringValueQ16,
    target: i32,
) -> StiffspringError {
    // SAFETY: this function's contract.
    code(
        unsafe {
            with::<I16F16, _>(value.cast(), TAG_Q16, |v| {
                v.try_set_target([q16::from_bits(target)])
            })
        }
        .and_then(|r| r.map_err(Into::into)),
    )
}

/// Moves the value to `position` at once (its target stays), keeping its velocity: a drag.
/// Cannot fail on the position (NaN is ignored, out-of-range input saturates).
///
/// ```c
/// stiffspring_value_q16_set_position(&slider, finger_x);
/// ```
///
/// # Safety
///
/// As [`stiffspring_value_q16_drop`].
#[unsafe(no_mangle)]
pub unsafe extern "C" fn stiffspring_value_q16_set_position(
    value: *mut StiffspringValueQ16,
    position: i32,
) -> StiffspringError {
    // SAFETY: this function's contract.
    code(unsafe {
        with::<I16F16, _>(value.cast(), TAG_Q16, |v| {
            v.set_position([q16::from_bits(position)])
        })
    })
}

/// [`stiffspring_value_q16_set_position`], reporting instead of saturating.
///
/// ```c
/// stiffspring_value_q16_try_set_position(&slider, 10);
/// ```
///
/// # Safety
///
/// As [`stiffspring_value_q16_drop`].
#[unsafe(no_mangle)]
pub unsafe extern "C" fn stiffspring_value_q16_try_set_position(
    value: *mut StiffspringValueQ16,
    position: i32,
) -> StiffspringError {
    // SAFETY: this function's contract.
    code(
        unsafe {
            with::<I16F16, _>(value.cast(), TAG_Q16, |v| {
                v.try_set_position([q16::from_bits(position)])
            })
        }
        .and_then(|r| r.map_err(Into::into)),
    )
}

/// Gives the value a velocity (units per second), as a finger releasing a fling does. Cannot
/// fail on the velocity (NaN is ignored, a step velocity beyond the state's range saturates).
///
/// ```c
/// stiffspring_value_q16_fling(&slider, -800);
/// ```
///
/// # Safety
///
/// As [`stiffspring_value_q16_drop`].
#[unsafe(no_mangle)]
pub unsafe extern "C" fn stiffspring_value_q16_fling(
    value: *mut StiffspringValueQ16,
    velocity: i32,
) -> StiffspringError {
    // SAFETY: this function's contract.
    code(unsafe {
        with::<I16F16, _>(value.cast(), TAG_Q16, |v| {
            v.fling([q16::from_bits(velocity)])
        })
    })
}

/// [`stiffspring_value_q16_fling`], reporting instead of saturating.
///
/// ```c
/// stiffspring_value_q16_try_fling(&slider, -800);
/// ```
///
/// # Safety
///
/// As [`stiffspring_value_q16_drop`].
#[unsafe(no_mangle)]
pub unsafe extern "C" fn stiffspring_value_q16_try_fling(
    value: *mut StiffspringValueQ16,
    velocity: i32,
) -> StiffspringError {
    // SAFETY: this function's contract.
    code(
        unsafe {
            with::<I16F16, _>(value.cast(), TAG_Q16, |v| {
                v.try_fling([q16::from_bits(velocity)])
            })
        }
        .and_then(|r| r.map_err(Into::into)),
    )
}

/// When the value counts as settled: within `position` units of its target and slower
/// than `velocity` units per second (the Rust API's `RestThreshold::new`).
///
/// ```c
/// stiffspring_value_q16_set_rest_threshold(&slider, 0.5, 10.0); /* pixels */
/// ```
///
/// # Safety
///
/// As [`stiffspring_value_q16_drop`].
#[unsafe(no_mangle)]
pub unsafe extern "C" fn stiffspring_value_q16_set_rest_threshold(
    value: *mut StiffspringValueQ16,
    position: f64,
    velocity: f64,
) -> StiffspringError {
    // SAFETY: this function's contract.
    unsafe { set_rest_threshold::<I16F16>(value.cast(), TAG_Q16, position, velocity) }
}

/// One time step; `motion` (optional, may be null) receives what it did.
///
/// ```c
/// StiffspringMotion m;
/// do { stiffspring_value_q16_step(&slider, &m); } while (m == STIFFSPRING_MOTION_MOVING);
/// ```
///
/// # Safety
///
/// As [`stiffspring_value_q16_drop`]; `motion` is null or valid for a write.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn stiffspring_value_q16_step(
    value: *mut StiffspringValueQ16,
    motion: *mut StiffspringMotion,
) -> StiffspringError {
    // SAFETY: this function's contract.
    unsafe { step::<I16F16>(value.cast(), TAG_Q16, motion) }
}

/// The value's position, into `out`.
///
/// ```c
/// int32_t x;
/// stiffspring_value_q16_position(&slider, &x);
/// ```
///
/// # Safety
///
/// As [`stiffspring_value_q16_drop`]; `out` is null or valid for a write.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn stiffspring_value_q16_position(
    value: *const StiffspringValueQ16,
    out: *mut i32,
) -> StiffspringError {
    // SAFETY: this function's contract.
    unsafe {
        read::<I16F16, _>(value.cast(), TAG_Q16, out, |v| {
            q16::to_bits(v.position()[0])
        })
    }
}

/// The value's target, into `out`.
///
/// ```c
/// int32_t t;
/// stiffspring_value_q16_target(&slider, &t);
/// ```
///
/// # Safety
///
/// As [`stiffspring_value_q16_position`].
#[unsafe(no_mangle)]
pub unsafe extern "C" fn stiffspring_value_q16_target(
    value: *const StiffspringValueQ16,
    out: *mut i32,
) -> StiffspringError {
    // SAFETY: this function's contract.
    unsafe { read::<I16F16, _>(value.cast(), TAG_Q16, out, |v| q16::to_bits(v.target()[0])) }
}

/// The value's velocity (units per second), into `out`.
///
/// ```c
/// int32_t v;
/// stiffspring_value_q16_velocity(&slider, &v);
/// ```
///
/// # Safety
///
/// As [`stiffspring_value_q16_position`].
#[unsafe(no_mangle)]
pub unsafe extern "C" fn stiffspring_value_q16_velocity(
    value: *const StiffspringValueQ16,
    out: *mut i32,
) -> StiffspringError {
    // SAFETY: this function's contract.
    unsafe {
        read::<I16F16, _>(value.cast(), TAG_Q16, out, |v| {
            q16::to_bits(v.velocity()[0])
        })
    }
}

/// Whether the value rests on its target, into `out`.
///
/// ```c
/// bool resting;
/// stiffspring_value_q16_is_at_rest(&slider, &resting);
/// ```
///
/// # Safety
///
/// As [`stiffspring_value_q16_position`].
#[unsafe(no_mangle)]
pub unsafe extern "C" fn stiffspring_value_q16_is_at_rest(
    value: *const StiffspringValueQ16,
    out: *mut bool,
) -> StiffspringError {
    // SAFETY: this function's contract.
    unsafe { read::<I16F16, _>(value.cast(), TAG_Q16, out, |v| v.is_at_rest()) }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::tuning::{STIFFSPRING_TUNING_WORDS, stiffspring_tuning_from_frequency};
    use core::mem::size_of;
    use core::ptr::{null, null_mut};
    use stiffspring::Tuning;

    fn tuning() -> StiffspringTuning {
        let mut t = StiffspringTuning::zeroed_for_tests();
        // SAFETY: `t` is our storage of its size.
        let e = unsafe {
            stiffspring_tuning_from_frequency(
                &mut t,
                size_of::<StiffspringTuning>(),
                2.0,
                0.3,
                1.0 / 60.0,
            )
        };
        assert_eq!(e, StiffspringError::Ok);
        t
    }

    fn f32_storage() -> StiffspringValueF32 {
        StiffspringValueF32 {
            opaque: [handle::ZERO; STIFFSPRING_VALUE_F32_WORDS],
        }
    }

    fn q16_storage() -> StiffspringValueQ16 {
        StiffspringValueQ16 {
            opaque: [handle::ZERO; STIFFSPRING_VALUE_Q16_WORDS],
        }
    }

    #[test]
    fn the_c_value_follows_the_rust_value_to_the_bit() {
        let t = tuning();
        let mut rust = SpringValue::<f32>::new(
            [0.0],
            &Tuning::from_frequency(2.0, 0.3, 1.0 / 60.0).unwrap(),
        )
        .unwrap();
        let mut c = f32_storage();
        let size = size_of::<StiffspringValueF32>();
        // SAFETY: `c` and `t` are our storage; the out-pointers are ours.
        unsafe {
            assert_eq!(
                stiffspring_value_f32_init(&mut c, size, &t, 0.0),
                StiffspringError::Ok
            );
            assert_eq!(
                stiffspring_value_f32_set_target(&mut c, 100.0),
                StiffspringError::Ok
            );
            rust.set_target([100.0]);
            let mut settled = false;
            for frame in 0..600 {
                if frame == 30 {
                    stiffspring_value_f32_set_target(&mut c, 40.0);
                    rust.set_target([40.0]);
                }
                if frame == 90 {
                    stiffspring_value_f32_fling(&mut c, -300.0);
                    rust.fling([-300.0]);
                }
                let mut m = StiffspringMotion::Resting;
                assert_eq!(
                    stiffspring_value_f32_step(&mut c, &mut m),
                    StiffspringError::Ok
                );
                assert_eq!(m, rust.step().into());
                let (mut x, mut v) = (f32::NAN, f32::NAN);
                stiffspring_value_f32_position(&c, &mut x);
                stiffspring_value_f32_velocity(&c, &mut v);
                assert_eq!(
                    (x.to_bits(), v.to_bits()),
                    (rust.position()[0].to_bits(), rust.velocity()[0].to_bits())
                );
                settled |= m == StiffspringMotion::Settled;
            }
            assert!(settled);
            let mut resting = false;
            assert_eq!(
                stiffspring_value_f32_is_at_rest(&c, &mut resting),
                StiffspringError::Ok
            );
            let mut target = 0.0;
            stiffspring_value_f32_target(&c, &mut target);
            assert!(resting && target == 40.0);
        }
    }

    #[test]
    fn the_q16_value_takes_and_gives_q16_bits() {
        let t = tuning();
        let mut c = q16_storage();
        let one = crate::q16::STIFFSPRING_Q16_ONE;
        // SAFETY: as above.
        unsafe {
            assert_eq!(
                stiffspring_value_q16_init(&mut c, size_of::<StiffspringValueQ16>(), &t, 5 * one),
                StiffspringError::Ok
            );
            let mut x = 0;
            stiffspring_value_q16_position(&c, &mut x);
            assert_eq!(x, 5 * one);
            stiffspring_value_q16_set_target(&mut c, -one);
            let mut m = StiffspringMotion::Moving;
            while m != StiffspringMotion::Settled {
                stiffspring_value_q16_step(&mut c, &mut m);
            }
            stiffspring_value_q16_position(&c, &mut x);
            assert_eq!(x, -one);
            assert_eq!(stiffspring_value_q16_drop(&mut c), StiffspringError::Ok);
            assert_eq!(
                stiffspring_value_q16_position(&c, &mut x),
                StiffspringError::Dropped
            );
        }
    }

    #[test]
    fn bad_input_is_an_error_code() {
        let t = tuning();
        let mut c = f32_storage();
        let size = size_of::<StiffspringValueF32>();
        let mut x = 0.0f32;
        // SAFETY: every pointer is null or our storage; misaligned ones are refused unread.
        unsafe {
            // Before init: zeroed storage holds nothing.
            assert_eq!(
                stiffspring_value_f32_step(&mut c, null_mut()),
                StiffspringError::NotInitialised
            );
            assert_eq!(
                stiffspring_value_f32_init(null_mut(), size, &t, 0.0),
                StiffspringError::NullPointer
            );
            assert_eq!(
                stiffspring_value_f32_init(&mut c, size - 1, &t, 0.0),
                StiffspringError::BufferTooSmall
            );
            assert_eq!(
                stiffspring_value_f32_init(&mut c, size, null(), 0.0),
                StiffspringError::NullPointer
            );
            let untuned = StiffspringTuning::zeroed_for_tests();
            assert_eq!(
                stiffspring_value_f32_init(&mut c, size, &untuned, 0.0),
                StiffspringError::NotInitialised
            );
            assert_eq!(
                stiffspring_value_f32_init(&mut c, size, &t, f32::NAN),
                StiffspringError::NotFinite
            );
            assert!(handle::is_zero(&c.opaque), "a failed init writes nothing");
            let odd = c
                .opaque
                .as_mut_ptr()
                .cast::<u8>()
                .add(4)
                .cast::<StiffspringValueF32>();
            assert_eq!(
                stiffspring_value_f32_init(odd, size - 8, &t, 0.0),
                StiffspringError::Misaligned
            );

            assert_eq!(
                stiffspring_value_f32_init(&mut c, size, &t, 1.0),
                StiffspringError::Ok
            );
            // The UI path: NaN is ignored, and the call succeeds.
            assert_eq!(
                stiffspring_value_f32_set_target(&mut c, f32::NAN),
                StiffspringError::Ok
            );
            assert_eq!(
                stiffspring_value_f32_fling(&mut c, f32::NAN),
                StiffspringError::Ok
            );
            assert_eq!(
                stiffspring_value_f32_set_position(&mut c, f32::NAN),
                StiffspringError::Ok
            );
            stiffspring_value_f32_position(&c, &mut x);
            assert_eq!(x, 1.0);
            // The try_ twins report it.
            assert_eq!(
                stiffspring_value_f32_try_set_target(&mut c, f32::NAN),
                StiffspringError::NotFinite
            );
            assert_eq!(
                stiffspring_value_f32_try_set_position(&mut c, f32::INFINITY),
                StiffspringError::NotFinite
            );
            assert_eq!(
                stiffspring_value_f32_try_fling(&mut c, f32::NAN),
                StiffspringError::NotFinite
            );
            assert_eq!(
                stiffspring_value_f32_try_set_target(&mut c, 2.0),
                StiffspringError::Ok
            );
            assert_eq!(
                stiffspring_value_f32_set_rest_threshold(&mut c, f64::NAN, 1.0),
                StiffspringError::NotFinite
            );
            assert_eq!(
                stiffspring_value_f32_set_rest_threshold(&mut c, 0.5, 10.0),
                StiffspringError::Ok
            );
            // Out-pointers.
            assert_eq!(
                stiffspring_value_f32_position(&c, null_mut()),
                StiffspringError::NullPointer
            );
            assert_eq!(
                stiffspring_value_f32_step(&mut c, null_mut()),
                StiffspringError::Ok
            );
            // Another type's storage.
            let as_q16 = (&raw mut c).cast::<StiffspringValueQ16>();
            assert_eq!(
                stiffspring_value_q16_drop(as_q16),
                StiffspringError::NotInitialised
            );
            // Use after drop.
            assert_eq!(stiffspring_value_f32_drop(&mut c), StiffspringError::Ok);
            assert_eq!(
                stiffspring_value_f32_drop(&mut c),
                StiffspringError::Dropped
            );
            assert_eq!(
                stiffspring_value_f32_set_target(&mut c, 3.0),
                StiffspringError::Dropped
            );
            assert_eq!(
                stiffspring_value_f32_position(&c, &mut x),
                StiffspringError::Dropped
            );
            // Null handles.
            assert_eq!(
                stiffspring_value_f32_step(null_mut(), null_mut()),
                StiffspringError::NullPointer
            );
            assert_eq!(
                stiffspring_value_f32_position(null(), &mut x),
                StiffspringError::NullPointer
            );
        }
        let _ = STIFFSPRING_TUNING_WORDS;
    }

    #[test]
    fn a_q16_spring_too_slow_for_its_rate_is_unrepresentable() {
        let mut t = StiffspringTuning::zeroed_for_tests();
        let mut c = q16_storage();
        // SAFETY: our storage.
        unsafe {
            stiffspring_tuning_from_frequency(
                &mut t,
                size_of::<StiffspringTuning>(),
                0.1,
                0.5,
                1e-4,
            );
            let e = stiffspring_value_q16_init(&mut c, size_of::<StiffspringValueQ16>(), &t, 0);
            assert_eq!(e, StiffspringError::Unrepresentable);
        }
    }
}
