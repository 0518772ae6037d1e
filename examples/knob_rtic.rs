//! The knob run as a product runs it: an RTIC 2 application on the Cortex-M4F whose
//! 10 kHz timer interrupt (SysTick) reads the encoder, calls [`Knob::update`] and writes
//! the torque to the motor, tick by tick; a simulated rotor stands in for the motor, the
//! knob and the hand. Logs go out through defmt and are decoded on the host.
//!
//! ```text
//! cargo run --release --example knob_rtic        # host: the same periods from a loop
//! STIFFSPRING_QEMU_ARGS="-icount shift=7,align=off,sleep=off" \
//!   cargo run --release --target thumbv7em-none-eabihf --example knob_rtic
//! ```
//!
//! # The application
//!
//! - `init` sets up the knob (10 kHz, 1e−5 kg·m², 50 mN·m, a 14-bit encoder, one period of
//!   delay, 24 detents of 20 mN·m peak between endstops at ±135°, the last detent on each
//!   stop), the simulated rotor, and SysTick at 10 kHz of the 25 MHz processor clock.
//! - The SysTick task (priority 1) reads the encoder's count register, calls
//!   `Knob::update` in `f32`, writes the torque to the motor's register, then advances the
//!   simulated rotor by one period and queues the events (a detent change, an endstop hit)
//!   for `idle`.
//! - `idle` logs the events through defmt and, at the end, the summary and the checks; the
//!   firmware exits with failure when one fails.
//!
//! The simulated world is plain code here, not the library: a rotor whose angle is kept as
//! whole encoder counts plus an `f32` fraction (the encoder reads the whole counts), under
//! the motor's torque, which acts from the next period (the current loop takes it at its
//! next update), and a hand (a stiff spring-damper, as a finger is) that turns the knob up
//! through its detents, pushes it into the upper endstop, holds it on the last detent and
//! lets go there (issue 13's "released on the last detent"), then flicks it down and lets
//! go. Each period is integrated exactly for the torques held over it.
//!
//! # The interrupt's cost
//!
//! Under QEMU with `-icount shift=7` every instruction advances the virtual clock by
//! 128 ns, and the CMSDK TIMER0 of `mps2-an386` ticks every 40 ns, so the instructions
//! between two reads of the timer are `round(40·Δticks/128)` exactly (the two readings are
//! each within a tick, 0.3 of an instruction, of the true time). `init` measures the
//! nanoseconds per instruction on a block of 4,096 `nop`s; when it is a power of two from
//! 128 up, the interrupt counts its instructions on every tick:
//!
//! - **control**: reading the encoder, `Knob::update`, writing the torque (what a product's
//!   interrupt does), less the two timer reads' own instructions;
//! - **interrupt**: the whole task body, the simulated rotor and the bookkeeping included.
//!
//! Their mean and maximum are checked against the golden values below (within 5 %). At
//! `shift=7` the emulated core runs 7.8 M instructions per second, so a 10 kHz period is
//! 781 instructions, and the interrupt must never miss a tick. Without `-icount` the costs
//! are not measured (the timer then runs in real time).
//!
//! On the host, and on the Cortex-M0 (`thumbv6m-none-eabi`, where this example has no
//! RTIC: its backend is per architecture, and issue 13 asks for the M4F), the same periods
//! run from a plain loop, with the same checks and no cost.
#![cfg_attr(target_os = "none", no_std, no_main)]

firmware::output!(defmt);

use core::sync::atomic::{AtomicI32, AtomicU32, Ordering};
use stiffspring::knob::Endstop;
use stiffspring::{Knob, KnobOutput};

/// The scene: the knob, the rotor and the hand's script.
#[allow(dead_code)]
mod scene {
    use core::f64::consts::TAU;
    use stiffspring::KnobConfig;
    use stiffspring::knob::Latency;

