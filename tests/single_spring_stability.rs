//! One spring over the whole `(C_k, C_d)` plane: property tests of stability, in every
//! backend, with random masses, time steps and positions up to each backend's range.
//!
//! - **The region.** The map `u ← (1 − C_d)·u − C_k·x, x ← x + u` is stable exactly on
//!   Jury's region `C_k > 0, 0 < C_d < 2, C_k + 2·C_d < 4`, plus the article's closed
//!   square `[0, 1]²` (whose edges `C_k = 0` or `C_d = 0` are neutral: no spring, or no
//!   damping) less its origin (no spring and no damping: a value would drift for ever).
//!   [`Tuning::from_coefficients_extended`] must accept exactly that set: every
//!   point drawn in the plane `[−1, 5] × [−1, 3]` is checked both ways. Outside, the
//!   independent reference map (`lab::reference`) must visibly grow, so the test fails
//!   if either the library or the region is wrong.
//! - **Inside, nothing grows.** The library's value, stepped 10 000 times, never swings
//!   beyond the reference map's transient bound `max_n ‖Mⁿ‖` and decays at its spectral
//!   radius, in `f64`, `f32` and `I32F32`.
//! - **Two bodies.** With masses in any ratio up to `10⁶` and `dt` from `10⁻⁵` to 1 s,
//!   the kernel's two-body step moves the pair's relative coordinate exactly as the
//!   single spring and conserves momentum.
//! - **Range.** Positions, targets and flings anywhere in `f32`/`f64`'s accepted range
//!   (`±Scalar::MAX`) never give NaN or infinity over 10 000 steps, nor does a value with
//!   almost no pull drifting for `2²⁵` steps (`a_drifting_value_never_becomes_infinite`);
//!   fixed point from `MIN` and `MAX` steps as the study's integer model (saturating, never
//!   wrapping) and every damped value comes to rest, in the whole region.
//!
//! `cargo test --test single_spring_stability` runs 256 cases per property (part of
//! `cargo test`); `PROPTEST_CASES=100000 cargo test --release --test
//! single_spring_stability` is the full run.

use lab::reference;

use lab::precision::{Coefs, Fixed, KRound, Kept, Stepper};
use proptest::prelude::*;
use stiffspring::kernel::{self, BodyWeights};
use stiffspring::{
    Error, I16F16, I32F32, Motion, Parameter, RestThreshold, Scalar, SpringValue, Tuning,
};

const STEPS: usize = 10_000;

/// The set the library must accept: Jury's open region and the closed unit square less
/// its origin.
fn in_region(ck: f64, cd: f64) -> bool {
    let square = (0.0..=1.0).contains(&ck) && (0.0..=1.0).contains(&cd) && (ck, cd) != (0.0, 0.0);
    square || (ck > 0.0 && cd > 0.0 && cd < 2.0 && ck + 2.0 * cd < 4.0)
}

/// `max_{n ≤ steps} ‖Mⁿ‖∞` of the reference map.
fn transient_bound(ck: f64, cd: f64, steps: usize) -> f64 {
    let m = reference::map_matrix(ck, cd);
    let mut p = [[1.0, 0.0], [0.0, 1.0]];
    let mut worst = 1.0f64;
    for _ in 0..steps {
        p = [
            [
                m[0][0] * p[0][0] + m[0][1] * p[1][0],
                m[0][0] * p[0][1] + m[0][1] * p[1][1],
            ],
            [
                m[1][0] * p[0][0] + m[1][1] * p[1][0],
                m[1][0] * p[0][1] + m[1][1] * p[1][1],
            ],
        ];
        worst = worst.max((p[0][0].abs() + p[0][1].abs()).max(p[1][0].abs() + p[1][1].abs()));
    }
    worst
}

/// The largest `max(|x|, |u|)` the reference map reaches from `(x, u)` in `steps`.
fn reference_peak(ck: f64, cd: f64, (mut x, mut u): (f64, f64), steps: usize) -> f64 {
    let mut peak = x.abs().max(u.abs());
    for _ in 0..steps {
        reference::map_step(&mut x, &mut u, ck, cd);
        peak = peak.max(x.abs().max(u.abs()));
        if !peak.is_finite() {
            return f64::INFINITY;
        }
    }
    peak
}

/// A coefficient drawn across `[lo, hi]`, with the special values drawn often.
fn coefficient(lo: f64, hi: f64, special: &'static [f64]) -> impl Strategy<Value = f64> {
    prop_oneof![
        6 => lo..=hi,
        1 => proptest::sample::select(special),
        // Within a few ULP of a special value.
        1 => (proptest::sample::select(special), -4i64..=4)
            .prop_map(|(v, k)| f64::from_bits((v.to_bits() as i64 + k).max(0) as u64)),
    ]
}

