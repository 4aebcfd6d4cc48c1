//! DESIGN §2: dependencies flow one way. A module may use only layers below (or equal to) its
//! own: error, numeric → poly → lti → analysis → nonlinear → plot → cli. Checked by reading the
//! `crate::…` paths in every source file. Also: only the CLI prints.

use std::fs;
use std::path::{Path, PathBuf};

fn layer(module: &str) -> Option<usize> {
    Some(match module {
        "error" | "numeric" => 0,
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

/// Every top-level module named in a `crate::X` path in the text (comments included on
/// purpose: a doc comment should not point upwards either).
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
        for r in referenced(&text) {
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

#[test]
fn only_the_cli_prints() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut files = Vec::new();
    rust_files(&src, &mut files);
    let mut offenders = Vec::new();
    for f in &files {
        let m = module_of(f, &src);
        if m.as_deref() == Some("cli") || m.is_none() {
            continue;
        }
        let text = fs::read_to_string(f).unwrap();
        // Only non-test code: cut at the first `#[cfg(test)]`.
        let code = text.split("#[cfg(test)]").next().unwrap_or("");
        for needle in ["println!", "eprintln!", "print!(", "eprint!(", "dbg!("] {
            if code.contains(needle) {
                offenders.push(format!("{} contains {needle}", f.display()));
            }
        }
    }
    assert!(offenders.is_empty(), "{}", offenders.join("\n"));
}
