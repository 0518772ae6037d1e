//! Independent f64 reference model of the springs in the seed article
//! ("Towards a simpler, stiffer, and more stable spring").
//!
//! It is written straight from the article's equations (the equation number is
//! given in a comment on every line that implements one) and from textbook
//! mathematics, and deliberately shares no code with the library. Its self-tests
//! are `lab/tests/reference_selftest.rs` and
//! `lab/tests/reference_network_selftest.rs`.
//!
//! Conventions:
//! - `x` is a displacement (extension) from rest, `v` a velocity, `m` a mass,
//!   `dt` the time step, `C_k`/`C_d` (`ck`/`cd`) the article's dimensionless
//!   stiffness and damping coefficients.
//! - A pinned body has mass `f64::INFINITY`; it receives no velocity change.
//! - Eq. 27 and 28 are used in their corrected form: the printed damping term
//!   `-C_d·v` lacks the mass; the impulse is `-(m/dt)·C_k·x - m·C_d·v`.

// Particle and angular-spring networks (distance springs in 1-3 D, angular
// springs; Gauss-Seidel and Jacobi steppers; invariants; scene builders). Its own
// module docs are the documentation: an outer doc here would make rustdoc resolve
// their links in this module instead of that one.
pub mod network;

// UI motion beyond a spring to a target: friction, rubber band, a throw into a bound,
// snapping, a trail (its module docs say what each is written from).
pub mod ui;

// ---------------------------------------------------------------------------
// Coefficient limits and reduced mass
// ---------------------------------------------------------------------------

/// Stiffness that returns a body of mass `m` to rest in one step: `m/dt²`.
pub fn k_max(m: f64, dt: f64) -> f64 {
    m / (dt * dt) // eq. 6 / eq. 14 (eq. 19 / 24 with a reduced mass)
}

/// Damping that stops a body of mass `m` in one step: `m/dt`.
pub fn d_max(m: f64, dt: f64) -> f64 {
    m / dt // eq. 11 / eq. 15 (eq. 20 / 25 with a reduced mass)
}

/// Reduced mass (or reduced moment of inertia) of two bodies.
///
/// Written in the inverse-mass form so that a pinned body
/// (`f64::INFINITY`) contributes nothing: `reduced_mass(m, INF) == m`, and
/// `reduced_mass(INF, INF) == INF`.
pub fn reduced_mass(m1: f64, m2: f64) -> f64 {
    1.0 / (1.0 / m1 + 1.0 / m2) // eq. 18 (== eq. 17 for finite masses; eq. 22/23 for inertia)
}

/// Reduced mass in the product form of eq. 17 (finite masses only); used by
/// the self-test to check eq. 17 == eq. 18.
pub fn reduced_mass_product_form(m1: f64, m2: f64) -> f64 {
    m1 * m2 / (m1 + m2) // eq. 17
}

/// Velocity change of a body of mass `m` that receives impulse `j`
/// (`j/m`). A pinned body (infinite mass) never moves, even if `j` is
/// infinite or NaN (which happens only when both bodies are pinned).
fn dv(j: f64, m: f64) -> f64 {
    if m.is_infinite() { 0.0 } else { j / m }
}

// ---------------------------------------------------------------------------
// One body on a fixed anchor (1D)
// ---------------------------------------------------------------------------

/// One body of mass `m` on a spring to a fixed anchor; `x` is the
/// displacement from the rest position, `v` the velocity.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Particle1 {
    pub x: f64,
    pub v: f64,
    pub m: f64,
}

impl Particle1 {
    pub fn new(x: f64, v: f64, m: f64) -> Self {
        Self { x, v, m }
    }

    /// Force form (eq. 13/16) integrated with symplectic Euler
    /// (velocity first, then position with the new velocity).
    pub fn force_step(&mut self, ck: f64, cd: f64, dt: f64) {
        let f = -k_max(self.m, dt) * ck * self.x - d_max(self.m, dt) * cd * self.v; // eq. 13 / 16
        self.v += f / self.m * dt; // eq. 3 / 8 (a = f/m, v += a·dt)
        self.x += self.v * dt; // eq. 1 (x += v·dt)
    }