    /// The control loop's rate, Hz.
    pub const RATE: f64 = 10_000.0;
    /// The control period, s.
    pub const DT: f32 = 1e-4;
    /// The rotor and knob cap, kg·m².
    pub const INERTIA: f32 = 1e-5;
    /// The motor's torque limit, N·m.
    pub const LIMIT: f32 = 0.05;
    /// The encoder's counts per turn (14 bits).
    pub const COUNTS_PER_TURN: u32 = 16384;
    /// One count, rad.
    pub const COUNT: f32 = (TAU / 16384.0) as f32;
    /// The endstops: ±135°.
    pub const LO: f64 = -0.375 * TAU;
    /// See [`LO`].
    pub const HI: f64 = 0.375 * TAU;
    /// Detents over the range, the first and the last on the stops.
    pub const DETENTS: u32 = 24;
    /// A detent's width, rad.
    pub const WIDTH: f64 = (HI - LO) / (DETENTS - 1) as f64;
    /// A detent's peak torque, N·m.
    pub const DETENT_TORQUE: f64 = 0.02;
    /// The upper stop in whole encoder counts.
    pub const STOP_COUNTS: i32 = (HI / (TAU / 16384.0)) as i32;
    /// The detent the rotor starts on.
    pub const START_DETENT: i32 = 12;
    /// Periods in the scene: 2.6 s.
    pub const TICKS: u32 = 26_000;

    /// The knob.
    pub fn config() -> KnobConfig {
        KnobConfig::new(RATE, INERTIA as f64, LIMIT as f64, COUNTS_PER_TURN)
            .latency(Latency::OneStep)
            .endstops(LO, HI)
            .detent_count(DETENTS)
            .detent_torque(DETENT_TORQUE)
    }

    /// The angle of detent `i`'s centre, rad.
    pub fn centre(i: i32) -> f64 {
        LO + i as f64 * WIDTH
    }

    /// The hand's phases, by period.
    pub const PUSH_FROM: u32 = 9_000;
    pub const HOLD_FROM: u32 = 10_500;
    pub const RELEASED_AT_STOP: u32 = 13_000;
    pub const GRAB: u32 = 18_000;
    pub const FLICK_RELEASE: u32 = 19_000;

    /// Where the finger pulls the knob in period `n`, if it touches it: up through the
    /// detents into the upper stop (0.15 rad past it), back onto the last detent (on the
    /// stop) and held there; let go; grabbed there and flicked 2 rad down in 10 ms, let go
    /// while it moves fast.
    pub fn hand_target(n: u32) -> Option<f32> {
        let start = centre(START_DETENT) as f32;
        let (hi, t) = (HI as f32, n as f32 * DT);
        match n {
            n if n < PUSH_FROM => Some(start + (hi + 0.15 - start) * t / 0.9),
            n if n < HOLD_FROM => Some(hi + 0.15),
            n if n < RELEASED_AT_STOP => Some(hi),
            n if n < GRAB => None,
            n if n < FLICK_RELEASE => Some(hi - 2.0 * (t - 1.8) / 0.1),
            _ => None,
        }
    }
}

use scene::{COUNT, DT, INERTIA, LIMIT};

/// The encoder's count register, written by the simulated rotor.
static ENCODER: AtomicI32 = AtomicI32::new(0);
/// The motor's torque register: a fraction of the limit, as `f32` bits.
static MOTOR: AtomicU32 = AtomicU32::new(0);

/// The simulated rotor: plain code, not the library.
struct Rotor {
    /// The angle in whole encoder counts (what the encoder reads) and the fraction of a
    /// count on top, in `[0, 1)`.
    counts: i32,
    fraction: f32,
    /// Angular velocity, counts per second.
    velocity: f32,
    /// The motor torque acting over this period (the previous command), fraction of the
    /// limit.
    acting: f32,
}

impl Rotor {
    /// At rest at `angle` (rad).
    fn new(angle: f32) -> Self {
        let counts = angle / COUNT;
        let whole = floor(counts);
        Rotor {
            counts: whole,
            fraction: counts - whole as f32,
            velocity: 0.0,
            acting: 0.0,
        }
    }

