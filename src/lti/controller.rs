//! Controllers: P, PI, PD, PID with a derivative filter, lead and lag, read from one spec
//! `KIND:NAME=VALUE,…` (the `--controller` option) or from a plant file's `[controller]`
//! section (`kind = "pid"` and the same names).
//!
//! | kind | parameters (missing gains are 0) | C(s) |
//! |---|---|---|
//! | `p` | `kp` | kp |
//! | `pi` | `kp`, `ki` | kp + ki/s |
//! | `pd` | `kp`, `kd`, `tf` (≥ 0, default 0) | kp + kd·s/(tf·s + 1) |
//! | `pid` | `kp`, `ki`, `kd`, `tf` (≥ 0, default 0) | kp + ki/s + kd·s/(tf·s + 1) |
//! | `lead` | `k`, `z`, `p` (0 < z < p) | k·(s + z)/(s + p) |
//! | `lag` | `k`, `z`, `p` (0 < p < z) | k·(s + z)/(s + p) |
//! | `tf` | `tf:NUM/DEN`, coefficient lists in descending powers | NUM/DEN **in the loop's own variable**: s for a continuous plant, z for a discrete one (a controller given in z is used as given, not discretised) |
//!
//! `tf` is the time constant of the derivative filter (MATLAB's `Tf` of `pid(Kp, Ki, Kd, Tf)`);
//! `tf = 0` leaves the derivative unfiltered, an improper controller that only a plant with
//! enough roll-off can take. A term whose gain is 0 is left out (no integrator for `ki = 0`).
//!
//! ```
//! use ltikit::lti::Controller;
//! let c = Controller::parse("pid:kp=2,ki=1,kd=0.5,tf=0.01").unwrap();
//! let g = c.tf().unwrap();
//! // (kp·tf + kd) s² + (kp + ki·tf) s + ki over tf·s² + s
//! assert_eq!(g.num().coeffs(), &[0.52, 2.01, 1.0]);
//! assert_eq!(g.den().coeffs(), &[0.01, 1.0, 0.0]);
//! assert_eq!(c.to_string(), "pid:kp=2,ki=1,kd=0.5,tf=0.01");
//! let e = Controller::parse("pid:kq=1").unwrap_err().to_string();
//! assert!(e.contains("kp, ki, kd, tf"), "{e}");
//! ```

use serde::Serialize;
use std::fmt;

use crate::error::{LtiError, Result, abbreviate};
use crate::fmt::fmt_num;
use crate::lti::{Discretization, TransferFunction};
use crate::poly::Poly;

/// Which transfer function of the loop to analyse.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum LoopSystem {
    /// The loop L = C·G.
    Loop,
    /// The closed loop T = L/(1 + L) (reference to output).
    ClosedLoop,
    /// The sensitivity S = 1/(1 + L) (reference to error; output disturbance to output).
    Sensitivity,
    /// The control sensitivity C·S (reference to control signal).
    ControlSensitivity,
}

impl LoopSystem {
    /// The usual formula, e.g. "T = L/(1 + L)".
    pub fn formula(self) -> &'static str {
        match self {
            LoopSystem::Loop => "L = C·G",
            LoopSystem::ClosedLoop => "T = L/(1 + L)",
            LoopSystem::Sensitivity => "S = 1/(1 + L)",
            LoopSystem::ControlSensitivity => "C·S = C/(1 + L)",
        }
    }
}

/// The kinds of controller, with their parameter names.
const KINDS: &[(&str, &[&str])] = &[
    ("p", &["kp"]),
    ("pi", &["kp", "ki"]),
    ("pd", &["kp", "kd", "tf"]),
    ("pid", &["kp", "ki", "kd", "tf"]),
    ("lead", &["k", "z", "p"]),
    ("lag", &["k", "z", "p"]),
];

