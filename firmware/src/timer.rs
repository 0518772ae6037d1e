//! The CMSDK TIMER0 of QEMU's MPS2 boards, free-running at 25 MHz (40 ns a tick) and
//! counting down: the instruction counter of `examples/cost.rs` and `examples/knob_rtic.rs`.
//! QEMU does not implement the DWT cycle counter, but with `-icount shift=S` one
//! instruction is `2^S` ns of virtual time, so the timer counts instructions exactly
//! (ARM's MPS2 documentation for the address, QEMU's for `-icount`).

const CTRL: *mut u32 = 0x4000_0000 as *mut u32;
const VALUE: *mut u32 = 0x4000_0004 as *mut u32;
const RELOAD: *mut u32 = 0x4000_0008 as *mut u32;

/// Starts the timer counting down from `u32::MAX`.
pub fn start() {
    // SAFETY: the MPS2 boards map TIMER0's registers here; nothing else uses them.
    unsafe {
        RELOAD.write_volatile(u32::MAX);
        VALUE.write_volatile(u32::MAX);
        CTRL.write_volatile(1);
    }
}

/// The current count (it counts down).
#[inline(always)]
pub fn now() -> u32 {
    // SAFETY: as in `start`; a read has no side effect.
    unsafe { VALUE.read_volatile() }
}

/// Instructions in `ticks` at `2^shift` ns per instruction, rounded to nearest (exact for
/// `shift ≥ 7`, where an instruction is at least 3.2 ticks).
#[inline(always)]
pub fn instructions(ticks: u32, shift: u32) -> u32 {
    ((ticks as u64 * 40 + (1 << (shift - 1))) >> shift) as u32
}

/// 4,096 `nop`s.
#[inline(always)]
fn nops() {
    // SAFETY: no operands, no memory, no stack.
    unsafe {
        core::arch::asm!(
            ".rept 4096",
            "nop",
            ".endr",
            options(nomem, nostack, preserves_flags)
        );
    }
}

/// The virtual nanoseconds per instruction as a power of two, `2^shift` with `shift ≥ 7`,
/// when QEMU runs with `-icount shift=…`: the ticks of 4,096 `nop`s more, times 40 ns,
/// over 4,096. `None` otherwise (real time, or a shift whose readings do not give exact
/// instruction counts).
pub fn icount_shift() -> Option<u32> {
    let a = now();
    nops();
    let b = now();
    nops();
    nops();
    let c = now();
    let once = a.wrapping_sub(b) as i64;
    let twice = b.wrapping_sub(c) as i64;
    let ns = (twice - once) as f32 * 40.0 / 4096.0;
    (7..=12).find(|&s| {
        let expected = (1u32 << s) as f32;
        (ns - expected).abs() < 0.01 * expected
    })
}