    /// The angle, rad.
    fn angle(&self) -> f32 {
        (self.counts as f32 + self.fraction) * COUNT
    }

    /// One period of period `n`: the previous command and the hand act, held over the
    /// period; `command` acts from the next one.
    fn period(&mut self, n: u32, command: f32) {
        let hand = match scene::hand_target(n) {
            // 1 N·m/rad and 10 mN·m·s/rad: a firm grip.
            Some(target) => -(self.angle() - target) - 0.01 * self.velocity * COUNT,
            None => 0.0,
        };
        let torque = self.acting * LIMIT + hand;
        self.acting = command;
        let acceleration = torque / (INERTIA * COUNT);
        let step = self.velocity * DT + 0.5 * acceleration * DT * DT;
        self.velocity += acceleration * DT;
        self.fraction += step;
        let carry = floor(self.fraction);
        self.counts += carry;
        self.fraction -= carry as f32;
    }
}

/// `floor` to an integer, without `std`.
fn floor(x: f32) -> i32 {
    let t = x as i32;
    if (t as f32) > x { t - 1 } else { t }
}

/// What the interrupt reports to `idle`.
#[derive(Clone, Copy)]
enum Event {
    Detent {
        tick: u32,
        detent: i32,
    },
    Endstop {
        tick: u32,
        max: bool,
    },
    /// The interrupt's costs, sent before [`Event::Finished`] (the firmware only).
    #[cfg_attr(not(all(target_os = "none", target_abi = "eabihf")), allow(dead_code))]
    Costs(Cost),
    Finished(Summary),
}

/// The interrupt's costs, in instructions, when QEMU counts them (`shift` is `Some`).
#[derive(Clone, Copy, Default)]
#[cfg_attr(not(all(target_os = "none", target_abi = "eabihf")), allow(dead_code))]
struct Cost {
    /// `-icount shift`: `2^shift` ns per instruction.
    shift: Option<u32>,
    ticks: u32,
    control_sum: u64,
    control_max: u32,
    interrupt_sum: u64,
    interrupt_max: u32,
    /// Ticks lost: an interrupt that came two periods or more after the previous one
    /// (SysTick's pending flag holds one tick, so a later start is jitter, not a loss;
    /// the longest gap reports the jitter).
    missed: u32,
    /// The longest gap between two interrupts, in timer ticks (2,500 at 10 kHz).
    longest_gap: u32,
    /// The period of the first missed tick.
    first_miss: u32,
}

/// What the run measured, for the checks.
#[derive(Clone, Copy, Default)]
struct Summary {
    /// The highest detent reached before the flick.
    top_detent: i32,
    /// Endstop hits on the way up and pushed into the stop.
    hits_pushed: u32,
    /// Detent changes and endstop hits after the release on the last detent.
    changes_released: u32,
    hits_released: u32,
    /// Peak to peak of the counts over the last 0.2 s before the grab, and their distance
    /// from the stop.
    swing_released: i32,
    off_stop_released: i32,
    /// The same over the last 0.2 s of the run, and where it ended.
    swing_end: i32,
    final_counts: i32,
    final_detent: i32,
    final_torque: f32,
    /// Events the queue could not take.
    dropped: u32,
}

/// The scene's bookkeeping around the knob: the rotor, the tick, the summary.
struct Sim {
    knob: Knob<f32>,
    rotor: Rotor,
    tick: u32,
    summary: Summary,
    window: (i32, i32),
}

impl Sim {
    fn new() -> Option<Self> {
        let start = scene::centre(scene::START_DETENT) as f32;
        let rotor = Rotor::new(start);
        ENCODER.store(rotor.counts, Ordering::Relaxed);
        let knob = Knob::<f32>::new(&scene::config(), rotor.counts as f32 * COUNT).ok()?;
        Some(Sim {
            knob,
            rotor,
            tick: 0,
            summary: Summary {
                top_detent: scene::START_DETENT,
                ..Summary::default()
            },
            window: (i32::MAX, i32::MIN),
        })
    }

