//! Self-tests of the independent reference model in `lab/src/reference.rs`.
//!
//! These check the reference against itself and against mathematics (ODE
//! residuals, an RK4 integration, algebraic identities, conservation laws),
//! so that a wrong reference is caught before it is used to judge the
//! library. They use nothing but std and the reference module.

use lab::reference;
use lab::rng::Rng;

use reference::*;
use std::f64::consts::{PI, TAU};

// ---------------------------------------------------------------------------
// Helpers
// ---------------------------------------------------------------------------

/// Damping ratios covering all regimes, including near-critical ones.
const ZETAS: [f64; 14] = [
    0.0,
    0.01,
    0.1,
    0.3,
    0.7,
    0.999,
    0.999_999_9,
    1.0,
    1.000_000_1,
    1.001,
    1.1,
    1.5,
    3.0,
    10.0,
];

/// One classical RK4 step of `x'' = -2ζω·x' - ω²·x`.
fn rk4_step(x: &mut f64, v: &mut f64, omega: f64, zeta: f64, h: f64) {
    let acc = |x: f64, v: f64| -2.0 * zeta * omega * v - omega * omega * x;
    let (k1x, k1v) = (*v, acc(*x, *v));
    let (k2x, k2v) = (
        *v + 0.5 * h * k1v,
        acc(*x + 0.5 * h * k1x, *v + 0.5 * h * k1v),
    );
    let (k3x, k3v) = (
        *v + 0.5 * h * k2v,
        acc(*x + 0.5 * h * k2x, *v + 0.5 * h * k2v),
    );
    let (k4x, k4v) = (*v + h * k3v, acc(*x + h * k3x, *v + h * k3v));
    *x += h / 6.0 * (k1x + 2.0 * k2x + 2.0 * k3x + k4x);
    *v += h / 6.0 * (k1v + 2.0 * k2v + 2.0 * k3v + k4v);
}

fn assert_close(what: &str, got: f64, want: f64, tol: f64) {
    assert!(
        (got - want).abs() <= tol,
        "{what}: got {got:e}, want {want:e}, |diff| {:e} > tol {tol:e}",
        (got - want).abs()
    );
}

// ---------------------------------------------------------------------------
// Coefficient limits and reduced mass
// ---------------------------------------------------------------------------

#[test]
fn limits_and_reduced_mass() {
    assert_close("k_max", k_max(2.0, 0.1), 200.0, 1e-12);
    assert_close("d_max", d_max(2.0, 0.1), 20.0, 1e-13);
    assert_close("m_red(3, 6)", reduced_mass(3.0, 6.0), 2.0, 1e-15);
    assert_close("m_red(m, m)", reduced_mass(5.0, 5.0), 2.5, 1e-15);
    // A pinned body: the reduced mass is the free body's mass, exactly.
    assert_eq!(reduced_mass(1.7, f64::INFINITY), 1.7);
    assert_eq!(reduced_mass(f64::INFINITY, 0.3), 0.3);
    assert_eq!(reduced_mass(f64::INFINITY, f64::INFINITY), f64::INFINITY);

    let mut rng = Rng::seeded(1);
    for _ in 0..1000 {
        let (m1, m2) = (rng.log_range(1e-3, 1e3), rng.log_range(1e-3, 1e3));
        let r = reduced_mass(m1, m2);
        // eq. 17 == eq. 18, symmetric, below both masses.
        assert_close(
            "eq17 vs eq18",
            reduced_mass_product_form(m1, m2),
            r,
            1e-14 * r,
        );
        assert_close("symmetry", reduced_mass(m2, m1), r, 1e-15 * r);
        assert!(r < m1 && r < m2);
    }
}

// ---------------------------------------------------------------------------
// Analytic solution of the continuous oscillator
// ---------------------------------------------------------------------------

#[test]
fn analytic_meets_initial_conditions_in_every_regime() {
    let mut rng = Rng::seeded(2);
    for &zeta in ZETAS.iter().chain([30.0, 1e4].iter()) {
        for _ in 0..50 {
            let omega = rng.log_range(0.1, 1e3);
            let (x0, v0) = (rng.sym(10.0), rng.sym(10.0) * omega);
            let (x, v) = analytic(x0, v0, omega, zeta, 0.0);
            // v(0) = v0 may come out of a sum of mode terms of size ω·|x0|.
            let a = x0.abs() + v0.abs() / omega;
            assert_close("x(0)", x, x0, 4.0 * f64::EPSILON * a);
            assert_close("v(0)", v, v0, 4.0 * f64::EPSILON * a * omega);
        }
    }
    // omega = 0: free motion, in every regime.
    for &zeta in &ZETAS {
        let (x, v) = analytic(1.5, -0.5, 0.0, zeta, 3.0);
        assert_close("free x", x, 0.0, 1e-15);
        assert_close("free v", v, -0.5, 1e-15);
    }
}

