//! The rest search of the `kept` family: does every damped start end at rest?

use super::*;
use crate::rng::Rng;

/// Where one `kept` run ends, in state LSB.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct KeptEnd {
    /// Steps until the repeat was seen (None: none within the cap).
    pub steps: Option<u64>,
    /// Cycle length (1: a fixed point, `u = ũ = 0`; 0: no repeat).
    pub period: u64,
    /// A state on the final cycle (or the last state).
    pub state: (i128, i128),
    /// Largest `|x|·C_k` over the final cycle (quantised `C_k`): `< 1` is inside the dead band.
    pub band: f64,
    /// Peak-to-peak of `x` over the final cycle, state LSB.
    pub pp: i128,
    /// Steps before the repeat during which `ũ` was 0 after the step, trailing: the creep
    /// of one state LSB per step outside the dead band (0 if the last step moved `ũ`).
    pub creep: u64,
}

/// Runs `k` until its state repeats (Brent, and an immediate test for a fixed point) or `cap`.
pub fn kept_settle(mut k: Kept, cap: u64) -> KeptEnd {
    let (mut power, mut lam, mut steps, mut creep) = (1u64, 0u64, 0u64, 0u64);
    let mut tortoise = k.state();
    let found = loop {
        let before = k.state();
        k.step();
        steps += 1;
        lam += 1;
        let now = k.state();
        if now == before {
            lam = 1;
            break true;
        }
        creep = if now.1 == 0 { creep + 1 } else { 0 };
        if now == tortoise {
            break true;
        }
        if lam == power {
            tortoise = now;
            power *= 2;
            lam = 0;
        }
        if steps >= cap {
            break false;
        }
    };
    let span = if found { lam } else { 1 };
    let (mut lo, mut hi, mut band) = (i128::MAX, i128::MIN, 0.0f64);
    let db = k.dead_band();
    for _ in 0..span {
        k.step();
        let x = k.state().0;
        lo = lo.min(x);
        hi = hi.max(x);
        band = band.max(x.abs() as f64 / db);
    }
    KeptEnd {
        steps: found.then_some(steps),
        period: if found { lam } else { 0 },
        state: k.state(),
        band,
        pp: hi - lo,
        creep: if found && lam == 1 { creep } else { 0 },
    }
}

/// One spring of the claim search: how its starts end.
#[derive(Clone, Debug)]
pub struct ClaimCase {
    /// Which search: `"exhaustive"` or `"random"`.
    pub search: &'static str,
    /// I16F16 (31-bit mantissas) or I32F32 (63-bit).
    pub backend: Backend,
    /// Rounding of the two terms.
    pub round: KRound,
    /// f·dt.
    pub fdt: f64,
    /// ζ.
    pub zeta: f64,
    /// `1/C_k` (quantised), state LSB.
    pub dead_band: f64,
    /// Starts run.
    pub starts: u64,
    /// Ended on a fixed point.
    pub rest: u64,
    /// Ended on a cycle of period > 1.
    pub cycles: u64,
    /// No repeat within the cap.
    pub open: u64,
    /// Largest `|x|·C_k` at a fixed point (must be < 1).
    pub band_at_rest: f64,
    /// Largest `|x|·C_k` on a cycle.
    pub band_on_cycle: f64,
    /// Longest period of a cycle.
    pub period: u64,
    /// Largest peak-to-peak of a cycle, state LSB.
    pub pp: i128,
    /// Most steps to the repeat.
    pub slowest: u64,
    /// Longest trailing creep before rest (steps with `ũ = 0`).
    pub creep: u64,
    /// Up to three starts that do not rest: (start, end).
    pub examples: Vec<((i128, i128), KeptEnd)>,
}

/// The ζ of the claim search (all damped).
pub const CLAIM_ZETAS: [f64; 14] = [
    0.001, 0.005, 0.01, 0.02, 0.05, 0.1, 0.2, 0.3, 0.5, 0.7, 1.0, 2.0, 5.0, 10.0,
];

/// The smallest half-width of the exhaustive box, state LSB.
pub const EXHAUSTIVE_MIN: i128 = 24;

/// Springs and sizes of the claim search.
#[derive(Clone, Debug)]
pub struct ClaimGrid {
    /// Exhaustive, the lead's rounding: f·dt values; every integer state with
    /// `|x| ≤ max(2.5/C_k + 4, 24)`, `|ũ| ≤ max(2.5·θ/C_k + 4, 24)`, for each of [`CLAIM_ZETAS`].
    pub exhaustive_fdt: Vec<f64>,
    /// The same for all three roundings.
    pub exhaustive_all_fdt: Vec<f64>,
    /// Random springs: f·dt log-uniform in this range, ζ log-uniform in [0.01, 10].
    pub random_fdt: (f64, f64),
    /// Random springs per backend.
    pub random_springs: usize,
    /// Random starts per spring, uniform in `|x| ≤ 3/C_k`, `|ũ| ≤ 3·θ/C_k`.
    pub random_starts: usize,
}

