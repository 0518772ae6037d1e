//! Golden values kept in the repository as Rust source, so that a `no_std` firmware can
//! compile them in: render them, compare them with recomputed ones, regenerate them.
//!
//! A test recomputes the values on the host and calls [`check_or_bless`]: it fails when
//! the stored file is missing a value or differs, and rewrites the file instead when the
//! environment has `STIFFSPRING_BLESS=1`.

use std::fmt::Write as _;
use std::path::Path;

/// The environment variable that makes [`check_or_bless`] rewrite instead of compare.
pub const BLESS: &str = "STIFFSPRING_BLESS";

/// Rust source of `pub const NAME: [&[f64]; N] = [...]`: one slice per row, each
/// preceded by a comment with its label and printed to the last bit (`{:?}`), four
/// values a line, under `#[rustfmt::skip]`. `doc` is the item's doc comment (one line).
pub fn f64_table(name: &str, doc: &str, rows: &[(String, &[f64])]) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "/// {doc}\n#[rustfmt::skip]\npub const {name}: [&[f64]; {}] = [",
        rows.len()
    );
    for (label, values) in rows {
        let _ = writeln!(s, "    // {label}\n    &[");
        for chunk in values.chunks(4) {
            let line: Vec<String> = chunk.iter().map(|v| format!("{v:?}")).collect();
            let _ = writeln!(s, "        {},", line.join(", "));
        }
        let _ = writeln!(s, "    ],");
    }
    s.push_str("];\n");
    s
}

/// True when the environment asks for regeneration (`STIFFSPRING_BLESS=1`).
pub fn blessing() -> bool {
    std::env::var_os(BLESS).is_some_and(|v| v == "1")
}

/// Compares `recomputed` with the `stored` golden values of `path`, each to `relative`
/// error (relative to the larger magnitude, at least 1); or, when [`blessing`], writes
/// `source` to `path`. `hint` (how to regenerate) is part of every failure message.
///
/// # Panics
///
/// On a mismatch (a stale or missing file), or when the file cannot be written.
pub fn check_or_bless(
    path: &Path,
    source: &str,
    recomputed: &[Vec<f64>],
    stored: &[&[f64]],
    relative: f64,
    hint: &str,
) {
    let file = path.display();
    if blessing() {
        std::fs::write(path, source).unwrap_or_else(|e| panic!("cannot write {file}: {e}"));
        eprintln!("wrote {file}");
        return;
    }
    assert_eq!(recomputed.len(), stored.len(), "{file} is stale: {hint}");
    for (row, (new, old)) in recomputed.iter().zip(stored).enumerate() {
        assert_eq!(new.len(), old.len(), "{file}, row {row}: stale, {hint}");
        for (k, (a, b)) in new.iter().zip(old.iter()).enumerate() {
            let scale = a.abs().max(b.abs()).max(1.0);
            assert!(
                (a - b).abs() <= relative * scale,
                "{file}, row {row}, sample {k}: {a} recomputed, {b} stored; {hint}"
            );
        }
    }
}

#[cfg(test)]
mod tests {
    use super::f64_table;

    #[test]
    fn a_table_prints_every_bit() {
        let third = 1.0 / 3.0;
        let s = f64_table(
            "X",
            "Thirds.",
            &[("one".into(), &[third, -2.5, 0.0, 1e-300, 7.0])],
        );
        assert!(s.contains("pub const X: [&[f64]; 1] = ["));
        assert!(s.contains("// one"));
        assert!(s.contains("0.3333333333333333, -2.5, 0.0, 1e-300,\n        7.0,"));
        // The printed text reads back as the same value.
        assert_eq!(format!("{third:?}").parse::<f64>().unwrap(), third);
    }
}