    /// Impulse form, corrected eq. 27 with `m_red = m`:
    /// `j = -(m/dt)·C_k·x - m·C_d·v`, then `v += j/m`, `x += v·dt`.
    pub fn impulse_step(&mut self, ck: f64, cd: f64, dt: f64) {
        let j = -(self.m / dt) * ck * self.x - self.m * cd * self.v; // eq. 27 (corrected)
        self.v += j / self.m;
        self.x += self.v * dt; // eq. 1
    }

    /// Mechanical energy `½·m·v² + ½·k·x²` for a physical stiffness `k`.
    pub fn energy(&self, k: f64) -> f64 {
        0.5 * self.m * self.v * self.v + 0.5 * k * self.x * self.x
    }
}

// ---------------------------------------------------------------------------
// Two bodies joined by one spring (1D)
// ---------------------------------------------------------------------------

/// Two bodies on a line joined by one spring. Masses may be
/// `f64::INFINITY` for pinned bodies.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Pair1 {
    pub xa: f64,
    pub va: f64,
    pub ma: f64,
    pub xb: f64,
    pub vb: f64,
    pub mb: f64,
}

impl Pair1 {
    pub fn new(xa: f64, va: f64, ma: f64, xb: f64, vb: f64, mb: f64) -> Self {
        Self {
            xa,
            va,
            ma,
            xb,
            vb,
            mb,
        }
    }

    /// Spring extension `(xb - xa) - rest`.
    pub fn extension(&self, rest: f64) -> f64 {
        (self.xb - self.xa) - rest
    }

    /// Relative velocity `vb - va`.
    pub fn relative_velocity(&self) -> f64 {
        self.vb - self.va
    }

    /// Impulse form with reduced mass (corrected eq. 27 with eq. 18-20):
    /// `j = -(m_red/dt)·C_k·x - m_red·C_d·v`, `+j` on b, `-j` on a, then
    /// positions advance with the new velocities.
    pub fn impulse_step(&mut self, ck: f64, cd: f64, rest: f64, dt: f64) {
        let m_red = reduced_mass(self.ma, self.mb); // eq. 18
        let x = self.extension(rest);
        let v = self.relative_velocity();
        let j = -(m_red / dt) * ck * x - m_red * cd * v; // eq. 27 (corrected)
        self.va -= dv(j, self.ma);
        self.vb += dv(j, self.mb);
        self.xa += self.va * dt; // eq. 1
        self.xb += self.vb * dt; // eq. 1
    }

    /// Force form with reduced mass (eq. 19-21 with the coefficients of
    /// eq. 13/16), `+f` on b and `-f` on a, symplectic Euler.
    pub fn force_step(&mut self, ck: f64, cd: f64, rest: f64, dt: f64) {
        let m_red = reduced_mass(self.ma, self.mb); // eq. 18
        let x = self.extension(rest);
        let v = self.relative_velocity();
        // eq. 21 with the coefficients of eq. 16 (k_max, d_max from eq. 19, 20):
        let f = -k_max(m_red, dt) * ck * x - d_max(m_red, dt) * cd * v; // eq. 21 / 16
        self.va -= dv(f, self.ma) * dt; // eq. 3 / 8
        self.vb += dv(f, self.mb) * dt; // eq. 3 / 8
        self.xa += self.va * dt; // eq. 1
        self.xb += self.vb * dt; // eq. 1
    }

    /// Total linear momentum of the bodies with finite mass (a pinned body
    /// is an external agent and is left out).
    pub fn momentum(&self) -> f64 {
        let mut p = 0.0;
        if self.ma.is_finite() {
            p += self.ma * self.va;
        }
        if self.mb.is_finite() {
            p += self.mb * self.vb;
        }
        p
    }

    /// Kinetic energy of the finite bodies plus `½·k·x²` of the spring.
    pub fn energy(&self, k: f64, rest: f64) -> f64 {
        let mut e = 0.0;
        if self.ma.is_finite() {
            e += 0.5 * self.ma * self.va * self.va;
        }
        if self.mb.is_finite() {
            e += 0.5 * self.mb * self.vb * self.vb;
        }
        let x = self.extension(rest);
        e + 0.5 * k * x * x
    }
}

// ---------------------------------------------------------------------------
// Two rotors joined by one angular spring
// ---------------------------------------------------------------------------

/// Two rotors joined by one angular (torsional) spring; angles are not
/// wrapped, so a spring can be wound up over many turns. Moments of inertia
/// may be `f64::INFINITY` for a pinned rotor.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AngularPair {
    pub tha: f64,
    pub wa: f64,
    pub ia: f64,
    pub thb: f64,
    pub wb: f64,
    pub ib: f64,
}

