//! # stiffspring-c
//!
//! The C API of stiffspring: UI values ([`SpringValue`](stiffspring::SpringValue)),
//! batches of them ([`SpringBatch`](stiffspring::SpringBatch)) and the haptic knob
//! ([`Knob`](stiffspring::Knob)), in `f32` and in Q16.16 fixed point (`int32_t`, the
//! library's `I16F16`), as a static library (`libstiffspring_c.a`) and the header
//! `capi/include/stiffspring.h`, which cbindgen generates from this crate.
//!
//! ```c
//! #include "stiffspring.h"
//!
//! StiffspringTuning tuning;
//! StiffspringValueF32 card;                       /* storage the caller owns */
//! stiffspring_tuning_from_frequency(&tuning, sizeof tuning, 2.0, 0.3, 1.0 / 60.0);
//! if (stiffspring_value_f32_init(&card, sizeof card, &tuning, 0.0f) != STIFFSPRING_ERROR_OK) {
//!     /* stiffspring_error_name(code) names what went wrong */
//! }
//! stiffspring_value_f32_set_target(&card, 100.0f);
//! StiffspringMotion motion;
//! do {
//!     stiffspring_value_f32_step(&card, &motion);
//! } while (motion != STIFFSPRING_MOTION_SETTLED);
//! ```
//!
//! ## Handles in storage the caller owns
//!
//! Each object lives in a struct the header declares with its size and alignment
//! (`StiffspringValueF32`, ...; `STIFFSPRING_VALUE_F32_SIZE` and `STIFFSPRING_STORAGE_ALIGN`
//! for a buffer of one's own). An `init` function writes the object into it and a `drop`
//! function marks it dead; nothing allocates. The storage begins with a tag word that says
//! which object lives there ([`handle`]), so that every call can refuse, with an error
//! code and without touching anything:
//!
//! - a null pointer ([`StiffspringError::NullPointer`]);
//! - storage smaller than the object ([`StiffspringError::BufferTooSmall`], checked by
//!   `init`, which takes the size) or not aligned for it
//!   ([`StiffspringError::Misaligned`]);
//! - storage that holds no object of the type: never initialised (zeroed storage, as a
//!   `static` or `= {0}` gives, always reads so), or another type's
//!   ([`StiffspringError::NotInitialised`]);
//! - an object used after its `drop` ([`StiffspringError::Dropped`]).
//!
//! What cannot be detected, and is the caller's part of the contract: a pointer to memory
//! that is not the caller's (a dangling or wild pointer), storage that is smaller than its
//! type but passed to a function other than `init`, and two calls on the same object at
//! once (an object is not thread-safe; guard it as any C struct). Objects hold no pointers,
//! so they may be copied with `memcpy` or moved.
//!
//! ## What the API does with bad values
//!
//! As the Rust API: set-up (`init`, the `try_` setters) reports a NaN or an out-of-range
//! argument as an error code and changes nothing; the UI path's setters (`set_target`,
//! `set_position`, `fling`) cannot fail on a value (NaN is ignored, out-of-range input
//! saturates) and return an error only for a bad handle; stepping never fails.
//!
//! ## Panics
//!
//! The library does not panic. Should it ever, no panic unwinds into C: every function is
//! `extern "C"`, which aborts on an unwinding panic, and the bare-metal static library is
//! built with `panic = "abort"` (the thumb targets' default) and the handler below.
#![cfg_attr(target_os = "none", no_std)]
#![deny(missing_docs)]
#![deny(unsafe_op_in_unsafe_fn)]
#![warn(clippy::unwrap_used, clippy::expect_used, clippy::panic)]
#![cfg_attr(test, allow(clippy::unwrap_used, clippy::expect_used, clippy::panic))]

pub mod batch;
pub mod error;
pub mod handle;
pub mod knob;
pub mod knob_config;

pub mod q16;
pub mod tuning;
pub mod value;

pub use error::{StiffspringError, stiffspring_error_name};

/// The bare-metal static library's panic handler: the library does not panic, so this is
/// never reached; if it were, it stops the core in a permanent fault (`udf`) rather than
/// return into C or spin silently, so that a debugger or a watchdog sees it.
#[cfg(all(target_os = "none", feature = "panic-handler"))]
#[panic_handler]
fn panic(_: &core::panic::PanicInfo) -> ! {
    loop {
        // An undefined instruction: a HardFault, whose handler the firmware owns. The
        // loop keeps the type `!` should a handler return.
        // SAFETY: `udf` has no operands and touches no memory; it only raises a fault.
        unsafe { core::arch::asm!("udf #0") };
    }
}
