//! The candidate representations of one spring, each a bit-exact model (integers) or a float model with no fused operations.

use super::*;

/// One spring's state and step.
pub trait Stepper {
    /// One step `u ← u − a, x ← x + u`.
    fn step(&mut self);
    /// The position the user reads, in units.
    fn position(&self) -> f64;
    /// The position the user reads, in LSB of the user type (0 for floats).
    fn visible_lsb(&self) -> i128;
    /// The internal offset in LSB of the user type, unrounded.
    fn internal_lsb(&self) -> f64;
    /// The whole state, for cycle detection.
    fn key(&self) -> [i128; 3];
}

/// Which fixed-point user type.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Fixed {
    /// Q16.16 in `i32`.
    I16F16,
    /// Q32.32 in `i64`.
    I32F32,
}

impl Fixed {
    /// Fractional bits of the user type.
    pub fn frac(self) -> u32 {
        match self {
            Fixed::I16F16 => 16,
            Fixed::I32F32 => 32,
        }
    }
    /// Bits of the user type.
    pub fn bits(self) -> u32 {
        match self {
            Fixed::I16F16 => 32,
            Fixed::I32F32 => 64,
        }
    }
    /// Fractional bits of the r-form's coefficients (Q3.29, Q3.61).
    pub fn coef_frac(self) -> u32 {
        self.bits() - 3
    }
    /// Bits of a gain's mantissa (31, 63).
    pub fn mantissa_bits(self) -> u32 {
        self.bits() - 1
    }
}

/// Saturates to a signed `bits`-bit integer (`bits ≤ 128`).
#[inline(always)]
pub(super) fn sat(v: i128, bits: u32) -> i128 {
    let max = i128::MAX >> (128 - bits);
    v.clamp(-max - 1, max)
}

/// Today's r-form in the user format, with or without a carried remainder.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RMode {
    /// Rounded once toward zero.
    Truncate,
    /// Remainder carried, floor.
    RemFloor,
    /// Remainder carried, to nearest.
    RemCentred,
}

/// `u ← (1 − C_d)·u − C_k·x` in Q16.16/Q3.29 or Q32.32/Q3.61.
#[derive(Clone, Debug)]
pub struct RForm {
    x: i128,
    u: i128,
    e: i128,
    r: i128,
    k: i128,
    cf: u32,
    bits: u32,
    frac: u32,
    mode: RMode,
}

impl RForm {
    /// Quantises the coefficients (to nearest, saturating) and the start.
    pub fn new(t: Fixed, mode: RMode, c: Coefs, x0: f64, u0: f64) -> RForm {
        let cf = t.coef_frac();
        let bits = t.bits();
        RForm {
            x: sat(quantise(x0, t.frac()), bits),
            u: sat(quantise(u0, t.frac()), bits),
            e: 0,
            r: sat(quantise(1.0 - c.cd, cf), bits),
            k: sat(quantise(c.ck, cf), bits),
            cf,
            bits,
            frac: t.frac(),
            mode,
        }
    }
}

impl Stepper for RForm {
    #[inline(always)]
    fn step(&mut self) {
        let p = self.u * self.r - self.x * self.k + self.e;
        let q = match self.mode {
            RMode::Truncate => shr_round(p, self.cf, Round::Zero),
            RMode::RemFloor => shr_round(p, self.cf, Round::Floor),
            RMode::RemCentred => shr_round(p, self.cf, Round::Nearest),
        };
        if self.mode != RMode::Truncate {
            self.e = p - (q << self.cf);
        }
        self.u = sat(q, self.bits);
        self.x = sat(self.x + self.u, self.bits);
    }
    fn position(&self) -> f64 {
        self.x as f64 / 2f64.powi(self.frac as i32)
    }
    fn visible_lsb(&self) -> i128 {
        self.x
    }
    fn internal_lsb(&self) -> f64 {
        self.x as f64
    }
    fn key(&self) -> [i128; 3] {
        [self.x, self.u, self.e]
    }
}

/// How the wide delta form rounds.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum WRound {
    /// `a` toward zero.
    Zero,
    /// `a` to nearest (half up).
    Nearest,
    /// `a` toward −∞.
    Floor,
    /// The new `u` toward zero.
    UTrunc,
}

