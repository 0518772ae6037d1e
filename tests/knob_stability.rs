//! The knob's loop guarantee, checked independently of the library's analysis:
//!
//! - the loop's state matrix is built from the rotor's physics in `lab/src/knob/linear.rs`
//!   (ZOH, the filtered backward difference, a delay of any fraction of a period); its
//!   characteristic polynomial `det(z·I − A)` agrees with the library's polynomial, and its
//!   eigenvalues (nalgebra's Schur form) with the library's Jury test;
//! - every zone of every accepted configuration of a grid, at 41 inertias from `J/2` to
//!   `2J` (the library checks 9), with and without the period of delay: every pole inside
//!   the decay radius, with a Tustin damping ratio of at least `MIN_DAMPING_RATIO` and clear
//!   of `z = −1`; also stable at half a period of delay;
//! - just past the stiffest accepted detent the guarantee fails (so the test can fail), and
//!   a simulated rotor grows past the stability boundary.
//!
//! Run `cargo test --release --test knob_stability -- --nocapture` for the figures.

use lab::knob::linear::{characteristic_at, poles, state_matrix};
use lab::knob::sweep::Rotor;
use lab::linear::Complex;
use lab::rng::Rng;
use std::f64::consts::TAU;
use stiffspring::knob::{
    DECAY_FRACTION, INERTIA_UNCERTAINTY, Latency, Limit, LoopCoefficients, MIN_DAMPING_RATIO,
    characteristic_polynomial, is_stable, meets_guarantee,
};
use stiffspring::{Knob, KnobConfig};

fn delay_of(latency: Latency) -> f64 {
    match latency {
        Latency::SameStep => 0.0,
        Latency::OneStep => 1.0,
    }
}

/// The delays a latency is checked at: its own, and none for one period.
fn delays(latency: Latency) -> &'static [f64] {
    match latency {
        Latency::SameStep => &[0.0],
        Latency::OneStep => &[0.0, 1.0],
    }
}

/// What the guarantee says of one loop at one delay, from the eigenvalues: (largest |z|,
/// least Tustin ζ, largest |w|, least discrete ζ from s = ln z / dt). Zero poles (states
/// the loop does not use) are left out of the last three.
fn measures(c: LoopCoefficients, delay: f64) -> (f64, f64, f64, f64) {
    let mut out = (0.0f64, f64::INFINITY, 0.0f64, f64::INFINITY);
    for z in poles(c.stiffness, c.damping, c.filter, delay) {
        out.0 = out.0.max(z.norm());
        if z.norm() < 1e-9 {
            continue;
        }
        let w = (z - 1.0) / (z + 1.0);
        if w.norm() > 1e-12 {
            out.1 = out.1.min(-w.re / w.norm());
        }
        out.2 = out.2.max(w.norm());
        let (re, im) = (z.norm().ln(), z.im.atan2(z.re));
        out.3 = out.3.min(-re / re.hypot(im));
    }
    out
}

fn scaled(c: LoopCoefficients, g: f64) -> LoopCoefficients {
    LoopCoefficients {
        stiffness: g * c.stiffness,
        damping: g * c.damping,
        filter: c.filter,
    }
}

/// The slowest decay rate of `J·s² + B·s + K` (1/s); `B/J` without a spring.
fn slowest_decay(k: f64, b: f64, j: f64) -> f64 {
    if k <= 0.0 {
        return b / j;
    }
    let disc = b * b - 4.0 * j * k;
    if disc <= 0.0 {
        b / (2.0 * j)
    } else {
        (b - disc.sqrt()) / (2.0 * j)
    }
}

#[test]
fn the_physics_gives_the_documented_polynomials() {
    let mut rng = Rng::seeded(13);
    let mut compared = 0;
    for _ in 0..40 {
        let c = LoopCoefficients {
            stiffness: rng.log_range(1e-4, 1.0),
            damping: rng.log_range(1e-3, 1.5),
            filter: rng.range(0.02, 1.0),
        };
        // Without delay the Δu_prev state adds a root at 0, and the θ_prev state another:
        // det(zI − A) = z^(2−d)·p(z)/2, p of degree 3 + d.
        for delay in [0usize, 1] {
            let a = state_matrix(c.stiffness, c.damping, c.filter, delay as f64);
            let (p, n) = characteristic_polynomial(c, delay);
            assert_eq!(n, 3 + delay);
            // Two polynomials of degree 5 that agree at 6 points are the same.
            for k in 0..6 {
                let z = Complex::from_polar(1.3, 0.4 + TAU * k as f64 / 6.0);
                let library = p[..=n]
                    .iter()
                    .rev()
                    .fold(Complex::new(0.0, 0.0), |acc, &x| acc * z + x)
                    * z.powi(2 - delay as i32)
                    / 2.0;
                let physics = characteristic_at(&a, z);
                assert!(
                    (library - physics).norm() < 1e-11 * physics.norm().max(1.0),
                    "{c:?} delay {delay} at {z}: {library} against {physics}"
                );
                compared += 1;
            }
        }
    }
    assert_eq!(compared, 480);
}