#[test]
fn analytic_satisfies_the_ode_and_v_is_dx_dt() {
    let mut rng = Rng::seeded(3);
    for &zeta in ZETAS.iter().chain([100.0].iter()) {
        for _ in 0..20 {
            let omega = rng.log_range(0.5, 500.0);
            let (x0, v0) = (rng.sym(1.0), rng.sym(1.0) * omega);
            let fast = omega * (1.0 + 2.0 * zeta); // bound on the fastest rate
            let h = 1e-3 / fast;
            for _ in 0..20 {
                // Negative times too (u0_from_analytic evaluates t = -dt), on
                // the fast and on the slow time scale.
                let t = if rng.unit() < 0.5 {
                    rng.range(-1.0, 10.0) / fast
                } else {
                    rng.range(-0.1, 10.0) / omega
                };
                let (xm, _) = analytic(x0, v0, omega, zeta, t - h);
                let (x, v) = analytic(x0, v0, omega, zeta, t);
                let (xp, _) = analytic(x0, v0, omega, zeta, t + h);
                let d1 = (xp - xm) / (2.0 * h);
                let d2 = (xp - 2.0 * x + xm) / (h * h);
                let damp = 2.0 * zeta * omega * v;
                let spring = omega * omega * x;
                let scale = d2.abs() + damp.abs() + spring.abs() + 1e-300;
                // Rounding of the differences themselves (not the formula).
                let fd2 = 8.0 * f64::EPSILON * (xp.abs() + 2.0 * x.abs() + xm.abs()) / (h * h);
                let fd1 = 8.0 * f64::EPSILON * (xp.abs() + xm.abs()) / (2.0 * h);
                let residual = d2 + damp + spring;
                assert!(
                    residual.abs() <= 1e-5 * scale + fd2,
                    "ODE residual {residual:e} vs {scale:e} (zeta {zeta}, omega {omega}, t {t})"
                );
                let vscale = v.abs() + fast * x.abs();
                assert!(
                    (d1 - v).abs() <= 1e-6 * vscale + fd1,
                    "v != dx/dt: {v:e} vs {d1:e} (zeta {zeta}, omega {omega}, t {t})"
                );
            }
        }
    }
}

#[test]
fn analytic_is_a_flow() {
    // phi(t2, phi(t1, s)) == phi(t1 + t2, s), also with negative times; this
    // is what makes u0_from_analytic (a backward step) consistent.
    let mut rng = Rng::seeded(4);
    for &zeta in &ZETAS {
        for _ in 0..50 {
            let omega = rng.log_range(0.5, 100.0);
            let (x0, v0) = (rng.sym(1.0), rng.sym(1.0) * omega);
            let t1 = rng.range(-0.5, 3.0) / omega;
            let t2 = rng.range(-0.5, 3.0) / omega;
            let (x1, v1) = analytic(x0, v0, omega, zeta, t1);
            let (x12, v12) = analytic(x1, v1, omega, zeta, t2);
            let (x, v) = analytic(x0, v0, omega, zeta, t1 + t2);
            let a = x0.abs() + v0.abs() / omega;
            let growth = (zeta + 1.0) * 20.0; // backward-time growth allowance
            assert_close("flow x", x12, x, 1e-13 * a * growth);
            assert_close("flow v", v12, v, 1e-13 * a * omega * growth);
        }
    }
}

#[test]
fn analytic_is_continuous_across_critical_damping() {
    let mut rng = Rng::seeded(5);
    for _ in 0..200 {
        let omega = rng.log_range(0.1, 1e3);
        let (x0, v0) = (rng.sym(1.0), rng.sym(1.0) * omega);
        let a = x0.abs() + v0.abs() / omega;
        let t = rng.range(-0.2, 12.0) / omega;
        let (xc, vc) = analytic(x0, v0, omega, 1.0, t);
        for (delta, tol) in [(1e-7, 1e-6), (1e-12, 1e-10), (f64::EPSILON, 1e-12)] {
            for zeta in [1.0 - delta, 1.0 + delta] {
                let (x, v) = analytic(x0, v0, omega, zeta, t);
                assert!(x.is_finite() && v.is_finite());
                assert_close("x near zeta=1", x, xc, tol * a);
                assert_close("v near zeta=1", v, vc, tol * a * omega);
            }
        }
    }
}

#[test]
fn analytic_is_continuous_across_the_overdamped_form_switch() {
    // The overdamped branch switches form at q = √(ζ²−1) = 0.5.
    let z_switch = 1.25_f64.sqrt();
    let mut rng = Rng::seeded(23);
    for _ in 0..200 {
        let omega = rng.log_range(0.1, 1e3);
        let (x0, v0) = (rng.sym(1.0), rng.sym(1.0) * omega);
        let a = x0.abs() + v0.abs() / omega;
        let t = rng.range(-0.2, 12.0) / omega;
        let (xl, vl) = analytic(x0, v0, omega, z_switch * (1.0 - 1e-15), t);
        let (xh, vh) = analytic(x0, v0, omega, z_switch * (1.0 + 1e-15), t);
        assert_close("x at switch", xl, xh, 1e-13 * a);
        assert_close("v at switch", vl, vh, 1e-13 * a * omega);
    }
}