impl AngularPair {
    pub fn new(tha: f64, wa: f64, ia: f64, thb: f64, wb: f64, ib: f64) -> Self {
        Self {
            tha,
            wa,
            ia,
            thb,
            wb,
            ib,
        }
    }

    /// Angular displacement `(thb - tha) - rest_angle` (no wrapping).
    pub fn displacement(&self, rest_angle: f64) -> f64 {
        (self.thb - self.tha) - rest_angle
    }

    /// Relative angular velocity `wb - wa`.
    pub fn relative_velocity(&self) -> f64 {
        self.wb - self.wa
    }

    /// Angular impulse form, corrected eq. 28:
    /// `j = -(I_red/dt)·C_k·θ - I_red·C_d·ω`, `+j` on b, `-j` on a.
    pub fn impulse_step(&mut self, ck: f64, cd: f64, rest_angle: f64, dt: f64) {
        let i_red = reduced_mass(self.ia, self.ib); // eq. 23
        let th = self.displacement(rest_angle);
        let w = self.relative_velocity();
        let j = -(i_red / dt) * ck * th - i_red * cd * w; // eq. 28 (corrected)
        self.wa -= dv(j, self.ia);
        self.wb += dv(j, self.ib);
        self.tha += self.wa * dt; // angular eq. 1
        self.thb += self.wb * dt; // angular eq. 1
    }

    /// Torque form (eq. 26), symplectic Euler.
    pub fn torque_step(&mut self, ck: f64, cd: f64, rest_angle: f64, dt: f64) {
        let i_red = reduced_mass(self.ia, self.ib); // eq. 23
        let th = self.displacement(rest_angle);
        let w = self.relative_velocity();
        let tau = -k_max(i_red, dt) * ck * th - d_max(i_red, dt) * cd * w; // eq. 26, 24, 25
        self.wa -= dv(tau, self.ia) * dt; // angular eq. 8
        self.wb += dv(tau, self.ib) * dt; // angular eq. 8
        self.tha += self.wa * dt; // angular eq. 1
        self.thb += self.wb * dt; // angular eq. 1
    }

    /// Total angular momentum of the rotors with finite inertia.
    pub fn angular_momentum(&self) -> f64 {
        let mut l = 0.0;
        if self.ia.is_finite() {
            l += self.ia * self.wa;
        }
        if self.ib.is_finite() {
            l += self.ib * self.wb;
        }
        l
    }

    /// Rotational kinetic energy of the finite rotors plus `½·k·θ²`.
    pub fn energy(&self, k: f64, rest_angle: f64) -> f64 {
        let mut e = 0.0;
        if self.ia.is_finite() {
            e += 0.5 * self.ia * self.wa * self.wa;
        }
        if self.ib.is_finite() {
            e += 0.5 * self.ib * self.wb * self.wb;
        }
        let th = self.displacement(rest_angle);
        e + 0.5 * k * th * th
    }
}

// ---------------------------------------------------------------------------
// Continuous damped oscillator: analytic solution
// ---------------------------------------------------------------------------

/// `sin(w·t)/w`, equal to `t` in the limit `w → 0`.
///
/// For `|w·t| < 1e-8` the two-term series `t·(1 - (w·t)²/6)` is used
/// (truncation error below 1e-33 relative); otherwise the quotient, which
/// is accurate to a few ulp because `sin` is relatively accurate.
fn sin_over(w: f64, t: f64) -> f64 {
    let y = w * t;
    if y.abs() < 1e-8 {
        t * (1.0 - y * y / 6.0)
    } else {
        y.sin() / w
    }
}

/// `(1 - e^{-d·t})/d`, equal to `t` in the limit `d → 0`.
///
/// Uses `expm1` (no cancellation) and the series `t·(1 - y/2 + y²/6)`,
/// `y = d·t`, for `|y| < 1e-8`.
fn decay_over(d: f64, t: f64) -> f64 {
    let y = d * t;
    if y.abs() < 1e-8 {
        t * (1.0 - y / 2.0 + y * y / 6.0)
    } else {
        -(-y).exp_m1() / d
    }
}

