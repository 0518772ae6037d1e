//! The docs check (`scripts/check-docs`): the docs may cite only what exists, and may not
//! reach outside the repository.
//!
//! It reads the Markdown files (`*.md` at the root and under `docs/`, `lab/`,
//! `firmware/`) and the doc comments (`///`, `//!`) of every Rust file (the library's
//! rustdoc, and the docs of the tests, examples, benches and instruments), and fails when
//!
//! 1. a cited **file** does not exist: a path that starts with a top-level entry of the
//!    repository (`src/…`, `tests/…`, `scripts/…`, `.ci/…`, …; `*` matches within a
//!    name, `target/` is build output and not checked), a root file named alone
//!    (`README.md`, `Cargo.toml`), or the target of a relative Markdown link;
//! 2. a cited **command** names what does not exist: in `cargo …` (in backticks or in a
//!    code block) an `--example`, `--bench`, `--test`, `--bin`, `-p`/`--package`, a
//!    feature of `--features`, a `--target` that `rust-toolchain.toml` does not install,
//!    or a test filter after `--` that matches no test of the named `--test` targets; a
//!    cited `scripts/…`, `bash …` or `.ci/…` program that does not exist;
//! 3. a cited **test** (a backticked name after the word "test", or any backticked name
//!    that is a test function) does not exist; or it is `#[ignore]`d while the text
//!    around the citation does not say "ignore"; or the text calls it ignored while it
//!    runs; or a `cargo test` command selects only ignored tests without `--ignored` or
//!    `--include-ignored`, or passes `--ignored` where none of the selected tests is;
//! 4. a doc **refers outside the repository**: any text file that Git tracks naming
//!    a design brief kept outside the repository (by its file name, see
//!    `forbidden_words`) or an absolute prefix of the machines' home folders, or a
//!    doc (Markdown, doc comments, and the comments of Rust, TOML and shell files) with
//!    a `../` path that leaves the repository.
//!
//! Run from anywhere inside the repository; exits with status 1 and one line per
//! finding, or prints a summary and exits with 0.

use std::collections::{BTreeMap, BTreeSet};
use std::fs;
use std::path::{Component, Path, PathBuf};
use std::process::{Command, ExitCode};

fn main() -> ExitCode {
    let root = match repo_root() {
        Some(r) => r,
        None => {
            eprintln!("check-docs: not inside a Git work tree");
            return ExitCode::FAILURE;
        }
    };
    let repo = Repo::load(&root);
    let (findings, cited) = repo.check();
    if findings.is_empty() {
        println!(
            "check-docs: {} docs, {} files, {} commands and {} tests cited, all present; \
             nothing outside the repository",
            repo.docs.len(),
            cited.files,
            cited.commands,
            cited.tests
        );
        ExitCode::SUCCESS
    } else {
        for f in &findings {
            println!("{f}");
        }
        println!("check-docs: {} finding(s)", findings.len());
        ExitCode::FAILURE
    }
}

fn repo_root() -> Option<PathBuf> {
    let out = Command::new("git")
        .args(["rev-parse", "--show-toplevel"])
        .output()
        .ok()?;
    out.status
        .success()
        .then(|| PathBuf::from(String::from_utf8_lossy(&out.stdout).trim()))
}

/// This file, which names what it looks for.
const SELF: &str = "lab/src/bin/check-docs.rs";

/// The words this tool looks for, spelled so that its own source does not contain them.
fn forbidden_words() -> [String; 3] {
    [
        ["DESIGN", ".md"].concat(),
        ["/wo", "rk/"].concat(),
        ["/ho", "me/"].concat(),
    ]
}

/// One piece of documentation: where it is and its text, line by line.
#[derive(Clone, Debug)]
struct Doc {
    /// Repository-relative path of the file.
    path: String,
    /// `(line number, text)`; for Rust sources only the doc comment lines, without
    /// their `///` or `//!`.
    lines: Vec<(usize, String)>,
}

/// A test function: its target and whether it is ignored.
#[derive(Clone, Debug)]
struct TestFn {
    target: String,
    name: String,
    ignored: bool,
}

/// How many citations were checked, for the summary.
#[derive(Clone, Copy, Debug, Default)]
struct Counts {
    files: usize,
    commands: usize,
    tests: usize,
}

