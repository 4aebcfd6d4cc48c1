//! [`Plant`]: a plant as the commands read it — its model (transfer function, state space, a
//! textbook model), its name, description and signal names, the coefficients as typed, and
//! the controller and loop selection — from coefficient text, a plant file, a model with
//! parameters or a batch line.

use std::path::Path;

use super::file::{self, MatrixSpec, PlantFile};
use super::text::{Coefficient, coefficients_of, parse_list, parse_matrix};
use nalgebra::DMatrix;

use crate::error::{LtiError, Result};
use crate::fmt::fmt_num;
use crate::lti::controller::LoopSystem;
use crate::lti::lattice::{Lattice, Output};
use crate::lti::{Controller, Domain, Model, Signals, StateSpace, TransferFunction, build_plant};

/// A plant as the user gave it: a name, a description, the model (transfer function or state
/// space), the names of its signals, and the coefficients as typed when it was given by them.
#[derive(Debug, Clone, PartialEq)]
pub struct Plant {
    /// Display name (the file's name, the model with its parameters, or G itself).
    pub name: String,
    /// What it is, with its input and output when known.
    pub description: Option<String>,
    /// The model.
    pub model: Model,
    /// Names of the inputs, outputs and states.
    pub signals: Signals,
    /// Numerator and denominator coefficients as typed (text kept), when given by them.
    pub typed: Option<(Vec<Coefficient>, Vec<Coefficient>)>,
    /// A controller in front of the plant (unity negative feedback), from a plant file's
    /// `[controller]` section or the command line.
    pub controller: Option<Controller>,
    /// Which transfer function of the loop the analyses read (`None`: the plant itself).
    pub selection: Option<LoopSystem>,
}

impl Plant {
    /// From coefficient lists typed as text (descending powers; the numerator defaults to 1).
    ///
    /// Errors: a token that is not a number, an empty list, and those of
    /// [`TransferFunction::from_descending`].
    pub fn from_text(num: Option<&str>, den: &str) -> Result<Plant> {
        let den = parse_list(den, "`den`")?;
        let num = match num {
            Some(n) => parse_list(n, "`num`")?,
            None => coefficients_of(&[1.0]),
        };
        Self::from_coefficients(num, den, None)
    }

    /// From coefficients (numerator, denominator) with their text.
    pub fn from_coefficients(
        num: Vec<Coefficient>,
        den: Vec<Coefficient>,
        name: Option<String>,
    ) -> Result<Plant> {
        let values = |c: &[Coefficient]| c.iter().map(|x| x.value).collect::<Vec<_>>();
        let tf = TransferFunction::from_descending(&values(&num), &values(&den))?;
        let mut plant = Self::from_tf(tf, name)?;
        plant.typed = Some((num, den));
        Ok(plant)
    }

    /// From a transfer function (named by its own text unless `name` is given).
    pub fn from_tf(tf: TransferFunction, name: Option<String>) -> Result<Plant> {
        let model = Model::Tf(tf);
        let Model::Tf(g) = &model else {
            unreachable!("just built")
        };
        let name = name.unwrap_or_else(|| g.to_string());
        Ok(Plant {
            name,
            description: None,
            signals: Signals::for_model(&model, vec![], vec![], vec![])?,
            model,
            typed: None,
            controller: None,
            selection: None,
        })
    }

    /// From a state-space model (size-checked: [`crate::lti::MAX_STATES`]).
    pub fn from_state_space(ss: StateSpace, name: Option<String>) -> Result<Plant> {
        ss.check_size()?;
        let (n, m, p) = (ss.order(), ss.n_inputs(), ss.n_outputs());
        let model = Model::Ss(ss);
        Ok(Plant {
            name: name.unwrap_or_else(|| {
                let s =
                    |k: usize, what: &str| format!("{k} {what}{}", if k == 1 { "" } else { "s" });
                format!(
                    "state-space model ({}, {}, {})",
                    s(n, "state"),
                    s(m, "input"),
                    s(p, "output")
                )
            }),
            description: None,
            signals: Signals::for_model(&model, vec![], vec![], vec![])?,
            model,
            typed: None,
            controller: None,
            selection: None,
        })
    }