    /// The product's part of a period: read the encoder, update the knob, command the
    /// torque. Never inlined, so that the code between the interrupt's two timer reads is
    /// exactly this call (the compiler may not move its work across the call).
    #[inline(never)]
    fn control(&mut self) -> KnobOutput<f32> {
        let counts = ENCODER.load(Ordering::Relaxed);
        let out = self.knob.update(counts as f32 * COUNT);
        MOTOR.store(out.torque.to_bits(), Ordering::Relaxed);
        out
    }

    /// The rest of the period: the world moves, the events are noted. Returns the events
    /// to log (a detent change, an endstop hit) and whether the scene is over.
    fn world(&mut self, out: &KnobOutput<f32>, mut log: impl FnMut(Event)) -> bool {
        let n = self.tick;
        let command = f32::from_bits(MOTOR.load(Ordering::Relaxed));
        self.rotor.period(n, command);
        ENCODER.store(self.rotor.counts, Ordering::Relaxed);

        let s = &mut self.summary;
        if out.events.detent_step != 0 {
            log(Event::Detent {
                tick: n,
                detent: out.detent,
            });
            if n < scene::GRAB {
                s.top_detent = s.top_detent.max(out.detent);
            }
            if (scene::RELEASED_AT_STOP..scene::GRAB).contains(&n) {
                s.changes_released += 1;
            }
        }
        if let Some(which) = out.events.endstop_hit {
            log(Event::Endstop {
                tick: n,
                max: which == Endstop::Max,
            });
            if n < scene::RELEASED_AT_STOP {
                s.hits_pushed += 1;
            }
            if (scene::RELEASED_AT_STOP..scene::GRAB).contains(&n) {
                s.hits_released += 1;
            }
        }
        // The last 0.2 s before the grab and of the run.
        let c = self.rotor.counts;
        let last = |end: u32| n + 2_000 >= end && n < end;
        if last(scene::GRAB) || last(scene::TICKS) {
            self.window = (self.window.0.min(c), self.window.1.max(c));
        }
        if n + 1 == scene::GRAB {
            s.swing_released = self.window.1 - self.window.0;
            s.off_stop_released = (c - scene::STOP_COUNTS).abs();
            self.window = (i32::MAX, i32::MIN);
        }
        self.tick += 1;
        if self.tick < scene::TICKS {
            return false;
        }
        s.swing_end = self.window.1 - self.window.0;
        s.final_detent = out.detent;
        s.final_counts = c;
        s.final_torque = command;
        true
    }
}

/// Logs an event; false when the run failed a check.
fn report(event: &Event) -> bool {
    match *event {
        Event::Detent { tick, detent } => {
            say!("t = {} ms: detent {}", tick / 10, detent);
            true
        }
        Event::Endstop { tick, max } => {
            say!(
                "t = {} ms: {} endstop",
                tick / 10,
                if max { "upper" } else { "lower" }
            );
            true
        }
        Event::Costs(_) => true,
        Event::Finished(s) => check(&s),
    }
}

