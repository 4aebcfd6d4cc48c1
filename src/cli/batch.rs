//! `ltikit analyze --batch FILE.jsonl`: one plant record per line (the plant-file schema in
//! JSON: `{"num": [...], "den": [...], "name": "..."}` or `{"model": ..., "params": {...}}`),
//! one JSON line out per plant — the `analyze` contract plus `margins` — in input order,
//! computed on all cores. A bad line gives an error record and the batch goes on.

use anyhow::{Context, Result};
use indicatif::{ProgressBar, ProgressStyle};
use rayon::prelude::*;
use serde_json::{Value, json};
use std::io::{BufRead, IsTerminal, Read, Write};

use super::analyze::json::AnalyzeJson;
use super::output::json_value;
use crate::lti::Plant;
use crate::lti::plant::MAX_RECORD_BYTES;

/// The record for one input line (1-based `line`).
fn record(line: usize, text: &str) -> Value {
    let plant = match Plant::from_json_line_at(text, Some(line)) {
        Ok(p) => p,
        Err(e) => return json!({"line": line, "error": super::one_line(&e.into())}),
    };
    let result = (|| -> Result<Value> {
        let f = plant.factored()?;
        let a = f.analyze()?;
        let mut v = json_value(&AnalyzeJson::from(&a))?;
        if let Value::Object(map) = &mut v {
            // margins that cannot be computed do not take the analysis down
            match f.margins() {
                Ok(m) => {
                    map.insert("margins".into(), json_value(&m)?);
                }
                Err(e) => {
                    map.insert("margins".into(), Value::Null);
                    map.insert("margins_note".into(), json!(format!("not computed: {e}")));
                }
            }
        }
        Ok(v)
    })();
    let mut out = serde_json::Map::new();
    out.insert("line".into(), json!(line));
    // the domain of the record, as in every plant document
    out.insert("dt".into(), json!(plant.domain().dt()));
    if plant.delay() > 0.0 {
        // the dead time the analyses read (every instant of the step metrics includes it)
        out.insert("delay".into(), json!(plant.delay()));
    }
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

/// Lines computed in parallel at a time, and the bytes of text they may hold: memory stays
/// that of one chunk (at most 64 MiB of input lines, not 1024 lines of 1 MiB each).
const CHUNK: usize = 1024;
/// Bytes of input text held by one chunk (a chunk ends early when its lines reach this).
const CHUNK_BYTES: usize = 64 << 20;

/// Reads one line of at most [`MAX_RECORD_BYTES`] into `buf` (without the newline); `false`
/// at the end of the input. A longer line or a NUL byte (not text: `/dev/zero`) stops the
/// batch with an error naming the line.
fn read_line(r: &mut impl BufRead, buf: &mut Vec<u8>, line: usize) -> Result<bool> {
    buf.clear();
    let n = r
        .by_ref()
        .take(MAX_RECORD_BYTES + 1)
        .read_until(b'\n', buf)
        .with_context(|| format!("reading line {line}"))?;
    if n == 0 {
        return Ok(false);
    }
    if buf.last() == Some(&b'\n') {
        buf.pop();
    } else if buf.len() as u64 > MAX_RECORD_BYTES {
        anyhow::bail!(
            "line {line} is longer than the {} MiB a plant record may have",
            MAX_RECORD_BYTES >> 20
        );
    }
    if buf.contains(&0) {
        anyhow::bail!("line {line} holds a NUL byte: the batch input is not text");
    }
    Ok(true)
}

/// Runs a batch from a file, or from stdin for "-": read line by line (bounded), computed a
/// chunk at a time on all cores, written in input order.
pub fn run(source: &str) -> Result<()> {
    let mut reader: Box<dyn BufRead> = if source == "-" {
        Box::new(std::io::BufReader::new(std::io::stdin().lock()))
    } else {
        let f = std::fs::File::open(source).with_context(|| format!("cannot open {source}"))?;
        Box::new(std::io::BufReader::new(f))
    };
    let bar = if std::io::stderr().is_terminal() {
        let b = ProgressBar::new_spinner();
        if let Ok(style) = ProgressStyle::with_template("{spinner} {pos} plants ({per_sec})") {
            b.set_style(style);
        }
        Some(b)
    } else {
        None
    };
    let mut stdout = std::io::BufWriter::new(std::io::stdout().lock());
    let mut buf = Vec::new();
    let mut line = 0usize;
    let mut done = false;
    while !done {
        let mut work: Vec<(usize, String)> = Vec::with_capacity(CHUNK);
        let mut bytes = 0usize;
        while work.len() < CHUNK && bytes < CHUNK_BYTES {
            line += 1;
            if !read_line(&mut reader, &mut buf, line)? {
                done = true;
                break;
            }
            let text = String::from_utf8_lossy(&buf);
            if !text.trim().is_empty() {
                bytes += text.len();
                work.push((line, text.into_owned()));
            }
        }
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
        for l in out {
            if let Err(e) = writeln!(stdout, "{l}") {
                if e.kind() == std::io::ErrorKind::BrokenPipe {
                    return Ok(());
                }
                return Err(e.into());
            }
        }
    }
    if let Some(b) = bar {
        b.finish_and_clear();
    }
    match stdout.flush() {
        Err(e) if e.kind() != std::io::ErrorKind::BrokenPipe => Err(e.into()),
        _ => Ok(()),
    }
}
