//! Writing to stdout: whole documents at once (no partial JSON), quietly stopping on a closed
//! pipe (`ltikit … | head`), JSON without NaN/Infinity tokens.

use anyhow::Result;
use serde::Serialize;
use std::io::Write;

/// Prints `text` (a complete document) to stdout. A closed pipe is not an error.
pub fn print(text: &str) -> Result<()> {
    let mut out = std::io::stdout().lock();
    match out.write_all(text.as_bytes()).and_then(|_| out.flush()) {
        Ok(()) => Ok(()),
        Err(e) if e.kind() == std::io::ErrorKind::BrokenPipe => Ok(()),
        Err(e) => Err(e.into()),
    }
}

/// Output written as it is computed (large `freq`, `response` and `simulate` results), so the
/// memory stays that of one block. A closed pipe ends the output quietly: [`Stream::put`]
/// then returns `Ok(false)` and the caller stops computing.
pub struct Stream {
    out: std::io::BufWriter<std::io::StdoutLock<'static>>,
    closed: bool,
}

impl Stream {
    /// A stream to stdout.
    pub fn stdout() -> Stream {
        Stream {
            out: std::io::BufWriter::with_capacity(1 << 16, std::io::stdout().lock()),
            closed: false,
        }
    }

    /// Writes `text`; `Ok(false)` once the reader has gone.
    pub fn put(&mut self, text: &str) -> Result<bool> {
        if self.closed {
            return Ok(false);
        }
        match self.out.write_all(text.as_bytes()) {
            Ok(()) => Ok(true),
            Err(e) if e.kind() == std::io::ErrorKind::BrokenPipe => {
                self.closed = true;
                Ok(false)
            }
            Err(e) => Err(e.into()),
        }
    }

    /// Flushes (a closed pipe is not an error).
    pub fn finish(mut self) -> Result<()> {
        match self.out.flush() {
            Err(e) if e.kind() != std::io::ErrorKind::BrokenPipe => Err(e.into()),
            _ => Ok(()),
        }
    }
}

/// Serialises `value` as JSON (serde_json writes non-finite floats as `null`) and prints it
/// with a trailing newline: objects indented, arrays of numbers on one line (`[re, im]`
/// pairs, matrix rows, sample vectors).
pub fn print_json<T: Serialize>(value: &T) -> Result<()> {
    let mut v = json_value(value)?;
    with_dt(&mut v);
    let mut s = String::new();
    pretty(&v, 0, &mut s);
    s.push('\n');
    print(&s)
}

thread_local! {
    /// The sampling period of the plants this command read (`None`: continuous time).
    static DOCUMENT_DT: std::cell::Cell<Option<Option<f64>>> =
        const { std::cell::Cell::new(None) };
}

/// Records the domain of the plants a command analyses: every JSON document it prints then
/// starts with `"dt"` (the sampling period, `null` for continuous time), so a script knows
/// the domain without knowing the command. (Documents of commands that read no plant — the
/// nonlinear models — have no `"dt"`.)
pub fn set_document_dt(dt: Option<f64>) {
    DOCUMENT_DT.with(|c| c.set(Some(dt)));
}

thread_local! {
    /// The dead time of the plants this command read (0: none).
    static DOCUMENT_DELAY: std::cell::Cell<f64> = const { std::cell::Cell::new(0.0) };
}

/// Records the dead time of the plants a command analyses: every JSON document it prints then
/// carries `"delay"` (seconds) after `"dt"` when it is not 0.
pub fn set_document_delay(delay: f64) {
    DOCUMENT_DELAY.with(|c| c.set(delay));
}

/// Puts `"dt"` first in a document object that does not carry it yet.
fn with_dt(v: &mut serde_json::Value) {
    if let serde_json::Value::Object(map) = v
        && !map.contains_key("dt")
        && let Some(dt) = DOCUMENT_DT.with(|c| c.get())
    {
        let mut out = serde_json::Map::new();
        out.insert("dt".into(), serde_json::json!(dt));
        let delay = DOCUMENT_DELAY.with(|c| c.get());
        if delay > 0.0 && !map.contains_key("delay") {
            out.insert("delay".into(), serde_json::json!(delay));
        }
        out.extend(std::mem::take(map));
        *map = out;
    }
}

/// `value` as a JSON tree with every −0.0 written as 0.0 (a sign of zero is rounding, not
/// information, and `-0.0` in a contract surprises scripts).
pub fn json_value<T: Serialize>(value: &T) -> Result<serde_json::Value> {
    let mut v = serde_json::to_value(value)?;
    positive_zeros(&mut v);
    Ok(v)
}

fn positive_zeros(v: &mut serde_json::Value) {
    use serde_json::Value;
    match v {
        Value::Number(n) if n.as_f64().is_some_and(|x| x == 0.0 && x.is_sign_negative()) => {
            *v = Value::from(0.0);
        }
        Value::Array(items) => items.iter_mut().for_each(positive_zeros),
        Value::Object(map) => map.values_mut().for_each(positive_zeros),
        _ => {}
    }
}

fn is_scalar(v: &serde_json::Value) -> bool {
    !matches!(
        v,
        serde_json::Value::Array(_) | serde_json::Value::Object(_)
    )
}

pub fn pretty(v: &serde_json::Value, indent: usize, out: &mut String) {
    use serde_json::Value;
    let pad = |n: usize| "  ".repeat(n);
    match v {
        Value::Array(items) if items.iter().all(is_scalar) => {
            out.push('[');
            for (i, x) in items.iter().enumerate() {
                if i > 0 {
                    out.push_str(", ");
                }
                out.push_str(&x.to_string());
            }
            out.push(']');
        }
        Value::Array(items) => {
            out.push_str("[\n");
            for (i, x) in items.iter().enumerate() {
                out.push_str(&pad(indent + 1));
                pretty(x, indent + 1, out);
                if i + 1 < items.len() {
                    out.push(',');
                }
                out.push('\n');
            }
            out.push_str(&pad(indent));
            out.push(']');
        }
        Value::Object(map) if map.is_empty() => out.push_str("{}"),
        Value::Object(map) => {
            out.push_str("{\n");
            for (i, (k, x)) in map.iter().enumerate() {
                out.push_str(&pad(indent + 1));
                out.push_str(&Value::String(k.clone()).to_string());
                out.push_str(": ");
                pretty(x, indent + 1, out);
                if i + 1 < map.len() {
                    out.push(',');
                }
                out.push('\n');
            }
            out.push_str(&pad(indent));
            out.push('}');
        }
        scalar => out.push_str(&scalar.to_string()),
    }
}

/// A number as the JSON writer prints it: `null` when not finite, never `-0.0`.
pub fn json_number(x: f64) -> String {
    if !x.is_finite() {
        return "null".into();
    }
    let x = if x == 0.0 { 0.0 } else { x };
    serde_json::Value::from(x).to_string()
}

/// A finite number or `None` (JSON null).
pub fn finite(x: f64) -> Option<f64> {
    x.is_finite().then_some(x)
}

/// A complex number as the JSON pair `[re, im]`.
pub fn pair(z: num_complex::Complex64) -> [f64; 2] {
    [z.re, z.im]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn negative_zero_is_written_as_zero() {
        let v = json_value(&vec![-0.0f64, 1.0, -2.5]).unwrap();
        assert_eq!(v.to_string(), "[0.0,1.0,-2.5]");
        let v = json_value(&serde_json::json!({"a": [-0.0], "b": {"c": -0.0}})).unwrap();
        assert_eq!(v.to_string(), r#"{"a":[0.0],"b":{"c":0.0}}"#);
    }
}
