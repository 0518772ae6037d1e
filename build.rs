//! Links the firmware examples: nothing happens unless the target is a bare-metal one
//! (`target_os = "none"`), so host builds, tests and dependents are unaffected.
//!
//! The memory map depends on the machine: `memory/mps2-an386.x` for
//! `thumbv7em-none-eabihf` (QEMU `mps2-an386`), `memory/microbit.x` for
//! `thumbv6m-none-eabi` (QEMU `microbit`). The chosen one is copied into `OUT_DIR` as
//! `memory-map.x`, which the top-level `memory.x` includes (the linker finds that one in
//! the package root, its working directory), and as `memory.x`, for a link that runs
//! elsewhere. Every flag is passed
//! with `rustc-link-arg-examples`, never `rustc-link-search`: the latter would reach the
//! link of any firmware that depends on this crate and hand it our memory map.
//! `-Tdefmt.x` is not passed here; an example that logs through defmt asks for it itself
//! (see `firmware::output!(defmt)` in `firmware/src/output.rs`).

use std::{env, fs, path::PathBuf};

fn main() {
    println!("cargo::rerun-if-changed=build.rs");
    println!("cargo::rerun-if-changed=memory.x");
    println!("cargo::rerun-if-changed=memory");
    // `examples/size.rs` picks its configuration with `--cfg size="…"` (scripts/size-report).
    println!(
        "cargo::rustc-check-cfg=cfg(size, values(\"empty\", \"value_f32_raw\", \
         \"value_f32_raw_runtime\", \"value_f32_exact_const\", \"value_f32_exact_runtime\", \
         \"value_i16f16_raw\", \"batch16_f32\", \"rope_f32\", \"knob_f32\", \
         \"knob_f32_const\", \"knob_i16f16_const\", \"everything\", \
         \"c_twin_value\", \"c_twin_batch\", \"c_twin_knob\", \"c_twin_value_q16\", \
         \"c_twin_batch_q16\", \"c_twin_knob_q16\"))"
    );

    // ARMv6-M (Cortex-M0/M0+/M1) and ARMv8-M Baseline (M23) multiply 32×32 → 32 bits
    // only: the fixed-point backends build their long products from 16-bit halves there
    // (`src/scalar/widening.rs`, and the fast step's in `src/scalar/fast.rs`). Rust has no
    // stable `target_feature` cfg for this.
    println!("cargo::rustc-check-cfg=cfg(no_long_multiply)");
    let target = env::var("TARGET").unwrap_or_default();
    if target.starts_with("thumbv6m") || target.starts_with("thumbv8m.base") {
        println!("cargo::rustc-cfg=no_long_multiply");
    }

    if env::var("CARGO_CFG_TARGET_OS").as_deref() != Ok("none") {
        return;
    }
    let layout = if target.starts_with("thumbv6m") {
        "memory/microbit.x"
    } else {
        "memory/mps2-an386.x"
    };
    let manifest = PathBuf::from(env::var_os("CARGO_MANIFEST_DIR").unwrap_or_default());
    let out = PathBuf::from(env::var_os("OUT_DIR").unwrap_or_default());
    // A packaged copy of the crate may not carry the layouts; then there is nothing to link.
    let copied = fs::copy(manifest.join(layout), out.join("memory-map.x"))
        .and_then(|_| fs::copy(manifest.join(layout), out.join("memory.x")));
    if copied.is_err() {
        println!("cargo::warning={layout} not found: the firmware examples cannot be linked");
        return;
    }
    println!("cargo::rustc-link-arg-examples=-L{}", out.display());
    println!("cargo::rustc-link-arg-examples=-Tlink.x");
}