/// The checks of the scene.
fn check(s: &Summary) -> bool {
    let centre = (scene::centre(s.final_detent) / f64::from(COUNT)) as i32;
    let off_centre_end = (s.final_counts - centre).abs();
    say!(
        "turned up to detent {} (of {}), {} endstop hit on the way and pushed",
        s.top_detent,
        scene::DETENTS - 1,
        s.hits_pushed
    );
    say!(
        "released on the last detent: {} detent changes, {} endstop hits in 0.5 s; at rest {} counts from the stop, swinging {} counts",
        s.changes_released,
        s.hits_released,
        s.off_stop_released,
        s.swing_released
    );
    say!(
        "flicked: ended in detent {}, {} counts from its centre, swinging {} counts, torque {} of the limit",
        s.final_detent,
        off_centre_end,
        s.swing_end,
        s.final_torque
    );
    let last = scene::DETENTS as i32 - 1;
    use firmware::scenes::knob_rest::{OFFSET as REST_OFFSET, SWING as REST_SWING};
    let checks = [
        ("turned up to the last detent", s.top_detent == last),
        (
            "the push into the stop hit the endstop once",
            s.hits_pushed == 1,
        ),
        (
            "released on the last detent, it stays there",
            s.changes_released == 0 && s.hits_released <= 1,
        ),
        (
            "at rest on the stop",
            s.swing_released <= REST_SWING && s.off_stop_released <= REST_OFFSET,
        ),
        (
            "the flick ends at rest in a lower detent",
            s.final_detent < last && s.swing_end <= REST_SWING && off_centre_end <= REST_OFFSET,
        ),
        ("no event lost", s.dropped == 0),
    ];
    let mut ok = true;
    for (what, passed) in checks {
        if !passed {
            say!("FAILED: {}", what);
            ok = false;
        }
    }
    ok
}

// ---------------------------------------------------------------------------------------
// The host and the Cortex-M0: the same periods from a loop, no interrupt, no cost.
// ---------------------------------------------------------------------------------------

/// Runs the scene's periods from a loop and checks it; false when a check fails.
#[cfg(any(not(target_os = "none"), not(target_abi = "eabihf")))]
fn run_loop() -> bool {
    say!(
        "knob_rtic on {}: the interrupt's periods from a loop (RTIC runs on the Cortex-M4F)",
        firmware::MACHINE
    );
    let Some(mut sim) = Sim::new() else {
        say!("the configuration was rejected");
        return false;
    };
    let mut ok = true;
    loop {
        let out = sim.control();
        let mut events: [Option<Event>; 4] = [None; 4];
        let mut k = 0;
        let done = sim.world(&out, |e| {
            if k < events.len() {
                events[k] = Some(e);
                k += 1;
            }
        });
        for e in events.iter().flatten() {
            ok &= report(e);
        }
        if done {
            return ok & report(&Event::Finished(sim.summary));
        }
    }
}

#[cfg(not(target_os = "none"))]
fn main() -> std::process::ExitCode {
    if run_loop() {
        std::process::ExitCode::SUCCESS
    } else {
        std::process::ExitCode::FAILURE
    }
}

#[cfg(all(target_os = "none", not(target_abi = "eabihf")))]
firmware::entry!(run_loop);

// ---------------------------------------------------------------------------------------
// The Cortex-M4F: the RTIC application.
// ---------------------------------------------------------------------------------------

// The runtime (vector table, reset handler, `link.x`), which RTIC's `main` runs on; a
// device crate would link it otherwise.
#[cfg(all(target_os = "none", target_abi = "eabihf"))]
use cortex_m_rt as _;

/// What RTIC needs of a device crate, for an application whose only interrupt is the
/// core's SysTick: the NVIC's priority bits (three on the Cortex-M4 of the MPS2 AN386) and
/// an (empty) list of device interrupts.
#[cfg(all(target_os = "none", target_abi = "eabihf"))]
mod mps2 {
    /// Priority bits of the NVIC.
    pub const NVIC_PRIO_BITS: u8 = 3;
    /// The device's interrupts: none used.
    #[derive(Clone, Copy)]
    #[allow(dead_code)]
    pub enum Interrupt {}
    // SAFETY: an enum without variants has no number to be wrong.
    unsafe impl cortex_m::interrupt::InterruptNumber for Interrupt {
        fn number(self) -> u16 {
            match self {}
        }
    }
    /// The device's interrupt handlers: none.
    pub mod interrupt {}
}

#[cfg(all(target_os = "none", target_abi = "eabihf"))]
use firmware::timer;

