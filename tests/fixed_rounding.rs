//! Fixed-point rounding: dead bands and limit cycles, measured for every rounding mode.
//!
//! An independent integer model of one spring in Q16.16 with Q3.29 coefficients,
//!
//! ```text
//! u ← R((1 − C_d)·u − C_k·x)        x ← x + u        (one rounding R per step)
//! ```
//!
//! is run from many starts with each rounding mode R until its state repeats (Brent's
//! cycle detection), which tells whether it ends on a fixed point (period 1, necessarily
//! with u = 0) and how far from the target, or in a limit cycle, and how large.
//!
//! The library's `I16F16` backend must follow the model of its chosen mode bit for bit;
//! that is checked here too, so the table describes the library and not only the model.
//!
//! `cargo test --release --test fixed_rounding -- --nocapture` prints the table.

use stiffspring::{I16F16, RestThreshold, SpringValue, Tuning};

const FRAC: u32 = 29;

#[derive(Clone, Copy, Debug, PartialEq)]
enum Mode {
    Floor,
    NearestUp,
    NearestAway,
    NearestEven,
    TowardZero,
}

const MODES: [Mode; 5] = [
    Mode::Floor,
    Mode::NearestUp,
    Mode::NearestAway,
    Mode::NearestEven,
    Mode::TowardZero,
];

/// `p / 2^29` rounded by `mode`, written from the definitions with `div_euclid` (floor)
/// rather than shifts, so it does not share code or tricks with the library.
fn round(p: i64, mode: Mode) -> i64 {
    let one = 1i64 << FRAC;
    let floor = p.div_euclid(one);
    let rem = p.rem_euclid(one); // 0 ≤ rem < one
    let twice = 2 * rem;
    match mode {
        Mode::Floor => floor,
        Mode::NearestUp => floor + i64::from(twice >= one),
        Mode::NearestAway => {
            if twice > one || (twice == one && p > 0) {
                floor + 1
            } else {
                floor
            }
        }
        Mode::NearestEven => {
            if twice > one || (twice == one && floor % 2 != 0) {
                floor + 1
            } else {
                floor
            }
        }
        Mode::TowardZero => {
            if p < 0 && rem != 0 {
                floor + 1
            } else {
                floor
            }
        }
    }
}

fn saturate(v: i64) -> i64 {
    v.clamp(i32::MIN as i64, i32::MAX as i64)
}

#[derive(Clone, Copy, PartialEq, Eq)]
struct State {
    x: i64,
    u: i64,
}

/// Coefficients as raw Q3.29, rounded to nearest as the library's set-up does.
fn raw(c: f64) -> i64 {
    (c * (1u64 << FRAC) as f64).round() as i64
}

fn step(s: State, ck: i64, keep: i64, mode: Mode) -> State {
    let u = saturate(round(keep * s.u - ck * s.x, mode));
    State {
        x: saturate(s.x + u),
        u,
    }
}

/// How a trajectory ends.
#[derive(Clone, Copy, Debug)]
enum End {
    /// A fixed point at offset `x` (LSB); `u` is 0 there.
    Rest { x: i64 },
    /// A cycle of this period and these peak magnitudes (LSB).
    Cycle { period: u64, x: i64, u: i64 },
    /// No repetition within the step budget (a very lightly damped spring still ringing).
    Unresolved,
}

/// Brent's cycle detection on the deterministic map.
fn end(start: State, ck: i64, keep: i64, mode: Mode, budget: u64) -> End {
    let mut power = 1u64;
    let mut period = 1u64;
    let mut tortoise = start;
    let mut hare = step(start, ck, keep, mode);
    let mut steps = 1u64;
    while tortoise != hare {
        if power == period {
            tortoise = hare;
            power *= 2;
            period = 0;
        }
        hare = step(hare, ck, keep, mode);
        period += 1;
        steps += 1;
        if steps > budget {
            return End::Unresolved;
        }
    }
    if period == 1 {
        return End::Rest { x: hare.x };
    }
    let (mut x, mut u) = (0i64, 0i64);
    let mut s = hare;
    for _ in 0..period {
        x = x.max(s.x.abs());
        u = u.max(s.u.abs());
        s = step(s, ck, keep, mode);
    }
    End::Cycle { period, x, u }
}

