//! Issue 17: the knob silent at rest, measured on torque, and a bad encoder sample
//! survived. The rotors, the encoder, the torque-window metric and the grid are in
//! `lab/src/knob/rest.rs`, written from the physics and independent of the library; this
//! file sets up the library's knob through its public API for each of them.
//!
//! - `cargo test --test knob_rest -- --nocapture`: the short grid (69 configurations of
//!   the issue's grid) in `f64`, `f32` and `I16F16`, printing the table;
//! - `cargo test --release --test knob_rest full_rest_sweep -- --ignored --nocapture`: the
//!   full grid (7,776 configurations), ignored for its run time;
//! - the targets the knob does not meet yet are ignored with their numbers in the
//!   reason (`cargo test --test knob_rest -- --ignored` runs them).
//!
//! The bounds, from the issue: at rest, on the frictionless rotor, at most 20 sign
//! reversals of the commanded torque per second and at most 2 % of the limit peak to
//! peak (over the runs at rest: within 8 counts peak to peak); on the rotor with
//! friction, cogging and ±1-count encoder noise, at most 20 reversals per second; no run
//! oscillating (more than 8 counts peak to peak with at least 4 reversals of the count);
//! after one bad encoder sample, |torque| above 0.2 of the limit for at most 3 periods.

use lab::knob::rest::{
    Case, ENDSTOPS, FULL, MAX_PEAK_TO_PEAK, MAX_REVERSALS_PER_S, RestRun, Rotor, RotorKind,
    Rounding, SECONDS, Setup, Sweep, periods_above, periods_apart, rest, run_with, short, start,
};
use std::f64::consts::{PI, TAU};
use stiffspring::knob::Latency;
use stiffspring::{I16F16, Knob, KnobConfig, Scalar};

/// The knob of a grid case: the detents' peak torque set in N·m, endstops at ±135° with
/// the first and last detent on them, or endless detents of the case's width.
fn config(c: &Case) -> KnobConfig {
    let latency = if c.latency == 1 {
        Latency::OneStep
    } else {
        Latency::SameStep
    };
    let base = KnobConfig::new(c.rate, c.inertia, c.limit, 1 << c.bits)
        .latency(latency)
        .damping_ratio(c.zeta);
    let base = if c.endstops {
        base.endstops(ENDSTOPS.0, ENDSTOPS.1)
            .detent_count(c.detents)
    } else {
        base.detent_width(c.width())
    };
    base.detent_torque(c.peak_torque())
}

/// The knob as the lab's law: encoder angle in, torque fraction out.
fn law<S: Scalar>(knob: &mut Knob<S>) -> impl FnMut(f64) -> f64 + '_ {
    |a| knob.update(S::from_f64(a)).torque.to_f64()
}

/// The rest sweep of `cases` in backend `S`: each configuration `S` accepts runs on the
/// three rotors from [`start`], for [`SECONDS`].
fn sweep<S: Scalar>(backend: &str, cases: &[Case]) -> Sweep {
    let mut out = Sweep {
        configs: cases.len(),
        ..Sweep::default()
    };
    for (i, c) in cases.iter().enumerate() {
        let config = config(c);
        let (theta0, omega0) = start(c);
        let mut accepted = false;
        for (kind, tally) in RotorKind::ALL.iter().zip(out.rotors.iter_mut()) {
            let setup = c.setup(*kind, i as u64);
            let reading = setup.rotor.encoder(c.bits, Rounding::Floor, 0).read(theta0);
            let Ok(mut knob) = Knob::<S>::new(&config, S::from_f64(reading)) else {
                break;
            };
            accepted = true;
            let r = rest(&setup, theta0, omega0, SECONDS, law(&mut knob));
            if r.oscillating() {
                println!("oscillating, {backend}, {}: {c:?}: {r:?}", kind.name());
            }
            tally.record(&r, || format!("{c:?}: {r:?}"));
        }
        if accepted {
            out.accepted += 1;
        }
    }
    out
}

fn print(backend: &str, s: &Sweep) {
    println!("{}", s.table(backend));
    println!("{}", s.worst());
}

