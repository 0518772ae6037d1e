//! The second step of the set-up: the loop design of a validated configuration. The
//! damping, the default endstop, the velocity filter, each zone's loop against the
//! guarantee of [`stability`](super::stability), one count's torque, and the backend's
//! range; all in `f64`, all `const fn`.
//!
//! A design that fails says which zone and which bound; the error the user sees names
//! the argument they set instead (the detent's stiffness, the encoder's counts per turn,
//! the rate), with the value of it that would pass, found by running the same design
//! again ([`KnobConfig::detent_stiffness_limit`] is one of these searches).

use super::config::{Damping, DetentSpring, KnobConfig, Latency, MAX_MAGNETS};
use super::error::{KnobError, Limit, below};
use super::stability::{
    COUNT_TORQUE_FRACTION, DECAY_FRACTION, FILTER_LADDER, LoopCoefficients, MIN_FILTER_ALPHA,
    Plant, ZONES, decay_radius, slowest_decay, sqrt,
};
use super::validate::{Checked, Grid, MIN_LOOP_RATE, libm_free_floor, validate};
use crate::error::{Bound, Error, Parameter, tri};
use crate::scalar::Scalar;

/// Zones: inside the range and free, inside and held by a magnet, beyond an endstop.
pub(crate) const FREE: usize = 0;
pub(crate) const MAGNET: usize = 1;
pub(crate) const BEYOND: usize = 2;

/// The multiples of the inside stiffness tried for the default endstop, stiffest first.
/// At most 4×: the endstop zone then keeps a damping ratio of `ζ/√5` (0.31 at the default
/// 0.7), so that a knob flicked into the stop bounces little. Down to 1/16 before the
/// detent itself is refused: an endstop that adds a sixteenth of the detent still stops
/// the rotor (beyond the stop the detent field holds it too).
const ENDSTOP_MULTIPLES: [f64; 7] = [4.0, 2.0, 1.0, 0.5, 0.25, 0.125, 0.0625];

/// A designed knob, in `f64`: what the backend's values are prepared from.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub(crate) struct Design {
    pub(crate) dt: f64,
    /// The rotor's inertia, kg·m² (the sensor screen's jolt).
    pub(crate) inertia: f64,
    /// The configured maximum speed, rad/s (checked positive).
    pub(crate) max_speed: Option<f64>,
    pub(crate) torque_limit: f64,
    /// One encoder count, rad: the rest zone.
    pub(crate) count: f64,
    /// The largest angle magnitude the hot path takes (inputs are clamped to it).
    pub(crate) reach: f64,
    pub(crate) bounds: Option<(f64, f64)>,
    pub(crate) grid: Option<Grid>,
    pub(crate) hysteresis: f64,
    pub(crate) return_centre: f64,
    pub(crate) magnets: [f64; MAX_MAGNETS],
    pub(crate) magnet_count: usize,
    pub(crate) magnet_radius: f64,
    /// Stiffness of each layer, N·m/rad.
    pub(crate) detent: f64,
    pub(crate) magnet: f64,
    pub(crate) ret: f64,
    pub(crate) endstop: f64,
    /// The damping, N·m·s/rad, and the velocity filter's `α`.
    pub(crate) damping: f64,
    pub(crate) alpha: f64,
    /// The damper's state scale: a power of two up to `law::STATE_SCALE`.
    pub(crate) state_scale: f64,
    /// Each zone's loop, `None` where the zone cannot occur.
    pub(crate) zones: [Option<LoopCoefficients>; 3],
    pub(crate) zone_stiffness: [f64; 3],
    /// The play's half-width, in encoder counts ([`play_counts`]).
    pub(crate) play_counts: f64,
}

/// Why a design failed, before the error is put in the user's terms.
#[derive(Clone, Copy, Debug)]
pub(crate) enum Failure {
    /// Already in the user's terms.
    Refused(KnobError),
    /// The damper alone fails the guarantee.
    Damper,
    /// A zone's loop fails the guarantee with every filter.
    Loop(usize),
    /// One count commands `ratio` times the most it may in a zone.
    Count(usize, f64),
}

