//! The whole study and its report: Markdown tables and CSV files.

use super::*;

/// Everything measured.
pub struct Study {
    /// The grid used.
    pub grid: Grid,
    /// Fixed-point grid (and f64 at amplitude 1).
    pub fixed: Vec<Run>,
    /// Float grid.
    pub float: Vec<Run>,
    /// Undamped long runs.
    pub long: Vec<Long>,
    /// Limit cycles.
    pub cycles: Vec<Cycle>,
    /// The `kept` rest search.
    pub claim: Vec<ClaimCase>,
    /// Wall time of the five parts (fixed grid, float grid, undamped, limit cycles, `kept`
    /// rest search), s.
    pub seconds: [f64; 5],
}

/// Runs the whole study.
pub fn study(grid: Grid) -> Study {
    let t = std::time::Instant::now();
    let fixed = fixed_grid(&grid);
    let t1 = t.elapsed().as_secs_f64();
    let float = float_grid(&grid);
    let t2 = t.elapsed().as_secs_f64();
    let long = undamped(&grid);
    let t3 = t.elapsed().as_secs_f64();
    let cycles = limit_cycles(&grid);
    let t4 = t.elapsed().as_secs_f64();
    let claim = claim_search(&grid.claim);
    let t5 = t.elapsed().as_secs_f64();
    Study {
        fixed,
        float,
        long,
        cycles,
        claim,
        grid,
        seconds: [t1, t2 - t1, t3 - t2, t4 - t3, t5 - t4],
    }
}

pub(super) fn worst<'a>(runs: impl Iterator<Item = &'a Run>) -> Option<&'a Run> {
    runs.filter(|r| !r.rejected)
        .fold(None, |w: Option<&Run>, r| match w {
            Some(w) if w.error >= r.error => Some(w),
            _ => Some(r),
        })
}

/// `|x|·C_k` at rest: how far below 1 (the dead band's edge) it stays; "—" with no rest.
pub(super) fn band_cell(v: f64, any: bool) -> String {
    if !any {
        "—".into()
    } else if v < 0.99 {
        format!("{v:.3}")
    } else if v < 1.0 {
        format!("1 − {:.1e}", 1.0 - v)
    } else {
        format!("{v:.6} (≥ 1!)")
    }
}

pub(super) fn sci(v: f64) -> String {
    if v == 0.0 {
        "0".into()
    } else {
        format!("{v:.1e}")
    }
}

pub(super) fn cell(r: Option<&Run>) -> String {
    r.map_or("—".into(), |r| sci(r.error))
}

pub(super) fn case(r: &Run) -> String {
    let spring = if r.rate_hz > 0.0 {
        format!("{} Hz @ {} Hz", r.f_hz, r.rate_hz)
    } else {
        format!("f·dt {}", r.fdt)
    };
    format!(
        "{spring}, ζ {}, A {}, {}, step {}",
        r.zeta,
        r.amplitude,
        r.kind.name(),
        r.at
    )
}

/// The rate classes of the tables: (label, lowest rate, highest rate).
pub const RATE_CLASSES: [(&str, f64, f64); 3] = [
    ("60–240 Hz", 60.0, 240.0),
    ("0.5–2 kHz", 500.0, 2000.0),
    ("5–10 kHz", 5000.0, 10000.0),
];

/// The f·dt bands of the float table.
/// The f·dt bands of the float table: `[lo, hi)`.
pub const FDT_BANDS: [(&str, f64, f64); 5] = [
    ("[1e-4, 1e-3)", 1e-4, 1e-3),
    ("[1e-3, 1e-2)", 1e-3, 1e-2),
    ("[1e-2, 0.1)", 1e-2, 0.1),
    ("[0.1, 0.25)", 0.1, 0.25),
    ("[0.25, 0.4]", 0.25, 0.41),
];

impl Study {
    fn fixed_runs(&self, b: Backend, c: Cand) -> impl Iterator<Item = &Run> {
        self.fixed
            .iter()
            .filter(move |r| r.backend == b && r.cand == c)
    }

