//! Text formatting shared by the reports (CLI text output and the demo's Markdown).

use crate::Root;
use crate::poly::{fmt_root, fmt_sig};

/// Roots with multiplicities, one entry per conjugate pair: "-1 (×2), -0.2 ± 1.98997j", or
/// "none".
pub fn roots_text(r: &[Root]) -> String {
    let v: Vec<String> = r
        .iter()
        .filter(|r| r.value.im >= 0.0)
        .map(|r| {
            let m = if r.multiplicity > 1 {
                format!(" (×{})", r.multiplicity)
            } else {
                String::new()
            };
            format!("{}{m}", fmt_root(r.value, 6))
        })
        .collect();
    if v.is_empty() {
        "none".into()
    } else {
        v.join(", ")
    }
}

/// A vector as "[a, b, c]" with 6 significant digits.
pub fn vector_text(v: &[f64]) -> String {
    format!(
        "[{}]",
        v.iter()
            .map(|x| fmt_sig(*x, 6))
            .collect::<Vec<_>>()
            .join(", ")
    )
}

/// Orders above which a state-space channel is not printed as a formula.
pub const MAX_PRINTED_ORDER: usize = 12;

/// "G(s) = …" for a SISO plant: its coefficients, or for a state-space plant its factors and
/// its size.
pub fn g_text(plant: &crate::lti::Plant, f: &crate::analysis::Factored) -> String {
    if let Some(which) = plant.selection {
        return format!("{}\n{} = {f}", plant.name, which.formula());
    }
    match &plant.model {
        crate::lti::Model::Tf(g) => format!("G(s) = {g}"),
        crate::lti::Model::Ss(ss)
            if f.poles().iter().map(|r| r.multiplicity).sum::<usize>() > MAX_PRINTED_ORDER =>
        {
            format!(
                "G(s): a channel of a {}-state model, minimal order {}, gain {} (poles and zeros below)",
                ss.order(),
                f.reduced_poles()
                    .iter()
                    .map(|r| r.multiplicity)
                    .sum::<usize>(),
                crate::poly::fmt_num(f.gain())
            )
        }
        crate::lti::Model::Ss(ss) => format!("G(s) = {f}  (state space: {} states)", ss.order()),
    }
}