/// A deterministic grid of tunings: the exact map over f·dt and ζ (what users build),
/// plus raw coefficients with very light damping (where limit cycles live).
fn tunings() -> Vec<(f64, f64)> {
    let mut out = Vec::new();
    for &fdt in &[1e-3, 3e-3, 1e-2, 3e-2, 0.1, 0.2] {
        for &z in &[0.01, 0.05, 0.2, 0.7, 1.0, 3.0] {
            let t = Tuning::from_frequency(fdt / 1e-3, z, 1e-3).unwrap();
            out.push((t.stiffness(), t.damping()));
        }
    }
    for &ck in &[1e-3, 1e-2, 0.05, 0.3, 0.8, 1.5] {
        for &cd in &[1e-4, 1e-3, 1e-2] {
            out.push((ck, cd));
        }
    }
    out
}

fn starts() -> [State; 6] {
    [
        State { x: 1 << 16, u: 0 },
        State {
            x: -(1 << 20),
            u: 0,
        },
        State { x: 12_345, u: -678 },
        State { x: 0, u: 4_000 },
        State { x: 100 << 16, u: 0 },
        State { x: -7, u: 3 },
    ]
}

#[derive(Default)]
struct Summary {
    runs: usize,
    rests: usize,
    cycles: usize,
    unresolved: usize,
    /// Worst rest offset in units of the dead band `0.5/C_k`.
    worst_rest_in_half_bands: f64,
    /// Worst cycle peaks: offset in units of `0.5/C_k`, step velocity in LSB.
    worst_cycle_x_in_half_bands: f64,
    worst_cycle_u: i64,
    longest_period: u64,
}

const BUDGET: u64 = 4_000_000;

fn summarise(mode: Mode) -> Summary {
    let mut s = Summary::default();
    for (ck, cd) in tunings() {
        let (k, keep) = (raw(ck), raw(1.0 - cd));
        let half_band = 0.5 / ck;
        for start in starts() {
            s.runs += 1;
            match end(start, k, keep, mode, BUDGET) {
                End::Rest { x } => {
                    s.rests += 1;
                    s.worst_rest_in_half_bands =
                        s.worst_rest_in_half_bands.max(x.abs() as f64 / half_band);
                }
                End::Cycle { period, x, u } => {
                    s.cycles += 1;
                    s.worst_cycle_x_in_half_bands =
                        s.worst_cycle_x_in_half_bands.max(x as f64 / half_band);
                    s.worst_cycle_u = s.worst_cycle_u.max(u);
                    s.longest_period = s.longest_period.max(period);
                }
                End::Unresolved => s.unresolved += 1,
            }
        }
    }
    s
}

/// The table of `Scalar`'s documentation (`src/scalar/mod.rs`) and the README, printed
/// with `--nocapture` and checked here, figure for figure: runs, rests, cycles, and the
/// worst cycle in half-bands and LSB per step.
#[test]
fn rounding_mode_table_is_the_documented_one() {
    println!(
        "mode          runs  rest  cycle  unresolved  worst rest |x|·C_k/0.5  worst cycle |x|·C_k/0.5  |u| LSB  period"
    );
    for mode in MODES {
        let s = summarise(mode);
        println!(
            "{:<12} {:>5} {:>5} {:>6} {:>11} {:>22.2} {:>24.2} {:>8} {:>7}",
            format!("{mode:?}"),
            s.runs,
            s.rests,
            s.cycles,
            s.unresolved,
            s.worst_rest_in_half_bands,
            s.worst_cycle_x_in_half_bands,
            s.worst_cycle_u,
            s.longest_period
        );
        // (rests, cycles, worst cycle in half-bands rounded, worst cycle |u| in LSB)
        let documented = match mode {
            Mode::Floor => (228, 96, 144, 322),
            Mode::NearestUp | Mode::NearestAway | Mode::NearestEven => (192, 132, 1795, 1004),
            Mode::TowardZero => (324, 0, 0, 0),
        };
        let measured = (
            s.rests,
            s.cycles,
            s.worst_cycle_x_in_half_bands.round() as i64,
            s.worst_cycle_u,
        );
        assert_eq!((s.runs, s.unresolved), (324, 0), "{mode:?}");
        assert_eq!(
            measured, documented,
            "{mode:?}: the documented table is stale"
        );
    }
}