#[test]
fn jury_and_eigenvalues_agree_everywhere() {
    let mut checked = 0;
    let mut unstable = 0;
    for latency in [Latency::SameStep, Latency::OneStep] {
        for a in [1.0, 0.5, 0.1] {
            for i in 1..=30 {
                for j in 0..=30 {
                    let c = LoopCoefficients {
                        stiffness: i as f64 * 0.02,
                        damping: j as f64 * 0.05,
                        filter: a,
                    };
                    let (r, ..) = measures(c, delay_of(latency));
                    // Points within rounding of the boundary say nothing.
                    if (r - 1.0).abs() > 1e-6 {
                        assert_eq!(is_stable(c, latency), r < 1.0, "{latency:?} {c:?}: {r}");
                        checked += 1;
                        unstable += usize::from(r > 1.0);
                    }
                }
            }
        }
    }
    // Both sides of the boundary are on the grid.
    assert!(checked > 5_000 && unstable > 1_000, "{checked} {unstable}");
}

/// An accepted configuration of the grid, with what the test needs to know of it.
struct Case {
    config: KnobConfig,
    inertia: f64,
    latency: Latency,
}

/// A grid of configurations: detents (fractions of the stiffest accepted), with endstops
/// at their default, or a return spring and magnets.
fn configs() -> Vec<Case> {
    let mut v = Vec::new();
    for rate in [1_000.0, 4_000.0, 10_000.0] {
        for inertia in [1e-6, 1e-5, 1e-4] {
            for zeta in [0.2, 0.7, 1.3, 2.0] {
                for latency in [Latency::SameStep, Latency::OneStep] {
                    for layout in 0..3 {
                        let base = KnobConfig::new(rate, inertia, 0.1, 16384)
                            .latency(latency)
                            .damping_ratio(zeta);
                        let base = match layout {
                            0 => base.detent_width(TAU / 24.0),
                            1 => base.endstops(-2.0, 2.0).detent_count(24),
                            _ => base
                                .endstops(-2.0, 2.0)
                                .magnets(&[-1.0, 0.0, 1.0])
                                .magnet_radius(0.2)
                                .return_to_centre(0.0, 0.001),
                        };
                        let Ok(top) = base.detent_stiffness_limit::<f64>() else {
                            continue;
                        };
                        for s in [0.01, 0.1, 0.5, 1.0] {
                            let config = if layout == 2 {
                                // Magnets up to their peak torque at the release radius.
                                base.magnet_stiffness(s * 0.1 / 0.21)
                            } else {
                                base.detent_stiffness(s * top)
                            };
                            v.push(Case {
                                config,
                                inertia,
                                latency,
                            });
                        }
                    }
                }
            }
        }
    }
    v
}

#[test]
fn every_accepted_configuration_meets_the_guarantee_by_eigenvalues() {
    let mut zones = 0;
    let mut least_tustin = f64::INFINITY;
    let mut least_discrete = f64::INFINITY;
    let mut largest_half_delay = 0.0f64;
    for Case {
        config,
        inertia,
        latency,
    } in configs()
    {
        let Ok(knob) = Knob::<f64>::new(&config, 0.0) else {
            continue;
        };
        let stiffness = knob.zone_stiffness();
        let coefficients = knob.loop_coefficients();
        let (b, dt) = (knob.damping(), config.dt());
        // The reported coefficients are the physical ones: C_k = K·dt²/J, C_d = B·dt/J.
        for z in 0..3 {
            if let Some(c) = coefficients[z] {
                assert!(
                    (c.stiffness - stiffness[z] * dt * dt / inertia).abs()
                        <= 1e-12 * c.stiffness.max(1e-300)
                );
                assert!((c.damping - b * dt / inertia).abs() <= 1e-12 * c.damping.max(1e-300));
            }
        }
        // The decay target: a third of the slowest continuous decay over the zones.
        let slowest = (0..3)
            .filter(|&z| coefficients[z].is_some())
            .map(|z| slowest_decay(stiffness[z], b, inertia))
            .fold(f64::INFINITY, f64::min);
        let radius = (-DECAY_FRACTION * slowest * dt).exp();
        for c in coefficients.into_iter().flatten() {
            if c.stiffness == 0.0 && c.damping == 0.0 {
                continue;
            }
            assert!(meets_guarantee(c, latency, radius * (1.0 + 1e-12)));
            zones += 1;
            for k in 0..=40 {
                let g = (1.0 / INERTIA_UNCERTAINTY)
                    * (INERTIA_UNCERTAINTY * INERTIA_UNCERTAINTY).powf(k as f64 / 40.0);
                for &delay in delays(latency) {
                    let (r, zt, w, zd) = measures(scaled(c, g), delay);
                    let what = format!("{config:?} {c:?} g {g} delay {delay}");
                    // The decay with a little slack for the sampled grid of gains
                    // between the library's nine.
                    assert!(
                        r < 1.0 && r <= radius.powf(0.8),
                        "{what}: radius {r} > {radius}"
                    );
                    assert!(zt >= 0.8 * MIN_DAMPING_RATIO, "{what}: Tustin ζ {zt}");
                    assert!(w < 6.5, "{what}: |w| {w}");
                    least_tustin = least_tustin.min(zt);
                    least_discrete = least_discrete.min(zd);
                }
                if latency == Latency::OneStep {
                    let (r, ..) = measures(scaled(c, g), 0.5);
                    assert!(r < 1.0, "{config:?} half a period: {r}");
                    largest_half_delay = largest_half_delay.max(r);
                }
            }
        }
    }
    println!(
        "{zones} zones; least Tustin damping ratio {least_tustin:.3}, least discrete {least_discrete:.3} \
         over J/2…2J; largest radius at half a period of delay {largest_half_delay:.5}"
    );
    assert!(zones > 300);
}

