//! How the program ends: the exit code (0, 1, or 2 for usage errors), one error line on
//! stderr, the warnings of a command that succeeded, and one line instead of a panic trace.

use clap::Parser;

use super::commands::{Cli, run};

/// A usage error (exit code 2): a missing or inconsistent option, as opposed to bad values.
#[derive(Debug)]
pub struct UsageError(pub String);

impl std::fmt::Display for UsageError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for UsageError {}

/// Entry point of the binary: parses the arguments, runs the command, returns the exit code.
pub fn main() -> i32 {
    install_panic_hook();
    let cli = match Cli::try_parse() {
        Ok(c) => c,
        Err(e) if e.use_stderr() => {
            eprintln!("error: {}", usage_line(&e.to_string()));
            return 2;
        }
        Err(e) => {
            // --help, --version
            let _ = e.print();
            return 0;
        }
    };
    let result = run(cli);
    let warnings = take_warnings();
    match result {
        Ok(()) => {
            for w in warnings {
                eprintln!("warning: {w}");
            }
            0
        }
        Err(e) => {
            // a failing command says one line: the error (its warnings are dropped)
            eprintln!("error: {}", one_line(&e));
            if e.downcast_ref::<UsageError>().is_some() {
                2
            } else {
                1
            }
        }
    }
}

/// Warnings of the running command, printed to stderr after it succeeds (a failing command
/// prints only its error line).
static WARNINGS: std::sync::Mutex<Vec<String>> = std::sync::Mutex::new(Vec::new());

/// Records a warning for the end of the command.
pub(crate) fn warn(message: String) {
    if let Ok(mut w) = WARNINGS.lock() {
        w.push(message);
    }
}

/// The recorded warnings, emptied.
fn take_warnings() -> Vec<String> {
    WARNINGS
        .lock()
        .map(|mut w| std::mem::take(&mut *w))
        .unwrap_or_default()
}

/// A usage error of the argument parser on one line: its first line, its tip if it has one,
/// and where to look, with offending text abbreviated.
fn usage_line(text: &str) -> String {
    let mut lines = text.lines().map(str::trim).filter(|l| !l.is_empty());
    let first = lines
        .next()
        .unwrap_or("invalid arguments")
        .trim_start_matches("error:")
        .trim();
    let mut out = abbreviate_quoted(first);
    if let Some(tip) = lines.find(|l| l.starts_with("tip:")) {
        out.push_str(&format!(" ({})", abbreviate_quoted(tip)));
    }
    out.push_str("; see --help");
    out
}

/// `text` with every quoted part cut to [`crate::error::TOKEN_SHOWN`] characters.
fn abbreviate_quoted(text: &str) -> String {
    let mut out = String::new();
    for (i, part) in text.split('\'').enumerate() {
        if i > 0 {
            out.push('\'');
        }
        if i % 2 == 1 {
            out.push_str(&crate::error::abbreviate(part));
        } else {
            out.push_str(part);
        }
    }
    out
}

/// The error and its causes on one line.
pub(crate) fn one_line(e: &anyhow::Error) -> String {
    let mut parts: Vec<String> = Vec::new();
    for cause in e.chain() {
        let s = cause.to_string();
        if !parts.iter().any(|p| p.contains(&s)) {
            parts.push(s);
        }
    }
    parts.join(": ").replace('\n', " ")
}

/// A panic is a bug; print one line instead of a trace.
fn install_panic_hook() {
    std::panic::set_hook(Box::new(|info| {
        let msg = info
            .payload()
            .downcast_ref::<&str>()
            .map(|s| s.to_string())
            .or_else(|| info.payload().downcast_ref::<String>().cloned())
            .unwrap_or_else(|| "unknown".into());
        let at = info
            .location()
            .map(|l| format!(" at {}:{}", l.file(), l.line()))
            .unwrap_or_default();
        eprintln!("error: internal error (a bug, please report it): {msg}{at}");
    }));
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn usage_errors_fit_on_one_line() {
        let e = Cli::try_parse_from(["ltikit", "analyze", "--bogus"]).unwrap_err();
        let l = usage_line(&e.to_string());
        assert!(
            !l.contains('\n') && l.contains("--bogus") && l.ends_with("see --help"),
            "{l}"
        );
        let long = format!("--{}", "x".repeat(10_000));
        let e = Cli::try_parse_from(["ltikit", "analyze", &long]).unwrap_err();
        let l = usage_line(&e.to_string());
        assert!(l.len() < 300, "{l}");
        let e = Cli::try_parse_from(["ltikit", "analyze", "--den"]).unwrap_err();
        assert!(usage_line(&e.to_string()).contains("--den"));
    }
}
