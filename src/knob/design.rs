//! The knob's loop design: the checks and the filter, once every stiffness is known.

use super::config::KnobConfig;
use super::detents::MAX_MAGNETS;
use super::error::{KnobError, Limit};
use super::stability::{
    COUNT_TORQUE_FRACTION, DECAY_FRACTION, FILTER_LADDER, Latency, Plant, decay_radius,
    slowest_decay, sqrt,
};
use super::validate::{Validated, libm_free_floor};
use crate::error::{Bound, Error, Parameter};
use crate::scalar::Scalar;

impl KnobConfig {
    /// The loop check and the backend's range, once every stiffness is known.
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn finish<S: Scalar>(
        &self,
        d: Design,
        bounds: Option<(f64, f64)>,
        grid: Option<(f64, f64, f64, (i32, i32))>,
        hysteresis: f64,
        return_centre: f64,
        magnets: [f64; MAX_MAGNETS],
        magnet_count: usize,
        magnet_radius: f64,
    ) -> Result<Validated, KnobError> {
        use Parameter as P;
        let has_magnets = magnet_count > 0;
        let has_stops = bounds.is_some();
        let free = d.detent + d.ret;
        let held = free + d.magnet;
        let beyond = free + d.endstop;
        let stiffness = [free, held, beyond];
        let present = [true, has_magnets, has_stops];
        let sigma = DECAY_FRACTION
            * zone_decays(
                free,
                held,
                has_magnets,
                has_stops.then_some(beyond),
                d.damping,
                d.inertia,
            );
        let p = Plant {
            dt: d.dt,
            inertia: d.inertia,
            damping: d.damping,
            latency: self.latency,
            radius: decay_radius(sigma * d.dt),
        };
        // With the damping from a ratio, the zone that sets it moves with it: its bound is
        // the stiffest spring that meets the guarantee at that damping ratio.
        let ratio_error = |zone: usize| {
            d.ratio.filter(|&(_, z)| z == zone).map(|(zeta, _)| {
                KnobError::range(
                    P::SpringConstant,
                    Limit::LoopStiffness(super::stability::ZONES[zone]),
                    stiffness[zone],
                    top_stiffness(zeta, d.dt, d.inertia, self.latency),
                )
            })
        };
        // The damper alone: a velocity loop that must meet the guarantee too.
        if !p.zone_ok(0.0, 1.0) {
            return Err(match d.ratio {
                Some((_, zone)) => {
                    ratio_error(zone).unwrap_or_else(|| damping_limit(p, d.inertia, d.dt))
                }
                None => damping_limit(p, d.inertia, d.dt),
            });
        }
        let inside = if has_magnets { held } else { free };
        let omega = reference_frequency(
            if inside > 0.0 { inside } else { beyond },
            d.damping,
            d.inertia,
        );
        let zones_ok = |a: f64| (0..3).all(|z| !present[z] || p.zone_ok(stiffness[z], a));
        let Some(alpha) = FILTER_LADDER
            .iter()
            .map(|&c| p.alpha(c, omega))
            .find(|&a| zones_ok(a))
        else {
            // No filter passes: name the first zone that fails without one.
            let zone = (0..3)
                .find(|&z| present[z] && !p.zone_ok(stiffness[z], 1.0))
                .unwrap_or(0);
            if let Some(e) = ratio_error(zone) {
                return Err(e);
            }
            return Err(KnobError::range(
                P::SpringConstant,
                Limit::LoopStiffness(super::stability::ZONES[zone]),
                stiffness[zone],
                p.stiffness_limit(stiffness[zone]),
            ));
        };

        // The encoder: one count must not command more than a fraction of the limit.
        let most = COUNT_TORQUE_FRACTION * d.torque_limit;
        for z in 0..3 {
            let ripple = (stiffness[z] + d.damping * alpha / d.dt) * d.count;
            if present[z] && ripple > most {
                // The crate-wide error names the encoder, the one remedy that works for
                // every zone and damping: a count's torque scales with the count, so
                // `counts·ripple/most` counts per turn would pass.
                let counts = core::f64::consts::TAU / d.count;
                return Err(KnobError::new(
                    Error::OutOfRange {
                        parameter: P::EncoderResolution,
                        value: counts,
                        bound: Bound::AtLeast {
                            min: counts * ripple / most,
                        },
                    },
                    Limit::CountTorque(super::stability::ZONES[z]),
                    ripple,
                    most,
                ));
            }
        }

        // The backend: the gains (torque fraction per radian) and the reach.
        let damping_gain = d.damping / (d.torque_limit * d.dt);
        let per_rad = [
            (d.detent / d.torque_limit, P::SpringConstant),
            (d.magnet / d.torque_limit, P::SpringConstant),
            (d.ret / d.torque_limit, P::SpringConstant),
            (d.endstop / d.torque_limit, P::SpringConstant),
            (damping_gain, P::DampingConstant),
        ];
        let (largest, which) = per_rad
            .iter()
            .fold((1.0f64, P::SpringConstant), |m, &(g, p)| {
                if g > m.0 { (g, p) } else { m }
            });
        if largest >= S::MAX / 4.0 {
            return Err(KnobError::range(
                which,
                Limit::BackendRange,
                largest,
                S::MAX / 4.0,
            ));
        }
        // The damper's state keeps up to four more bits where the range allows.
        let mut state_scale = super::law::STATE_SCALE;
        while state_scale > 1.0 && state_scale * damping_gain >= S::MAX / 4.0 {
            state_scale /= 2.0;
        }
        // Floats: angles (and differences of two) times any gain stay finite, with room.
        let reach = if S::RESOLUTION > 0.0 {
            S::MAX
        } else {
            S::MAX / (16.0 * largest)
        };
        let half = reach / 2.0;
        let beyond_reach = bounds
            .map(|(lo, hi)| lo.abs().max(hi.abs()))
            .into_iter()
            .chain(grid.map(|g| g.0.abs()))
            .chain(core::iter::once(return_centre.abs()))
            .chain(magnets[..magnet_count].iter().map(|m| m.abs()))
            .fold(0.0f64, f64::max);
        if beyond_reach > half {
            return Err(KnobError::range(
                P::Position,
                Limit::BackendRange,
                beyond_reach,
                half,
            ));
        }
        // An endless grid spans the whole reach (less a width, so that a centre and the
        // next switching point stay inside it).
        let grid = grid.map(|(origin, width, threshold, range)| {
            let range = if bounds.is_none() {
                let n = libm_free_floor((reach - origin.abs()) / width - 1.0)
                    .min(f64::from(i32::MAX - 1));
                (-(n as i32), n as i32)
            } else {
                range
            };
            (origin, width, threshold, range)
        });

        let mut zones = [None; 3];
        for z in 0..3 {
            if present[z] {
                zones[z] = Some(p.coefficients(stiffness[z], alpha));
            }
        }
        Ok(Validated {
            dt: d.dt,
            torque_limit: d.torque_limit,
            count: d.count,
            reach,
            bounds,
            grid,
            hysteresis,
            return_centre,
            magnets,
            magnet_count,
            magnet_radius,
            detent: d.detent,
            magnet: d.magnet,
            ret: d.ret,
            endstop: d.endstop,
            damping: d.damping,
            alpha,
            state_scale,
            zones,
            zone_stiffness: stiffness,
        })
    }
}

