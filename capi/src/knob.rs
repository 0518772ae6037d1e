//! The haptic knob (`Knob<S>`) in C, in `f32` and Q16.16: made from a
//! [`StiffspringKnobConfig`] (checked then against the loop guarantee), then
//! `stiffspring_knob_f32_update` once per control period with the encoder angle.

use crate::error::{StiffspringError, code};
use crate::handle::{self, Tag};
use crate::knob_config::{self, StiffspringKnobConfig};
use crate::q16;
use core::mem::MaybeUninit;
use stiffspring::knob::{Endstop, KnobEvents, SensorFault};
use stiffspring::{I16F16, Knob, KnobOutput, Scalar};

/// 64-bit words of a [`StiffspringKnobF32`].
pub const STIFFSPRING_KNOB_F32_WORDS: usize = 60;
/// Bytes of a [`StiffspringKnobF32`], for a buffer of one's own.
pub const STIFFSPRING_KNOB_F32_SIZE: usize = STIFFSPRING_KNOB_F32_WORDS * 8;
/// 64-bit words of a [`StiffspringKnobQ16`].
pub const STIFFSPRING_KNOB_Q16_WORDS: usize = 60;
/// Bytes of a [`StiffspringKnobQ16`].
pub const STIFFSPRING_KNOB_Q16_SIZE: usize = STIFFSPRING_KNOB_Q16_WORDS * 8;

const _: () = assert!(handle::fits::<Knob<f32>>(STIFFSPRING_KNOB_F32_SIZE));
const _: () = assert!(handle::fits::<Knob<I16F16>>(STIFFSPRING_KNOB_Q16_SIZE));

const TAG_F32: Tag = Tag::new(7);
const TAG_Q16: Tag = Tag::new(8);

/// Storage for an `f32` knob; `stiffspring_knob_f32_init` fills it.
///
/// ```c
/// static StiffspringKnobF32 knob;
/// ```
#[repr(C)]
pub struct StiffspringKnobF32 {
    opaque: [MaybeUninit<u64>; STIFFSPRING_KNOB_F32_WORDS],
}

/// Storage for a Q16.16 knob; `stiffspring_knob_q16_init` fills it.
///
/// ```c
/// static StiffspringKnobQ16 knob;
/// ```
#[repr(C)]
pub struct StiffspringKnobQ16 {
    opaque: [MaybeUninit<u64>; STIFFSPRING_KNOB_Q16_WORDS],
}

/// Which endstop a period hit, if any.
#[repr(u8)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum StiffspringEndstop {
    /// None.
    None = 0,
    /// The lower end of the range.
    Min = 1,
    /// The upper end of the range.
    Max = 2,
}

/// Why a period's reading was not used, if it was not (the Rust API's `SensorFault`).
#[repr(u8)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum StiffspringSensorFault {
    /// The reading was used.
    None = 0,
    /// A NaN.
    NotANumber = 1,
    /// An infinite angle, or one beyond the range the knob's arithmetic holds.
    OutOfRange = 2,
    /// A reading too far from where the rotor can be.
    Jump = 3,
    /// Readings that agree, of a rotor turning faster than the configured maximum speed.
    TooFast = 4,
}

/// What happened in one period (the Rust API's `KnobEvents`).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct StiffspringKnobEvents {
    /// The detent index changed this period, by this much (its sign says which way).
    pub detent_step: i8,
    /// The rotor went past an endstop this period.
    pub endstop_hit: StiffspringEndstop,
    /// A magnetic detent captured the rotor this period: its index in the sorted list,
    /// or −1.
    pub magnet_captured: i16,
    /// This period's reading was not used, and why.
    pub sensor: StiffspringSensorFault,
    /// The knob took up the readings again after a fault.
    pub resynced: bool,
}