/// The measurements behind the library's choice, as assertions: truncation toward zero
/// always comes to rest within `1/C_k` LSB; round-to-nearest does produce limit cycles
/// (so the grid is not one where every mode would look fine).
#[test]
fn toward_zero_always_rests_and_nearest_does_not() {
    let chosen = summarise(Mode::TowardZero);
    assert_eq!(chosen.rests, chosen.runs);
    assert!(chosen.worst_rest_in_half_bands <= 2.0);
    for mode in [Mode::NearestUp, Mode::NearestAway, Mode::NearestEven] {
        let s = summarise(mode);
        assert!(s.cycles > 0, "{mode:?}");
        assert!(s.worst_rest_in_half_bands <= 1.0, "{mode:?}");
    }
}

/// The library's `I16F16` value follows the model with truncation toward zero bit for
/// bit, from the same raw coefficients and starts (the model's `u = 0` start is the
/// library's value at rest retargeted, with raw coefficients so no `P·Δx` is added).
#[test]
fn library_i16f16_follows_the_toward_zero_model_bit_for_bit() {
    let never = RestThreshold::new(1e-300, 1e-300).unwrap();
    for (ck, cd) in tunings() {
        let tuning = Tuning::from_coefficients_extended(ck, cd).unwrap();
        let (k, keep) = (raw(tuning.stiffness()), raw(tuning.retention()));
        for x0 in [1i64 << 16, -(1 << 20), 12_345, -7, 100 << 16] {
            let mut value =
                SpringValue::<I16F16, 1>::new([I16F16::from_bits(x0 as i32)], tuning, 1e-3)
                    .unwrap()
                    .with_rest_threshold(never);
            value.set_target([I16F16::ZERO]).unwrap();
            let mut model = State { x: x0, u: 0 };
            for n in 0..3_000 {
                model = step(model, k, keep, Mode::TowardZero);
                value.step();
                if value.is_at_rest() {
                    // Snapped to the target inside the widened band: the model must be
                    // inside it too — the dead band 1/C_k LSB, and beyond the square
                    // (C_k > 1) the limit-cycle band 4/C_d LSB (`rest.rs`).
                    let mut band = (1.0 / ck + 1.0).ceil() as i64;
                    if ck > 1.0 {
                        band = band.max((4.0 / cd + 4.0).ceil() as i64);
                    }
                    assert!(model.x.abs() <= band, "({ck}, {cd}) from {x0}, step {n}");
                    break;
                }
                assert_eq!(
                    (
                        value.offset()[0].to_bits() as i64,
                        value.step_velocity()[0].to_bits() as i64
                    ),
                    (model.x, model.u),
                    "({ck}, {cd}) from {x0}, step {n}"
                );
            }
        }
    }
}

/// With a threshold far below the dead band, a fixed-point value still settles, on every
/// tuning and start of the grid: the widened band covers where truncation stops.
#[test]
fn library_i16f16_always_settles() {
    let tiny = RestThreshold::new(1e-12, 1e-12).unwrap();
    for (ck, cd) in tunings() {
        let tuning = Tuning::from_coefficients_extended(ck, cd).unwrap();
        for start in starts() {
            let x0 = I16F16::from_bits(start.x as i32);
            let mut value = SpringValue::<I16F16, 1>::new([x0], tuning, 1e-3)
                .unwrap()
                .with_rest_threshold(tiny);
            value.set_target([I16F16::ZERO]).unwrap();
            let mut steps = 0u64;
            while !value.is_at_rest() && steps < BUDGET {
                value.step();
                steps += 1;
            }
            assert!(value.is_at_rest(), "({ck}, {cd}) from {}", start.x);
            assert_eq!(value.position(), [I16F16::ZERO]);
        }
    }
}
