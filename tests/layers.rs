//! DESIGN §2: dependencies flow one way. A module may use only layers below (or equal to) its
//! own: error, numeric → poly → lti → analysis → nonlinear → plot → cli. Checked by reading the
//! `crate::…` paths in every source file. Also: only the CLI prints.

use std::fs;
use std::path::{Path, PathBuf};

fn layer(module: &str) -> Option<usize> {
    Some(match module {
        "error" | "fmt" | "limits" | "numeric" => 0,
        "poly" => 1,
        "lti" => 2,
        "analysis" => 3,
        "nonlinear" => 4,
        "plot" => 5,
        "cli" => 6,
        _ => return None,
    })
}

fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for e in fs::read_dir(dir).unwrap() {
        let p = e.unwrap().path();
        if p.is_dir() {
            rust_files(&p, out);
        } else if p.extension().is_some_and(|x| x == "rs") {
            out.push(p);
        }
    }
}

/// Top-level module a source file belongs to (None for lib.rs / main.rs).
fn module_of(path: &Path, src: &Path) -> Option<String> {
    let rel = path.strip_prefix(src).ok()?;
    let first = rel.components().next()?.as_os_str().to_str()?.to_string();
    let name = first.trim_end_matches(".rs").to_string();
    (name != "lib" && name != "main").then_some(name)
}

/// The crate-root re-exports of lib.rs (`pub use lti::{StateSpace, TransferFunction};`) as
/// (name, module): `crate::TransferFunction` is a use of `lti`.
fn root_reexports(lib: &str) -> Vec<(String, String)> {
    let mut out = Vec::new();
    for line in lib.lines().map(str::trim) {
        let Some(rest) = line.strip_prefix("pub use ") else {
            continue;
        };
        let rest = rest.trim_end_matches(';');
        let Some((module, items)) = rest.split_once("::") else {
            continue;
        };
        let items = items.trim_start_matches('{').trim_end_matches('}');
        for item in items.split(',') {
            let name = item.trim().rsplit("::").next().unwrap_or("").trim();
            if !name.is_empty() {
                out.push((name.to_string(), module.to_string()));
            }
        }
    }
    out
}

/// Every top-level module named in a `crate::X` path in the text (comments included on
/// purpose: a doc comment should not point upwards either); a crate-root re-export stands
/// for its module.
fn referenced_modules(text: &str, reexports: &[(String, String)]) -> Vec<String> {
    referenced(text)
        .into_iter()
        .map(|n| {
            reexports
                .iter()
                .find(|(name, _)| *name == n)
                .map_or(n, |(_, m)| m.clone())
        })
        .collect()
}

/// The text without its `#[cfg(test)]` items (a test module, or a single test-only method):
/// each is cut from the attribute to the end of its body, so production code after a
/// method-level `#[cfg(test)]` is still read.
fn without_test_items(text: &str) -> String {
    let mut out = String::new();
    let mut rest = text;
    while let Some(i) = rest.find("#[cfg(test)]") {
        out.push_str(&rest[..i]);
        let after = &rest[i..];
        let brace = after.find('{');
        let semi = after.find(';');
        let end = match (brace, semi) {
            (Some(b), Some(s)) if s < b => s + 1,
            (Some(b), _) => {
                let mut depth = 0usize;
                let mut end = after.len();
                for (k, ch) in after[b..].char_indices() {
                    match ch {
                        '{' => depth += 1,
                        '}' => {
                            depth -= 1;
                            if depth == 0 {
                                end = b + k + 1;
                                break;
                            }
                        }
                        _ => {}
                    }
                }
                end
            }
            (None, Some(s)) => s + 1,
            (None, None) => after.len(),
        };
        rest = &after[end..];
    }
    out.push_str(rest);
    out
}