struct Repo {
    root: PathBuf,
    /// Every file Git tracks or would add (untracked, not ignored).
    tracked: Vec<String>,
    docs: Vec<Doc>,
    tests: Vec<TestFn>,
    /// Test targets: name → the files whose tests belong to it.
    targets: BTreeMap<String, BTreeSet<String>>,
    examples: BTreeSet<String>,
    benches: BTreeSet<String>,
    bins: BTreeSet<String>,
    packages: BTreeSet<String>,
    features: BTreeSet<String>,
    rust_targets: BTreeSet<String>,
}

impl Repo {
    fn load(root: &Path) -> Repo {
        let tracked = git_files(root);
        let read = |p: &str| fs::read_to_string(root.join(p)).unwrap_or_default();
        let mut docs = Vec::new();
        for p in &tracked {
            let markdown = p.ends_with(".md")
                && (!p.contains('/')
                    || p.starts_with("docs/")
                    || p.starts_with("lab/")
                    || p.starts_with("firmware/"));
            // The doc comments of every Rust file: the library's rustdoc, and the module
            // docs of the tests, examples and benches, which say what they measure. The
            // checker's own doc spells out the patterns it looks for.
            let rustdoc = p.ends_with(".rs") && p != SELF;
            if markdown {
                let lines = read(p)
                    .lines()
                    .enumerate()
                    .map(|(i, l)| (i + 1, l.to_string()))
                    .collect();
                docs.push(Doc {
                    path: p.clone(),
                    lines,
                });
            } else if rustdoc {
                docs.push(Doc {
                    path: p.clone(),
                    lines: doc_comments(&read(p)),
                });
            }
        }
        let mut tests = Vec::new();
        let mut targets: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
        let mut examples = BTreeSet::new();
        let mut benches = BTreeSet::new();
        let mut bins = BTreeSet::new();
        for p in &tracked {
            if !p.ends_with(".rs") {
                continue;
            }
            let parts: Vec<&str> = p.split('/').collect();
            // Integration test targets: `tests/NAME.rs`, `tests/NAME/main.rs`, the same
            // under a member crate; the unit tests of a library: `lib`.
            let target = match parts.as_slice() {
                ["tests", f] | [_, "tests", f] => f.strip_suffix(".rs").map(String::from),
                ["tests", d, "main.rs"] | [_, "tests", d, "main.rs"] => Some(d.to_string()),
                ["tests", d, ..] | [_, "tests", d, ..] => Some(d.to_string()),
                ["src", ..]
                | ["lab", "src", ..]
                | ["firmware", "src", ..]
                | ["capi", "src", ..] => Some("lib".into()),
                _ => None,
            };
            match parts.as_slice() {
                // The root's examples and a member crate's (`capi/examples/…`).
                ["examples", f] | [_, "examples", f] => {
                    examples.insert(f.trim_end_matches(".rs").to_string());
                }
                ["examples", d, "main.rs"] | [_, "examples", d, "main.rs"] => {
                    examples.insert(d.to_string());
                }
                ["benches", f] => {
                    benches.insert(f.trim_end_matches(".rs").to_string());
                }
                ["benches", d, "main.rs"] => {
                    benches.insert(d.to_string());
                }
                [.., "src", "bin", f] => {
                    bins.insert(f.trim_end_matches(".rs").to_string());
                }
                _ => {}
            }
            if let Some(target) = target {
                let found = test_fns(&read(p));
                if !found.is_empty() || !parts.contains(&"src") {
                    targets.entry(target.clone()).or_default().insert(p.clone());
                }
                // A unit test's name, as libtest filters it, starts with its module's path
                // (`src/math.rs` → `math::…`); an integration test's with its function.
                let module = match parts.iter().position(|part| *part == "src") {
                    Some(at) if target == "lib" => parts[at + 1..]
                        .join("::")
                        .trim_end_matches(".rs")
                        .trim_end_matches("mod")
                        .trim_end_matches("lib")
                        .trim_end_matches("::")
                        .to_string(),
                    _ => String::new(),
                };
                tests.extend(found.into_iter().map(|(name, ignored)| TestFn {
                    target: target.clone(),
                    name: if module.is_empty() {
                        name
                    } else {
                        format!("{module}::{name}")
                    },
                    ignored,
                }));
            }
        }
        let manifest = read("Cargo.toml");
        let mut packages = BTreeSet::new();
        for p in tracked.iter().filter(|p| p.ends_with("Cargo.toml")) {
            if let Some(name) = toml_value(&read(p), "package", "name") {
                packages.insert(name);
            }
        }
        let features = toml_keys(&manifest, "features");
        let mut rust_targets: BTreeSet<String> = read("rust-toolchain.toml")
            .split('"')
            .filter(|s| s.starts_with("thumb") || s.contains("-none-") || s.contains("-linux-"))
            .map(String::from)
            .collect();
        rust_targets.insert("x86_64-unknown-linux-gnu".into());
        Repo {
            root: root.to_path_buf(),
            tracked,
            docs,
            tests,
            targets,
            examples,
            benches,
            bins,
            packages,
            features,
            rust_targets,
        }
    }

