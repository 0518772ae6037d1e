//! Plain-text output for the dual-target examples: `say!` prints a line on the host's
//! stdout, or on QEMU's through semihosting. A panic on the target prints its message
//! and exits with failure.
#![allow(unused_macros)]

/// Prints one line (`println!` syntax, restricted to what defmt also accepts).
#[cfg(not(target_os = "none"))]
macro_rules! say {
    ($($arg:tt)*) => { std::println!($($arg)*) };
}

/// Prints one line (`println!` syntax, restricted to what defmt also accepts).
#[cfg(target_os = "none")]
macro_rules! say {
    ($($arg:tt)*) => { semihosting::println!($($arg)*) };
}

#[cfg(target_os = "none")]
#[panic_handler]
fn panic(info: &core::panic::PanicInfo) -> ! {
    semihosting::eprintln!("panic: {}", info);
    semihosting::process::exit(101)
}
