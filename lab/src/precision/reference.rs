//! The reference: the exact map's coefficients and the analytic damped oscillator, in step units.

use super::*;

/// `C_k`, `C_d` of the exact sampled map, in f64.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Coefs {
    /// `C_k = (1 − z₁)(1 − z₂)`.
    pub ck: f64,
    /// `C_d = 1 − z₁z₂`.
    pub cd: f64,
}

impl Coefs {
    /// The exact map for `f·dt` and `ζ` (cancellation-free forms).
    pub fn exact(fdt: f64, zeta: f64) -> Coefs {
        let theta = 2.0 * PI * fdt;
        let a = zeta * theta;
        let cd = -(-2.0 * a).exp_m1();
        let ck = if zeta < 1.0 {
            let wd = theta * (1.0 - zeta * zeta).sqrt();
            let s = (wd / 2.0).sin();
            let e = (-a).exp_m1();
            e * e + 4.0 * (-a).exp() * s * s
        } else if zeta == 1.0 {
            let e = (-theta).exp_m1();
            e * e
        } else {
            let q = (zeta * zeta - 1.0).sqrt();
            let r1 = 1.0 / (zeta + q);
            let r2 = zeta + q;
            (-theta * r1).exp_m1() * (-theta * r2).exp_m1()
        };
        Coefs { ck, cd }
    }
}

/// The continuous damped oscillator in step units (`ω = θ` rad per step).
#[derive(Clone, Copy, Debug)]
pub struct Analytic {
    x0: f64,
    v0: f64,
    theta: f64,
    zeta: f64,
}

impl Analytic {
    /// Start at `x0` with velocity `v0` (per step).
    pub fn new(fdt: f64, zeta: f64, x0: f64, v0: f64) -> Analytic {
        Analytic {
            x0,
            v0,
            theta: 2.0 * PI * fdt,
            zeta,
        }
    }

    /// A release from `a` at rest.
    pub fn release(fdt: f64, zeta: f64, a: f64) -> Analytic {
        Analytic::new(fdt, zeta, a, 0.0)
    }

    /// A fling from 0 whose peak is `a`.
    pub fn fling(fdt: f64, zeta: f64, a: f64) -> Analytic {
        let unit = Analytic::new(fdt, zeta, 0.0, 1.0);
        let w = unit.theta;
        let z = zeta;
        let t_peak = if z < 1.0 {
            let wd = w * (1.0 - z * z).sqrt();
            (wd).atan2(z * w) / wd
        } else if z == 1.0 {
            1.0 / w
        } else {
            let q = (z * z - 1.0).sqrt();
            let (s1, s2) = (-w / (z + q), -w * (z + q));
            (s2 / s1).ln() / (s1 - s2)
        };
        let peak = unit.at(t_peak);
        Analytic::new(fdt, zeta, 0.0, a / peak)
    }

    /// `x(t)`, `t` in steps.
    pub fn at(&self, t: f64) -> f64 {
        self.eval(t)
    }

    /// `x(n)` at an integer step, with the phase `n·ω_d` formed to twice f64 precision, so
    /// that the reference over 10⁶ steps is limited by `θ`, not by the product.
    pub fn sample(&self, n: i64) -> f64 {
        self.eval(n as f64)
    }

    fn eval(&self, t: f64) -> f64 {
        let (w, z, x0, v0) = (self.theta, self.zeta, self.x0, self.v0);
        if z < 1.0 {
            let wd = w * (1.0 - z * z).sqrt();
            // phase = t·wd exactly as p + e (TwoProduct)
            let p = t * wd;
            let e = t.mul_add(wd, -p);
            let (s, c) = p.sin_cos();
            let (sin, cos) = (s + e * c, c - e * s);
            (-z * w * t).exp() * (x0 * cos + (v0 + z * w * x0) / wd * sin)
        } else if z == 1.0 {
            (-w * t).exp() * (x0 + (v0 + w * x0) * t)
        } else {
            let q = (z * z - 1.0).sqrt();
            let (s1, s2) = (-w / (z + q), -w * (z + q));
            let c1 = (v0 - s2 * x0) / (s1 - s2);
            let c2 = x0 - c1;
            c1 * (s1 * t).exp() + c2 * (s2 * t).exp()
        }
    }

    /// `x(0)`.
    pub fn x0(&self) -> f64 {
        self.x0
    }

    /// The start of the discrete spring on this trajectory: `u₀ = x(0) − x(−1)`.
    pub fn u0(&self) -> f64 {
        self.x0 - self.at(-1.0)
    }

    /// `v(0)`, per step.
    pub fn v0(&self) -> f64 {
        self.v0
    }

    /// The start of the `kept` form: `ũ₀ = (1 − C_d)·u₀ = P̃·x(0) + Q̃·v(0)`, without
    /// forming `u₀` ([`kept_pq`]).
    pub fn kept0(&self) -> f64 {
        let (p, q) = kept_pq(self.theta / (2.0 * PI), self.zeta);
        p * self.x0 + q * self.v0
    }
}

/// `(P̃, Q̃)` of the `kept` start `ũ₀ = P̃·x₀ + Q̃·v₀` (`v₀` per step), in the
/// cancellation-free forms of the lead's implementation. `ũ₀ = x(1) − x(0) + C_k·x(0)`:
/// it carries no fast mode, so it stays of the order of the amplitude where `u₀` does not.
pub fn kept_pq(fdt: f64, zeta: f64) -> (f64, f64) {
    let w = 2.0 * PI * fdt;
    let a = zeta * w;
    if zeta < 1.0 {
        let wd = w * (1.0 - zeta * zeta).sqrt();
        let b = wd;
        let q = (-a).exp() * b.sin() / wd;
        let h = (b / 2.0).sin();
        let p = (-2.0 * a).exp_m1() - (-a).exp_m1() + 2.0 * (-a).exp() * h * h + q * zeta * w;
        (p, q)
    } else if zeta == 1.0 {
        let q = (-a).exp();
        let p = (-2.0 * a).exp_m1() - (-a).exp_m1() + q * w;
        (p, q)
    } else {
        let gamma = w * (zeta * zeta - 1.0).sqrt();
        let g = gamma;
        let q = 0.5 * ((g - a).exp_m1() - (-g - a).exp_m1()) / gamma;
        let p = (-2.0 * a).exp_m1() - 0.5 * ((g - a).exp_m1() + (-g - a).exp_m1()) + q * zeta * w;
        (p, q)
    }
}

/// A start in every representation the candidates take: `(x₀, u₀)` for the step-velocity
/// forms and `(x₀, ũ₀)` for `kept` (units).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Start {
    /// `x(0)`.
    pub x0: f64,
    /// `u₀ = x(0) − x(−dt)`.
    pub u0: f64,
    /// `ũ₀ = (1 − C_d)·u₀`.
    pub kept: f64,
}

impl Start {
    /// On an analytic trajectory: `ũ₀` from `(x(0), v(0))` ([`kept_pq`]).
    pub fn analytic(an: &Analytic) -> Start {
        Start {
            x0: an.x0(),
            u0: an.u0(),
            kept: an.kept0(),
        }
    }

    /// A discrete state `(x₀, u₀)` with no trajectory behind it: `ũ₀ = (1 − C_d)·u₀` in f64.
    pub fn discrete(c: Coefs, x0: f64, u0: f64) -> Start {
        Start {
            x0,
            u0,
            kept: (1.0 - c.cd) * u0,
        }
    }
}
