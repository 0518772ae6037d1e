//! The knob and the UI together under embassy: on the Cortex-M4F the knob runs in one task
//! at 4 kHz (an embassy `Ticker`, on an interrupt executor), the UI animates a list in
//! another at 60 Hz (a `SpringValue`, on the thread executor), and the knob's detent steps
//! reach the UI through an embassy-sync `Channel`. The time driver is the example's own,
//! on the CMSDK timers of QEMU's `mps2-an386`; logs go out through defmt and are decoded
//! on the host.
//!
//! ```text
//! cargo run --release --example knob_embassy        # host: the same periods from a loop
//! STIFFSPRING_QEMU_ARGS="-icount shift=7,align=off,sleep=off" \
//!   cargo run --release --target thumbv7em-none-eabihf --example knob_embassy
//! ```
//!
//! # The application
//!
//! - `main` starts the time driver, runs the scene once as a plain loop (the reference the
//!   executor's run must equal, bit for bit), then starts an `InterruptExecutor` on IRQ 10
//!   (the dual timer's, which nothing else uses) and the thread-mode `Executor`.
//! - The **knob task** (interrupt executor, so it preempts the UI) waits on a 4 kHz
//!   `Ticker`, reads the encoder's count register, calls `Knob::update` in `f32`, writes
//!   the torque to the motor's register, advances the simulated rotor by one period and
//!   `try_send`s the events (a detent change, an endstop hit) into the channel; it never
//!   waits on the UI. At the end it hands the summary and its costs to the UI through a
//!   `Signal`.
//! - The **UI task** (thread mode) waits on a 60 Hz `Ticker`; each frame it drains the
//!   channel, logs the events through defmt, moves the list's target to the knob's detent
//!   (one 24 px row per detent) and steps the list's spring (SwiftUI's `smooth`, sampled
//!   exactly at 60 Hz). After the knob's summary it animates until the list rests,
//!   checks the run and exits.
//!
//! The simulated rotor and hand are plain code, not the library, as in
//! `examples/knob_rtic.rs`, at 4 kHz: the hand turns the knob up through its 24 detents,
//! pushes it into the upper endstop, holds it on the last detent and lets go there, then
//! flicks it down and lets go.
//!
//! # The time driver
//!
//! `embassy_time_driver::Driver` on two CMSDK timers of the MPS2 board (25 MHz, counting
//! down): TIMER0 runs free from `u32::MAX` and is the time base (its wrap interrupt, IRQ
//! 8, extends it to 64 bits); TIMER1 is the alarm, loaded with the ticks to the next
//! expiry of the timer queue (`embassy-time-queue-utils`, the executor's integrated
//! queue) and stopped by its interrupt, IRQ 9. Embassy's tick is 1 µs (25 timer ticks).
//! Without a device crate, cortex-m-rt sends every device interrupt to `DefaultHandler`,
//! which dispatches on the interrupt number. TIMER0 is also the instruction counter of
//! `firmware::timer`: it runs exactly as that module's `start` would leave it.
//!
//! # What the executor adds per knob period
//!
//! Under QEMU `-icount shift=7` an instruction is 128 ns of virtual time and the timer
//! counts instructions exactly (see `firmware::timer`). Per period the example counts:
//!
//! - **wake**: from the alarm interrupt's first timer read to the knob task's first
//!   instruction after `ticker.next().await` (the driver's alarm, the timer queue, waking
//!   the task, re-arming the alarm, the executor's interrupt and its poll);
//! - **sleep**: from the task's last instruction before `ticker.next().await` to the end
//!   of the executor's poll (the ticker's `schedule_wake`, the timer queue, the alarm);
//! - **control**: reading the encoder, `Knob::update`, writing the torque;
//! - **task**: the task's whole body, the simulated rotor and the channel included.
//!
//! The executor's part, wake + sleep, is checked against golden values (within 5 %), and
//! no period may come more than 1.5 periods after the previous one. At `shift=7` a 4 kHz
//! period is 1,953 instructions. Without `-icount` nothing is counted.
//!
//! On the host, and on the Cortex-M0 (`thumbv6m-none-eabi`, where this example has no
//! embassy), the same knob periods and UI frames run from a loop, with the same checks and
//! the same lines; `.ci/firmware` compares the event lines and the digest of every
//! torque between the host and the Cortex-M4F.
#![cfg_attr(target_os = "none", no_std, no_main)]

