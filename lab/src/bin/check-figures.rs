//! The figures check (`scripts/check-figures`): every table of figures in the docs that a
//! command generates must agree with what the command last wrote, within the tolerance
//! the doc states.
//!
//! A generated table sits in a Markdown file (`*.md` at the root and under `docs/`) or in
//! a doc comment (`//!`, `///`) of a Rust file under `src/`, `examples/`, `benches/` or
//! `tests/`, between two markers:
//!
//! ```text
//! <!-- figures: target/size/flash.md from `scripts/size-report`, within 2 % -->
//! | configuration | Cortex-M4F | Cortex-M0 |
//! …
//! <!-- figures: end -->
//! ```
//!
//! The first names the file the command writes (relative to the repository's root), the
//! command in backticks, and the tolerance: `within X %` (relative to the generated
//! figure) or `exact`. A marker that also says `long` is for a figure that takes minutes
//! to measure (the pareto bench): it is checked only with `--long`, after its command has
//! run; without `--long` only its command and file name are checked for form.
//!
//! The check compares the block with the file line by line: the text between the numbers
//! must be the same, and every number must be within the tolerance of the generated one
//! (a number is a run of digits, with thousands commas, a decimal point, a sign `+`, `-`
//! or `−` and an exponent `e±N` allowed; digits inside a name such as `I16F16` or
//! `thumbv7em` are text). It fails when a block disagrees, when a file that a checked
//! block names is missing (run its command first), or when a marker is malformed.
//!
//! ```text
//! scripts/check-figures              # after scripts/size-report and scripts/cost
//! scripts/check-figures --long       # also the long blocks (after their commands)
//! scripts/check-figures --bless      # rewrite the blocks from the files (then review the diff)
//! ```

use std::fs;
use std::path::{Path, PathBuf};
use std::process::{Command, ExitCode};

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let long = args.iter().any(|a| a == "--long");
    let bless = args.iter().any(|a| a == "--bless");
    if let Some(a) = args.iter().find(|a| *a != "--long" && *a != "--bless") {
        eprintln!("check-figures: unknown argument {a} (--long, --bless)");
        return ExitCode::FAILURE;
    }
    let Some(root) = repo_root() else {
        eprintln!("check-figures: not inside a Git work tree");
        return ExitCode::FAILURE;
    };
    let mut findings = Vec::new();
    let (mut checked, mut skipped, mut blessed) = (0, 0, 0);
    for doc in docs(&root) {
        let Ok(text) = fs::read_to_string(&doc) else {
            continue;
        };
        let name = doc
            .strip_prefix(&root)
            .unwrap_or(&doc)
            .display()
            .to_string();
        let lines: Vec<&str> = text.lines().collect();
        let blocks = match blocks(&lines) {
            Ok(b) => b,
            Err((line, why)) => {
                findings.push(format!("{name}:{line}: {why}"));
                continue;
            }
        };
        let mut rewritten: Vec<String> = lines.iter().map(|l| l.to_string()).collect();
        // Back to front, so that a rewritten block does not move the ones before it.
        for block in blocks.iter().rev() {
            if block.marker.long && !long {
                skipped += 1;
                continue;
            }
            let path = root.join(&block.marker.file);
            let Ok(generated) = fs::read_to_string(&path) else {
                findings.push(format!(
                    "{name}:{}: {} is missing: run `{}` first",
                    block.start + 1,
                    block.marker.file,
                    block.marker.command
                ));
                continue;
            };
            let generated: Vec<&str> = generated.lines().collect();
            if bless {
                let body: Vec<String> = generated
                    .iter()
                    .map(|g| format!("{}{}", block.prefix, g).trim_end().to_string())
                    .collect();
                rewritten.splice(block.start + 1..block.end, body);
                blessed += 1;
                continue;
            }
            checked += 1;
            let body = &lines[block.start + 1..block.end];
            for f in compare(body, &generated, block.marker.tolerance) {
                findings.push(format!(
                    "{name}:{}: {} (from `{}`, {}): {f}",
                    block.start + 1,
                    block.marker.file,
                    block.marker.command,
                    tolerance_text(block.marker.tolerance)
                ));
            }
        }
        if bless {
            let mut out = rewritten.join("\n");
            if text.ends_with('\n') {
                out.push('\n');
            }
            if out != text && fs::write(&doc, out).is_err() {
                findings.push(format!("{name}: could not be rewritten"));
            }
        }
    }
    if bless {
        println!("check-figures: {blessed} block(s) rewritten from their files");
    }
    if findings.is_empty() {
        if !bless {
            println!(
                "check-figures: {checked} generated block(s) agree with their commands' output{}",
                if skipped > 0 {
                    format!(" ({skipped} long one(s) not checked: --long)")
                } else {
                    String::new()
                }
            );
        }
        ExitCode::SUCCESS
    } else {
        for f in &findings {
            println!("{f}");
        }
        println!("check-figures: {} finding(s)", findings.len());
        ExitCode::FAILURE
    }
}