    /// Every finding, and how many citations were checked.
    fn check(&self) -> (Vec<String>, Counts) {
        let mut findings = Vec::new();
        let mut counts = Counts::default();
        for doc in &self.docs {
            let mut in_code = false;
            let lines = logical_lines(&doc.lines);
            for (i, (n, line)) in lines.iter().enumerate() {
                let at = format!("{}:{n}", doc.path);
                let fence = line.trim_start().starts_with("```");
                if fence {
                    in_code = !in_code;
                    continue;
                }
                // The text around a citation: this line and its neighbours.
                let context: String = lines[i.saturating_sub(2)..(i + 3).min(lines.len())]
                    .iter()
                    .map(|(_, l)| l.as_str())
                    .collect::<Vec<_>>()
                    .join(" ");
                for path in cited_paths(line, &self.top_level()) {
                    counts.files += 1;
                    if !self.exists(&path) {
                        findings.push(format!("{at}: cites `{path}`, which does not exist"));
                    }
                }
                for link in markdown_links(line) {
                    counts.files += 1;
                    match self.resolve(&doc.path, &link) {
                        Some(p) if self.exists(&p) => {}
                        Some(p) => {
                            findings.push(format!("{at}: links to `{p}`, which does not exist"))
                        }
                        None => findings
                            .push(format!("{at}: links to `{link}`, outside the repository")),
                    }
                }
                let commands = if in_code {
                    vec![line.clone()]
                } else {
                    backticked(line)
                };
                for cmd in commands {
                    let cmd = strip_comment(&cmd);
                    if let Some(errors) = self.check_command(cmd) {
                        counts.commands += 1;
                        for e in errors {
                            findings.push(format!("{at}: `{}`: {e}", cmd.trim()));
                        }
                    }
                }
                for (name, explicit) in cited_tests(line) {
                    let found: Vec<&TestFn> = self
                        .tests
                        .iter()
                        .filter(|t| {
                            t.name == name
                                || t.name
                                    .strip_suffix(name.as_str())
                                    .is_some_and(|m| m.ends_with("::"))
                        })
                        .collect();
                    if found.is_empty() {
                        if explicit {
                            counts.tests += 1;
                            findings
                                .push(format!("{at}: cites test `{name}`, which does not exist"));
                        }
                        continue;
                    }
                    counts.tests += 1;
                    let says_ignored = mentions_ignore(&context);
                    let ignored = found.iter().all(|t| t.ignored);
                    if ignored && !says_ignored {
                        findings.push(format!(
                            "{at}: cites test `{name}`, which is #[ignore]d, without saying so"
                        ));
                    }
                    // "ignored" may end the previous line, with the name on this one.
                    let previous = if i > 0 { lines[i - 1].1.as_str() } else { "" };
                    let called_ignored = calls_ignored(&format!("{previous} {line}"), &name);
                    if !ignored && called_ignored {
                        findings.push(format!(
                            "{at}: calls test `{name}` ignored, but it runs in `cargo test`"
                        ));
                    }
                }
            }
        }
        findings.extend(self.outside_references());
        (findings, counts)
    }

