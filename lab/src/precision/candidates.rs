//! The backends, the candidates of each, and the dispatch of a job to a candidate's stepper.

use super::*;

/// A backend of the study.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Backend {
    /// Fixed point Q16.16.
    I16F16,
    /// Fixed point Q32.32.
    I32F32,
    /// f32.
    F32,
    /// f64.
    F64,
}

impl Backend {
    /// Its name in the tables.
    pub fn name(self) -> &'static str {
        match self {
            Backend::I16F16 => "I16F16",
            Backend::I32F32 => "I32F32",
            Backend::F32 => "f32",
            Backend::F64 => "f64",
        }
    }
    /// The fixed-point type (I16F16 for the float backends, which have none).
    pub fn fixed(self) -> Fixed {
        match self {
            Backend::I32F32 => Fixed::I32F32,
            _ => Fixed::I16F16,
        }
    }
}

/// A candidate representation.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Cand {
    /// Fixed r-form in the user format.
    R(RMode),
    /// Wide delta form.
    Wide {
        /// Guard bits.
        g: u32,
        /// Rounding.
        round: WRound,
    },
    /// `wide-24` with the approximate low partial product (I16F16):
    /// `(x_lo >> 16)·(m >> 16)` (one 32-bit multiply) or, `two`, `(x_lo >> 16)·m` (two).
    Wide24ApproxLo {
        /// Two 16×16 multiplies instead of one.
        two: bool,
        /// Add the mean of the dropped part back (a set-up constant).
        centred: bool,
    },
    /// f32 forms.
    F32(F32Form),
    /// f64, delta (`false`) or r-form (`true`).
    F64(bool),
    /// The `kept` form (floats: only `KRound::Lead`, meaning IEEE rounding).
    Kept(KRound),
}

impl Cand {
    /// The published name.
    pub fn name(self) -> String {
        match self {
            Cand::R(RMode::Truncate) => "truncate".into(),
            Cand::R(RMode::RemFloor) => "remainder-floor".into(),
            Cand::R(RMode::RemCentred) => "remainder-centred".into(),
            Cand::Wide { g, round } => match round {
                WRound::Zero => format!("wide-{g}"),
                WRound::Nearest => format!("wide-{g}-nearest"),
                WRound::Floor => format!("wide-{g}-floor"),
                WRound::UTrunc => format!("wide-{g}-utrunc"),
            },
            Cand::Wide24ApproxLo { two, centred } => format!(
                "wide-24-approx-lo{}{}",
                if two { "-2mul" } else { "" },
                if centred { "-centred" } else { "" }
            ),
            Cand::F32(f) => match f {
                F32Form::RForm => "r-form".into(),
                F32Form::Delta => "delta".into(),
                F32Form::CompX => "delta+comp-x".into(),
                F32Form::SplitK => "delta+split-k".into(),
                F32Form::CompXSplitK => "delta+comp-x+split-k".into(),
                F32Form::SplitKFma => "delta+split-k+fma".into(),
            },
            Cand::F64(false) => "delta".into(),
            Cand::F64(true) => "r-form".into(),
            Cand::Kept(KRound::Lead) => "kept".into(),
            Cand::Kept(KRound::Zero) => "kept-zero".into(),
            Cand::Kept(KRound::Nearest) => "kept-nearest".into(),
        }
    }
}

impl Cand {
    /// The largest magnitude (units) the candidate's state holds.
    pub fn range(self, b: Backend) -> f64 {
        let t = b.fixed();
        match self {
            Cand::R(_) => 2f64.powi((t.bits() - 1 - t.frac()) as i32),
            Cand::Wide { g, .. } => 2f64.powi((2 * t.bits() - 1 - t.frac() - g) as i32),
            Cand::Wide24ApproxLo { .. } => 2f64.powi(23),
            Cand::F32(_) => f32::MAX as f64,
            Cand::F64(_) => f64::MAX,
            Cand::Kept(_) => match b {
                Backend::F32 => f32::MAX as f64,
                Backend::F64 => f64::MAX,
                _ => 2f64.powi((2 * t.bits() - 1 - t.frac() - Kept::guard(t)) as i32),
            },
        }
    }

    /// The start does not fit the candidate's state: set-up would reject it.
    pub fn rejects(self, b: Backend, s: Start) -> bool {
        let r = self.range(b);
        let v = match self {
            Cand::Kept(_) => s.kept,
            _ => s.u0,
        };
        s.x0.abs() >= r || v.abs() >= r
    }
}

/// The candidates of a backend, in table order.
pub fn candidates(b: Backend) -> Vec<Cand> {
    let rounds = [WRound::Zero, WRound::UTrunc, WRound::Nearest, WRound::Floor];
    let mut v = vec![
        Cand::R(RMode::Truncate),
        Cand::R(RMode::RemFloor),
        Cand::R(RMode::RemCentred),
    ];
    match b {
        Backend::I16F16 => {
            for g in [16, 24, 32] {
                for round in rounds {
                    v.push(Cand::Wide { g, round });
                }
                if g == 24 {
                    for two in [false, true] {
                        for centred in [false, true] {
                            v.push(Cand::Wide24ApproxLo { two, centred });
                        }
                    }
                }
            }
        }
        Backend::I32F32 => {
            for g in [16, 32] {
                for round in rounds {
                    v.push(Cand::Wide { g, round });
                }
            }
        }
        Backend::F32 => {
            v = [
                F32Form::RForm,
                F32Form::Delta,
                F32Form::CompX,
                F32Form::SplitK,
                F32Form::CompXSplitK,
                F32Form::SplitKFma,
            ]
            .into_iter()
            .map(Cand::F32)
            .collect()
        }
        Backend::F64 => v = vec![Cand::F64(true), Cand::F64(false)],
    }
    match b {
        Backend::I16F16 | Backend::I32F32 => {
            v.extend([KRound::Lead, KRound::Zero, KRound::Nearest].map(Cand::Kept))
        }
        Backend::F32 | Backend::F64 => v.push(Cand::Kept(KRound::Lead)),
    }
    v
}

/// Something to do with a stepper, monomorphised per stepper type.
pub trait Job {
    /// Its result.
    type Out;
    /// Does it.
    fn run<S: Stepper>(&mut self, s: S) -> Self::Out;
}

/// Builds the candidate's stepper for `c` started at `start` and runs `job` on it.
pub fn dispatch<J: Job>(b: Backend, cand: Cand, c: Coefs, start: Start, job: &mut J) -> J::Out {
    let Start { x0, u0, .. } = start;
    match cand {
        Cand::R(mode) => job.run(RForm::new(b.fixed(), mode, c, x0, u0)),
        Cand::Wide { g, round } => {
            job.run(Wide::new(b.fixed(), g, round, Approx::Exact, c, x0, u0))
        }
        Cand::Wide24ApproxLo { two, centred } => {
            let approx = match (two, centred) {
                (false, false) => Approx::OneMul,
                (false, true) => Approx::OneMulCentred,
                (true, false) => Approx::TwoMul,
                (true, true) => Approx::TwoMulCentred,
            };
            job.run(Wide::new(
                Fixed::I16F16,
                24,
                WRound::Zero,
                approx,
                c,
                x0,
                u0,
            ))
        }
        Cand::F32(form) => job.run(F32::new(form, c, x0, u0)),
        Cand::F64(rform) => job.run(F64::new(rform, c, x0, u0)),
        Cand::Kept(r) => match b {
            Backend::F32 => job.run(KeptF32::new(c, start)),
            Backend::F64 => job.run(KeptF64::new(c, start)),
            _ => job.run(Kept::new(b.fixed(), r, c, start)),
        },
    }
}