#[test]
fn analytic_matches_fine_rk4() {
    let mut rng = Rng::seeded(6);
    for &zeta in ZETAS.iter().chain([100.0].iter()) {
        let omega = rng.log_range(0.5, 50.0);
        let (x0, v0) = (rng.sym(1.0), rng.sym(1.0) * omega);
        let a = x0.abs() + v0.abs() / omega;
        let fast = omega * (1.0 + 2.0 * zeta);
        let h = 2e-3 / fast;
        let n = (8.0 * fast / omega / 2e-3).ceil() as usize; // up to t = 8/omega
        let (mut x, mut v) = (x0, v0);
        for i in 1..=n {
            rk4_step(&mut x, &mut v, omega, zeta, h);
            if i % (n / 16) == 0 || i == n {
                let (xa, va) = analytic(x0, v0, omega, zeta, i as f64 * h);
                assert_close("rk4 x", x, xa, 1e-9 * a);
                assert_close("rk4 v", v, va, 1e-9 * a * fast);
            }
        }
    }
}

#[test]
fn analytic_large_zeta_is_sane() {
    // For large ζ the solution must stay finite, never exceed the bound
    // |x0| + |v0|/λ2-ish, and follow the slow mode after the fast transient.
    for zeta in [10.0, 100.0, 1e4, 1e8] {
        let omega = 3.0;
        let (x0, v0) = (1.0, -2.0);
        let q = ((zeta - 1.0) * (zeta + 1.0_f64)).sqrt();
        let (l1, l2) = (omega / (zeta + q), omega * (zeta + q));
        for t in [1e-3, 0.1, 1.0, 10.0, 1e3, 1e6] {
            let (x, v) = analytic(x0, v0, omega, zeta, t);
            assert!(x.is_finite() && v.is_finite(), "zeta {zeta} t {t}");
            assert!(x.abs() <= x0.abs() + v0.abs() / l2 + 1e-15);
            if l2 * t > 50.0 {
                // Fast mode gone: x = c1·e^{-λ1 t}, c1 = (λ2·x0 + v0)/(λ2 − λ1).
                let c1 = (l2 * x0 + v0) / (l2 - l1);
                let want = c1 * (-l1 * t).exp();
                assert_close("slow mode x", x, want, 1e-12 * c1.abs());
                assert_close("slow mode v", v, -l1 * want, 1e-12 * l1 * c1.abs());
            }
        }
    }
}

#[test]
fn analytic_undamped_conserves_energy() {
    let mut rng = Rng::seeded(7);
    for _ in 0..200 {
        let omega = rng.log_range(0.1, 1e3);
        let (x0, v0) = (rng.sym(1.0), rng.sym(1.0) * omega);
        let e0 = v0 * v0 + omega * omega * x0 * x0;
        let (x, v) = analytic(x0, v0, omega, 0.0, rng.range(-100.0, 100.0) / omega);
        assert_close("energy", v * v + omega * omega * x * x, e0, 1e-12 * e0);
    }
}

// ---------------------------------------------------------------------------
// One body on an anchor
// ---------------------------------------------------------------------------

#[test]
fn full_coefficients_reach_rest_in_one_step_and_stop_in_two() {
    let mut rng = Rng::seeded(8);
    for _ in 0..1000 {
        let m = rng.log_range(1e-3, 1e3);
        let dt = rng.log_range(1e-4, 1e-1);
        let (x0, v0) = (rng.sym(10.0), rng.sym(10.0) / dt);
        let sx = x0.abs() + v0.abs() * dt;
        for impulse in [false, true] {
            let mut p = Particle1::new(x0, v0, m);
            let step = |p: &mut Particle1| {
                if impulse {
                    p.impulse_step(1.0, 1.0, dt)
                } else {
                    p.force_step(1.0, 1.0, dt)
                }
            };
            step(&mut p);
            // Position at rest after one step, but the velocity is -x0/dt
            // (the body is fully at rest only after the second step).
            assert_close("x after 1", p.x, 0.0, 1e-14 * sx);
            assert_close("v after 1", p.v, -x0 / dt, 1e-14 * sx / dt);
            step(&mut p);
            assert_close("x after 2", p.x, 0.0, 1e-14 * sx);
            assert_close("v after 2", p.v, 0.0, 1e-14 * sx / dt);
        }
    }
}

#[test]
fn impulse_and_force_forms_agree_for_one_body() {
    let mut rng = Rng::seeded(9);
    for _ in 0..500 {
        let m = rng.log_range(1e-3, 1e3);
        let dt = rng.log_range(1e-4, 1e-1);
        let (ck, cd) = (rng.range(1e-4, 1.0), rng.range(0.0, 1.0));
        let (x0, v0) = (rng.sym(10.0), rng.sym(10.0) / dt);
        let sx = x0.abs() + v0.abs() * dt;
        let mut f = Particle1::new(x0, v0, m);
        let mut i = f;
        for _ in 0..200 {
            f.force_step(ck, cd, dt);
            i.impulse_step(ck, cd, dt);
            assert_close("x", f.x, i.x, 1e-12 * sx);
            assert_close("v", f.v, i.v, 1e-12 * sx / dt);
        }
    }
}

