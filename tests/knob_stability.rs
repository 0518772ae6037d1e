//! The knob's closed-loop stability region and its strength map, checked independently:
//!
//! - the loop's state matrix is built here from the rotor's physics (ZOH, backward
//!   difference, a delay of any fraction of a period), its characteristic polynomial
//!   computed numerically (Faddeev–LeVerrier) and its roots found by Durand–Kerner; they
//!   agree with the library's polynomial, Jury test and spectral radius;
//! - every strength of every accepted damping ratio and latency keeps the gain margin of
//!   2, also for fractional delays and for a caller-supplied exact velocity;
//! - every configuration the knob accepts (strength combinations over zones) runs with
//!   coefficients that keep the margin;
//! - just outside the stable region, a simulated rotor does grow (so these tests can
//!   fail), and just inside it decays.

use lab::knob::Plant;
use stiffspring::knob::{
    DAMPING_RATIO_RANGE, GAIN_MARGIN, Latency, StrengthMap, characteristic_polynomial, is_stable,
    same_step_stiffness_limit, spectral_radius,
};
use stiffspring::{Error, Knob, KnobConfig, Parameter};

#[derive(Clone, Copy, Debug)]
struct C(f64, f64);
impl C {
    fn add(self, o: C) -> C {
        C(self.0 + o.0, self.1 + o.1)
    }
    fn sub(self, o: C) -> C {
        C(self.0 - o.0, self.1 - o.1)
    }
    fn mul(self, o: C) -> C {
        C(self.0 * o.0 - self.1 * o.1, self.0 * o.1 + self.1 * o.0)
    }
    fn div(self, o: C) -> C {
        let d = o.0 * o.0 + o.1 * o.1;
        C(
            (self.0 * o.0 + self.1 * o.1) / d,
            (self.1 * o.0 - self.0 * o.1) / d,
        )
    }
    fn abs(self) -> f64 {
        self.0.hypot(self.1)
    }
}

/// The loop over one period, on the state (θ, w, θ_prev, Δu_prev), in step units: the
/// controller reads θ (or, with `exact_velocity`, the true w) and commands
/// Δu = −(C_k·θ + C_d·u); the previous command acts for `delay` of the period, the new
/// one for the rest, each integrated exactly (θ'' = Δu per step²).
fn period(x: [f64; 4], ck: f64, cd: f64, delay: f64, exact_velocity: bool) -> [f64; 4] {
    let [theta, w, prev, du_prev] = x;
    let u = if exact_velocity { w } else { theta - prev };
    let du = -(ck * theta + cd * u);
    let (d1, d2) = (delay, 1.0 - delay);
    let theta1 = theta + w * d1 + 0.5 * du_prev * d1 * d1;
    let w1 = w + du_prev * d1;
    [
        theta1 + w1 * d2 + 0.5 * du * d2 * d2,
        w1 + du * d2,
        theta,
        du,
    ]
}

fn matrix(ck: f64, cd: f64, delay: f64, exact_velocity: bool) -> [[f64; 4]; 4] {
    let mut m = [[0.0; 4]; 4];
    for j in 0..4 {
        let mut e = [0.0; 4];
        e[j] = 1.0;
        let col = period(e, ck, cd, delay, exact_velocity);
        for i in 0..4 {
            m[i][j] = col[i];
        }
    }
    m
}

/// det(zI − A) = z⁴ + c₃z³ + … + c₀ by Faddeev–LeVerrier; returned low to high, monic.
fn char_poly(a: [[f64; 4]; 4]) -> [f64; 5] {
    let n = 4;
    let mut c = [0.0; 5];
    c[n] = 1.0;
    let mut m = [[0.0; 4]; 4]; // M_0 = 0
    for k in 1..=n {
        // M_k = A·M_{k−1} + c_{n−k+1}·I
        let mut next = [[0.0; 4]; 4];
        for i in 0..n {
            for j in 0..n {
                let mut s = 0.0;
                for l in 0..n {
                    s += a[i][l] * m[l][j];
                }
                next[i][j] = s + if i == j { c[n - k + 1] } else { 0.0 };
            }
        }
        m = next;
        // c_{n−k} = −tr(A·M_k)/k
        let mut tr = 0.0;
        for i in 0..n {
            for l in 0..n {
                tr += a[i][l] * m[l][i];
            }
        }
        c[n - k] = -tr / k as f64;
    }
    c
}