#[test]
fn just_past_the_stiffest_accepted_detent_the_guarantee_fails() {
    let mut failed_checks = 0;
    for rate in [1_000.0, 10_000.0] {
        for zeta in [0.2, 0.7, 2.0] {
            for latency in [Latency::SameStep, Latency::OneStep] {
                // A 2 N·m motor, so that the loop binds before the peak torque.
                let base = KnobConfig::new(rate, 1e-5, 2.0, 16384)
                    .latency(latency)
                    .damping_ratio(zeta)
                    .detent_width(TAU / 24.0);
                let top = base.detent_stiffness_limit::<f64>().unwrap();
                assert!(Knob::<f64>::new(&base.detent_stiffness(0.98 * top), 0.0).is_ok());
                let above = base.detent_stiffness(1.02 * top);
                let err = Knob::<f64>::new(&above, 0.0).unwrap_err();
                println!(
                    "{rate} Hz ζ {zeta} {latency:?}: stiffest {top:.4} N·m/rad; 1.02× refused: {:?}",
                    err.bound
                );
                // With the filter off and that stiffness, the eigenvalues break a condition
                // of the guarantee somewhere in J/2…2J (unless the peak torque binds).
                if matches!(err.bound, Limit::LoopStiffness(_)) {
                    let k = 1.02 * top;
                    let b = 2.0 * zeta * (k * 1e-5f64).sqrt();
                    let dt = 1.0 / rate;
                    let c = LoopCoefficients {
                        stiffness: k * dt * dt / 1e-5,
                        damping: b * dt / 1e-5,
                        filter: 1.0,
                    };
                    let radius = (-DECAY_FRACTION * slowest_decay(k, b, 1e-5) * dt).exp();
                    let broken = (0..=40).any(|i| {
                        let g = 0.5 * 4f64.powf(i as f64 / 40.0);
                        delays(latency).iter().any(|&d| {
                            let (r, zt, w, _) = measures(scaled(c, g), d);
                            r > radius || zt < MIN_DAMPING_RATIO || w > 6.0
                        })
                    });
                    assert!(broken, "{rate} {zeta} {latency:?}");
                    failed_checks += 1;
                }
            }
        }
    }
    assert!(failed_checks >= 8, "{failed_checks}");
}

/// A rotor under the raw law, no quantisation or clamp: amplitude over the last quarter
/// relative to the start.
fn simulate_raw(c: LoopCoefficients, delay: usize, steps: usize) -> f64 {
    let (inertia, dt) = (1e-5, 1e-3);
    let mut rotor = Rotor::new(inertia, dt, delay, 0.01, 0.0);
    let (mut prev, mut v, mut late) = (0.01, 0.0, 0.0f64);
    for n in 0..steps {
        let theta = rotor.theta;
        v = (1.0 - c.filter) * v + c.filter * (theta - prev);
        prev = theta;
        let tau = -(inertia / (dt * dt)) * (c.stiffness * theta + c.damping * v);
        rotor.step(tau);
        if n > steps * 3 / 4 {
            late = late.max(rotor.theta.abs());
        }
    }
    late / 0.01
}

#[test]
fn past_the_stability_boundary_the_rotor_grows() {
    // Along a ray of gains from a guaranteed loop: 3% past where the library says it turns
    // unstable, a simulated rotor grows; 3% inside, it decays.
    for latency in [Latency::SameStep, Latency::OneStep] {
        let c = LoopCoefficients {
            stiffness: 0.02,
            damping: 0.2,
            filter: 0.5,
        };
        let (mut lo, mut hi) = (1.0, 50.0);
        for _ in 0..60 {
            let mid = 0.5 * (lo + hi);
            if is_stable(scaled(c, mid), latency) {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        assert!(lo > INERTIA_UNCERTAINTY);
        let d = usize::from(latency == Latency::OneStep);
        let outside = simulate_raw(scaled(c, 1.03 * lo), d, 40_000);
        let inside = simulate_raw(scaled(c, 0.97 * lo), d, 40_000);
        assert!(outside > 10.0, "{latency:?}: outside grew only {outside}");
        assert!(inside < 0.1, "{latency:?}: inside {inside}");
        println!("{latency:?}: boundary at {lo:.3}×; 3% out ×{outside:.1e}, 3% in ×{inside:.1e}");
    }
}