/// The root of the Git work tree around the current directory.
fn repo_root() -> Option<PathBuf> {
    let out = Command::new("git")
        .args(["rev-parse", "--show-toplevel"])
        .output()
        .ok()?;
    out.status
        .success()
        .then(|| PathBuf::from(String::from_utf8_lossy(&out.stdout).trim()))
}

/// The files that may hold generated blocks.
fn docs(root: &Path) -> Vec<PathBuf> {
    let mut out = Vec::new();
    let mut walk = |dir: &Path, ext: &str, deep: bool| {
        let mut stack = vec![dir.to_path_buf()];
        while let Some(d) = stack.pop() {
            let Ok(entries) = fs::read_dir(&d) else {
                continue;
            };
            for e in entries.flatten() {
                let p = e.path();
                if p.is_dir() {
                    if deep {
                        stack.push(p);
                    }
                } else if p.extension().is_some_and(|x| x == ext) {
                    out.push(p);
                }
            }
        }
    };
    walk(root, "md", false);
    walk(&root.join("docs"), "md", true);
    for dir in ["src", "examples", "benches", "tests"] {
        walk(&root.join(dir), "rs", true);
    }
    out.sort();
    out
}

/// A block's tolerance: relative, or exact.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Tolerance {
    Exact,
    Relative(f64),
}

fn tolerance_text(t: Tolerance) -> String {
    match t {
        Tolerance::Exact => "exact".into(),
        Tolerance::Relative(r) => format!("within {} %", r * 100.0),
    }
}

#[derive(Debug, PartialEq)]
struct Marker {
    file: String,
    command: String,
    tolerance: Tolerance,
    long: bool,
}

#[derive(Debug)]
struct Block {
    marker: Marker,
    /// The doc-comment prefix of the marker's line (`//! `), empty in Markdown.
    prefix: String,
    /// The lines of the opening and the closing marker.
    start: usize,
    end: usize,
}

const OPEN: &str = "<!-- figures:";
const CLOSE: &str = "<!-- figures: end -->";

/// The text after a doc comment's prefix, and the prefix.
fn split_prefix(line: &str) -> (&str, &str) {
    let trimmed = line.trim_start();
    let indent = line.len() - trimmed.len();
    for p in ["//! ", "/// ", "//!", "///"] {
        if let Some(rest) = trimmed.strip_prefix(p) {
            return (&line[..indent + p.len()], rest);
        }
    }
    ("", line)
}

/// The generated blocks of a file, or the line (1-based) of a malformed marker.
fn blocks(lines: &[&str]) -> Result<Vec<Block>, (usize, String)> {
    let mut out = Vec::new();
    let mut open: Option<(usize, Marker, String)> = None;
    for (i, line) in lines.iter().enumerate() {
        let (prefix, text) = split_prefix(line);
        let text = text.trim();
        if text == CLOSE {
            let Some((start, marker, prefix)) = open.take() else {
                return Err((
                    i + 1,
                    "a closing figures marker without an opening one".into(),
                ));
            };
            out.push(Block {
                marker,
                prefix,
                start,
                end: i,
            });
        } else if text.starts_with(OPEN) {
            if open.is_some() {
                return Err((i + 1, "a figures marker inside another block".into()));
            }
            let marker = marker(text).map_err(|why| (i + 1, why))?;
            open = Some((i, marker, prefix.to_string()));
        }
    }
    match open {
        Some((start, ..)) => Err((start + 1, "a figures block that is never closed".into())),
        None => Ok(out),
    }
}

