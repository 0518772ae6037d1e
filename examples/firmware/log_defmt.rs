//! defmt output for the dual-target examples: `say!` logs one line through
//! defmt-semihosting on the target (scripts/qemu-run decodes it with `defmt-print`), and
//! prints it with `println!` on the host. A panic on the target is logged through defmt,
//! never as semihosting text, which would corrupt the defmt stream.
#![allow(unused_macros)]

/// Logs one line (`println!` syntax, restricted to what defmt accepts).
#[cfg(not(target_os = "none"))]
macro_rules! say {
    ($($arg:tt)*) => { std::println!($($arg)*) };
}

/// Logs one line (`println!` syntax, restricted to what defmt accepts). It is
/// `defmt::println!`, which no `DEFMT_LOG` level filters out.
#[cfg(target_os = "none")]
macro_rules! say {
    ($($arg:tt)*) => { defmt::println!($($arg)*) };
}

/// The global logger: defmt frames over semihosting.
#[cfg(target_os = "none")]
use defmt_semihosting as _;

// `-Tdefmt.x` for this example only. Cargo can pass a linker argument to all examples
// (build.rs) but not to one, and the script must be given only when defmt is linked:
// it demands a global logger. An input file the linker does not recognise as an object
// is read as a linker script, so naming `defmt.x` (which defmt's build script puts on
// the search path) as a verbatim library has the effect of `-Tdefmt.x`.
#[cfg(target_os = "none")]
#[link(name = "defmt.x", kind = "static", modifiers = "+verbatim")]
unsafe extern "C" {}

#[cfg(target_os = "none")]
#[panic_handler]
fn panic(info: &core::panic::PanicInfo) -> ! {
    defmt::error!("panic: {}", defmt::Display2Format(info));
    semihosting::process::exit(101)
}
