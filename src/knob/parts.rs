//! The numbers a knob runs on, computed by the set-up from its [`Design`]: a `const fn`,
//! so that a knob designed at compile time ([`knob!`](crate::knob!)) starts from bits the
//! compiler wrote, and [`Knob::from_design`](crate::Knob::from_design) links no `f64`
//! arithmetic and no float-to-fixed conversion (`docs/knob.md`, "Set-up at compile
//! time"). Each value is what `S::from_f64` of the same `f64` expression gives, bit for
//! bit (`crate::scalar::Raw`).

use super::design::Design;
use super::detents::{LadderParts, MagnetParts};
use super::{law, screen};
use crate::scalar::{Raw, RawCoef, Scalar};

/// A zone's gain for the layer that only it has, and its rest zone and knee in torque.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub(crate) struct ZoneParts<S> {
    pub(crate) other: Raw<S>,
    pub(crate) rest: Raw<S>,
    pub(crate) knee: Raw<S>,
    pub(crate) half_knee: Raw<S>,
    pub(crate) curvature: Raw<S>,
}

impl<S: Scalar> ZoneParts<S> {
    /// A zone whose own layer has stiffness `other` and whose layers sum to `stiffness`
    /// (N·m/rad), as fractions of `limit` per radian; the rest zone and the knee are
    /// `rest_angle` and `knee_angle` wide (rad).
    const fn new(other: f64, stiffness: f64, limit: f64, rest_angle: f64, knee_angle: f64) -> Self {
        let knee = stiffness / limit * knee_angle;
        ZoneParts {
            other: Raw::new(other / limit),
            rest: Raw::new(stiffness / limit * rest_angle),
            knee: Raw::new(knee),
            half_knee: Raw::new(0.5 * knee),
            curvature: Raw::new(if knee > 0.0 { 0.5 / knee } else { 0.0 }),
        }
    }
}

/// Every backend number of a knob at rest, and the set-up's reports.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub(crate) struct KnobParts<S> {
    pub(crate) reach: Raw<S>,
    pub(crate) play: Raw<S>,
    pub(crate) jolt: Raw<S>,
    pub(crate) max_step: Raw<S>,
    pub(crate) fade_unit: Raw<S>,
    pub(crate) slew: Raw<S>,
    pub(crate) damping_gain: Raw<S>,
    pub(crate) unscale: RawCoef<S>,
    pub(crate) alpha: RawCoef<S>,
    pub(crate) beta: RawCoef<S>,
    pub(crate) step: RawCoef<S>,
    pub(crate) detent_gain: Raw<S>,
    pub(crate) return_gain: Raw<S>,
    pub(crate) zones: [ZoneParts<S>; 3],
    pub(crate) floor: Raw<S>,
    pub(crate) lo: Raw<S>,
    pub(crate) hi: Raw<S>,
    pub(crate) lo_hit: Raw<S>,
    pub(crate) hi_hit: Raw<S>,
    pub(crate) lo_release: Raw<S>,
    pub(crate) hi_release: Raw<S>,
    pub(crate) return_centre: Raw<S>,
    pub(crate) inverse_width: Raw<S>,
    pub(crate) ladder: LadderParts<S>,
    pub(crate) magnets: MagnetParts<S>,
    /// Reports, in `f64` (copied, not computed, at run time).
    pub(crate) filter_time: f64,
    pub(crate) rest_zone: f64,
    pub(crate) knee: f64,
}

impl<S: Scalar> KnobParts<S> {
    /// The numbers of design `v`.
    pub(crate) const fn new(v: &Design) -> Self {
        let limit = v.torque_limit;
        let rest_angle = law::REST_COUNTS * v.count;
        // The knee: KNEE_COUNTS counts, or a quarter of the way from the rest zone to the
        // switching point where a detent is narrower.
        let knee_angle = match v.grid {
            Some(g) => (law::KNEE_COUNTS * v.count).min(0.25 * (g.threshold - rest_angle)),
            None => law::KNEE_COUNTS * v.count,
        };
        let (lo, hi) = match v.bounds {
            Some(b) => b,
            None => (-v.reach, v.reach),
        };
        // The most the rotor's movement per period can change: the torque limit, three
        // times more from a hand, on half the inertia, plus the encoder's rounding.
        let jolt = (screen::JOLT_TORQUES * limit / (0.5 * v.inertia) * v.dt * v.dt
            + screen::JOLT_COUNTS * v.count)
            .min(v.reach);
        let max_step = match v.max_speed {
            Some(w) => (w * v.dt).min(v.reach),
            None => v.reach,
        };
        let ladder = match v.grid {
            // Index 0, or the nearest the range has: `Knob::from_design` walks it to the
            // initial angle in the backend's arithmetic.
            Some(g) => LadderParts::new(g.origin, g.width, g.threshold, g.range, 0),
            None => LadderParts::fixed(match v.bounds {
                Some((lo, _)) => lo,
                None => 0.0,
            }),
        };
        KnobParts {
            reach: Raw::new(v.reach),
            play: Raw::new(v.play_counts * v.count),
            jolt: Raw::new(jolt),
            max_step: Raw::new(max_step),
            fade_unit: Raw::new(1.0 / screen::FADE_PERIODS as f64),
            slew: Raw::new((v.zone_stiffness[0] / limit * v.count).max(1.0 / 256.0)),
            damping_gain: Raw::new(v.state_scale * v.damping / (limit * v.dt)),
            unscale: RawCoef::new(1.0 / v.state_scale),
            alpha: RawCoef::new(v.alpha),
            beta: RawCoef::new(1.0 - v.alpha),
            step: RawCoef::new(v.dt),
            detent_gain: Raw::new(v.detent / limit),
            return_gain: Raw::new(v.ret / limit),
            zones: [
                ZoneParts::new(0.0, v.zone_stiffness[0], limit, rest_angle, knee_angle),
                ZoneParts::new(v.magnet, v.zone_stiffness[1], limit, rest_angle, knee_angle),
                ZoneParts::new(
                    v.endstop,
                    v.zone_stiffness[2],
                    limit,
                    rest_angle,
                    knee_angle,
                ),
            ],
            floor: Raw::new(law::TORQUE_FLOOR),
            lo: Raw::new(lo),
            hi: Raw::new(hi),
            // Hit past the rest zone and the knee: the spring is at full stiffness there.
            lo_hit: Raw::new(lo - rest_angle - knee_angle),
            hi_hit: Raw::new(hi + rest_angle + knee_angle),
            lo_release: Raw::new(lo + v.hysteresis),
            hi_release: Raw::new(hi - v.hysteresis),
            return_centre: Raw::new(v.return_centre),
            inverse_width: Raw::new(match v.grid {
                Some(g) => 1.0 / g.width,
                None => 0.0,
            }),
            ladder,
            magnets: MagnetParts::new(
                &v.magnets,
                v.magnet_count,
                v.magnet_radius,
                v.magnet_radius + v.hysteresis,
            ),
            filter_time: v.dt * (1.0 - v.alpha) / v.alpha,
            rest_zone: rest_angle,
            knee: knee_angle,
        }
    }
}
