//! A knob's configuration in C (`KnobConfig`): a builder in storage the caller owns. The
//! setters only record their arguments, as in Rust; `stiffspring_knob_f32_init` (and the
//! Q16.16 one) checks everything at once against the loop guarantee.

use crate::error::{StiffspringError, code};
use crate::handle::{self, Tag};
use core::mem::MaybeUninit;
use stiffspring::KnobConfig;
use stiffspring::knob::{Latency, MAX_MAGNETS};

/// 64-bit words of a [`StiffspringKnobConfig`].
pub const STIFFSPRING_KNOB_CONFIG_WORDS: usize = 37;
/// Bytes of a [`StiffspringKnobConfig`], for a buffer of one's own.
pub const STIFFSPRING_KNOB_CONFIG_SIZE: usize = STIFFSPRING_KNOB_CONFIG_WORDS * 8;
/// The most magnetic detents a knob has.
pub const STIFFSPRING_KNOB_MAX_MAGNETS: usize = MAX_MAGNETS;

const _: () = assert!(handle::fits::<KnobConfig>(STIFFSPRING_KNOB_CONFIG_SIZE));

pub(crate) const TAG: Tag = Tag::new(6);

/// Storage for a knob's configuration; `stiffspring_knob_config_init` fills it.
///
/// ```c
/// StiffspringKnobConfig config;
/// stiffspring_knob_config_init(&config, sizeof config, 1000.0, 1e-5, 0.05, 16384);
/// stiffspring_knob_config_endstops(&config, 0.0, 3.0);
/// stiffspring_knob_config_detent_count(&config, 16);
/// stiffspring_knob_config_detent_stiffness(&config, 0.05);
/// ```
#[repr(C)]
pub struct StiffspringKnobConfig {
    opaque: [MaybeUninit<u64>; STIFFSPRING_KNOB_CONFIG_WORDS],
}

/// When the torque acts, as the Rust API's `Latency`.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum StiffspringLatency {
    /// The torque computed from a reading acts within the same period.
    SameStep = 0,
    /// The torque computed from a reading acts over the next period (SimpleFOC-style
    /// firmware); the default.
    OneStep = 1,
}

#[cfg(test)]
impl StiffspringKnobConfig {
    /// Zeroed storage, as a C `static` gives.
    pub(crate) fn zeroed_for_tests() -> Self {
        StiffspringKnobConfig {
            opaque: [handle::ZERO; STIFFSPRING_KNOB_CONFIG_WORDS],
        }
    }
}

/// The configuration in `config`, by reference (a copy would cost a `memcpy`).
///
/// # Safety
///
/// As [`handle::get_ref`].
pub(crate) unsafe fn read<'a>(
    config: *const StiffspringKnobConfig,
) -> Result<&'a KnobConfig, StiffspringError> {
    // SAFETY: the caller's contract.
    unsafe { handle::get_ref::<KnobConfig>(config.cast(), TAG) }
}

/// Replaces the configuration in `config` by `f` of it.
///
/// # Safety
///
/// As [`handle::get`].
unsafe fn edit(
    config: *mut StiffspringKnobConfig,
    f: impl FnOnce(KnobConfig) -> KnobConfig,
) -> StiffspringError {
    // SAFETY: the caller's contract.
    code(unsafe { handle::get::<KnobConfig>(config.cast(), TAG) }.map(|c| *c = f(*c)))
}

/// A knob run at `rate` hertz, driving a rotor of moment of inertia `inertia` (kg·m²)
/// with a motor that gives at most `torque_limit` (N·m), read by an encoder of
/// `counts_per_turn`; no detents, endstops or springs yet, a damping ratio of 0.7, one
/// period of latency, a hysteresis of two counts (the Rust API's `KnobConfig::new`).
/// Nothing is checked until a knob is made from it.
///
/// ```c
/// StiffspringKnobConfig config;
/// stiffspring_knob_config_init(&config, sizeof config, 1000.0, 1e-5, 0.05, 16384);
/// ```
///
/// # Safety
///
/// `storage` is null or points to `size` bytes the caller owns.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn stiffspring_knob_config_init(
    storage: *mut StiffspringKnobConfig,
    size: usize,
    rate: f64,
    inertia: f64,
    torque_limit: f64,
    counts_per_turn: u32,
) -> StiffspringError {
    let config = KnobConfig::new(rate, inertia, torque_limit, counts_per_turn);
    // SAFETY: this function's contract.
    code(unsafe { handle::init(storage.cast(), size, TAG, || Ok(config)) })
}

