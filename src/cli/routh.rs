//! `ltikit routh`: the Routh–Hurwitz table of the characteristic polynomial, or of the
//! closed loop D + K·N with a gain K in unity negative feedback. A discrete plant (`--dt`)
//! gets the Jury table instead (`jury.rs`).

use anyhow::{Result, bail};
use serde::Serialize;

use super::output::{print, print_json};
pub use super::table_args::RouthArgs;
use crate::analysis::{RouthEvent, RouthTable, routh};
use crate::error::LtiError;
use crate::fmt::fmt_sig;
use crate::lti::Model;
use crate::poly::{Poly, format_poly};

/// Root counts decided in exact rational arithmetic.
#[derive(Serialize, Debug, Clone, Copy, PartialEq, Eq)]
struct Exact {
    rhp: usize,
    axis: usize,
    lhp: usize,
}

#[derive(Serialize)]
struct Doc<'a> {
    polynomial: &'a [f64],
    #[serde(flatten)]
    table: &'a RouthTable,
    /// The counts in exact rational arithmetic of the coefficients as typed (null when beyond
    /// the exact path's budget).
    exact: Option<Exact>,
    #[serde(skip_serializing_if = "Option::is_none")]
    stable_gains: Option<Vec<[Option<f64>; 2]>>,
}

pub fn run(a: &RouthArgs) -> Result<()> {
    let plant = a.plant.single()?;
    if plant.domain().is_discrete() {
        // in z the stability boundary is the unit circle: the Jury table
        return super::jury::run(a, &plant);
    }
    if plant.selection.is_some() {
        bail!("routh takes the plant itself: give the loop gain with --gain K (no --controller)");
    }
    let Model::Tf(g) = &plant.model else {
        bail!(
            "routh needs a transfer function (its characteristic polynomial); this plant is a state-space model"
        );
    };
    let p = match a.gain {
        None => g.den().clone(),
        Some(k) if k.is_finite() => &g.den().clone() + &g.num().scale(k),
        Some(k) => bail!("--gain must be finite, got {}", crate::error::number(k)),
    };
    let t = routh(&p)?;
    let exact = exact_counts(&plant, g, a.gain)?;
    let gains = if a.gain_range {
        Some(crate::analysis::stable_gains(g.num(), g.den())?)
    } else {
        None
    };
    if a.json {
        let finite = |x: f64| x.is_finite().then_some(x);
        return print_json(&Doc {
            polynomial: p.coeffs(),
            table: &t,
            exact,
            stable_gains: gains.as_ref().map(|v| {
                v.iter()
                    .map(|(lo, hi)| [finite(*lo), finite(*hi)])
                    .collect()
            }),
        });
    }
    let mut s = format!("Characteristic polynomial: {}\n\n", format_poly(&p, "s"));
    let cells: Vec<Vec<String>> = t
        .rows
        .iter()
        .map(|r| r.iter().map(|x| fmt_sig(*x, 6)).collect())
        .collect();
    let w = cells
        .iter()
        .flatten()
        .map(|c| c.chars().count())
        .max()
        .unwrap_or(1);
    for (pw, row) in t.powers.iter().zip(&cells) {
        let row: Vec<String> = row.iter().map(|c| format!("{c:>w$}")).collect();
        s.push_str(&format!("  s^{pw:<4} {}\n", row.join("  ")));
    }
    for e in &t.events {
        match e {
            RouthEvent::ZeroFirstElement { power, epsilon } => s.push_str(&format!(
                "\nRow s^{power}: first element 0, replaced by ε = {} (signs read for ε → 0+)",
                fmt_sig(*epsilon, 3)
            )),
            RouthEvent::ZeroRow {
                power,
                auxiliary,
                axis_roots,
            } => {
                let aux = Poly::from_descending(auxiliary)
                    .map(|q| format_poly(&q, "s"))
                    .unwrap_or_default();
                s.push_str(&format!(
                    "\nRow s^{power}: all zeros — auxiliary polynomial {aux} (roots symmetric about the origin, {axis_roots} on the imaginary axis); the row is its derivative"
                ));
            }
        }
    }
    if !t.events.is_empty() {
        s.push('\n');
    }
    let f64_counts = Exact {
        rhp: t.rhp,
        axis: t.axis,
        lhp: t.lhp,
    };
    // the exact counts decide when they exist
    let c = exact.unwrap_or(f64_counts);
    s.push_str(&format!(
        "\nRoots: {} in the open right half plane, {} on the imaginary axis, {} in the open left half plane — {}",
        c.rhp,
        c.axis,
        c.lhp,
        if c.rhp > 0 {
            "unstable"
        } else if c.axis > 0 {
            "not asymptotically stable"
        } else {
            "asymptotically stable"
        }
    ));
    s.push_str(&match exact {
        Some(e) if e == f64_counts => {
            "\nConfirmed in exact rational arithmetic (the coefficients as typed).".to_string()
        }
        Some(_) => format!(
            "\nThe floating-point table read {} / {} / {}; exact rational arithmetic on the coefficients as typed decides the counts above.",
            t.rhp, t.axis, t.lhp
        ),
        None => "\nNot confirmed in exact arithmetic (beyond the exact path's budget).".to_string(),
    });
    if let Some(v) = &gains {
        let text: Vec<String> = v
            .iter()
            .map(|(lo, hi)| {
                let f = |x: f64| {
                    if x.is_finite() {
                        fmt_sig(x, 10)
                    } else if x > 0.0 {
                        "∞".into()
                    } else {
                        "-∞".into()
                    }
                };
                format!("{} < K < {}", f(*lo), f(*hi))
            })
            .collect();
        s.push_str(&format!(
            "\nStable for (unity negative feedback, D + K·N): {}",
            if text.is_empty() {
                "no gain".to_string()
            } else {
                text.join(", ")
            }
        ));
    }
    print(&s)
}