    fn left(&self, b: Backend, c: Cand) -> String {
        let mut parts = Vec::new();
        for &fdt in &self.grid.long_fdt {
            let m = self
                .long
                .iter()
                .filter(|l| l.backend == b && l.cand == c && l.fdt == fdt)
                .map(|l| l.left)
                // the one farthest from 100 %
                .fold(f64::NAN, |a, v| {
                    if a.is_nan() || (v - 1.0).abs() > (a - 1.0).abs() {
                        v
                    } else {
                        a
                    }
                });
            parts.push(format!("{:.1} %", 100.0 * m));
        }
        parts.join(" / ")
    }

    /// One fixed-point tracking table: rows = candidates.
    fn tracking_table(&self, b: Backend, zeta0: bool, target: f64, amplitudes: &[f64]) -> String {
        let keep = |r: &&Run| {
            (r.zeta == 0.0) == zeta0 && amplitudes.contains(&r.amplitude) && r.kappa <= KAPPA_MAX
        };
        let mut s = String::new();
        let amp_cols: Vec<String> = self
            .grid
            .amplitudes
            .iter()
            .map(|a| format!("A = {a}, all rates"))
            .collect();
        s += &format!(
            "| candidate | {} | {} | ≤ {target:.0e} | worst case |{}\n",
            RATE_CLASSES.map(|c| c.0).join(" | "),
            amp_cols.join(" | "),
            if zeta0 {
                format!(
                    " left after {} steps (f·dt {}) |",
                    self.grid.long_steps,
                    self.grid
                        .long_fdt
                        .iter()
                        .map(|f| f.to_string())
                        .collect::<Vec<_>>()
                        .join(" / ")
                )
            } else {
                String::new()
            },
        );
        let ncol = 3 + self.grid.amplitudes.len() + 2 + usize::from(zeta0);
        s += &format!("|---|{}\n", "---|".repeat(ncol));
        for c in candidates(b) {
            let runs = || self.fixed_runs(b, c).filter(keep);
            let classes = RATE_CLASSES.map(|(_, lo, hi)| {
                cell(worst(runs().filter(|r| r.rate_hz >= lo && r.rate_hz <= hi)))
            });
            let amps: Vec<String> = self
                .grid
                .amplitudes
                .iter()
                .map(|&a| {
                    if amplitudes.contains(&a) {
                        cell(worst(runs().filter(|r| r.amplitude == a)))
                    } else {
                        "(not run)".into()
                    }
                })
                .collect();
            let w = worst(runs());
            let meets = match w {
                Some(w) if w.error <= target => "yes",
                Some(_) => "no",
                None => "—",
            };
            s += &format!(
                "| `{}` | {} | {} | {meets} | {} |{}\n",
                c.name(),
                classes.join(" | "),
                amps.join(" | "),
                w.map_or("—".into(), case),
                if zeta0 {
                    format!(" {} |", self.left(b, c))
                } else {
                    String::new()
                },
            );
        }
        s
    }

    fn float_table(&self) -> String {
        let mut s = String::new();
        s += &format!(
            "| backend | candidate | {} | ≤ 1e-5 (all) | worst, ζ > 0 | worst case | left after {} steps, ζ = 0 (f·dt {}) |\n",
            FDT_BANDS.map(|b| format!("f·dt {}", b.0)).join(" | "),
            self.grid.long_steps,
            self.grid
                .long_fdt
                .iter()
                .map(|f| f.to_string())
                .collect::<Vec<_>>()
                .join(" / "),
        );
        s += &format!("|---|---|{}\n", "---|".repeat(FDT_BANDS.len() + 4));
        for b in [Backend::F32, Backend::F64] {
            for c in candidates(b) {
                let runs = || {
                    self.float
                        .iter()
                        .filter(move |r| r.backend == b && r.cand == c && r.kappa <= KAPPA_MAX)
                };
                let bands = FDT_BANDS
                    .map(|(_, lo, hi)| cell(worst(runs().filter(|r| r.fdt >= lo && r.fdt < hi))));
                let w = worst(runs());
                let meets = if w.is_some_and(|w| w.error <= 1e-5) {
                    "yes"
                } else {
                    "no"
                };
                s += &format!(
                    "| {} | `{}` | {} | {meets} | {} | {} | {} |\n",
                    b.name(),
                    c.name(),
                    bands.join(" | "),
                    cell(worst(runs().filter(|r| r.zeta > 0.0))),
                    w.map_or("—".into(), case),
                    self.left(b, c),
                );
            }
        }
        s
    }

