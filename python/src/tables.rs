//! The Routh–Hurwitz table (continuous time) and the Jury table (discrete time) of a transfer
//! function's characteristic polynomial D, or of the closed loop D + K·N, with the root counts
//! decided in exact rational arithmetic (the coefficients as typed) and the exact set of
//! stabilising gains — the documents of `ltikit routh --json` / `ltikit jury --json`, from the
//! same library calls ([`routh`], [`stable_gains`], [`jury_exact`],
//! [`discrete_stable_gains_exact`]).

use serde_json::{Value, json};

use ltikit::LtiError;
use ltikit::analysis::jury::{discrete_stable_gains_exact, jury_exact};
use ltikit::analysis::{routh, stable_gains};
use ltikit::lti::TransferFunction;
use ltikit::lti::plant::Coefficient;
use ltikit::poly::exact::{ExactPoly, Rational};

/// Typed coefficients (numerator, denominator) as the plant reader kept them.
pub type Typed = (Vec<Coefficient>, Vec<Coefficient>);

/// The exact numerator and denominator: the coefficients as typed, or the f64 values (exact
/// binary fractions) — as the command line's `routh` and `jury` take them.
fn exact_parts(
    g: &TransferFunction,
    typed: Option<&Typed>,
) -> ltikit::Result<(ExactPoly, ExactPoly)> {
    Ok(match typed {
        Some((n, d)) => {
            let texts = |c: &[Coefficient]| c.iter().map(|x| x.text.clone()).collect::<Vec<_>>();
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

/// D + K·N in exact arithmetic (D alone without a gain).
fn closed(num: &ExactPoly, den: &ExactPoly, gain: Option<f64>) -> ltikit::Result<ExactPoly> {
    match gain {
        None => Ok(den.clone()),
        Some(k) if k.is_finite() => {
            let k = ExactPoly::from_rationals(&[Rational::from_f64(k)?])?;
            Ok(den + &(&k * num))
        }
        Some(k) => Err(LtiError::invalid(format!(
            "`gain` must be finite, got {}",
            ltikit::error::number(k)
        ))),
    }
}

/// Gain intervals as `[low, high]` pairs (±∞ as infinities).
fn intervals(v: &[(f64, f64)]) -> Value {
    json!(v.iter().map(|(lo, hi)| [*lo, *hi]).collect::<Vec<_>>())
}

/// The Routh–Hurwitz document of a continuous-time transfer function.
pub fn routh_doc(
    g: &TransferFunction,
    typed: Option<&Typed>,
    gain: Option<f64>,
    gains: bool,
) -> ltikit::Result<Value> {
    if g.domain().is_discrete() {
        return Err(LtiError::invalid(
            "the Routh table counts roots against the imaginary axis: for a discrete-time \
             model use jury()",
        ));
    }
    if g.delay() > 0.0 {
        return Err(LtiError::invalid(format!(
            "the model has a dead time of {} s: its characteristic equation is not a \
             polynomial, so there is no Routh table (approximate the delay first)",
            ltikit::fmt::fmt_num(g.delay())
        )));
    }
    let p = match gain {
        None => g.den().clone(),
        Some(k) if k.is_finite() => &g.den().clone() + &g.num().scale(k),
        Some(k) => {
            return Err(LtiError::invalid(format!(
                "`gain` must be finite, got {}",
                ltikit::error::number(k)
            )));
        }
    };
    let t = routh(&p)?;
    let (num, den) = exact_parts(g, typed)?;
    let exact = match closed(&num, &den, gain)?.half_plane_counts() {
        Ok(h) => Some((h.rhp, h.axis, h.lhp)),
        Err(LtiError::BeyondExactBudget { .. }) => None,
        Err(e) => return Err(e),
    };
    let (rhp, axis, lhp) = exact.unwrap_or((t.rhp, t.axis, t.lhp));
    let mut doc = serde_json::to_value(&t).map_err(|e| LtiError::invalid(e.to_string()))?;
    if let Value::Object(m) = &mut doc {
        m.insert("polynomial".into(), json!(p.coeffs()));
        m.insert("table_rhp".into(), json!(t.rhp));
        m.insert("table_axis".into(), json!(t.axis));
        m.insert("table_lhp".into(), json!(t.lhp));
        m.insert("rhp".into(), json!(rhp));
        m.insert("axis".into(), json!(axis));
        m.insert("lhp".into(), json!(lhp));
        m.insert("exact".into(), json!(exact.is_some()));
        m.insert("stable".into(), json!(rhp == 0 && axis == 0));
        if gains {
            m.insert(
                "stable_gains".into(),
                intervals(&stable_gains(g.num(), g.den())?),
            );
        }
    }
    Ok(doc)
}

/// The Jury document of a discrete-time transfer function.
pub fn jury_doc(
    g: &TransferFunction,
    typed: Option<&Typed>,
    gain: Option<f64>,
    gains: bool,
) -> ltikit::Result<Value> {
    if !g.domain().is_discrete() {
        return Err(LtiError::invalid(
            "the Jury table counts roots against the unit circle: it is for discrete-time \
             models (dt given); for a continuous-time model use routh()",
        ));
    }
    let (num, den) = exact_parts(g, typed)?;
    let p = closed(&num, &den, gain)?;
    let t = jury_exact(&p)?;
    let c = t.counts();
    let mut doc = serde_json::to_value(&t).map_err(|e| LtiError::invalid(e.to_string()))?;
    if let Value::Object(m) = &mut doc {
        m.insert("polynomial".into(), json!(p.to_poly()?.coeffs()));
        m.insert("table_inside".into(), json!(t.inside));
        m.insert("table_on".into(), json!(t.on));
        m.insert("table_outside".into(), json!(t.outside));
        m.insert("inside".into(), json!(c.inside));
        m.insert("on".into(), json!(c.on));
        m.insert("outside".into(), json!(c.outside));
        m.insert("exact".into(), json!(t.exact.is_some()));
        m.insert("stable".into(), json!(c.on == 0 && c.outside == 0));
        if gains {
            m.insert(
                "stable_gains".into(),
                intervals(&discrete_stable_gains_exact(&num, &den)?),
            );
        }
    }
    Ok(doc)
}
