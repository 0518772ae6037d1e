//! Checking a [`KnobConfig`] against everything the knob guarantees, for one backend.

use super::config::{Damping, DetentSpacing, DetentSpring, KnobConfig};
use super::design::{Design, reference_frequency, top_stiffness, zone_decays};
use super::detents::MAX_MAGNETS;
use super::error::{KnobError, Limit, Zone};
use super::stability::{
    COUNT_TORQUE_FRACTION, DAMPING_RATIO_RANGE, DECAY_FRACTION, FILTER_LADDER, LoopCoefficients,
    Plant, decay_radius, sqrt,
};
use crate::error::Parameter;
use crate::scalar::Scalar;
use core::f64::consts::TAU;

/// Everything the hot path needs, validated and in `f64`.
pub(crate) struct Validated {
    pub(crate) dt: f64,
    pub(crate) torque_limit: f64,
    /// The rest zone: one encoder count.
    pub(crate) count: f64,
    /// The largest angle magnitude the hot path takes (inputs are clamped to it).
    pub(crate) reach: f64,
    pub(crate) bounds: Option<(f64, f64)>,
    /// `(origin, width, threshold, (min, max) index)`, or `None` without detents.
    pub(crate) grid: Option<(f64, f64, f64, (i32, i32))>,
    pub(crate) hysteresis: f64,
    pub(crate) return_centre: f64,
    pub(crate) magnets: [f64; MAX_MAGNETS],
    pub(crate) magnet_count: usize,
    pub(crate) magnet_radius: f64,
    /// Stiffness of each layer, N·m/rad: detent, magnet, return, endstop.
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
}

/// `floor` for non-negative values below 2⁵², without `libm`.
pub(crate) fn libm_free_floor(value: f64) -> f64 {
    if value.is_nan() || value < 0.0 {
        return 0.0;
    }
    if value >= 4_503_599_627_370_496.0 {
        return value;
    }
    (value as u64) as f64
}

/// `floor` for any finite value.
pub(crate) fn floor(value: f64) -> f64 {
    if value >= 0.0 {
        libm_free_floor(value)
    } else {
        let f = -libm_free_floor(-value);
        if f > value { f - 1.0 } else { f }
    }
}

/// The index of the detent nearest to `angle`: `round((angle − origin)/width)`, clamped.
pub(crate) fn nearest_index(angle: f64, origin: f64, width: f64, (lo, hi): (i32, i32)) -> i32 {
    let r = floor((angle - origin) / width + 0.5);
    r.clamp(f64::from(lo), f64::from(hi)) as i32
}

/// The multiples of the inside stiffness tried for the default endstop, stiffest first.
/// At most 4×: the endstop zone then keeps a damping ratio of `ζ/√5` (0.31 at the default
/// 0.7), so that a knob flicked into the stop bounces little.
const ENDSTOP_MULTIPLES: [f64; 5] = [4.0, 2.0, 1.0, 0.5, 0.25];