/// How `m·x` is formed in the I16F16 wide-24 model.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Approx {
    /// Exactly.
    Exact,
    /// `m·x_hi·2³² + (x_lo >> 16)·(m >> 16)·2³²`.
    OneMul,
    /// `m·x_hi·2³² + (x_lo >> 16)·m·2¹⁶`.
    TwoMul,
    /// `OneMul` plus the mean of what it drops, `2¹⁵·m + 2³¹·(m mod 2¹⁶)`.
    OneMulCentred,
    /// `TwoMul` plus the mean of what it drops, `2¹⁵·m`.
    TwoMulCentred,
}

/// The wide delta form: state with `g` guard bits, mantissas with one shared shift.
#[derive(Clone, Debug)]
pub struct Wide {
    x: i128,
    u: i128,
    mk: i128,
    md: i128,
    s: u32,
    g: u32,
    frac: u32,
    user_bits: u32,
    state_bits: u32,
    round: WRound,
    approx: Approx,
    i32f32: bool,
}

impl Wide {
    /// `t` with `g` guard bits; an approximate product only for I16F16 with G = 24.
    pub fn new(
        t: Fixed,
        g: u32,
        round: WRound,
        approx: Approx,
        c: Coefs,
        x0: f64,
        u0: f64,
    ) -> Wide {
        let (mk, md, s) = mantissas(c, t.mantissa_bits());
        let state_bits = 2 * t.bits();
        let frac = t.frac() + g;
        assert!(approx == Approx::Exact || (t == Fixed::I16F16 && frac == 40));
        Wide {
            x: sat(quantise(x0, frac), state_bits),
            u: sat(quantise(u0, frac), state_bits),
            mk,
            md,
            s,
            g,
            frac: t.frac(),
            user_bits: t.bits(),
            state_bits,
            round,
            approx,
            i32f32: t == Fixed::I32F32,
        }
    }

    /// The M0 shortcut: `m·x` with the low word's product `m·x_lo` replaced by
    /// `(x_lo >> 16)·(m >> 16)·2¹⁶`, always at or below the exact product.
    #[inline(always)]
    pub(super) fn approx(m: i128, x: i128) -> i128 {
        let x = x as i64;
        let hi = x >> 32;
        let lo = (x as u64) & 0xffff_ffff;
        let m = m as i64;
        let q = m * hi + ((lo >> 16) * ((m as u64) >> 16)) as i64;
        (q as i128) << 32
    }

    /// `(x_lo >> 16)·m` in full (two 16×16 multiplies on the M0): only `x_lo`'s low half
    /// is dropped.
    #[inline(always)]
    pub(super) fn approx2(m: i128, x: i128) -> i128 {
        let x = x as i64;
        let hi = x >> 32;
        let lo = (x as u64) & 0xffff_ffff;
        ((m * hi as i128) << 32) + (((lo >> 16) as i128 * m) << 16)
    }

    #[inline(always)]
    fn new_u(&self, p_floor_and_rem: impl Fn(Round) -> (i128, bool)) -> i128 {
        match self.round {
            WRound::Zero => self.u - p_floor_and_rem(Round::Zero).0,
            WRound::Nearest => self.u - p_floor_and_rem(Round::Nearest).0,
            WRound::Floor => self.u - p_floor_and_rem(Round::Floor).0,
            WRound::UTrunc => {
                // u' = u − p/2^s exactly lies in (n − 1, n] with n = u − floor(p/2^s);
                // toward zero it is n − 1 when it is positive and not an integer.
                let (a, inexact) = p_floor_and_rem(Round::Floor);
                let n = self.u - a;
                if inexact && n > 0 { n - 1 } else { n }
            }
        }
    }
}

