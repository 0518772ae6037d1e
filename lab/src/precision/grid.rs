//! The grids and the runs over them: tracking, the undamped long runs, the limit cycles.

use super::*;
use crate::rng::Rng;

/// Release (`x0 = A, v0 = 0`) or fling (`x0 = 0`, peak ≈ `A`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    /// From `A` at rest.
    Release,
    /// From 0, peak `A`.
    Fling,
}

impl Kind {
    /// Its name.
    pub fn name(self) -> &'static str {
        match self {
            Kind::Release => "release",
            Kind::Fling => "fling",
        }
    }
    /// The analytic trajectory of this start for a spring of `f·dt`, `ζ` and amplitude `a`.
    pub fn analytic(self, fdt: f64, zeta: f64, a: f64) -> Analytic {
        match self {
            Kind::Release => Analytic::release(fdt, zeta, a),
            Kind::Fling => Analytic::fling(fdt, zeta, a),
        }
    }
}

/// The grids (full or quick).
#[derive(Clone, Debug)]
pub struct Grid {
    /// Spring frequencies, Hz.
    pub freqs: Vec<f64>,
    /// Step rates, Hz.
    pub rates: Vec<f64>,
    /// Damping ratios.
    pub zetas: Vec<f64>,
    /// Amplitudes (units).
    pub amplitudes: Vec<f64>,
    /// Steps tracked.
    pub steps: usize,
    /// The largest f·dt on the fixed-point grid.
    pub max_fdt: f64,
    /// Undamped run: steps and the f·dt values.
    pub long_steps: u64,
    /// f·dt of the undamped long run.
    pub long_fdt: Vec<f64>,
    /// f32 grid: f·dt values.
    pub f32_fdt: Vec<f64>,
    /// Limit cycles: f·dt values, damping ratios, random starts, cap.
    pub lc_fdt: Vec<f64>,
    /// Damping ratios of the limit-cycle study.
    pub lc_zetas: Vec<f64>,
    /// Random small starts per spring (plus a release and a fling of 1 unit).
    pub lc_starts: usize,
    /// Step cap of the limit-cycle study.
    pub lc_cap: u64,
    /// Step cap of the limit-cycle study for the `kept` family: its lead rounding creeps one
    /// state LSB per step through `1/C_k ≤ |x| < 2/C_k` (up to `1/C_k` steps, 2.5·10⁶ at
    /// f·dt = 1e-4) before it rests.
    pub lc_kept_cap: u64,
    /// The search for starts of the `kept` family that do not come to rest.
    pub claim: ClaimGrid,
}

impl Grid {
    /// The grid of issue 10.
    pub fn full() -> Grid {
        Grid {
            // The springs, and some off the round numbers: a rational f·dt can put
            // the float map on an exactly periodic orbit that hides its drift.
            freqs: vec![1.0, 1.37, 2.0, 3.3, 5.0, 7.7, 10.0, 13.3, 20.0, 37.1, 50.0],
            rates: vec![60.0, 120.0, 240.0, 500.0, 1000.0, 2000.0, 5000.0, 10000.0],
            zetas: vec![0.0, 0.1, 0.3, 0.7, 1.0, 2.0, 10.0],
            amplitudes: vec![1.0, 100.0],
            steps: 10_000,
            max_fdt: 0.2,
            long_steps: 1_000_000,
            long_fdt: vec![1e-3, 1e-2],
            // 1e-4 to 0.4 in 32 log steps (generic values), and the round ones.
            f32_fdt: {
                let mut v: Vec<f64> = (0..=32)
                    .map(|i| 1e-4 * 4000f64.powf(i as f64 / 32.0))
                    .collect();
                v.extend([
                    2e-4, 5e-4, 1e-3, 2e-3, 5e-3, 1e-2, 2e-2, 5e-2, 0.1, 0.2, 0.3,
                ]);
                v.sort_by(f64::total_cmp);
                v
            },
            lc_fdt: vec![1e-4, 2e-4, 1e-3, 1e-2, 1.0 / 60.0, 0.05, 0.1, 0.2],
            lc_zetas: vec![0.05, 0.1, 0.3],
            lc_starts: 24,
            lc_cap: 1_000_000,
            lc_kept_cap: 10_000_000,
            claim: ClaimGrid::full(),
        }
    }

    /// A reduced grid for the tests.
    pub fn quick() -> Grid {
        Grid {
            freqs: vec![1.0, 2.0, 10.0, 50.0],
            rates: vec![60.0, 1000.0, 10000.0],
            zetas: vec![0.0, 0.1, 1.0, 10.0],
            amplitudes: vec![1.0, 100.0],
            steps: 10_000,
            max_fdt: 0.2,
            long_steps: 100_000,
            long_fdt: vec![1e-2],
            f32_fdt: vec![1e-4, 1e-2, 0.1137, 0.2, 0.4],
            lc_fdt: vec![1e-3, 0.1],
            lc_zetas: vec![0.1],
            lc_starts: 2,
            lc_cap: 300_000,
            lc_kept_cap: 3_000_000,
            claim: ClaimGrid::quick(),
        }
    }
}

