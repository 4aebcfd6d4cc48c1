//! `ltikit jury` (and `ltikit routh` on a discrete plant): the Jury table of the characteristic
//! polynomial in z, or of the closed loop D + K·N with a gain K, the roots inside, on and
//! outside the unit circle (exact for coefficients typed as text), and the stabilising gains.

use anyhow::{Result, bail};
use serde::Serialize;

use super::output::{print, print_json};
use super::table_args::RouthArgs;
use crate::analysis::jury::{JuryTable, discrete_stable_gains_exact, jury_exact};
use crate::fmt::fmt_sig;
use crate::lti::{Model, Plant};
use crate::poly::exact::{CircleCounts, ExactPoly, Rational};
use crate::poly::format_poly;

#[derive(Serialize)]
struct Doc<'a> {
    polynomial: &'a [f64],
    #[serde(flatten)]
    table: &'a JuryTable,
    #[serde(skip_serializing_if = "Option::is_none")]
    stable_gains: Option<Vec<[Option<f64>; 2]>>,
}

/// `ltikit jury`: discrete plants only (a continuous one is pointed to `routh`).
pub fn run_jury(a: &RouthArgs) -> Result<()> {
    let plant = a.plant.single()?;
    if !plant.domain().is_discrete() {
        bail!(
            "the Jury table counts roots against the unit circle: it is for discrete-time plants (give --dt T); for a continuous-time plant use `ltikit routh`"
        );
    }
    run(a, &plant)
}

/// The exact numerator and denominator: the coefficients as typed, or the f64 values (the
/// Routh and Jury tables' exact counts both start here).
pub(super) fn exact_parts(
    plant: &Plant,
    g: &crate::TransferFunction,
) -> crate::error::Result<(ExactPoly, ExactPoly)> {
    Ok(match &plant.typed {
        Some((n, d)) => {
            let texts = |c: &[crate::lti::plant::Coefficient]| {
                c.iter().map(|x| x.text.clone()).collect::<Vec<_>>()
            };
            (
                ExactPoly::parse_descending(&texts(n))?,
                ExactPoly::parse_descending(&texts(d))?,
            )
        }
        None => (
            ExactPoly::from_f64_descending(g.num().coeffs())?,
            ExactPoly::from_f64_descending(g.den().coeffs())?,
        ),
    })
}

/// The Jury report of a discrete plant (shared by `jury` and `routh`).
pub fn run(a: &RouthArgs, plant: &Plant) -> Result<()> {
    if plant.selection.is_some() {
        bail!("jury takes the plant itself: give the loop gain with --gain K (no --controller)");
    }
    let Model::Tf(g) = &plant.model else {
        bail!(
            "the Jury table needs a transfer function (its characteristic polynomial); this plant is a state-space model"
        );
    };
    let (num, den) = exact_parts(plant, g)?;
    let p = match a.gain {
        None => den.clone(),
        Some(k) if k.is_finite() => {
            let k = ExactPoly::from_rationals(&[Rational::from_f64(k)?])?;
            &den + &(&k * &num)
        }
        Some(k) => bail!("--gain must be finite, got {}", crate::error::number(k)),
    };
    let t = jury_exact(&p)?;
    let pf = p.to_poly()?;
    let gains = if a.gain_range {
        Some(discrete_stable_gains_exact(&num, &den)?)
    } else {
        None
    };
    if a.json {
        let finite = |x: f64| x.is_finite().then_some(x);
        return print_json(&Doc {
            polynomial: pf.coeffs(),
            table: &t,
            stable_gains: gains.as_ref().map(|v| {
                v.iter()
                    .map(|(lo, hi)| [finite(*lo), finite(*hi)])
                    .collect()
            }),
        });
    }
    print(&report(&pf, &t, gains.as_deref()))
}

fn report(p: &crate::Poly, t: &JuryTable, gains: Option<&[(f64, f64)]>) -> String {
    let mut s = format!(
        "Characteristic polynomial: {}\n\nJury table (Åström–Wittenmark form: each stage's coefficients and their reverse, αₖ = aₖ/a₀):\n",
        format_poly(p, "z")
    );
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
    let n = p.degree();
    for (i, row) in cells.iter().enumerate() {
        let k = n - i / 2;
        let label = if i % 2 == 0 {
            format!("k = {k}")
        } else {
            String::new()
        };
        let joined: Vec<String> = row.iter().map(|c| format!("{c:>w$}")).collect();
        let alpha = match t.alphas.get(i / 2) {
            Some(al) if i % 2 == 1 => format!("   α{} = {}", k, fmt_sig(*al, 6)),
            _ => String::new(),
        };
        s.push_str(&format!("  {label:<7} {}{alpha}\n", joined.join("  ")));
    }
    if let Some(k) = t.singular_at {
        s.push_str(&format!(
            "\nStage {k}: first element 0 (|α{}| = 1: roots on the circle or in pairs z, 1/z̄) — the table stops; the counts come from the bilinear map w = (z − 1)/(z + 1)\n",
            k + 1
        ));
    } else {
        let neg = t.first[1..].iter().filter(|x| **x < 0.0).count();
        s.push_str(&format!(
            "\nFirst elements a₀ᵏ: {} — {neg} negative\n",
            t.first
                .iter()
                .map(|x| fmt_sig(*x, 6))
                .collect::<Vec<_>>()
                .join(", ")
        ));
    }
    let table_counts = CircleCounts {
        inside: t.inside,
        on: t.on,
        outside: t.outside,
    };
    let c = t.counts();
    s.push_str(&format!(
        "\nRoots: {} strictly inside the unit circle, {} on it, {} outside — {}",
        c.inside,
        c.on,
        c.outside,
        if c.outside > 0 {
            "unstable"
        } else if c.on > 0 {
            "not asymptotically stable"
        } else {
            "asymptotically stable"
        }
    ));
    s.push_str(&match t.exact {
        Some(e) if e == table_counts => {
            "\nConfirmed in exact rational arithmetic (the coefficients as typed).".to_string()
        }
        Some(_) => format!(
            "\nThe floating-point table read {} / {} / {}; exact rational arithmetic on the coefficients as typed decides the counts above.",
            t.inside, t.on, t.outside
        ),
        None => "\nNot confirmed in exact arithmetic (beyond the exact path's budget).".to_string(),
    });
    if let Some(v) = gains {
        let f = |x: f64| {
            if x.is_finite() {
                fmt_sig(x, 10)
            } else if x > 0.0 {
                "∞".into()
            } else {
                "-∞".into()
            }
        };
        let text: Vec<String> = v
            .iter()
            .map(|(lo, hi)| format!("{} < K < {}", f(*lo), f(*hi)))
            .collect();
        s.push_str(&format!(
            "\nStable for (unity negative feedback, D + K·N, every root strictly inside the unit circle): {}",
            if text.is_empty() {
                "no gain".to_string()
            } else {
                text.join(", ")
            }
        ));
    }
    s.push('\n');
    s
}