impl Stepper for Wide {
    #[inline(always)]
    fn step(&mut self) {
        let s = self.s;
        let u = if self.i32f32 {
            let p = I256::mul(self.x, self.mk as u64).add(I256::mul(self.u, self.md as u64));
            self.new_u(|m| (p.shr_round(s, m), p.low_bits(s) != 0))
        } else {
            let p = match self.approx {
                Approx::Exact => self.mk * self.x + self.md * self.u,
                Approx::OneMul => Wide::approx(self.mk, self.x) + Wide::approx(self.md, self.u),
                Approx::TwoMul => Wide::approx2(self.mk, self.x) + Wide::approx2(self.md, self.u),
                Approx::OneMulCentred => {
                    let mean = |m: i128| (m << 15) + ((m & 0xffff) << 31);
                    Wide::approx(self.mk, self.x)
                        + Wide::approx(self.md, self.u)
                        + mean(self.mk)
                        + mean(self.md)
                }
                Approx::TwoMulCentred => {
                    Wide::approx2(self.mk, self.x)
                        + Wide::approx2(self.md, self.u)
                        + ((self.mk + self.md) << 15)
                }
            };
            self.new_u(|m| (shr_round(p, s, m), p & ((1i128 << s) - 1) != 0))
        };
        self.u = sat(u, self.state_bits);
        self.x = sat(self.x + self.u, self.state_bits);
    }
    fn position(&self) -> f64 {
        self.visible_lsb() as f64 / 2f64.powi(self.frac as i32)
    }
    fn visible_lsb(&self) -> i128 {
        sat(shr_round(self.x, self.g, Round::Nearest), self.user_bits)
    }
    fn internal_lsb(&self) -> f64 {
        self.x as f64 / 2f64.powi(self.g as i32)
    }
    fn key(&self) -> [i128; 3] {
        [self.x, self.u, 0]
    }
}

/// The f32 forms.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum F32Form {
    /// `u ← r·u − k·x`, `r = f32(1 − C_d)`.
    RForm,
    /// `u ← u − (k·x + d·u)`.
    Delta,
    /// Delta, `x` compensated with Fast2Sum.
    CompX,
    /// Delta, `C_k = k_hi + k_lo`.
    SplitK,
    /// Both.
    CompXSplitK,
    /// Split `C_k`, `a = fma(k_hi, x, k_lo·x + d·u)`: `k_hi·x` enters unrounded (the M4F's
    /// `vfma.f32`; `mul_add` is not in `core` on stable).
    SplitKFma,
}

/// One f32 spring.
#[derive(Clone, Debug)]
pub struct F32 {
    x: f32,
    u: f32,
    c: f32,
    k: f32,
    k_lo: f32,
    d: f32,
    r: f32,
    form: F32Form,
}

impl F32 {
    /// Coefficients rounded to f32 from f64.
    pub fn new(form: F32Form, c: Coefs, x0: f64, u0: f64) -> F32 {
        let k = c.ck as f32;
        F32 {
            x: x0 as f32,
            u: u0 as f32,
            c: 0.0,
            k,
            k_lo: (c.ck - k as f64) as f32,
            d: c.cd as f32,
            r: (1.0 - c.cd) as f32,
            form,
        }
    }
}

impl Stepper for F32 {
    #[inline(always)]
    fn step(&mut self) {
        let (x, u) = (self.x, self.u);
        self.u = match self.form {
            F32Form::RForm => self.r * u - self.k * x,
            F32Form::Delta | F32Form::CompX => u - (self.k * x + self.d * u),
            F32Form::SplitK | F32Form::CompXSplitK => {
                u - (self.k * x + (self.k_lo * x + self.d * u))
            }
            F32Form::SplitKFma => u - self.k.mul_add(x, self.k_lo * x + self.d * u),
        };
        match self.form {
            F32Form::CompX | F32Form::CompXSplitK => {
                // Fast2Sum of x and the step plus the carried error.
                let y = self.u + self.c;
                let s = x + y;
                self.c = y - (s - x);
                self.x = s;
            }
            _ => self.x = x + self.u,
        }
    }
    fn position(&self) -> f64 {
        self.x as f64
    }
    fn visible_lsb(&self) -> i128 {
        0
    }
    fn internal_lsb(&self) -> f64 {
        0.0
    }
    fn key(&self) -> [i128; 3] {
        [
            self.x.to_bits() as i128,
            self.u.to_bits() as i128,
            self.c.to_bits() as i128,
        ]
    }
}

/// One f64 spring, delta or r-form.
#[derive(Clone, Debug)]
pub struct F64 {
    x: f64,
    u: f64,
    k: f64,
    d: f64,
    r: f64,
    rform: bool,
}

