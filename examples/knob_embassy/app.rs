//! The embassy application on the Cortex-M4F: the executors, the knob and UI tasks, the
//! interrupt handlers and the instruction counts.

use super::time_driver;
use super::{Event, Sim, Summary, Ui, check, scene};
use core::sync::atomic::{AtomicBool, AtomicU32, Ordering};
use cortex_m::interrupt::InterruptNumber;
use cortex_m::peripheral::NVIC;
use embassy_executor::{Executor, InterruptExecutor, Spawner};
use embassy_sync::blocking_mutex::raw::CriticalSectionRawMutex;
use embassy_sync::channel::Channel;
use embassy_sync::signal::Signal;
use embassy_time::{Duration, Ticker};
use firmware::timer;

/// The interrupt the knob's executor runs in: the dual timer's, which nothing starts.
const EXECUTOR_IRQ: u16 = 10;
/// The NVIC priority of the three interrupts (the top three bits count on the AN386):
/// one level, so that none preempts another and the knob's poll is never cut by the UI's
/// alarm; all preempt thread mode, where the UI runs.
const PRIORITY: u8 = 0x20;

/// A device interrupt by number (no device crate describes the MPS2 AN386 here).
#[derive(Clone, Copy)]
struct Irq(u16);

// SAFETY: the numbers used are the MPS2 AN386's interrupts 8, 9 and 10 (of its 32).
unsafe impl InterruptNumber for Irq {
    fn number(self) -> u16 {
        self.0
    }
}

/// The knob's executor.
static KNOB_EXECUTOR: InterruptExecutor = InterruptExecutor::new();
/// The knob's events, to the UI. Room for a flick's worth of detents between two frames.
static EVENTS: Channel<CriticalSectionRawMutex, Event, 32> = Channel::new();
/// The knob's summary and costs, once, at the end.
static DONE: Signal<CriticalSectionRawMutex, (Summary, Cost)> = Signal::new();

/// Timer readings shared between the interrupt handlers and the knob task: the last
/// alarm interrupt's entry and their count, and the task's reading before it awaits.
static ALARM_ENTRY: AtomicU32 = AtomicU32::new(0);
static ALARMS: AtomicU32 = AtomicU32::new(0);
static BEFORE_AWAIT: AtomicU32 = AtomicU32::new(0);
static AWAITING: AtomicBool = AtomicBool::new(false);
/// The sleep counts (instructions), summed in the executor's interrupt after each poll.
static SLEEP_SUM: AtomicU32 = AtomicU32::new(0);
static SLEEP_MAX: AtomicU32 = AtomicU32::new(0);
static SLEEPS: AtomicU32 = AtomicU32::new(0);
/// `-icount shift`, 0 when not counting; and the two timer reads' own instructions.
static SHIFT: AtomicU32 = AtomicU32::new(0);
static READ_PAIR: AtomicU32 = AtomicU32::new(0);

/// Instructions from reading `from` to reading `to` (the timer counts down), less the
/// reads' own.
fn between(from: u32, to: u32, shift: u32) -> u32 {
    timer::instructions(from.wrapping_sub(to), shift)
        .saturating_sub(READ_PAIR.load(Ordering::Relaxed))
}

/// Without a device crate, cortex-m-rt sends every device interrupt here.
#[cortex_m_rt::exception]
unsafe fn DefaultHandler(irqn: i16) {
    match irqn {
        9 => {
            ALARM_ENTRY.store(timer::now(), Ordering::Relaxed);
            ALARMS.fetch_add(1, Ordering::Relaxed);
            time_driver::on_alarm();
        }
        10 => {
            // SAFETY: this is the executor's interrupt, and `main` started it before
            // unmasking it.
            unsafe { KNOB_EXECUTOR.on_interrupt() };
            let end = timer::now();
            let shift = SHIFT.load(Ordering::Relaxed);
            if shift != 0 && AWAITING.swap(false, Ordering::Relaxed) {
                let sleep = between(BEFORE_AWAIT.load(Ordering::Relaxed), end, shift);
                SLEEP_SUM.fetch_add(sleep, Ordering::Relaxed);
                SLEEP_MAX.fetch_max(sleep, Ordering::Relaxed);
                SLEEPS.fetch_add(1, Ordering::Relaxed);
            }
        }
        8 => time_driver::on_wrap(),
        _ => {
            say!("unexpected interrupt {}", irqn);
            semihosting::process::exit(1)
        }
    }
}

/// The knob task's counts, in instructions (`shift` is 0 when QEMU does not count).
#[derive(Clone, Copy, Default)]
pub struct Cost {
    shift: u32,
    periods: u32,
    /// Periods woken by an alarm (the others found their instant past).
    woken: u32,
    wake_sum: u32,
    wake_max: u32,
    wake_min: u32,
    control_sum: u32,
    control_max: u32,
    task_sum: u32,
    task_max: u32,
    /// Periods that came more than 1.5 periods after the previous one, and the longest
    /// gap, in timer ticks (6,250 at 4 kHz).
    missed: u32,
    longest_gap: u32,
}

