//! Text formatting shared by the reports (CLI text output and the demo's Markdown).

use num_complex::Complex64;

use crate::Root;
use crate::fmt::{fmt_root, fmt_sig};

/// Roots with multiplicities, one entry per conjugate pair: "-1 (×2), -0.2 ± 1.98997j", or
/// "none".
pub fn roots_text(r: &[Root]) -> String {
    roots_texts(&[r]).remove(0)
}

/// Several root lists printed together (poles, zeros, cancelled roots): each value with six
/// significant digits, more when a distinct value — in the same list or another — would print
/// alike (a zero at −2.00000000001 beside a pole at −2 must not read as "−2" twice); values
/// that are not that close keep six digits.
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
    let digits = digits_per_value(&all, 6);
    let mut k = 0;
    items
        .iter()
        .map(|list| {
            if list.is_empty() {
                return "none".into();
            }
            let text = list
                .iter()
                .map(|(v, label)| {
                    let t = format!("{}{label}", fmt_root(*v, digits[k]));
                    k += 1;
                    t
                })
                .collect::<Vec<_>>();
            text.join(", ")
        })
        .collect()
}

/// For each value, the fewest significant digits from `min` up to 17 with which it prints
/// differently from every other distinct value of `values` (printed with the same digits).
/// Only values within a relative 1e-4 of each other are compared (farther ones differ at six
/// digits already), and not those within 64 eps of each other: a difference at the level of
/// double-precision rounding is not known to be real, and printing it would print noise.
pub fn digits_per_value(values: &[Complex64], min: usize) -> Vec<usize> {
    let close = |a: Complex64, b: Complex64| {
        let (d, m) = ((a - b).norm(), a.norm().max(b.norm()));
        d <= 1e-4 * m && d > 64.0 * f64::EPSILON * m
    };
    values
        .iter()
        .map(|&v| {
            let near: Vec<Complex64> = values
                .iter()
                .copied()
                .filter(|&u| u != v && close(u, v))
                .collect();
            (min..=17)
                .find(|&sig| {
                    let t = fmt_root(v, sig);
                    near.iter().all(|&u| fmt_root(u, sig) != t)
                })
                .unwrap_or(17)
        })
        .collect()
}

/// The fewest significant digits, from `min` up to 17, with which the distinct values of
/// `values` all print differently (one precision for all).
pub fn distinguishing_digits(values: &[Complex64], min: usize) -> usize {
    digits_per_value(values, min)
        .into_iter()
        .max()
        .unwrap_or(min)
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
    let digits = digits_per_value(&values, 6);
    items
        .iter()
        .zip(digits)
        .map(|((v, label), sig)| format!("{}{label}", fmt_root(*v, sig)))
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
pub fn typed_poly(c: &[crate::lti::plant::Coefficient], var: &str) -> String {
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
            1 => var.into(),
            _ => format!("{var}^{k}"),
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
    let g = g_of(f.domain());
    let order = f.poles().iter().map(|r| r.multiplicity).sum::<usize>();
    if order > MAX_PRINTED_ORDER {
        format!(
            "{g}: order {order}, minimal order {}, gain {} (poles and zeros below)",
            f.reduced_poles()
                .iter()
                .map(|r| r.multiplicity)
                .sum::<usize>(),
            crate::fmt::fmt_num(f.gain())
        )
    } else {
        format!("{g} = {f}")
    }
}

/// "G(s)", or "G(z)" for a discrete-time plant.
pub fn g_of(domain: crate::lti::Domain) -> &'static str {
    if domain.is_discrete() { "G(z)" } else { "G(s)" }
}

/// ", dt = 0.1 s" for a discrete-time plant, "" otherwise: appended where the report names
/// the plant, so a reader always knows the domain.
pub fn dt_suffix(domain: crate::lti::Domain) -> String {
    domain.dt().map_or_else(String::new, |dt| {
        format!("  (discrete time, dt = {} s)", crate::fmt::fmt_num(dt))
    })
}

/// "G(s) = …" for a SISO plant: its coefficients as typed, or for a state-space plant its
/// factors and its size (a large one in words).
pub fn g_text(plant: &crate::lti::Plant, f: &crate::analysis::Factored) -> String {
    let text = g_text_in(plant, f);
    let delay = match (&plant.model, &plant.typed) {
        // the typed coefficients are the rational part
        (crate::lti::Model::Tf(_), Some(_)) if plant.selection.is_none() && f.delay() > 0.0 => {
            format!(" · {}", crate::lti::delay::factor_text(f.delay()))
        }
        _ if plant.selection.is_none() && f.delay() == 0.0 && plant.delay() > 0.0 => format!(
            " · {}  (the delay replaced by a Padé approximant)",
            crate::lti::delay::factor_text(plant.delay())
        ),
        _ => String::new(),
    };
    format!("{text}{delay}{}", dt_suffix(f.domain()))
}

fn g_text_in(plant: &crate::lti::Plant, f: &crate::analysis::Factored) -> String {
    let head = g_of(f.domain());
    let var = f.domain().variable();
    if let Some(which) = plant.selection {
        return format!("{}\n{} = {f}", plant.name, which.formula());
    }
    match &plant.model {
        crate::lti::Model::Tf(g) => match &plant.typed {
            // As typed: "2.00000002" must not read as "2".
            Some((num, den)) => format!(
                "{head} = {} / {}",
                typed_poly(num, var),
                typed_poly(den, var)
            ),
            None => format!("{head} = {g}"),
        },
        crate::lti::Model::Ss(ss)
            if f.poles().iter().map(|r| r.multiplicity).sum::<usize>() > MAX_PRINTED_ORDER =>
        {
            format!(
                "{head}: a channel of a {}-state model, minimal order {}, gain {} (poles and zeros below)",
                ss.order(),
                f.reduced_poles()
                    .iter()
                    .map(|r| r.multiplicity)
                    .sum::<usize>(),
                crate::fmt::fmt_num(f.gain())
            )
        }
        crate::lti::Model::Ss(ss) => format!("{head} = {f}  (state space: {} states)", ss.order()),
    }
}