/// All roots of a polynomial (low to high, leading coefficient non-zero) by
/// Durand–Kerner.
fn roots(p: &[f64]) -> Vec<C> {
    let n = p.len() - 1;
    let lead = p[n];
    let q: Vec<f64> = p.iter().map(|c| c / lead).collect();
    let eval = |z: C| {
        q.iter()
            .rev()
            .fold(C(0.0, 0.0), |acc, &c| acc.mul(z).add(C(c, 0.0)))
    };
    let mut r: Vec<C> = (0..n)
        .map(|k| {
            let a = 0.4 + 0.9 * k as f64;
            C(0.9 * a.cos(), 0.9 * a.sin())
        })
        .collect();
    for _ in 0..2000 {
        let mut change: f64 = 0.0;
        for i in 0..n {
            let mut den = C(1.0, 0.0);
            for j in 0..n {
                if i != j {
                    den = den.mul(r[i].sub(r[j]));
                }
            }
            let step = eval(r[i]).div(den);
            r[i] = r[i].sub(step);
            change = change.max(step.abs());
        }
        if change < 1e-15 {
            break;
        }
    }
    r
}

fn radius_by_eigenvalues(ck: f64, cd: f64, delay: f64, exact_velocity: bool) -> f64 {
    let p = char_poly(matrix(ck, cd, delay, exact_velocity));
    roots(&p).iter().map(|z| z.abs()).fold(0.0, f64::max)
}

fn delay_of(latency: Latency) -> f64 {
    match latency {
        Latency::SameStep => 0.0,
        Latency::OneStep => 1.0,
    }
}

#[test]
fn the_physics_gives_the_documented_polynomials() {
    // The state matrix's characteristic polynomial is z·p(z)/2 without delay (the
    // unused Δu_prev state adds a root at 0) and p(z)/2 with a period of delay.
    for &(ck, cd) in &[(0.1, 0.3), (0.02, 0.05), (0.5, 0.9), (1.0, 1.0), (0.3, 1.7)] {
        let same = char_poly(matrix(ck, cd, 0.0, false));
        let (p, _) = characteristic_polynomial(ck, cd, Latency::SameStep);
        for k in 0..4 {
            assert!(
                (same[k + 1] - p[k] / 2.0).abs() < 1e-12,
                "{k}: {same:?} {p:?}"
            );
        }
        assert!(same[0].abs() < 1e-12);
        let one = char_poly(matrix(ck, cd, 1.0, false));
        let (p, _) = characteristic_polynomial(ck, cd, Latency::OneStep);
        for k in 0..5 {
            assert!((one[k] - p[k] / 2.0).abs() < 1e-12, "{k}: {one:?} {p:?}");
        }
    }
}

#[test]
fn jury_and_eigenvalues_agree_everywhere() {
    // A grid over (C_k, C_d) ∈ [0, 1.2] × [0, 2.2]: stable by Jury ⇔ all eigenvalues
    // inside the unit circle (away from the boundary, where rounding decides), and the
    // library's spectral radius equals the largest eigenvalue.
    let mut checked = 0;
    for latency in [Latency::SameStep, Latency::OneStep] {
        for i in 0..=60 {
            for j in 0..=110 {
                let (ck, cd) = (i as f64 * 0.02, j as f64 * 0.02);
                let eig = radius_by_eigenvalues(ck, cd, delay_of(latency), false);
                if (eig - 1.0).abs() > 1e-6 {
                    assert_eq!(
                        is_stable(ck, cd, latency),
                        eig < 1.0,
                        "{latency:?} {ck} {cd}: {eig}"
                    );
                    checked += 1;
                }
                let lib = spectral_radius(ck, cd, latency);
                // Double roots (the free rotor) are only found to √ε.
                assert!(
                    (lib - eig).abs() < 1e-5,
                    "{latency:?} {ck} {cd}: {lib} vs {eig}"
                );
            }
        }
    }
    assert!(checked > 13_000);
}

