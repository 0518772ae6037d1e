//! Tables: fixed-width for the terminal (the tour), Markdown (the reports) and CSV.

/// Prints a header, a rule and the rows, each column right-aligned to its widest cell
/// (the first column left-aligned).
pub fn print(header: &[&str], rows: &[Vec<String>]) {
    let columns = header.len();
    let mut widths: Vec<usize> = header.iter().map(|h| h.chars().count()).collect();
    for row in rows {
        for (w, cell) in widths.iter_mut().zip(row) {
            *w = (*w).max(cell.chars().count());
        }
    }
    let line = |cells: Vec<String>| {
        let mut out = String::new();
        for (i, cell) in cells.iter().enumerate().take(columns) {
            let pad = widths[i] - cell.chars().count();
            if i == 0 {
                out.push_str(cell);
                out.push_str(&" ".repeat(pad));
            } else {
                out.push_str("  ");
                out.push_str(&" ".repeat(pad));
                out.push_str(cell);
            }
        }
        println!("{}", out.trim_end());
    };
    line(header.iter().map(|h| h.to_string()).collect());
    let total: usize = widths.iter().sum::<usize>() + 2 * (columns - 1);
    println!("{}", "─".repeat(total));
    for row in rows {
        line(row.clone());
    }
}

/// A compact scientific number: `3.2e-7`, or `0` for an exact zero.
pub fn sci(v: f64) -> String {
    if v == 0.0 {
        "0".into()
    } else {
        format!("{v:.1e}")
    }
}

/// A whole number with thousands commas, as the docs write them: `1,452`.
pub fn grouped(n: impl ToString) -> String {
    let digits = n.to_string();
    let mut out = String::new();
    for (i, d) in digits.chars().enumerate() {
        if i > 0 && d.is_ascii_digit() && (digits.len() - i).is_multiple_of(3) {
            out.push(',');
        }
        out.push(d);
    }
    out
}

/// Writes `text` to `target/figures/NAME` in the workspace: the file a test or a tool
/// generates for a figures block of the docs (`scripts/check-figures` compares them), and
/// the path, for the test's output.
pub fn write_figures(name: &str, text: &str) -> std::path::PathBuf {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .expect("lab/ lies in the workspace")
        .join("target/figures")
        .join(name);
    if let Some(dir) = path.parent() {
        std::fs::create_dir_all(dir).expect("create the figures directory");
    }
    std::fs::write(&path, text).expect("write the figures file");
    path
}

/// A Markdown table: the header, the `|---|` rule, and the rows (cells as given).
pub fn markdown(header: &[&str], rows: &[Vec<String>]) -> String {
    let mut out = format!("| {} |\n", header.join(" | "));
    out.push_str(&format!("|{}\n", "---|".repeat(header.len())));
    for row in rows {
        out.push_str(&format!("| {} |\n", row.join(" | ")));
    }
    out
}

/// CSV: the header line and one line per row. Cells are written as given; a cell with a
/// comma, a quote or a line break is quoted (RFC 4180).
pub fn csv(header: &[&str], rows: &[Vec<String>]) -> String {
    fn cell(c: &str) -> String {
        if c.contains([',', '"', '\n', '\r']) {
            format!("\"{}\"", c.replace('"', "\"\""))
        } else {
            c.to_string()
        }
    }
    let mut out = header.iter().map(|h| cell(h)).collect::<Vec<_>>().join(",");
    out.push('\n');
    for row in rows {
        out.push_str(&row.iter().map(|c| cell(c)).collect::<Vec<_>>().join(","));
        out.push('\n');
    }
    out
}

#[cfg(test)]
mod tests {
    use super::{csv, markdown, sci};

    #[test]
    fn tables() {
        let rows = vec![
            vec!["a,b".to_string(), "1".into()],
            vec!["c".into(), "2".into()],
        ];
        assert_eq!(csv(&["name", "n"], &rows), "name,n\n\"a,b\",1\nc,2\n");
        assert_eq!(
            markdown(&["name", "n"], &rows),
            "| name | n |\n|---|---|\n| a,b | 1 |\n| c | 2 |\n"
        );
        assert_eq!(sci(0.0), "0");
        assert_eq!(sci(3.21e-7), "3.2e-7");
    }
}