firmware::output!(defmt);

use core::sync::atomic::{AtomicI32, AtomicU32, Ordering};
use stiffspring::knob::Endstop;
use stiffspring::{Knob, KnobOutput, Motion, RestThreshold, SpringValue, Tuning, presets, tuning};

/// The scene: the knob, the rotor, the hand's script and the list.
#[allow(dead_code)]
mod scene {
    use core::f64::consts::TAU;
    use stiffspring::KnobConfig;
    use stiffspring::knob::Latency;

    /// The knob task's rate, Hz.
    pub const RATE: u32 = 4_000;
    /// The control period, s.
    pub const DT: f32 = 1.0 / RATE as f32;
    /// The UI's frame rate, Hz.
    pub const FRAME_RATE: u32 = 60;
    /// A frame as embassy's 1 µs ticks count it (`Duration::from_hz(60)`), µs.
    pub const FRAME_US: u64 = 1_000_000 / FRAME_RATE as u64;
    /// A knob period, µs.
    pub const PERIOD_US: u64 = 1_000_000 / RATE as u64;
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
    pub const TICKS: u32 = 26 * RATE / 10;
    /// The list's row per detent, px.
    pub const ROW: f32 = 24.0;

    /// The knob.
    pub fn config() -> KnobConfig {
        KnobConfig::new(RATE as f64, INERTIA as f64, LIMIT as f64, COUNTS_PER_TURN)
            .latency(Latency::OneStep)
            .endstops(LO, HI)
            .detent_count(DETENTS)
            .detent_torque(DETENT_TORQUE)
    }

    /// The angle of detent `i`'s centre, rad.
    pub fn centre(i: i32) -> f64 {
        LO + i as f64 * WIDTH
    }

    /// The hand's phases, by period (0.9 s, 1.05 s, 1.3 s, 1.8 s, 1.9 s).
    pub const PUSH_FROM: u32 = 9 * RATE / 10;
    pub const HOLD_FROM: u32 = 105 * RATE / 100;
    pub const RELEASED_AT_STOP: u32 = 13 * RATE / 10;
    pub const GRAB: u32 = 18 * RATE / 10;
    pub const FLICK_RELEASE: u32 = 19 * RATE / 10;
    /// 0.2 s of periods: the windows over which the rest is judged.
    pub const WINDOW: u32 = RATE / 5;

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

/// One step of the FNV-1a hash of 32-bit words, for the digest of the run.
fn fnv(hash: u32, word: u32) -> u32 {
    (hash ^ word).wrapping_mul(16_777_619)
}

/// What the knob tells the UI.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Event {
    /// The knob moved to `detent` in period `tick`.
    Detent { tick: u32, detent: i32 },
    /// The rotor went past an endstop in period `tick`.
    Endstop { tick: u32, max: bool },
}

/// What the run measured, for the checks.
#[derive(Clone, Copy, Default, PartialEq, Eq)]
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
    /// The last torque command, as `f32` bits.
    final_torque: u32,
    /// Detent changes sent to the UI, and events the channel could not take.
    detent_events: u32,
    dropped: u32,
    /// The FNV-1a digest of every torque command's bits and every event.
    digest: u32,
}