impl F64 {
    /// The f64 map with the exact coefficients.
    pub fn new(rform: bool, c: Coefs, x0: f64, u0: f64) -> F64 {
        F64 {
            x: x0,
            u: u0,
            k: c.ck,
            d: c.cd,
            r: 1.0 - c.cd,
            rform,
        }
    }
}

impl Stepper for F64 {
    #[inline(always)]
    fn step(&mut self) {
        self.u = if self.rform {
            self.r * self.u - self.k * self.x
        } else {
            self.u - (self.k * self.x + self.d * self.u)
        };
        self.x += self.u;
    }
    fn position(&self) -> f64 {
        self.x
    }
    fn visible_lsb(&self) -> i128 {
        0
    }
    fn internal_lsb(&self) -> f64 {
        0.0
    }
    fn key(&self) -> [i128; 3] {
        [self.x.to_bits() as i128, self.u.to_bits() as i128, 0]
    }
}

/// How the `kept` form rounds its spring term `C_k·x` and its damping term `C_d·u`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum KRound {
    /// The lead's choice: spring toward zero, damping away from zero.
    Lead,
    /// Both toward zero.
    Zero,
    /// Both to nearest (half up, `(p + 2^(s−1)) >> s`, as the study's other nearest modes).
    Nearest,
}

impl KRound {
    /// (spring, damping) rounding.
    pub fn modes(self) -> (Round, Round) {
        match self {
            KRound::Lead => (Round::Zero, Round::Away),
            KRound::Zero => (Round::Zero, Round::Zero),
            KRound::Nearest => (Round::Nearest, Round::Nearest),
        }
    }
}

/// `round(v·2^s)` with the largest `s` for which it has at most `bits` bits (`v > 0`), or
/// `(0, 1)` for `v = 0`: a coefficient as its own mantissa and exponent.
pub fn mantissa(v: f64, bits: u32) -> (i128, u32) {
    if v == 0.0 {
        return (0, 1);
    }
    assert!(v > 0.0 && v.is_finite(), "coefficient {v}");
    let limit = ((1u128 << bits) - 1) as f64;
    let fits = |s: i32| (v * 2f64.powi(s)).round() <= limit;
    let mut s = (limit / v).log2().floor() as i32;
    while fits(s + 1) {
        s += 1;
    }
    while !fits(s) {
        s -= 1;
    }
    assert!((1..126).contains(&s), "shift {s} out of range for {v}");
    ((v * 2f64.powi(s)).round() as i128, s as u32)
}

/// The `kept` form in fixed point: state `x` and the kept step velocity `ũ = (1 − C_d)·u`,
/// Q24.40 in `i64` (I16F16) or Q64.64 in `i128` (I32F32); `C_k` and `C_d` each with its own
/// 31-/63-bit mantissa and shift; exact products.
///
/// ```text
/// u ← ũ − round_k(C_k·x);  x ← x + u;  ũ ← u − round_d(C_d·u)
/// ```
#[derive(Clone, Debug)]
pub struct Kept {
    x: i128,
    v: i128,
    mk: i128,
    sk: u32,
    md: i128,
    sd: u32,
    rk: Round,
    rd: Round,
    g: u32,
    frac: u32,
    user_bits: u32,
    state_bits: u32,
    i32f32: bool,
}

/// The bits the I16F16 step scales its state `(x, ũ)` into before each step (halving both
/// together): 2^16 units of a Q16.16 position, which the offset between two positions
/// stays within.
pub const I16F16_HELD_BITS: u32 = 57;

impl Kept {
    /// Guard bits of the state: 24 (Q24.40) for I16F16, 32 (Q64.64) for I32F32.
    pub fn guard(t: Fixed) -> u32 {
        match t {
            Fixed::I16F16 => 24,
            Fixed::I32F32 => 32,
        }
    }

    /// Quantises the coefficients (each its own mantissa) and the start (to nearest).
    pub fn new(t: Fixed, round: KRound, c: Coefs, start: Start) -> Kept {
        let (mk, sk) = mantissa(c.ck, t.mantissa_bits());
        let (md, sd) = mantissa(c.cd.max(0.0), t.mantissa_bits());
        let g = Kept::guard(t);
        let state_bits = 2 * t.bits();
        let f = t.frac() + g;
        let (rk, rd) = round.modes();
        Kept {
            x: sat(quantise(start.x0, f), state_bits),
            v: sat(quantise(start.kept, f), state_bits),
            mk,
            sk,
            md,
            sd,
            rk,
            rd,
            g,
            frac: t.frac(),
            user_bits: t.bits(),
            state_bits,
            i32f32: t == Fixed::I32F32,
        }
    }

