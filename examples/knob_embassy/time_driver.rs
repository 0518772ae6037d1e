//! An `embassy_time_driver::Driver` on the CMSDK timers of QEMU's MPS2 boards (ARM's
//! MPS2 documentation for the addresses, QEMU's `hw/arm/mps2.c` for the interrupt
//! numbers): both count down at 25 MHz and interrupt when they reach zero.
//!
//! - **TIMER0** (`0x4000_0000`, IRQ 8) runs free from `u32::MAX` and is the time base:
//!   its wrap interrupt, every 2³² ticks (171.8 s), adds 2³² ticks to a 64-bit count.
//!   It is also `firmware::timer`'s instruction counter, which sees it run exactly as
//!   `firmware::timer::start` would leave it.
//! - **TIMER1** (`0x4000_1000`, IRQ 9) is the alarm: loaded with the ticks from now to the
//!   next expiry of the timer queue, it interrupts when it reaches zero; the handler stops
//!   it, wakes what expired and loads the next expiry.
//!
//! Embassy counts 1 µs ticks (its default `TICK_HZ`), 25 timer ticks each. The 64-bit
//! count is kept as microseconds plus a remainder of timer ticks, so that neither `now`
//! nor the alarm divides a 64-bit number (which the Cortex-M4 does in a library call of
//! a few hundred instructions).

use core::cell::{Cell, RefCell};
use core::task::Waker;
use critical_section::{CriticalSection, Mutex};
use embassy_time_driver::Driver;
use embassy_time_queue_utils::Queue;

/// The time base's interrupt.
pub const TIMER0_IRQ: u16 = 8;
/// The alarm's interrupt.
pub const TIMER1_IRQ: u16 = 9;

const TIMER0: usize = 0x4000_0000;
const TIMER1: usize = 0x4000_1000;
/// Register offsets: control (bit 0 enable, bit 3 interrupt enable), current value,
/// reload value, interrupt status (read) and clear (write 1).
const CTRL: usize = 0x0;
const VALUE: usize = 0x4;
const RELOAD: usize = 0x8;
const INT: usize = 0xC;
const ENABLE: u32 = 1;
const IRQ_ENABLE: u32 = 8;

/// Timer ticks per embassy tick: 25 MHz over 1 MHz.
const TICKS_PER_US: u32 = 25;
/// A wrap of TIMER0, 2³² ticks, as whole microseconds and the remaining ticks.
const WRAP_US: u64 = (1u64 << 32) / TICKS_PER_US as u64;
const WRAP_REM: u32 = ((1u64 << 32) % TICKS_PER_US as u64) as u32;

// The tick rate this driver counts in.
const _: () = assert!(embassy_time_driver::TICK_HZ == 1_000_000);

fn read(timer: usize, offset: usize) -> u32 {
    // SAFETY: the MPS2 boards map the CMSDK timers' registers at TIMER0 and TIMER1; a read
    // has no side effect.
    unsafe { ((timer + offset) as *const u32).read_volatile() }
}

fn write(timer: usize, offset: usize, value: u32) {
    // SAFETY: as in `read`; only this driver writes the timers' registers (after `start`,
    // `firmware::timer` only reads TIMER0's value).
    unsafe { ((timer + offset) as *mut u32).write_volatile(value) }
}

/// The wraps of TIMER0 handled so far: their time as whole microseconds and the ticks
/// left over (below 25).
#[derive(Clone, Copy)]
struct Wraps {
    us: u64,
    rem: u32,
}

impl Wraps {
    /// The next wrap.
    fn next(self) -> Self {
        let rem = self.rem + WRAP_REM;
        if rem >= TICKS_PER_US {
            Wraps {
                us: self.us + WRAP_US + 1,
                rem: rem - TICKS_PER_US,
            }
        } else {
            Wraps {
                us: self.us + WRAP_US,
                rem,
            }
        }
    }
}

/// The driver: TIMER0's handled wraps and the timer queue.
pub struct Mps2Timer {
    wraps: Mutex<Cell<Wraps>>,
    queue: Mutex<RefCell<Queue>>,
}

