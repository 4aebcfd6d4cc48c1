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

/// Serialises `value` as JSON (serde_json writes non-finite floats as `null`) and prints it
/// with a trailing newline: objects indented, arrays of numbers on one line (`[re, im]`
/// pairs, matrix rows, sample vectors).
pub fn print_json<T: Serialize>(value: &T) -> Result<()> {
    let v = serde_json::to_value(value)?;
    let mut s = String::new();
    pretty(&v, 0, &mut s);
    s.push('\n');
    print(&s)
}

fn is_scalar(v: &serde_json::Value) -> bool {
    !matches!(
        v,
        serde_json::Value::Array(_) | serde_json::Value::Object(_)
    )
}

fn pretty(v: &serde_json::Value, indent: usize, out: &mut String) {
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

/// A finite number or `None` (JSON null).
pub fn finite(x: f64) -> Option<f64> {
    x.is_finite().then_some(x)
}

/// A complex number as the JSON pair `[re, im]`.
pub fn pair(z: num_complex::Complex64) -> [f64; 2] {
    [z.re, z.im]
}
