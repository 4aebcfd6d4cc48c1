//! The report's evidence: every check computed at run time, with its worst error.

use super::md::Md;
use crate::fmt::fmt_sig;

/// One verified quantity.
pub struct Check {
    pub group: &'static str,
    pub what: String,
    pub error: f64,
    pub tolerance: f64,
}

/// All checks of a demo run.
#[derive(Default)]
pub struct Checks {
    pub rows: Vec<Check>,
}

impl Checks {
    /// Records a check; `error` is a relative (or stated) error, `tolerance` its bound.
    pub fn add(
        &mut self,
        group: &'static str,
        what: impl Into<String>,
        error: f64,
        tolerance: f64,
    ) {
        self.rows.push(Check {
            group,
            what: what.into(),
            error,
            tolerance,
        });
    }

    pub fn passed(&self) -> usize {
        self.rows.iter().filter(|c| c.error <= c.tolerance).count()
    }

    pub fn all_pass(&self) -> bool {
        self.passed() == self.rows.len()
    }

    /// The worst error of each group, in first-seen order.
    pub fn groups(&self) -> Vec<(&'static str, usize, f64, f64, bool)> {
        let mut out: Vec<(&'static str, usize, f64, f64, bool)> = Vec::new();
        for c in &self.rows {
            let ok = c.error <= c.tolerance;
            match out.iter_mut().find(|g| g.0 == c.group) {
                Some(g) => {
                    g.1 += 1;
                    g.2 = g.2.max(c.error);
                    g.3 = g.3.max(c.tolerance);
                    g.4 &= ok;
                }
                None => out.push((c.group, 1, c.error, c.tolerance, ok)),
            }
        }
        out
    }

    /// The verification section.
    pub fn render(&self, md: &mut Md) {
        md.h2("Verification");
        md.p(&format!(
            "Everything below was recomputed while this report was generated. {} of {} checks \
             pass{}.",
            self.passed(),
            self.rows.len(),
            if self.all_pass() {
                ""
            } else {
                " — the failing ones are marked ✗"
            }
        ));
        let rows: Vec<Vec<String>> = self
            .groups()
            .iter()
            .map(|(g, n, worst, tol, ok)| {
                vec![
                    g.to_string(),
                    n.to_string(),
                    fmt_sig(*worst, 3),
                    fmt_sig(*tol, 3),
                    if *ok { "✓".into() } else { "✗".into() },
                ]
            })
            .collect();
        md.table(&["check", "cases", "worst error", "tolerance", ""], &rows);
        md.h3("All cases");
        let rows: Vec<Vec<String>> = self
            .rows
            .iter()
            .map(|c| {
                vec![
                    c.group.to_string(),
                    c.what.clone(),
                    fmt_sig(c.error, 3),
                    if c.error <= c.tolerance {
                        "✓".into()
                    } else {
                        "✗".into()
                    },
                ]
            })
            .collect();
        md.table(&["check", "case", "error", ""], &rows);
    }
}