/// The knob task's state: the knob, the rotor, the tick, the summary.
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
        MOTOR.store(0, Ordering::Relaxed);
        let knob = Knob::<f32>::new(&scene::config(), rotor.counts as f32 * COUNT).ok()?;
        Some(Sim {
            knob,
            rotor,
            tick: 0,
            summary: Summary {
                top_detent: scene::START_DETENT,
                digest: 0x811c_9dc5,
                ..Summary::default()
            },
            window: (i32::MAX, i32::MIN),
        })
    }

    /// The product's part of a period: read the encoder, update the knob, command the
    /// torque. Never inlined, so that the code between the task's two timer reads is
    /// exactly this call.
    #[inline(never)]
    fn control(&mut self) -> KnobOutput<f32> {
        let counts = ENCODER.load(Ordering::Relaxed);
        let out = self.knob.update(counts as f32 * COUNT);
        MOTOR.store(out.torque.to_bits(), Ordering::Relaxed);
        out
    }

    /// The rest of the period: the world moves, the events go to `send` (which returns
    /// false when it could not take one). Returns whether the scene is over.
    fn world(&mut self, out: &KnobOutput<f32>, mut send: impl FnMut(Event) -> bool) -> bool {
        let n = self.tick;
        let command = f32::from_bits(MOTOR.load(Ordering::Relaxed));
        self.rotor.period(n, command);
        ENCODER.store(self.rotor.counts, Ordering::Relaxed);

        let s = &mut self.summary;
        s.digest = fnv(s.digest, command.to_bits());
        let mut emit = |s: &mut Summary, e: Event, word: u32| {
            s.digest = fnv(fnv(s.digest, n), word);
            if !send(e) {
                s.dropped += 1;
            }
        };
        if out.events.detent_step != 0 {
            s.detent_events += 1;
            emit(
                s,
                Event::Detent {
                    tick: n,
                    detent: out.detent,
                },
                out.detent as u32,
            );
            if n < scene::GRAB {
                s.top_detent = s.top_detent.max(out.detent);
            }
            if (scene::RELEASED_AT_STOP..scene::GRAB).contains(&n) {
                s.changes_released += 1;
            }
        }
        if let Some(which) = out.events.endstop_hit {
            let max = which == Endstop::Max;
            emit(s, Event::Endstop { tick: n, max }, 0x8000_0000 | max as u32);
            if n < scene::RELEASED_AT_STOP {
                s.hits_pushed += 1;
            }
            if (scene::RELEASED_AT_STOP..scene::GRAB).contains(&n) {
                s.hits_released += 1;
            }
        }
        // The last 0.2 s before the grab and of the run.
        let c = self.rotor.counts;
        let last = |end: u32| n + scene::WINDOW >= end && n < end;
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
        s.final_torque = command.to_bits();
        true
    }
}

/// SwiftUI's `smooth` spring (0.5 s, no bounce), sampled exactly at 60 Hz.
const LIST_SPRING: Tuning =
    tuning!(presets::swiftui::SMOOTH.tuning(1.0 / scene::FRAME_RATE as f64));

/// The UI: a list whose scroll offset springs to the knob's detent, one row per detent.
struct Ui {
    list: SpringValue<f32, 1>,
    /// The detent the list is heading to.
    detent: i32,
    /// Detent changes received, frames drawn, and frames after the knob's summary.
    received: u32,
    frames: u32,
    frames_after: u32,
}

impl Ui {
    fn new() -> Option<Self> {
        let start = [scene::START_DETENT as f32 * scene::ROW];
        let list = SpringValue::new(start, &LIST_SPRING)
            .ok()?
            .with_rest_threshold(RestThreshold::PIXELS);
        Some(Ui {
            list,
            detent: scene::START_DETENT,
            received: 0,
            frames: 0,
            frames_after: 0,
        })
    }

