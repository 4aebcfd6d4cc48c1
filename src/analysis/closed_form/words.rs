//! The words of a closed form shared by y(t) and y\[k\]: powers of the variable, cosines,
//! products and signed sums (a leaf: no closed-form type here).

use crate::fmt::fmt_num;

/// `v`, `v^2`, … for the power k of the variable `v` (empty for k = 0).
pub(super) fn var_power(v: &str, k: usize) -> String {
    match k {
        0 => String::new(),
        1 => v.into(),
        _ => format!("{v}^{k}"),
    }
}

/// `cos(0.5 k + 0.3)`, `cos(k)`: the cosine of ω·v + φ for the variable `v`.
pub(super) fn cos_of(omega: f64, phase: f64, v: &str) -> String {
    let wt = match fmt_num(omega).as_str() {
        "1" => v.to_string(),
        w => format!("{w} {v}"),
    };
    let ph = fmt_num(phase);
    if ph == "0" {
        format!("cos({wt})")
    } else if let Some(m) = ph.strip_prefix('-') {
        format!("cos({wt} - {m})")
    } else {
        format!("cos({wt} + {ph})")
    }
}

/// Joins non-empty factors with spaces; a magnitude of 1 is dropped when other factors follow.
pub(super) fn product(mag: f64, factors: &[String]) -> String {
    let factors: Vec<&String> = factors.iter().filter(|f| !f.is_empty()).collect();
    let m = fmt_num(mag);
    let mut parts: Vec<String> = Vec::new();
    if m != "1" || factors.is_empty() {
        parts.push(m);
    }
    parts.extend(factors.into_iter().cloned());
    parts.join(" ")
}

pub(super) fn signed_sum(pieces: Vec<(bool, String)>) -> String {
    let mut s = String::new();
    for (i, (neg, body)) in pieces.iter().enumerate() {
        match (i, neg) {
            (0, true) => s.push_str(&format!("-{body}")),
            (0, false) => s.push_str(body),
            (_, true) => s.push_str(&format!(" - {body}")),
            (_, false) => s.push_str(&format!(" + {body}")),
        }
    }
    s
}