/// What every backend does today and must keep doing: the torque within its limit, and
/// the knob accepting some of the grid.
fn assert_within_limit(backend: &str, s: &Sweep) {
    assert!(s.accepted > 0, "{backend}: nothing accepted");
    for (kind, t) in RotorKind::ALL.iter().zip(&s.rotors) {
        assert!(t.max_fraction <= 1.0, "{backend}, {}", kind.name());
    }
}

/// No run oscillating: more than 8 counts peak to peak with at least 4 reversals of the
/// count. Today's knob fails it on the frictionless rotor (10 counts at 16 bits, 10 kHz,
/// J 1e−6, ζ 0.2, no delay, 2 detents between the endstops).
fn assert_no_oscillation(backend: &str, s: &Sweep) {
    for (kind, t) in RotorKind::ALL.iter().zip(&s.rotors) {
        assert_eq!(t.oscillating, 0, "{backend}, {}", kind.name());
    }
}

/// The issue's targets on a sweep: no chatter on the frictionless rotor and no ripple in
/// its runs at rest, no chatter on the noisy one.
fn assert_silent(backend: &str, s: &Sweep) {
    let [free, _, noisy] = &s.rotors;
    assert_eq!(
        free.chatter, 0,
        "{backend}, frictionless: {:?}",
        free.worst_chatter
    );
    assert_eq!(
        free.ripple, 0,
        "{backend}, frictionless: {:?}",
        free.worst_ripple
    );
    assert_eq!(
        noisy.chatter, 0,
        "{backend}, noisy: {:?}",
        noisy.worst_chatter
    );
}

/// The short grid, printed, the torque within its limit (what the knob does today; its
/// torque still chatters in some configurations: see `short_rest_sweep_is_silent`,
/// ignored until it does not).
#[test]
fn short_rest_sweep_table() {
    let cases = short();
    let mut rows = Vec::new();
    for (name, s) in [
        ("f64", sweep::<f64>("f64", &cases)),
        ("f32", sweep::<f32>("f32", &cases)),
        ("I16F16", sweep::<I16F16>("I16F16", &cases)),
    ] {
        print(name, &s);
        assert_within_limit(name, &s);
        rows.extend(s.rows(name));
    }
    // docs/knob.md's table ("Silence at rest"), checked by scripts/check-figures.
    let path = lab::table::write_figures(
        "knob/rest-short.md",
        &lab::table::markdown(&Sweep::ROW_HEADER, &rows),
    );
    println!("wrote {}", path.display());
}

/// The issue's target on the short grid, in every backend. Not met yet (`f64`: 13 of 55
/// frictionless runs chatter, worst 480/s, a heavy overdamped rotor creeping down a wide
/// detent; 21 ripple above 2 %, worst 15.7 %, a 10-bit encoder with 7.7 counts per detent;
/// 8 noisy runs chatter, worst 222/s; none oscillates; docs/knob.md, "Silence at rest").
#[test]
#[ignore = "issue 17: not met yet, 13 of 55 frictionless runs chatter (docs/knob.md)"]
fn short_rest_sweep_is_silent() {
    let cases = short();
    for (name, s) in [
        ("f64", sweep::<f64>("f64", &cases)),
        ("f32", sweep::<f32>("f32", &cases)),
        ("I16F16", sweep::<I16F16>("I16F16", &cases)),
    ] {
        print(name, &s);
        assert_within_limit(name, &s);
        assert_no_oscillation(name, &s);
        assert_silent(name, &s);
    }
}