/// When the torque acts: `STIFFSPRING_LATENCY_ONE_STEP` (the default) or
/// `STIFFSPRING_LATENCY_SAME_STEP`; any other integer is `OUT_OF_RANGE`.
///
/// ```c
/// stiffspring_knob_config_latency(&config, STIFFSPRING_LATENCY_ONE_STEP);
/// ```
///
/// # Safety
///
/// `config` is null or points to a `StiffspringKnobConfig` the caller owns.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn stiffspring_knob_config_latency(
    config: *mut StiffspringKnobConfig,
    latency: i32,
) -> StiffspringError {
    let latency = match latency {
        0 => Latency::SameStep,
        1 => Latency::OneStep,
        _ => return StiffspringError::OutOfRange,
    };
    // SAFETY: this function's contract.
    unsafe { edit(config, |c| c.latency(latency)) }
}

/// The magnetic detents' angles (radians): `count` of them from `angles`, at most
/// `STIFFSPRING_KNOB_MAX_MAGNETS` (more is `CAPACITY_FULL`, and the configuration is
/// unchanged).
///
/// ```c
/// static const double magnets[] = {0.0, 1.0};
/// stiffspring_knob_config_magnets(&config, magnets, 2);
/// ```
///
/// # Safety
///
/// `config` as in [`stiffspring_knob_config_latency`]; `angles` is null (with `count` 0)
/// or valid for reads of `count` doubles.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn stiffspring_knob_config_magnets(
    config: *mut StiffspringKnobConfig,
    angles: *const f64,
    count: usize,
) -> StiffspringError {
    if count > MAX_MAGNETS {
        return StiffspringError::CapacityFull;
    }
    let mut read = [0.0; MAX_MAGNETS];
    for (i, angle) in read.iter_mut().enumerate().take(count) {
        // SAFETY: `i < count`: within the caller's array (this function's contract).
        match unsafe { handle::read_in(angles.wrapping_add(i)) } {
            Ok(a) => *angle = a,
            Err(e) => return e,
        }
    }
    // SAFETY: this function's contract.
    unsafe { edit(config, |c| c.magnets(&read[..count])) }
}

/// The damping ratio of the designed spring (default 0.7). As the Rust API's `KnobConfig::damping_ratio`; checked when a knob is made.
///
/// ```c
/// stiffspring_knob_config_damping_ratio(&config, 0.7);
/// ```
///
/// # Safety
///
/// As [`stiffspring_knob_config_latency`].
#[unsafe(no_mangle)]
pub unsafe extern "C" fn stiffspring_knob_config_damping_ratio(
    config: *mut StiffspringKnobConfig,
    zeta: f64,
) -> StiffspringError {
    // SAFETY: this function's contract.
    unsafe { edit(config, |c| c.damping_ratio(zeta)) }
}

/// The damping in N·m·s/rad, instead of a ratio. As the Rust API's `KnobConfig::damping`; checked when a knob is made.
///
/// ```c
/// stiffspring_knob_config_damping(&config, 2e-4);
/// ```
///
/// # Safety
///
/// As [`stiffspring_knob_config_latency`].
#[unsafe(no_mangle)]
pub unsafe extern "C" fn stiffspring_knob_config_damping(
    config: *mut StiffspringKnobConfig,
    damping: f64,
) -> StiffspringError {
    // SAFETY: this function's contract.
    unsafe { edit(config, |c| c.damping(damping)) }
}

/// Endstops at `min` and `max` (radians). As the Rust API's `KnobConfig::endstops`; checked when a knob is made.
///
/// ```c
/// stiffspring_knob_config_endstops(&config, 0.0, 3.0);
/// ```
///
/// # Safety
///
/// As [`stiffspring_knob_config_latency`].
#[unsafe(no_mangle)]
pub unsafe extern "C" fn stiffspring_knob_config_endstops(
    config: *mut StiffspringKnobConfig,
    min: f64,
    max: f64,
) -> StiffspringError {
    // SAFETY: this function's contract.
    unsafe { edit(config, |c| c.endstops(min, max)) }
}