    /// From the matrices A, B, C (and D, zero when absent) typed as text, rows separated by
    /// `;`: `a = "0 1; -4 -0.8"`, `b = "0; 1"`, `c = "1 0"`, `d = "0"`.
    ///
    /// Errors: a bad token, ragged rows, inconsistent dimensions (naming the matrices),
    /// NaN/∞ entries, more than [`crate::lti::MAX_STATES`] states.
    pub fn from_matrices_text(a: &str, b: &str, c: &str, d: Option<&str>) -> Result<Plant> {
        let a = parse_matrix(a, "`a`")?;
        let b = parse_matrix(b, "`b`")?;
        let c = parse_matrix(c, "`c`")?;
        let d = d.map(|d| parse_matrix(d, "`d`")).transpose()?;
        Self::from_state_space(state_space_of(a, b, c, d)?, None)
    }

    /// The transfer function, when the plant is one.
    pub fn tf(&self) -> Option<&TransferFunction> {
        match &self.model {
            Model::Tf(g) => Some(g),
            Model::Ss(_) => None,
        }
    }

    /// The plant as a state-space model (a transfer function in controllable canonical form;
    /// errors for an improper one).
    pub fn state_space(&self) -> Result<StateSpace> {
        match &self.model {
            Model::Tf(g) => StateSpace::from_tf(g),
            Model::Ss(ss) => Ok(ss.clone()),
        }
    }

    /// A textbook model ([`crate::lti::plant_specs`]) with parameter overrides, or the seed's
    /// linear lattice (`lattice`, parameters [`crate::lti::lattice::LATTICE_PARAMS`]), which
    /// is a state-space plant.
    ///
    /// Errors: an unknown model or parameter, an invalid value.
    ///
    /// ```
    /// use ltikit::lti::Plant;
    /// let p = Plant::from_model("lattice", &[("N".into(), 8.0), ("output".into(), 3.0)]).unwrap();
    /// assert_eq!((p.model.order(), p.model.dims()), (16, (1, 1)));
    /// assert_eq!(p.signals.outputs, vec!["q3 [m]".to_string()]);
    /// assert!(Plant::from_model("lattice", &[("N".into(), 1.0)]).is_err());
    /// ```
    pub fn from_model(name: &str, params: &[(String, f64)]) -> Result<Plant> {
        if name == "lattice" {
            return Self::from_lattice(&Lattice::from_params(params)?);
        }
        let (tf, used) = build_plant(name, params)?;
        let list = used
            .iter()
            .map(|(k, v)| format!("{k}={}", fmt_num(*v)))
            .collect::<Vec<_>>()
            .join(", ");
        Self::from_tf(tf, Some(format!("{name} ({list})")))
    }

    /// The seed's linear lattice (§2.4) as a state-space plant: states q1…qN, then
    /// v1…vN (the velocities); the force on one particle in, one displacement (or all) out.
    ///
    /// Errors: a model beyond [`crate::lti::MAX_STATES`] states or
    /// [`crate::lti::model::MAX_SIGNALS`] outputs.
    pub fn from_lattice(lat: &Lattice) -> Result<Plant> {
        let list = lat
            .params()
            .iter()
            .map(|(k, v)| format!("{k}={}", fmt_num(*v)))
            .collect::<Vec<_>>()
            .join(", ");
        let mut p = Self::from_state_space(lat.state_space()?, Some(format!("lattice ({list})")))?;
        let n = lat.n();
        let q = |j: usize| format!("q{j} [m]");
        let outputs = match lat.output() {
            Output::Particle(j) => vec![q(j)],
            Output::All => (1..=n).map(q).collect(),
        };
        let states = (1..=n)
            .map(|j| format!("q{j}"))
            .chain((1..=n).map(|j| format!("v{j}")))
            .collect();
        p.signals = Signals::for_model(
            &p.model,
            vec![format!("F{} [N]", lat.input())],
            outputs,
            states,
        )?;
        p.description = Some(format!(
            "The linear lattice of seed §2.4: {n} particles, {} boundary, ω0 = {} rad/s; input F = force on a particle, outputs q = displacements, states q then v = q̇.",
            lat.boundary().name(),
            fmt_num(lat.w0())
        ));
        Ok(p)
    }