embassy_time_driver::time_driver_impl!(static DRIVER: Mps2Timer = Mps2Timer {
    wraps: Mutex::new(Cell::new(Wraps { us: 0, rem: 0 })),
    queue: Mutex::new(RefCell::new(Queue::new())),
});

/// Starts TIMER0 from `u32::MAX` with its wrap interrupt, and stops TIMER1. Call once,
/// before the first `now` and before the NVIC unmasks either interrupt.
pub fn start() {
    write(TIMER1, CTRL, 0);
    write(TIMER1, INT, 1);
    write(TIMER0, CTRL, 0);
    write(TIMER0, RELOAD, u32::MAX);
    write(TIMER0, VALUE, u32::MAX);
    write(TIMER0, INT, 1);
    write(TIMER0, CTRL, ENABLE | IRQ_ENABLE);
}

/// TIMER0's wrap interrupt (IRQ 8): count the wrap.
pub fn on_wrap() {
    // The status is set when the count reaches zero, one tick before it reloads: wait for
    // the reload (at most 40 ns), so that `now` never counts a wrap twice.
    while read(TIMER0, VALUE) == 0 {}
    critical_section::with(|cs| {
        let wraps = DRIVER.wraps.borrow(cs);
        wraps.set(wraps.get().next());
        write(TIMER0, INT, 1);
    });
}

/// TIMER1's interrupt (IRQ 9): the alarm. Wakes what expired and arms the next expiry.
pub fn on_alarm() {
    critical_section::with(|cs| {
        write(TIMER1, CTRL, 0);
        write(TIMER1, INT, 1);
        DRIVER.arm_next(cs);
    });
}

impl Mps2Timer {
    /// The time since `start`, as whole microseconds and the ticks left over.
    fn time(&self, cs: CriticalSection) -> (u64, u32) {
        let mut wraps = self.wraps.borrow(cs).get();
        let mut value = read(TIMER0, VALUE);
        if read(TIMER0, INT) & 1 != 0 {
            // TIMER0 reached zero and its interrupt waits (masked here): a value read now
            // tells whether it reloaded yet.
            value = read(TIMER0, VALUE);
            if value != 0 {
                wraps = wraps.next();
            }
        }
        let elapsed = u32::MAX - value;
        // `rem + elapsed % 25 < 50`: no 64-bit division.
        let low = wraps.rem + elapsed % TICKS_PER_US;
        let us = wraps.us + u64::from(elapsed / TICKS_PER_US) + u64::from(low / TICKS_PER_US);
        (us, low % TICKS_PER_US)
    }

    /// Loads TIMER1 to interrupt at `at` (µs); false when `at` is not in the future.
    /// `u64::MAX` (nothing queued) stops it.
    fn set_alarm(&self, cs: CriticalSection, at: u64) -> bool {
        if at == u64::MAX {
            write(TIMER1, CTRL, 0);
            return true;
        }
        let (us, rem) = self.time(cs);
        if at <= us {
            return false;
        }
        // The ticks to `at`, at most a whole count of TIMER1: a later expiry is re-armed
        // when this one fires and finds nothing due.
        let ticks = (at - us)
            .saturating_mul(u64::from(TICKS_PER_US))
            .saturating_sub(u64::from(rem))
            .min(u64::from(u32::MAX)) as u32;
        write(TIMER1, CTRL, 0);
        write(TIMER1, INT, 1);
        write(TIMER1, RELOAD, ticks);
        write(TIMER1, VALUE, ticks);
        write(TIMER1, CTRL, ENABLE | IRQ_ENABLE);
        true
    }

    /// Wakes what expired and arms the next expiry.
    fn arm_next(&self, cs: CriticalSection) {
        let mut queue = self.queue.borrow(cs).borrow_mut();
        let mut next = queue.next_expiration(self.time(cs).0);
        while !self.set_alarm(cs, next) {
            next = queue.next_expiration(self.time(cs).0);
        }
    }
}

impl Driver for Mps2Timer {
    fn now(&self) -> u64 {
        critical_section::with(|cs| self.time(cs).0)
    }

    fn schedule_wake(&self, at: u64, waker: &Waker) {
        critical_section::with(|cs| {
            let changed = self.queue.borrow(cs).borrow_mut().schedule_wake(at, waker);
            if changed {
                self.arm_next(cs);
            }
        });
    }
}
