//! The output of a dual-target example: [`output!`](crate::output) defines `say!` and,
//! on the target, the panic handler (and for defmt the global logger).
//!
//! - `output!(text)`: `say!` prints a line on the host's stdout, or on QEMU's through
//!   semihosting. A panic on the target prints its message and exits with failure
//!   (status 101).
//! - `output!(defmt)`: `say!` logs one line through defmt-semihosting on the target
//!   (scripts/qemu-run decodes it with `defmt-print`), and prints it with `println!` on
//!   the host. A panic on the target is logged through defmt, never as semihosting text,
//!   which would corrupt the defmt stream.

/// Defines `say!` (`println!` syntax, restricted to what defmt also accepts) and the
/// target's panic handler, for `text` or `defmt` output; see the crate documentation.
/// Invoke it once, at the top of the example, before the first `say!`.
#[macro_export]
macro_rules! output {
    (text) => {
        $crate::__output!(text, $);
    };
    (defmt) => {
        $crate::__output!(defmt, $);
    };
}

/// The body of [`output!`]; `$d` is a `$`, for the repetitions of the `say!` it defines.
#[doc(hidden)]
#[macro_export]
macro_rules! __output {
    (text, $d:tt) => {
        #[cfg(not(target_os = "none"))]
        #[allow(unused_macros)]
        macro_rules! say {
                                    ($d($d arg:tt)*) => { std::println!($d($d arg)*) };
                                }

        #[cfg(target_os = "none")]
        #[allow(unused_macros)]
        macro_rules! say {
                                    ($d($d arg:tt)*) => { semihosting::println!($d($d arg)*) };
                                }

        #[cfg(target_os = "none")]
        #[panic_handler]
        fn panic(info: &core::panic::PanicInfo) -> ! {
            semihosting::eprintln!("panic: {}", info);
            semihosting::process::exit(101)
        }
    };
    (defmt, $d:tt) => {
        #[cfg(not(target_os = "none"))]
        #[allow(unused_macros)]
        macro_rules! say {
                                    ($d($d arg:tt)*) => { std::println!($d($d arg)*) };
                                }

        // `defmt::println!`, which no `DEFMT_LOG` level filters out.
        #[cfg(target_os = "none")]
        #[allow(unused_macros)]
        macro_rules! say {
                                    ($d($d arg:tt)*) => { defmt::println!($d($d arg)*) };
                                }

        // The global logger: defmt frames over semihosting.
        #[cfg(target_os = "none")]
        use defmt_semihosting as _;

        // `-Tdefmt.x` for this example only. Cargo can pass a linker argument to all
        // examples (build.rs) but not to one, and the script must be given only when
        // defmt is linked: it demands a global logger. An input file the linker does not
        // recognise as an object is read as a linker script, so naming `defmt.x` (which
        // defmt's build script puts on the search path) as a verbatim library has the
        // effect of `-Tdefmt.x`.
        #[cfg(target_os = "none")]
        #[link(name = "defmt.x", kind = "static", modifiers = "+verbatim")]
        unsafe extern "C" {}

        #[cfg(target_os = "none")]
        #[panic_handler]
        fn panic(info: &core::panic::PanicInfo) -> ! {
            defmt::error!("panic: {}", defmt::Display2Format(info));
            semihosting::process::exit(101)
        }
    };
}