/// Exact solution `(x(t), x'(t))` of `x'' + 2ζω·x' + ω²·x = 0` with
/// `x(0) = x0`, `x'(0) = v0`. Valid for any real `t` (also negative),
/// `omega >= 0`, `zeta >= 0`.
///
/// Regimes (textbook closed forms):
/// - `ζ < 1` (includes `ζ = 0`), with `σ = ζω`, `ω_d = ω·√((1-ζ)(1+ζ))`:
///   `x = e^{-σt}·(x0·cos ω_d t + (v0 + σ·x0)·S)`,
///   `v = e^{-σt}·(v0·cos ω_d t − (σ·v0 + ω²·x0)·S)`, `S = sin(ω_d t)/ω_d`.
/// - `ζ = 1`: `x = e^{-ωt}·(x0 + (v0 + ω·x0)·t)`,
///   `v = e^{-ωt}·(v0 − ω·(v0 + ω·x0)·t)`.
/// - `ζ > 1`: with the two real decay rates `λ1 = ω/(ζ+q)` (slow; not
///   `ω·(ζ−q)`, which cancels for large ζ) and `λ2 = ω·(ζ+q)` (fast),
///   `q = √((ζ-1)(ζ+1))`, `Δ = λ2 − λ1 = 2ωq`:
///   - `q ≥ 0.5` (ζ ≳ 1.12): the two modes,
///     `x = c1·e^{-λ1 t} + c2·e^{-λ2 t}`, `v = −λ1·c1·e^{-λ1 t} − λ2·c2·e^{-λ2 t}`,
///     `c1 = (λ2·x0 + v0)/Δ`, `c2 = −(λ1·x0 + v0)/Δ`. The weights are
///     bounded (`λ2/Δ ≤ 1.7`), nothing overflows for large ζ, and the slow
///     mode keeps full relative accuracy even for ζ = 1e8.
///   - `q < 0.5` (or `ω` so small that `1/Δ` overflows): the same solution
///     with the slow exponential factored out, `G = (1 − e^{-Δt})/Δ`,
///     `x = e^{-λ1 t}·(x0 + (λ1·x0 + v0)·G)`,
///     `v = e^{-λ1 t}·(v0 − λ2·(λ1·x0 + v0)·G)`, which has no `1/Δ`
///     cancellation as `ζ → 1⁺`. (For large ζ this form would lose the
///     relative accuracy of `v` in the slow mode, hence the switch.)
///
/// Near-critical damping: no tolerance band is needed. The only quotients
/// whose divisor vanishes at `ζ = 1` are `S = sin(ω_d t)/ω_d` and `G`, and
/// both are evaluated by `sin_over`/`decay_over` (quotient of two accurate
/// small numbers, or a series when the argument is below 1e-8). Both forms
/// tend to the critical form as `ζ → 1` (`S → t`, `G → t`, `λ1, λ2 → ω`),
/// so the solution is continuous across `ζ = 1` to rounding; the self-test
/// checks `ζ = 1 ± 1e-7` and `1 ± 1e-12` against `ζ = 1`. `ζ == 1` exactly
/// takes the critical branch.
pub fn analytic(x0: f64, v0: f64, omega: f64, zeta: f64, t: f64) -> (f64, f64) {
    assert!(
        omega >= 0.0 && zeta >= 0.0,
        "analytic: omega, zeta must be >= 0"
    );
    if zeta < 1.0 {
        let sigma = zeta * omega;
        let wd = omega * ((1.0 - zeta) * (1.0 + zeta)).sqrt();
        let e = (-sigma * t).exp();
        let c = (wd * t).cos();
        let s = sin_over(wd, t);
        let x = e * (x0 * c + (v0 + sigma * x0) * s);
        let v = e * (v0 * c - (sigma * v0 + omega * omega * x0) * s);
        (x, v)
    } else if zeta == 1.0 {
        let e = (-omega * t).exp();
        let b = v0 + omega * x0;
        (e * (x0 + b * t), e * (v0 - omega * b * t))
    } else {
        let q = ((zeta - 1.0) * (zeta + 1.0)).sqrt();
        let l1 = omega / (zeta + q); // slow decay rate, no cancellation
        let l2 = omega * (zeta + q); // fast decay rate
        let delta = 2.0 * omega * q; // l2 - l1
        if q >= 0.5 {
            // Clearly overdamped: the two modes, with bounded weights.
            let c1 = (l2 * x0 + v0) / delta;
            let c2 = -(l1 * x0 + v0) / delta;
            // Finite unless omega is (nearly) 0: then fall through to the
            // factored form, which tends to free motion.
            if c1.is_finite() && c2.is_finite() {
                let (e1, e2) = ((-l1 * t).exp(), (-l2 * t).exp());
                return (c1 * e1 + c2 * e2, -l1 * c1 * e1 - l2 * c2 * e2);
            }
        }
        // Near critical: slow exponential factored out, G -> t as q -> 0.
        let g = decay_over(delta, t);
        let e = (-l1 * t).exp();
        let b = l1 * x0 + v0;
        (e * (x0 + b * g), e * (v0 - l2 * b * g))
    }
}