    fn cycle_table(&self) -> String {
        let mut s = String::new();
        s += "| backend | candidate | largest cycle, peak-to-peak (LSB) | longest period | largest final \\|x\\| read (LSB) | largest final \\|x\\| inside (LSB) | slowest repeat (steps) | no repeat within cap | at rest (fixed point) | ≤ 1 LSB | worst case |\n";
        s += "|---|---|---|---|---|---|---|---|---|---|---|\n";
        for b in [Backend::I16F16, Backend::I32F32] {
            for c in candidates(b) {
                let runs: Vec<&Cycle> = self
                    .cycles
                    .iter()
                    .filter(|r| r.backend == b && r.cand == c)
                    .collect();
                let pp = runs.iter().map(|r| r.end.peak_to_peak).max().unwrap_or(0);
                let period = runs.iter().map(|r| r.end.period).max().unwrap_or(0);
                let off = runs.iter().map(|r| r.end.offset).max().unwrap_or(0);
                let int = runs.iter().map(|r| r.end.internal).fold(0.0, f64::max);
                let open = runs.iter().filter(|r| r.end.steps.is_none()).count();
                let rest = runs.iter().filter(|r| r.end.period == 1).count();
                let slowest = runs.iter().filter_map(|r| r.end.steps).max().unwrap_or(0);
                let w = runs.iter().max_by(|a, b| {
                    (a.end.offset, a.end.peak_to_peak).cmp(&(b.end.offset, b.end.peak_to_peak))
                });
                let wc = w.map_or("—".into(), |r| {
                    format!(
                        "f·dt {:.3e}, ζ {}, start {}: period {}, p-p {}, \\|x\\| {} LSB",
                        r.fdt, r.zeta, r.start, r.end.period, r.end.peak_to_peak, r.end.offset
                    )
                });
                let meets = if off <= 1 && pp <= 1 { "yes" } else { "no" };
                s += &format!(
                    "| {} | `{}` | {pp} | {period} | {off} | {int:.3} | {slowest} | {open}/{n} | {rest}/{n} | {meets} | {wc} |\n",
                    b.name(),
                    c.name(),
                    n = runs.len()
                );
            }
        }
        s
    }

    /// The starts with `κ = |u₀|/A > KAPPA_MAX`, per backend and candidate.
    fn ill_conditioned_table(&self) -> String {
        let mut s = String::new();
        s += "| backend | candidate | starts | κ range | rejected (u₀ beyond the state) | worst error of the others | worst case | all started one step ahead: worst error |\n";
        s += "|---|---|---|---|---|---|---|---|\n";
        for b in [Backend::I16F16, Backend::I32F32, Backend::F32, Backend::F64] {
            for c in candidates(b) {
                let runs: Vec<&Run> = self
                    .fixed
                    .iter()
                    .chain(self.float.iter())
                    .filter(|r| r.backend == b && r.cand == c && r.kappa > KAPPA_MAX)
                    .collect();
                if runs.is_empty() {
                    continue;
                }
                let lo = runs.iter().map(|r| r.kappa).fold(f64::INFINITY, f64::min);
                let hi = runs.iter().map(|r| r.kappa).fold(0.0, f64::max);
                let rejected = runs.iter().filter(|r| r.rejected).count();
                let w = worst(runs.iter().copied());
                let ahead = runs.iter().map(|r| r.error_ahead).fold(0.0, f64::max);
                s += &format!(
                    "| {} | `{}` | {} | {}–{} | {rejected} | {} | {} | {} |\n",
                    b.name(),
                    c.name(),
                    runs.len(),
                    sci(lo),
                    sci(hi),
                    cell(w),
                    w.map_or("—".into(), |r| format!("{}, κ {}", case(r), sci(r.kappa))),
                    sci(ahead),
                );
            }
        }
        s
    }