#[test]
fn the_same_step_region_is_the_closed_form() {
    for j in 1..200 {
        let cd = j as f64 * 0.01;
        let limit = same_step_stiffness_limit(cd);
        assert!(
            radius_by_eigenvalues(limit * 0.99, cd, 0.0, false) < 1.0,
            "{cd}"
        );
        assert!(
            radius_by_eigenvalues(limit * 1.01, cd, 0.0, false) > 1.0,
            "{cd}"
        );
    }
    // The stiffest stable spring: C_k = 12 − 8√2 at C_d = 2√2 − 2.
    let best = 2.0 * 2f64.sqrt() - 2.0;
    assert!((same_step_stiffness_limit(best) - (12.0 - 8.0 * 2f64.sqrt())).abs() < 1e-12);
    // The article's rigid spring is unstable on a rotor, stable as a particle.
    assert!(radius_by_eigenvalues(1.0, 1.0, 0.0, false) > 1.0);
    // Without damping, nothing is stable.
    assert!(radius_by_eigenvalues(0.01, 0.0, 0.0, false) > 1.0);
}

fn zetas() -> impl Iterator<Item = f64> {
    let (lo, hi) = DAMPING_RATIO_RANGE;
    (0..=36).map(move |k| lo + (hi - lo) * k as f64 / 36.0)
}

#[test]
fn every_strength_keeps_the_gain_margin() {
    // Every strength on a grid of 0.02, every accepted ζ on a grid of 0.05, both maps;
    // every gain factor up to the margin in steps of 0.1; for the one-step map, delays
    // of 0, ¼, ½, ¾ and 1 period, and a caller-supplied exact velocity.
    let mut worst: f64 = 0.0;
    let mut top_radius: f64 = 0.0;
    for latency in [Latency::SameStep, Latency::OneStep] {
        let delays: &[f64] = match latency {
            Latency::SameStep => &[0.0],
            Latency::OneStep => &[0.0, 0.25, 0.5, 0.75, 1.0],
        };
        for zeta in zetas() {
            let map = StrengthMap::new(zeta, latency).unwrap();
            let mut previous = (0.0, 0.0);
            for s in 1..=50 {
                let strength = s as f64 / 50.0;
                let (ck, cd) = map.coefficients(strength).unwrap();
                assert!(ck > previous.0, "stiffness must rise with strength");
                previous = (ck, cd);
                for &delay in delays {
                    for g in 1..=20 {
                        let gain = GAIN_MARGIN * g as f64 / 20.0;
                        for exact in [false, true] {
                            let r = radius_by_eigenvalues(gain * ck, gain * cd, delay, exact);
                            assert!(
                                r < 1.0,
                                "{latency:?} ζ {zeta} s {strength} delay {delay} gain {gain} exact {exact}: {r}"
                            );
                            if g == 20 {
                                worst = worst.max(r);
                            }
                        }
                    }
                }
                if s == 50 {
                    let r = radius_by_eigenvalues(ck, cd, delay_of(latency), false);
                    top_radius = top_radius.max(r);
                }
            }
        }
    }
    println!("largest radius at twice the gains: {worst:.6}; at strength 1: {top_radius:.4}");
    assert!(top_radius < 0.96);
}

