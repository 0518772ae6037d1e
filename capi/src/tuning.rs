//! A spring's tuning in C: its coefficients and time step, made once and shared by the
//! values and batches that use it (they copy it; the tuning may be dropped after).

use crate::error::{StiffspringError, code};
use crate::handle::{self, Tag};
use core::mem::MaybeUninit;
use stiffspring::Tuning;

/// 64-bit words of a [`StiffspringTuning`].
pub const STIFFSPRING_TUNING_WORDS: usize = 12;
/// Bytes of a [`StiffspringTuning`], for a buffer of one's own.
pub const STIFFSPRING_TUNING_SIZE: usize = STIFFSPRING_TUNING_WORDS * 8;

const _: () = assert!(handle::fits::<Tuning>(STIFFSPRING_TUNING_SIZE));

pub(crate) const TAG: Tag = Tag::new(1);

/// Storage for a tuning; one of the `stiffspring_tuning_from_*` functions fills it.
///
/// ```c
/// StiffspringTuning bouncy;
/// stiffspring_tuning_from_frequency(&bouncy, sizeof bouncy, 2.0, 0.3, 1.0 / 60.0);
/// ```
#[repr(C)]
pub struct StiffspringTuning {
    opaque: [MaybeUninit<u64>; STIFFSPRING_TUNING_WORDS],
}

#[cfg(test)]
impl StiffspringTuning {
    /// Zeroed storage, as a C `static` gives.
    pub(crate) fn zeroed_for_tests() -> Self {
        StiffspringTuning {
            opaque: [handle::ZERO; STIFFSPRING_TUNING_WORDS],
        }
    }
}

/// The tuning in `tuning`, by reference (a copy would cost a `memcpy` in every init).
///
/// # Safety
///
/// As [`handle::get_ref`].
pub(crate) unsafe fn read<'a>(
    tuning: *const StiffspringTuning,
) -> Result<&'a Tuning, StiffspringError> {
    // SAFETY: the caller's contract is `get_ref`'s.
    unsafe { handle::get_ref::<Tuning>(tuning.cast(), TAG) }
}

/// Writes `make()`'s tuning into `out`.
///
/// # Safety
///
/// As [`handle::init`].
unsafe fn make(
    out: *mut StiffspringTuning,
    size: usize,
    make: impl FnOnce() -> Result<Tuning, stiffspring::Error>,
) -> StiffspringError {
    // SAFETY: the caller's contract is `init`'s.
    code(unsafe { handle::init(out.cast(), size, TAG, || make().map_err(Into::into)) })
}

/// The exact tuning of a continuous spring of `frequency` hertz and damping ratio
/// `damping_ratio`, sampled every `dt` seconds: the discrete spring hits the continuous
/// trajectory at every sample.
///
/// Errors: `NOT_FINITE` or `OUT_OF_RANGE` for an argument, `ALIASED` for an undamped
/// spring at a multiple of half the sample rate; `NULL_POINTER`, `BUFFER_TOO_SMALL`,
/// `MISALIGNED` for the storage. On an error `out` is unchanged.
///
/// ```c
/// StiffspringTuning t;
/// assert(stiffspring_tuning_from_frequency(&t, sizeof t, 2.0, 0.3, 1.0 / 60.0) == STIFFSPRING_ERROR_OK);
/// ```
///
/// # Safety
///
/// `out` is null or points to `size` bytes the caller owns.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn stiffspring_tuning_from_frequency(
    out: *mut StiffspringTuning,
    size: usize,
    frequency: f64,
    damping_ratio: f64,
    dt: f64,
) -> StiffspringError {
    // SAFETY: this function's contract.
    unsafe {
        make(out, size, || {
            Tuning::from_frequency(frequency, damping_ratio, dt)
        })
    }
}

/// A tuning from the raw coefficients `C_k` (`stiffness`) and `C_d` (`damping`), each in
/// `[0, 1]`, at a time step of `dt` seconds.
///
/// Errors: as [`stiffspring_tuning_from_frequency`].
///
/// ```c
/// StiffspringTuning t;
/// stiffspring_tuning_from_coefficients(&t, sizeof t, 0.2, 0.5, 1.0 / 60.0);
/// ```
///
/// # Safety
///
/// `out` is null or points to `size` bytes the caller owns.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn stiffspring_tuning_from_coefficients(
    out: *mut StiffspringTuning,
    size: usize,
    stiffness: f64,
    damping: f64,
    dt: f64,
) -> StiffspringError {
    // SAFETY: this function's contract.
    unsafe {
        make(out, size, || {
            Tuning::from_coefficients(stiffness, damping, dt)
        })
    }
}

/// The tuning's coefficients and time step, each out-pointer optional (null skips it).
///
/// ```c
/// double dt;
/// stiffspring_tuning_coefficients(&t, NULL, NULL, &dt);
/// ```
///
/// # Safety
///
/// `tuning` is null or points to a `StiffspringTuning` the caller owns; each out-pointer
/// is null or valid for a write of a `double`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn stiffspring_tuning_coefficients(
    tuning: *const StiffspringTuning,
    stiffness: *mut f64,
    damping: *mut f64,
    dt: *mut f64,
) -> StiffspringError {
    // SAFETY: this function's contract.
    code(unsafe {
        read(tuning).and_then(|t| {
            handle::write_optional(stiffness, t.stiffness())?;
            handle::write_optional(damping, t.damping())?;
            handle::write_optional(dt, t.dt())
        })
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use core::mem::size_of;
    use core::ptr::{null, null_mut};

    fn zeroed() -> StiffspringTuning {
        StiffspringTuning::zeroed_for_tests()
    }

    #[test]
    fn a_tuning_is_made_and_read() {
        let mut t = zeroed();
        let size = size_of::<StiffspringTuning>();
        let (mut k, mut dt) = (0.0, 0.0);
        // SAFETY: `t` is our storage of `size` bytes; the out-pointers are ours or null.
        unsafe {
            assert_eq!(
                stiffspring_tuning_coefficients(&t, &mut k, null_mut(), &mut dt),
                StiffspringError::NotInitialised
            );
            let e = stiffspring_tuning_from_coefficients(&mut t, size, 0.25, 0.5, 0.01);
            assert_eq!(e, StiffspringError::Ok);
            let e = stiffspring_tuning_coefficients(&t, &mut k, null_mut(), &mut dt);
            assert_eq!((e, k, dt), (StiffspringError::Ok, 0.25, 0.01));
        }
    }

    #[test]
    fn bad_arguments_are_codes_and_change_nothing() {
        let mut t = zeroed();
        let size = size_of::<StiffspringTuning>();
        // SAFETY: as above.
        unsafe {
            let nan = stiffspring_tuning_from_frequency(&mut t, size, f64::NAN, 0.5, 0.01);
            assert_eq!(nan, StiffspringError::NotFinite);
            let range = stiffspring_tuning_from_coefficients(&mut t, size, 0.5, 2.0, 0.01);
            assert_eq!(range, StiffspringError::OutOfRange);
            let small = stiffspring_tuning_from_frequency(&mut t, 8, 2.0, 0.5, 0.01);
            assert_eq!(small, StiffspringError::BufferTooSmall);
            let no_storage = stiffspring_tuning_from_frequency(null_mut(), size, 2.0, 0.5, 0.01);
            assert_eq!(no_storage, StiffspringError::NullPointer);
            assert_eq!(
                stiffspring_tuning_coefficients(null(), null_mut(), null_mut(), null_mut()),
                StiffspringError::NullPointer
            );
        }
        assert!(handle::is_zero(&t.opaque));
    }
}