/// A controller: its kind and parameters (validated; see the [module docs](self)).
#[derive(Debug, Clone, PartialEq)]
pub struct Controller {
    kind: &'static str,
    params: Vec<(&'static str, f64)>,
    /// How C(s) becomes C(z) in front of a discrete-time plant (Tustin by default).
    method: Discretization,
    /// The `tf` kind: its coefficients (numerator, denominator, descending powers), read in
    /// the loop's variable.
    coefficients: Option<(Vec<f64>, Vec<f64>)>,
}

impl Controller {
    /// Reads `KIND:NAME=VALUE,…` (`p:kp=2`, `pi:kp=1,ki=0.5`, `lead:k=4,z=1,p=10`; `KIND`
    /// alone is allowed for a kind whose parameters all have defaults — none has).
    ///
    /// Errors: an unknown kind or parameter (the known ones are named), a value that is not a
    /// number, a parameter given twice, and those of [`Controller::new`].
    pub fn parse(spec: &str) -> Result<Controller> {
        let (kind, rest) = spec.split_once(':').unwrap_or((spec, ""));
        if kind.trim().eq_ignore_ascii_case("tf") {
            let Some((num, den)) = rest.split_once('/') else {
                return Err(LtiError::invalid(
                    "`controller` tf:NUM/DEN: give the numerator and the denominator \
                     coefficients separated by '/', e.g. tf:0.5 -0.4/1 -1",
                ));
            };
            let list = |text: &str, what: &str| -> Result<Vec<f64>> {
                text.split([' ', ','])
                    .filter(|t| !t.is_empty())
                    .map(|t| {
                        t.parse::<f64>()
                            .map_err(|_| LtiError::bad_number(what, t, "is not a number"))
                    })
                    .collect()
            };
            return Controller::from_coefficients(
                &list(num, "`controller` numerator")?,
                &list(den, "`controller` denominator")?,
            );
        }
        let mut params = Vec::new();
        for item in rest.split(',').map(str::trim).filter(|s| !s.is_empty()) {
            let Some((k, v)) = item.split_once('=') else {
                return Err(LtiError::bad_number(
                    "`controller`",
                    item,
                    "is not NAME=VALUE",
                ));
            };
            let v = v.trim();
            let value = v
                .parse::<f64>()
                .map_err(|_| LtiError::bad_number("`controller`", v, "is not a number"))?;
            params.push((k.trim().to_string(), value));
        }
        Self::new(kind.trim(), &params)
    }

    /// A controller given by its transfer-function coefficients (descending powers), read in
    /// the loop's own variable: s in front of a continuous plant, z in front of a discrete one
    /// (there it is used as given, not discretised — a digital controller designed in z).
    ///
    /// Errors: those of [`TransferFunction::from_descending`] (empty or zero denominator,
    /// NaN/∞).
    ///
    /// ```
    /// use ltikit::lti::Controller;
    /// // a digital PI in z: C(z) = (0.5 z − 0.4)/(z − 1)
    /// let c = Controller::parse("tf:0.5 -0.4/1 -1").unwrap();
    /// assert_eq!(c.tf().unwrap().to_string(), "(0.5 s - 0.4) / (s - 1)");
    /// assert_eq!(c.to_string(), "tf:0.5 -0.4/1 -1");
    /// assert!(c.is_given_in_loop_variable());
    /// ```
    pub fn from_coefficients(num: &[f64], den: &[f64]) -> Result<Controller> {
        let g = TransferFunction::from_descending(num, den)?;
        Ok(Controller {
            kind: "tf",
            params: Vec::new(),
            method: Discretization::Tustin { prewarp: None },
            coefficients: Some((g.num().coeffs().to_vec(), g.den().coeffs().to_vec())),
        })
    }

    /// True for a controller given by coefficients (`tf`): read in the loop's variable, so in
    /// front of a discrete plant it is already C(z).
    pub fn is_given_in_loop_variable(&self) -> bool {
        self.coefficients.is_some()
    }

