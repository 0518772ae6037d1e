//! The error-against-cost table of issue 10: every candidate representation of the
//! precision study (`lab::precision`), in every backend, at 60 Hz, 1 kHz and 10 kHz.
//!
//! - **Error**: the study's tracking grid (`lab::precision::fixed_grid` and
//!   `float_grid`, 10,000 steps, releases and flings, springs of 1–50 Hz where
//!   `f·dt ≤ 0.2`, ζ from 0 to 10, amplitudes 1 and 100 in fixed point, 1 in floats)
//!   restricted to the three rates: the worst `max |x − x(t)| / A` at each rate, over the
//!   starts the candidate accepts whose `κ = |u₀|/A` is at most
//!   `lab::precision::KAPPA_MAX` (the study reports the ill-conditioned starts apart).
//! - **Cost**: the instructions per step of the study's model of the candidate on the
//!   host (callgrind, the stepping loop only), and its time per step. The models are
//!   bit-exact references in `i128` (a 256-bit accumulator for the wide `I32F32` forms)
//!   with their rounding mode chosen at run time: they rank the candidates' arithmetic,
//!   and overstate what a kernel written for one candidate costs. The library's kernel of
//!   the representation it ships (`kept`, `Scalar::advance`) is counted beside them.
//!   The step is the same for every candidate: a 2 Hz spring, ζ = 0.3, stepped at
//!   1 kHz from a release of amplitude 1.

use lab::measure::{self, Candidate};
use lab::precision::{
    Analytic, Backend, Cand, Coefs, Grid, Job, KAPPA_MAX, Run, Start, Stepper, candidates,
    dispatch, fixed_grid, float_grid,
};
use std::hint::black_box;
use std::time::{Duration, Instant};
use stiffspring::{I16F16, I32F32, Scalar};

/// The rates of the table.
pub const RATES: [f64; 3] = [60.0, 1000.0, 10_000.0];
/// The backends, in table order.
pub const BACKENDS: [Backend; 4] = [Backend::I16F16, Backend::I32F32, Backend::F32, Backend::F64];
/// Steps of the timed and counted run.
pub const STEPS: usize = 10_000;

/// The spring every candidate's cost is measured on: 2 Hz, ζ = 0.3 at 1 kHz, released
/// from 1.
fn cost_case() -> (Coefs, Start) {
    let (fdt, zeta) = (2.0 / 1000.0, 0.3);
    (
        Coefs::exact(fdt, zeta),
        Start::analytic(&Analytic::release(fdt, zeta, 1.0)),
    )
}

/// The study's grid at the table's three rates (`quick`: its short grid's springs).
fn grid(quick: bool) -> Grid {
    let mut g = if quick { Grid::quick() } else { Grid::full() };
    g.rates = RATES.to_vec();
    let mut fdt: Vec<f64> = RATES
        .iter()
        .flat_map(|r| g.freqs.iter().map(move |f| f / r))
        .filter(|&x| x <= g.max_fdt)
        .collect();
    fdt.sort_by(f64::total_cmp);
    fdt.dedup();
    g.f32_fdt = fdt;
    g
}

/// The runs of the grid: the fixed grid (I16F16, I32F32, and f64 at amplitude 1) and the
/// float grid's f32 runs, each f32 run placed at every rate whose springs give its `f·dt`.
pub fn runs(quick: bool) -> Vec<Run> {
    let g = grid(quick);
    let mut runs = fixed_grid(&g);
    for r in float_grid(&g) {
        if r.backend != Backend::F32 {
            continue;
        }
        for rate in RATES {
            if g.freqs
                .iter()
                .any(|f| (f / rate - r.fdt).abs() <= 1e-15 * r.fdt)
            {
                let mut r = r.clone();
                r.rate_hz = rate;
                runs.push(r);
            }
        }
    }
    runs
}

/// One row of the table.
pub struct Row {
    /// The backend.
    pub backend: &'static str,
    /// The candidate's published name.
    pub candidate: String,
    /// Worst error at each of [`RATES`] (`None`: every start rejected).
    pub errors: [Option<f64>; 3],
    /// Starts rejected (the state cannot hold them), over the three rates.
    pub rejected: usize,
    /// Host instructions per step (callgrind), if counted.
    pub instructions: Option<f64>,
    /// Host time per step, ns.
    pub ns: f64,
}