    /// The markdown report.
    pub fn markdown(&self) -> String {
        let g = &self.grid;
        let mut s = String::new();
        s += &format!(
            "Grid: springs {:?} Hz at {:?} Hz with f·dt ≤ {}; ζ {:?}; releases (x0 = A, v0 = 0) and flings \
             (x0 = 0, peak A); {} steps; error = max |x − x(t)| / A of the position the user reads.\n\n",
            g.freqs, g.rates, g.max_fdt, g.zetas, g.steps
        );
        s += &format!(
            "Starts with κ = |u₀|/A > {KAPPA_MAX} (overdamped at large f·dt: u₀ = x(0) − x(−dt) carries the \
             fast mode, which the first step cancels) are left out of the tracking tables and shown in their own table.\n\n"
        );
        s += "### I16F16, ζ 0.1–10 (target ≤ 1e-3)\n\n";
        s += &self.tracking_table(Backend::I16F16, false, 1e-3, &g.amplitudes);
        s += "\n### I16F16, ζ = 0 (target ≤ 1e-3; ≥ 99 % left after 10⁶ steps; left = the worse of A = 1 and A = 100)\n\n";
        s += &self.tracking_table(Backend::I16F16, true, 1e-3, &g.amplitudes);
        s += "\n### I32F32, ζ 0–10, A = 1 (target ≤ 1e-7)\n\n";
        s += &self.i32_table();
        s += &format!(
            "\n### f32 and f64, A = 1, ζ {:?}, {} values of f·dt from {} to {} (log-spaced and round) (target ≤ 1e-5)\n\n",
            g.zetas,
            g.f32_fdt.len(),
            g.f32_fdt[0],
            g.f32_fdt[g.f32_fdt.len() - 1]
        );
        s += &self.float_table();
        s += &format!(
            "\n### Limit cycles and dead band: f·dt {:?}, ζ {:?}; per spring a release and a fling of 1 unit and {} random starts \
             within ±256 LSB; run until the state repeats (cap {} steps, `kept*` {}); LSB of the user type\n\n",
            g.lc_fdt
                .iter()
                .map(|f| format!("{f:.3e}"))
                .collect::<Vec<_>>(),
            g.lc_zetas,
            g.lc_starts,
            g.lc_cap,
            g.lc_kept_cap
        );
        s += &self.cycle_table();
        s += &format!("\n### Ill-conditioned starts (κ = |u₀|/A > {KAPPA_MAX}), all grids\n\n");
        s += &self.ill_conditioned_table();
        s += &self.claim_section();
        s
    }