    /// A controller of `kind` with `params` (names as in the [module docs](self)).
    ///
    /// Errors: an unknown kind or parameter, a parameter given twice, a NaN or infinite value,
    /// a negative filter time constant, all gains 0, a lead/lag without 0 < z < p (lead) or
    /// 0 < p < z (lag), k = 0.
    pub fn new(kind: &str, params: &[(String, f64)]) -> Result<Controller> {
        let lower = kind.to_ascii_lowercase();
        let Some(&(kind, names)) = KINDS.iter().find(|(k, _)| *k == lower) else {
            return Err(LtiError::invalid(format!(
                "unknown controller kind '{}' (known: {}, tf)",
                abbreviate(kind),
                KINDS.iter().map(|(k, _)| *k).collect::<Vec<_>>().join(", ")
            )));
        };
        let mut out: Vec<(&'static str, f64)> = Vec::new();
        for (name, value) in params {
            let Some(&n) = names.iter().find(|n| n.eq_ignore_ascii_case(name)) else {
                return Err(LtiError::invalid(format!(
                    "controller '{kind}' has no parameter '{}' (parameters: {})",
                    abbreviate(name),
                    names.join(", ")
                )));
            };
            if out.iter().any(|(m, _)| *m == n) {
                return Err(LtiError::invalid(format!(
                    "controller '{kind}': parameter '{n}' given twice"
                )));
            }
            if !value.is_finite() {
                return Err(LtiError::NonFinite {
                    what: format!("controller parameter {n}"),
                    value: *value,
                });
            }
            out.push((n, *value));
        }
        out.sort_by_key(|(n, _)| names.iter().position(|m| m == n));
        let c = Controller {
            kind,
            params: out,
            method: Discretization::Tustin { prewarp: None },
            coefficients: None,
        };
        c.validate()?;
        Ok(c)
    }

    /// The kind (`p`, `pi`, `pd`, `pid`, `lead`, `lag`).
    pub fn kind(&self) -> &str {
        self.kind
    }

    /// A parameter's value (0 when not given).
    pub fn get(&self, name: &str) -> f64 {
        self.params
            .iter()
            .find(|(n, _)| *n == name)
            .map_or(0.0, |p| p.1)
    }

    fn validate(&self) -> Result<()> {
        let bad = |name: &str, reason: &str| LtiError::InvalidParameter {
            name: name.into(),
            value: self.get(name),
            reason: reason.into(),
        };
        match self.kind {
            "lead" | "lag" => {
                let (k, z, p) = (self.get("k"), self.get("z"), self.get("p"));
                for n in ["k", "z", "p"] {
                    if !self.params.iter().any(|(m, _)| *m == n) {
                        return Err(LtiError::invalid(format!(
                            "controller '{}' needs k, z and p: C(s) = k·(s + z)/(s + p); '{n}' is missing",
                            self.kind
                        )));
                    }
                }
                if k == 0.0 {
                    return Err(bad("k", "the gain must not be 0"));
                }
                if z <= 0.0 || p <= 0.0 {
                    let n = if z <= 0.0 { "z" } else { "p" };
                    return Err(bad(n, "z and p must be positive (zero at −z, pole at −p)"));
                }
                if self.kind == "lead" && z >= p {
                    return Err(bad("z", "a lead compensator needs z < p (phase lead)"));
                }
                if self.kind == "lag" && p >= z {
                    return Err(bad("p", "a lag compensator needs p < z (phase lag)"));
                }
            }
            _ => {
                if self.get("tf") < 0.0 {
                    return Err(bad(
                        "tf",
                        "the derivative filter time constant must be ≥ 0 (0: no filter)",
                    ));
                }
                if ["kp", "ki", "kd"].iter().all(|n| self.get(n) == 0.0) {
                    return Err(LtiError::invalid(format!(
                        "controller '{}' has all gains 0 (give kp, ki or kd)",
                        self.kind
                    )));
                }
            }
        }
        Ok(())
    }

    /// The same controller, discretised by `method` in front of a discrete-time plant.
    ///
    /// ```
    /// use ltikit::lti::{Controller, Discretization};
    /// let c = Controller::parse("pi:kp=1,ki=0.5").unwrap().with_method(Discretization::Zoh);
    /// assert_eq!(c.method(), Discretization::Zoh);
    /// ```
    pub fn with_method(mut self, method: Discretization) -> Controller {
        self.method = method;
        self
    }

    /// How C(s) is discretised in front of a discrete-time plant (Tustin unless set).
    pub fn method(&self) -> Discretization {
        self.method
    }

    /// True when C(s) is improper (a derivative term without a filter).
    pub fn is_improper(&self) -> bool {
        self.get("kd") != 0.0 && self.get("tf") == 0.0
    }

    /// C(s) as a transfer function (the terms with gain 0 left out).
    ///
    /// Errors: none for a validated controller beyond those of [`TransferFunction::new`].
    pub fn tf(&self) -> Result<TransferFunction> {
        if let Some((num, den)) = &self.coefficients {
            return TransferFunction::from_descending(num, den);
        }
        if let "lead" | "lag" = self.kind {
            return TransferFunction::from_descending(
                &[self.get("k"), self.get("k") * self.get("z")],
                &[1.0, self.get("p")],
            );
        }
        let (kp, ki, kd, tf) = (
            self.get("kp"),
            self.get("ki"),
            self.get("kd"),
            self.get("tf"),
        );
        let s = Poly::s();
        let one = Poly::from_descending(&[1.0])?;
        let integ = if ki != 0.0 { s.clone() } else { one.clone() };
        let filter = if kd != 0.0 && tf > 0.0 {
            Poly::from_descending(&[tf, 1.0])?
        } else {
            one.clone()
        };
        let den = &integ * &filter;
        let mut num = den.scale(kp);
        if ki != 0.0 {
            num = &num + &filter.scale(ki);
        }
        if kd != 0.0 {
            num = &num + &(&s * &integ).scale(kd);
        }
        TransferFunction::new(num, den)
    }
}

impl fmt::Display for Controller {
    /// The spec that reads back as this controller: `pid:kp=2,ki=1,kd=0.5,tf=0.01`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if let Some((num, den)) = &self.coefficients {
            let text = |c: &[f64]| c.iter().map(|x| fmt_num(*x)).collect::<Vec<_>>().join(" ");
            return write!(f, "tf:{}/{}", text(num), text(den));
        }
        let list: Vec<String> = self
            .params
            .iter()
            .map(|(n, v)| format!("{n}={}", fmt_num(*v)))
            .collect();
        write!(f, "{}:{}", self.kind, list.join(","))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn err(spec: &str) -> String {
        Controller::parse(spec).unwrap_err().to_string()
    }