/// The worst error of each backend and candidate at each rate.
pub fn errors(runs: &[Run], b: Backend, c: Cand) -> ([Option<f64>; 3], usize) {
    let mut worst = [None; 3];
    let mut rejected = 0;
    for r in runs.iter().filter(|r| r.backend == b && r.cand == c) {
        let Some(k) = RATES.iter().position(|&rate| rate == r.rate_hz) else {
            continue;
        };
        if r.rejected {
            rejected += 1;
            continue;
        }
        if r.kappa > KAPPA_MAX {
            continue;
        }
        let e = if r.error.is_nan() {
            f64::INFINITY
        } else {
            r.error
        };
        worst[k] = Some(worst[k].map_or(e, |w: f64| w.max(e)));
    }
    (worst, rejected)
}

/// Times [`STEPS`] steps of a model per run (construction not timed).
struct Time;

impl Job for Time {
    type Out = Duration;
    fn run<S: Stepper>(&mut self, mut s: S) -> Duration {
        black_box(&mut s);
        let t = Instant::now();
        for _ in 0..STEPS {
            s.step();
        }
        let d = t.elapsed();
        black_box(s.position());
        d
    }
}

/// Runs [`STEPS`] steps of a model inside `lab::measure::counted`.
struct Count;

impl Job for Count {
    type Out = ();
    fn run<S: Stepper>(&mut self, mut s: S) {
        black_box(&mut s);
        measure::counted(&mut || {
            for _ in 0..STEPS {
                s.step();
            }
            black_box(s.position());
        });
    }
}

/// The timing closure of candidate `c` of backend `b`.
pub fn candidate(b: Backend, c: Cand) -> Candidate<'static> {
    let (coefs, start) = cost_case();
    Candidate::self_timed(STEPS, move |runs| {
        (0..runs)
            .map(|_| dispatch(b, c, coefs, start, &mut Time))
            .sum()
    })
}

/// The callgrind child: candidate number `c` of backend number `b` (or, for
/// `c == candidates(b).len()`, the library's kernel of that backend).
pub fn count(b: usize, c: usize) {
    let backend = BACKENDS[b];
    let all = candidates(backend);
    if c < all.len() {
        let (coefs, start) = cost_case();
        dispatch(backend, all[c], coefs, start, &mut Count);
    } else {
        match backend {
            Backend::I16F16 => library_count::<I16F16>(),
            Backend::I32F32 => library_count::<I32F32>(),
            Backend::F32 => library_count::<f32>(),
            Backend::F64 => library_count::<f64>(),
        }
    }
}

/// The library's step of the cost case, `Scalar::advance` on the wide state.
fn library_state<S: Scalar>() -> (S::Gains, S::State, S::State) {
    let (coefs, start) = cost_case();
    let gains = S::gains(coefs.ck, coefs.cd).expect("representable");
    (
        gains,
        S::state_from_f64(start.x0),
        S::state_from_f64(start.kept),
    )
}

fn library_count<S: Scalar>() {
    let (gains, mut x, mut v) = library_state::<S>();
    black_box((&mut x, &mut v));
    measure::counted(&mut || {
        for _ in 0..STEPS {
            S::advance(&gains, &mut x, &mut v);
        }
        black_box((x, v));
    });
}

/// The timing closure of the library's kernel in backend `S`.
pub fn library_candidate<S: Scalar>() -> Candidate<'static> {
    Candidate::self_timed(STEPS, move |runs| {
        let mut total = Duration::ZERO;
        for _ in 0..runs {
            let (gains, mut x, mut v) = library_state::<S>();
            black_box((&mut x, &mut v));
            let t = Instant::now();
            for _ in 0..STEPS {
                S::advance(&gains, &mut x, &mut v);
            }
            total += t.elapsed();
            black_box((x, v));
        }
        total
    })
}

/// The library's candidate of backend `b`.
pub fn library(b: Backend) -> Candidate<'static> {
    match b {
        Backend::I16F16 => library_candidate::<I16F16>(),
        Backend::I32F32 => library_candidate::<I32F32>(),
        Backend::F32 => library_candidate::<f32>(),
        Backend::F64 => library_candidate::<f64>(),
    }
}