    /// Does every damped `kept` start end on a fixed point (`u = ũ = 0`, `|x| < 1/C_k`)?
    fn claim_section(&self) -> String {
        let cg = &self.grid.claim;
        let mut s = String::new();
        s += &format!(
            "\n### `kept`: does every damped start end at rest?\n\n\
             A fixed point of `kept` has `u = ũ = 0` and `round_k(C_k·x) = 0`; with `C_k·x` toward zero that is \
             `|x| < 1/C_k` state LSB. The question is whether every damped start reaches one. Sources: the \
             limit-cycle grid above; every integer state with |x| ≤ max(2.5/C_k + 4, {EXHAUSTIVE_MIN}), \
             |ũ| ≤ max(2.5·θ/C_k + 4, {EXHAUSTIVE_MIN}) state LSB (I16F16 mantissas) at f·dt {:?} (the lead's \
             rounding) and {:?} (all three), ζ {:?}; {} random springs per backend (f·dt log-uniform in [{}, {}], \
             ζ in [0.01, 10]) with {} random states each in |x| ≤ 3/C_k, |ũ| ≤ 3·θ/C_k. Runs go until the state \
             repeats (Brent; cap 50/C_k + 10⁶ steps for the searches). `C_k` is the quantised coefficient; \
             rows split at C_k = 1.5.\n\n",
            cg.exhaustive_fdt
                .iter()
                .map(|f| format!("{f:.4}"))
                .collect::<Vec<_>>(),
            cg.exhaustive_all_fdt,
            CLAIM_ZETAS,
            cg.random_springs,
            cg.random_fdt.0,
            cg.random_fdt.1,
            cg.random_starts,
        );
        s += "| source | backend | rounding | C_k | springs | starts | at rest | cycles | no repeat | largest \\|x\\|·C_k at rest | longest period | largest cycle p-p (state LSB) | largest \\|x\\|·C_k on a cycle | slowest (steps) | longest final creep (steps with ũ = 0) |\n";
        s += "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
        let rounds = [KRound::Lead, KRound::Zero, KRound::Nearest];
        // The limit-cycle grid, from the cycles above.
        for b in [Backend::I16F16, Backend::I32F32] {
            for r in rounds {
                let runs: Vec<&Cycle> = self
                    .cycles
                    .iter()
                    .filter(|c| c.backend == b && c.cand == Cand::Kept(r))
                    .collect();
                if runs.is_empty() {
                    continue;
                }
                let g = Kept::guard(b.fixed());
                let band = runs
                    .iter()
                    .filter(|c| c.end.period == 1)
                    .map(|c| {
                        let k = Kept::from_state(b.fixed(), r, Coefs::exact(c.fdt, c.zeta), 0, 0);
                        c.end.internal * 2f64.powi(g as i32) / k.dead_band()
                    })
                    .fold(0.0, f64::max);
                let springs = runs.len() / (self.grid.lc_starts + 2);
                let rest = runs.iter().filter(|c| c.end.period == 1).count();
                s += &format!(
                    "| limit-cycle grid | {} | `{}` | < 1.5 | {springs} | {} | {rest} | {} | {} | {} | {} | (visible: {}) | — | {} | — |\n",
                    b.name(),
                    Cand::Kept(r).name(),
                    runs.len(),
                    runs.iter().filter(|c| c.end.period > 1).count(),
                    runs.iter().filter(|c| c.end.steps.is_none()).count(),
                    band_cell(band, rest > 0),
                    runs.iter().map(|c| c.end.period).max().unwrap_or(0),
                    runs.iter().map(|c| c.end.peak_to_peak).max().unwrap_or(0),
                    runs.iter().filter_map(|c| c.end.steps).max().unwrap_or(0),
                );
            }
        }
        for search in ["exhaustive", "random"] {
            for b in [Backend::I16F16, Backend::I32F32] {
                for r in rounds {
                    for high in [false, true] {
                        let cs: Vec<&ClaimCase> = self
                            .claim
                            .iter()
                            .filter(|c| {
                                c.search == search
                                    && c.backend == b
                                    && c.round == r
                                    && (1.0 / c.dead_band >= 1.5) == high
                            })
                            .collect();
                        if cs.is_empty() {
                            continue;
                        }
                        let sum = |f: fn(&ClaimCase) -> u64| cs.iter().map(|c| f(c)).sum::<u64>();
                        let max =
                            |f: fn(&ClaimCase) -> u64| cs.iter().map(|c| f(c)).max().unwrap_or(0);
                        let maxf =
                            |f: fn(&ClaimCase) -> f64| cs.iter().map(|c| f(c)).fold(0.0, f64::max);
                        s += &format!(
                            "| {search} | {} | `{}` | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} |\n",
                            b.name(),
                            Cand::Kept(r).name(),
                            if high { "≥ 1.5" } else { "< 1.5" },
                            cs.len(),
                            sum(|c| c.starts),
                            sum(|c| c.rest),
                            sum(|c| c.cycles),
                            sum(|c| c.open),
                            band_cell(maxf(|c| c.band_at_rest), sum(|c| c.rest) > 0),
                            max(|c| c.period),
                            cs.iter().map(|c| c.pp).max().unwrap_or(0),
                            if sum(|c| c.cycles) > 0 {
                                format!("{:.2}", maxf(|c| c.band_on_cycle))
                            } else {
                                "—".into()
                            },
                            max(|c| c.slowest),
                            max(|c| c.creep),
                        );
                    }
                }
            }
        }
        // Counterexamples of the lead's rounding.
        let bad: Vec<&ClaimCase> = self
            .claim
            .iter()
            .filter(|c| c.round == KRound::Lead && !c.examples.is_empty())
            .collect();
        let searched = self
            .claim
            .iter()
            .filter(|c| c.round == KRound::Lead)
            .count();
        if bad.is_empty() {
            s += &format!(
                "\nNo counterexample of the lead's rounding (spring toward zero, damping away from zero) among \
                 {searched} searched springs.\n"
            );
        } else {
            s += &format!(
                "\nCounterexamples of the lead's rounding (spring toward zero, damping away from zero): {} of \
                 {searched} searched springs have starts that end on a cycle; the smallest quantised C_k among them \
                 is {:.4}. One cycle is exact: for a quantised C_k in [1.5, 2) and ⌈3·C_d⌉ = 1 (C_d ≤ 1/3), \
                 (x, ũ) = (2, 0) → (−1, −2) → (−2, 0) → (1, 2) → (2, 0) (u = −3, −1, 3, 1: the spring gives \
                 ⌊2C_k⌋ = 3 and ⌊C_k⌋ = 1, the damping takes 1 LSB per step). C_k ≥ 1.5 is f·dt ≳ 0.21 at light \
                 damping, beyond the fixed-point grid (f·dt ≤ 0.2, C_k ≤ 1.38). The first start of each spring \
                 (state LSB; C_d as f64), lowest C_k first:\n\n",
                bad.len(),
                bad.iter()
                    .map(|c| 1.0 / c.dead_band)
                    .fold(f64::INFINITY, f64::min),
            );
        }
        if !bad.is_empty() {
            s += "| source | backend | f·dt | ζ | C_k | C_d | start (x, ũ) | period | a state on the cycle | p-p (state LSB) | max \\|x\\|·C_k |\n";
            s += "|---|---|---|---|---|---|---|---|---|---|---|\n";
            let mut shown = bad.clone();
            shown.sort_by(|a, b| (1.0 / a.dead_band).total_cmp(&(1.0 / b.dead_band)));
            for c in shown.iter().take(12) {
                let (st, e) = c.examples[0];
                s += &format!(
                    "| {} | {} | {:.4} | {:.4} | {:.4} | {:.4} | ({}, {}) | {} | ({}, {}) | {} | {:.2} |\n",
                    c.search,
                    c.backend.name(),
                    c.fdt,
                    c.zeta,
                    1.0 / c.dead_band,
                    Coefs::exact(c.fdt, c.zeta).cd,
                    st.0,
                    st.1,
                    e.period,
                    e.state.0,
                    e.state.1,
                    e.pp,
                    e.band
                );
            }
        }
        s
    }