/// The root counts of D (or D + K·N) in exact rational arithmetic: the coefficients as typed
/// when the plant was given by them, otherwise the f64 values (exact binary fractions); `None`
/// beyond the exact path's budget ([`LtiError::BeyondExactBudget`]: the floating-point table
/// decides and the report says so).
///
/// Errors: any other error of the exact path, as itself (every typed token was checked by the
/// exact reader when the plant was read, so none is expected).
fn exact_counts(
    plant: &crate::lti::Plant,
    g: &crate::TransferFunction,
    gain: Option<f64>,
) -> crate::error::Result<Option<Exact>> {
    match exact_counts_within_budget(plant, g, gain) {
        Ok(e) => Ok(Some(e)),
        Err(LtiError::BeyondExactBudget { .. }) => Ok(None),
        Err(e) => Err(e),
    }
}

/// [`exact_counts`], with the budget error as an error.
fn exact_counts_within_budget(
    plant: &crate::lti::Plant,
    g: &crate::TransferFunction,
    gain: Option<f64>,
) -> crate::error::Result<Exact> {
    use crate::poly::exact::{ExactPoly, Rational};
    let (num, den) = super::jury::exact_parts(plant, g)?;
    let p = match gain {
        None => den,
        Some(k) => {
            let k = ExactPoly::from_rationals(&[Rational::from_f64(k)?])?;
            &den + &(&k * &num)
        }
    };
    let h = p.half_plane_counts()?;
    Ok(Exact {
        rhp: h.rhp,
        axis: h.axis,
        lhp: h.lhp,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lti::Plant;
    use crate::lti::plant::Coefficient;

    #[test]
    fn only_the_budget_sends_routh_to_the_floating_point_counts() {
        // within the budget: counted exactly
        let p = Plant::from_text(None, "1 2 3").unwrap();
        let Model::Tf(g) = &p.model else {
            unreachable!()
        };
        let e = exact_counts(&p, g, None).unwrap().unwrap();
        assert_eq!((e.rhp, e.axis, e.lhp), (0, 0, 2));
        // beyond it (degree 120 > 100): no exact counts, not an error
        let den = format!("1{} 1", " 0".repeat(119));
        let p = Plant::from_text(None, &den).unwrap();
        let Model::Tf(g) = &p.model else {
            unreachable!()
        };
        assert!(exact_counts(&p, g, None).unwrap().is_none());
        // any other error of the exact path is reported as itself, not as "beyond the budget"
        let mut p = Plant::from_text(None, "1 2 3").unwrap();
        let Model::Tf(g) = p.model.clone() else {
            unreachable!()
        };
        let bad = Coefficient {
            text: "2x".into(),
            value: 2.0,
        };
        if let Some((_, den)) = &mut p.typed {
            den[1] = bad;
        }
        let e = exact_counts(&p, &g, None).unwrap_err();
        assert!(matches!(e, LtiError::BadNumber { .. }), "{e}");
        assert!(e.to_string().contains("'2x'"), "{e}");
    }
}