#[test]
fn map_step_in_units_of_v_dt_agrees_with_impulse_step() {
    let mut rng = Rng::seeded(10);
    for _ in 0..500 {
        let m = rng.log_range(1e-3, 1e3);
        let dt = rng.log_range(1e-4, 1e-1);
        let (ck, cd) = (rng.range(1e-4, 1.0), rng.range(0.0, 1.0));
        let (x0, v0) = (rng.sym(10.0), rng.sym(10.0) / dt);
        let sx = x0.abs() + v0.abs() * dt;
        let mut p = Particle1::new(x0, v0, m);
        let (mut x, mut u) = (x0, v0 * dt);
        for _ in 0..200 {
            p.impulse_step(ck, cd, dt);
            map_step(&mut x, &mut u, ck, cd);
            assert_close("x", x, p.x, 1e-12 * sx);
            assert_close("u", u, p.v * dt, 1e-12 * sx);
        }
    }
}

#[test]
fn undamped_symplectic_euler_energy_is_bounded_without_drift() {
    // Symplectic Euler conserves a modified quadratic energy exactly. From the
    // recurrence x_{n+1} = (2 − C_k)·x_n − x_{n−1} (C_d = 0), the invariant is
    // u² − C_k·x·u + C_k·x² with u = v·dt, i.e. E − ½·k·dt·x·v with the
    // physical E = ½·m·v² + ½·k·x². So E oscillates (by about ω·dt/2
    // relative) but never drifts.
    let (m, dt, ck) = (2.0, 1e-3, 0.01);
    let k = k_max(m, dt) * ck;
    let modified = |p: &Particle1| p.energy(k) - 0.5 * k * dt * p.x * p.v;
    let mut p = Particle1::new(0.3, 0.0, m);
    let (e0, h0) = (p.energy(k), modified(&p));
    for _ in 0..100_000 {
        p.force_step(ck, 0.0, dt);
        let e = p.energy(k);
        assert!(e > 0.9 * e0 && e < 1.1 * e0, "energy {e} vs {e0}");
        assert_close("modified energy", modified(&p), h0, 1e-11 * h0);
    }
}

// ---------------------------------------------------------------------------
// Coefficients for a physical spring
// ---------------------------------------------------------------------------

#[test]
fn naive_coefficients_are_fractions_of_the_maxima() {
    let mut rng = Rng::seeded(11);
    for _ in 0..500 {
        let (k, c, m, dt) = (
            rng.log_range(1e-2, 1e4),
            rng.log_range(1e-3, 1e2),
            rng.log_range(1e-2, 1e2),
            rng.log_range(1e-4, 1e-1),
        );
        let (ck, cd) = naive_coefficients(k, c, m, dt);
        assert_close("ck", ck, k * dt * dt / m, 1e-14 * ck);
        assert_close("cd", cd, c * dt / m, 1e-14 * cd);
        assert_close("ck*k_max", ck * k_max(m, dt), k, 1e-14 * k);
        assert_close("cd*d_max", cd * d_max(m, dt), c, 1e-14 * c);
    }
}

#[test]
fn naive_coefficients_are_first_order_accurate() {
    // For ζ > 0 both relative errors against the exact coefficients are
    // ≈ ζ·ω·dt: halving dt halves them.
    let (m, omega, zeta) = (1.5, 2.0 * PI * 2.0, 0.4);
    let k = m * omega * omega;
    let c = 2.0 * zeta * omega * m;
    let rel_err = |dt: f64| {
        let (nk, nd) = naive_coefficients(k, c, m, dt);
        let (ek, ed) = exact_coefficients_from_poles(omega, zeta, dt);
        ((nk - ek).abs() / ek, (nd - ed).abs() / ed)
    };
    let mut dt = 0.01;
    let (mut ek_prev, mut ed_prev) = rel_err(dt);
    for _ in 0..4 {
        dt /= 2.0;
        let (ek, ed) = rel_err(dt);
        let (rk, rd) = (ek_prev / ek, ed_prev / ed);
        assert!((1.8..2.2).contains(&rk), "ck error ratio {rk}");
        assert!((1.8..2.2).contains(&rd), "cd error ratio {rd}");
        assert!(ek < 1.5 * zeta * omega * dt && ed < 1.5 * zeta * omega * dt);
        (ek_prev, ed_prev) = (ek, ed);
    }
}