    fn top_level(&self) -> BTreeSet<String> {
        self.tracked
            .iter()
            .filter_map(|p| p.split('/').next())
            .filter(|t| *t != "target")
            .map(String::from)
            .collect()
    }

    /// True when `path` (repository-relative, may end in `/`, may hold `*`) names a
    /// tracked file or a directory holding one.
    fn exists(&self, path: &str) -> bool {
        let path = path.trim_end_matches('/');
        if path.contains('*') {
            return self
                .tracked
                .iter()
                .any(|t| glob(path, t) || t.rsplit_once('/').is_some_and(|(d, _)| glob(path, d)));
        }
        self.tracked
            .iter()
            .any(|t| t == path || t.starts_with(&format!("{path}/")))
    }

    /// A link target relative to the document `from`, as a repository path; `None` when
    /// it leaves the repository.
    fn resolve(&self, from: &str, link: &str) -> Option<String> {
        let base = Path::new(from).parent().unwrap_or(Path::new(""));
        normalise(&base.join(link))
    }

    /// The errors of a cited command, or `None` when `cmd` is not a command.
    fn check_command(&self, cmd: &str) -> Option<Vec<String>> {
        let words: Vec<&str> = cmd
            .split_whitespace()
            .skip_while(|w| w.contains('=') && !w.starts_with('-'))
            .collect();
        let first = *words.first()?;
        let mut errors = Vec::new();
        match first {
            "cargo" => {}
            "bash" | "sh" => {
                let script = words.get(1)?;
                if !self.exists(script) {
                    errors.push(format!("`{script}` does not exist"));
                }
                return Some(errors);
            }
            w if w.starts_with("scripts/") || w.starts_with(".ci/") => {
                if !self.exists(w) {
                    errors.push(format!("`{w}` does not exist"));
                }
                return Some(errors);
            }
            _ => return None,
        }
        let sub = words.get(1).copied().unwrap_or("");
        if ![
            "test", "run", "build", "bench", "doc", "check", "clippy", "rustc",
        ]
        .contains(&sub)
        {
            return Some(errors);
        }
        let split = words.iter().position(|w| *w == "--").unwrap_or(words.len());
        let (args, rest) = (&words[..split], &words[(split + 1).min(words.len())..]);
        let mut test_targets = Vec::new();
        let mut positional: Vec<&str> = Vec::new();
        let mut it = args.iter().skip(2);
        while let Some(&w) = it.next() {
            let (flag, inline) = match w.split_once('=') {
                Some((f, v)) if f.starts_with("--") => (f, Some(v)),
                _ => (w, None),
            };
            let takes = [
                "--example",
                "--bench",
                "--test",
                "--bin",
                "-p",
                "--package",
                "--features",
                "--target",
            ];
            // Flags whose value is not checked, but is not a test filter either.
            let others = [
                "--profile",
                "-j",
                "--jobs",
                "--config",
                "--manifest-path",
                "--target-dir",
                "--color",
                "--message-format",
                "-Z",
            ];
            if others.contains(&flag) {
                if inline.is_none() {
                    it.next();
                }
                continue;
            }
            if !takes.contains(&flag) {
                // `cargo test NAME`: a filter, as after `--`.
                if sub == "test" && !w.starts_with('-') {
                    positional.push(w);
                }
                continue;
            }
            let Some(value) = inline.or_else(|| it.next().copied()) else {
                errors.push(format!("`{flag}` without a value"));
                continue;
            };
            if placeholder(value) {
                continue;
            }
            let known = match flag {
                "--example" => self.examples.contains(value),
                "--bench" => self.benches.contains(value),
                "--test" => {
                    test_targets.push(value.to_string());
                    self.targets.contains_key(value)
                }
                "--bin" => self.bins.contains(value),
                "-p" | "--package" => self.packages.contains(value),
                "--target" => {
                    self.rust_targets.contains(value)
                        || value.starts_with('"')
                        || value.starts_with('$')
                }
                _ => value
                    .split(',')
                    .all(|f| self.features.contains(f) || f.contains('/') || f.starts_with('$')),
            };
            if !known {
                errors.push(format!(
                    "{flag} {value}: no such {}",
                    &flag.trim_start_matches('-')
                ));
            }
        }
        if sub == "test" {
            let filters: Vec<&str> = rest
                .iter()
                .copied()
                .filter(|w| !w.starts_with('-'))
                .chain(positional.iter().copied())
                .collect();
            let wants_ignored = rest
                .iter()
                .any(|w| *w == "--ignored" || *w == "--include-ignored");
            let in_scope =
                |t: &&TestFn| test_targets.is_empty() || test_targets.contains(&t.target);
            let selected: Vec<&TestFn> = self
                .tests
                .iter()
                .filter(in_scope)
                .filter(|t| filters.is_empty() || filters.iter().any(|f| t.name.contains(f)))
                .collect();
            for f in &filters {
                if !self
                    .tests
                    .iter()
                    .filter(in_scope)
                    .any(|t| t.name.contains(f))
                {
                    errors.push(format!("the filter `{f}` matches no test"));
                }
            }
            if !test_targets.is_empty()
                && !selected.is_empty()
                && selected.iter().all(|t| t.ignored)
                && !wants_ignored
            {
                errors.push("selects only ignored tests, without `--ignored`".into());
            }
            let only_ignored = rest.contains(&"--ignored");
            if only_ignored && !selected.iter().any(|t| t.ignored) {
                errors.push("`--ignored` runs no test: none of those selected is ignored".into());
            }
        }
        Some(errors)
    }