/// The slowest decay rate over the zones that occur (1/s).
const fn zone_decays(
    free: f64,
    held: f64,
    has_magnets: bool,
    beyond: Option<f64>,
    damping: f64,
    inertia: f64,
) -> f64 {
    let mut s = slowest_decay(free, damping, inertia);
    if has_magnets {
        s = s.min(slowest_decay(held, damping, inertia));
    }
    if let Some(k) = beyond {
        s = s.min(slowest_decay(k, damping, inertia));
    }
    s
}

/// The frequency the filter's time constant is measured against: the higher of the
/// natural frequency `√(K/J)` and the damper's `B/J`.
const fn reference_frequency(stiffness: f64, damping: f64, inertia: f64) -> f64 {
    sqrt(stiffness / inertia).max(damping / inertia)
}

/// The stiffest spring with damping ratio `zeta` that meets the guarantee on its own
/// without a filter (bisection on `C_k`; a knob with no stiffness inside its range).
const fn top_stiffness(zeta: f64, dt: f64, inertia: f64, latency: Latency) -> f64 {
    let (mut lo, mut hi) = (0.0, 1.0);
    let mut step = 0;
    while step < 48 {
        step += 1;
        let ck = 0.5 * (lo + hi);
        // In dimensionless form: C_k = K·dt²/J, C_d = 2ζ√C_k, decay σ·dt from the same.
        let cd = 2.0 * zeta * sqrt(ck);
        let p = Plant {
            dt: 1.0,
            inertia: 1.0,
            damping: cd,
            latency,
            radius: decay_radius(DECAY_FRACTION * slowest_decay(ck, cd, 1.0)),
        };
        if p.zone_ok(ck, 1.0) {
            lo = ck;
        } else {
            hi = ck;
        }
    }
    lo * inertia / (dt * dt)
}

/// The least filter step `α` of backend `S`: fixed point keeps its filter state's
/// truncation errors for about `1/α` periods ([`MIN_FILTER_ALPHA`]); a float does not.
const fn least_alpha<S: Scalar>() -> f64 {
    if S::RESOLUTION > 0.0 {
        MIN_FILTER_ALPHA
    } else {
        1.0 / 4096.0
    }
}

/// The filter `α` whose damper keeps one count's torque within `most` in every zone
/// (`stiffness` where `present`): one count through the filtered damper commands
/// `B·count/(T_f + dt)` at most (the first period's kick), so `T_f + dt` must reach
/// `B·count/(most − K·count)`, a time that does not depend on the rate. `None` when a
/// spring alone is over the bound, or the filter would be longer than backend `S` keeps.
///
/// This is what makes acceptance monotone in the rate: a knob accepted at a rate with a
/// filter `T₁` has `T₁ + dt₁` at least that time; at a higher rate this filter is
/// `T₁ + dt₁ − dt₂` long, with less lag in the loop (`T_f + 2·dt` in all) than the knob
/// that passed.
const fn count_alpha<S: Scalar>(
    c: &Checked,
    damping: f64,
    stiffness: &[f64; 3],
    present: &[bool; 3],
) -> Option<f64> {
    let most = COUNT_TORQUE_FRACTION * c.torque_limit;
    let mut need = 0.0f64;
    let mut z = 0;
    while z < 3 {
        if present[z] {
            let room = most - stiffness[z] * c.count;
            if room.is_nan() || room <= 0.0 {
                return None;
            }
            need = need.max(damping * c.count / room);
        }
        z += 1;
    }
    // A hair longer, so that the rounded torque is within the bound.
    let alpha = c.dt / (need * (1.0 + 1e-9));
    if alpha >= 1.0 {
        Some(1.0)
    } else if alpha >= least_alpha::<S>() {
        Some(alpha)
    } else {
        None
    }
}