/// The golden costs on QEMU `mps2-an386` with `-icount shift=7`: mean (thousandths of an
/// instruction) and most, of the control part and of the whole interrupt. Measured by
/// this example; a change in the library or the compiler that moves one by more than 5 %
/// fails the run, and the new figures are then copied here (and into `docs/knob.md`).
#[cfg(all(target_os = "none", target_abi = "eabihf"))]
mod golden {
    pub const CONTROL_MEAN_MILLI: u64 = 151_014;
    pub const CONTROL_MAX: u32 = 287;
    pub const INTERRUPT_MEAN_MILLI: u64 = 260_993;
    pub const INTERRUPT_MAX: u32 = 427;
}

/// Prints a figure (thousandths of an instruction) against its golden value; false when
/// it is more than 5 % off.
#[cfg(all(target_os = "none", target_abi = "eabihf"))]
fn against_golden(what: &str, milli: u64, golden: u64) -> bool {
    let ok = milli * 100 <= golden * 105 && milli * 100 >= golden * 95;
    say!(
        "{}: {}.{}{}{} instructions (golden {}.{}{}{}){}",
        what,
        milli / 1000,
        milli / 100 % 10,
        milli / 10 % 10,
        milli % 10,
        golden / 1000,
        golden / 100 % 10,
        golden / 10 % 10,
        golden % 10,
        if ok { "" } else { " -- more than 5 % off" }
    );
    ok
}

/// Reports the interrupt's costs and checks them; false when one fails.
#[cfg(all(target_os = "none", target_abi = "eabihf"))]
fn costs(c: &Cost) -> bool {
    let Some(shift) = c.shift else {
        say!("the interrupt's cost was not measured (no -icount)");
        return true;
    };
    let period = 100_000u32 >> shift;
    say!(
        "{} interrupts; longest gap between two {} us, {} ticks missed",
        c.ticks,
        c.longest_gap / 25,
        c.missed
    );
    let mut ok = c.missed == 0 && c.ticks == scene::TICKS;
    if !ok {
        say!(
            "FAILED: the interrupt missed ticks of the 10 kHz timer (a period is {} instructions at shift={}; the figures are for shift=7)",
            period,
            shift
        );
    }
    let n = u64::from(c.ticks.max(1));
    ok &= against_golden(
        "control (encoder, Knob::update, motor), mean",
        c.control_sum * 1000 / n,
        golden::CONTROL_MEAN_MILLI,
    );
    ok &= against_golden(
        "control, most",
        u64::from(c.control_max) * 1000,
        u64::from(golden::CONTROL_MAX) * 1000,
    );
    ok &= against_golden(
        "whole interrupt (with the simulated rotor), mean",
        c.interrupt_sum * 1000 / n,
        golden::INTERRUPT_MEAN_MILLI,
    );
    ok &= against_golden(
        "whole interrupt, most",
        u64::from(c.interrupt_max) * 1000,
        u64::from(golden::INTERRUPT_MAX) * 1000,
    );
    say!(
        "the whole interrupt at its most takes {} % of the {}-instruction period",
        c.interrupt_max * 100 / period,
        period
    );
    ok
}

#[cfg(all(target_os = "none", target_abi = "eabihf"))]
#[rtic::app(device = crate::mps2, peripherals = false)]
mod app {
    use super::{Cost, Event, Sim, timer};
    use cortex_m::peripheral::syst::SystClkSource;
    use heapless::spsc::{Consumer, Producer, Queue};

    /// SysTick's reload for 10 kHz of the 25 MHz processor clock.
    const RELOAD: u32 = 25_000_000 / 10_000 - 1;

    #[shared]
    struct Shared {}

    #[local]
    struct Local {
        sim: Sim,
        events: Producer<'static, Event>,
        log: Consumer<'static, Event>,
        cost: Cost,
        last_entry: Option<u32>,
        overhead: u32,
        spin: bool,
    }

