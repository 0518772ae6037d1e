//! What the examples that run both on the host and on a microcontroller share: the
//! skeleton below, the [`scenes`] they play and the [`golden`] values they check against;
//! and, on the host only, the simulated display the starter examples draw on
//! (`display`). `no_std`; on the target the library is its only dependency.
//!
//! An example is one file with the same scene code for both: a std `main` on the host,
//! and a `#![no_std]`, `#![no_main]` cortex-m-rt firmware on `thumbv7em-none-eabihf`
//! (QEMU `mps2-an386`, Cortex-M4F) and `thumbv6m-none-eabi` (QEMU `microbit`,
//! Cortex-M0). The skeleton:
//!
//! ```ignore
//! #![cfg_attr(target_os = "none", no_std, no_main)]
//!
//! firmware::output!(text); // or `firmware::output!(defmt);` to log through defmt
//!
//! fn run() -> bool {
//!     say!("hello from {}", firmware::MACHINE);
//!     true // false: the firmware exits with failure
//! }
//!
//! firmware::main!(run); // or firmware::entry!(run) next to a host `main` of its own
//! ```
//!
//! `say!` takes the format strings both `core::fmt` and defmt understand: plain `{}`
//! with numbers, `bool` and `&str`. The example links, on the target, what the macros
//! name: `cortex-m` (with `critical-section-single-core`), `cortex-m-rt`, `semihosting`,
//! and for `output!(defmt)` also `defmt` and `defmt-semihosting` (the root manifest's
//! target dev-dependencies).
//!
//! A new example then runs with `cargo run --release --target … --example NAME`; CI runs
//! it on both machines once its name is in `firmware_examples` in `.ci/firmware`. To
//! check it against the f64 reference, put its scene in `firmware/src/scenes/NAME.rs`
//! (data and builders shared with the test), generate `firmware/src/golden/NAME.rs` in
//! `tests/golden.rs` (as the `value` and `rope` scenes do) and compare with [`Tally`].
#![no_std]

// The simulated display of the starters records GIFs: host only.
#[cfg(not(target_os = "none"))]
extern crate std;

#[cfg(not(target_os = "none"))]
pub mod display;
pub mod golden;
pub mod scenes;
/// The MPS2 boards' timer as an instruction counter under QEMU `-icount`.
#[cfg(target_os = "none")]
pub mod timer;

mod output;

/// Where the example runs, for its report.
#[cfg(not(target_os = "none"))]
pub const MACHINE: &str = "host";
#[cfg(all(target_os = "none", target_abi = "eabihf"))]
pub const MACHINE: &str = "Cortex-M4F (thumbv7em-none-eabihf)";
#[cfg(all(target_os = "none", not(target_abi = "eabihf")))]
pub const MACHINE: &str = "Cortex-M0 (thumbv6m-none-eabi)";

/// Declares the program's entry point around `run: fn() -> bool`: a std `main` on the
/// host, cortex-m-rt's `#[entry]` on the target. Either way the process (QEMU, for the
/// firmware) exits with success exactly when `run` returns `true`.
#[macro_export]
macro_rules! main {
    ($run:path) => {
        #[cfg(not(target_os = "none"))]
        fn main() -> std::process::ExitCode {
            if $run() {
                std::process::ExitCode::SUCCESS
            } else {
                std::process::ExitCode::FAILURE
            }
        }

        $crate::entry!($run);
    };
}

/// Only the target's entry point around `run: fn() -> bool`, for an example that has
/// its own host `main`.
///
/// The firmware ends through semihosting with status 0 or 1; QEMU exits with the same
/// status.
#[macro_export]
macro_rules! entry {
    ($run:path) => {
        /// The critical-section implementation defmt-semihosting needs (single core).
        #[cfg(target_os = "none")]
        use cortex_m as _;

        #[cfg(target_os = "none")]
        #[cortex_m_rt::entry]
        fn main() -> ! {
            let ok = $run();
            semihosting::process::exit(if ok { 0 } else { 1 })
        }
    };
}

/// Compares a trajectory with its golden values and remembers the worst deviation.
#[derive(Clone, Copy, Debug)]
pub struct Tally {
    /// The largest `|got − golden|` seen.
    pub worst: f64,
    /// The sample at which it occurred.
    pub worst_step: usize,
    /// The number of samples outside their tolerance.
    pub failures: usize,
    /// The number of samples compared.
    pub samples: usize,
}

impl Default for Tally {
    fn default() -> Self {
        Self::new()
    }
}

impl Tally {
    /// An empty tally.
    pub const fn new() -> Self {
        Tally {
            worst: 0.0,
            worst_step: 0,
            failures: 0,
            samples: 0,
        }
    }

    /// Records sample `step`, which may deviate by up to `tolerance`.
    pub fn check(&mut self, step: usize, got: f64, golden: f64, tolerance: f64) {
        let err = abs(got - golden);
        // NaN fails too.
        if err.is_nan() || err > tolerance {
            self.failures += 1;
        }
        if err > self.worst || err.is_nan() {
            self.worst = err;
            self.worst_step = step;
        }
        self.samples += 1;
    }

    /// True when every sample was within its tolerance.
    pub fn passed(&self) -> bool {
        self.failures == 0
    }
}

/// `|x|` without std.
pub fn abs(x: f64) -> f64 {
    if x < 0.0 { -x } else { x }
}

/// `√x` without std (Newton's iteration; set-up and reports only).
pub fn sqrt(x: f64) -> f64 {
    if x.is_nan() || x <= 0.0 {
        return 0.0;
    }
    let mut r = if x > 1.0 { x } else { 1.0 };
    for _ in 0..64 {
        r = 0.5 * (r + x / r);
    }
    r
}
