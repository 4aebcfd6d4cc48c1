//! `ltikit residue`: partial fractions with repeated and complex poles.

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
    plant.domain().require_continuous(
        "`residue` (partial fractions in s for the inverse Laplace transform)",
    )?;
    let chans = a.plant.channels(&plant)?;
    super::channels::print_each(&plant, &chans, a.json, |f| f.partial_fractions(), report)
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

/// `(s - p)` written naturally: `s + 2`, `s`, `(s + 1 - 2j)`.
fn factor(p: Complex64) -> String {
    if p.re == 0.0 && p.im == 0.0 {
        return "s".into();
    }
    let neg = -p;
    if neg.im == 0.0 {
        let sign = if neg.re < 0.0 { "-" } else { "+" };
        return format!("(s {sign} {})", fmt_sig(neg.re.abs(), 7));
    }
    let c = complex(neg);
    if let Some(rest) = c.strip_prefix('-') {
        format!("(s - {rest})")
    } else {
        format!("(s + {c})")
    }
}

/// The expansion as text, one term per line.
pub fn report(pf: &PartialFractions) -> String {
    let mut s = String::from("G(s) =\n");
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
        s.push_str(&format!("    {r} / {}{pow}\n", factor(t.pole)));
    }
    if !pf.direct.is_empty() {
        let d = Poly::from_descending(&pf.direct)
            .map(|p| p.to_string())
            .unwrap_or_default();
        s.push_str(&format!("  + {d}   (direct part)\n"));
    }
    if pf.terms.iter().all(|t| t.residue.norm() == 0.0) && pf.direct.is_empty() {
        s.push_str("    0\n");
    }
    s
}