    #[init(local = [queue: Queue<Event, 64> = Queue::new()])]
    fn init(cx: init::Context) -> (Shared, Local) {
        timer::start();
        let shift = timer::icount_shift();
        // The two timer reads' own instructions, subtracted from the control part.
        let (a, b) = (timer::now(), timer::now());
        let overhead = shift.map_or(0, |s| timer::instructions(a.wrapping_sub(b), s));
        say!(
            "knob_rtic on {}: RTIC, SysTick at 10 kHz, 24 detents between endstops at ±135°, f32",
            firmware::MACHINE
        );
        match shift {
            Some(s) => say!(
                "QEMU -icount shift={}: {} ns per instruction, {} instructions per 10 kHz period",
                s,
                1u32 << s,
                100_000u32 >> s
            ),
            None => {
                say!("not under QEMU -icount shift=7..12: the interrupt's cost is not measured")
            }
        }
        let Some(sim) = Sim::new() else {
            say!("the configuration was rejected");
            semihosting::process::exit(1)
        };
        let (events, log) = cx.local.queue.split();
        let mut syst = cx.core.SYST;
        syst.set_clock_source(SystClkSource::Core);
        syst.set_reload(RELOAD);
        syst.clear_current();
        syst.enable_interrupt();
        syst.enable_counter();
        (
            Shared {},
            Local {
                sim,
                events,
                log,
                cost: Cost {
                    shift,
                    ..Cost::default()
                },
                last_entry: None,
                overhead,
                spin: shift.is_some(),
            },
        )
    }

    /// One control period.
    #[task(binds = SysTick, priority = 1, local = [sim, events, cost, last_entry, overhead])]
    fn control(cx: control::Context) {
        let t0 = timer::now();
        let sim = cx.local.sim;
        if sim.tick >= super::scene::TICKS {
            return;
        }
        let out = sim.control();
        let t1 = timer::now();
        let events = cx.local.events;
        let mut dropped = 0;
        let done = sim.world(&out, |e| {
            if events.enqueue(e).is_err() {
                dropped += 1;
            }
        });
        sim.summary.dropped += dropped;
        let cost = cx.local.cost;
        if let Some(previous) = cx.local.last_entry.replace(t0) {
            let gap = previous.wrapping_sub(t0);

            cost.longest_gap = cost.longest_gap.max(gap);
            if gap >= (RELOAD + 1) * 2 {
                if cost.missed == 0 {
                    cost.first_miss = sim.tick;
                }
                cost.missed += 1;
            }
        }
        let t2 = timer::now();
        if let Some(s) = cost.shift {
            let control = timer::instructions(t0.wrapping_sub(t1), s) - *cx.local.overhead;
            let interrupt = timer::instructions(t0.wrapping_sub(t2), s);
            cost.ticks += 1;
            cost.control_sum += u64::from(control);
            cost.control_max = cost.control_max.max(control);
            cost.interrupt_sum += u64::from(interrupt);
            cost.interrupt_max = cost.interrupt_max.max(interrupt);
        }
        if done {
            // Room was kept: at most a few events per period, drained every period.
            let _ = events.enqueue(Event::Costs(*cost));
            let _ = events.enqueue(Event::Finished(sim.summary));
        }
    }

    /// Logs the events. Under QEMU's `-icount sleep=off` a `wfi` here sleeps through the
    /// next SysTick (measured: every interrupt then came 200 µs after the previous one),
    /// so `idle` spins there; elsewhere it sleeps until the next interrupt, as a product's
    /// does.
    #[idle(local = [log, spin])]
    fn idle(cx: idle::Context) -> ! {
        let mut ok = true;
        let mut costs = None;
        loop {
            while let Some(event) = cx.local.log.dequeue() {
                ok &= super::report(&event);
                match event {
                    Event::Costs(c) => costs = Some(c),
                    Event::Finished(_) => {
                        ok &= costs.is_some_and(|c| super::costs(&c));
                        semihosting::process::exit(if ok { 0 } else { 1 });
                    }
                    _ => {}
                }
            }
            if !*cx.local.spin {
                cortex_m::asm::wfi();
            }
        }
    }
}