/// One period's output of an `f32` knob.
///
/// ```c
/// StiffspringKnobOutputF32 out;
/// stiffspring_knob_f32_update(&knob, encoder_angle(), &out);
/// set_torque(out.torque * TORQUE_LIMIT);
/// ```
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StiffspringKnobOutputF32 {
    /// The torque to command, as a fraction of the torque limit, in `[−1, 1]`.
    pub torque: f32,
    /// The current detent index.
    pub detent: i32,
    /// What happened this period.
    pub events: StiffspringKnobEvents,
}

/// One period's output of a Q16.16 knob.
///
/// ```c
/// StiffspringKnobOutputQ16 out;
/// stiffspring_knob_q16_update(&knob, encoder_angle_q16(), &out);
/// ```
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct StiffspringKnobOutputQ16 {
    /// The torque to command, as a fraction of the torque limit, in Q16.16 (`[−65536, 65536]`).
    pub torque: i32,
    /// The current detent index.
    pub detent: i32,
    /// What happened this period.
    pub events: StiffspringKnobEvents,
}

impl From<KnobEvents> for StiffspringKnobEvents {
    fn from(e: KnobEvents) -> Self {
        StiffspringKnobEvents {
            detent_step: e.detent_step,
            endstop_hit: match e.endstop_hit {
                None => StiffspringEndstop::None,
                Some(Endstop::Min) => StiffspringEndstop::Min,
                Some(Endstop::Max) => StiffspringEndstop::Max,
            },
            magnet_captured: e.magnet_captured.map_or(-1, i16::from),
            sensor: match e.sensor {
                None => StiffspringSensorFault::None,
                Some(SensorFault::NotANumber) => StiffspringSensorFault::NotANumber,
                Some(SensorFault::OutOfRange) => StiffspringSensorFault::OutOfRange,
                Some(SensorFault::Jump) => StiffspringSensorFault::Jump,
                Some(SensorFault::TooFast) => StiffspringSensorFault::TooFast,
            },
            resynced: e.resynced,
        }
    }
}

impl From<KnobOutput<f32>> for StiffspringKnobOutputF32 {
    fn from(out: KnobOutput<f32>) -> Self {
        StiffspringKnobOutputF32 {
            torque: out.torque,
            detent: out.detent,
            events: out.events.into(),
        }
    }
}

impl From<KnobOutput<I16F16>> for StiffspringKnobOutputQ16 {
    fn from(out: KnobOutput<I16F16>) -> Self {
        StiffspringKnobOutputQ16 {
            torque: q16::to_bits(out.torque),
            detent: out.detent,
            events: out.events.into(),
        }
    }
}

/// # Safety
///
/// As [`handle::init`] and [`handle::get_ref`].
unsafe fn init<S: Scalar>(
    storage: *mut u8,
    size: usize,
    tag: Tag,
    config: *const StiffspringKnobConfig,
    angle: S,
) -> StiffspringError {
    // SAFETY: the caller's contract.
    code(unsafe {
        handle::init(storage, size, tag, || {
            let config = knob_config::read(config)?;
            Ok(Knob::<S>::new(config, angle)?)
        })
    })
}

/// # Safety
///
/// As [`handle::get`] and [`handle::write_out`].
unsafe fn update<S: Scalar, O: From<KnobOutput<S>>>(
    storage: *mut u8,
    tag: Tag,
    angle: S,
    out: *mut O,
) -> StiffspringError {
    // SAFETY: the caller's contract.
    code(unsafe {
        handle::get::<Knob<S>>(storage, tag)
            .and_then(|k| handle::write_out(out, k.update(angle).into()))
    })
}