/// The endstops' stiffness in N·m/rad, added beyond the stops (default: up to 4 times the
/// stiffness inside the range, the stiffest that meets the loop guarantee). As the Rust API's `KnobConfig::endstop_stiffness`; checked when a knob is made.
///
/// ```c
/// stiffspring_knob_config_endstop_stiffness(&config, 0.15);
/// ```
///
/// # Safety
///
/// As [`stiffspring_knob_config_latency`].
#[unsafe(no_mangle)]
pub unsafe extern "C" fn stiffspring_knob_config_endstop_stiffness(
    config: *mut StiffspringKnobConfig,
    stiffness: f64,
) -> StiffspringError {
    // SAFETY: this function's contract.
    unsafe { edit(config, |c| c.endstop_stiffness(stiffness)) }
}

/// This many detents spread over the endstops (which it needs). As the Rust API's `KnobConfig::detent_count`; checked when a knob is made.
///
/// ```c
/// stiffspring_knob_config_detent_count(&config, 16);
/// ```
///
/// # Safety
///
/// As [`stiffspring_knob_config_latency`].
#[unsafe(no_mangle)]
pub unsafe extern "C" fn stiffspring_knob_config_detent_count(
    config: *mut StiffspringKnobConfig,
    count: u32,
) -> StiffspringError {
    // SAFETY: this function's contract.
    unsafe { edit(config, |c| c.detent_count(count)) }
}

/// Detents this wide (radians), from the detent origin. As the Rust API's `KnobConfig::detent_width`; checked when a knob is made.
///
/// ```c
/// stiffspring_knob_config_detent_width(&config, 0.1);
/// ```
///
/// # Safety
///
/// As [`stiffspring_knob_config_latency`].
#[unsafe(no_mangle)]
pub unsafe extern "C" fn stiffspring_knob_config_detent_width(
    config: *mut StiffspringKnobConfig,
    width: f64,
) -> StiffspringError {
    // SAFETY: this function's contract.
    unsafe { edit(config, |c| c.detent_width(width)) }
}

/// Where detent 0 is centred without endstops (radians, default 0). As the Rust API's `KnobConfig::detent_origin`; checked when a knob is made.
///
/// ```c
/// stiffspring_knob_config_detent_origin(&config, 0.0);
/// ```
///
/// # Safety
///
/// As [`stiffspring_knob_config_latency`].
#[unsafe(no_mangle)]
pub unsafe extern "C" fn stiffspring_knob_config_detent_origin(
    config: *mut StiffspringKnobConfig,
    origin: f64,
) -> StiffspringError {
    // SAFETY: this function's contract.
    unsafe { edit(config, |c| c.detent_origin(origin)) }
}

/// The detents' stiffness in N·m/rad. As the Rust API's `KnobConfig::detent_stiffness`; checked when a knob is made.
///
/// ```c
/// stiffspring_knob_config_detent_stiffness(&config, 0.05);
/// ```
///
/// # Safety
///
/// As [`stiffspring_knob_config_latency`].
#[unsafe(no_mangle)]
pub unsafe extern "C" fn stiffspring_knob_config_detent_stiffness(
    config: *mut StiffspringKnobConfig,
    stiffness: f64,
) -> StiffspringError {
    // SAFETY: this function's contract.
    unsafe { edit(config, |c| c.detent_stiffness(stiffness)) }
}

/// The detents' peak torque in N·m, instead of a stiffness. As the Rust API's `KnobConfig::detent_torque`; checked when a knob is made.
///
/// ```c
/// stiffspring_knob_config_detent_torque(&config, 0.01);
/// ```
///
/// # Safety
///
/// As [`stiffspring_knob_config_latency`].
#[unsafe(no_mangle)]
pub unsafe extern "C" fn stiffspring_knob_config_detent_torque(
    config: *mut StiffspringKnobConfig,
    peak: f64,
) -> StiffspringError {
    // SAFETY: this function's contract.
    unsafe { edit(config, |c| c.detent_torque(peak)) }
}

