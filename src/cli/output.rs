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

/// Serialises `value` as pretty JSON (serde_json writes non-finite floats as `null`) and prints
/// it with a trailing newline.
pub fn print_json<T: Serialize>(value: &T) -> Result<()> {
    let mut s = serde_json::to_string_pretty(value)?;
    s.push('\n');
    print(&s)
}

/// A finite number or `None` (JSON null).
pub fn finite(x: f64) -> Option<f64> {
    x.is_finite().then_some(x)
}

/// A complex number as the JSON pair `[re, im]`.
pub fn pair(z: num_complex::Complex64) -> [f64; 2] {
    [z.re, z.im]
}