/// The full grid, in every backend, printed, then checked against the issue's targets
/// (which today's knob fails). Ignored for its run time:
/// `cargo test --release --test knob_rest full_rest_sweep -- --ignored --nocapture`.
#[test]
#[ignore = "minutes of run time; asserts the issue 17 targets"]
fn full_rest_sweep() {
    let cases = FULL.cases();
    let sweeps = [
        ("f64", sweep::<f64>("f64", &cases)),
        ("f32", sweep::<f32>("f32", &cases)),
        ("I16F16", sweep::<I16F16>("I16F16", &cases)),
    ];
    let mut rows = Vec::new();
    for (name, s) in &sweeps {
        print(name, s);
        rows.extend(s.rows(name));
    }
    // docs/knob.md's table of the full grid, checked by `scripts/check-figures --long`;
    // written before the assertions, which the knob does not meet yet.
    let path = lab::table::write_figures(
        "knob/rest-full.md",
        &lab::table::markdown(&Sweep::ROW_HEADER, &rows),
    );
    println!("wrote {}", path.display());
    for (name, s) in &sweeps {
        assert_within_limit(name, s);
        assert_no_oscillation(name, s);
        assert_silent(name, s);
    }
}

// The issue's knob: 4 kHz, J 1e−5 kg·m², 20 mN·m, 14 bits, 24 detents between endstops at
// ±135°, peak detent torque 10 mN·m, one period late (the default latency).

const RATE: f64 = 4_000.0;
const INERTIA: f64 = 1e-5;
const LIMIT: f64 = 0.02;
const BITS: u32 = 14;
const DETENTS: u32 = 24;

fn issue_knob(rate: f64) -> KnobConfig {
    KnobConfig::new(rate, INERTIA, LIMIT, 1 << BITS)
        .endstops(ENDSTOPS.0, ENDSTOPS.1)
        .detent_count(DETENTS)
        .detent_torque(0.01)
}

fn width() -> f64 {
    (ENDSTOPS.1 - ENDSTOPS.0) / f64::from(DETENTS - 1)
}

fn count() -> f64 {
    TAU / f64::from(1u32 << BITS)
}

/// The issue's knob released at `theta0` turning at `omega0` on `rotor`, read by a `rounding`
/// encoder, the torque `delay` periods late; 2 s, measured over the last 30 %.
fn issue_run<S: Scalar>(
    (theta0, omega0): (f64, f64),
    rotor: RotorKind,
    rounding: Rounding,
    delay: usize,
) -> RestRun {
    let setup = Setup {
        rate: RATE,
        inertia: INERTIA,
        limit: LIMIT,
        delay,
        bits: BITS,
        rounding,
        rotor,
        seed: 17,
    };
    let reading = rotor.encoder(BITS, rounding, 0).read(theta0);
    let mut knob = Knob::<S>::new(&issue_knob(RATE), S::from_f64(reading)).expect("accepted");
    rest(&setup, theta0, omega0, SECONDS, law(&mut knob))
}

/// One run of the issue's knob: the rotor, a description, and what the window measured.
struct IssueRun {
    rotor: RotorKind,
    what: String,
    run: RestRun,
}

impl IssueRun {
    /// Above a bound the issue sets: chatter on either rotor, ripple on the frictionless
    /// one, or not at rest.
    fn fails(&self) -> bool {
        self.run.chatters()
            || (self.rotor == RotorKind::Frictionless && self.run.ripples())
            || !self.run.at_rest()
    }
}

/// Every run of the issue's knob from `starts`: both rotors the issue bounds, both
/// encoders, with and without the period of delay, three backends.
fn issue_knob_runs(starts: &[(f64, f64, &str)]) -> Vec<IssueRun> {
    let mut runs = Vec::new();
    for &(theta0, omega0, name) in starts {
        let theta0 = (theta0, omega0);
        for rotor in [RotorKind::Frictionless, RotorKind::Noisy] {
            for rounding in [Rounding::Floor, Rounding::Nearest] {
                for delay in [1, 0] {
                    for (backend, r) in [
                        ("f64", issue_run::<f64>(theta0, rotor, rounding, delay)),
                        ("f32", issue_run::<f32>(theta0, rotor, rounding, delay)),
                        (
                            "I16F16",
                            issue_run::<I16F16>(theta0, rotor, rounding, delay),
                        ),
                    ] {
                        let what = format!(
                            "{name}, {}, {rounding:?}, delay {delay}, {backend}: {:.0} reversals/s, \
                             {:.2} % p-p, {} counts",
                            rotor.name(),
                            r.reversals_per_s,
                            100.0 * r.torque_pp,
                            r.position_pp
                        );
                        println!("{what}");
                        runs.push(IssueRun {
                            rotor,
                            what,
                            run: r,
                        });
                    }
                }
            }
        }
    }
    runs
}