/// True when every present zone meets the guarantee with filter `alpha`.
const fn zones_pass(p: &Plant, stiffness: &[f64; 3], present: &[bool; 3], alpha: f64) -> bool {
    let mut z = 0;
    while z < 3 {
        if present[z] && !p.zone_ok(stiffness[z], alpha) {
            return false;
        }
        z += 1;
    }
    true
}

/// The design of a validated configuration for backend `S`, or why it fails.
pub(crate) const fn try_design<S: Scalar>(c: &Checked) -> Result<Design, Failure> {
    let (dt, inertia) = (c.dt, c.inertia);
    let free = c.detent + c.ret;
    let held = free + c.magnet;
    let has_magnets = c.magnet_count > 0;
    let has_stops = c.bounds.is_some();
    let inside = if has_magnets { held } else { free };
    // The damping, and the endstop if the damping ratio needs one to refer to.
    let (damping, endstop) = match c.damping {
        Damping::Coefficient(b) => (b, c.endstop),
        Damping::Ratio(z) => {
            let (reference, endstop) = if has_magnets && held > 0.0 {
                (held, c.endstop)
            } else if free > 0.0 {
                (free, c.endstop)
            } else if let (true, Some(k)) = (has_stops, c.endstop) {
                (k, c.endstop)
            } else {
                // Nothing sets a stiffness: the stiffest spring that meets the guarantee
                // on its own at this damping ratio (also the default endstop).
                let top = top_stiffness(z, dt, inertia, c.latency);
                (top, if has_stops { Some(top) } else { None })
            };
            (2.0 * z * sqrt(reference * inertia), endstop)
        }
    };
    let most = COUNT_TORQUE_FRACTION * c.torque_limit;
    // The default endstop: the stiffest multiple of the inside stiffness that meets the
    // guarantee, and keeps one count's torque in bounds, with a filter the inside passes.
    let endstop = match (has_stops, endstop) {
        (false, _) => 0.0,
        (true, Some(k)) => k,
        (true, None) => {
            // Without springs inside, the stiffness this damping gives ζ = 0.7.
            let base = if inside > 0.0 {
                inside
            } else {
                let root = damping / (2.0 * KnobConfig::DEFAULT_DAMPING_RATIO);
                root * root / inertia
            };
            let sigma =
                DECAY_FRACTION * zone_decays(free, held, has_magnets, None, damping, inertia);
            let p = plant(c, damping, decay_radius(sigma * dt));
            let omega = reference_frequency(inside, damping, inertia);
            let mut found = -1.0;
            // The least count ratio among the combinations whose loop passes.
            let mut count_ratio = f64::INFINITY;
            let mut i = 0;
            while i < FILTER_LADDER.len() && found < 0.0 {
                let a = p.alpha(FILTER_LADDER[i], omega);
                i += 1;
                if !(p.zone_ok(free, a) && (!has_magnets || p.zone_ok(held, a))) {
                    continue;
                }
                let mut m = 0;
                while m < ENDSTOP_MULTIPLES.len() {
                    let k = free + ENDSTOP_MULTIPLES[m] * base;
                    if p.zone_ok(k, a) {
                        let ratio = (k + damping * a / dt) * c.count / most;
                        if ratio <= 1.0 {
                            found = ENDSTOP_MULTIPLES[m] * base;
                            break;
                        }
                        count_ratio = count_ratio.min(ratio);
                    }
                    m += 1;
                }
            }
            // Every filter of the ladder that the loop passes commands too much torque per
            // count: the filter the count needs, with the stiffest multiple whose loop
            // passes with it.
            let mut m = 0;
            while found < 0.0 && count_ratio.is_finite() && m < ENDSTOP_MULTIPLES.len() {
                let stiffness = [free, held, free + ENDSTOP_MULTIPLES[m] * base];
                let present = [true, has_magnets, true];
                if let Some(a) = count_alpha::<S>(c, damping, &stiffness, &present)
                    && zones_pass(&p, &stiffness, &present, a)
                {
                    found = ENDSTOP_MULTIPLES[m] * base;
                }
                m += 1;
            }
            if found < 0.0 {
                return Err(if count_ratio.is_finite() {
                    Failure::Count(BEYOND, count_ratio)
                } else {
                    Failure::Loop(BEYOND)
                });
            }
            found
        }
    };
    finish::<S>(c, damping, endstop)
}