    /// The same plant in `domain`: a discrete-time plant reads its coefficients in powers of z
    /// and its matrices as x\[k+1\] = A x\[k\] + B u\[k\].
    ///
    /// ```
    /// use ltikit::lti::{Domain, Plant};
    /// let p = Plant::from_text(Some("0.5"), "1 -0.5").unwrap()
    ///     .with_domain(Domain::discrete(0.1).unwrap()).unwrap();
    /// assert_eq!(p.domain().dt(), Some(0.1));
    /// assert_eq!(p.name, "0.5 / (z - 0.5)");
    /// ```
    pub fn with_domain(mut self, domain: Domain) -> Result<Plant> {
        let typed_name = match &self.model {
            Model::Tf(g) => self.name == g.to_string(),
            Model::Ss(_) => false,
        };
        self.model = match self.model {
            Model::Tf(g) => Model::Tf(g.with_domain(domain)),
            Model::Ss(ss) => Model::Ss(ss.with_domain(domain)),
        };
        if typed_name && let Model::Tf(g) = &self.model {
            self.name = g.to_string();
        }
        Ok(self)
    }

    /// The same plant with a dead time `delay` (s): G(s)·e^(−s·delay) for a transfer function,
    /// the same delay on every input of a state-space model. In discrete time the delay is a
    /// whole number d of periods, absorbed exactly as z^(−d) (the typed denominator gains d
    /// trailing zeros, so the exact path sees it too).
    ///
    /// Errors: those of [`TransferFunction::with_delay`](crate::TransferFunction::with_delay)
    /// and [`StateSpace::with_delays`](crate::StateSpace::with_delays).
    ///
    /// ```
    /// use ltikit::lti::Plant;
    /// let p = Plant::from_text(None, "1 1").unwrap().with_delay(0.5).unwrap();
    /// assert_eq!(p.name, "1 / (s + 1) · e^(-0.5 s)");
    /// assert_eq!(p.factored().unwrap().delay(), 0.5);
    /// ```
    pub fn with_delay(mut self, delay: f64) -> Result<Plant> {
        let delay = crate::lti::delay::check_delay(delay)?;
        if delay == 0.0 {
            return Ok(self);
        }
        let typed_name = match &self.model {
            Model::Tf(g) => self.name == g.to_string(),
            Model::Ss(_) => false,
        };
        self.model = match self.model {
            Model::Tf(g) => {
                if let (Some(dt), Some((_, den))) = (g.domain().dt(), self.typed.as_mut()) {
                    let d = crate::lti::delay::delay_samples(delay, dt)?;
                    den.extend((0..d).map(|_| super::text::Coefficient {
                        text: "0".into(),
                        value: 0.0,
                    }));
                }
                Model::Tf(g.with_delay(delay)?)
            }
            Model::Ss(ss) => {
                let m = ss.n_inputs();
                let out = ss.output_delays.clone();
                Model::Ss(ss.with_delays(vec![delay; m], out)?)
            }
        };
        if typed_name && let Model::Tf(g) = &self.model {
            self.name = g.to_string();
        }
        Ok(self)
    }