/// The runs of [`issue_knob_runs`] above a bound.
fn issue_knob_failures(starts: &[(f64, f64, &str)]) -> Vec<String> {
    issue_knob_runs(starts)
        .into_iter()
        .filter(IssueRun::fails)
        .map(|r| r.what)
        .collect()
}

/// The starts on detent 16: flicked at 5 rad/s from 0.45 of a width below its centre (it
/// stays in detent 16), released 0.3 of a width off its centre, and half a count off it.
fn detent_16_starts() -> [(f64, f64, &'static str); 3] {
    let centre = ENDSTOPS.0 + 16.0 * width();
    [
        (
            centre - 0.45 * width(),
            5.0,
            "detent 16, flicked from 0.45 width below",
        ),
        (centre + 0.3 * width(), 0.0, "detent 16, 0.3 width off"),
        (centre + 0.5 * count(), 0.0, "detent 16, half a count off"),
    ]
}

/// The starts on the last detent, which is on the upper stop: flicked into the stop at
/// 5 rad/s from 0.45 of a width inside, released 0.3 of a width inside it, and 3 counts
/// beyond it.
fn last_detent_starts() -> [(f64, f64, &'static str); 3] {
    [
        (
            ENDSTOPS.1 - 0.45 * width(),
            5.0,
            "last detent, flicked into the stop",
        ),
        (
            ENDSTOPS.1 - 0.3 * width(),
            0.0,
            "last detent, 0.3 width inside",
        ),
        (
            ENDSTOPS.1 + 3.0 * count(),
            0.0,
            "last detent, 3 counts beyond",
        ),
    ]
}

/// The issue's knob on detent 16 ([`detent_16_starts`]).
#[test]
fn issue_knob_is_silent_on_detent_16() {
    let failures = issue_knob_failures(&detent_16_starts());
    assert!(
        failures.is_empty(),
        "{} runs above {MAX_REVERSALS_PER_S}/s or {MAX_PEAK_TO_PEAK} p-p:\n{}",
        failures.len(),
        failures.join("\n")
    );
}

/// docs/knob.md's table of the issue's knob ("Silence at rest"), checked by
/// scripts/check-figures: per detent and rotor, the worst reversals per second and peak
/// to peak over every start, encoder, delay and backend, and the runs above a bound.
#[test]
fn issue_knob_table() {
    let mut rows = Vec::new();
    for (detent, starts) in [
        ("16", detent_16_starts()),
        ("last, at the stop", last_detent_starts()),
    ] {
        let runs = issue_knob_runs(&starts);
        for rotor in [RotorKind::Frictionless, RotorKind::Noisy] {
            let of: Vec<&IssueRun> = runs.iter().filter(|r| r.rotor == rotor).collect();
            let worst = |f: fn(&RestRun) -> f64| of.iter().map(|r| f(&r.run)).fold(0.0, f64::max);
            let failing = of.iter().filter(|r| r.fails()).count();
            rows.push(vec![
                detent.to_string(),
                rotor.name().to_string(),
                of.len().to_string(),
                format!("{:.0}", worst(|r| r.reversals_per_s)),
                format!("{:.2} %", 100.0 * worst(|r| r.torque_pp)),
                failing.to_string(),
            ]);
        }
    }
    let header = [
        "detent",
        "rotor",
        "runs",
        "worst reversals/s",
        "worst peak to peak",
        "runs above a bound",
    ];
    let path =
        lab::table::write_figures("knob/issue-knob.md", &lab::table::markdown(&header, &rows));
    println!("wrote {}", path.display());
}

/// The issue's knob on its last detent ([`last_detent_starts`]).
///
/// Not met yet in 3 of 36 runs: a frictionless rotor creeping in the rest zone, whose
/// one-count damper pulses are 2.44 % of the limit peak to peak at 5–17 reversals/s.
#[test]
#[ignore = "issue 17: 3 of 36 frictionless runs at 2.44 % p-p (docs/knob.md)"]
fn issue_knob_is_silent_on_the_last_detent_at_the_stop() {
    let failures = issue_knob_failures(&last_detent_starts());
    assert!(
        failures.is_empty(),
        "{} runs above {MAX_REVERSALS_PER_S}/s or {MAX_PEAK_TO_PEAK} p-p:\n{}",
        failures.len(),
        failures.join("\n")
    );
}

// Bad encoder samples: one reading replaced, once, in a knob at rest and in one turning
// slowly. The issue's knob at 1, 4 and 10 kHz.
//
// - At rest: the frictionless rotor resting on the centre of detent 16 for 0.25 s, the
//   bad reading, then 1 s more: the periods from the bad one on in which |torque| > 0.2
//   of the limit (the rotor answers whatever the knob commands).
// - Turning slowly: a hand holds the rotor and turns it at 0.5 rad/s through the detents,
//   whatever the motor does (the readings are the encoder's of that ramp). The detents
//   themselves then command up to half the limit, so the measure is against a twin knob
//   given the same readings without the bad one: the periods in which the two torques
//   differ by more than 0.2 of the limit.

/// At most this many periods above 0.2 of the limit after one bad sample.
const MAX_BAD_PERIODS: usize = 3;
const BAD_BOUND: f64 = 0.2;

/// A bad reading: the healthy reading `a` in, what the knob is handed out (f64).
type Fault = fn(f64) -> f64;

/// `(periods at rest, periods turning)` above the bound, for `fault` in backend `S`
/// (`to_s` converts a reading, keeping NaN and ±∞ where `S` has them), at `rate`.
fn bad_sample<S: Scalar>(rate: f64, fault: Fault, to_s: fn(f64) -> S) -> (usize, usize) {
    let config = issue_knob(rate);
    let dt = 1.0 / rate;
    let k0 = (0.25 * rate) as usize;
    // At rest.
    let centre = ENDSTOPS.0 + 16.0 * width();
    let reading = (centre / count()).floor() * count();
    let mut knob = Knob::<S>::new(&config, S::from_f64(reading)).expect("accepted");
    let mut rotor = Rotor::new(INERTIA, dt, 1, centre, 0.0);
    let mut encoder = RotorKind::Frictionless.encoder(BITS, Rounding::Floor, 0);
    let mut trace = Vec::new();
    run_with(
        &mut rotor,
        &mut encoder,
        LIMIT,
        1.25,
        |k, a| if k == k0 { fault(a) } else { a },
        |a| knob.update(to_s(a)).torque.to_f64(),
        |_, t| trace.push(t),
    );
    let at_rest = periods_above(&trace, k0, BAD_BOUND);
    // Turning slowly, against the twin.
    let theta0 = ENDSTOPS.0 + 8.4 * width();
    let read = |k: usize| ((theta0 + 0.5 * k as f64 * dt) / count()).floor() * count();
    let mut faulty = Knob::<S>::new(&config, S::from_f64(read(0))).expect("accepted");
    let mut healthy = faulty.clone();
    let (mut f, mut h) = (Vec::new(), Vec::new());
    for k in 0..(1.25 * rate) as usize {
        let a = read(k);
        let bad = if k == k0 { fault(a) } else { a };
        f.push(faulty.update(to_s(bad)).torque.to_f64());
        h.push(healthy.update(to_s(a)).torque.to_f64());
    }
    (at_rest, periods_apart(&f, &h, k0, BAD_BOUND))
}

/// Runs `fault` at 1, 4 and 10 kHz in f64, in f32 (if `f32_too`) and in I16F16 (if
/// `fixed_too`: the reading converted saturating, as firmware in fixed point gets it),
/// and asserts the bound.
fn assert_bad_sample(name: &str, fault: Fault, f32_too: bool, fixed_too: bool) {
    let mut lines = Vec::new();
    let mut worst = 0;
    for rate in [1_000.0, 4_000.0, 10_000.0] {
        let mut runs = vec![("f64", bad_sample::<f64>(rate, fault, |a| a))];
        if f32_too {
            runs.push(("f32", bad_sample::<f32>(rate, fault, |a| a as f32)));
        }
        if fixed_too {
            runs.push((
                "I16F16",
                bad_sample::<I16F16>(rate, fault, I16F16::from_f64),
            ));
        }
        for (backend, (rest, turning)) in runs {
            worst = worst.max(rest).max(turning);
            lines.push(format!(
                "{name}, {rate} Hz, {backend}: {rest} periods at rest, {turning} turning"
            ));
        }
    }
    println!("{}", lines.join("\n"));
    assert!(
        worst <= MAX_BAD_PERIODS,
        "|torque| > {BAD_BOUND} of the limit for more than {MAX_BAD_PERIODS} periods:\n{}",
        lines.join("\n")
    );
}

#[test]
fn bad_sample_nan() {
    assert_bad_sample("NaN", |_| f64::NAN, true, false);
}

#[test]
fn bad_sample_positive_infinity() {
    assert_bad_sample("+inf", |_| f64::INFINITY, true, true);
}

#[test]
fn bad_sample_negative_infinity() {
    assert_bad_sample("-inf", |_| f64::NEG_INFINITY, true, true);
}

#[test]
fn bad_sample_1e30() {
    assert_bad_sample("1e30", |_| 1e30, true, true);
}

#[test]
fn bad_sample_1e300_in_f64() {
    assert_bad_sample("1e300", |_| 1e300, false, false);
}

#[test]
fn bad_sample_half_turn_jump() {
    assert_bad_sample("half a turn", |a| a + PI, true, true);
}

/// Passes today (one period above the bound): kept, so that the new law keeps it.
#[test]
fn bad_sample_64_count_jump() {
    assert_bad_sample("64 counts", |a| a + 64.0 * TAU / 16384.0, true, true);
}

// The sensor screen's events: `KnobConfig::max_speed`, `KnobOutput::events.sensor` with
// `SensorFault::{NotANumber, OutOfRange, Jump}`.
mod sensor_faults {
    use super::*;
    use stiffspring::knob::SensorFault;

    /// The maximum speed of these tests: 20 rad/s, so that a jump of 64 counts of a 14-bit
    /// encoder (24.5 mrad) is beyond `max_speed·dt` at every rate from 1 kHz (20 mrad).
    const MAX_SPEED: f64 = 20.0;

    fn knob<S: Scalar>(rate: f64, angle: f64) -> Knob<S> {
        Knob::<S>::new(&issue_knob(rate).max_speed(MAX_SPEED), S::from_f64(angle))
            .expect("accepted")
    }

    /// The events of `fault` injected once into a knob turning slowly (0.5 rad/s) at
    /// `rate`: the event of the faulty period, and the periods after it that still report
    /// a fault.
    fn events<S: Scalar>(
        rate: f64,
        fault: Fault,
        to_s: fn(f64) -> S,
    ) -> (Option<SensorFault>, usize) {
        let dt = 1.0 / rate;
        let theta0 = ENDSTOPS.0 + 8.4 * width();
        let read = |k: usize| ((theta0 + 0.5 * k as f64 * dt) / count()).floor() * count();
        let mut k = knob::<S>(rate, read(0));
        let k0 = (0.25 * rate) as usize;
        let (mut at, mut after) = (None, 0);
        for n in 0..(0.5 * rate) as usize {
            let a = if n == k0 { fault(read(n)) } else { read(n) };
            let out = k.update(to_s(a));
            if n < k0 {
                assert_eq!(out.events.sensor, None, "a healthy reading reported at {n}");
            } else if n == k0 {
                at = out.events.sensor;
            } else if out.events.sensor.is_some() {
                after += 1;
            }
        }
        (at, after)
    }

    fn check(fault: Fault, expect: fn(Option<SensorFault>) -> bool, name: &str) {
        for rate in [1_000.0, 4_000.0, 10_000.0] {
            for (backend, (at, after)) in [
                ("f64", events::<f64>(rate, fault, |a| a)),
                ("f32", events::<f32>(rate, fault, |a| a as f32)),
            ] {
                assert!(expect(at), "{name}, {rate} Hz, {backend}: {at:?}");
                assert!(
                    after <= MAX_BAD_PERIODS,
                    "{name}, {rate} Hz, {backend}: {after} more"
                );
            }
        }
    }

    #[test]
    fn nan_is_reported() {
        check(|_| f64::NAN, |e| e == Some(SensorFault::NotANumber), "NaN");
    }

    #[test]
    fn infinities_are_reported() {
        let bad = |e| matches!(e, Some(SensorFault::NotANumber | SensorFault::OutOfRange));
        check(|_| f64::INFINITY, bad, "+inf");
        check(|_| f64::NEG_INFINITY, bad, "-inf");
    }

    #[test]
    fn huge_readings_are_reported() {
        let bad = |e| matches!(e, Some(SensorFault::OutOfRange | SensorFault::Jump));
        check(|_| 1e30, bad, "1e30");
    }

    #[test]
    fn jumps_are_reported() {
        let jump = |e| e == Some(SensorFault::Jump);
        check(|a| a + PI, jump, "half a turn");
        check(|a| a + 64.0 * TAU / 16384.0, jump, "64 counts");
    }

    /// The bad-sample bound with the maximum speed set: the same as without, every fault.
    #[test]
    fn bad_samples_with_max_speed_hold_the_bound() {
        let faults: [(&str, Fault); 6] = [
            ("NaN", |_| f64::NAN),
            ("+inf", |_| f64::INFINITY),
            ("-inf", |_| f64::NEG_INFINITY),
            ("1e30", |_| 1e30),
            ("half a turn", |a| a + PI),
            ("64 counts", |a| a + 64.0 * TAU / 16384.0),
        ];
        for (name, fault) in faults {
            for rate in [1_000.0, 4_000.0, 10_000.0] {
                let dt = 1.0 / rate;
                let k0 = (0.25 * rate) as usize;
                let centre = ENDSTOPS.0 + 16.0 * width();
                let reading = (centre / count()).floor() * count();
                let mut k = knob::<f64>(rate, reading);
                let mut rotor = Rotor::new(INERTIA, dt, 1, centre, 0.0);
                let mut encoder = RotorKind::Frictionless.encoder(BITS, Rounding::Floor, 0);
                let mut trace = Vec::new();
                run_with(
                    &mut rotor,
                    &mut encoder,
                    LIMIT,
                    1.25,
                    |n, a| if n == k0 { fault(a) } else { a },
                    |a| k.update(a).torque,
                    |_, t| trace.push(t),
                );
                let n = periods_above(&trace, k0, BAD_BOUND);
                assert!(n <= MAX_BAD_PERIODS, "{name}, {rate} Hz: {n} periods");
            }
        }
    }

    /// Above the maximum speed the torque is cut: a hand turning the rotor at twice it
    /// (through the detents, which would otherwise command up to half the limit) gets at
    /// most 0.2 of the limit after the first 3 periods.
    #[test]
    fn torque_is_cut_above_max_speed() {
        for rate in [1_000.0, 4_000.0, 10_000.0] {
            let dt = 1.0 / rate;
            let theta0 = ENDSTOPS.0 + 8.4 * width();
            let read =
                |n: usize| ((theta0 + 2.0 * MAX_SPEED * n as f64 * dt) / count()).floor() * count();
            let mut k = knob::<f64>(rate, read(0));
            // 0.1 s at 40 rad/s: 4 rad, well inside the endstops from detent 8.
            for n in 0..(0.1 * rate) as usize {
                let t = k.update(read(n)).torque;
                assert!(n < 3 || t.abs() <= BAD_BOUND, "{rate} Hz, period {n}: {t}");
            }
        }
    }
}