#[test]
fn exact_coefficients_identities_and_ranges() {
    let mut rng = Rng::seeded(12);
    for _ in 0..2000 {
        let fdt = rng.log_range(1e-2, 0.45);
        let wdt = TAU * fdt;
        let zeta = if rng.unit() < 0.2 {
            ZETAS[rng.below(ZETAS.len())]
        } else {
            rng.log_range(1e-3, 30.0)
        };
        let dt = rng.log_range(1e-4, 1e-1);
        let omega = wdt / dt;
        let (ck, cd) = exact_coefficients_from_poles(omega, zeta, dt);

        // The discarded imaginary parts vanish.
        let (z1, z2) = discrete_poles(omega, zeta, dt);
        let ck_c = Complex::ONE.sub(z1).mul(Complex::ONE.sub(z2));
        let cd_c = Complex::ONE.sub(z1.mul(z2));
        assert!(ck_c.im.abs() <= 1e-15 && cd_c.im.abs() <= 1e-15);

        // z1·z2 = e^{(s1+s2)·dt} = e^{-2ζω·dt}.
        assert_close("cd", cd, -(-2.0 * zeta * wdt).exp_m1(), 1e-14);
        // z1 + z2 = 2 − C_k − C_d (Vieta) against an independent sum.
        let sum = if zeta < 1.0 {
            2.0 * (-zeta * wdt).exp() * (wdt * (1.0 - zeta * zeta).sqrt()).cos()
        } else {
            let q = (zeta * zeta - 1.0).sqrt();
            2.0 * (-zeta * wdt).exp() * (q * wdt).cosh()
        };
        assert_close("vieta", 2.0 - ck - cd, sum, 1e-13);

        // Ranges: C_d in [0, 1) (it rounds to 1 once e^{-2ζω·dt} < ε/2),
        // C_k in (0, 4].
        assert!((-1e-15..=1.0).contains(&cd), "cd {cd}");
        assert!(ck > 0.0 && ck <= 4.0 + 1e-14, "ck {ck}");
    }

    // ζ = 0: C_d = 0, C_k = |1 − e^{iω·dt}|² = 4·sin²(ω·dt/2), which exceeds 1
    // exactly when ω·dt > π/3, i.e. f·dt > 1/6.
    for i in 1..100 {
        let fdt = i as f64 * 0.005;
        let wdt = TAU * fdt;
        let (ck, cd) = exact_coefficients_from_poles(wdt, 0.0, 1.0);
        let s = (wdt / 2.0).sin();
        assert_close("undamped ck", ck, 4.0 * s * s, 1e-14);
        assert_close("undamped cd", cd, 0.0, 1e-15);
        if (fdt - 1.0 / 6.0).abs() > 1e-3 {
            assert_eq!(ck > 1.0, fdt > 1.0 / 6.0, "f·dt {fdt}");
        }
    }
    // ζ = 1: double pole e^{-ω·dt}, C_k = (1 − e^{-ω·dt})².
    for wdt in [0.05, 0.3, 1.0, 3.0] {
        let (ck, _) = exact_coefficients_from_poles(wdt, 1.0, 1.0);
        let e = -(-wdt).exp_m1();
        assert_close("critical ck", ck, e * e, 1e-14);
    }
    // A Nyquist-rate undamped spring needs the maximum C_k = 4.
    let (ck, _) = exact_coefficients_from_poles(PI, 0.0, 1.0);
    assert_close("ck at Nyquist", ck, 4.0, 1e-15);
}

#[test]
fn exact_coefficients_and_u0_reproduce_analytic_samples() {
    let mut rng = Rng::seeded(13);
    for &zeta in &ZETAS {
        for &fdt in &[0.01, 0.03, 0.1, 0.3] {
            for _ in 0..10 {
                let f = rng.log_range(0.5, 50.0);
                let omega = TAU * f;
                let dt = fdt / f;
                let (x0, v0) = (rng.sym(1.0), rng.sym(1.0) * omega);
                let a = x0.abs() + v0.abs() / omega;
                let (ck, cd) = exact_coefficients_from_poles(omega, zeta, dt);
                let mut x = x0;
                let mut u = u0_from_analytic(x0, v0, omega, zeta, dt);
                // Strongly overdamped with a fast pole z2 = e^{-λ2·dt} near ε:
                // u0 ~ e^{λ2·dt} is huge and 1 − C_d = z1·z2 is lost to
                // rounding, so the map is only good to about ε·|u0|.
                let tol = 1e-10 * a + 1e-14 * u.abs();
                for n in 1..=300 {
                    map_step(&mut x, &mut u, ck, cd);
                    let xa = analytic(x0, v0, omega, zeta, n as f64 * dt).0;
                    assert_close("sample x", x, xa, tol);
                    // u is the backward difference of the samples.
                    let xa_prev = analytic(x0, v0, omega, zeta, (n - 1) as f64 * dt).0;
                    assert_close("sample u", u, xa - xa_prev, tol);
                }
            }
        }
    }
}

#[test]
fn starting_with_v0_dt_instead_of_u0_is_off_the_trajectory() {
    // The DESIGN note: u0 must be x(0) − x(−dt), not v0·dt. With v0·dt the
    // discrete trajectory misses the samples by an O(ω·dt) fraction.
    let (omega, zeta, dt) = (TAU * 2.0, 0.2, 0.05); // f·dt = 0.1
    let (x0, v0) = (1.0, 0.0);
    let (ck, cd) = exact_coefficients_from_poles(omega, zeta, dt);
    let (mut x_good, mut u_good) = (x0, u0_from_analytic(x0, v0, omega, zeta, dt));
    let (mut x_bad, mut u_bad) = (x0, v0 * dt);
    let mut worst_good = 0.0_f64;
    let mut worst_bad = 0.0_f64;
    for n in 1..=100 {
        map_step(&mut x_good, &mut u_good, ck, cd);
        map_step(&mut x_bad, &mut u_bad, ck, cd);
        let xa = analytic(x0, v0, omega, zeta, n as f64 * dt).0;
        worst_good = worst_good.max((x_good - xa).abs());
        worst_bad = worst_bad.max((x_bad - xa).abs());
    }
    assert!(worst_good < 1e-12, "{worst_good:e}");
    assert!(worst_bad > 0.05, "{worst_bad:e}");
}