/// A knob at rest at `initial_angle` (radians), made from `config`, written into `storage`
/// of `size` bytes. The configuration is checked here, against the loop guarantee of the
/// Rust API's `Knob::new`; the knob copies it (the configuration may be dropped after).
///
/// Errors: what `Knob::new` refuses, by kind: `OUT_OF_RANGE` (a stiffness, damping or
/// rate outside what the guarantee allows, an angle beyond the backend's range),
/// `NOT_FINITE`, `NEEDS_ENDSTOPS`, `CAPACITY_FULL`; `NULL_POINTER`, `BUFFER_TOO_SMALL`,
/// `MISALIGNED` for the storage, `NOT_INITIALISED` or `DROPPED` for the configuration. On
/// an error the storage is unchanged.
///
/// ```c
/// StiffspringKnobF32 knob;
/// if (stiffspring_knob_f32_init(&knob, sizeof knob, &config, 0.0f) != STIFFSPRING_ERROR_OK) { /* ... */ }
/// ```
///
/// # Safety
///
/// `storage` is null or points to `size` bytes the caller owns; `config` is null or points
/// to a `StiffspringKnobConfig`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn stiffspring_knob_f32_init(
    storage: *mut StiffspringKnobF32,
    size: usize,
    config: *const StiffspringKnobConfig,
    initial_angle: f32,
) -> StiffspringError {
    // SAFETY: this function's contract.
    unsafe { init::<f32>(storage.cast(), size, TAG_F32, config, initial_angle) }
}

/// Ends the knob: later calls on it return `DROPPED` until it is initialised again.
///
/// ```c
/// stiffspring_knob_f32_drop(&knob);
/// ```
///
/// # Safety
///
/// `knob` is null or points to a `StiffspringKnobF32` the caller owns.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn stiffspring_knob_f32_drop(
    knob: *mut StiffspringKnobF32,
) -> StiffspringError {
    // SAFETY: this function's contract.
    code(unsafe { handle::drop::<Knob<f32>>(knob.cast(), TAG_F32) })
}

/// One control period: from the encoder `angle` (radians), the torque to command and the
/// events, into `out`. Cannot fail on the angle: a NaN, an angle out of reach or one the
/// rotor cannot have moved to is a sensor fault in `out->events.sensor` (the knob holds
/// its last torque, then none).
///
/// ```c
/// StiffspringKnobOutputF32 out;
/// stiffspring_knob_f32_update(&knob, angle, &out);
/// if (out.events.detent_step != 0) ui_send(out.detent);
/// ```
///
/// # Safety
///
/// As [`stiffspring_knob_f32_drop`]; `out` is null or valid for a write.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn stiffspring_knob_f32_update(
    knob: *mut StiffspringKnobF32,
    angle: f32,
    out: *mut StiffspringKnobOutputF32,
) -> StiffspringError {
    // SAFETY: this function's contract.
    unsafe { update::<f32, _>(knob.cast(), TAG_F32, angle, out) }
}

/// Takes up the encoder at `angle` at once, at rest (after the motor was off, or the
/// encoder re-zeroed). Cannot fail on the angle: a NaN or out-of-range one keeps the last
/// good angle.
///
/// ```c
/// stiffspring_knob_f32_reset(&knob, angle);
/// ```
///
/// # Safety
///
/// As [`stiffspring_knob_f32_drop`].
#[unsafe(no_mangle)]
pub unsafe extern "C" fn stiffspring_knob_f32_reset(
    knob: *mut StiffspringKnobF32,
    angle: f32,
) -> StiffspringError {
    // SAFETY: this function's contract.
    code(unsafe { handle::get::<Knob<f32>>(knob.cast(), TAG_F32) }.map(|k| k.reset(angle)))
}

/// The current detent index, into `out`.
///
/// ```c
/// int32_t detent;
/// stiffspring_knob_f32_detent(&knob, &detent);
/// ```
///
/// # Safety
///
/// As [`stiffspring_knob_f32_drop`]; `out` is null or valid for a write.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn stiffspring_knob_f32_detent(
    knob: *const StiffspringKnobF32,
    out: *mut i32,
) -> StiffspringError {
    // SAFETY: this function's contract.
    code(unsafe {
        handle::get_ref::<Knob<f32>>(knob.cast(), TAG_F32)
            .and_then(|k| handle::write_out(out, k.detent()))
    })
}

