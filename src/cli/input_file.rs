//! An input signal read from a CSV file for `response --input-file`: columns t, u1 … um, one
//! sample a line; an optional header line (its first field not a number); blank lines and
//! lines starting with `#` are skipped. Errors name the file and the line.

use anyhow::{Result, bail};
use std::io::Read;
use std::path::Path;

use crate::analysis::ss::InputSignal;

pub use crate::limits::{MAX_INPUT_BYTES, MAX_INPUT_SAMPLES};

/// Reads `path` as the input signal of a model with `m` inputs.
pub fn read(path: &Path, m: usize) -> Result<InputSignal> {
    let name = path.display().to_string();
    let file = std::fs::File::open(path).map_err(|e| anyhow::anyhow!("{name}: {e}"))?;
    let mut text = String::new();
    file.take(MAX_INPUT_BYTES + 1)
        .read_to_string(&mut text)
        .map_err(|e| anyhow::anyhow!("{name}: {e}"))?;
    if text.len() as u64 > MAX_INPUT_BYTES {
        bail!("{name}: larger than {MAX_INPUT_BYTES} bytes (the input file limit)");
    }
    parse(&text, m).map_err(|e| anyhow::anyhow!("{name}: {e}"))
}

/// Parses CSV text (see the module documentation) for `m` inputs.
pub fn parse(text: &str, m: usize) -> Result<InputSignal> {
    let mut t = Vec::new();
    let mut u = Vec::new();
    let mut first = true;
    for (k, line) in text.lines().enumerate() {
        let line = line.trim();
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        let fields: Vec<&str> = line.split([',', ';', '\t']).map(str::trim).collect();
        let is_header = first && fields.first().is_some_and(|f| f.parse::<f64>().is_err());
        first = false;
        if is_header {
            continue;
        }
        if fields.len() != m + 1 {
            bail!(
                "line {}: {} values, expected {} (t, then u1…u{m})",
                k + 1,
                fields.len(),
                m + 1
            );
        }
        let mut row = Vec::with_capacity(m + 1);
        for f in &fields {
            let v: f64 = f.parse().map_err(|_| {
                anyhow::anyhow!(
                    "line {}: '{}' is not a number",
                    k + 1,
                    crate::error::abbreviate(f)
                )
            })?;
            if !v.is_finite() {
                bail!("line {}: {v} is not a finite number", k + 1);
            }
            row.push(v);
        }
        if let Some(&prev) = t.last()
            && row[0] <= prev
        {
            bail!(
                "line {}: t = {} does not increase (the previous sample is at t = {prev})",
                k + 1,
                row[0]
            );
        }
        if row[0] < 0.0 {
            bail!("line {}: t = {} is negative", k + 1, row[0]);
        }
        if t.len() == MAX_INPUT_SAMPLES {
            bail!(
                "line {}: more than {MAX_INPUT_SAMPLES} samples (the input file limit)",
                k + 1
            );
        }
        t.push(row[0]);
        u.push(row[1..].to_vec());
    }
    if t.len() < 2 {
        bail!("needs at least two samples (t, u1…u{m} per line)");
    }
    Ok(InputSignal { t, u })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn header_comments_and_errors_by_line() {
        let s = parse("t,u1,u2\n# a comment\n0, 1, 2\n\n0.5, 3, 4\n", 2).unwrap();
        assert_eq!(s.t, vec![0.0, 0.5]);
        assert_eq!(s.u[1], vec![3.0, 4.0]);
        let e = |text: &str| parse(text, 1).unwrap_err().to_string();
        assert!(
            e("0,1\n1,x\n").starts_with("line 2: 'x'"),
            "{}",
            e("0,1\n1,x\n")
        );
        assert!(e("0,1\n1,2,3\n").starts_with("line 2: 3 values, expected 2"));
        assert!(e("0,1\n0,2\n").starts_with("line 2: t = 0 does not increase"));
        assert!(e("0,1\n1,nan\n").starts_with("line 2: NaN"));
        assert!(e("-1,1\n").starts_with("line 1: t = -1 is negative"));
        assert!(e("0,1\n").contains("at least two samples"));
    }
}
