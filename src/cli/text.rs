//! Text formatting shared by the reports (CLI text output and the demo's Markdown).

use num_complex::Complex64;

use crate::Root;
use crate::fmt::{fmt_root, fmt_sig};

/// Roots with multiplicities, one entry per conjugate pair: "-1 (×2), -0.2 ± 1.98997j", or
/// "none".
pub fn roots_text(r: &[Root]) -> String {
    roots_texts(&[r]).remove(0)
}

/// Several root lists printed together (poles, zeros, cancelled roots): six significant
/// digits, more when distinct values — within a list or across the lists — would print
/// alike (a zero at −2.00000000001 beside a pole at −2 must not read as "−2" twice).
pub fn roots_texts(lists: &[&[Root]]) -> Vec<String> {
    let items: Vec<Vec<(Complex64, String)>> = lists
        .iter()
        .map(|r| {
            r.iter()
                .filter(|r| r.value.im >= 0.0)
                .map(|r| {
                    let m = if r.multiplicity > 1 {
                        format!(" (×{})", r.multiplicity)
                    } else {
                        String::new()
                    };
                    (r.value, m)
                })
                .collect()
        })
        .collect();
    let all: Vec<Complex64> = items.iter().flatten().map(|(v, _)| *v).collect();
    let sig = distinguishing_digits(&all, 6);
    items
        .iter()
        .map(|list| {
            if list.is_empty() {
                "none".into()
            } else {
                list.iter()
                    .map(|(v, label)| format!("{}{label}", fmt_root(*v, sig)))
                    .collect::<Vec<_>>()
                    .join(", ")
            }
        })
        .collect()
}

/// The fewest significant digits, from `min` up to 17, with which the distinct values of
/// `values` all print differently.
pub fn distinguishing_digits(values: &[Complex64], min: usize) -> usize {
    let mut distinct: Vec<Complex64> = Vec::new();
    for v in values {
        if !distinct.contains(v) {
            distinct.push(*v);
        }
    }
    (min..=17)
        .find(|&sig| {
            let mut t: Vec<String> = distinct.iter().map(|v| fmt_root(*v, sig)).collect();
            t.sort();
            t.dedup();
            t.len() == distinct.len()
        })
        .unwrap_or(17)
}

/// Values (upper members of conjugate pairs) each followed by its label, joined with ", ":
/// "0 (×2, defective), ±1.41421j"; "none" when empty. Six significant digits, more when
/// distinct values would print alike.
pub fn labelled_roots_text(items: &[(Complex64, String)]) -> String {
    if items.is_empty() {
        return "none".into();
    }
    // (the exact path keeps ±j and ±j(1 + 1e-8) apart: they must not read as "±1j, ±1j")
    let values: Vec<Complex64> = items.iter().map(|(v, _)| *v).collect();
    let sig = distinguishing_digits(&values, 6);
    items
        .iter()
        .map(|(v, label)| format!("{}{label}", fmt_root(*v, sig)))
        .collect::<Vec<_>>()
        .join(", ")
}

/// One complex number (not a pair): "0.5", "-0.25j", "0.5 - 0.25j", six significant digits.
pub fn complex_text(z: Complex64) -> String {
    let im = |x: f64| format!("{}j", fmt_sig(x, 6));
    match (z.re == 0.0, z.im == 0.0) {
        (_, true) => fmt_sig(z.re, 6),
        (true, false) => im(z.im),
        (false, false) => format!(
            "{} {} {}",
            fmt_sig(z.re, 6),
            if z.im < 0.0 { "-" } else { "+" },
            im(z.im.abs())
        ),
    }
}

/// A polynomial in s from its coefficients as typed (descending powers), e.g.
/// `s^4 + 2.00000002 s^2 + 1.00000002`; parenthesised when it has several terms.
pub fn typed_poly(c: &[crate::lti::plant::Coefficient]) -> String {
    let n = c.len().saturating_sub(1);
    let mut out = String::new();
    let mut terms = 0;
    for (i, coef) in c.iter().enumerate() {
        if coef.value == 0.0 {
            continue;
        }
        let k = n - i;
        let t = coef.text.trim();
        let (neg, mag) = match t.strip_prefix('-') {
            Some(m) => (true, m),
            None => (false, t.strip_prefix('+').unwrap_or(t)),
        };
        let power = match k {
            0 => String::new(),
            1 => "s".into(),
            _ => format!("s^{k}"),
        };
        let body = match (mag == "1" && k > 0, power.is_empty()) {
            (true, _) => power,
            (false, true) => mag.to_string(),
            (false, false) => format!("{mag} {power}"),
        };
        out.push_str(match (terms == 0, neg) {
            (true, true) => "-",
            (true, false) => "",
            (false, true) => " - ",
            (false, false) => " + ",
        });
        out.push_str(&body);
        terms += 1;
    }
    match terms {
        0 => "0".into(),
        1 => out,
        _ => format!("({out})"),
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

/// "G(s) = …" of one channel of a state-space model, or — above [`MAX_PRINTED_ORDER`] poles —
/// its size in words (the factors follow in the report).
pub fn channel_g_text(f: &crate::analysis::Factored) -> String {
    let order = f.poles().iter().map(|r| r.multiplicity).sum::<usize>();
    if order > MAX_PRINTED_ORDER {
        format!(
            "G(s): order {order}, minimal order {}, gain {} (poles and zeros below)",
            f.reduced_poles()
                .iter()
                .map(|r| r.multiplicity)
                .sum::<usize>(),
            crate::fmt::fmt_num(f.gain())
        )
    } else {
        format!("G(s) = {f}")
    }
}

/// "G(s) = …" for a SISO plant: its coefficients as typed, or for a state-space plant its
/// factors and its size (a large one in words).
pub fn g_text(plant: &crate::lti::Plant, f: &crate::analysis::Factored) -> String {
    if let Some(which) = plant.selection {
        return format!("{}\n{} = {f}", plant.name, which.formula());
    }
    match &plant.model {
        crate::lti::Model::Tf(g) => match &plant.typed {
            // As typed: "2.00000002" must not read as "2".
            Some((num, den)) => format!("G(s) = {} / {}", typed_poly(num), typed_poly(den)),
            None => format!("G(s) = {g}"),
        },
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
                crate::fmt::fmt_num(f.gain())
            )
        }
        crate::lti::Model::Ss(ss) => format!("G(s) = {f}  (state space: {} states)", ss.order()),
    }
}
