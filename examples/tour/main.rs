//! The tour: stiffspring's canonical scenes, run live in every backend.
//!
//! ```sh
//! cargo run --release --example tour
//! ```
//!
//! Prints compact tables (steps to rest, error against the independent f64 reference
//! model of the article and against the analytic solution, run time against the peer
//! crates) and writes SVG plots to `target/tour/`. Every number printed is computed by
//! this run.

mod bench;
mod knob;
mod networks;
mod rigid;
mod values;

use std::path::{Path, PathBuf};

/// Where the plots go: `target/tour/` under the workspace.
fn out_dir() -> PathBuf {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("target")
        .join("tour");
    let _ = std::fs::create_dir_all(&dir);
    dir
}

fn main() {
    let dir = out_dir();
    println!("stiffspring tour — plots in {}\n", dir.display());
    values::presets(&dir);
    values::fling(&dir);
    rigid::rest_in_two_steps();
    networks::rope(&dir);
    networks::jelly(&dir);
    knob::against_pd();
    knob::trace(&dir);
    bench::peers();
    println!(
        "\nDone. Open the SVG files in {} in a browser.",
        dir.display()
    );
}