// ---------------------------------------------------------------------------
// Coefficients for a physical spring
// ---------------------------------------------------------------------------

/// Naive mapping of a physical spring (stiffness `k`, damping `c`, mass `m`)
/// to the article's coefficients: `C_k = k/k_max = k·dt²/m`,
/// `C_d = c/d_max = c·dt/m`. Only first-order accurate.
pub fn naive_coefficients(k: f64, c: f64, m: f64, dt: f64) -> (f64, f64) {
    let ck = k / k_max(m, dt); // eq. 16 with eq. 14: k = k_max·C_k
    let cd = c / d_max(m, dt); // eq. 16 with eq. 15: d = d_max·C_d
    (ck, cd)
}

/// A minimal complex number, just enough for the pole computation.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Complex {
    pub re: f64,
    pub im: f64,
}

// Written as plain methods, the way the pole computation reads; the operators are not
// worth a trait implementation each.
#[allow(clippy::should_implement_trait)]
impl Complex {
    pub const ONE: Complex = Complex { re: 1.0, im: 0.0 };

    pub fn new(re: f64, im: f64) -> Self {
        Self { re, im }
    }

    pub fn add(self, o: Complex) -> Complex {
        Complex::new(self.re + o.re, self.im + o.im)
    }

    pub fn sub(self, o: Complex) -> Complex {
        Complex::new(self.re - o.re, self.im - o.im)
    }

    pub fn mul(self, o: Complex) -> Complex {
        Complex::new(
            self.re * o.re - self.im * o.im,
            self.re * o.im + self.im * o.re,
        )
    }

    pub fn scale(self, s: f64) -> Complex {
        Complex::new(self.re * s, self.im * s)
    }

    /// `e^{re}·(cos im + i·sin im)`.
    pub fn exp(self) -> Complex {
        let r = self.re.exp();
        Complex::new(r * self.im.cos(), r * self.im.sin())
    }

    pub fn abs(self) -> f64 {
        self.re.hypot(self.im)
    }
}

/// Poles of `s² + 2ζω·s + ω² = 0`, textbook formula
/// `s = ω·(−ζ ± √(ζ²−1))` (complex pair `−ζω ± i·ω√(1−ζ²)` for `ζ < 1`).
pub fn poles(omega: f64, zeta: f64) -> (Complex, Complex) {
    if zeta < 1.0 {
        let wd = omega * (1.0 - zeta * zeta).sqrt();
        (
            Complex::new(-zeta * omega, wd),
            Complex::new(-zeta * omega, -wd),
        )
    } else {
        let q = (zeta * zeta - 1.0).sqrt();
        (
            Complex::new(omega * (-zeta + q), 0.0),
            Complex::new(omega * (-zeta - q), 0.0),
        )
    }
}

/// Discrete poles `z_i = e^{s_i·dt}` of the sampled continuous oscillator.
pub fn discrete_poles(omega: f64, zeta: f64, dt: f64) -> (Complex, Complex) {
    let (s1, s2) = poles(omega, zeta);
    (s1.scale(dt).exp(), s2.scale(dt).exp())
}

