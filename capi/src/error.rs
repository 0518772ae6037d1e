//! The error codes every function returns, and their names.

use core::ffi::c_char;
use stiffspring::Error;
use stiffspring::knob::KnobError;

/// What a call did: [`StiffspringError::Ok`] (0), or why it changed nothing.
///
/// The Rust API's errors carry the parameter, its value and the bound it broke; in C the
/// code says which kind of error, and the arguments of the call say which value. Codes are
/// stable: new ones are only added at the end.
///
/// ```c
/// StiffspringError e = stiffspring_value_f32_init(&v, sizeof v, &tuning, NAN);
/// printf("%s\n", stiffspring_error_name(e)); /* "STIFFSPRING_ERROR_NOT_FINITE" */
/// ```
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum StiffspringError {
    /// Success.
    Ok = 0,
    /// A pointer argument (a handle, the storage, an out-pointer) was null.
    NullPointer = 1,
    /// The storage given to an `init` function is smaller than the object.
    BufferTooSmall = 2,
    /// The storage or an out-pointer is not aligned for its type
    /// (`STIFFSPRING_STORAGE_ALIGN` for the storage).
    Misaligned = 3,
    /// The storage holds no live object of this type: it was never initialised (or its
    /// `init` failed), or it holds another type's object.
    NotInitialised = 4,
    /// The object was dropped (`..._drop`) and not initialised again.
    Dropped = 5,
    /// An argument was NaN or infinite.
    NotFinite = 6,
    /// An argument lies outside the range the call accepts (for a knob: a configuration
    /// outside what its loop guarantee allows).
    OutOfRange = 7,
    /// The backend cannot hold the value at its resolution or in its range (a spring too
    /// slow for Q16.16 at its rate, a velocity beyond the state's range).
    Unrepresentable = 8,
    /// A batch is full (`STIFFSPRING_BATCH_CAPACITY` values), or a knob has more magnets
    /// than it holds.
    CapacityFull = 9,
    /// A batch index that names no live value: removed, or never pushed.
    StaleIndex = 10,
    /// A knob given a detent count and no endstops to spread them over.
    NeedsEndstops = 11,
    /// A tuning with no continuous oscillator behind it, where one is needed.
    NoContinuousEquivalent = 12,
    /// An undamped oscillator at a multiple of half the sample rate.
    Aliased = 13,
    /// Any other refusal of the library (an error added after this API).
    Other = 14,
}

impl From<Error> for StiffspringError {
    fn from(error: Error) -> Self {
        match error {
            Error::NotFinite { .. } => StiffspringError::NotFinite,
            Error::OutOfRange { .. } => StiffspringError::OutOfRange,
            Error::Unrepresentable { .. } => StiffspringError::Unrepresentable,
            Error::CapacityFull { .. } => StiffspringError::CapacityFull,
            Error::Stale { .. } => StiffspringError::StaleIndex,
            Error::NeedsEndstops => StiffspringError::NeedsEndstops,
            Error::NoContinuousEquivalent => StiffspringError::NoContinuousEquivalent,
            Error::Aliased { .. } => StiffspringError::Aliased,
            _ => StiffspringError::Other,
        }
    }
}

impl From<KnobError> for StiffspringError {
    fn from(error: KnobError) -> Self {
        error.error.into()
    }
}

/// `Ok(())` as [`StiffspringError::Ok`], an error as its code: what every function
/// returns.
pub(crate) fn code(result: Result<(), StiffspringError>) -> StiffspringError {
    match result {
        Ok(()) => StiffspringError::Ok,
        Err(e) => e,
    }
}

/// The names, in code order, then the name of an integer that is no code: each ends in NUL
/// for C.
///
/// One `static` of bytes, not a string literal per name: the compiler pools
/// NUL-terminated literals with the library's other constant strings (the file names of
/// its panic locations) in one section, which the linker keeps whole as soon as any of
/// them is used, so a firmware that never asks for a name paid for all of them
/// (`scripts/capi-size`: 545 bytes of a batch firmware's). A `static` has its own section,
/// which the linker drops when `stiffspring_error_name` is not linked.
static NAME_TEXT: [u8; NAME_TEXT_LEN] = bytes_of(NAME_SOURCE);