/// One tracked run.
#[derive(Clone, Debug)]
pub struct Run {
    /// Backend.
    pub backend: Backend,
    /// Candidate.
    pub cand: Cand,
    /// Spring frequency (Hz), 0 on the f32 grid (given by f·dt only).
    pub f_hz: f64,
    /// Rate (Hz), 0 on the f32 grid.
    pub rate_hz: f64,
    /// f·dt.
    pub fdt: f64,
    /// ζ.
    pub zeta: f64,
    /// Amplitude.
    pub amplitude: f64,
    /// Release or fling.
    pub kind: Kind,
    /// max |x − x(t)| / A.
    pub error: f64,
    /// The step where it occurred.
    pub at: usize,
    /// Conditioning of the start, `|u₀| / A` (large for overdamped springs at large f·dt:
    /// `u₀ = x(0) − x(−dt)` then carries the fast mode, which the first step cancels).
    pub kappa: f64,
    /// The start does not fit the candidate's state (set-up would reject it).
    pub rejected: bool,
    /// For `κ > KAPPA_MAX`: the error when the state is started one step ahead,
    /// `(x(dt), x(dt) − x(0))`, and the position read as `x − u` (NaN otherwise).
    pub error_ahead: f64,
}

/// Starts with `|u₀| / A` above this are reported apart: their error is the cancellation
/// of the first step, `κ` times the relative precision of `C_d`, not the step's precision.
pub const KAPPA_MAX: f64 = 100.0;

pub(super) fn track_case(
    backends: &[Backend],
    (f_hz, rate_hz, fdt): (f64, f64, f64),
    zeta: f64,
    amplitude: f64,
    kind: Kind,
    steps: usize,
    out: &mut Vec<Run>,
) {
    let c = Coefs::exact(fdt, zeta);
    let an = kind.analytic(fdt, zeta, amplitude);
    let reference: Vec<f64> = (0..=steps as i64).map(|n| an.sample(n)).collect();
    let start = Start::analytic(&an);
    let u0 = start.u0;
    // One step ahead: the fast mode that u₀ carries is gone after the first step.
    let u1 = reference[1] - reference[0];
    let ahead = Start::discrete(c, reference[1], u1);
    for &b in backends {
        for cand in candidates(b) {
            let rejected = cand.rejects(b, start);
            let (e, at) = if rejected {
                (f64::NAN, 0)
            } else {
                dispatch(
                    b,
                    cand,
                    c,
                    start,
                    &mut Track {
                        reference: &reference,
                    },
                )
            };
            let error_ahead = if u0.abs() / amplitude > KAPPA_MAX && !cand.rejects(b, ahead) {
                dispatch(
                    b,
                    cand,
                    c,
                    ahead,
                    &mut Track {
                        reference: &reference[1..],
                    },
                )
                .0 / amplitude
            } else {
                f64::NAN
            };
            out.push(Run {
                backend: b,
                cand,
                f_hz,
                rate_hz,
                fdt,
                zeta,
                amplitude,
                kind,
                error: e / amplitude,
                at,
                kappa: u0.abs() / amplitude,
                rejected,
                error_ahead,
            });
        }
    }
}

/// The fixed-point grid: I16F16 at every amplitude, I32F32 at every amplitude, f64 at 1.
pub fn fixed_grid(g: &Grid) -> Vec<Run> {
    let mut cases = Vec::new();
    for &rate in &g.rates {
        for &f in &g.freqs {
            let fdt = f / rate;
            if fdt <= g.max_fdt {
                for &zeta in &g.zetas {
                    for &a in &g.amplitudes {
                        for kind in [Kind::Release, Kind::Fling] {
                            cases.push(((f, rate, fdt), zeta, a, kind));
                        }
                    }
                }
            }
        }
    }
    parallel(&cases, |&(spring, zeta, a, kind)| {
        let mut out = Vec::new();
        track_case(
            &[Backend::I16F16, Backend::I32F32],
            spring,
            zeta,
            a,
            kind,
            g.steps,
            &mut out,
        );
        if a == 1.0 {
            track_case(&[Backend::F64], spring, zeta, a, kind, g.steps, &mut out);
        }
        out
    })
}

/// The float grid: f·dt from 1e-4 to 0.4, amplitude 1.
pub fn float_grid(g: &Grid) -> Vec<Run> {
    let mut cases = Vec::new();
    for &fdt in &g.f32_fdt {
        for &zeta in &g.zetas {
            for kind in [Kind::Release, Kind::Fling] {
                cases.push((fdt, zeta, kind));
            }
        }
    }
    parallel(&cases, |&(fdt, zeta, kind)| {
        let mut out = Vec::new();
        track_case(
            &[Backend::F32, Backend::F64],
            (0.0, 0.0, fdt),
            zeta,
            1.0,
            kind,
            g.steps,
            &mut out,
        );
        out
    })
}