/// Where a detent switches to the next, as a fraction of its width (default 0.55). As the Rust API's `KnobConfig::snap_point`; checked when a knob is made.
///
/// ```c
/// stiffspring_knob_config_snap_point(&config, 0.55);
/// ```
///
/// # Safety
///
/// As [`stiffspring_knob_config_latency`].
#[unsafe(no_mangle)]
pub unsafe extern "C" fn stiffspring_knob_config_snap_point(
    config: *mut StiffspringKnobConfig,
    fraction: f64,
) -> StiffspringError {
    // SAFETY: this function's contract.
    unsafe { edit(config, |c| c.snap_point(fraction)) }
}

/// The events' hysteresis (radians; default two encoder counts). As the Rust API's `KnobConfig::hysteresis`; checked when a knob is made.
///
/// ```c
/// stiffspring_knob_config_hysteresis(&config, 2.0 * 6.283185307179586 / 16384);
/// ```
///
/// # Safety
///
/// As [`stiffspring_knob_config_latency`].
#[unsafe(no_mangle)]
pub unsafe extern "C" fn stiffspring_knob_config_hysteresis(
    config: *mut StiffspringKnobConfig,
    angle: f64,
) -> StiffspringError {
    // SAFETY: this function's contract.
    unsafe { edit(config, |c| c.hysteresis(angle)) }
}

/// A spring of `stiffness` N·m/rad back to `centre` (radians). As the Rust API's `KnobConfig::return_to_centre`; checked when a knob is made.
///
/// ```c
/// stiffspring_knob_config_return_to_centre(&config, 0.0, 0.02);
/// ```
///
/// # Safety
///
/// As [`stiffspring_knob_config_latency`].
#[unsafe(no_mangle)]
pub unsafe extern "C" fn stiffspring_knob_config_return_to_centre(
    config: *mut StiffspringKnobConfig,
    centre: f64,
    stiffness: f64,
) -> StiffspringError {
    // SAFETY: this function's contract.
    unsafe { edit(config, |c| c.return_to_centre(centre, stiffness)) }
}

/// The magnetic detents' stiffness in N·m/rad. As the Rust API's `KnobConfig::magnet_stiffness`; checked when a knob is made.
///
/// ```c
/// stiffspring_knob_config_magnet_stiffness(&config, 0.05);
/// ```
///
/// # Safety
///
/// As [`stiffspring_knob_config_latency`].
#[unsafe(no_mangle)]
pub unsafe extern "C" fn stiffspring_knob_config_magnet_stiffness(
    config: *mut StiffspringKnobConfig,
    stiffness: f64,
) -> StiffspringError {
    // SAFETY: this function's contract.
    unsafe { edit(config, |c| c.magnet_stiffness(stiffness)) }
}

/// How near a magnet captures the rotor (radians). As the Rust API's `KnobConfig::magnet_radius`; checked when a knob is made.
///
/// ```c
/// stiffspring_knob_config_magnet_radius(&config, 0.05);
/// ```
///
/// # Safety
///
/// As [`stiffspring_knob_config_latency`].
#[unsafe(no_mangle)]
pub unsafe extern "C" fn stiffspring_knob_config_magnet_radius(
    config: *mut StiffspringKnobConfig,
    radius: f64,
) -> StiffspringError {
    // SAFETY: this function's contract.
    unsafe { edit(config, |c| c.magnet_radius(radius)) }
}

/// The fastest the rotor turns (rad/s): above it the torque goes off, and a reading that
/// moves farther than `max_speed·dt` is a sensor fault (default: none). As the Rust API's `KnobConfig::max_speed`; checked when a knob is made.
///
/// ```c
/// stiffspring_knob_config_max_speed(&config, 200.0);
/// ```
///
/// # Safety
///
/// As [`stiffspring_knob_config_latency`].
#[unsafe(no_mangle)]
pub unsafe extern "C" fn stiffspring_knob_config_max_speed(
    config: *mut StiffspringKnobConfig,
    max_speed: f64,
) -> StiffspringError {
    // SAFETY: this function's contract.
    unsafe { edit(config, |c| c.max_speed(max_speed)) }
}