const fn plant(c: &Checked, damping: f64, radius: f64) -> Plant {
    Plant {
        dt: c.dt,
        inertia: c.inertia,
        damping,
        latency: c.latency,
        radius,
    }
}

/// The loop check and the backend's range, once every stiffness is known.
const fn finish<S: Scalar>(c: &Checked, damping: f64, endstop: f64) -> Result<Design, Failure> {
    use Parameter as P;
    let (dt, inertia, torque_limit) = (c.dt, c.inertia, c.torque_limit);
    let has_magnets = c.magnet_count > 0;
    let has_stops = c.bounds.is_some();
    let free = c.detent + c.ret;
    let held = free + c.magnet;
    let beyond = free + endstop;
    let stiffness = [free, held, beyond];
    let present = [true, has_magnets, has_stops];
    let sigma = DECAY_FRACTION
        * zone_decays(
            free,
            held,
            has_magnets,
            if has_stops { Some(beyond) } else { None },
            damping,
            inertia,
        );
    let p = plant(c, damping, decay_radius(sigma * dt));
    // The damper alone: a velocity loop that must meet the guarantee too.
    if !p.zone_ok(0.0, 1.0) {
        return Err(Failure::Damper);
    }
    let inside = if has_magnets { held } else { free };
    let omega = reference_frequency(if inside > 0.0 { inside } else { beyond }, damping, inertia);
    let mut alpha = -1.0;
    let mut i = 0;
    while i < FILTER_LADDER.len() {
        let a = p.alpha(FILTER_LADDER[i], omega);
        i += 1;
        let mut ok = true;
        let mut z = 0;
        while z < 3 && ok {
            ok = !present[z] || p.zone_ok(stiffness[z], a);
            z += 1;
        }
        if ok {
            alpha = a;
            break;
        }
    }
    if alpha < 0.0 {
        // No filter passes: name the first zone that fails without one.
        let mut z = 0;
        while z < 3 {
            if present[z] && !p.zone_ok(stiffness[z], 1.0) {
                return Err(Failure::Loop(z));
            }
            z += 1;
        }
        return Err(Failure::Loop(FREE));
    }

    // The encoder: one count must not command more than a fraction of the limit. If the
    // filter the loop chose lets it, the longer filter the count needs, where the loop
    // passes with it.
    let most = COUNT_TORQUE_FRACTION * torque_limit;
    let mut z = 0;
    while z < 3 {
        let ratio = (stiffness[z] + damping * alpha / dt) * c.count / most;
        if present[z] && ratio > 1.0 {
            match count_alpha::<S>(c, damping, &stiffness, &present) {
                Some(a) if a < alpha && zones_pass(&p, &stiffness, &present, a) => {
                    alpha = a;
                    break;
                }
                _ => return Err(Failure::Count(z, ratio)),
            }
        }
        z += 1;
    }

    // The backend: the gains (torque fraction per radian) and the reach. The error names
    // the layer, against its stiffest gain in N·m/rad (the damping in N·m·s/rad).
    let damping_gain = damping / (torque_limit * dt);
    let gain_most = S::MAX / 4.0;
    let per_rad = [
        (c.detent, P::DetentStiffness),
        (c.magnet, P::MagnetStiffness),
        (c.ret, P::ReturnStiffness),
        (endstop, P::EndstopStiffness),
    ];
    let mut largest = damping_gain.max(1.0);
    let mut i = 0;
    while i < per_rad.len() {
        let (k, which) = per_rad[i];
        i += 1;
        largest = largest.max(k / torque_limit);
        if k / torque_limit >= gain_most {
            return Err(Failure::Refused(KnobError::range(
                which,
                Limit::BackendRange,
                k,
                below(k, gain_most * torque_limit),
            )));
        }
    }
    if damping_gain >= gain_most {
        return Err(Failure::Refused(KnobError::range(
            P::DampingConstant,
            Limit::BackendRange,
            damping,
            below(damping, gain_most * torque_limit * dt),
        )));
    }
    // The damper's state keeps up to four more bits where the range allows.
    let mut state_scale = super::law::STATE_SCALE;
    while state_scale > 1.0 && state_scale * damping_gain >= gain_most {
        state_scale /= 2.0;
    }
    // Floats: angles (and differences of two) times any gain stay finite, with room.
    let reach = if S::RESOLUTION > 0.0 {
        S::MAX
    } else {
        S::MAX / (16.0 * largest)
    };
    let half = reach / 2.0;
    // The farthest angle the user set, for the error.
    let mut far = (c.return_centre.abs(), P::ReturnCentre);
    if let Some((lo, hi)) = c.bounds
        && lo.abs().max(hi.abs()) > far.0
    {
        far = (lo.abs().max(hi.abs()), P::Endstops);
    }
    if let Some(g) = c.grid
        && g.origin.abs() > far.0
    {
        far = (g.origin.abs(), P::DetentOrigin);
    }
    let mut i = 0;
    while i < c.magnet_count {
        if c.magnets[i].abs() > far.0 {
            far = (c.magnets[i].abs(), P::Magnets);
        }
        i += 1;
    }
    if far.0 > half {
        return Err(Failure::Refused(KnobError::range(
            far.1,
            Limit::BackendRange,
            far.0,
            half,
        )));
    }
    // An endless grid spans the whole reach (less a width, so that a centre and the
    // next switching point stay inside it).
    let grid = match c.grid {
        Some(g) if !has_stops => {
            let n = libm_free_floor((reach - g.origin.abs()) / g.width - 1.0)
                .min((i32::MAX - 1) as f64);
            Some(Grid {
                range: (-(n as i32), n as i32),
                ..g
            })
        }
        other => other,
    };

    let mut zones = [None; 3];
    let mut z = 0;
    while z < 3 {
        if present[z] {
            zones[z] = Some(p.coefficients(stiffness[z], alpha));
        }
        z += 1;
    }
    Ok(Design {
        dt,
        inertia: c.inertia,
        max_speed: c.max_speed,
        torque_limit,
        count: c.count,
        reach,
        bounds: c.bounds,
        grid,
        hysteresis: c.hysteresis,
        return_centre: c.return_centre,
        magnets: c.magnets,
        magnet_count: c.magnet_count,
        magnet_radius: c.magnet_radius,
        detent: c.detent,
        magnet: c.magnet,
        ret: c.ret,
        endstop,
        damping,
        alpha,
        state_scale,
        zones,
        zone_stiffness: stiffness,
        play_counts: play_counts(damping, alpha, c.inertia, dt),
    })
}