    fn i32_table(&self) -> String {
        // The target grid is A = 1; A = 100 is shown for information.
        let b = Backend::I32F32;
        let mut s = String::new();
        s += &format!(
            "| candidate | {} | ζ = 0 only | A = 100 (info) | ≤ 1e-7 | worst case | left after {} steps, ζ = 0 (f·dt {}) |\n",
            RATE_CLASSES.map(|c| c.0).join(" | "),
            self.grid.long_steps,
            self.grid
                .long_fdt
                .iter()
                .map(|f| f.to_string())
                .collect::<Vec<_>>()
                .join(" / "),
        );
        s += &format!("|---|{}\n", "---|".repeat(RATE_CLASSES.len() + 6));
        for c in candidates(b) {
            let runs = || {
                self.fixed_runs(b, c)
                    .filter(|r| r.amplitude == 1.0 && r.kappa <= KAPPA_MAX)
            };
            let classes = RATE_CLASSES.map(|(_, lo, hi)| {
                cell(worst(runs().filter(|r| r.rate_hz >= lo && r.rate_hz <= hi)))
            });
            let w = worst(runs());
            let meets = if w.is_some_and(|w| w.error <= 1e-7) {
                "yes"
            } else {
                "no"
            };
            s += &format!(
                "| `{}` | {} | {} | {} | {meets} | {} | {} |\n",
                c.name(),
                classes.join(" | "),
                cell(worst(runs().filter(|r| r.zeta == 0.0))),
                cell(worst(
                    self.fixed_runs(b, c)
                        .filter(|r| r.amplitude == 100.0 && r.kappa <= KAPPA_MAX)
                )),
                w.map_or("—".into(), case),
                self.left(b, c),
            );
        }
        s
    }