/// A Q16.16 knob at rest at `initial_angle` (radians, Q16.16), made from `config`, written into `storage`
/// of `size` bytes. The configuration is checked here, against the loop guarantee of the
/// Rust API's `Knob::new`; the knob copies it (the configuration may be dropped after).
///
/// Errors: what `Knob::new` refuses, by kind: `OUT_OF_RANGE` (a stiffness, damping or
/// rate outside what the guarantee allows, an angle beyond the backend's range),
/// `NOT_FINITE`, `NEEDS_ENDSTOPS`, `CAPACITY_FULL`; `NULL_POINTER`, `BUFFER_TOO_SMALL`,
/// `MISALIGNED` for the storage, `NOT_INITIALISED` or `DROPPED` for the configuration. On
/// an error the storage is unchanged.
///
/// ```c
/// StiffspringKnobQ16 knob;
/// if (stiffspring_knob_q16_init(&knob, sizeof knob, &config, 0) != STIFFSPRING_ERROR_OK) { /* ... */ }
/// ```
///
/// # Safety
///
/// `storage` is null or points to `size` bytes the caller owns; `config` is null or points
/// to a `StiffspringKnobConfig`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn stiffspring_knob_q16_init(
    storage: *mut StiffspringKnobQ16,
    size: usize,
    config: *const StiffspringKnobConfig,
    initial_angle: i32,
) -> StiffspringError {
    // SAFETY: this function's contract.
    unsafe {
        init::<I16F16>(
            storage.cast(),
            size,
            TAG_Q16,
            config,
            q16::from_bits(initial_angle),
        )
    }
}

/// Ends the knob: later calls on it return `DROPPED` until it is initialised again.
///
/// ```c
/// stiffspring_knob_q16_drop(&knob);
/// ```
///
/// # Safety
///
/// `knob` is null or points to a `StiffspringKnobQ16` the caller owns.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn stiffspring_knob_q16_drop(
    knob: *mut StiffspringKnobQ16,
) -> StiffspringError {
    // SAFETY: this function's contract.
    code(unsafe { handle::drop::<Knob<I16F16>>(knob.cast(), TAG_Q16) })
}

/// One control period: from the encoder `angle` (radians, Q16.16), the torque to command and the
/// events, into `out`. Cannot fail on the angle: a NaN, an angle out of reach or one the
/// rotor cannot have moved to is a sensor fault in `out->events.sensor` (the knob holds
/// its last torque, then none).
///
/// ```c
/// StiffspringKnobOutputQ16 out;
/// stiffspring_knob_q16_update(&knob, angle, &out);
/// if (out.events.detent_step != 0) ui_send(out.detent);
/// ```
///
/// # Safety
///
/// As [`stiffspring_knob_q16_drop`]; `out` is null or valid for a write.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn stiffspring_knob_q16_update(
    knob: *mut StiffspringKnobQ16,
    angle: i32,
    out: *mut StiffspringKnobOutputQ16,
) -> StiffspringError {
    // SAFETY: this function's contract.
    unsafe { update::<I16F16, _>(knob.cast(), TAG_Q16, q16::from_bits(angle), out) }
}

/// Takes up the encoder at `angle` at once, at rest (after the motor was off, or the
/// encoder re-zeroed). Cannot fail on the angle: a NaN or out-of-range one keeps the last
/// good angle.
///
/// ```c
/// stiffspring_knob_q16_reset(&knob, angle);
/// ```
///
/// # Safety
///
/// As [`stiffspring_knob_q16_drop`].
#[unsafe(no_mangle)]
pub unsafe extern "C" fn stiffspring_knob_q16_reset(
    knob: *mut StiffspringKnobQ16,
    angle: i32,
) -> StiffspringError {
    // SAFETY: this function's contract.
    code(
        unsafe { handle::get::<Knob<I16F16>>(knob.cast(), TAG_Q16) }
            .map(|k| k.reset(q16::from_bits(angle))),
    )
}