/// The play's half-width, in encoder counts: [`law::PLAY_COUNTS`](super::law::PLAY_COUNTS),
/// or half a count where the damper's own mode is poorly damped.
///
/// A rotor of inertia `J` against the filtered damper `B/(1 + s·T)` (the filter's time
/// constant `T = dt·(1 − α)/α`) has a mode of its own, `J·T·s² + J·s + B = 0`, with the
/// damping ratio `ζ' = ½·√(J/(T·B))`. Where it is below [`MIN_DAMPER_MODE_RATIO`] for a
/// rotor of half the configured inertia, the play's lag sustains that mode as an
/// oscillation of several counts (at ζ = 2, 10 kHz, a 10-bit encoder: 9 counts peak to
/// peak with the full play, in `tests/knob_sweep.rs`); half a count still absorbs a
/// reading toggling between two counts.
const fn play_counts(damping: f64, alpha: f64, inertia: f64, dt: f64) -> f64 {
    if damping <= 0.0 || alpha >= 1.0 {
        return super::law::PLAY_COUNTS;
    }
    let t = dt * (1.0 - alpha) / alpha;
    let ratio = 0.5 * sqrt(0.5 * inertia / (t * damping));
    if ratio >= MIN_DAMPER_MODE_RATIO {
        super::law::PLAY_COUNTS
    } else {
        super::law::MIN_PLAY_COUNTS
    }
}