const CK_SPECIAL: &[f64] = &[0.0, 1.0, 2.0, 3.0, 4.0, 1e-9, 3.999];
const CD_SPECIAL: &[f64] = &[0.0, 1.0, 2.0, 1e-9, 0.5, 1.5];

/// A point of the stable region: any of the plane that is in it, and points near its
/// edges.
fn region_point() -> impl Strategy<Value = (f64, f64)> {
    prop_oneof![
        (
            coefficient(0.0, 4.0, CK_SPECIAL),
            coefficient(0.0, 2.0, CD_SPECIAL)
        ),
        // Just inside the Jury edge C_k + 2·C_d = 4.
        (0.0..2.0f64, 1e-6..0.1f64).prop_map(|(cd, gap)| (4.0 - 2.0 * cd - gap, cd)),
    ]
    .prop_filter("inside the region", |&(ck, cd)| in_region(ck, cd))
}

/// Set-up refuses only a coefficient the backend cannot hold: one that rounds to zero or
/// to a subnormal (floats), or below the state's resolution (fixed point), all below 1e−7.
fn refused_for_resolution<S: Scalar>(ck: f64, cd: f64) -> bool {
    let tiny = |c: f64| c != 0.0 && c < 1e-7;
    S::gains(ck, cd).is_none() && (tiny(ck) || tiny(cd))
}

