//! `ltikit residue`: partial fractions with repeated and complex poles, in s or — for a
//! discrete-time plant — in z (G(z) = Σ r/(z − p)^k + direct: the same algebra).

use anyhow::Result;
use clap::Args;
use num_complex::Complex64;

use super::PlantArgs;
use crate::analysis::pfe::PartialFractions;
use crate::fmt::fmt_sig;
use crate::poly::Poly;

#[derive(Args, Debug)]
pub struct ResidueArgs {
    #[command(flatten)]
    pub plant: PlantArgs,
    /// Print one JSON document: {"terms": [{"pole", "power", "residue"}], "direct": [...]}.
    #[arg(long)]
    pub json: bool,
}

pub fn run(a: &ResidueArgs) -> Result<()> {
    let plant = a.plant.single()?;
    let var = plant.domain().variable();
    let chans = a.plant.channels(&plant)?;
    super::channels::print_each(
        &plant,
        &chans,
        a.json,
        |f| f.partial_fractions(),
        |pf| report(pf, var),
    )
}

/// `a ± bj` with 7 significant digits.
fn complex(z: Complex64) -> String {
    if z.im == 0.0 {
        return fmt_sig(z.re, 7);
    }
    let im = fmt_sig(z.im.abs(), 7);
    if z.re == 0.0 {
        format!("{}{im}j", if z.im < 0.0 { "-" } else { "" })
    } else {
        format!(
            "{} {} {im}j",
            fmt_sig(z.re, 7),
            if z.im < 0.0 { "-" } else { "+" }
        )
    }
}

/// `(v - p)` for the variable `v` (s or z) written naturally: `(s + 2)`, `s`, `(z - 0.5)`,
/// `(s + 1 - 2j)`.
fn factor(p: Complex64, v: &str) -> String {
    if p.re == 0.0 && p.im == 0.0 {
        return v.into();
    }
    let neg = -p;
    if neg.im == 0.0 {
        let sign = if neg.re < 0.0 { "-" } else { "+" };
        return format!("({v} {sign} {})", fmt_sig(neg.re.abs(), 7));
    }
    let c = complex(neg);
    if let Some(rest) = c.strip_prefix('-') {
        format!("({v} - {rest})")
    } else {
        format!("({v} + {c})")
    }
}

/// The expansion in the variable `v` (s or z) as text, one term per line.
pub fn report(pf: &PartialFractions, v: &str) -> String {
    let mut s = format!("G({v}) =\n");
    // Terms with an exactly zero coefficient are listed in JSON (every power up to the
    // multiplicity) but not in the text.
    for t in pf.terms.iter().filter(|t| t.residue.norm() != 0.0) {
        let pow = if t.power > 1 {
            format!("^{}", t.power)
        } else {
            String::new()
        };
        let r = if t.residue.im == 0.0 {
            complex(t.residue)
        } else {
            format!("({})", complex(t.residue))
        };
        s.push_str(&format!("    {r} / {}{pow}\n", factor(t.pole, v)));
    }
    if !pf.direct.is_empty() {
        let d = Poly::from_descending(&pf.direct)
            .map(|p| crate::poly::format_poly(&p, v))
            .unwrap_or_default();
        s.push_str(&format!("  + {d}   (direct part)\n"));
    }
    if pf.terms.iter().all(|t| t.residue.norm() == 0.0) && pf.direct.is_empty() {
        s.push_str("    0\n");
    }
    s
}