#[test]
fn test_items_are_cut_and_the_rest_is_kept() {
    let src = "fn a() {}\n#[cfg(test)]\nfn b() { x(); }\nfn c() { println!(); }\n#[cfg(test)]\nmod tests { fn d() { if x { y } } }\nfn e() {}";
    let kept = without_test_items(src);
    assert!(kept.contains("fn a()") && kept.contains("fn c()") && kept.contains("fn e()"));
    assert!(!kept.contains("fn b()") && !kept.contains("fn d()"));
    let re = root_reexports(
        "pub use lti::{StateSpace, TransferFunction};\npub use poly::{MAX_ORDER, Poly, Root};",
    );
    assert!(re.contains(&("TransferFunction".into(), "lti".into())));
    assert_eq!(
        referenced_modules("use crate::{Root, analysis};", &re),
        vec!["poly".to_string(), "analysis".to_string()]
    );
}

/// Every top-level name in a `crate::X` path in the text.
fn referenced(text: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut rest = text;
    while let Some(i) = rest.find("crate::") {
        rest = &rest[i + "crate::".len()..];
        let name: String = rest
            .chars()
            .take_while(|c| c.is_alphanumeric() || *c == '_')
            .collect();
        if !name.is_empty() {
            out.push(name);
        }
        // `use crate::{a, b}` groups
        if rest.starts_with('{') {
            let end = rest.find('}').unwrap_or(rest.len());
            for part in rest[1..end].split(',') {
                let n: String = part
                    .trim()
                    .chars()
                    .take_while(|c| c.is_alphanumeric() || *c == '_')
                    .collect();
                if !n.is_empty() {
                    out.push(n);
                }
            }
        }
    }
    out
}

#[test]
fn dependencies_flow_one_way() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut files = Vec::new();
    rust_files(&src, &mut files);
    let reexports = root_reexports(&fs::read_to_string(src.join("lib.rs")).unwrap());
    assert!(
        reexports.iter().any(|(n, _)| n == "TransferFunction"),
        "lib.rs re-exports not read"
    );
    let mut violations = Vec::new();
    for f in &files {
        let Some(m) = module_of(f, &src) else {
            continue;
        };
        let Some(own) = layer(&m) else {
            violations.push(format!(
                "{}: module '{m}' has no layer in DESIGN §2",
                f.display()
            ));
            continue;
        };
        let text = fs::read_to_string(f).unwrap();
        for r in referenced_modules(&text, &reexports) {
            if let Some(l) = layer(&r)
                && l > own
            {
                violations.push(format!("{} ({m}) uses crate::{r}", f.display()));
            }
        }
    }
    assert!(
        violations.is_empty(),
        "layer violations:\n{}",
        violations.join("\n")
    );
}

/// Every source file below `cli` (lib.rs and main.rs excluded) with its text.
fn below_the_cli() -> Vec<(PathBuf, String)> {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut files = Vec::new();
    rust_files(&src, &mut files);
    files
        .into_iter()
        .filter(|f| module_of(f, &src).is_some_and(|m| m != "cli"))
        .map(|f| {
            let text = fs::read_to_string(&f).unwrap();
            (f, text)
        })
        .collect()
}

#[test]
fn only_the_cli_prints() {
    let mut offenders = Vec::new();
    for (f, text) in below_the_cli() {
        // Only non-test code: every `#[cfg(test)]` item cut out.
        let code = without_test_items(&text);
        for needle in ["println!", "eprintln!", "print!(", "eprint!(", "dbg!("] {
            if code.contains(needle) {
                offenders.push(format!("{} contains {needle}", f.display()));
            }
        }
    }
    assert!(offenders.is_empty(), "{}", offenders.join("\n"));
}