// ---------------------------------------------------------------------------
// Two bodies
// ---------------------------------------------------------------------------

fn random_pair(rng: &mut Rng, dt: f64) -> (Pair1, f64) {
    let rest = rng.range(0.5, 2.0);
    let xa = rng.sym(1.0);
    let xb = xa + rest + rng.sym(0.5);
    let p = Pair1::new(
        xa,
        rng.sym(1.0) / dt * 0.1,
        rng.log_range(1e-2, 1e2),
        xb,
        rng.sym(1.0) / dt * 0.1,
        rng.log_range(1e-2, 1e2),
    );
    (p, rest)
}

#[test]
fn pair_conserves_momentum_and_centre_of_mass_motion() {
    let mut rng = Rng::seeded(14);
    for case in 0..400 {
        let dt = rng.log_range(1e-4, 1e-1);
        let (ck, cd) = (rng.range(1e-4, 1.0), rng.range(0.0, 1.0));
        let (p0, rest) = random_pair(&mut rng, dt);
        let mut p = p0;
        let mt = p0.ma + p0.mb;
        let xcm0 = (p0.ma * p0.xa + p0.mb * p0.xb) / mt;
        let vcm = p0.momentum() / mt;
        let mut scale = p0.ma * p0.va.abs() + p0.mb * p0.vb.abs();
        for n in 1..=200 {
            if case % 2 == 0 {
                p.impulse_step(ck, cd, rest, dt);
            } else {
                p.force_step(ck, cd, rest, dt);
            }
            scale = scale.max(p.ma * p.va.abs() + p.mb * p.vb.abs());
            assert_close("momentum", p.momentum(), p0.momentum(), 1e-13 * scale);
            let xcm = (p.ma * p.xa + p.mb * p.xb) / mt;
            let sx = p.xa.abs() + p.xb.abs() + scale / mt * dt * n as f64;
            assert_close(
                "centre of mass",
                xcm,
                xcm0 + vcm * dt * n as f64,
                1e-12 * sx,
            );
        }
    }
}

#[test]
fn pair_relative_motion_is_one_body_with_reduced_mass() {
    let mut rng = Rng::seeded(15);
    for case in 0..400 {
        let dt = rng.log_range(1e-4, 1e-1);
        let (ck, cd) = (rng.range(1e-4, 1.0), rng.range(0.0, 1.0));
        let (mut p, rest) = random_pair(&mut rng, dt);
        let m_red = reduced_mass(p.ma, p.mb);
        let mut q = Particle1::new(p.extension(rest), p.relative_velocity(), m_red);
        let sx = p.xa.abs() + p.xb.abs() + rest + q.v.abs() * dt;
        for _ in 0..200 {
            if case % 2 == 0 {
                p.impulse_step(ck, cd, rest, dt);
                q.impulse_step(ck, cd, dt);
            } else {
                p.force_step(ck, cd, rest, dt);
                q.force_step(ck, cd, dt);
            }
            assert_close("extension", p.extension(rest), q.x, 1e-11 * sx);
            assert_close("rel v", p.relative_velocity(), q.v, 1e-11 * sx / dt);
        }
    }
}

#[test]
fn pair_full_coefficients_reach_rest_length_in_one_step() {
    let mut rng = Rng::seeded(16);
    for _ in 0..400 {
        let dt = rng.log_range(1e-4, 1e-1);
        let (mut p, rest) = random_pair(&mut rng, dt);
        let p0 = p;
        let sx = p.xa.abs() + p.xb.abs() + rest + p.relative_velocity().abs() * dt;
        p.impulse_step(1.0, 1.0, rest, dt);
        assert_close("extension after 1", p.extension(rest), 0.0, 1e-13 * sx);
        p.impulse_step(1.0, 1.0, rest, dt);
        assert_close("extension after 2", p.extension(rest), 0.0, 1e-13 * sx);
        assert_close("rel v after 2", p.relative_velocity(), 0.0, 1e-13 * sx / dt);
        // Both bodies now move with the centre-of-mass velocity.
        let vcm = p0.momentum() / (p0.ma + p0.mb);
        assert_close("va", p.va, vcm, 1e-12 * sx / dt);
        assert_close("vb", p.vb, vcm, 1e-12 * sx / dt);
    }
}