/// `<!-- figures: FILE from `COMMAND`, within X % [, long] -->` or `…, exact …`.
fn marker(text: &str) -> Result<Marker, String> {
    let form =
        "expected `<!-- figures: FILE from `COMMAND`, within X % -->` (or `exact`, and `long`)";
    let body = text
        .strip_prefix(OPEN)
        .and_then(|t| t.strip_suffix("-->"))
        .ok_or_else(|| form.to_string())?
        .trim();
    let (file, rest) = body.split_once(" from `").ok_or_else(|| form.to_string())?;
    let (command, rest) = rest.split_once('`').ok_or_else(|| form.to_string())?;
    let file = file.trim();
    if file.is_empty() || file.contains(' ') || command.trim().is_empty() {
        return Err(form.into());
    }
    let mut tolerance = None;
    let mut long = false;
    for part in rest.split(',').map(str::trim).filter(|p| !p.is_empty()) {
        if part == "exact" {
            tolerance = Some(Tolerance::Exact);
        } else if part == "long" {
            long = true;
        } else if let Some(p) = part
            .strip_prefix("within ")
            .and_then(|p| p.strip_suffix('%'))
        {
            let r: f64 = p
                .trim()
                .parse()
                .map_err(|_| format!("tolerance `{part}` is not a number of %"))?;
            if !(r.is_finite() && r >= 0.0) {
                return Err(format!("tolerance `{part}` is not a number of %"));
            }
            tolerance = Some(Tolerance::Relative(r / 100.0));
        } else {
            return Err(format!("unknown part `{part}`: {form}"));
        }
    }
    Ok(Marker {
        file: file.into(),
        command: command.trim().into(),
        tolerance: tolerance.ok_or_else(|| format!("no tolerance: {form}"))?,
        long,
    })
}

/// A line split into its text and its numbers: `Text` between, `Number` with the value
/// and the spelling.
#[derive(Debug, PartialEq)]
enum Token {
    Text(String),
    Number(f64, String),
}

/// The tokens of a line (see the module's doc for what a number is).
fn tokens(line: &str) -> Vec<Token> {
    let chars: Vec<char> = line.chars().collect();
    let mut out = Vec::new();
    let mut text = String::new();
    let mut i = 0;
    let word = |c: char| c.is_alphanumeric() || c == '_';
    while i < chars.len() {
        let c = chars[i];
        let after_word = i > 0 && (word(chars[i - 1]) || chars[i - 1] == '.');
        let signed = matches!(c, '+' | '-' | '−')
            && chars.get(i + 1).is_some_and(|d| d.is_ascii_digit())
            && !after_word;
        if (c.is_ascii_digit() && !after_word) || signed {
            let start = i;
            let mut s = String::new();
            if signed {
                s.push(if c == '+' { '+' } else { '-' });
                i += 1;
            }
            let digits = |i: &mut usize, s: &mut String, commas: bool| {
                while *i < chars.len() {
                    let d = chars[*i];
                    if d.is_ascii_digit() {
                        s.push(d);
                    } else if commas
                        && d == ','
                        && chars.get(*i + 1).is_some_and(|d| d.is_ascii_digit())
                        && chars.get(*i + 3).is_some_and(|d| d.is_ascii_digit())
                        && !chars.get(*i + 4).is_some_and(|d| d.is_ascii_digit())
                    {
                        // A thousands comma: exactly three digits follow.
                    } else {
                        break;
                    }
                    *i += 1;
                }
            };
            digits(&mut i, &mut s, true);
            if chars.get(i) == Some(&'.') && chars.get(i + 1).is_some_and(|d| d.is_ascii_digit()) {
                s.push('.');
                i += 1;
                digits(&mut i, &mut s, false);
            }
            // An exponent: e5, e-5, e−5.
            if matches!(chars.get(i), Some('e' | 'E')) {
                let mut j = i + 1;
                let mut exp = String::from("e");
                if matches!(chars.get(j), Some('+' | '-' | '−')) {
                    exp.push(if chars[j] == '+' { '+' } else { '-' });
                    j += 1;
                }
                if chars.get(j).is_some_and(|d| d.is_ascii_digit()) {
                    let mut k = j;
                    while chars.get(k).is_some_and(|d| d.is_ascii_digit()) {
                        exp.push(chars[k]);
                        k += 1;
                    }
                    if !chars.get(k).is_some_and(|&d| word(d)) {
                        s.push_str(&exp);
                        i = k;
                    }
                }
            }
            if chars.get(i).is_some_and(|&d| word(d)) {
                // Digits that run into a name (`2D`, `64KiB`): text.
                text.extend(&chars[start..i]);
                continue;
            }
            if !text.is_empty() {
                out.push(Token::Text(std::mem::take(&mut text)));
            }
            let spelled: String = chars[start..i].iter().collect();
            out.push(Token::Number(s.parse().unwrap_or(f64::NAN), spelled));
        } else {
            text.push(c);
            i += 1;
        }
    }
    if !text.is_empty() {
        out.push(Token::Text(text));
    }
    out
}

/// Whether `doc` is within `tolerance` of `generated`.
fn agrees(doc: f64, generated: f64, tolerance: Tolerance) -> bool {
    match tolerance {
        Tolerance::Exact => doc == generated,
        Tolerance::Relative(r) => (doc - generated).abs() <= r * generated.abs(),
    }
}