    /// Finding 4: references outside the repository.
    fn outside_references(&self) -> Vec<String> {
        let mut findings = Vec::new();
        let words = forbidden_words();
        for p in &self.tracked {
            if p == SELF {
                continue;
            }
            let Ok(text) = fs::read_to_string(self.root.join(p)) else {
                continue;
            };
            let commented = [".rs", ".toml", ".md", ".sh", ".x"]
                .iter()
                .any(|e| p.ends_with(e))
                || p.starts_with("scripts/")
                || p.starts_with(".ci/");
            for (i, line) in text.lines().enumerate() {
                let at = format!("{p}:{}", i + 1);
                for w in &words {
                    if line.contains(w.as_str()) {
                        findings.push(format!("{at}: refers to `{w}`, outside the repository"));
                    }
                }
                if !commented {
                    continue;
                }
                let doc_text = if p.ends_with(".md") {
                    Some(line)
                } else {
                    comment_of(line, p)
                };
                let Some(doc_text) = doc_text else { continue };
                for token in doc_text.split(|c: char| c.is_whitespace() || "`()[]<>\"'".contains(c))
                {
                    if let Some(start) = token.find("../") {
                        let rel = token[start..].trim_end_matches(|c: char| ".,;:".contains(c));
                        let base = Path::new(p).parent().unwrap_or(Path::new(""));
                        if normalise(&base.join(rel)).is_none() {
                            findings.push(format!("{at}: `{rel}` leaves the repository"));
                        }
                    }
                }
            }
        }
        findings
    }
}

/// The files Git knows (tracked, and untracked but not ignored), as repository paths.
fn git_files(root: &Path) -> Vec<String> {
    let out = Command::new("git")
        .args(["ls-files", "--cached", "--others", "--exclude-standard"])
        .current_dir(root)
        .output()
        .expect("git ls-files");
    let mut files: Vec<String> = String::from_utf8_lossy(&out.stdout)
        .lines()
        .filter(|p| root.join(p).exists())
        .map(String::from)
        .collect();
    files.sort();
    files.dedup();
    files
}

/// The doc comment lines of a Rust source, with their line numbers, markers removed.
fn doc_comments(source: &str) -> Vec<(usize, String)> {
    source
        .lines()
        .enumerate()
        .filter_map(|(i, l)| {
            let t = l.trim_start();
            let text = t.strip_prefix("//!").or_else(|| t.strip_prefix("///"))?;
            Some((i + 1, text.strip_prefix(' ').unwrap_or(text).to_string()))
        })
        .collect()
}

/// The comment of a line of a Rust, TOML or shell file, if it has one (a `//` or `#`
/// at the start of the line, after whitespace; `#[…]` attributes are code).
fn comment_of<'a>(line: &'a str, path: &str) -> Option<&'a str> {
    let t = line.trim_start();
    if path.ends_with(".rs") || path.ends_with(".x") {
        t.strip_prefix("//")
    } else {
        t.strip_prefix('#')
            .filter(|rest| !rest.starts_with('[') && !rest.starts_with('!'))
    }
}

