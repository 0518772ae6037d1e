//! The precision study of issue 10 (`lab::precision`): every candidate representation of
//! one spring, in every backend, against the analytic damped oscillator.
//!
//! ```text
//! cargo run --release -p stiffspring-lab --bin precision            # the full grid
//! cargo run --release -p stiffspring-lab --bin precision -- --quick # the short grid
//! ```
//!
//! Prints Markdown tables and writes their CSV files to `target/precision/`.

use lab::precision;
use std::time::Instant;

fn main() -> std::io::Result<()> {
    let quick = std::env::args().any(|a| a == "--quick");
    let grid = if quick {
        precision::Grid::quick()
    } else {
        precision::Grid::full()
    };
    let start = Instant::now();
    let study = precision::study(grid);
    print!("{}", study.markdown());
    // The workspace's target directory, beside the other reports (target/pareto, ...).
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .expect("lab/ lies in the workspace")
        .join("target/precision");
    std::fs::create_dir_all(&dir)?;
    for (name, text) in study.csv() {
        std::fs::write(dir.join(name), text)?;
    }
    let [a, b, c, d, e] = study.seconds;
    eprintln!(
        "{:.1} s (fixed grid {a:.1}, float grid {b:.1}, undamped {c:.1}, limit cycles {d:.1}, kept rest search {e:.1}); CSV in {}",
        start.elapsed().as_secs_f64(),
        dir.display()
    );
    Ok(())
}
