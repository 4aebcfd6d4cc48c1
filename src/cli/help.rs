//! Help text generated from the library's tables: the limits of a command's options
//! ([`crate::limits::LIMITS`] through [`super::FIELD_FLAGS`]) and the models with their
//! parameters, defaults and units (the model registry). Nothing here is written by hand, so
//! the help cannot drift from the code.

use crate::fmt::fmt_num;
use crate::limits::{LIMITS, amount};

/// "Limits (…):" and one line per limit of the options in `flags` (`--points`, …) of
/// `command`, leaving out a limit that names another command (`` `freq` ``) and not this one;
/// with no flags, every limit (the top-level help).
pub fn limits_text(command: &str, others: &[&String], flags: &[String]) -> String {
    let mut lines = Vec::new();
    for l in LIMITS {
        let names = |c: &str| {
            l.applies_to.contains(&format!("`{c}`")) || l.applies_to.contains(&format!("`{c} "))
        };
        if !command.is_empty() && !names(command) && others.iter().any(|o| names(o)) {
            continue;
        }
        let options: Vec<&str> = l
            .fields
            .iter()
            .filter_map(|f| super::flag_of(f))
            .filter(|flag| flags.is_empty() || flags.iter().any(|g| g == flag))
            .collect();
        if options.is_empty() && !flags.is_empty() {
            continue;
        }
        let named = if options.is_empty() {
            String::new()
        } else {
            format!("{}: ", options.join(", "))
        };
        lines.push(format!(
            "  {named}at most {} — {} ({})",
            amount(l.max, l.unit),
            l.applies_to,
            l.name
        ));
    }
    if lines.is_empty() {
        return String::new();
    }
    format!(
        "Limits (checked before anything is allocated; docs/ARCHITECTURE.md, \"Robustness\"):\n{}\n",
        lines.join("\n")
    )
}

/// Every model of the registry with its parameters: name = default unit (what, rule).
pub fn models_text() -> String {
    let mut out =
        String::from("Models and their parameters (--param NAME=VALUE; default, unit):\n");
    for m in crate::nonlinear::models() {
        out.push_str(&format!("  {} — {}\n", m.name, m.title));
        if m.params.is_empty() {
            out.push_str("      (no parameters)\n");
        }
        for p in &m.params {
            let unit = if p.unit == "1" {
                String::new()
            } else {
                format!(" {}", p.unit)
            };
            out.push_str(&format!(
                "      {} = {}{unit}  {} ({})\n",
                p.name,
                fmt_num(p.default),
                p.description,
                p.constraint.symbol()
            ));
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn limits_of_a_command_s_options() {
        let others = ["freq".to_string(), "response".to_string()];
        let others: Vec<&String> = others.iter().collect();
        let t = limits_text(
            "simulate",
            &others,
            &["--points".to_string(), "--size".to_string()],
        );
        assert!(
            t.contains("--points: at most 1 000 000 sample points"),
            "{t}"
        );
        assert!(t.contains("--size: at most 16 384 px a side"), "{t}");
        assert!(t.contains("MAX_SIMULATION_VALUES"), "{t}");
        assert!(
            !t.contains("--den") && !t.contains("MAX_CHANNEL_VALUES"),
            "{t}"
        );
        let all = limits_text("", &[], &[]);
        for l in LIMITS {
            assert!(all.contains(l.name), "{}", l.name);
        }
    }

    #[test]
    fn every_model_and_parameter_is_listed() {
        let t = models_text();
        for m in crate::nonlinear::models() {
            assert!(t.contains(&format!("  {} — ", m.name)), "{}", m.name);
            for p in &m.params {
                assert!(
                    t.contains(&format!("      {} = {}", p.name, fmt_num(p.default))),
                    "{}.{}",
                    m.name,
                    p.name
                );
            }
        }
    }
}