/// The text of [`NAME_TEXT`].
const NAME_SOURCE: &str = concat!(
    "STIFFSPRING_ERROR_OK\0",
    "STIFFSPRING_ERROR_NULL_POINTER\0",
    "STIFFSPRING_ERROR_BUFFER_TOO_SMALL\0",
    "STIFFSPRING_ERROR_MISALIGNED\0",
    "STIFFSPRING_ERROR_NOT_INITIALISED\0",
    "STIFFSPRING_ERROR_DROPPED\0",
    "STIFFSPRING_ERROR_NOT_FINITE\0",
    "STIFFSPRING_ERROR_OUT_OF_RANGE\0",
    "STIFFSPRING_ERROR_UNREPRESENTABLE\0",
    "STIFFSPRING_ERROR_CAPACITY_FULL\0",
    "STIFFSPRING_ERROR_STALE_INDEX\0",
    "STIFFSPRING_ERROR_NEEDS_ENDSTOPS\0",
    "STIFFSPRING_ERROR_NO_CONTINUOUS_EQUIVALENT\0",
    "STIFFSPRING_ERROR_ALIASED\0",
    "STIFFSPRING_ERROR_OTHER\0",
    "STIFFSPRING_ERROR_UNKNOWN\0",
);
const NAME_TEXT_LEN: usize = NAME_SOURCE.len();

/// How many codes there are (the last name is of an integer that is no code).
const CODES: usize = 15;

/// Where each name of [`NAME_TEXT`] starts: the code's, and at `CODES` the unknown one.
const NAME_START: [u16; CODES + 1] = starts();

const fn bytes_of(text: &str) -> [u8; NAME_TEXT_LEN] {
    let mut out = [0; NAME_TEXT_LEN];
    let mut i = 0;
    while i < NAME_TEXT_LEN {
        out[i] = text.as_bytes()[i];
        i += 1;
    }
    out
}

const fn starts() -> [u16; CODES + 1] {
    let text = NAME_SOURCE.as_bytes();
    let mut out = [0; CODES + 1];
    let (mut i, mut n) = (0, 1);
    while i + 1 < text.len() {
        if text[i] == 0 {
            out[n] = (i + 1) as u16;
            n += 1;
        }
        i += 1;
    }
    // Exactly one name per code and the unknown one: a compile error otherwise.
    assert!(n == CODES + 1 && text[text.len() - 1] == 0);
    out
}

/// The name of an error code, as the header spells it (`"STIFFSPRING_ERROR_NOT_FINITE"`), or
/// `"STIFFSPRING_ERROR_UNKNOWN"` for an integer that is no code. Never null; the string
/// is static.
///
/// It takes an `int` rather than the enum, so that any integer a C caller passes is
/// defined behaviour.
///
/// ```c
/// puts(stiffspring_error_name(stiffspring_value_f32_step(NULL, NULL))); /* STIFFSPRING_ERROR_NULL_POINTER */
/// ```
#[unsafe(no_mangle)]
pub extern "C" fn stiffspring_error_name(code: i32) -> *const c_char {
    let index = usize::try_from(code).map_or(CODES, |i| i.min(CODES));
    // Every start is within the text (`starts`): the pointer is to a name's first byte.
    NAME_TEXT
        .as_ptr()
        .wrapping_add(usize::from(NAME_START[index]))
        .cast()
}

#[cfg(test)]
mod tests {
    use super::*;
    use core::ffi::CStr;

    fn name(code: i32) -> &'static str {
        // SAFETY: the function returns a pointer into a static, NUL-terminated string.
        unsafe { CStr::from_ptr(stiffspring_error_name(code)) }
            .to_str()
            .unwrap()
    }

    #[test]
    fn every_code_has_its_header_name() {
        assert_eq!(name(StiffspringError::Ok as i32), "STIFFSPRING_ERROR_OK");
        assert_eq!(
            name(StiffspringError::NotFinite as i32),
            "STIFFSPRING_ERROR_NOT_FINITE"
        );
        assert_eq!(
            name(StiffspringError::Other as i32),
            "STIFFSPRING_ERROR_OTHER"
        );
        for code in 0..CODES as i32 {
            assert!(name(code).starts_with("STIFFSPRING_ERROR_"), "{code}");
            assert_ne!(name(code), "STIFFSPRING_ERROR_UNKNOWN", "{code}");
        }
    }

    #[test]
    fn integers_that_are_no_code_have_a_name_too() {
        for code in [-1, 15, 16, i32::MIN, i32::MAX] {
            assert_eq!(name(code), "STIFFSPRING_ERROR_UNKNOWN");
        }
    }

    #[test]
    fn library_errors_map_to_their_codes() {
        let e = stiffspring::Tuning::from_frequency(f64::NAN, 0.5, 0.01).unwrap_err();
        assert_eq!(StiffspringError::from(e), StiffspringError::NotFinite);
        let e = stiffspring::Tuning::from_coefficients(0.5, -0.1, 0.01).unwrap_err();
        assert_eq!(StiffspringError::from(e), StiffspringError::OutOfRange);
    }
}
