//! The first step of the set-up: every argument of a [`KnobConfig`] checked on its own and
//! against the others, for one backend, and turned into the physical quantities the loop
//! design starts from (the layers' stiffnesses, the detent grid, the sorted magnets).
//! Nothing here knows the loop: that is `design.rs`, which comes after.
//!
//! All `const fn`: a configuration known when the firmware is built is checked by the
//! compiler ([`knob!`](crate::knob!)).

use super::config::{Damping, DetentSpacing, DetentSpring, KnobConfig, Latency, MAX_MAGNETS};
use super::error::{KnobError, Limit, below};
use crate::error::{Parameter, tri};
use crate::scalar::Scalar;
use core::f64::consts::TAU;

/// The lowest loop rate a knob runs at, in hertz. Below it no detent a person can feel
/// meets the loop guarantee (the stiffest spring the sampled loop holds falls as the
/// square of the rate: about 0.038·J·rate² N·m/rad at ζ 0.7 with one period of delay,
/// 3.8e−7 N·m/rad at 100 Hz on 1e−5 kg·m²). A rate below it is usually a period passed
/// where the rate goes.
///
/// ```
/// assert_eq!(stiffspring::knob::MIN_LOOP_RATE, 100.0);
/// ```
pub const MIN_LOOP_RATE: f64 = 100.0;

/// A detent grid: centres at `origin + i·width` for `i` in `range`, switching `threshold`
/// past the centre.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub(crate) struct Grid {
    pub(crate) origin: f64,
    pub(crate) width: f64,
    pub(crate) threshold: f64,
    pub(crate) range: (i32, i32),
}

/// A configuration whose arguments are each valid, in physical units: what the loop design
/// starts from.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Checked {
    pub(crate) dt: f64,
    pub(crate) inertia: f64,
    /// The configured maximum speed, rad/s (checked positive).
    pub(crate) max_speed: Option<f64>,
    pub(crate) torque_limit: f64,
    pub(crate) latency: Latency,
    /// Counts per turn, and one count in radians (the rest zone).
    pub(crate) counts: f64,
    pub(crate) count: f64,
    pub(crate) damping: Damping,
    pub(crate) bounds: Option<(f64, f64)>,
    pub(crate) grid: Option<Grid>,
    pub(crate) hysteresis: f64,
    pub(crate) return_centre: f64,
    /// Sorted.
    pub(crate) magnets: [f64; MAX_MAGNETS],
    pub(crate) magnet_count: usize,
    pub(crate) magnet_radius: f64,
    /// Stiffness of each layer, N·m/rad (0 where the layer is absent).
    pub(crate) detent: f64,
    pub(crate) magnet: f64,
    pub(crate) ret: f64,
    /// `None`: the default endstop, chosen by the design.
    pub(crate) endstop: Option<f64>,
}

/// `floor` for non-negative values below 2⁵², without `libm`.
pub(crate) const fn libm_free_floor(value: f64) -> f64 {
    if value.is_nan() || value < 0.0 {
        return 0.0;
    }
    if value >= 4_503_599_627_370_496.0 {
        return value;
    }
    (value as u64) as f64
}

/// `floor` for any finite value.
pub(crate) const fn floor(value: f64) -> f64 {
    if value >= 0.0 {
        libm_free_floor(value)
    } else {
        let f = -libm_free_floor(-value);
        if f > value { f - 1.0 } else { f }
    }
}

/// A float backend's significant bits (24 for `f32`, 53 for `f64`), told apart by their
/// set-up range ([`Scalar::MAX`] is 2⁶⁴ for `f32`, 2⁵⁰⁰ for `f64`).
const fn float_bits<S: Scalar>() -> u32 {
    if S::MAX < 1e30 { 24 } else { 53 }
}

/// `x` rounded to backend `S`'s numbers (floats only: to nearest, like `S::from_f64`).
const fn to_float<S: Scalar>(x: f64) -> f64 {
    if float_bits::<S>() == 24 {
        x as f32 as f64
    } else {
        x
    }
}