/// The current detent index, into `out`.
///
/// ```c
/// int32_t detent;
/// stiffspring_knob_q16_detent(&knob, &detent);
/// ```
///
/// # Safety
///
/// As [`stiffspring_knob_q16_drop`]; `out` is null or valid for a write.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn stiffspring_knob_q16_detent(
    knob: *const StiffspringKnobQ16,
    out: *mut i32,
) -> StiffspringError {
    // SAFETY: this function's contract.
    code(unsafe {
        handle::get_ref::<Knob<I16F16>>(knob.cast(), TAG_Q16)
            .and_then(|k| handle::write_out(out, k.detent()))
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::knob_config::*;
    use core::mem::size_of;
    use core::ptr::null_mut;
    use stiffspring::KnobConfig;

    fn config() -> StiffspringKnobConfig {
        let mut c = StiffspringKnobConfig::zeroed_for_tests();
        // SAFETY: our storage.
        unsafe {
            let size = size_of::<StiffspringKnobConfig>();
            assert_eq!(
                stiffspring_knob_config_init(&mut c, size, 1_000.0, 1e-5, 0.05, 16384),
                StiffspringError::Ok
            );
            assert_eq!(
                stiffspring_knob_config_endstops(&mut c, 0.0, 3.0),
                StiffspringError::Ok
            );
            assert_eq!(
                stiffspring_knob_config_detent_count(&mut c, 16),
                StiffspringError::Ok
            );
            assert_eq!(
                stiffspring_knob_config_detent_stiffness(&mut c, 0.05),
                StiffspringError::Ok
            );
        }
        c
    }

    #[test]
    fn the_c_knob_gives_the_rust_knobs_torques_to_the_bit() {
        let rust_config = KnobConfig::new(1_000.0, 1e-5, 0.05, 16384)
            .endstops(0.0, 3.0)
            .detent_count(16)
            .detent_stiffness(0.05);
        let mut rust = Knob::<f32>::new(&rust_config, 0.0).unwrap();
        let mut rust_q = Knob::<I16F16>::new(&rust_config, I16F16::ZERO).unwrap();
        let c = config();
        let mut k = StiffspringKnobF32 {
            opaque: [handle::ZERO; STIFFSPRING_KNOB_F32_WORDS],
        };
        let mut kq = StiffspringKnobQ16 {
            opaque: [handle::ZERO; STIFFSPRING_KNOB_Q16_WORDS],
        };
        // SAFETY: our storage and out-pointers.
        unsafe {
            assert_eq!(
                stiffspring_knob_f32_init(&mut k, size_of::<StiffspringKnobF32>(), &c, 0.0),
                StiffspringError::Ok
            );
            assert_eq!(
                stiffspring_knob_q16_init(&mut kq, size_of::<StiffspringKnobQ16>(), &c, 0),
                StiffspringError::Ok
            );
            let mut detents = 0;
            let mut out = StiffspringKnobOutputF32::from(rust.update(0.0));
            stiffspring_knob_f32_update(&mut k, 0.0, &mut out);
            let mut outq = StiffspringKnobOutputQ16::from(rust_q.update(I16F16::ZERO));
            stiffspring_knob_q16_update(&mut kq, 0, &mut outq);
            // A slow turn up through every detent (3.4 rad in 4 s at 1 kHz).
            for n in 0..4000 {
                let angle = 3.4 * (n as f32 / 4000.0) - 0.2;
                let expected = StiffspringKnobOutputF32::from(rust.update(angle));
                let e = stiffspring_knob_f32_update(&mut k, angle, &mut out);
                assert_eq!(e, StiffspringError::Ok);
                assert_eq!(
                    out.torque.to_bits(),
                    expected.torque.to_bits(),
                    "period {n}"
                );
                assert_eq!(out, expected);
                detents += i32::from(out.events.detent_step != 0);
                let aq = I16F16::from_num(angle);
                let expected = StiffspringKnobOutputQ16::from(rust_q.update(aq));
                let e = stiffspring_knob_q16_update(&mut kq, q16::to_bits(aq), &mut outq);
                assert_eq!(e, StiffspringError::Ok);
                assert_eq!(outq, expected);
            }
            assert!(detents > 0);
        }
    }

    #[test]
    fn refused_configurations_and_bad_readings_are_codes() {
        let mut c = config();
        let mut k = StiffspringKnobF32 {
            opaque: [handle::ZERO; STIFFSPRING_KNOB_F32_WORDS],
        };
        let size = size_of::<StiffspringKnobF32>();
        // SAFETY: our storage and out-pointers.
        unsafe {
            assert_eq!(
                stiffspring_knob_f32_init(&mut k, size, &c, f32::NAN),
                StiffspringError::NotFinite
            );
            assert_eq!(
                stiffspring_knob_f32_init(&mut k, size - 8, &c, 0.0),
                StiffspringError::BufferTooSmall
            );
            let unset = StiffspringKnobConfig::zeroed_for_tests();
            assert_eq!(
                stiffspring_knob_f32_init(&mut k, size, &unset, 0.0),
                StiffspringError::NotInitialised
            );
            stiffspring_knob_config_detent_stiffness(&mut c, 5.0); // far beyond the guarantee
            assert_eq!(
                stiffspring_knob_f32_init(&mut k, size, &c, 0.0),
                StiffspringError::OutOfRange
            );
            let mut no_stops = StiffspringKnobConfig::zeroed_for_tests();
            stiffspring_knob_config_init(
                &mut no_stops,
                size_of::<StiffspringKnobConfig>(),
                1_000.0,
                1e-5,
                0.05,
                16384,
            );
            stiffspring_knob_config_detent_count(&mut no_stops, 4);
            stiffspring_knob_config_detent_stiffness(&mut no_stops, 0.05);
            assert_eq!(
                stiffspring_knob_f32_init(&mut k, size, &no_stops, 0.0),
                StiffspringError::NeedsEndstops
            );
            assert_eq!(
                stiffspring_knob_config_latency(&mut c, 7),
                StiffspringError::OutOfRange
            );
            let magnets = [0.0; 9];
            assert_eq!(
                stiffspring_knob_config_magnets(&mut c, magnets.as_ptr(), 9),
                StiffspringError::CapacityFull
            );
            assert_eq!(
                stiffspring_knob_config_magnets(&mut c, core::ptr::null(), 2),
                StiffspringError::NullPointer
            );
            assert!(handle::is_zero(&k.opaque), "nothing was written");

            let c = config();
            assert_eq!(
                stiffspring_knob_f32_init(&mut k, size, &c, 0.0),
                StiffspringError::Ok
            );
            let mut out = StiffspringKnobOutputF32::from(KnobOutput::<f32> {
                torque: 0.0,
                detent: 0,
                events: KnobEvents::default(),
            });
            assert_eq!(
                stiffspring_knob_f32_update(&mut k, f32::NAN, &mut out),
                StiffspringError::Ok
            );
            assert_eq!(out.events.sensor, StiffspringSensorFault::NotANumber);
            assert_eq!(
                stiffspring_knob_f32_update(&mut k, 0.0, null_mut()),
                StiffspringError::NullPointer
            );
            assert_eq!(
                stiffspring_knob_f32_reset(&mut k, 1.0),
                StiffspringError::Ok
            );
            let mut detent = -1;
            assert_eq!(
                stiffspring_knob_f32_detent(&k, &mut detent),
                StiffspringError::Ok
            );
            assert_eq!(detent, 5);
            assert_eq!(stiffspring_knob_f32_drop(&mut k), StiffspringError::Ok);
            assert_eq!(
                stiffspring_knob_f32_update(&mut k, 0.0, &mut out),
                StiffspringError::Dropped
            );
        }
    }
}
