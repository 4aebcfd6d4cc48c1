//! `ltikit analyze --batch FILE.jsonl`: one plant record per line (the plant-file schema in
//! JSON: `{"num": [...], "den": [...], "name": "..."}` or `{"model": ..., "params": {...}}`),
//! one JSON line out per plant — the `analyze` contract plus `margins` — in input order,
//! computed on all cores. A bad line gives an error record and the batch goes on.

use anyhow::{Context, Result};
use indicatif::{ProgressBar, ProgressStyle};
use rayon::prelude::*;
use serde_json::{Value, json};
use std::io::{BufRead, IsTerminal, Write};

use super::analyze::AnalyzeJson;
use super::output::json_value;
use crate::lti::Plant;

/// The record for one input line (1-based `line`).
fn record(line: usize, text: &str) -> Value {
    let plant = match Plant::from_json_line(text) {
        Ok(p) => p,
        Err(e) => return json!({"line": line, "error": super::one_line(&e.into())}),
    };
    let result = (|| -> Result<Value> {
        let f = plant.factored()?;
        let a = f.analyze()?;
        let m = f.margins()?;
        let mut v = json_value(&AnalyzeJson::from(&a))?;
        if let Value::Object(map) = &mut v {
            map.insert("margins".into(), json_value(&m)?);
        }
        Ok(v)
    })();
    let mut out = serde_json::Map::new();
    out.insert("line".into(), json!(line));
    // a record's own name, never the generated one
    if let Some(n) = serde_json::from_str::<Value>(text)
        .ok()
        .and_then(|v| v.get("name").and_then(Value::as_str).map(String::from))
    {
        out.insert("name".into(), json!(n));
    }
    match result {
        Ok(Value::Object(map)) => out.extend(map),
        Ok(other) => {
            out.insert("result".into(), other);
        }
        Err(e) => {
            out.insert("error".into(), json!(super::one_line(&e)));
        }
    }
    Value::Object(out)
}

/// Runs a batch from a file, or from stdin for "-".
pub fn run(source: &str) -> Result<()> {
    let lines: Vec<String> = if source == "-" {
        std::io::stdin()
            .lock()
            .lines()
            .collect::<std::io::Result<_>>()
            .context("reading plants from stdin")?
    } else {
        let f = std::fs::File::open(source).with_context(|| format!("cannot open {source}"))?;
        std::io::BufReader::new(f)
            .lines()
            .collect::<std::io::Result<_>>()
            .with_context(|| format!("reading {source}"))?
    };
    let work: Vec<(usize, &str)> = lines
        .iter()
        .enumerate()
        .filter(|(_, l)| !l.trim().is_empty())
        .map(|(i, l)| (i + 1, l.as_str()))
        .collect();
    let bar = if std::io::stderr().is_terminal() {
        let b = ProgressBar::new(work.len() as u64);
        if let Ok(style) =
            ProgressStyle::with_template("{bar:40} {pos}/{len} plants ({per_sec}, eta {eta})")
        {
            b.set_style(style);
        }
        Some(b)
    } else {
        None
    };
    let out: Vec<String> = work
        .par_iter()
        .map(|(line, text)| {
            let s = serde_json::to_string(&record(*line, text))
                .unwrap_or_else(|e| format!("{{\"line\":{line},\"error\":\"{e}\"}}"));
            if let Some(b) = &bar {
                b.inc(1);
            }
            s
        })
        .collect();
    if let Some(b) = bar {
        b.finish_and_clear();
    }
    let mut stdout = std::io::BufWriter::new(std::io::stdout().lock());
    for l in out {
        if let Err(e) = writeln!(stdout, "{l}") {
            if e.kind() == std::io::ErrorKind::BrokenPipe {
                return Ok(());
            }
            return Err(e.into());
        }
    }
    match stdout.flush() {
        Err(e) if e.kind() != std::io::ErrorKind::BrokenPipe => Err(e.into()),
        _ => Ok(()),
    }
}