/// The spacing of float backend `S`'s numbers at `angle` (positive, finite): the smallest
/// power of two that moves the backend's value of `angle` when added to it (its last
/// place, or half of it where the sum ties and rounds away). Set-up only: a power of two
/// above the angle halved down to it, 24 halvings in `f32`, 53 in `f64`.
pub(crate) const fn float_step<S: Scalar>(angle: f64) -> f64 {
    let at = to_float::<S>(angle);
    // A power of two at least the angle (which moves it), then halved while half of it
    // still moves it.
    let mut step = 1.0;
    while step < at {
        step *= 2.0;
    }
    while step > f64::MIN_POSITIVE && to_float::<S>(at + 0.5 * step) != at {
        step *= 0.5;
    }
    step
}

/// Checks every argument of `config` for backend `S`, in the order the builder documents.
pub(crate) const fn validate<S: Scalar>(config: &KnobConfig) -> Result<Checked, KnobError> {
    use Parameter as P;
    let rate = tri!(KnobError::positive(config.rate, P::LoopRate));
    if rate < MIN_LOOP_RATE {
        return Err(KnobError::range(
            P::LoopRate,
            Limit::AtLeast,
            rate,
            MIN_LOOP_RATE,
        ));
    }
    let dt = 1.0 / rate;
    let inertia = tri!(KnobError::positive(config.inertia, P::Inertia));
    let torque_limit = tri!(KnobError::positive(config.torque_limit, P::TorqueLimit));
    if let Some(w) = config.max_speed {
        let _ = tri!(KnobError::positive(w, P::MaxSpeed));
    }
    if config.counts_per_turn == 0 {
        return Err(KnobError::range(
            P::CountsPerTurn,
            Limit::Positive,
            0.0,
            0.0,
        ));
    }
    let counts = config.counts_per_turn as f64;
    let count = TAU / counts;
    if count < S::RESOLUTION {
        // A count finer than the backend's LSB: the backend cannot tell counts apart.
        return Err(KnobError::range(
            P::CountsPerTurn,
            Limit::AtMost,
            counts,
            libm_free_floor(TAU / S::RESOLUTION),
        ));
    }
    let damping = match config.damping {
        Damping::Ratio(z) => {
            let z = tri!(KnobError::finite(z, P::DampingRatio));
            let (lo, hi) = super::stability::DAMPING_RATIO_RANGE;
            if z < lo {
                return Err(KnobError::range(P::DampingRatio, Limit::AtLeast, z, lo));
            }
            if z > hi {
                return Err(KnobError::range(P::DampingRatio, Limit::AtMost, z, hi));
            }
            Damping::Ratio(z)
        }
        Damping::Coefficient(b) => {
            Damping::Coefficient(tri!(KnobError::non_negative(b, P::DampingConstant)))
        }
    };

    // The backend's reach: fixed point takes its whole range (it saturates); a float
    // is limited below, once the gains are known.
    let backend_half = S::MAX / 2.0;
    let bounds = match config.endstops {
        None => None,
        Some((lo, hi)) => {
            let lo = tri!(KnobError::finite(lo, P::Endstops));
            let hi = tri!(KnobError::finite(hi, P::Endstops));
            if lo >= hi {
                return Err(KnobError::range(P::Endstops, Limit::Below, lo, hi));
            }
            let m = lo.abs().max(hi.abs());
            if m > backend_half {
                return Err(KnobError::range(
                    P::Endstops,
                    Limit::BackendRange,
                    m,
                    backend_half,
                ));
            }
            if S::RESOLUTION == 0.0 {
                // A float's spacing grows with the angle: at the farther stop a count
                // must still span four float steps, or the rest zone and the
                // hysteresis (a count or two) cannot be told apart. (Fixed point's
                // spacing is its last bit everywhere, checked above.)
                let step = float_step::<S>(m);
                if count < 4.0 * step {
                    return Err(KnobError::range(
                        P::CountsPerTurn,
                        Limit::AtMost,
                        counts,
                        libm_free_floor(TAU / (4.0 * step)),
                    ));
                }
            }
            Some((lo, hi))
        }
    };
    let hysteresis = match config.hysteresis {
        Some(h) => tri!(KnobError::non_negative(h, P::Hysteresis)),
        None => KnobConfig::DEFAULT_HYSTERESIS_COUNTS * count,
    };
    let snap = tri!(KnobError::finite(config.snap_point, P::SnapPoint));
    if snap < 0.5 {
        return Err(KnobError::range(P::SnapPoint, Limit::AtLeast, snap, 0.5));
    }
    if snap >= 1.0 {
        return Err(KnobError::range(P::SnapPoint, Limit::Below, snap, 1.0));
    }
    // A width of at least four counts, so that the switching points and the rest zone
    // stay apart; and one the backend resolves to 1%.
    let least_width = (4.0 * count).max(100.0 * S::RESOLUTION);
    let layout = match (config.detents, bounds) {
        (DetentSpacing::None, _) => None,
        (DetentSpacing::Count(n), Some((lo, hi))) if n >= 2 => {
            let width = (hi - lo) / (n - 1) as f64;
            if width < least_width {
                // The most detents that fit, at the least width.
                let most = libm_free_floor((hi - lo) / least_width) + 1.0;
                return Err(KnobError::range(
                    P::DetentCount,
                    Limit::AtMost,
                    n as f64,
                    most,
                ));
            }
            Some((lo, width, Some(n - 1)))
        }
        (DetentSpacing::Count(n), Some(_)) => {
            return Err(KnobError::range(
                P::DetentCount,
                Limit::AtLeast,
                n as f64,
                2.0,
            ));
        }
        (DetentSpacing::Count(n), None) => {
            // A count needs endstops to spread over.
            return Err(KnobError::range(
                P::DetentCount,
                Limit::NeedsEndstops,
                n as f64,
                f64::NAN,
            ));
        }
        (DetentSpacing::Width(w), Some((lo, hi))) => {
            let w = tri!(KnobError::positive(w, P::DetentWidth));
            if w < least_width {
                return Err(KnobError::range(
                    P::DetentWidth,
                    Limit::AtLeast,
                    w,
                    least_width,
                ));
            }
            // The last detent at or just below `max` (1e−9 absorbs the rounding of a
            // width that divides the range).
            let n = libm_free_floor((hi - lo) / w + 1e-9);
            if n > (i32::MAX - 1) as f64 {
                return Err(KnobError::range(
                    P::DetentWidth,
                    Limit::AtLeast,
                    w,
                    (hi - lo) / (i32::MAX - 1) as f64,
                ));
            }
            Some((lo, w, Some(n as u32)))
        }
        (DetentSpacing::Width(w), None) => {
            let origin = tri!(KnobError::finite(config.detent_origin, P::DetentOrigin));
            let w = tri!(KnobError::positive(w, P::DetentWidth));
            if w < least_width {
                return Err(KnobError::range(
                    P::DetentWidth,
                    Limit::AtLeast,
                    w,
                    least_width,
                ));
            }
            if origin.abs() > backend_half {
                return Err(KnobError::range(
                    P::DetentOrigin,
                    Limit::BackendRange,
                    origin.abs(),
                    backend_half,
                ));
            }
            Some((origin, w, None))
        }
    };
    let grid = match layout {
        None => None,
        Some((origin, width, span)) => {
            let threshold = (snap * width).max(0.5 * width + hysteresis);
            if threshold >= width {
                return Err(KnobError::range(
                    P::Hysteresis,
                    Limit::Below,
                    hysteresis,
                    0.5 * width,
                ));
            }
            let range = match span {
                Some(n) => (
                    0,
                    if n < i32::MAX as u32 - 1 {
                        n as i32
                    } else {
                        i32::MAX - 1
                    },
                ),
                None => {
                    // Keep every centre within half the reach.
                    let n = libm_free_floor((backend_half - origin.abs()) / width);
                    let n = n.min((i32::MAX - 1) as f64);
                    (-(n as i32), n as i32)
                }
            };
            Some(Grid {
                origin,
                width,
                threshold,
                range,
            })
        }
    };

    // The layers' stiffnesses, each checked as the user gave it.
    let detent = match config.detent_spring {
        DetentSpring::Stiffness(k) => tri!(KnobError::non_negative(k, P::DetentStiffness)),
        DetentSpring::PeakTorque(t) => {
            let t = tri!(KnobError::non_negative(t, P::DetentTorque));
            match grid {
                Some(g) => t / g.threshold,
                None => 0.0,
            }
        }
    };
    let detent = if grid.is_some() { detent } else { 0.0 };
    let ret = tri!(KnobError::non_negative(
        config.return_stiffness,
        P::ReturnStiffness
    ));
    let return_centre = tri!(KnobError::finite(config.return_centre, P::ReturnCentre));
    if return_centre.abs() > backend_half {
        return Err(KnobError::range(
            P::ReturnCentre,
            Limit::BackendRange,
            return_centre.abs(),
            backend_half,
        ));
    }
    let magnet = tri!(KnobError::non_negative(
        config.magnet_stiffness,
        P::MagnetStiffness
    ));
    let endstop = match config.endstop_stiffness {
        Some(k) => Some(tri!(KnobError::non_negative(k, P::EndstopStiffness))),
        None => None,
    };

    // Magnets.
    if config.magnets_asked > MAX_MAGNETS {
        return Err(KnobError::range(
            P::Magnets,
            Limit::Capacity,
            config.magnets_asked as f64,
            MAX_MAGNETS as f64,
        ));
    }
    let mut magnets = config.magnets;
    let magnet_count = config.magnet_count;
    let mut i = 0;
    while i < magnet_count {
        let m = tri!(KnobError::finite(magnets[i], P::Magnets));
        i += 1;
        match bounds {
            Some((lo, _)) if m < lo => {
                return Err(KnobError::range(P::Magnets, Limit::AtLeast, m, lo));
            }
            Some((_, hi)) if m > hi => {
                return Err(KnobError::range(P::Magnets, Limit::AtMost, m, hi));
            }
            None if m.abs() > backend_half => {
                return Err(KnobError::range(
                    P::Magnets,
                    Limit::BackendRange,
                    m.abs(),
                    backend_half,
                ));
            }
            _ => {}
        }
    }
    // Insertion sort: at most MAX_MAGNETS elements, no allocation.
    let mut i = 1;
    while i < magnet_count {
        let mut j = i;
        while j > 0 && magnets[j - 1] > magnets[j] {
            let t = magnets[j - 1];
            magnets[j - 1] = magnets[j];
            magnets[j] = t;
            j -= 1;
        }
        i += 1;
    }
    let mut spacing = f64::INFINITY;
    let mut i = 1;
    while i < magnet_count {
        spacing = spacing.min(magnets[i] - magnets[i - 1]);
        i += 1;
    }
    let magnet_radius = match config.magnet_radius {
        Some(r) => tri!(KnobError::positive(r, P::CaptureRadius)),
        None if spacing.is_finite() => 0.25 * spacing,
        None => 0.1,
    };
    if magnet_count > 0 {
        let least = (2.0 * count).max(100.0 * S::RESOLUTION);
        if magnet_radius < least {
            return Err(KnobError::range(
                P::CaptureRadius,
                Limit::AtLeast,
                magnet_radius,
                least,
            ));
        }
        let most = 0.5 * spacing - hysteresis;
        if magnet_radius > most {
            return Err(KnobError::range(
                P::CaptureRadius,
                Limit::AtMost,
                magnet_radius,
                most,
            ));
        }
    }
    let magnet = if magnet_count > 0 { magnet } else { 0.0 };

    // Peak torques: a detent or magnet the motor renders unclipped. The error names what
    // the user set, against the most of it whose peak the motor gives.
    if let Some(g) = grid
        && detent * g.threshold > torque_limit
    {
        return Err(match config.detent_spring {
            DetentSpring::PeakTorque(t) => {
                KnobError::range(P::DetentTorque, Limit::PeakTorque, t, torque_limit)
            }
            DetentSpring::Stiffness(k) => KnobError::range(
                P::DetentStiffness,
                Limit::PeakTorque,
                k,
                below(k, torque_limit / g.threshold),
            ),
        });
    }
    if magnet_count > 0 && magnet * (magnet_radius + hysteresis) > torque_limit {
        return Err(KnobError::range(
            P::MagnetStiffness,
            Limit::PeakTorque,
            magnet,
            torque_limit / (magnet_radius + hysteresis),
        ));
    }
    Ok(Checked {
        max_speed: config.max_speed,
        dt,
        inertia,
        torque_limit,
        latency: config.latency,
        counts,
        count,
        damping,
        bounds,
        grid,
        hysteresis,
        return_centre,
        magnets,
        magnet_count,
        magnet_radius,
        detent,
        magnet,
        ret,
        endstop,
    })
}