/// Steps a value and checks it against the reference's transient bound and decay. The
/// value starts at rest at `x0`, so its offsets are the reference map's `x` from `(x0, 0)`;
/// the bound is on them.
fn no_growth<S: Scalar>(ck: f64, cd: f64, x0: f64, slack: f64) -> Result<(), TestCaseError> {
    let tuning = Tuning::from_coefficients_extended(ck, cd, 1.0).expect("stable");
    let Ok(mut v) = SpringValue::<S>::new([S::from_f64(x0)], &tuning) else {
        // Set-up refuses a coefficient the backend cannot hold, and a float tuning whose
        // transient growth leaves no room (both documented).
        let growth = S::RESOLUTION == 0.0 && tuning.growth() > 1e6;
        prop_assert!(
            growth || refused_for_resolution::<S>(ck, cd),
            "({ck}, {cd}) refused"
        );
        return Ok(());
    };
    v.set_target([S::ZERO]);
    // The coefficients the backend actually runs.
    let (ck, cd) = S::gains_to_f64(&S::gains(ck, cd).expect("representable"));
    let bound = transient_bound(ck, cd, STEPS) * x0.abs();
    let mut peak = 0.0f64;
    for n in 0..STEPS {
        v.advance();
        let x = v.offset()[0].to_f64();
        prop_assert!(
            x.is_finite() && v.step_velocity()[0].to_f64().is_finite(),
            "{} step {n}",
            S::NAME
        );
        peak = peak.max(x.abs());
    }
    prop_assert!(
        peak <= bound * (1.0 + 1e-5) + slack,
        "{} ({ck}, {cd}): peak {peak} above the bound {bound}",
        S::NAME
    );
    let rho = reference::spectral_radius(ck, cd);
    if rho < 0.998 {
        // 0.998^10000 ≈ 2e−9: decayed to rounding.
        let end = v.offset()[0].to_f64().abs();
        prop_assert!(
            end <= 1e-6 * x0.abs() + slack,
            "{} ({ck}, {cd}): {end}",
            S::NAME
        );
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    /// The library accepts exactly the stable region, and the reference map grows
    /// outside it (so that a wrong region in either fails the test).
    #[test]
    fn the_library_accepts_exactly_the_stable_region(
        ck in coefficient(-1.0, 5.0, CK_SPECIAL),
        cd in coefficient(-1.0, 3.0, CD_SPECIAL),
    ) {
        let accepted = Tuning::from_coefficients_extended(ck, cd, 0.01);
        prop_assert_eq!(accepted.is_ok(), in_region(ck, cd), "({}, {}): {:?}", ck, cd, accepted);
        match accepted {
            Ok(t) => prop_assert_eq!((t.stiffness(), t.damping()), (ck, cd)),
            Err(e) => {
                let named = matches!(
                    e,
                    Error::OutOfRange { parameter: Parameter::Stiffness | Parameter::Damping, .. }
                );
                prop_assert!(named, "{:?}", e);
            }
        }
        let rho = reference::spectral_radius(ck, cd);
        if !in_region(ck, cd) && rho > 1.001 {
            // ρ^10000 > e^10: from either start the unstable mode shows.
            let growth = reference_peak(ck, cd, (1.0, 0.0), STEPS)
                .max(reference_peak(ck, cd, (0.0, 1.0), STEPS));
            prop_assert!(growth > 1e3, "({}, {}) ρ = {}: grew only {}", ck, cd, rho, growth);
        }
        if in_region(ck, cd) {
            prop_assert!(rho <= 1.0 + 1e-12, "({}, {}) ρ = {}", ck, cd, rho);
        }
    }

    /// Inside the region a value never swings above the transient bound and decays at
    /// the spectral radius: f64 to rounding, f32 and I32F32 (amplitude 1000) within
    /// their resolution.
    #[test]
    fn inside_the_region_nothing_grows((ck, cd) in region_point(), x0 in -1e3..1e3f64) {
        no_growth::<f64>(ck, cd, x0, 1e-9 * x0.abs())?;
        no_growth::<f32>(ck, cd, x0, 1e-3 * x0.abs())?;
        no_growth::<I32F32>(ck, cd, x0, 1e-3)?;
    }

    /// Two free bodies of masses in any ratio up to 10⁶, at any dt from 10⁻⁵ to 1 s: the
    /// kernel moves their relative coordinate as the single spring and conserves
    /// momentum; velocities (`u/dt`) stay finite.
    #[test]
    fn two_bodies_of_any_masses_are_one_spring(
        (ck, cd) in region_point(),
        log_ratio in -6.0..=6.0f64,
        log_dt in -5.0..=0.0f64,
        (x0, u0) in (-10.0..10.0f64, -1.0..1.0f64),
    ) {
        let (ma, mb) = (1.0, 10f64.powf(log_ratio));
        let dt = 10f64.powf(log_dt);
        let Some(g) = f64::gains(ck, cd) else {
            prop_assert!(refused_for_resolution::<f64>(ck, cd));
            return Ok(());
        };
        let w = BodyWeights::<f64>::from_inverse_masses(1.0 / ma, 1.0 / mb).expect("masses");
        // Bodies on a line: a at 0, b at the extension x0; relative step velocity u0.
        let (mut xa, mut xb, mut ua, mut ub) = (0.0f64, x0, -u0 * mb / (ma + mb), u0 * ma / (ma + mb));
        let p0 = ma * ua + mb * ub;
        let (mut x, mut u) = (x0, u0);
        let mut scale = x0.abs() + u0.abs() + 1e-300;
        let mut momentum_scale = 0.0f64;
        for n in 0..2_000 {
            // Near the edge of the region the transient grows far above the start (ρ ≈ 1,
            // C_k ≈ 4): rounding scales with the largest state so far.
            scale = scale.max(x.abs() + u.abs());
            momentum_scale = momentum_scale.max(ma * ua.abs() + mb * ub.abs());
            let delta = kernel::respond::<f64>(&g, xb - xa, ub - ua);
            let (da, db) = w.split(delta);
            ua += da;
            ub += db;
            xa += ua;
            xb += ub;
            reference::map_step(&mut x, &mut u, ck, cd);
            prop_assert!((xb - xa - x).abs() <= 1e-9 * scale * (1.0 + n as f64 / 100.0),
                "step {}: {} vs {}", n, xb - xa, x);
            prop_assert!((ua / dt).is_finite() && (ub / dt).is_finite());
        }
        let p = ma * ua + mb * ub;
        // Each step rounds each body's change once: 2 000 steps, a few ε each.
        prop_assert!((p - p0).abs() <= 2000.0 * 4.0 * f64::EPSILON * momentum_scale,
            "momentum {} → {}", p0, p);
    }

    /// Floats: positions, targets and flings anywhere in the accepted range, any tuning
    /// of the region, any dt from 10⁻⁵ to 1: never NaN, never infinite.
    #[test]
    fn floats_never_produce_nan_or_inf_across_their_range(
        (ck, cd) in region_point(),
        (p, t, v) in (-1.0..=1.0f64, -1.0..=1.0f64, -1.0..=1.0f64),
        log_dt in -5.0..=0.0f64,
    ) {
        let tuning = Tuning::from_coefficients_extended(ck, cd, 10f64.powf(log_dt)).expect("stable");
        floats_stay_finite::<f32>(&tuning, (p, t, v))?;
        floats_stay_finite::<f64>(&tuning, (p, t, v))?;
    }

    /// Fixed point from the ends of its range, with any tuning of the region: every
    /// step is the integer model's (saturating, no wrap across the range), and a value
    /// with damping comes to rest on its target.
    #[test]
    fn fixed_point_saturates_and_still_comes_to_rest(
        (ck, cd) in region_point(),
        from_max in any::<bool>(),
        to_zero in any::<bool>(),
    ) {
        fixed_saturates::<I16F16>((ck, cd), from_max, to_zero, |p| p.to_bits().into())?;
        fixed_saturates::<I32F32>((ck, cd), from_max, to_zero, |p| p.to_bits().into())?;
    }
}

fn floats_stay_finite<S: Scalar>(
    tuning: &Tuning,
    (p, t, v): (f64, f64, f64),
) -> Result<(), TestCaseError> {
    let max = S::MAX;
    let Ok(mut value) = SpringValue::<S>::new([S::from_f64(p * max)], tuning) else {
        let (ck, cd) = (tuning.stiffness(), tuning.damping());
        let refused = tuning.growth() > 1e6 || refused_for_resolution::<S>(ck, cd);
        prop_assert!(refused, "{tuning:?} refused");
        return Ok(());
    };
    // The infallible setters saturate what the state cannot hold.
    value.set_target([S::from_f64(t * max)]);
    value.fling([S::from_f64(v * max)]);
    for n in 0..STEPS {
        let _ = value.step();
        let all = [
            value.position()[0],
            value.offset()[0],
            value.step_velocity()[0],
            value.velocity()[0],
        ];
        prop_assert!(
            all.iter().all(|x| x.to_f64().is_finite()),
            "{} step {n}: {all:?} ({tuning:?})",
            S::NAME
        );
    }
    Ok(())
}

/// `bits` reads a position's raw bits (the model compares them exactly).
fn fixed_saturates<S: Scalar>(
    (ck, cd): (f64, f64),
    from_max: bool,
    to_zero: bool,
    bits: fn(S) -> i128,
) -> Result<(), TestCaseError> {
    let tuning = Tuning::from_coefficients_extended(ck, cd, 1e-3).expect("stable");
    let top = S::from_f64(S::MAX);
    let end = if from_max { top } else { top.neg() };
    let target = if to_zero {
        S::ZERO
    } else {
        S::from_f64(end.to_f64() * 0.25)
    };
    let tiny = RestThreshold::new(1e-12, 1e-12).expect("positive");
    let Ok(v) = SpringValue::<S>::new([end], &tuning) else {
        prop_assert!(refused_for_resolution::<S>(ck, cd), "({ck}, {cd}) refused");
        return Ok(());
    };
    let mut v = v.with_rest_threshold(tiny);
    v.set_target([target]);
    let fixed = if S::NAME == "I16F16" {
        Fixed::I16F16
    } else {
        Fixed::I32F32
    };
    let x = bits(end) - bits(target);
    let mut model = Kept::from_state(
        fixed,
        KRound::Lead,
        Coefs { ck, cd },
        x << Kept::guard(fixed),
        0,
    );
    // Decays by e^−50 within the budget when ρ ≤ 0.999; the model then rests.
    let rho = reference::spectral_radius(ck, cd);
    for n in 0..50_000 {
        model.step();
        match v.step() {
            Motion::Settled | Motion::Resting => {
                prop_assert_eq!(v.position()[0], target);
                return Ok(());
            }
            Motion::Moving => {
                prop_assert_eq!(
                    bits(v.offset()[0]),
                    model.visible_lsb(),
                    "{} step {}: ({}, {})",
                    S::NAME,
                    n,
                    ck,
                    cd
                );
            }
        }
    }
    // Every damped start of the library's rounding comes to rest (tests/fixed_rounding.rs);
    // only a spring that decays too slowly for the budget is still moving.
    prop_assert!(
        cd == 0.0 || rho > 0.999,
        "{} ({}, {}), ρ = {}: not at rest",
        S::NAME,
        ck,
        cd,
        rho
    );
    Ok(())
}

/// A value with almost no pull and little damping, flung at the top of a float
/// backend's range, drifts a long way: `x` grows by `u` per step. Set-up bounds every state
/// a stable tuning can reach (`Tuning::growth`): a tuning whose growth leaves no room is
/// refused, and one that is accepted limits the start so that no step can overflow. The
/// value then stays finite for `2²⁵` steps. (No spring and no damping at all, `(0, 0)`,
/// is refused: `tests/bad_input.rs`.)
#[test]
fn a_drifting_value_never_becomes_infinite() {
    let mut accepted = 0;
    for (ck, cd) in [(1e-300, 0.0), (0.0, 1e-12), (1e-20, 1e-9), (1e-12, 0.0)] {
        let tuning = Tuning::from_coefficients(ck, cd, 1.0).expect("in the square");
        let Ok(mut v) = SpringValue::<f64>::new([0.0], &tuning) else {
            continue;
        };
        accepted += 1;
        v.fling([f64::MAX]);
        for n in 0..(1u64 << 25) {
            v.advance();
            assert!(
                v.offset()[0].is_finite() && v.position()[0].is_finite(),
                "{tuning:?}: infinite after {n} steps"
            );
        }
    }
    assert!(accepted >= 2, "{accepted}");
}