/// One undamped long run.
#[derive(Clone, Debug)]
pub struct Long {
    /// Backend.
    pub backend: Backend,
    /// Candidate.
    pub cand: Cand,
    /// f·dt.
    pub fdt: f64,
    /// Amplitude.
    pub amplitude: f64,
    /// Steps.
    pub steps: u64,
    /// max |x| over the last period / max |x(t)| over the same samples.
    pub left: f64,
}

/// ζ = 0 releases, `long_steps` steps: the amplitude left.
pub fn undamped(g: &Grid) -> Vec<Long> {
    let mut cases = Vec::new();
    for &fdt in &g.long_fdt {
        for &a in &g.amplitudes {
            for b in [Backend::I16F16, Backend::I32F32, Backend::F32, Backend::F64] {
                for cand in candidates(b) {
                    cases.push((b, cand, fdt, a));
                }
            }
        }
    }
    let steps = g.long_steps;
    parallel(&cases, |&(b, cand, fdt, a)| {
        let c = Coefs::exact(fdt, 0.0);
        let an = Analytic::release(fdt, 0.0, a);
        let window = (1.0 / fdt).ceil() as u64 + 1;
        let reference = ((steps - window + 1)..=steps)
            .map(|n| an.sample(n as i64).abs())
            .fold(0.0, f64::max);
        let m = dispatch(
            b,
            cand,
            c,
            Start::analytic(&an),
            &mut Amplitude { steps, window },
        );
        vec![Long {
            backend: b,
            cand,
            fdt,
            amplitude: a,
            steps,
            left: m / reference,
        }]
    })
}

/// One limit-cycle run.
#[derive(Clone, Debug)]
pub struct Cycle {
    /// Backend.
    pub backend: Backend,
    /// Candidate.
    pub cand: Cand,
    /// f·dt.
    pub fdt: f64,
    /// ζ.
    pub zeta: f64,
    /// Start number (0: release of 1 unit, 1: fling of 1 unit, then random small starts).
    pub start: usize,
    /// The end state.
    pub end: Final,
}

/// Starts of the limit-cycle study for one spring, in units of the backend's visible LSB:
/// a release and a fling of one unit, then random `x0` in ±256 LSB and `u0` in
/// ±256·θ LSB (the step velocity of an oscillation of that size; `kept` starts from
/// `ũ₀ = (1 − C_d)·u₀`). Deterministic.
pub fn lc_starts(g: &Grid, fdt: f64, zeta: f64, lsb: f64) -> Vec<Start> {
    let c = Coefs::exact(fdt, zeta);
    let mut v = Vec::new();
    for kind in [Kind::Release, Kind::Fling] {
        v.push(Start::analytic(&kind.analytic(fdt, zeta, 1.0)));
    }
    let mut rng = Rng::seeded(fdt.to_bits() ^ zeta.to_bits().rotate_left(17));
    let theta = 2.0 * PI * fdt;
    for _ in 0..g.lc_starts {
        // 2^-40 granularity of LSB keeps every value exact in f64 and random in the guard bits.
        let q = |r: f64| (r * 2f64.powi(40)).round() / 2f64.powi(40);
        let x = q(256.0 * rng.sym(1.0));
        let u = q(256.0 * theta * rng.sym(1.0));
        v.push(Start::discrete(c, x * lsb, u * lsb));
    }
    v
}

/// The limit-cycle and dead-band study of the fixed-point candidates.
pub fn limit_cycles(g: &Grid) -> Vec<Cycle> {
    let mut cases = Vec::new();
    for b in [Backend::I16F16, Backend::I32F32] {
        for &fdt in &g.lc_fdt {
            for &zeta in &g.lc_zetas {
                for cand in candidates(b) {
                    cases.push((b, cand, fdt, zeta));
                }
            }
        }
    }
    parallel(&cases, |&(b, cand, fdt, zeta)| {
        let c = Coefs::exact(fdt, zeta);
        let lsb = 2f64.powi(-(b.fixed().frac() as i32));
        let window = 2 * (1.0 / fdt).ceil() as u64;
        let cap = match cand {
            Cand::Kept(_) => g.lc_kept_cap,
            _ => g.lc_cap,
        };
        lc_starts(g, fdt, zeta, lsb)
            .into_iter()
            .enumerate()
            .map(|(i, start)| Cycle {
                backend: b,
                cand,
                fdt,
                zeta,
                start: i,
                end: dispatch(b, cand, c, start, &mut Settle { cap, window }),
            })
            .collect()
    })
}