    /// Starts at an exact state `(x, ũ)` in state LSB.
    pub fn from_state(t: Fixed, round: KRound, c: Coefs, x: i128, v: i128) -> Kept {
        let mut k = Kept::new(t, round, c, Start::discrete(c, 0.0, 0.0));
        k.x = sat(x, k.state_bits);
        k.v = sat(v, k.state_bits);
        k
    }

    /// `1/C_k` of the quantised `C_k`, state LSB: the dead band's half-width.
    pub fn dead_band(&self) -> f64 {
        2f64.powi(self.sk as i32) / self.mk as f64
    }

    /// `round(m·y / 2^s)`, exactly.
    #[inline(always)]
    fn term(&self, m: i128, y: i128, s: u32, mode: Round) -> i128 {
        if self.i32f32 {
            I256::mul(y, m as u64).shr_round(s, mode)
        } else {
            shr_round(m * y, s, mode)
        }
    }

    /// The quantised `C_k` as (mantissa, shift).
    pub fn ck(&self) -> (i128, u32) {
        (self.mk, self.sk)
    }

    /// The state `(x, ũ)` in state LSB.
    pub fn state(&self) -> (i128, i128) {
        (self.x, self.v)
    }
}

impl Stepper for Kept {
    #[inline(always)]
    fn step(&mut self) {
        if !self.i32f32 {
            // The I16F16 step halves its state until both are 57-bit integers (2^16
            // units) before it steps: within them it needs no general product for gains
            // up to C_k < 4.
            while sat(self.x, I16F16_HELD_BITS) != self.x || sat(self.v, I16F16_HELD_BITS) != self.v
            {
                self.x >>= 1;
                self.v >>= 1;
            }
        }
        let u = sat(
            self.v - self.term(self.mk, self.x, self.sk, self.rk),
            self.state_bits,
        );
        self.x = sat(self.x + u, self.state_bits);
        self.v = sat(u - self.term(self.md, u, self.sd, self.rd), self.state_bits);
    }
    fn position(&self) -> f64 {
        self.visible_lsb() as f64 / 2f64.powi(self.frac as i32)
    }
    fn visible_lsb(&self) -> i128 {
        sat(shr_round(self.x, self.g, Round::Nearest), self.user_bits)
    }
    fn internal_lsb(&self) -> f64 {
        self.x as f64 / 2f64.powi(self.g as i32)
    }
    fn key(&self) -> [i128; 3] {
        [self.x, self.v, 0]
    }
}

macro_rules! kept_float {
    ($name:ident, $t:ty, $doc:literal) => {
        #[doc = $doc]
        #[derive(Clone, Debug)]
        pub struct $name {
            x: $t,
            v: $t,
            k: $t,
            d: $t,
        }

        impl $name {
            /// Coefficients and start rounded from f64.
            pub fn new(c: Coefs, start: Start) -> $name {
                $name {
                    x: start.x0 as $t,
                    v: start.kept as $t,
                    k: c.ck as $t,
                    d: c.cd as $t,
                }
            }
        }

        impl Stepper for $name {
            #[inline(always)]
            fn step(&mut self) {
                let u = self.v - self.k * self.x;
                self.x += u;
                self.v = u - self.d * u;
            }
            fn position(&self) -> f64 {
                self.x as f64
            }
            fn visible_lsb(&self) -> i128 {
                0
            }
            fn internal_lsb(&self) -> f64 {
                0.0
            }
            fn key(&self) -> [i128; 3] {
                [self.x.to_bits() as i128, self.v.to_bits() as i128, 0]
            }
        }
    };
}

kept_float!(
    KeptF32,
    f32,
    "The `kept` form in f32: `u = v − k·x; x += u; v = u − d·u`, IEEE rounding, no fused operations."
);
kept_float!(KeptF64, f64, "The `kept` form in f64.");