/// The knob: 4 kHz from a ticker, the events into the channel.
#[embassy_executor::task]
async fn knob(mut sim: Sim) {
    let shift = SHIFT.load(Ordering::Relaxed);
    let mut cost = Cost {
        shift,
        wake_min: u32::MAX,
        ..Cost::default()
    };
    let mut ticker = Ticker::every(Duration::from_hz(u64::from(scene::RATE)));
    let mut alarms = ALARMS.load(Ordering::Relaxed);
    let mut previous = None;
    loop {
        BEFORE_AWAIT.store(timer::now(), Ordering::Relaxed);
        AWAITING.store(true, Ordering::Relaxed);
        ticker.next().await;
        let t0 = timer::now();
        let out = sim.control();
        let t1 = timer::now();
        let done = sim.world(&out, |e| EVENTS.try_send(e).is_ok());
        let t2 = timer::now();

        let alarm = ALARMS.load(Ordering::Relaxed);
        let woken = alarm != alarms;
        alarms = alarm;
        if let Some(p) = previous.replace(t0) {
            let gap: u32 = p.wrapping_sub(t0);
            cost.longest_gap = cost.longest_gap.max(gap);
            if gap > 25 * scene::PERIOD_US as u32 * 3 / 2 {
                cost.missed += 1;
            }
        }
        cost.periods += 1;
        if shift != 0 {
            let control = between(t0, t1, shift);
            let task = between(t0, t2, shift);
            cost.control_sum += control;
            cost.control_max = cost.control_max.max(control);
            cost.task_sum += task;
            cost.task_max = cost.task_max.max(task);
            if woken {
                let wake = between(ALARM_ENTRY.load(Ordering::Relaxed), t0, shift);
                cost.woken += 1;
                cost.wake_sum += wake;
                cost.wake_max = cost.wake_max.max(wake);
                cost.wake_min = cost.wake_min.min(wake);
            }
        }
        if done {
            DONE.signal((sim.summary, cost));
            return;
        }
    }
}

/// The UI: 60 Hz from a ticker, the list springing to the knob's detent.
#[embassy_executor::task]
async fn ui(mut ui: Ui, reference: Summary) {
    let mut ticker = Ticker::every(Duration::from_hz(u64::from(scene::FRAME_RATE)));
    let mut done: Option<(Summary, Cost)> = None;
    loop {
        ticker.next().await;
        if done.is_none() {
            // The summary is signalled after the last event is sent: drain after taking it.
            done = DONE.try_take();
        }
        while let Ok(e) = EVENTS.try_receive() {
            ui.event(e);
        }
        let moving = ui.frame();
        if let Some((summary, cost)) = done {
            if !moving {
                let ok = check(&summary, &reference, &ui) & costs(&cost);
                semihosting::process::exit(if ok { 0 } else { 1 });
            }
            ui.frames_after += 1;
        }
    }
}

/// The golden counts on QEMU `mps2-an386` with `-icount shift=7`, thousandths of an
/// instruction: the executor's mean wake and sleep per knob period. Measured by this
/// example; a change in embassy, the driver or the compiler that moves one by more than
/// 5 % fails the run, and the new figures are then copied here (and into docs/firmware.md).
mod golden {
    pub const WAKE_MEAN_MILLI: u64 = 320_505;
    pub const SLEEP_MEAN_MILLI: u64 = 263_135;
}

/// `milli` thousandths as `a.bcd`.
fn milli_parts(milli: u64) -> (u64, u64, u64, u64) {
    (milli / 1000, milli / 100 % 10, milli / 10 % 10, milli % 10)
}

/// Prints a figure (thousandths of an instruction) against its golden value; false when
/// it is more than 5 % off.
fn against_golden(what: &str, milli: u64, golden: u64) -> bool {
    let ok = milli * 100 <= golden * 105 && milli * 100 >= golden * 95;
    let (a, b, c, d) = milli_parts(milli);
    let (e, f, g, h) = milli_parts(golden);
    say!(
        "{}: {}.{}{}{} instructions (golden {}.{}{}{}){}",
        what,
        a,
        b,
        c,
        d,
        e,
        f,
        g,
        h,
        if ok { "" } else { " -- more than 5 % off" }
    );
    ok
}

/// Mean in thousandths.
fn mean_milli(sum: u32, n: u32) -> u64 {
    if n == 0 {
        0
    } else {
        u64::from(sum) * 1000 / u64::from(n)
    }
}