    /// A state-space plant with a dead time on each input and each output
    /// ([`StateSpace::with_delays`](crate::StateSpace::with_delays)); a transfer function
    /// takes the sum of its one input's and one output's delay.
    pub fn with_io_delays(mut self, input: Vec<f64>, output: Vec<f64>) -> Result<Plant> {
        match &self.model {
            Model::Ss(ss) => {
                self.model = Model::Ss(ss.clone().with_delays(input, output)?);
                Ok(self)
            }
            Model::Tf(_) => {
                if input.len() > 1 || output.len() > 1 {
                    return Err(LtiError::invalid(
                        "a transfer function has one input and one output: give one delay \
                         each (or `delay`)",
                    ));
                }
                let total =
                    input.first().copied().unwrap_or(0.0) + output.first().copied().unwrap_or(0.0);
                self.with_delay(total)
            }
        }
    }

    /// The dead time of a SISO plant (its channel's for a state-space model).
    pub fn delay(&self) -> f64 {
        match &self.model {
            Model::Tf(g) => g.delay(),
            Model::Ss(ss) => ss.channel_delay(0, 0),
        }
    }

    /// Continuous or discrete time.
    pub fn domain(&self) -> Domain {
        match &self.model {
            Model::Tf(g) => g.domain(),
            Model::Ss(ss) => ss.domain,
        }
    }

    /// From a plant record (see [`PlantFile`]).
    pub fn from_record(f: &PlantFile) -> Result<Plant> {
        Self::from_record_keyed(f).map_err(|k| k.1)
    }

    /// [`Plant::from_record`], an error with the key it is about (`den`, `params.M`,
    /// `controller`; `None` for the record as a whole), so that a file can say on which line.
    fn from_record_keyed(f: &PlantFile) -> std::result::Result<Plant, KeyedError> {
        let on = |key: &str| {
            let key = key.to_string();
            move |e: LtiError| Box::new((Some(key), e))
        };
        let whole = |e: LtiError| Box::new((None, e));
        let mut plant = match (&f.den, &f.model) {
            (Some(den), _) => {
                let num = match &f.num {
                    Some(n) => n.coefficients("`num`").map_err(on("num"))?,
                    None => coefficients_of(&[1.0]),
                };
                let den = den.coefficients("`den`").map_err(on("den"))?;
                Self::from_coefficients(num, den, None).map_err(whole)?
            }
            (None, Some(m)) => {
                let params: Vec<(String, f64)> =
                    f.params.iter().map(|(k, v)| (k.clone(), *v)).collect();
                Self::from_model(m, &params).map_err(|e| {
                    let key = match &e {
                        LtiError::UnknownParameter { name, .. }
                        | LtiError::InvalidParameter { name, .. } => format!("params.{name}"),
                        LtiError::UnknownModel { .. } => "model".into(),
                        _ => "params".into(),
                    };
                    Box::new((Some(key), e))
                })?
            }
            (None, None) => {
                let matrix = |m: &Option<MatrixSpec>, what: &str| {
                    m.as_ref()
                        .map(|x| x.matrix(&format!("`{what}`")))
                        .transpose()
                        .map_err(on(what))?
                        .ok_or_else(|| {
                            Box::new((
                                None,
                                LtiError::invalid(format!("a state-space plant needs `{what}`")),
                            ))
                        })
                };
                let d = match &f.d {
                    Some(d) => Some(d.matrix("`d`").map_err(on("d"))?),
                    None => None,
                };
                let ss = state_space_of(
                    matrix(&f.a, "a")?,
                    matrix(&f.b, "b")?,
                    matrix(&f.c, "c")?,
                    d,
                )
                .map_err(whole)?;
                let mut p = Self::from_state_space(ss, None).map_err(whole)?;
                let key = [
                    ("inputs", &f.inputs),
                    ("outputs", &f.outputs),
                    ("states", &f.states),
                ]
                .iter()
                .find(|(_, v)| !v.is_empty())
                .map(|(k, _)| *k);
                p.signals = Signals::for_model(
                    &p.model,
                    f.inputs.clone(),
                    f.outputs.clone(),
                    f.states.clone(),
                )
                .map_err(|e| Box::new((key.map(String::from), e)))?;
                p
            }
        };
        if let Some(n) = &f.name {
            plant.name = n.clone();
        }
        let mut desc = f.description.clone().unwrap_or_default();
        if let (Some(i), Some(o)) = (&f.input, &f.output) {
            if !desc.is_empty() {
                desc.push(' ');
            }
            desc.push_str(&format!("Input: {i}; output: {o}."));
        }
        plant.description = (!desc.is_empty()).then_some(desc);
        if let Some(c) = &f.controller {
            let params: Vec<(String, f64)> =
                c.params.iter().map(|(k, v)| (k.clone(), *v)).collect();
            plant.controller = Some(Controller::new(&c.kind, &params).map_err(on("controller"))?);
        }
        if let Some(dt) = f.dt {
            if f.model.is_some() {
                return Err(on("dt")(physical_model_has_no_dt()));
            }
            let domain = Domain::discrete(dt).map_err(on("dt"))?;
            plant = plant.with_domain(domain).map_err(on("dt"))?;
        }
        if let Some(t) = f.delay {
            plant = plant.with_delay(t).map_err(on("delay"))?;
        }
        if !f.input_delays.is_empty() || !f.output_delays.is_empty() {
            let key = if f.input_delays.is_empty() {
                "output_delays"
            } else {
                "input_delays"
            };
            plant = plant
                .with_io_delays(f.input_delays.clone(), f.output_delays.clone())
                .map_err(on(key))?;
        }
        Ok(plant)
    }