/// The error of a damper that fails the guarantee on its own, with the most damping that
/// passes (bisection; an error path).
#[cold]
#[inline(never)]
pub(crate) fn damping_limit(p: Plant, inertia: f64, dt: f64) -> KnobError {
    let mut q = p;
    let (mut lo, mut hi) = (0.0, p.damping);
    for _ in 0..48 {
        let mid = 0.5 * (lo + hi);
        q.damping = mid;
        // The damper's own decay target (the velocity mode, B/J).
        q.radius = decay_radius(DECAY_FRACTION * slowest_decay(0.0, mid, inertia) * dt);
        if q.zone_ok(0.0, 1.0) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    KnobError::range(
        Parameter::DampingConstant,
        Limit::LoopDamping,
        p.damping,
        lo,
    )
}

/// The physical design, before the loop check.
pub(crate) struct Design {
    /// With the damping set by a ratio: `ζ` and the zone whose stiffness sets it (for the
    /// errors: that zone's bound then moves with its damping).
    pub(crate) ratio: Option<(f64, usize)>,
    pub(crate) dt: f64,
    pub(crate) inertia: f64,
    pub(crate) torque_limit: f64,
    pub(crate) count: f64,
    pub(crate) damping: f64,
    pub(crate) detent: f64,
    pub(crate) magnet: f64,
    pub(crate) ret: f64,
    pub(crate) endstop: f64,
}

/// The slowest decay rate over the zones that occur (1/s).
pub(crate) fn zone_decays(
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
pub(crate) fn reference_frequency(stiffness: f64, damping: f64, inertia: f64) -> f64 {
    sqrt(stiffness / inertia).max(damping / inertia)
}

/// The stiffest spring with damping ratio `zeta` that meets the guarantee on its own
/// without a filter (bisection on `C_k`; set-up only, and rare: a knob with no stiffness
/// inside its range).
#[cold]
#[inline(never)]
pub(crate) fn top_stiffness(zeta: f64, dt: f64, inertia: f64, latency: Latency) -> f64 {
    // In dimensionless form: C_k = K·dt²/J, C_d = 2ζ√C_k, decay σ·dt from the same.
    let ok = |ck: f64| {
        let cd = 2.0 * zeta * sqrt(ck);
        let sigma_dt = DECAY_FRACTION * slowest_decay(ck, cd, 1.0);
        let p = Plant {
            dt: 1.0,
            inertia: 1.0,
            damping: cd,
            latency,
            radius: decay_radius(sigma_dt),
        };
        p.zone_ok(ck, 1.0)
    };
    let (mut lo, mut hi) = (0.0, 1.0);
    for _ in 0..48 {
        let mid = 0.5 * (lo + hi);
        if ok(mid) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    lo * inertia / (dt * dt)
}