/// The least damping ratio of the rotor's mode against its filtered damper, on half the
/// configured inertia, for the full play ([`play_counts`]).
const MIN_DAMPER_MODE_RATIO: f64 = 0.25;

/// True when `config` is accepted for backend `S`.
pub(crate) const fn passes<S: Scalar>(config: &KnobConfig) -> bool {
    match validate::<S>(config) {
        Ok(c) => try_design::<S>(&c).is_ok(),
        Err(_) => false,
    }
}

/// `config` with the argument `parameter` set to `x`.
const fn with(config: &KnobConfig, parameter: Parameter, x: f64) -> KnobConfig {
    let c = *config;
    match parameter {
        Parameter::DetentTorque => c.detent_torque(x),
        Parameter::ReturnStiffness => c.return_to_centre(c.return_centre, x),
        Parameter::MagnetStiffness => c.magnet_stiffness(x),
        Parameter::EndstopStiffness => c.endstop_stiffness(x),
        Parameter::DampingConstant => c.damping(x),
        Parameter::LoopRate => KnobConfig { rate: x, ..c },
        _ => c.detent_stiffness(x),
    }
}

/// The largest value of `parameter` (a stiffness, a peak torque or a damping) with which
/// `config` is accepted, everything else as configured: doubling from 1e−12, then 48
/// bisections. `None` when even 1e−12 is refused; 1e12 if that much passes.
pub(crate) const fn largest_passing<S: Scalar>(
    config: &KnobConfig,
    parameter: Parameter,
) -> Option<f64> {
    let tiny = 1e-12;
    if !passes::<S>(&with(config, parameter, tiny)) {
        return None;
    }
    let mut lo = tiny;
    while passes::<S>(&with(config, parameter, 2.0 * lo)) {
        lo *= 2.0;
        if lo > 1e12 {
            return Some(lo);
        }
    }
    let mut hi = 2.0 * lo;
    let mut step = 0;
    while step < 48 {
        step += 1;
        let mid = 0.5 * (lo + hi);
        if passes::<S>(&with(config, parameter, mid)) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    Some(lo)
}

/// The argument the user set that makes `zone` as stiff as it is: the detent (as a
/// stiffness or a peak torque), else the return spring, the magnet or the endstop that
/// adds to it. `None`: nothing the user set (the design's own default).
const fn blamed(config: &KnobConfig, c: &Checked, zone: usize) -> Option<Parameter> {
    let endstop_set = match config.endstop_stiffness {
        Some(k) => k > 0.0,
        None => false,
    };
    if zone == BEYOND && endstop_set {
        return Some(Parameter::EndstopStiffness);
    }
    if zone == MAGNET && c.magnet > 0.0 {
        return Some(Parameter::MagnetStiffness);
    }
    if c.detent > 0.0 {
        return Some(match config.detent_spring {
            DetentSpring::PeakTorque(_) => Parameter::DetentTorque,
            DetentSpring::Stiffness(_) => Parameter::DetentStiffness,
        });
    }
    if c.ret > 0.0 {
        return Some(Parameter::ReturnStiffness);
    }
    if c.magnet > 0.0 {
        return Some(Parameter::MagnetStiffness);
    }
    None
}

/// The value of `parameter` as the user set it.
const fn given(config: &KnobConfig, parameter: Parameter) -> f64 {
    match parameter {
        Parameter::DetentTorque | Parameter::DetentStiffness => match config.detent_spring {
            DetentSpring::PeakTorque(t) => t,
            DetentSpring::Stiffness(k) => k,
        },
        Parameter::ReturnStiffness => config.return_stiffness,
        Parameter::MagnetStiffness => config.magnet_stiffness,
        Parameter::EndstopStiffness => match config.endstop_stiffness {
            Some(k) => k,
            None => 0.0,
        },
        Parameter::DampingConstant => match config.damping {
            Damping::Coefficient(b) => b,
            Damping::Ratio(_) => 0.0,
        },
        _ => config.rate,
    }
}

/// The least rate (Hz) at which `config` is accepted, up to 1 MHz: doubling, then 48
/// bisections. `None` if not even 1 MHz.
const fn least_rate<S: Scalar>(config: &KnobConfig) -> Option<f64> {
    let mut hi = if config.rate > MIN_LOOP_RATE {
        config.rate
    } else {
        MIN_LOOP_RATE
    };
    while !passes::<S>(&with(config, Parameter::LoopRate, hi)) {
        hi *= 2.0;
        if hi > 1e6 {
            return None;
        }
    }
    let mut lo = config.rate;
    let mut step = 0;
    while step < 48 {
        step += 1;
        let mid = 0.5 * (lo + hi);
        if passes::<S>(&with(config, Parameter::LoopRate, mid)) {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    Some(hi)
}

/// The error of a design that failed, in the terms of what the user set.
const fn blame<S: Scalar>(config: &KnobConfig, c: &Checked, failure: Failure) -> KnobError {
    use Parameter as P;
    let zone = match failure {
        Failure::Refused(e) => return e,
        Failure::Count(zone, ratio) => {
            // A count's torque scales with the count: `counts·ratio` counts per turn pass,
            // or a few per cent more (a finer count also moves the default hysteresis).
            let mut need = libm_free_floor(c.counts * ratio) + 1.0;
            let mut tries = 0;
            while tries < 16 && need < u32::MAX as f64 {
                let finer = KnobConfig {
                    counts_per_turn: need as u32,
                    ..*config
                };
                if passes::<S>(&finer) {
                    break;
                }
                need = libm_free_floor(need * 1.02) + 1.0;
                tries += 1;
            }
            return KnobError::new(
                Error::OutOfRange {
                    parameter: P::CountsPerTurn,
                    value: c.counts,
                    bound: Bound::AtLeast { min: need },
                },
                Limit::CountTorque(ZONES[zone]),
                c.counts,
                need,
            );
        }
        Failure::Damper => match config.damping {
            Damping::Coefficient(b) => {
                return match largest_passing::<S>(config, P::DampingConstant) {
                    Some(most) => {
                        KnobError::range(P::DampingConstant, Limit::LoopDamping, b, below(b, most))
                    }
                    None => rate_error::<S>(config),
                };
            }
            // The damping follows the stiffest zone inside: that zone is too stiff.
            Damping::Ratio(_) => {
                if c.magnet_count > 0 && c.magnet > 0.0 {
                    MAGNET
                } else {
                    FREE
                }
            }
        },
        Failure::Loop(zone) => zone,
    };
    match blamed(config, c, zone) {
        Some(parameter) => match largest_passing::<S>(config, parameter) {
            Some(most) => {
                let value = given(config, parameter);
                KnobError::range(
                    parameter,
                    Limit::LoopStiffness(ZONES[zone]),
                    value,
                    below(value, most),
                )
            }
            None => rate_error::<S>(config),
        },
        None => rate_error::<S>(config),
    }
}

/// The rate is too low for the knob: the least rate at which it passes.
const fn rate_error<S: Scalar>(config: &KnobConfig) -> KnobError {
    let least = match least_rate::<S>(config) {
        Some(r) => r,
        None => f64::INFINITY,
    };
    KnobError::range(Parameter::LoopRate, Limit::AtLeast, config.rate, least)
}

/// Validation, then the design, for backend `S`; a refusal names what the user set.
pub(crate) const fn design<S: Scalar>(config: &KnobConfig) -> Result<Design, KnobError> {
    let c = tri!(validate::<S>(config));
    match try_design::<S>(&c) {
        Ok(d) => Ok(d),
        Err(f) => Err(blame::<S>(config, &c, f)),
    }
}

/// The design's refusal without the search for what would pass: the parameter and the
/// bound only (for a compile-time error, which prints no numbers).
pub(crate) const fn design_or_reason<S: Scalar>(
    config: &KnobConfig,
) -> Result<Design, (Option<Parameter>, Limit)> {
    let c = match validate::<S>(config) {
        Ok(c) => c,
        Err(e) => return Err((e.error.parameter(), e.bound)),
    };
    match try_design::<S>(&c) {
        Ok(d) => Ok(d),
        Err(Failure::Refused(e)) => Err((e.error.parameter(), e.bound)),
        Err(Failure::Count(zone, _)) => Err((
            Some(Parameter::CountsPerTurn),
            Limit::CountTorque(ZONES[zone]),
        )),
        Err(Failure::Damper) => match config.damping {
            Damping::Coefficient(_) => Err((Some(Parameter::DampingConstant), Limit::LoopDamping)),
            Damping::Ratio(_) => Err((blamed(config, &c, FREE), Limit::LoopStiffness(ZONES[FREE]))),
        },
        Err(Failure::Loop(zone)) => {
            Err((blamed(config, &c, zone), Limit::LoopStiffness(ZONES[zone])))
        }
    }
}

impl KnobConfig {
    /// The stiffest detent (N·m/rad) that [`Knob::new`](crate::Knob::new) accepts for
    /// backend `S` with everything else as configured: the loop guarantee in every zone
    /// and the detent's peak torque (a search over whole designs, doubling from 1e−12
    /// N·m/rad and then 48 bisections: a tool for the host, not for a boot path). It is the
    /// limit a refused `detent_stiffness` reports.
    ///
    /// # Errors
    ///
    /// The error of the configuration with a detent of (almost) no stiffness, when even
    /// that is refused.
    ///
    /// ```
    /// use stiffspring::KnobConfig;
    /// let c = KnobConfig::new(1_000.0, 1e-5, 0.05, 16384).detent_count(24).endstops(0.0, 6.0);
    /// let k = c.detent_stiffness_limit::<f32>()?;
    /// assert!(k > 0.01 && k < 1.0);
    /// assert!(stiffspring::Knob::<f32>::new(&c.detent_stiffness(0.99 * k), 0.0).is_ok());
    /// let e = stiffspring::Knob::<f32>::new(&c.detent_stiffness(1.01 * k), 0.0).unwrap_err();
    /// assert!((e.limit - k).abs() <= 1e-12 * k); // here the peak torque bounds it
    /// // In a constant too: some 90 designs, long for the compiler's evaluator.
    /// #[allow(long_running_const_eval)]
    /// const K: f64 = match KnobConfig::new(4_000.0, 1e-5, 0.05, 16384)
    ///     .detent_width(0.2)
    ///     .detent_stiffness_limit::<f32>()
    /// {
    ///     Ok(k) => k,
    ///     Err(_) => 0.0,
    /// };
    /// assert!(K > 0.1);
    /// # Ok::<(), stiffspring::knob::KnobError>(())
    /// ```
    pub const fn detent_stiffness_limit<S: Scalar>(&self) -> Result<f64, KnobError> {
        match largest_passing::<S>(self, Parameter::DetentStiffness) {
            Some(k) => Ok(k),
            None => match design::<S>(&self.detent_stiffness(1e-12)) {
                Err(e) => Err(e),
                // Not reached: the tiny detent was refused above.
                Ok(_) => Ok(0.0),
            },
        }
    }
}