    /// A plant file (TOML, see [`PlantFile`]); errors name the file, and for a bad record the
    /// line, the column and the key ([`LtiError::BadRecord`]).
    ///
    /// ```
    /// use ltikit::lti::Plant;
    /// let dir = std::env::temp_dir().join(format!("ltikit-doc-{}", std::process::id()));
    /// std::fs::create_dir_all(&dir).unwrap();
    /// let path = dir.join("bad.toml");
    /// std::fs::write(&path, "name = \"x\"\nden = \"1 2 x\"\n").unwrap();
    /// let e = Plant::from_file(&path).unwrap_err().to_string();
    /// assert!(e.ends_with("bad.toml, line 2, column 1: `den`: 'x' is not a number"), "{e}");
    /// ```
    pub fn from_file(path: &Path) -> Result<Plant> {
        Self::from_file_at_depth(path, 0)
    }

    /// [`Plant::from_file`] for a file `depth` diagram files deep (a diagram file — one with
    /// a `[blocks]` table — is connected into one model, see `lti::plant::diagram`).
    pub(super) fn from_file_at_depth(path: &Path, depth: usize) -> Result<Plant> {
        let text = file::read_text(path)?;
        if super::diagram::is_diagram(&text) {
            return super::diagram::load(path, &text, depth);
        }
        let f = PlantFile::parse(&text).map_err(|e| file::in_file(path, e))?;
        Self::from_record_keyed(&f).map_err(|k| {
            let (key, e) = *k;
            file::at_key_in_file(path, &text, key.as_deref(), e)
        })
    }

    /// A batch line (JSON, the plant-file schema).
    pub fn from_json_line(text: &str) -> Result<Plant> {
        Self::from_json_line_at(text, None)
    }

    /// Line `line` (1-based) of a batch file: errors say "line 3, column 9: …" and name the
    /// key.
    ///
    /// ```
    /// use ltikit::lti::Plant;
    /// let e = Plant::from_json_line_at(r#"{"den": [1, 2], "model": "tank"}"#, Some(4))
    ///     .unwrap_err()
    ///     .to_string();
    /// assert!(e.starts_with("line 4: a plant needs exactly one of"), "{e}");
    /// let e = Plant::from_json_line_at(r#"{"den": "1 x"}"#, Some(2)).unwrap_err().to_string();
    /// assert_eq!(e, "line 2, column 2: `den`: 'x' is not a number");
    /// ```
    pub fn from_json_line_at(text: &str, line: Option<usize>) -> Result<Plant> {
        let f = PlantFile::parse_json_at(text, line).map_err(|e| match e {
            LtiError::BadRecord { location, message } if location.is_empty() => {
                file::at_key_in_line(text, line, None, LtiError::invalid(message))
            }
            other => other,
        })?;
        Self::from_record_keyed(&f).map_err(|k| {
            let (key, e) = *k;
            file::at_key_in_line(text, line, key.as_deref(), e)
        })
    }
}

