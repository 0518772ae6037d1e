//! The tour: stiffspring's canonical scenes, run live in every backend, and the starters.
//!
//! ```sh
//! cargo run --release --example tour
//! ```
//!
//! Plays the six starters (`examples/card.rs`, `list.rs`, `scroll.rs`, `rope.rs`,
//! `knob_loop.rs`, `knob_menu.rs`),
//! whose frames go to animated GIFs in `target/tour/`, then prints compact tables (steps
//! to rest, error against the independent f64 reference model of the article and
//! against the analytic solution, run time against the peer crates) and writes SVG plots
//! to `target/tour/`. Every number printed is computed by this run.
//!
//! The starters are examples of their own (`cargo run --example card`) and modules of the
//! tour at once: this file is the tour's crate root, so `mod card;` is `examples/card.rs`,
//! and the tour's own sections live in `examples/tour/`.

mod card;
mod knob_loop;
// The tour calls its `run` (its `main`, from `firmware::main!`, is the example's own).
mod knob_menu;
mod list;
mod rope;
mod scroll;

mod tour {
    pub mod bench;
    pub mod knob;
    pub mod networks;
    pub mod rigid;
    pub mod values;
}

use std::path::{Path, PathBuf};
use tour::{bench, knob, networks, rigid, values};

/// Where the plots go: `target/tour/` under the workspace.
fn out_dir() -> PathBuf {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("target")
        .join("tour");
    let _ = std::fs::create_dir_all(&dir);
    dir
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let dir = out_dir();
    println!(
        "stiffspring tour — plots and animations in {}\n",
        dir.display()
    );
    println!(
        "The starters (examples/card.rs, list.rs, scroll.rs, rope.rs, knob_loop.rs, knob_menu.rs), as they print:"
    );
    card::main()?;
    list::main()?;
    scroll::main()?;
    rope::main()?;
    knob_loop::main()?;
    if !knob_menu::run() {
        return Err("knob_menu: the run differs from its golden values".into());
    }
    println!();
    values::presets(&dir);
    values::fling(&dir);
    rigid::rest_in_two_steps();
    networks::rope(&dir);
    networks::jelly(&dir);
    knob::against_pd();
    knob::trace(&dir);
    bench::peers();
    println!(
        "\nDone. Open the GIF and SVG files in {} in a browser.",
        dir.display()
    );
    Ok(())
}