/// The test functions of a Rust source: `#[test]` functions (proptest's included) and
/// whether an `#[ignore]` stands among their attributes.
fn test_fns(source: &str) -> Vec<(String, bool)> {
    let mut out = Vec::new();
    let (mut is_test, mut ignored) = (false, false);
    for line in source.lines() {
        let t = line.trim();
        if t.starts_with("#[test]") {
            is_test = true;
        } else if t.starts_with("#[ignore") {
            ignored = true;
        } else if t.starts_with("#[") || t.starts_with("//") || t.is_empty() {
            // Other attributes and comments between the attributes and the function.
        } else {
            if is_test {
                let name = t.split("fn ").nth(1).map(|r| {
                    r.split(|c: char| !c.is_alphanumeric() && c != '_')
                        .next()
                        .unwrap_or("")
                });
                if let Some(name) = name.filter(|n| !n.is_empty()) {
                    out.push((name.to_string(), ignored));
                }
            }
            is_test = false;
            ignored = false;
        }
    }
    out
}

/// The lines of a doc with an inline code span that continues on the next line joined
/// to it (a wrapped `` `cargo test --test\n name` ``), numbered by their first line. Code
/// blocks are left as they are.
fn logical_lines(lines: &[(usize, String)]) -> Vec<(usize, String)> {
    let mut out: Vec<(usize, String)> = Vec::new();
    let mut open = false;
    let mut in_code = false;
    for (n, line) in lines {
        let fence = line.trim_start().starts_with("```");
        if open && !fence && !in_code {
            let last = out.last_mut().expect("an open span has a line");
            last.1.push(' ');
            last.1.push_str(line.trim_start());
        } else {
            out.push((*n, line.clone()));
        }
        if fence {
            in_code = !in_code;
            open = false;
        } else if !in_code {
            let ticks = out.last().map_or(0, |(_, l)| l.matches('`').count());
            open = ticks % 2 == 1;
        }
    }
    out
}

/// The pieces of `line` between backticks.
fn backticked(line: &str) -> Vec<String> {
    line.split('`')
        .skip(1)
        .step_by(2)
        .map(String::from)
        .collect()
}

/// `cmd` without a trailing shell comment.
fn strip_comment(cmd: &str) -> &str {
    match cmd.find(" #") {
        Some(i) => &cmd[..i],
        None => cmd,
    }
}

/// Paths cited in `line`: tokens that start with a top-level entry of the repository
/// followed by `/`, or name a root file (`README.md`, `Cargo.toml`, …) on their own.
fn cited_paths(line: &str, top: &BTreeSet<String>) -> Vec<String> {
    let mut out = Vec::new();
    let separators = |c: char| c.is_whitespace() || "`()[]<>\"',;|".contains(c);
    for token in line.split(separators) {
        // `path:line`, `path#anchor`, `file.rs::item`, a trailing full stop.
        let token = token.split("::").next().unwrap_or("");
        let token = token.split(['#']).next().unwrap_or("");
        let token = match token.rsplit_once(':') {
            Some((p, n)) if n.chars().all(|c| c.is_ascii_digit()) => p,
            _ => token,
        };
        let token = token.trim_end_matches(['.', ':']);
        if token.is_empty() || token.contains("://") || placeholder(token) {
            continue;
        }
        let Some(first) = token.split('/').next() else {
            continue;
        };
        let is_path = token.contains('/') && top.contains(first) && first != "target";
        let is_root_file = !token.contains('/')
            && top.contains(token)
            && (token.ends_with(".md")
                || token.ends_with(".toml")
                || token.ends_with(".x")
                || token == "build.rs");
        let is_root_doc = !token.contains('/')
            && token.ends_with(".md")
            && token.chars().next().is_some_and(|c| c.is_ascii_uppercase());
        if is_path || is_root_file || is_root_doc {
            out.push(token.to_string());
        }
    }
    out
}

