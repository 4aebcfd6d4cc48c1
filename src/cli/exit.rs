//! How the program ends: the exit code (0, 1, or 2 for usage errors), one error line on
//! stderr, the warnings of a command that succeeded, and one line instead of a panic trace.

use super::commands::{parse, run};

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
    let cli = match parse(std::env::args_os()) {
        Ok(c) => c,
        Err(e) if e.use_stderr() => {
            eprintln!("error: {}", usage_line(&e));
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
            eprintln!("error: {}", error_line(&e));
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

/// A usage error of the argument parser on one line: its first line (with the arguments it
/// lists, such as the missing ones), its tip if it has one, and where to look, with offending
/// text abbreviated.
fn usage_line(e: &clap::Error) -> String {
    use clap::error::{ContextKind, ContextValue, ErrorKind};
    if e.kind() == ErrorKind::MissingRequiredArgument {
        if let Some(ContextValue::Strings(args)) = e.get(ContextKind::InvalidArg) {
            let (n, list) = (args.len(), args.join(", "));
            let what = if n == 1 {
                "a required argument was not given"
            } else {
                "required arguments were not given"
            };
            return one_line_net(&format!("{what}: {list}; see --help"));
        }
    }
    usage_text_line(&e.to_string())
}

/// [`usage_line`] from the parser's rendered text: a first line ending in ':' takes the
/// indented lines that follow (the list it announces).
fn usage_text_line(text: &str) -> String {
    let lines: Vec<&str> = text.lines().map(str::trim_end).collect();
    let Some(first_at) = lines.iter().position(|l| !l.trim().is_empty()) else {
        return "invalid arguments; see --help".into();
    };
    let mut first = lines[first_at]
        .trim()
        .trim_start_matches("error:")
        .trim()
        .to_string();
    if first.ends_with(':') {
        let listed: Vec<&str> = lines[first_at + 1..]
            .iter()
            .take_while(|l| l.starts_with(' ') && !l.trim().is_empty())
            .map(|l| l.trim())
            .collect();
        if !listed.is_empty() {
            first.push(' ');
            first.push_str(&listed.join(", "));
        }
    }
    let mut out = abbreviate_quoted(&first);
    if let Some(tip) = lines
        .iter()
        .map(|l| l.trim())
        .find(|l| l.starts_with("tip:"))
    {
        out.push_str(&format!(" ({})", abbreviate_quoted(tip)));
    }
    out.push_str("; see --help");
    one_line_net(&out)
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

/// The error and its causes on one line, as the command line prints it: the library's field
/// names as flags ([`FIELD_FLAGS`]; not inside a plant file's or batch line's error, whose
/// keys are the file's), every long run of characters abbreviated.
pub fn error_line(e: &anyhow::Error) -> String {
    let mut parts: Vec<String> = Vec::new();
    for cause in e.chain() {
        let mut s = cause.to_string();
        let record = matches!(
            cause.downcast_ref::<crate::LtiError>(),
            Some(crate::LtiError::BadRecord { .. } | crate::LtiError::Io { .. })
        );
        if !record {
            s = flags_for_fields(&s);
        }
        if !parts.iter().any(|p| p.contains(&s)) {
            parts.push(s);
        }
        if record {
            break;
        }
    }
    one_line_net(&parts.join(": "))
}

/// The error and its causes on one line (as [`error_line`]).
pub(crate) fn one_line(e: &anyhow::Error) -> String {
    error_line(e)
}

/// The library names the fields of its input (`` `den` ``, `` `points` ``, `` `size` ``); the
/// command line names them by its flags. One table, used wherever an error is printed.
pub const FIELD_FLAGS: &[(&str, &str)] = &[
    ("num", "--num"),
    ("den", "--den"),
    ("a", "--a"),
    ("b", "--b"),
    ("c", "--c"),
    ("d", "--d"),
    ("param", "--param"),
    ("model", "--model"),
    ("controller", "--controller"),
    ("channel", "--channel"),
    ("points", "--points"),
    ("t", "--t"),
    ("w", "--w"),
    ("size", "--size"),
    ("title", "--title"),
    ("font_scale", "--font-scale"),
    ("max_gains", "--max-gains"),
    ("max_steps", "--max-steps"),
    ("input_file", "--input-file"),
    ("plant", "--plant"),
    ("batch", "--batch"),
    ("x0", "--x0"),
    ("ic", "--ic"),
    ("u", "--u"),
    ("input", "--input"),
    ("t_end", "--t-end"),
    ("wmin", "--wmin"),
    ("wmax", "--wmax"),
    ("vmax", "--vmax"),
    ("gain", "--gain"),
    ("rtol", "--rtol"),
    ("atol", "--atol"),
    ("phase", "--phase"),
    ("method", "--method"),
    ("prewarp", "--prewarp"),
    ("dt", "--dt"),
    ("delay", "--delay"),
    ("pade", "--pade"),
    ("order", "--order"),
    ("poles", "--poles"),
    ("q", "--q"),
    ("r", "--r"),
    ("s", "--s"),
    ("qn", "--qn"),
    ("rn", "--rn"),
    ("nn", "--nn"),
    ("noise_input", "--noise-input"),
];

/// The flag of a library field name, if the command line has one.
pub fn flag_of(field: &str) -> Option<&'static str> {
    FIELD_FLAGS
        .iter()
        .find(|(f, _)| *f == field)
        .map(|(_, flag)| *flag)
}

/// `text` with every `` `field` `` of [`FIELD_FLAGS`] written as its flag.
///
/// ```
/// use ltikit::cli::flags_for_fields;
/// assert_eq!(flags_for_fields("`den`: 'x' is not a number"), "--den: 'x' is not a number");
/// assert_eq!(flags_for_fields("`other` stays"), "`other` stays");
/// ```
pub fn flags_for_fields(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    let mut rest = text;
    while let Some(i) = rest.find('`') {
        out.push_str(&rest[..i]);
        let after = &rest[i + 1..];
        match after.find('`').map(|j| (&after[..j], j)) {
            Some((name, j)) => match flag_of(name) {
                Some(flag) => {
                    out.push_str(flag);
                    rest = &after[j + 1..];
                }
                None => {
                    out.push('`');
                    rest = after;
                }
            },
            None => {
                out.push('`');
                rest = after;
            }
        }
    }
    out.push_str(rest);
    out
}

/// The last guard of every printed error: one line, every run of more than 120 characters
/// without a space abbreviated (an echoed input the message did not cut), and the whole line
/// at most 2000 characters.
fn one_line_net(text: &str) -> String {
    let flat = text.replace(['\n', '\r'], " ");
    let words: Vec<String> = flat
        .split(' ')
        .map(|w| {
            if w.chars().count() > 120 {
                crate::error::abbreviate(w)
            } else {
                w.to_string()
            }
        })
        .collect();
    let line = words.join(" ");
    let n = line.chars().count();
    if n <= 2000 {
        return line;
    }
    let head: String = line.chars().take(1900).collect();
    format!("{head}… ({n} characters)")
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
    use crate::cli::commands::parse;

    #[test]
    fn usage_errors_fit_on_one_line() {
        let e = parse(["ltikit", "analyze", "--bogus"]).unwrap_err();
        let l = usage_line(&e);
        assert!(
            !l.contains('\n') && l.contains("--bogus") && l.ends_with("see --help"),
            "{l}"
        );
        let long = format!("--{}", "x".repeat(10_000));
        let e = parse(["ltikit", "analyze", &long]).unwrap_err();
        let l = usage_line(&e);
        assert!(l.len() < 300, "{l}");
        let e = parse(["ltikit", "analyze", "--den"]).unwrap_err();
        assert!(usage_line(&e).contains("--den"));
    }

    /// Issue 25: "the following required arguments were not provided:; see --help" dropped
    /// the names.
    #[test]
    fn a_missing_argument_is_named() {
        let e = parse(["ltikit", "bode", "--den", "1 1"]).unwrap_err();
        assert_eq!(
            usage_line(&e),
            "a required argument was not given: --output <FILE.png>; see --help"
        );
        let e = parse(["ltikit", "linearize"]).unwrap_err();
        assert_eq!(
            usage_line(&e),
            "a required argument was not given: <MODEL>; see --help"
        );
        let e = parse(["ltikit", "mems-pullin"]).unwrap_err();
        assert!(usage_line(&e).contains("--output <FILE.png>"));
        // a negative number is a value
        assert!(parse(["ltikit", "routh", "--den", "1 1", "--gain", "-1"]).is_ok());
        // the text form joins an announced list too
        assert_eq!(
            usage_text_line("error: the following were wrong:\n  --a\n  --b\n\nUsage: x"),
            "the following were wrong: --a, --b; see --help"
        );
    }

    /// Issue 25: `-o x.jpg` wrote a PNG under a .jpg name.
    #[test]
    fn pictures_are_png_files() {
        for cmd in [
            vec!["bode", "--den", "1 1"],
            vec!["step", "--den", "1 1"],
            vec!["pzmap", "--den", "1 1"],
            vec!["nyquist", "--den", "1 1"],
            vec!["rlocus", "--den", "1 1"],
            vec!["simulate", "pendulum"],
            vec!["mems-pullin"],
        ] {
            for bad in ["x.jpg", "x.PNG.txt", "x", "dir/"] {
                let mut args = vec!["ltikit"];
                args.extend(&cmd);
                args.extend(["-o", bad]);
                let e = parse(args).unwrap_err();
                let l = usage_line(&e);
                assert!(
                    e.kind() == clap::error::ErrorKind::ValueValidation
                        && l.contains("PNG")
                        && !l.contains('\n'),
                    "{cmd:?} {bad}: {l}"
                );
            }
            let mut args = vec!["ltikit"];
            args.extend(&cmd);
            args.extend(["-o", "x.PNG"]);
            assert!(parse(args).is_ok(), "{cmd:?}");
        }
    }

    #[test]
    fn fields_become_flags_but_not_in_records() {
        let e: anyhow::Error = crate::LtiError::bad_number("`den`", "x", "is not a number").into();
        assert_eq!(error_line(&e), "--den: 'x' is not a number");
        let e: anyhow::Error = crate::LtiError::BadRecord {
            location: "p.toml, line 2, column 1".into(),
            message: "`den` must be a list of numbers".into(),
        }
        .into();
        assert_eq!(
            error_line(&e),
            "p.toml, line 2, column 1: `den` must be a list of numbers"
        );
        // every field the library names has a flag
        for l in crate::limits::LIMITS {
            for f in l.fields {
                assert!(flag_of(f).is_some(), "{} names {f}", l.name);
            }
        }
    }

    #[test]
    fn long_runs_are_cut_and_lines_bounded() {
        let e = anyhow::anyhow!("unknown thing {}", "y".repeat(5000));
        let l = error_line(&e);
        assert!(l.contains("… (5000 characters)") && l.len() < 300, "{l}");
        let e = anyhow::anyhow!("{}", "word ".repeat(2000));
        assert!(error_line(&e).chars().count() < 2000);
    }
}