/// A record error with the key it is about (`None`: the record as a whole), boxed (small
/// results).
type KeyedError = Box<(Option<String>, LtiError)>;

/// A state-space model from its matrices, D zero (p × m) when absent.
fn state_space_of(
    a: DMatrix<f64>,
    b: DMatrix<f64>,
    c: DMatrix<f64>,
    d: Option<DMatrix<f64>>,
) -> Result<StateSpace> {
    let d = d.unwrap_or_else(|| DMatrix::zeros(c.nrows(), b.ncols()));
    let ss = StateSpace::new(a, b, c, d)?;
    ss.check_size()?;
    Ok(ss)
}

/// The error for a sampling period given to a textbook model.
pub(crate) fn physical_model_has_no_dt() -> LtiError {
    LtiError::invalid(
        "the textbook models are continuous-time physics: sample one with `ltikit c2d` \
         instead of giving it a sampling period",
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_source_gives_the_same_plant() {
        let a = Plant::from_text(Some("1"), "1 0.4 4").unwrap();
        let b = Plant::from_json_line(r#"{"num": [1], "den": "1 0.4 4"}"#).unwrap();
        let c = Plant::from_record(
            &PlantFile::parse("name = \"x\"\nnum = \"1\"\nden = [1, 0.4, 4]").unwrap(),
        )
        .unwrap();
        let d = Plant::from_model("spring-mass-damper", &[]).unwrap();
        for p in [&b, &c, &d] {
            assert_eq!(p.tf(), a.tf());
        }
        assert_eq!(c.name, "x");
        assert_eq!(a.typed.as_ref().unwrap().1[1].text, "0.4");
    }

    #[test]
    fn state_space_from_text_and_records() {
        let p = Plant::from_matrices_text("0 1; -4 -0.8", "0; 1", "1 0", Some("0")).unwrap();
        let Model::Ss(ss) = &p.model else {
            panic!("state space expected")
        };
        assert_eq!((ss.order(), ss.n_inputs(), ss.n_outputs()), (2, 1, 1));
        let e = Plant::from_matrices_text("0 1; -4 -0.8", "0; 1; 2", "1 0", None)
            .unwrap_err()
            .to_string();
        assert!(e.contains("inconsistent dimensions"), "{e}");
        let e = Plant::from_matrices_text("0 1 2; -4 -0.8 1", "0; 1", "1 0", None)
            .unwrap_err()
            .to_string();
        assert!(e.contains("square"), "{e}");
        let r = Plant::from_json_line(
            r#"{"a": "-1 0; 0 -2", "b": [[1, 0], [0, 1]], "c": [[1, 1]], "outputs": ["sum"]}"#,
        )
        .unwrap();
        assert_eq!(r.model.dims(), (2, 1));
        assert_eq!(r.signals.outputs, vec!["sum".to_string()]);
        assert_eq!(r.signals.inputs, vec!["u1".to_string(), "u2".to_string()]);
    }

    #[test]
    fn errors_name_the_problem() {
        let e = Plant::from_text(None, "1 nan").unwrap_err().to_string();
        assert!(e.contains("NaN"), "{e}");
        let e = Plant::from_json_line(r#"{"den": [1], "model": "tank"}"#)
            .unwrap_err()
            .to_string();
        assert!(e.contains("exactly one of"), "{e}");
        let e = Plant::from_model("tank", &[("Q".into(), 1.0)])
            .unwrap_err()
            .to_string();
        assert!(e.contains("'Q'"), "{e}");
    }
}