impl KnobConfig {
    /// Checks everything, for backend `S`.
    pub(crate) fn validate<S: Scalar>(&self) -> Result<Validated, KnobError> {
        use Parameter as P;
        let rate = KnobError::positive(self.rate, P::LoopRate)?;
        let dt = 1.0 / rate;
        let inertia = KnobError::positive(self.inertia, P::Inertia)?;
        let torque_limit = KnobError::positive(self.torque_limit, P::TorqueLimit)?;
        if self.counts_per_turn == 0 {
            return Err(KnobError::range(
                P::EncoderResolution,
                Limit::Positive,
                0.0,
                0.0,
            ));
        }
        let count = TAU / f64::from(self.counts_per_turn);
        if count < S::RESOLUTION {
            // A count finer than the backend's LSB: the backend cannot tell counts apart.
            return Err(KnobError::range(
                P::EncoderResolution,
                Limit::AtMost,
                f64::from(self.counts_per_turn),
                TAU / S::RESOLUTION,
            ));
        }
        let damping_spec = match self.damping {
            Damping::Ratio(z) => {
                let z = KnobError::finite(z, P::DampingRatio)?;
                let (lo, hi) = DAMPING_RATIO_RANGE;
                if z < lo {
                    return Err(KnobError::range(P::DampingRatio, Limit::AtLeast, z, lo));
                }
                if z > hi {
                    return Err(KnobError::range(P::DampingRatio, Limit::AtMost, z, hi));
                }
                Damping::Ratio(z)
            }
            Damping::Coefficient(b) => {
                Damping::Coefficient(KnobError::non_negative(b, P::DampingConstant)?)
            }
        };

        // The backend's reach: fixed point takes its whole range (it saturates); a float
        // is limited below, once the gains are known.
        let backend_half = S::MAX / 2.0;
        let bounds = match self.endstops {
            None => None,
            Some((lo, hi)) => {
                let lo = KnobError::finite(lo, P::Position)?;
                let hi = KnobError::finite(hi, P::Position)?;
                if lo >= hi {
                    return Err(KnobError::range(P::Position, Limit::Below, lo, hi));
                }
                let m = lo.abs().max(hi.abs());
                if m > backend_half {
                    return Err(KnobError::range(
                        P::Position,
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
                            P::EncoderResolution,
                            Limit::AtMost,
                            f64::from(self.counts_per_turn),
                            libm_free_floor(TAU / (4.0 * step)),
                        ));
                    }
                }
                Some((lo, hi))
            }
        };
        let hysteresis = match self.hysteresis {
            Some(h) => KnobError::non_negative(h, P::Hysteresis)?,
            None => Self::DEFAULT_HYSTERESIS_COUNTS * count,
        };
        let snap = KnobError::finite(self.snap_point, P::SnapPoint)?;
        if snap < 0.5 {
            return Err(KnobError::range(P::SnapPoint, Limit::AtLeast, snap, 0.5));
        }
        if snap >= 1.0 {
            return Err(KnobError::range(P::SnapPoint, Limit::Below, snap, 1.0));
        }
        let layout = match (self.detents, bounds) {
            (DetentSpacing::None, _) => None,
            (DetentSpacing::Count(n), Some((lo, hi))) if n >= 2 => {
                Some((lo, (hi - lo) / f64::from(n - 1), Some(n - 1)))
            }
            (DetentSpacing::Count(n), Some(_)) => {
                return Err(KnobError::range(
                    P::DetentWidth,
                    Limit::AtLeast,
                    f64::from(n),
                    2.0,
                ));
            }
            (DetentSpacing::Count(n), None) => {
                // A count needs endstops to spread over.
                return Err(KnobError::range(
                    P::DetentWidth,
                    Limit::NeedsEndstops,
                    f64::from(n),
                    f64::NAN,
                ));
            }
            (DetentSpacing::Width(w), Some((lo, hi))) => {
                let w = KnobError::positive(w, P::DetentWidth)?;
                // The last detent at or just below `max` (1e−9 absorbs the rounding of a
                // width that divides the range).
                let n = libm_free_floor((hi - lo) / w + 1e-9);
                if n > f64::from(i32::MAX - 1) {
                    return Err(KnobError::range(
                        P::DetentWidth,
                        Limit::AtLeast,
                        w,
                        (hi - lo) / f64::from(i32::MAX - 1),
                    ));
                }
                Some((lo, w, Some(n as u32)))
            }
            (DetentSpacing::Width(w), None) => Some((
                KnobError::finite(self.detent_origin, P::Position)?,
                KnobError::positive(w, P::DetentWidth)?,
                None,
            )),
        };
        let grid = match layout {
            None => None,
            Some((origin, width, span)) => {
                // A width of at least four counts, so that the switching points and the
                // rest zone stay apart; and one the backend resolves to 1%.
                let least = (4.0 * count).max(100.0 * S::RESOLUTION);
                if width < least {
                    return Err(KnobError::range(
                        P::DetentWidth,
                        Limit::AtLeast,
                        width,
                        least,
                    ));
                }
                if origin.abs() > backend_half {
                    return Err(KnobError::range(
                        P::Position,
                        Limit::BackendRange,
                        origin.abs(),
                        backend_half,
                    ));
                }
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
                    Some(n) => (0, n.min(i32::MAX as u32 - 1) as i32),
                    None => {
                        // Keep every centre within half the reach.
                        let n = libm_free_floor((backend_half - origin.abs()) / width);
                        let n = n.min(f64::from(i32::MAX - 1));
                        (-(n as i32), n as i32)
                    }
                };
                Some((origin, width, threshold, range))
            }
        };

        // The layers' stiffnesses.
        let detent = match self.detent_spring {
            DetentSpring::Stiffness(k) => KnobError::non_negative(k, P::SpringConstant)?,
            DetentSpring::PeakTorque(t) => {
                let t = KnobError::non_negative(t, P::TorqueLimit)?;
                match grid {
                    Some((_, _, threshold, _)) => t / threshold,
                    None => 0.0,
                }
            }
        };
        let detent = if grid.is_some() { detent } else { 0.0 };
        let ret = KnobError::non_negative(self.return_stiffness, P::SpringConstant)?;
        let return_centre = KnobError::finite(self.return_centre, P::Position)?;
        if return_centre.abs() > backend_half {
            return Err(KnobError::range(
                P::Position,
                Limit::BackendRange,
                return_centre.abs(),
                backend_half,
            ));
        }
        let magnet = KnobError::non_negative(self.magnet_stiffness, P::SpringConstant)?;
        let endstop = match self.endstop_stiffness {
            Some(k) => Some(KnobError::non_negative(k, P::SpringConstant)?),
            None => None,
        };

        // Magnets.
        if self.magnets_asked > MAX_MAGNETS {
            return Err(KnobError::range(
                P::CaptureRadius,
                Limit::Capacity,
                self.magnets_asked as f64,
                MAX_MAGNETS as f64,
            ));
        }
        let mut magnets = self.magnets;
        let magnet_count = self.magnet_count;
        for &m in &magnets[..magnet_count] {
            let m = KnobError::finite(m, P::Position)?;
            match bounds {
                Some((lo, _)) if m < lo => {
                    return Err(KnobError::range(P::Position, Limit::AtLeast, m, lo));
                }
                Some((_, hi)) if m > hi => {
                    return Err(KnobError::range(P::Position, Limit::AtMost, m, hi));
                }
                None if m.abs() > backend_half => {
                    return Err(KnobError::range(
                        P::Position,
                        Limit::BackendRange,
                        m.abs(),
                        backend_half,
                    ));
                }
                _ => {}
            }
        }
        // Insertion sort: at most MAX_MAGNETS elements, no allocation.
        for i in 1..magnet_count {
            let mut j = i;
            while j > 0 && magnets[j - 1] > magnets[j] {
                magnets.swap(j - 1, j);
                j -= 1;
            }
        }
        let spacing = magnets[..magnet_count]
            .windows(2)
            .map(|w| w[1] - w[0])
            .fold(f64::INFINITY, f64::min);
        let magnet_radius = match self.magnet_radius {
            Some(r) => KnobError::positive(r, P::CaptureRadius)?,
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

        // Peak torques: a detent or magnet the motor renders unclipped.
        if let Some((_, _, threshold, _)) = grid {
            let peak = detent * threshold;
            if peak > torque_limit {
                return Err(KnobError::range(
                    P::SpringConstant,
                    Limit::PeakTorque,
                    peak,
                    torque_limit,
                ));
            }
        }
        if magnet_count > 0 {
            let peak = magnet * (magnet_radius + hysteresis);
            if peak > torque_limit {
                return Err(KnobError::range(
                    P::SpringConstant,
                    Limit::PeakTorque,
                    peak,
                    torque_limit,
                ));
            }
        }

        // The loop design.
        let free = detent + ret;
        let held = free + magnet;
        let has_magnets = magnet_count > 0;
        let has_stops = bounds.is_some();
        let inside = if has_magnets { held } else { free };
        let plant = |damping: f64, radius: f64| Plant {
            dt,
            inertia,
            damping,
            latency: self.latency,
            radius,
        };
        // The reference stiffness of the damping ratio, and the endstop if it needs one.
        let mut ratio = None;
        let (damping, endstop) = match damping_spec {
            Damping::Coefficient(b) => (b, endstop),
            Damping::Ratio(z) => {
                let (reference, zone) = if has_magnets && held > 0.0 {
                    (held, 1)
                } else if free > 0.0 {
                    (free, 0)
                } else if let (true, Some(k)) = (has_stops, endstop) {
                    (k, 2)
                } else {
                    // Nothing sets a stiffness: the stiffest spring that meets the
                    // guarantee on its own at this damping ratio (also the default
                    // endstop, if there are endstops).
                    let top = top_stiffness(z, dt, inertia, self.latency);
                    if has_stops && endstop.is_none() {
                        return self.finish::<S>(
                            Design {
                                ratio: Some((z, 2)),
                                dt,
                                inertia,
                                torque_limit,
                                count,
                                damping: 2.0 * z * sqrt(top * inertia),
                                detent,
                                magnet,
                                ret,
                                endstop: top,
                            },
                            bounds,
                            grid,
                            hysteresis,
                            return_centre,
                            magnets,
                            magnet_count,
                            magnet_radius,
                        );
                    }
                    (top, 2)
                };
                ratio = Some((z, zone));
                (2.0 * z * sqrt(reference * inertia), endstop)
            }
        };
        // The default endstop: the stiffest multiple of the inside stiffness that meets
        // the guarantee with the filter the inside needs.
        let endstop = match (has_stops, endstop) {
            (false, _) => 0.0,
            (true, Some(k)) => k,
            (true, None) => {
                // Without springs inside, the stiffness this damping gives ζ = 0.7.
                let base = if inside > 0.0 {
                    inside
                } else {
                    let root = damping / (2.0 * Self::DEFAULT_DAMPING_RATIO);
                    root * root / inertia
                };
                let sigma =
                    DECAY_FRACTION * zone_decays(free, held, has_magnets, None, damping, inertia);
                let p = plant(damping, decay_radius(sigma * dt));
                let omega = reference_frequency(inside, damping, inertia);
                let mut found = None;
                'ladder: for &c in &FILTER_LADDER {
                    let a = p.alpha(c, omega);
                    if !(p.zone_ok(free, a) && (!has_magnets || p.zone_ok(held, a))) {
                        continue;
                    }
                    for m in ENDSTOP_MULTIPLES {
                        let k = free + m * base;
                        let ripple = (k + damping * a / dt) * count;
                        if ripple <= COUNT_TORQUE_FRACTION * torque_limit && p.zone_ok(k, a) {
                            found = Some(m * base);
                            break 'ladder;
                        }
                    }
                }
                match found {
                    Some(k) => k,
                    None => {
                        // Even a quarter of the inside is too stiff: report that bound.
                        let k = free + 0.25 * base;
                        return Err(KnobError::range(
                            P::SpringConstant,
                            Limit::LoopStiffness(Zone::Beyond),
                            k,
                            p.stiffness_limit(k),
                        ));
                    }
                }
            }
        };
        self.finish::<S>(
            Design {
                ratio,
                dt,
                inertia,
                torque_limit,
                count,
                damping,
                detent,
                magnet,
                ret,
                endstop,
            },
            bounds,
            grid,
            hysteresis,
            return_centre,
            magnets,
            magnet_count,
            magnet_radius,
        )
    }
}

/// The spacing of backend `S`'s numbers at `angle` (positive, finite): the smallest power
/// of two that moves the backend's value of `angle` when added to it (its last place, or
/// half of it where the sum ties and rounds away). Set-up only: a power of two above the
/// angle halved down to it, 24 halvings in `f32`, 53 in `f64`.
fn float_step<S: Scalar>(angle: f64) -> f64 {
    let at = S::from_f64(angle);
    let exact = at.to_f64();
    // A power of two at least the angle (which moves it), then halved while half of it
    // still moves it.
    let mut step = 1.0;
    while step < exact {
        step *= 2.0;
    }
    while step > f64::MIN_POSITIVE && S::from_f64(exact + 0.5 * step) != at {
        step *= 0.5;
    }
    step
}