/// The disagreements of a block's lines with the generated lines (a block's lines are
/// read without their doc-comment prefix).
fn compare(body: &[&str], generated: &[&str], tolerance: Tolerance) -> Vec<String> {
    let mut out = Vec::new();
    let strip = |l: &str| -> String { split_prefix(l).1.trim_end().to_string() };
    let body: Vec<String> = body.iter().map(|l| strip(l)).collect();
    let generated: Vec<String> = generated.iter().map(|l| l.trim_end().to_string()).collect();
    if body.len() != generated.len() {
        out.push(format!(
            "{} line(s) in the doc, {} generated",
            body.len(),
            generated.len()
        ));
    }
    for (n, (d, g)) in body.iter().zip(&generated).enumerate() {
        let (td, tg) = (tokens(d), tokens(g));
        let same_shape = td.len() == tg.len()
            && td.iter().zip(&tg).all(|pair| match pair {
                (Token::Text(a), Token::Text(b)) => a == b,
                (Token::Number(..), Token::Number(..)) => true,
                _ => false,
            });
        if !same_shape {
            out.push(format!(
                "line {}: the text differs:\n  doc:       {d}\n  generated: {g}",
                n + 1
            ));
            continue;
        }
        for pair in td.iter().zip(&tg) {
            if let (Token::Number(a, sa), Token::Number(b, sb)) = pair
                && !agrees(*a, *b, tolerance)
            {
                out.push(format!(
                    "line {}: {sa} in the doc, {sb} generated:\n  doc:       {d}\n  generated: {g}",
                    n + 1
                ));
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn numbers(line: &str) -> Vec<f64> {
        tokens(line)
            .into_iter()
            .filter_map(|t| match t {
                Token::Number(v, _) => Some(v),
                Token::Text(_) => None,
            })
            .collect()
    }

    #[test]
    fn numbers_are_told_from_names() {
        assert_eq!(
            numbers("| `I16F16` value `step` on thumbv7em | +9,568 | −1.5e−5 | 2-D | 18.0 |"),
            vec![9568.0, -1.5e-5, 2.0, 18.0]
        );
        assert_eq!(numbers("value_f32_raw, m4f, 64KiB, 2D"), Vec::<f64>::new());
        assert_eq!(
            numbers("1,174 B and 3.31×, 1, 2"),
            vec![1174.0, 3.31, 1.0, 2.0]
        );
    }

    #[test]
    fn markers_parse() {
        assert_eq!(
            marker("<!-- figures: target/size/flash.md from `scripts/size-report`, within 2 % -->"),
            Ok(Marker {
                file: "target/size/flash.md".into(),
                command: "scripts/size-report".into(),
                tolerance: Tolerance::Relative(0.02),
                long: false,
            })
        );
        let long = marker("<!-- figures: target/p.md from `cargo bench`, exact, long -->").unwrap();
        assert!(long.long && long.tolerance == Tolerance::Exact);
        assert!(marker("<!-- figures: target/p.md from `x` -->").is_err());
        assert!(marker("<!-- figures: target/p.md, within 2 % -->").is_err());
    }

    #[test]
    fn tolerance_is_relative_to_the_generated_figure() {
        let doc = ["| a | 102 | 11.0 |"];
        assert!(compare(&doc, &["| a | 100 | 11.0 |"], Tolerance::Relative(0.02)).is_empty());
        assert_eq!(
            compare(&doc, &["| a | 99 | 11.0 |"], Tolerance::Relative(0.02)).len(),
            1
        );
        assert_eq!(
            compare(&doc, &["| b | 102 | 11.0 |"], Tolerance::Relative(0.02)).len(),
            1
        );
        assert_eq!(
            compare(&doc, &["| a | 102 | 11.0 |", "| c |"], Tolerance::Exact).len(),
            1
        );
    }

    #[test]
    fn blocks_in_doc_comments() {
        let lines = [
            "//! text",
            "//! <!-- figures: target/cost/m4f.md from `scripts/cost`, within 1 % -->",
            "//! | a | 1 |",
            "//! <!-- figures: end -->",
        ];
        let b = blocks(&lines).unwrap();
        assert_eq!((b.len(), b[0].start, b[0].end), (1, 1, 3));
        assert_eq!(b[0].prefix, "//! ");
        assert!(compare(&lines[2..3], &["| a | 1 |"], Tolerance::Exact).is_empty());
        assert!(blocks(&lines[..3]).is_err());
    }
}