#[test]
fn pinned_body_never_moves_and_the_free_one_is_a_particle() {
    let mut rng = Rng::seeded(17);
    for case in 0..400 {
        let dt = rng.log_range(1e-4, 1e-1);
        let (ck, cd) = (rng.range(1e-2, 1.0), rng.range(0.0, 1.0));
        let (mut p, rest) = random_pair(&mut rng, dt);
        let pin_b = case % 2 == 0;
        if pin_b {
            p.mb = f64::INFINITY;
            p.vb = 0.0;
        } else {
            p.ma = f64::INFINITY;
            p.va = 0.0;
        }
        let p0 = p;
        // Displacement of the free body from its rest position.
        let (x, v, m) = if pin_b {
            (p.xa - (p.xb - rest), p.va, p.ma)
        } else {
            (p.xb - (p.xa + rest), p.vb, p.mb)
        };
        let mut q = Particle1::new(x, v, m);
        let sx = p.xa.abs() + p.xb.abs() + rest + v.abs() * dt;
        let mut max_dp = 0.0_f64;
        for _ in 0..100 {
            if case % 4 < 2 {
                p.impulse_step(ck, cd, rest, dt);
                q.impulse_step(ck, cd, dt);
            } else {
                p.force_step(ck, cd, rest, dt);
                q.force_step(ck, cd, dt);
            }
            let (free_x, free_v) = if pin_b {
                assert_eq!((p.xb, p.vb), (p0.xb, p0.vb));
                (p.xa - (p.xb - rest), p.va)
            } else {
                assert_eq!((p.xa, p.va), (p0.xa, p0.va));
                (p.xb - (p.xa + rest), p.vb)
            };
            assert_close("free x", free_x, q.x, 1e-11 * sx);
            assert_close("free v", free_v, q.v, 1e-11 * sx / dt);
            max_dp = max_dp.max((p.momentum() - p0.momentum()).abs());
        }
        // The anchor exerts an external impulse: momentum is not conserved.
        let (x_abs, v_abs) = (x.abs(), v.abs());
        if x_abs > 1e-3 || v_abs * dt > 1e-3 {
            assert!(max_dp > 1e-6 * m * (x_abs / dt + v_abs), "dp {max_dp:e}");
        }
    }

    // Both pinned: nothing moves and nothing becomes NaN.
    let mut p = Pair1::new(0.0, 0.0, f64::INFINITY, 2.0, 0.0, f64::INFINITY);
    let p0 = p;
    p.impulse_step(0.5, 0.5, 1.0, 0.01);
    p.force_step(0.5, 0.5, 1.0, 0.01);
    assert_eq!(p, p0);
}

// ---------------------------------------------------------------------------
// Angular springs
// ---------------------------------------------------------------------------

#[test]
fn angular_pair_mirrors_the_linear_pair() {
    let mut rng = Rng::seeded(18);
    for case in 0..200 {
        let dt = rng.log_range(1e-4, 1e-1);
        let (ck, cd) = (rng.range(1e-4, 1.0), rng.range(0.0, 1.0));
        let (mut p, rest) = random_pair(&mut rng, dt);
        if case % 5 == 0 {
            p.mb = f64::INFINITY;
            p.vb = 0.0;
        }
        let mut r = AngularPair::new(p.xa, p.va, p.ma, p.xb, p.vb, p.mb);
        for _ in 0..100 {
            if case % 2 == 0 {
                p.impulse_step(ck, cd, rest, dt);
                r.impulse_step(ck, cd, rest, dt);
            } else {
                p.force_step(ck, cd, rest, dt);
                r.torque_step(ck, cd, rest, dt);
            }
            // Same equations with renamed variables: bit-identical.
            assert_eq!((r.tha, r.wa, r.thb, r.wb), (p.xa, p.va, p.xb, p.vb));
            assert_eq!(r.angular_momentum(), p.momentum());
            assert_eq!(r.energy(3.0, rest), p.energy(3.0, rest));
        }
    }
}

#[test]
fn angular_spring_winds_up_over_many_turns() {
    // Rest angle of five full turns: no wrapping, the rotors wind up to it.
    let rest = 5.0 * TAU;
    let dt = 1e-3;
    let mut r = AngularPair::new(0.0, 0.0, 0.02, 0.0, 0.0, 0.05);
    let l0 = r.angular_momentum();
    r.impulse_step(1.0, 1.0, rest, dt);
    assert_close("wound up", r.thb - r.tha, rest, 1e-13 * rest);
    r.impulse_step(1.0, 1.0, rest, dt);
    assert_close("rel w", r.relative_velocity(), 0.0, 1e-12 * rest / dt);
    assert_close("L", r.angular_momentum(), l0, 1e-12);

    // Softer spring: settles at the wound-up angle, not at rest mod 2π.
    let mut r = AngularPair::new(0.0, 0.0, 0.02, 0.0, 0.0, f64::INFINITY);
    for _ in 0..5000 {
        r.impulse_step(0.05, 0.3, rest, dt);
    }
    assert_close("settled", r.thb - r.tha, rest, 1e-9 * rest);
    assert_eq!((r.thb, r.wb), (0.0, 0.0));
}

// ---------------------------------------------------------------------------
// The discrete map and its stability
// ---------------------------------------------------------------------------