/// The string literals of Rust source `text` (comments skipped; escapes left as written;
/// raw strings included), each with its line number.
fn string_literals(text: &str) -> Vec<(usize, String)> {
    let b: Vec<char> = text.chars().collect();
    let mut out = Vec::new();
    let (mut i, mut line) = (0, 1);
    while i < b.len() {
        let c = b[i];
        let next = b.get(i + 1).copied();
        if c == '\n' {
            line += 1;
            i += 1;
        } else if c == '/' && next == Some('/') {
            while i < b.len() && b[i] != '\n' {
                i += 1;
            }
        } else if c == '/' && next == Some('*') {
            let mut depth = 0;
            while i < b.len() {
                if b[i] == '/' && b.get(i + 1) == Some(&'*') {
                    depth += 1;
                    i += 2;
                } else if b[i] == '*' && b.get(i + 1) == Some(&'/') {
                    depth -= 1;
                    i += 2;
                    if depth == 0 {
                        break;
                    }
                } else {
                    if b[i] == '\n' {
                        line += 1;
                    }
                    i += 1;
                }
            }
        } else if c == '\'' {
            // a char literal ('"', '\'') or a lifetime ('a): skip the char literal whole
            if next == Some('\\') {
                let end = (i + 2..b.len()).find(|&k| b[k] == '\'').unwrap_or(b.len());
                i = end + 1;
            } else if b.get(i + 2) == Some(&'\'') {
                i += 3;
            } else {
                i += 1;
            }
        } else if c == 'r'
            && (next == Some('"') || next == Some('#'))
            && (i == 0 || !(b[i - 1].is_alphanumeric() || b[i - 1] == '_'))
        {
            let hashes = b[i + 1..].iter().take_while(|&&h| h == '#').count();
            let open = i + 1 + hashes;
            if b.get(open) != Some(&'"') {
                i += 1;
                continue;
            }
            let close: String = std::iter::once('"')
                .chain(std::iter::repeat_n('#', hashes))
                .collect();
            let rest: String = b[open + 1..].iter().collect();
            let end = rest.find(&close).unwrap_or(rest.len());
            let lit: String = rest[..end].to_string();
            out.push((line, lit.clone()));
            line += lit.matches('\n').count();
            i = open + 1 + lit.chars().count() + close.chars().count();
        } else if c == '"' {
            let start_line = line;
            let mut lit = String::new();
            i += 1;
            while i < b.len() && b[i] != '"' {
                if b[i] == '\\' && i + 1 < b.len() {
                    lit.push(b[i]);
                    lit.push(b[i + 1]);
                    if b[i + 1] == '\n' {
                        line += 1;
                    }
                    i += 2;
                    continue;
                }
                if b[i] == '\n' {
                    line += 1;
                }
                lit.push(b[i]);
                i += 1;
            }
            i += 1;
            out.push((start_line, lit));
        } else {
            i += 1;
        }
    }
    out
}

/// True when `lit` holds a command-line flag: `--` followed by a letter.
fn has_flag(lit: &str) -> bool {
    lit.match_indices("--")
        .any(|(k, _)| lit[k + 2..].starts_with(|c: char| c.is_ascii_lowercase()))
}

#[test]
fn string_literals_are_found() {
    let src = "let a = \"--den\"; // \"--x\"\n/* \"--y\" */ let c = '\"'; let r = r#\"--raw \"q\"\"#;\nfn f<'a>() { \"b\\\"--c\" }";
    let lits: Vec<String> = string_literals(src).into_iter().map(|(_, l)| l).collect();
    assert_eq!(lits, vec!["--den", "--raw \"q\"", "b\\\"--c"]);
    assert!(has_flag("choose (--channel 1,2)") && !has_flag("a -- b") && !has_flag("x--1"));
}

/// Issue 25: library errors name fields (`den`, `channel`, `size`), the CLI maps them to its
/// flags in one table; no string literal below `cli` holds a flag (`"--den"`). Doc comments
/// may show command lines.
#[test]
fn no_cli_flags_below_the_cli() {
    let mut offenders = Vec::new();
    for (f, text) in below_the_cli() {
        for (line, lit) in string_literals(&text) {
            if has_flag(&lit) {
                offenders.push(format!("{}:{line}: \"{lit}\"", f.display()));
            }
        }
    }
    assert!(
        offenders.is_empty(),
        "CLI flags below cli (name the field instead, e.g. `den`):\n{}",
        offenders.join("\n")
    );
}