    /// CSV files: (name, contents).
    pub fn csv(&self) -> Vec<(&'static str, String)> {
        let mut grid = String::from(
            "backend,candidate,f_hz,rate_hz,fdt,zeta,amplitude,kind,kappa,rejected,max_rel_error,at_step\n",
        );
        for r in self.fixed.iter().chain(self.float.iter()) {
            grid += &format!(
                "{},{},{},{},{:e},{},{},{},{:e},{},{:e},{}\n",
                r.backend.name(),
                r.cand.name(),
                r.f_hz,
                r.rate_hz,
                r.fdt,
                r.zeta,
                r.amplitude,
                r.kind.name(),
                r.kappa,
                r.rejected,
                r.error,
                r.at
            );
        }
        let mut long = String::from("backend,candidate,fdt,amplitude,steps,amplitude_left\n");
        for l in &self.long {
            long += &format!(
                "{},{},{:e},{},{},{}\n",
                l.backend.name(),
                l.cand.name(),
                l.fdt,
                l.amplitude,
                l.steps,
                l.left
            );
        }
        let mut cyc = String::from(
            "backend,candidate,fdt,zeta,start,steps_to_repeat,period,peak_to_peak_lsb,max_abs_read_lsb,max_abs_inside_lsb\n",
        );
        for c in &self.cycles {
            cyc += &format!(
                "{},{},{:e},{},{},{},{},{},{},{}\n",
                c.backend.name(),
                c.cand.name(),
                c.fdt,
                c.zeta,
                c.start,
                c.end.steps.map_or("".into(), |s| s.to_string()),
                c.end.period,
                c.end.peak_to_peak,
                c.end.offset,
                c.end.internal
            );
        }
        let mut claim = String::from(
            "search,backend,rounding,fdt,zeta,ck_quantised,starts,at_rest,cycles,no_repeat,max_abs_x_ck_at_rest,max_period,max_cycle_pp_state_lsb,max_abs_x_ck_on_cycle,slowest_steps,longest_creep,first_counterexample\n",
        );
        for c in &self.claim {
            claim += &format!(
                "{},{},{},{:e},{},{:e},{},{},{},{},{},{},{},{},{},{},{}\n",
                c.search,
                c.backend.name(),
                Cand::Kept(c.round).name(),
                c.fdt,
                c.zeta,
                1.0 / c.dead_band,
                c.starts,
                c.rest,
                c.cycles,
                c.open,
                c.band_at_rest,
                c.period,
                c.pp,
                c.band_on_cycle,
                c.slowest,
                c.creep,
                c.examples
                    .first()
                    .map_or(String::new(), |((x, v), e)| format!(
                        "start ({x} {v}) period {} via ({} {})",
                        e.period, e.state.0, e.state.1
                    )),
            );
        }
        vec![
            ("tracking.csv", grid),
            ("undamped.csv", long),
            ("limit_cycles.csv", cyc),
            ("kept_claim.csv", claim),
        ]
    }
}