    #[test]
    fn every_kind_builds_its_transfer_function() {
        let tf = |s: &str| Controller::parse(s).unwrap().tf().unwrap();
        assert_eq!(tf("p:kp=3").num().coeffs(), &[3.0]);
        let pi = tf("pi:kp=2,ki=0.5");
        assert_eq!(
            (pi.num().coeffs(), pi.den().coeffs()),
            (&[2.0, 0.5][..], &[1.0, 0.0][..])
        );
        let pd = tf("pd:kp=1,kd=2");
        assert_eq!(
            (pd.num().coeffs(), pd.den().coeffs()),
            (&[2.0, 1.0][..], &[1.0][..])
        );
        let pdf = tf("PD:kp=1,kd=2,tf=0.5");
        assert_eq!(pdf.num().coeffs(), &[2.5, 1.0]);
        assert_eq!(pdf.den().coeffs(), &[0.5, 1.0]);
        let lead = tf("lead:k=4,z=1,p=10");
        assert_eq!(
            (lead.num().coeffs(), lead.den().coeffs()),
            (&[4.0, 4.0][..], &[1.0, 10.0][..])
        );
        assert!(Controller::parse("pid:kp=1,kd=1").unwrap().is_improper());
    }

    #[test]
    fn bad_specs_are_named() {
        assert!(err("pdi:kp=1").contains("known: p, pi, pd, pid, lead, lag"));
        assert!(err("pi:kd=1").contains("parameters: kp, ki"));
        assert!(err("pid:kp=1,tf=-0.1").contains("≥ 0"));
        assert!(err("pid:kp=x").contains("not a number"));
        assert!(err("pid:kp").contains("NAME=VALUE"));
        assert!(err("pid:kp=1,kp=2").contains("twice"));
        assert!(err("pid:kp=nan").contains("NaN"));
        assert!(err("pi").contains("all gains 0"));
        assert!(err("lead:k=1,z=2,p=1").contains("z < p"));
        assert!(err("lag:k=1,z=1,p=2").contains("p < z"));
        assert!(err("lead:k=1,z=1").contains("'p' is missing"));
    }
}