/// Reports the knob task's counts and checks them; false when one fails.
fn costs(c: &Cost) -> bool {
    say!(
        "{} knob periods; longest gap between two {} us, {} missed",
        c.periods,
        c.longest_gap / 25,
        c.missed
    );
    let mut ok = c.periods == scene::TICKS;
    if c.shift == 0 {
        say!("the executor's cost was not measured (no -icount)");
        return ok;
    }
    if c.missed != 0 {
        say!("FAILED: the knob missed periods of its 4 kHz ticker");
        ok = false;
    }
    let sleeps = SLEEPS.load(Ordering::Relaxed);
    let (sleep_sum, sleep_max) = (
        SLEEP_SUM.load(Ordering::Relaxed),
        SLEEP_MAX.load(Ordering::Relaxed),
    );
    let wake = mean_milli(c.wake_sum, c.woken);
    let sleep = mean_milli(sleep_sum, sleeps);
    say!(
        "per period ({} of {} woken by the alarm): wake most {}, least {}; sleep most {}; control most {}; task most {}",
        c.woken,
        c.periods,
        c.wake_max,
        c.wake_min,
        sleep_max,
        c.control_max,
        c.task_max
    );
    let (a, b, cc, d) = milli_parts(mean_milli(c.control_sum, c.periods));
    say!(
        "control (encoder, Knob::update, torque): {}.{}{}{} instructions",
        a,
        b,
        cc,
        d
    );
    let (a, b, cc, d) = milli_parts(mean_milli(c.task_sum, c.periods));
    say!(
        "the knob task's body (control, rotor, channel): {}.{}{}{} instructions",
        a,
        b,
        cc,
        d
    );
    let (a, b, cc, d) = milli_parts(wake + sleep);
    say!(
        "the executor per knob period, wake + sleep: {}.{}{}{} instructions of the {} in a period",
        a,
        b,
        cc,
        d,
        (100_000u32 * 25 / 10) >> c.shift
    );
    ok &= c.woken == c.periods;
    ok &= against_golden(
        "executor wake (alarm to task)",
        wake,
        golden::WAKE_MEAN_MILLI,
    );
    ok &= against_golden(
        "executor sleep (await to the poll's end)",
        sleep,
        golden::SLEEP_MEAN_MILLI,
    );
    ok
}

/// The whole scene from a plain loop, its events dropped: the reference of the run.
fn plain_loop(mut sim: Sim) -> Summary {
    loop {
        let out = sim.control();
        if sim.world(&out, |_| true) {
            return sim.summary;
        }
    }
}

#[cortex_m_rt::entry]
fn main() -> ! {
    time_driver::start();
    let shift = timer::icount_shift();
    let (a, b) = (timer::now(), timer::now());
    if let Some(s) = shift {
        READ_PAIR.store(timer::instructions(a.wrapping_sub(b), s), Ordering::Relaxed);
        SHIFT.store(s, Ordering::Relaxed);
    }
    say!(
        "knob_embassy on {}: the knob at 4 kHz on an interrupt executor, the UI at 60 Hz in thread mode, f32",
        firmware::MACHINE
    );
    match shift {
        Some(s) => say!(
            "QEMU -icount shift={}: {} ns per instruction, {} instructions per 4 kHz period",
            s,
            1u32 << s,
            250_000u32 >> s
        ),
        None => say!("not under QEMU -icount shift=7..12: the executor's cost is not measured"),
    }
    // The reference: the same periods from a plain loop (its events go nowhere). A new
    // `Sim` sets the encoder and the motor back to the start.
    let Some(reference) = Sim::new().map(plain_loop) else {
        say!("the configuration was rejected");
        semihosting::process::exit(1)
    };
    let (Some(sim), Some(list)) = (Sim::new(), Ui::new()) else {
        semihosting::process::exit(1)
    };

    // SAFETY: before any of the three interrupts is unmasked, as `InterruptExecutor::start`
    // requires; nothing else owns the NVIC.
    let mut core = unsafe { cortex_m::Peripherals::steal() };
    unsafe {
        core.NVIC
            .set_priority(Irq(time_driver::TIMER0_IRQ), PRIORITY);
        core.NVIC
            .set_priority(Irq(time_driver::TIMER1_IRQ), PRIORITY);
        core.NVIC.set_priority(Irq(EXECUTOR_IRQ), PRIORITY);
        NVIC::unmask(Irq(time_driver::TIMER0_IRQ));
        NVIC::unmask(Irq(time_driver::TIMER1_IRQ));
    }
    let knob_spawner = KNOB_EXECUTOR.start(Irq(EXECUTOR_IRQ));
    match knob(sim) {
        Ok(token) => knob_spawner.spawn(token),
        Err(_) => semihosting::process::exit(1),
    }
    let Some(executor) = cortex_m::singleton!(: Executor = Executor::new()) else {
        semihosting::process::exit(1)
    };
    executor.run(|spawner: Spawner| match ui(list, reference) {
        Ok(token) => spawner.spawn(token),
        Err(_) => semihosting::process::exit(1),
    })
}