/// Exact sampled-response coefficients, the naive way: from the poles,
/// `C_d = 1 − z1·z2`, `C_k = (1 − z1)(1 − z2)`; returns `(C_k, C_d)`.
///
/// Derivation: the map `u ← (1−C_d)·u − C_k·x; x ← x + u` gives
/// `x_{n+1} = (2 − C_k − C_d)·x_n − (1 − C_d)·x_{n−1}`, whose characteristic
/// roots are `z1, z2` iff `z1 + z2 = 2 − C_k − C_d` and `z1·z2 = 1 − C_d`.
/// The continuous samples `x(n·dt)` are combinations of `z1^n, z2^n`, so they
/// obey the same recurrence.
///
/// Deliberately cancellation-prone: `1 − z` is formed with an absolute error
/// of about `ε` while `|1 − z| ≈ |s|·dt`, so `C_k` carries a relative error
/// of about `2ε/(ω·dt)` for `ζ <= 1` and `ε·(ζ + √(ζ²−1))/(ω·dt)` for
/// `ζ > 1` (slow pole), and `C_d` an absolute error of about `ε` (at `ζ = 0`
/// it is rounding noise around 0 instead of exactly 0). Use it as a reference
/// only where `f·dt` is not tiny (e.g. 0.01..0.3). The imaginary parts are
/// zero up to rounding and are dropped.
pub fn exact_coefficients_from_poles(omega: f64, zeta: f64, dt: f64) -> (f64, f64) {
    let (z1, z2) = discrete_poles(omega, zeta, dt);
    let cd = Complex::ONE.sub(z1.mul(z2));
    let ck = Complex::ONE.sub(z1).mul(Complex::ONE.sub(z2));
    (ck.re, cd.re)
}

/// Initial per-step velocity `u0 = x(0) − x(−dt)` that starts the discrete
/// map on the continuous trajectory through `(x0, v0)` (not `v0·dt`).
///
/// Conditioning: for a strongly overdamped spring whose fast discrete pole
/// `z2 = e^{-λ2·dt}` is near or below `ε`, `x(−dt)` grows like
/// `e^{λ2·dt}`, so `u0` is huge, and `1 − C_d = z1·z2` is lost to rounding
/// in `C_d`. The map then reproduces the samples only to about `ε·|u0|`
/// absolute. This is a property of the `(x, u)` state with these
/// coefficients, not of this function.
pub fn u0_from_analytic(x0: f64, v0: f64, omega: f64, zeta: f64, dt: f64) -> f64 {
    let (x_prev, _) = analytic(x0, v0, omega, zeta, -dt);
    x0 - x_prev
}

// ---------------------------------------------------------------------------
// The discrete map on (x, u), u = v·dt
// ---------------------------------------------------------------------------

/// One step of the position-level map, `u = v·dt`:
/// `u ← u − (C_k·x + C_d·u)`, then `x ← x + u`.
///
/// This is corrected eq. 27 divided by `m` and multiplied by `dt`:
/// `v·dt += −C_k·x − C_d·v·dt`.
pub fn map_step(x: &mut f64, u: &mut f64, ck: f64, cd: f64) {
    *u -= ck * *x + cd * *u; // eq. 27 (corrected) in units u = v·dt
    *x += *u; // eq. 1 in units u = v·dt
}

/// The matrix `M` of `map_step` acting on the column `(x, u)`.
///
/// Derivation from `map_step`:
/// `u' = u − C_k·x − C_d·u = −C_k·x + (1 − C_d)·u`,
/// `x' = x + u' = (1 − C_k)·x + (1 − C_d)·u`, so
/// `M = [[1 − C_k, 1 − C_d], [−C_k, 1 − C_d]]` (rows give `x'`, `u'`),
/// with `trace M = 2 − C_k − C_d` and `det M = (1−C_k)(1−C_d) + C_k(1−C_d)
/// = 1 − C_d`.
pub fn map_matrix(ck: f64, cd: f64) -> [[f64; 2]; 2] {
    [[1.0 - ck, 1.0 - cd], [-ck, 1.0 - cd]]
}

/// Spectral radius of `map_matrix(ck, cd)`: the largest modulus of the
/// roots of `λ² − T·λ + D = 0`, `T = 2 − C_k − C_d`, `D = 1 − C_d`.
///
/// If `(T/2)² − D < 0` the roots are a conjugate pair of modulus `√D`;
/// otherwise both are real, `T/2 ± √((T/2)² − D)`, and the larger modulus
/// is `|T/2| + √((T/2)² − D)`. The map is asymptotically stable iff the
/// result is `< 1` (Jury: `C_k > 0`, `0 < C_d < 2`, `C_k + 2·C_d < 4`).
pub fn spectral_radius(ck: f64, cd: f64) -> f64 {
    let m = map_matrix(ck, cd);
    let half_trace = 0.5 * (m[0][0] + m[1][1]);
    let det = m[0][0] * m[1][1] - m[0][1] * m[1][0];
    let disc = half_trace * half_trace - det;
    if disc < 0.0 {
        det.sqrt()
    } else {
        half_trace.abs() + disc.sqrt()
    }
}