#[test]
fn map_matrix_is_the_matrix_of_map_step() {
    let mut rng = Rng::seeded(19);
    for _ in 0..1000 {
        let (ck, cd) = (rng.range(-1.0, 5.0), rng.range(-1.0, 3.0));
        let m = map_matrix(ck, cd);
        let (mut x, mut u) = (1.0, 0.0);
        map_step(&mut x, &mut u, ck, cd);
        assert_close("M00", m[0][0], x, 1e-15);
        assert_close("M10", m[1][0], u, 1e-15);
        let (mut x, mut u) = (0.0, 1.0);
        map_step(&mut x, &mut u, ck, cd);
        assert_close("M01", m[0][1], x, 1e-15);
        assert_close("M11", m[1][1], u, 1e-15);
        // trace = 2 − C_k − C_d, det = 1 − C_d.
        assert_close("trace", m[0][0] + m[1][1], 2.0 - ck - cd, 1e-14);
        let det = m[0][0] * m[1][1] - m[0][1] * m[1][0];
        assert_close("det", det, 1.0 - cd, 1e-13);
    }
}

#[test]
fn spectral_radius_follows_the_jury_region() {
    // Stable exactly when C_k > 0, 0 < C_d < 2, C_k + 2·C_d < 4; sample points
    // at least 1e-4 from the boundary.
    let mut rng = Rng::seeded(20);
    let (mut inside, mut outside) = (0, 0);
    for _ in 0..20_000 {
        let (ck, cd) = (rng.range(-1.0, 5.0), rng.range(-1.0, 3.0));
        let margin = ck.min(cd).min(2.0 - cd).min(4.0 - ck - 2.0 * cd);
        let rho = spectral_radius(ck, cd);
        if margin > 1e-4 {
            assert!(rho < 1.0, "({ck}, {cd}) inside but rho {rho}");
            inside += 1;
        } else if margin < -1e-4 {
            assert!(rho > 1.0, "({ck}, {cd}) outside but rho {rho}");
            outside += 1;
        }
    }
    assert!(inside > 1000 && outside > 1000);
    // The region is the open triangle (0, 0), (4, 0), (0, 2); its corners and
    // edges are marginal (rho = 1).
    for (ck, cd) in [
        (0.0, 0.0),
        (4.0, 0.0),
        (0.0, 2.0),
        (0.0, 0.5),
        (2.0, 0.0),
        (2.0, 1.0),
        (0.5, 1.75),
    ] {
        assert_close("boundary", spectral_radius(ck, cd), 1.0, 1e-7);
    }
}

#[test]
fn spectral_radius_predicts_growth_of_map_step() {
    let mut rng = Rng::seeded(21);
    let mut checked = 0;
    while checked < 300 {
        let (ck, cd) = (rng.range(-0.5, 4.5), rng.range(-0.5, 2.5));
        let rho = spectral_radius(ck, cd);
        if !(0.7..1.5).contains(&rho) || (rho - 1.0).abs() < 0.02 {
            continue;
        }
        let (mut x, mut u) = (1.0, 0.37);
        let norm = |x: f64, u: f64| x.hypot(u);
        for _ in 0..200 {
            map_step(&mut x, &mut u, ck, cd);
        }
        let n0 = norm(x, u);
        for _ in 0..400 {
            map_step(&mut x, &mut u, ck, cd);
        }
        let rate = (norm(x, u) / n0).powf(1.0 / 400.0);
        assert_close("growth rate", rate, rho, 2e-2);
        assert_eq!(rate > 1.0, rho > 1.0);
        checked += 1;
    }
}

#[test]
fn full_coefficients_are_deadbeat() {
    assert_eq!(spectral_radius(1.0, 1.0), 0.0);
    // M² = 0: every column of M² is M times a column of M.
    let m = map_matrix(1.0, 1.0);
    for (top, bottom) in m[0].iter().zip(&m[1]) {
        for row in m {
            assert_eq!(row[0] * top + row[1] * bottom, 0.0);
        }
    }
    // Any state is at (0, 0) after two steps of the map (up to rounding).
    let mut rng = Rng::seeded(24);
    for _ in 0..100 {
        let (mut x, mut u) = (rng.sym(10.0), rng.sym(10.0));
        let scale = x.abs() + u.abs();
        map_step(&mut x, &mut u, 1.0, 1.0);
        map_step(&mut x, &mut u, 1.0, 1.0);
        assert_close("x after 2", x, 0.0, 4.0 * f64::EPSILON * scale);
        assert_close("u after 2", u, 0.0, 4.0 * f64::EPSILON * scale);
    }
}

#[test]
fn spectral_radius_of_exact_coefficients_is_the_pole_modulus() {
    let mut rng = Rng::seeded(22);
    for &zeta in &ZETAS {
        for _ in 0..50 {
            let wdt = TAU * rng.log_range(1e-2, 0.3);
            let (ck, cd) = exact_coefficients_from_poles(wdt, zeta, 1.0);
            let (z1, z2) = discrete_poles(wdt, zeta, 1.0);
            let want = z1.abs().max(z2.abs());
            // A double root (ζ ≈ 1) is only determined to √ε.
            let tol = if (zeta - 1.0).abs() < 1e-2 {
                1e-7
            } else {
                1e-12
            };
            assert_close("rho", spectral_radius(ck, cd), want, tol);
            if zeta <= 1.0 {
                assert_close("|z|", want, (-zeta * wdt).exp(), 1e-14);
            }
        }
    }
}