    /// One event from the knob: logged, and a detent moves the list's target.
    fn event(&mut self, event: Event) {
        match event {
            Event::Detent { tick, detent } => {
                say!("t = {} ms: detent {}", tick / (scene::RATE / 1000), detent);
                self.received += 1;
                self.detent = detent;
                self.list.set_target([detent as f32 * scene::ROW]);
            }
            Event::Endstop { tick, max } => {
                say!(
                    "t = {} ms: {} endstop",
                    tick / (scene::RATE / 1000),
                    if max { "upper" } else { "lower" }
                );
            }
        }
    }

    /// One frame: the list's spring steps (the display would redraw when it moves).
    /// Returns false once the list rests.
    fn frame(&mut self) -> bool {
        self.frames += 1;
        self.list.step() == Motion::Moving
    }
}

/// Logs the run's end and checks it against the scene and the reference; false when a
/// check fails.
fn check(s: &Summary, reference: &Summary, ui: &Ui) -> bool {
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
        f32::from_bits(s.final_torque)
    );
    say!(
        "torques and events: {} periods, {} detent changes, digest {}",
        scene::TICKS,
        s.detent_events,
        s.digest
    );
    let row = ui.list.position()[0];
    say!(
        "UI: {} detent changes received, the list rests at {} px (detent {}) {} frames after the knob's last period",
        ui.received,
        row,
        ui.detent,
        ui.frames_after
    );
    let last = scene::DETENTS as i32 - 1;
    use firmware::scenes::knob_rest::{OFFSET as REST_OFFSET, SWING as REST_SWING};
    let checks = [
        (
            "the same run as the plain loop's, bit for bit",
            s == reference,
        ),
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
        (
            "every detent change reached the UI",
            ui.received == s.detent_events && ui.detent == s.final_detent,
        ),
        (
            "the list rests exactly on the final detent's row within 1 s",
            row == s.final_detent as f32 * scene::ROW && ui.frames_after <= scene::FRAME_RATE,
        ),
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
// The host and the Cortex-M0: the knob periods and the UI frames from a loop.
// ---------------------------------------------------------------------------------------

/// Runs the knob's periods and the UI's frames from a loop, each at its instant (knob
/// period `n` at `(n + 1)·250 µs`, frame `k` at `(k + 1)·16,666 µs`, as the two tickers
/// count), and checks the run; false when a check fails.
#[cfg(any(not(target_os = "none"), not(target_abi = "eabihf")))]
fn run_loop() -> bool {
    say!(
        "knob_embassy on {}: the knob's 4 kHz periods and the UI's 60 Hz frames from a loop (embassy runs on the Cortex-M4F)",
        firmware::MACHINE
    );
    let (Some(mut sim), Some(mut ui)) = (Sim::new(), Ui::new()) else {
        say!("the configuration was rejected");
        return false;
    };
    let mut pending: [Option<Event>; 16] = [None; 16];
    let mut queued = 0;
    let mut next_frame = scene::FRAME_US;
    let summary = loop {
        let now = u64::from(sim.tick + 1) * scene::PERIOD_US;
        let out = sim.control();
        let done = sim.world(&out, |e| {
            if queued < pending.len() {
                pending[queued] = Some(e);
                queued += 1;
                true
            } else {
                false
            }
        });
        if done {
            break sim.summary;
        }
        if now + scene::PERIOD_US > next_frame {
            for e in pending[..queued].iter_mut() {
                if let Some(e) = e.take() {
                    ui.event(e);
                }
            }
            queued = 0;
            next_frame += scene::FRAME_US;
            ui.frame();
        }
    };
    for e in pending[..queued].iter().flatten() {
        ui.event(*e);
    }
    while ui.frame() {
        ui.frames_after += 1;
    }
    check(&summary, &summary, &ui)
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
// The Cortex-M4F: the embassy application.
// ---------------------------------------------------------------------------------------

/// The time driver on the MPS2 board's CMSDK timers.
#[cfg(all(target_os = "none", target_abi = "eabihf"))]
mod time_driver;

/// The executors, the two tasks and the interrupt handlers.
#[cfg(all(target_os = "none", target_abi = "eabihf"))]
mod app;