/// True for a template rather than a name: `NAME`, `…`, `<file>`, `{a,b}`, `$VAR`.
fn placeholder(token: &str) -> bool {
    const NAMES: [&str; 6] = [
        "README",
        "CHANGELOG",
        "STABILITY",
        "BENCHMARKS",
        "BAD",
        "INPUT",
    ];
    token.contains(['…', '<', '{', '$'])
        || token.split(['/', '.', '-', '_']).any(|w| {
            w.len() >= 2 && w.chars().all(|c| c.is_ascii_uppercase()) && !NAMES.contains(&w)
        })
}

/// The relative targets of the Markdown links of `line` (`[text](target)`) that name
/// files: not web addresses, not anchors, not rustdoc's intra-doc links
/// (`crate::Item`, `Self::f`, `super`).
fn markdown_links(line: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut rest = line;
    while let Some(i) = rest.find("](") {
        let after = &rest[i + 2..];
        let Some(end) = after.find(')') else { break };
        let target = after[..end].split('#').next().unwrap_or("").trim();
        let intra_doc = target.contains("::") || !target.contains(['/', '.']);
        let web = target.contains("://") || target.starts_with("mailto:");
        if !target.is_empty() && !web && !intra_doc {
            out.push(target.to_string());
        }
        rest = &after[end..];
    }
    out
}

/// Test names cited in `line`: backticked snake_case names with at least two
/// underscores. `true` when the word "test" stands shortly before (an explicit citation,
/// which must exist); otherwise the name counts only if a test has it.
fn cited_tests(line: &str) -> Vec<(String, bool)> {
    let mut out = Vec::new();
    let pieces: Vec<&str> = line.split('`').collect();
    for k in (1..pieces.len()).step_by(2) {
        let name = pieces[k];
        let snake = name
            .chars()
            .all(|c| c.is_ascii_lowercase() || c.is_ascii_digit() || c == '_')
            && name.matches('_').count() >= 2
            && name.chars().next().is_some_and(|c| c.is_ascii_lowercase());
        if !snake {
            continue;
        }
        let before = pieces[k - 1];
        let tail: String = before
            .chars()
            .rev()
            .take(40)
            .collect::<Vec<_>>()
            .into_iter()
            .rev()
            .collect();
        let explicit = tail.contains("test `")
            || tail.trim_end().ends_with("test")
            || tail.trim_end().ends_with("tests");
        out.push((name.to_string(), explicit));
    }
    out
}

/// True when `text` says that something is ignored.
fn mentions_ignore(text: &str) -> bool {
    text.contains("ignore")
}

/// True when `line` calls the test `name` ignored: "ignored" within the 60 characters
/// before its citation.
fn calls_ignored(line: &str, name: &str) -> bool {
    let Some(at) = line.find(&format!("`{name}`")) else {
        return false;
    };
    let start = line[..at]
        .char_indices()
        .rev()
        .nth(59)
        .map_or(0, |(i, _)| i);
    let before = &line[start..at];
    let after = &line[at + name.len() + 2..];
    let said_after = [" is ignored", " (ignored", ", ignored", " is #[ignore]d"]
        .iter()
        .any(|s| after.starts_with(s));
    said_after
        || before.contains("ignored")
            && !before.contains("not ignored")
            && !before.contains("no longer ignored")
}

/// `*` matches any run of characters other than `/`.
fn glob(pattern: &str, text: &str) -> bool {
    match pattern.split_once('*') {
        None => pattern == text,
        Some((head, tail)) => {
            let Some(rest) = text.strip_prefix(head) else {
                return false;
            };
            (0..=rest.len())
                .filter(|&i| rest.is_char_boundary(i) && !rest[..i].contains('/'))
                .any(|i| glob(tail, &rest[i..]))
        }
    }
}

/// A relative path with `.` and `..` resolved, or `None` when it climbs above the root.
fn normalise(path: &Path) -> Option<String> {
    let mut parts: Vec<String> = Vec::new();
    for c in path.components() {
        match c {
            Component::CurDir => {}
            Component::ParentDir => {
                parts.pop()?;
            }
            Component::Normal(s) => parts.push(s.to_string_lossy().into_owned()),
            Component::RootDir | Component::Prefix(_) => return None,
        }
    }
    Some(parts.join("/"))
}