#[test]
fn every_accepted_configuration_keeps_the_margin() {
    // Strength combinations on a grid of 0.1 per layer, at two rates: each
    // accepted knob's three zones keep the margin; each rejected one exceeds a sum.
    let mut accepted = 0;
    let mut rejected = 0;
    for latency in [Latency::SameStep, Latency::OneStep] {
        for zeta in [0.2, 0.7, 1.3, 2.0] {
            // The coefficients do not depend on dt or the inertia (the map is
            // dimensionless); two rates show it.
            for (dt, inertia) in [(1e-3, 1e-5), (1e-4, 1e-6)] {
                for d in 0..=10 {
                    for m in 0..=10 {
                        for r in 0..=10 {
                            for e in [0, 5, 10] {
                                let (d, m, r, e) = (
                                    d as f64 / 10.0,
                                    m as f64 / 10.0,
                                    r as f64 / 10.0,
                                    e as f64 / 10.0,
                                );
                                let config = KnobConfig::new(dt, inertia, 0.05)
                                    .latency(latency)
                                    .damping_ratio(zeta)
                                    .endstops(-1.0, 1.0)
                                    .endstop_strength(e)
                                    .detent_count(9)
                                    .detent_strength(d)
                                    .magnets(&[-0.5, 0.5])
                                    .magnet_strength(m)
                                    .return_to_centre(0.0, r);
                                match Knob::<f32>::new(&config, 0.0) {
                                    Ok(knob) => {
                                        accepted += 1;
                                        for (ck, cd) in knob.loop_coefficients() {
                                            let delays: &[f64] = if latency == Latency::OneStep {
                                                &[0.0, 1.0]
                                            } else {
                                                &[0.0]
                                            };
                                            for &delay in delays {
                                                for g in [0.5, 1.0, 1.5, GAIN_MARGIN] {
                                                    let rad = radius_by_eigenvalues(
                                                        g * ck,
                                                        g * cd,
                                                        delay,
                                                        false,
                                                    );
                                                    assert!(rad < 1.0 || ck == 0.0, "{config:?}");
                                                }
                                            }
                                        }
                                    }
                                    Err(err) => {
                                        rejected += 1;
                                        assert_eq!(err, Error::OutOfRange(Parameter::Strength));
                                        assert!(d + m + r > 1.0 + 1e-9 || e + r > 1.0 + 1e-9);
                                    }
                                }
                            }
                        }
                    }
                }
            }
        }
    }
    println!("{accepted} accepted, {rejected} rejected");
    assert!(accepted > 5_000 && rejected > 5_000);
}

/// A rotor under the raw law τ = −(I/dt²)(C_k·θ + C_d·u), no quantisation or clamp:
/// the amplitude over the last quarter relative to the start.
fn simulate_raw(ck: f64, cd: f64, delay: f64, steps: usize) -> f64 {
    let (inertia, dt) = (1e-5, 1e-3);
    let mut plant = Plant::new(inertia, dt, delay);
    plant.theta = 0.01;
    let mut prev = plant.theta;
    let mut late: f64 = 0.0;
    for n in 0..steps {
        let theta = plant.theta;
        let tau = -(inertia / (dt * dt)) * (ck * theta + cd * (theta - prev));
        prev = theta;
        plant.step(tau, &mut lab::knob::no_hand);
        if n > steps * 3 / 4 {
            late = late.max(plant.theta.abs());
        }
    }
    late / 0.01
}

#[test]
fn just_outside_the_region_the_rotor_grows() {
    // Along the ray of each map's strongest spring: the true boundary lies beyond the
    // margin; 3% past it a simulated rotor grows, 3% inside it decays.
    for latency in [Latency::SameStep, Latency::OneStep] {
        for zeta in [0.2, 0.7, 1.0, 2.0] {
            let (ck, cd) = StrengthMap::new(zeta, latency)
                .unwrap()
                .coefficients(1.0)
                .unwrap();
            let (mut lo, mut hi) = (1.0, 10.0);
            for _ in 0..60 {
                let mid = 0.5 * (lo + hi);
                if radius_by_eigenvalues(mid * ck, mid * cd, delay_of(latency), false) < 1.0 {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            assert!(lo >= GAIN_MARGIN, "{latency:?} ζ {zeta}: boundary at {lo}");
            let d = delay_of(latency);
            let outside = simulate_raw(1.03 * lo * ck, 1.03 * lo * cd, d, 20_000);
            let inside = simulate_raw(0.97 * lo * ck, 0.97 * lo * cd, d, 20_000);
            assert!(
                outside > 10.0,
                "{latency:?} ζ {zeta}: outside grew only {outside}"
            );
            assert!(inside < 0.1, "{latency:?} ζ {zeta}: inside {inside}");
            println!(
                "{latency:?} ζ {zeta}: boundary at {lo:.3}× strength 1; 3% out ×{outside:.1e}, 3% in ×{inside:.1e}"
            );
        }
    }
    // And the API refuses the first step past strength 1.
    let config = KnobConfig::new(1e-3, 1e-5, 0.05)
        .detent_width(0.1)
        .detent_strength(1.0 + 1e-9);
    assert_eq!(
        Knob::<f32>::new(&config, 0.0).unwrap_err(),
        Error::OutOfRange(Parameter::Strength)
    );
}