impl ClaimGrid {
    /// The full search.
    pub fn full() -> ClaimGrid {
        ClaimGrid {
            exhaustive_fdt: vec![0.02, 1.0 / 60.0, 0.15, 0.205, 0.21, 0.22],
            exhaustive_all_fdt: vec![0.05, 0.1, 0.2, 0.25],
            random_fdt: (1e-3, 0.25),
            random_springs: 200,
            random_starts: 32,
        }
    }
    /// The quick one.
    pub fn quick() -> ClaimGrid {
        ClaimGrid {
            exhaustive_fdt: vec![0.05],
            exhaustive_all_fdt: vec![0.2],
            random_fdt: (1e-3, 0.25),
            random_springs: 8,
            random_starts: 8,
        }
    }
}

/// The claim search: every `kept` rounding over small integer states (I16F16 mantissas) and
/// random states near the dead band (both backends, the lead's rounding).
pub fn claim_search(cg: &ClaimGrid) -> Vec<ClaimCase> {
    let rounds = [KRound::Lead, KRound::Zero, KRound::Nearest];
    // (search, backend, round, fdt, zeta, seed)
    let mut cases = Vec::new();
    for (list, rs) in [
        (&cg.exhaustive_fdt, &rounds[..1]),
        (&cg.exhaustive_all_fdt, &rounds[..]),
    ] {
        for &fdt in list {
            for zeta in CLAIM_ZETAS {
                for &r in rs {
                    cases.push(("exhaustive", Backend::I16F16, r, fdt, zeta, 0u64));
                }
            }
        }
    }
    for b in [Backend::I16F16, Backend::I32F32] {
        let mut rng = Rng::seeded(0x6b65_7074 ^ b as u64);
        let (lo, hi) = cg.random_fdt;
        for i in 0..cg.random_springs {
            let fdt = lo * (hi / lo).powf(0.5 + 0.5 * rng.sym(1.0));
            let zeta = 0.01 * 1000f64.powf(0.5 + 0.5 * rng.sym(1.0));
            cases.push(("random", b, KRound::Lead, fdt, zeta, i as u64 + 1));
        }
    }
    let starts = cg.random_starts;
    parallel(&cases, |&(search, b, round, fdt, zeta, seed)| {
        let c = Coefs::exact(fdt, zeta);
        let t = b.fixed();
        let probe = Kept::from_state(t, round, c, 0, 0);
        let db = probe.dead_band();
        let theta = 2.0 * PI * fdt;
        // Every orbit here rests within a few times 1/C_k steps (creep included); the cap
        // leaves room for a cycle of any plausible period to be seen.
        let cap = (50.0 * db) as u64 + 1_000_000;
        let mut case = ClaimCase {
            search,
            backend: b,
            round,
            fdt,
            zeta,
            dead_band: db,
            starts: 0,
            rest: 0,
            cycles: 0,
            open: 0,
            band_at_rest: 0.0,
            band_on_cycle: 0.0,
            period: 0,
            pp: 0,
            slowest: 0,
            creep: 0,
            examples: Vec::new(),
        };
        let mut run = |x: i128, v: i128| {
            let e = kept_settle(Kept::from_state(t, round, c, x, v), cap);
            case.starts += 1;
            match e.period {
                1 => {
                    case.rest += 1;
                    case.band_at_rest = case.band_at_rest.max(e.band);
                    case.creep = case.creep.max(e.creep);
                }
                0 => case.open += 1,
                p => {
                    case.cycles += 1;
                    case.band_on_cycle = case.band_on_cycle.max(e.band);
                    case.period = case.period.max(p);
                    case.pp = case.pp.max(e.pp);
                }
            }
            case.slowest = case.slowest.max(e.steps.unwrap_or(cap));
            if e.period != 1 && case.examples.len() < 3 {
                case.examples.push(((x, v), e));
            }
        };
        if search == "exhaustive" {
            let xm = ((2.5 * db).ceil() as i128 + 4).max(EXHAUSTIVE_MIN);
            let vm = ((2.5 * theta * db).ceil() as i128 + 4).max(EXHAUSTIVE_MIN);
            for x in -xm..=xm {
                for v in -vm..=vm {
                    run(x, v);
                }
            }
        } else {
            let mut rng = Rng::seeded(seed.wrapping_mul(0x9E37_79B9) ^ fdt.to_bits());
            for _ in 0..starts {
                let x = (3.0 * db * rng.sym(1.0)).round() as i128;
                let v = (3.0 * theta * db * rng.sym(1.0)).round() as i128;
                run(x, v);
            }
        }
        vec![case]
    })
}

/// Maps `f` over `items` on up to two threads (the study machine is shared), keeping order.
pub fn parallel<T: Sync, R: Send>(items: &[T], f: impl Fn(&T) -> Vec<R> + Sync) -> Vec<R> {
    let threads = std::thread::available_parallelism()
        .map(|n| n.get())
        .unwrap_or(1)
        .min(2);
    let next = std::sync::atomic::AtomicUsize::new(0);
    let mut parts: Vec<(usize, Vec<R>)> = std::thread::scope(|scope| {
        let handles: Vec<_> = (0..threads)
            .map(|_| {
                scope.spawn(|| {
                    let mut mine = Vec::new();
                    loop {
                        let i = next.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
                        if i >= items.len() {
                            break mine;
                        }
                        mine.push((i, f(&items[i])));
                    }
                })
            })
            .collect();
        handles
            .into_iter()
            .flat_map(|h| h.join().unwrap())
            .collect()
    });
    parts.sort_by_key(|p| p.0);
    parts.into_iter().flat_map(|p| p.1).collect()
}