/// The value of `key` in `[section]` of a TOML text (a quoted string).
fn toml_value(toml: &str, section: &str, key: &str) -> Option<String> {
    let mut here = false;
    for line in toml.lines() {
        let t = line.trim();
        if t.starts_with('[') {
            here = t == format!("[{section}]");
        } else if here
            && let Some((k, v)) = t.split_once('=')
            && k.trim() == key
        {
            return Some(v.trim().trim_matches('"').to_string());
        }
    }
    None
}

/// The keys of `[section]` of a TOML text.
fn toml_keys(toml: &str, section: &str) -> BTreeSet<String> {
    let mut here = false;
    let mut out = BTreeSet::new();
    for line in toml.lines() {
        let t = line.trim();
        if t.starts_with('[') {
            here = t == format!("[{section}]");
        } else if here
            && !t.starts_with('#')
            && let Some((k, _)) = t.split_once('=')
        {
            out.insert(k.trim().to_string());
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn top() -> BTreeSet<String> {
        ["src", "tests", "README.md", "Cargo.toml", ".ci", "scripts"]
            .iter()
            .map(|s| s.to_string())
            .collect()
    }

    #[test]
    fn paths_are_found_in_prose_and_code() {
        let line = "see `tests/golden.rs:12`, src/knob/ and README.md; not target/tour/ nor https://x.org/src/a";
        assert_eq!(
            cited_paths(line, &top()),
            ["tests/golden.rs", "src/knob/", "README.md"]
        );
        assert_eq!(
            cited_paths("`src/kernel.rs::respond`.", &top()),
            ["src/kernel.rs"]
        );
        assert_eq!(cited_paths("the CHANGELOG.md", &top()), ["CHANGELOG.md"]);
    }

    #[test]
    fn tests_are_cited_by_name() {
        assert_eq!(
            cited_tests("(ignored failing test `a_value_never_drifts`; `SpringValue` and `x_y`)"),
            [("a_value_never_drifts".to_string(), true)]
        );
        assert_eq!(
            cited_tests("the function `step_in_place_now`"),
            [("step_in_place_now".to_string(), false)]
        );
        assert!(calls_ignored("ignored failing test `a_b_c`", "a_b_c"));
        assert!(!calls_ignored(
            "the test `a_b_c` runs; others are ignored",
            "a_b_c"
        ));
        assert!(calls_ignored("the test `a_b_c` is ignored", "a_b_c"));
    }

    #[test]
    fn test_functions_and_their_ignores() {
        let src = "#[test]\nfn runs() {}\n\n#[test]\n#[ignore = \"slow\"]\n// why\nfn slow() {}\nfn helper() {}\n proptest! {\n #[test]\n fn prop(x in 0..1) {}\n }";
        assert_eq!(
            test_fns(src),
            [
                ("runs".to_string(), false),
                ("slow".to_string(), true),
                ("prop".to_string(), false)
            ]
        );
    }

    #[test]
    fn wrapped_code_spans_are_joined() {
        let lines: Vec<(usize, String)> = ["a `cargo test --test", "  x` b", "```", "`c", "```"]
            .iter()
            .enumerate()
            .map(|(i, l)| (i + 1, l.to_string()))
            .collect();
        let joined = logical_lines(&lines);
        assert_eq!(joined[0], (1, "a `cargo test --test x` b".to_string()));
        assert_eq!(joined.len(), 4);
    }

    #[test]
    fn globs_and_normalisation() {
        assert!(glob("target/cost/*.csv", "target/cost/m0.csv"));
        assert!(glob("tests/knob_*", "tests/knob_fixed.rs"));
        assert!(!glob("tests/*.rs", "tests/a/b.rs"));
        assert_eq!(
            normalise(Path::new("docs/../README.md")).as_deref(),
            Some("README.md")
        );
        assert_eq!(normalise(Path::new("../outside/x.md")), None);
        assert_eq!(
            markdown_links("[a](docs/x.md#y), [b](https://e.org), [c](crate::X), [d](self)"),
            ["docs/x.md"]
        );
        assert!(placeholder("examples/NAME.rs") && placeholder("…") && !placeholder("README.md"));
    }
}
