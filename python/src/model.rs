//! [`Model`]: one LTI model as the library holds it — a [`Plant`] (transfer function, state
//! space, textbook model, plant file) or a factored form (zeros, poles and gain; an
//! interconnection) — with its factorisation computed once, at the first analysis.

use std::sync::OnceLock;

use nalgebra::DMatrix;
use num_complex::Complex64;
use numpy::{PyArray1, PyArray2};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use serde_json::json;

use ltikit::analysis::{
    Factored, Input, RootLocusOptions, SsAnalysis, auto_frequency_grid, auto_time_grid,
};
use ltikit::lti::plant::{coefficients_of, matrix_of_rows};
use ltikit::lti::{Controller, Domain, Model as LtiModel, Plant, StateSpace, TransferFunction};
use ltikit::{LtiError, Root};

use crate::analyze::{analysis_json, step_info_json};
use crate::convert::{
    array, array2, carray, finite, multiplicities, pair, roots_array, ser_to_py, to_py,
};
use crate::{attempt, guard, mimo, tables};

/// Times and sampled values (flat), handed to Python together.
type Samples<'py> = (Bound<'py, PyArray1<f64>>, Bound<'py, PyArray1<f64>>);

/// A frequency response as arrays: w, |G|, the continuous phase (degrees), G.
type Response<'py> = (
    Bound<'py, PyArray1<f64>>,
    Bound<'py, PyArray1<f64>>,
    Bound<'py, PyArray1<f64>>,
    Bound<'py, PyArray1<Complex64>>,
);

/// Points of the automatic time and frequency grids (`t=None`, `w=None`).
const AUTO_POINTS: usize = 1000;

/// What a model is made of.
#[derive(Clone)]
enum Source {
    /// As the user gave it (coefficients with their text, matrices, a textbook model, a file).
    Plant(Box<Plant>),
    /// Known by its factors only (zeros, poles and gain; an interconnection).
    Factored(Box<Factored>),
}

/// An LTI model (SISO or MIMO, continuous or discrete time). Built by the functions of the
/// `ltikit` module (`tf`, `zpk`, `ss`, `model`, `plant`, `pid`); the Python class
/// `ltikit.System` wraps it.
#[pyclass(frozen, module = "ltikit._core")]
pub struct Model {
    source: Source,
    /// The factored form of a SISO model, computed at the first analysis (or its error).
    factored: OnceLock<Result<Factored, String>>,
    /// The whole-model state-space analysis, computed at the first whole-model call.
    whole: OnceLock<Result<SsAnalysis, String>>,
}

impl Model {
    fn of_plant(p: Plant) -> Model {
        Model {
            source: Source::Plant(Box::new(p)),
            factored: OnceLock::new(),
            whole: OnceLock::new(),
        }
    }

    fn of_factored(f: Factored) -> Model {
        Model {
            source: Source::Factored(Box::new(f)),
            factored: OnceLock::new(),
            whole: OnceLock::new(),
        }
    }

    /// The factored form (SISO only; the library's error for a MIMO model).
    pub fn factored(&self) -> PyResult<&Factored> {
        self.factored_or_message().map_err(crate::LtiError::new_err)
    }

    /// The factored form, or the one-line message of why there is none.
    pub fn factored_or_message(&self) -> Result<&Factored, String> {
        match &self.source {
            Source::Factored(f) => Ok(f),
            Source::Plant(p) => self
                .factored
                .get_or_init(|| attempt(|| p.factored()))
                .as_ref()
                .map_err(Clone::clone),
        }
    }

    /// The transfer function (with the coefficients as typed, when typed) a Routh or Jury
    /// table is built on: refused for a state-space model, as the command line refuses it.
    fn transfer_function(
        &self,
        command: &str,
    ) -> ltikit::Result<(TransferFunction, Option<&tables::Typed>)> {
        match &self.source {
            Source::Plant(p) => match &p.model {
                LtiModel::Tf(g) => Ok((g.clone(), p.typed.as_ref())),
                LtiModel::Ss(_) => Err(LtiError::invalid(format!(
                    "{command} needs a transfer function (its characteristic polynomial); this \
                     model is a state-space model"
                ))),
            },
            Source::Factored(f) => match f.transfer_function() {
                Some(g) => Ok((g.clone(), None)),
                None => Ok((
                    TransferFunction::from_zpk(
                        &crate::convert::repeated(f.zeros()),
                        &crate::convert::repeated(f.poles()),
                        f.gain(),
                    )?
                    .with_domain(f.domain()),
                    None,
                )),
            },
        }
    }

    /// The whole-model analysis of the state-space model (computed once).
    fn whole(&self) -> PyResult<&SsAnalysis> {
        self.whole
            .get_or_init(|| attempt(|| self.state_space()?.analysis()))
            .as_ref()
            .map_err(|e| crate::LtiError::new_err(e.clone()))
    }

    /// The state-space model as given (`None` for a transfer function or factors).
    fn given_state_space(&self) -> Option<&StateSpace> {
        match &self.source {
            Source::Plant(p) => match &p.model {
                LtiModel::Ss(ss) => Some(ss),
                LtiModel::Tf(_) => None,
            },
            Source::Factored(_) => None,
        }
    }

    /// The state-space model an initial state refers to: refused for a model not given by
    /// its matrices (its states would be those of a realisation the user never saw).
    fn state_space_for_x0(&self) -> ltikit::Result<&StateSpace> {
        self.given_state_space().ok_or_else(|| {
            LtiError::invalid(
                "an initial state needs a state-space model (lk.ss): a transfer function's \
                 states are not defined",
            )
        })
    }

    /// Times for the whole model: `t`, or 1000 points over the longest automatic window of
    /// its channels (multiples of the period in discrete time).
    fn whole_times(&self, ss: &StateSpace, t: Option<Vec<f64>>) -> ltikit::Result<Vec<f64>> {
        if let Some(t) = t {
            return Ok(t);
        }
        let mut t_end: f64 = 0.0;
        for j in 0..ss.n_outputs() {
            for i in 0..ss.n_inputs() {
                let f = Factored::from_state_space(&ss.channel(i, j)?)?;
                t_end = t_end.max(ltikit::analysis::auto_time_span(&f)?.t_end);
            }
        }
        if !(t_end.is_finite() && t_end > 0.0) {
            t_end = 10.0;
        }
        Ok(match ss.domain.dt() {
            Some(dt) => {
                let k = ((t_end / dt).ceil() as usize).clamp(1, AUTO_POINTS - 1);
                (0..=k).map(|i| i as f64 * dt).collect()
            }
            None => (0..AUTO_POINTS)
                .map(|i| t_end * i as f64 / (AUTO_POINTS - 1) as f64)
                .collect(),
        })
    }

    /// Frequencies for the whole model: `w`, or 1000 points spanning every channel's
    /// automatic grid.
    fn whole_frequencies(&self, ss: &StateSpace, w: Option<Vec<f64>>) -> ltikit::Result<Vec<f64>> {
        if let Some(w) = w {
            return Ok(w);
        }
        let (mut lo, mut hi) = (f64::INFINITY, 0.0_f64);
        for j in 0..ss.n_outputs() {
            for i in 0..ss.n_inputs() {
                let f = Factored::from_state_space(&ss.channel(i, j)?)?;
                let g = auto_frequency_grid(&f, AUTO_POINTS)?;
                if let (Some(&a), Some(&b)) = (g.first(), g.last()) {
                    lo = lo.min(a);
                    hi = hi.max(b);
                }
            }
        }
        if !(lo.is_finite() && lo > 0.0 && hi > lo) {
            (lo, hi) = (1e-2, 1e2);
        }
        let (a, b) = (lo.log10(), hi.log10());
        Ok((0..AUTO_POINTS)
            .map(|i| 10f64.powf(a + (b - a) * i as f64 / (AUTO_POINTS - 1) as f64))
            .collect())
    }

    /// The model as a state-space model (a transfer function realised; factors as a cascade).
    /// A dead time stays on the realisation's input, so that a call that cannot take one
    /// (a simulated response) says so instead of dropping it.
    pub(crate) fn state_space(&self) -> ltikit::Result<StateSpace> {
        let (ss, delay) = match &self.source {
            Source::Plant(p) => (p.state_space()?, p.delay()),
            Source::Factored(f) => (
                StateSpace::from_zpk(f.zeros(), f.poles(), f.gain())?.with_domain(f.domain()),
                f.delay(),
            ),
        };
        if delay > 0.0 && !ss.has_delays() {
            let m = ss.n_inputs();
            return ss.with_delays(vec![delay; m], vec![]);
        }
        Ok(ss)
    }

    /// The state-space model a design (`lqr`, `lqe`, `lqg`, `place`) works on: the plant
    /// itself, refused (as the command line refuses it) with a plant file's controller, a
    /// dead time, or no states.
    pub(crate) fn design_state_space(&self, command: &str) -> ltikit::Result<StateSpace> {
        let delay = match &self.source {
            Source::Plant(p) => {
                if p.controller.is_some() {
                    return Err(LtiError::invalid(format!(
                        "{command} designs on the plant itself: the plant file's [controller] is not taken"
                    )));
                }
                p.delay()
            }
            Source::Factored(f) => f.delay(),
        };
        if delay > 0.0 {
            return Err(LtiError::invalid(format!(
                "{command}: the plant has a dead time of {} s; the design needs a delay-free \
                 state-space model",
                ltikit::fmt::fmt_num(delay)
            )));
        }
        let ss = self.state_space()?;
        if !ss.input_delays.is_empty() || !ss.output_delays.is_empty() {
            return Err(LtiError::invalid(format!(
                "{command}: the plant has dead times on its inputs or outputs"
            )));
        }
        if ss.order() == 0 {
            return Err(LtiError::invalid(format!(
                "{command}: the plant has no states (a static gain): there is nothing to design"
            )));
        }
        Ok(ss)
    }

    /// The state-space model a norm, Gramian or reduction works on (as the command line's):
    /// a state-space model as given, otherwise the minimal realisation of the factored form.
    pub(crate) fn norm_state_space(&self) -> PyResult<StateSpace> {
        if let Source::Plant(p) = &self.source
            && let LtiModel::Ss(ss) = &p.model
        {
            return Ok(ss.clone());
        }
        let f = self.factored()?;
        guard(|| f.norm_realization())
    }

    fn domain(&self) -> Domain {
        match &self.source {
            Source::Plant(p) => p.domain(),
            Source::Factored(f) => f.domain(),
        }
    }

    /// (outputs, inputs).
    fn dims(&self) -> (usize, usize) {
        match &self.source {
            Source::Plant(p) => {
                let (m, q) = p.model.dims();
                (q, m)
            }
            Source::Factored(_) => (1, 1),
        }
    }

    fn is_siso(&self) -> bool {
        self.dims() == (1, 1)
    }

    /// An interconnection: on the factored forms for SISO models (roots kept, nothing
    /// re-rooted), on the state-space models otherwise.
    fn join(
        &self,
        other: &Model,
        siso: impl FnOnce(&Factored, &Factored) -> ltikit::Result<Factored>,
        mimo: impl FnOnce(&StateSpace, &StateSpace) -> ltikit::Result<StateSpace>,
    ) -> PyResult<Model> {
        if self.is_siso() && other.is_siso() {
            let (a, b) = (self.factored()?, other.factored()?);
            return guard(|| siso(a, b)).map(Model::of_factored);
        }
        guard(|| {
            let ss = mimo(&self.state_space()?, &other.state_space()?)?;
            Plant::from_state_space(ss, None)
        })
        .map(Model::of_plant)
    }
}

/// A period `dt` as the library's domain (`None`: continuous time).
fn domain_of(dt: Option<f64>) -> ltikit::Result<Domain> {
    Domain::from_dt(dt)
}

/// Roots listed with repetition (complex numbers) as the library's roots.
fn roots_of(values: &[Complex64]) -> Vec<Root> {
    values.iter().map(|&v| Root::new(v, 1)).collect()
}

/// A matrix from rows of numbers (ragged rows are an error naming the matrix).
fn matrix(rows: Vec<Vec<f64>>, what: &str) -> ltikit::Result<DMatrix<f64>> {
    matrix_of_rows(rows, what)
}

/// Plot options: a title and a size in pixels.
fn plot_options(
    title: Option<String>,
    size: Option<(u32, u32)>,
) -> ltikit::Result<ltikit::plot::PlotOptions> {
    let mut o = ltikit::plot::PlotOptions {
        title,
        ..Default::default()
    };
    if let Some(s) = size {
        o.size = s;
    }
    o.validate()?;
    Ok(o)
}

/// A standard input by name: `step`, `impulse`, `ramp`, `exp:A`, `sin:W`, `cos:W`.
fn input_of(name: &str) -> ltikit::Result<Input> {
    name.parse::<Input>()
}

#[pymethods]
impl Model {
    // ---- constructors -------------------------------------------------------------------

    /// A transfer function from coefficients in descending powers (read like a plant file's
    /// lists: the exact path decides the structure from their shortest decimal text).
    #[staticmethod]
    #[pyo3(signature = (num, den, dt=None, delay=None))]
    fn from_tf(
        num: Vec<f64>,
        den: Vec<f64>,
        dt: Option<f64>,
        delay: Option<f64>,
    ) -> PyResult<Model> {
        guard(|| {
            if den.is_empty() {
                return Err(LtiError::invalid("`den`: no numbers given"));
            }
            if num.is_empty() {
                return Err(LtiError::invalid("`num`: no numbers given"));
            }
            // named when the name is first asked for (`name`): formatting the transfer
            // function's text is a tenth of a small plant's whole analysis
            let p = Plant::from_coefficients(
                coefficients_of(&num),
                coefficients_of(&den),
                Some(String::new()),
            )?;
            // (continuous time is the default: no re-typing for dt = None)
            let p = match dt {
                Some(_) => p.with_domain(domain_of(dt)?)?,
                None => p,
            };
            p.with_delay(delay.unwrap_or(0.0))
        })
        .map(Model::of_plant)
    }

    /// Zeros, poles (complex, conjugate pairs complete, listed with repetition) and gain.
    #[staticmethod]
    #[pyo3(signature = (zeros, poles, gain, dt=None, delay=None))]
    fn from_zpk(
        zeros: Vec<Complex64>,
        poles: Vec<Complex64>,
        gain: f64,
        dt: Option<f64>,
        delay: Option<f64>,
    ) -> PyResult<Model> {
        guard(|| {
            let f = Factored::from_zpk(&roots_of(&zeros), &roots_of(&poles), gain)?
                .with_domain(domain_of(dt)?);
            match delay {
                Some(t) => f.with_delay(t),
                None => Ok(f),
            }
        })
        .map(Model::of_factored)
    }

    /// A state-space model from the rows of A, B, C and D (D zero when `None`), with the dead
    /// time `delay` on every input.
    #[staticmethod]
    #[pyo3(signature = (a, b, c, d=None, dt=None, delay=None))]
    fn from_ss(
        a: Vec<Vec<f64>>,
        b: Vec<Vec<f64>>,
        c: Vec<Vec<f64>>,
        d: Option<Vec<Vec<f64>>>,
        dt: Option<f64>,
        delay: Option<f64>,
    ) -> PyResult<Model> {
        guard(|| {
            let (a, b, c) = (matrix(a, "`a`")?, matrix(b, "`b`")?, matrix(c, "`c`")?);
            let d = match d {
                Some(d) => matrix(d, "`d`")?,
                None => DMatrix::zeros(c.nrows(), b.ncols()),
            };
            let ss = StateSpace::new(a, b, c, d)?.with_domain(domain_of(dt)?);
            Plant::from_state_space(ss, None)?.with_delay(delay.unwrap_or(0.0))
        })
        .map(Model::of_plant)
    }

    /// Blocks joined by named signals (the library's `connect`, what a diagram file is read
    /// into): each block (name, model, input signals, output signals), the summing junctions
    /// (signal, expression such as `"r - y"`), the external inputs and the outputs; one
    /// state-space model with the states in block order, named `BLOCK.x1`, ….
    #[staticmethod]
    #[pyo3(signature = (blocks, sums, inputs, outputs, name=None))]
    #[allow(clippy::type_complexity)]
    fn connect(
        blocks: Vec<(String, PyRef<'_, Model>, Vec<String>, Vec<String>)>,
        sums: Vec<(String, String)>,
        inputs: Vec<String>,
        outputs: Vec<String>,
        name: Option<String>,
    ) -> PyResult<Model> {
        use ltikit::lti::connect::{Block, Sum, connect};
        guard(|| {
            let mut bs = Vec::with_capacity(blocks.len());
            for (n, m, ins, outs) in &blocks {
                let what = format!("block `{}`", ltikit::error::abbreviate(n));
                let model = match &m.source {
                    // refused with a dead time, as a diagram file's block
                    Source::Plant(p) => ltikit::lti::connect::state_space_of(&p.model, &what)?,
                    Source::Factored(f) if f.delay() > 0.0 => {
                        return Err(LtiError::invalid(format!(
                            "{what} has a dead time: it is connected exactly only as a \
                             rational model (replace the delay by a Padé approximant)"
                        )));
                    }
                    Source::Factored(_) => m.state_space()?,
                };
                bs.push(Block {
                    name: n.clone(),
                    model,
                    inputs: ins.clone(),
                    outputs: outs.clone(),
                });
            }
            let sums = sums
                .iter()
                .map(|(n, e)| Sum::parse(n, e))
                .collect::<ltikit::Result<Vec<_>>>()?;
            let ss = connect(&bs, &sums, &inputs, &outputs)?;
            let states = bs
                .iter()
                .flat_map(|b| (1..=b.model.order()).map(move |k| format!("{}.x{k}", b.name)))
                .collect();
            let name = name.unwrap_or_else(|| format!("diagram ({} blocks)", bs.len()));
            let mut plant = Plant::from_state_space(ss, Some(name))?;
            plant.signals = ltikit::lti::Signals::for_model(&plant.model, inputs, outputs, states)?;
            Ok(plant)
        })
        .map(Model::of_plant)
    }

    /// A controller from its specification (`"pid:kp=2,ki=1"`, `"lead:k=1,z=1,p=10"`,
    /// `"tf:NUM/DEN"`: the command line's `--controller`), in the domain of `dt` as a diagram
    /// block takes it: a continuous controller in front of a discrete loop is sampled by the
    /// specification's method (Tustin by default).
    #[staticmethod]
    #[pyo3(signature = (spec, dt=None))]
    fn from_controller_spec(spec: &str, dt: Option<f64>) -> PyResult<Model> {
        guard(|| {
            let c = Controller::parse(spec)?;
            let g = c.tf()?;
            let domain = domain_of(dt)?;
            let g = match domain.dt() {
                Some(_) if c.is_given_in_loop_variable() => g.with_domain(domain),
                Some(t) => g.c2d(t, c.method())?,
                None => g,
            };
            Plant::from_tf(g, Some(c.to_string()))
        })
        .map(Model::of_plant)
    }

    /// The names of the inputs, outputs and states (empty when the model has none).
    fn signal_names(&self) -> (Vec<String>, Vec<String>, Vec<String>) {
        match &self.source {
            Source::Plant(p) => (
                p.signals.inputs.clone(),
                p.signals.outputs.clone(),
                p.signals.states.clone(),
            ),
            Source::Factored(_) => (vec![], vec![], vec![]),
        }
    }

    /// A textbook model (or the seed's lattice) with parameter overrides.
    #[staticmethod]
    fn from_model(name: &str, params: Vec<(String, f64)>) -> PyResult<Model> {
        guard(|| Plant::from_model(name, &params)).map(Model::of_plant)
    }

    /// A plant file (TOML) or, with `line=True`, one batch line (JSON).
    #[staticmethod]
    fn from_plant_file(path: &str) -> PyResult<Model> {
        guard(|| Plant::from_file(std::path::Path::new(path))).map(Model::of_plant)
    }

    /// A batch line (JSON record: `num`/`den`, or `model` with `params`, optional `dt`).
    #[staticmethod]
    fn from_json_line(line: &str) -> PyResult<Model> {
        guard(|| Plant::from_json_line(line)).map(Model::of_plant)
    }

    /// A controller of `kind` (p, pi, pd, pid, lead, lag) as a transfer function.
    #[staticmethod]
    fn from_controller(kind: &str, params: Vec<(String, f64)>) -> PyResult<Model> {
        guard(|| {
            let c = Controller::new(kind, &params)?;
            Plant::from_tf(c.tf()?, Some(c.to_string()))
        })
        .map(Model::of_plant)
    }

    // ---- what it is ---------------------------------------------------------------------

    /// The model's name (its transfer function, the model with its parameters, the file).
    fn name(&self) -> String {
        match &self.source {
            Source::Plant(p) => match &p.model {
                LtiModel::Tf(g) if p.name.is_empty() => g.to_string(),
                _ => p.name.clone(),
            },
            Source::Factored(f) => f.to_string(),
        }
    }

    /// The model as the text report prints it: `G(s) = 4 / (s^2 + 0.8 s + 4)`, or the
    /// factors; a state-space model by its size.
    fn text(&self) -> String {
        let var = self.domain().variable();
        let dt = self
            .domain()
            .dt()
            .map(|t| format!(", dt = {}", ltikit::fmt::fmt_num(t)))
            .unwrap_or_default();
        match &self.source {
            Source::Factored(f) => format!("G({var}) = {f}{dt}"),
            Source::Plant(p) => match &p.model {
                LtiModel::Tf(g) => format!("G({var}) = {g}{dt}"),
                LtiModel::Ss(_) => format!("{}{dt}", p.name),
            },
        }
    }

    /// The sampling period (`None`: continuous time).
    fn dt(&self) -> Option<f64> {
        self.domain().dt()
    }

    /// (outputs, inputs).
    fn shape(&self) -> (usize, usize) {
        self.dims()
    }

    /// True for a state-space model (as given).
    fn is_state_space(&self) -> bool {
        matches!(&self.source, Source::Plant(p) if matches!(p.model, LtiModel::Ss(_)))
    }

    /// Numerator and denominator coefficients (descending) of a transfer function as given,
    /// or of the factored form expanded; `None` for a state-space model.
    #[allow(clippy::type_complexity)]
    fn coefficients<'py>(
        &self,
        py: Python<'py>,
    ) -> PyResult<Option<(Bound<'py, PyArray1<f64>>, Bound<'py, PyArray1<f64>>)>> {
        let tf: TransferFunction = match &self.source {
            Source::Plant(p) => match &p.model {
                LtiModel::Tf(g) => g.clone(),
                LtiModel::Ss(_) => return Ok(None),
            },
            Source::Factored(f) => match f.transfer_function() {
                Some(g) => g.clone(),
                None => guard(|| {
                    TransferFunction::from_zpk(
                        &crate::convert::repeated(f.zeros()),
                        &crate::convert::repeated(f.poles()),
                        f.gain(),
                    )
                })?,
            },
        };
        Ok(Some((
            array(py, tf.num().coeffs().to_vec()),
            array(py, tf.den().coeffs().to_vec()),
        )))
    }

    /// The matrices A, B, C, D (a transfer function in controllable canonical form).
    #[allow(clippy::type_complexity)]
    fn matrices<'py>(
        &self,
        py: Python<'py>,
    ) -> PyResult<(
        Bound<'py, PyArray2<f64>>,
        Bound<'py, PyArray2<f64>>,
        Bound<'py, PyArray2<f64>>,
        Bound<'py, PyArray2<f64>>,
    )> {
        let ss = guard(|| self.state_space())?;
        let rows = |m: &DMatrix<f64>| -> Vec<Vec<f64>> {
            (0..m.nrows())
                .map(|i| m.row(i).iter().copied().collect())
                .collect()
        };
        let two = |m: &DMatrix<f64>| -> PyResult<Bound<'py, PyArray2<f64>>> {
            if m.nrows() == 0 || m.ncols() == 0 {
                return Ok(PyArray2::zeros(py, [m.nrows(), m.ncols()], false));
            }
            array2(py, &rows(m))
        };
        Ok((two(&ss.a)?, two(&ss.b)?, two(&ss.c)?, two(&ss.d)?))
    }

    /// The channel from input `input` to output `output` (0-based) as a SISO model.
    fn channel(&self, output: usize, input: usize) -> PyResult<Model> {
        let (p, m) = self.dims();
        if output >= p || input >= m {
            return Err(crate::LtiError::new_err(format!(
                "channel [{output}, {input}] does not exist: the model has {p} output{} and {m} input{} (indices start at 0)",
                if p == 1 { "" } else { "s" },
                if m == 1 { "" } else { "s" }
            )));
        }
        match &self.source {
            Source::Factored(f) => Ok(Model::of_factored((**f).clone())),
            Source::Plant(pl) => match &pl.model {
                LtiModel::Tf(_) => Ok(Model::of_plant((**pl).clone())),
                LtiModel::Ss(ss) => guard(|| {
                    let mut c = Plant::from_state_space(ss.channel(input, output)?, None)?;
                    let names = &pl.signals;
                    if let (Some(u), Some(y)) = (names.inputs.get(input), names.outputs.get(output))
                    {
                        c.name = format!("{} ({u} → {y})", pl.name);
                    }
                    Ok(c)
                })
                .map(Model::of_plant),
            },
        }
    }

    // ---- analyses -----------------------------------------------------------------------

    /// The poles, listed with repetition (complex array).
    fn poles<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray1<Complex64>>> {
        Ok(roots_array(py, self.factored()?.poles()))
    }

    /// The zeros, listed with repetition (complex array).
    fn zeros<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray1<Complex64>>> {
        Ok(roots_array(py, self.factored()?.zeros()))
    }

    /// Distinct poles with their multiplicities.
    fn pole_multiplicities(&self) -> PyResult<Vec<(Complex64, usize)>> {
        Ok(multiplicities(self.factored()?.poles()))
    }

    /// Distinct zeros with their multiplicities.
    fn zero_multiplicities(&self) -> PyResult<Vec<(Complex64, usize)>> {
        Ok(multiplicities(self.factored()?.zeros()))
    }

    /// The gain k of G = k·Π(s − z)/Π(s − p).
    fn gain(&self) -> PyResult<f64> {
        Ok(self.factored()?.gain())
    }

    /// dc gain of the reduced G (G(1) in discrete time); `inf` when infinite.
    fn dc_gain(&self) -> PyResult<f64> {
        Ok(self.factored()?.dc_gain().unwrap_or(f64::INFINITY))
    }

    /// Stability: BIBO and internal, with the reasons.
    fn stability<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let f = self.factored()?;
        let s = guard(|| Ok(f.stability()))?;
        to_py(
            py,
            &json!({
                "bibo_stable": s.bibo_stable,
                "internally_stable": s.internally_stable,
                "reason": s.reason,
                "bibo_reason": s.bibo_reason,
                "internal_reason": s.internal_reason,
            }),
        )
    }

    /// The `analyze --json` document as a dict.
    fn analyze<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let f = self.factored()?;
        let a = guard(|| f.analyze())?;
        to_py(py, &analysis_json(&a))
    }

    /// Partial fractions of G: terms (pole, power, residue) and the direct part.
    fn residue<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let f = self.factored()?;
        let pf = guard(|| f.partial_fractions())?;
        let d = PyDict::new(py);
        let terms: Vec<(Complex64, usize, Complex64)> = pf
            .terms
            .iter()
            .map(|t| (t.pole, t.power, t.residue))
            .collect();
        d.set_item("terms", terms)?;
        d.set_item("direct", array(py, pf.direct.clone()))?;
        Ok(d)
    }

    /// The response to a standard input (`step`, `impulse`, `ramp`, `exp:A`, `sin:W`, `cos:W`)
    /// at the times `t` (an automatic grid when `None`): t, exact y, the final value, and the
    /// closed form with its transient and steady-state parts as text and sampled.
    #[pyo3(signature = (input, t=None))]
    fn response<'py>(
        &self,
        py: Python<'py>,
        input: &str,
        t: Option<Vec<f64>>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let f = self.factored()?;
        let r = guard(|| {
            let input = input_of(input)?;
            let t = match t {
                Some(t) => t,
                None => auto_time_grid(f, AUTO_POINTS)?,
            };
            f.response(&input, &[], &t)
        })?;
        let d = PyDict::new(py);
        let s = r.samples;
        d.set_item("t", array(py, s.t))?;
        d.set_item("y", array(py, s.y))?;
        d.set_item("final_value", r.final_value)?;
        d.set_item("closed_form", r.closed_form.to_string())?;
        d.set_item("transient", r.transient.to_string())?;
        d.set_item("steady_state", r.steady_state.to_string())?;
        d.set_item("closed_form_values", array(py, s.closed_form))?;
        d.set_item("closed_form_error", s.closed_form_error)?;
        Ok(d)
    }

    /// The response to sampled input values `u` (flat: one row of m values per time) at the
    /// times `t` (first-order hold by default, `hold="zoh"` for zero-order), from the initial
    /// state `x0` (zero when `None`; a state-space model only): every output, flat
    /// \[output\]\[time\].
    #[pyo3(signature = (u, t, hold="foh", x0=None))]
    fn lsim<'py>(
        &self,
        py: Python<'py>,
        u: Vec<f64>,
        t: Vec<f64>,
        hold: &str,
        x0: Option<Vec<f64>>,
    ) -> PyResult<Bound<'py, PyArray1<f64>>> {
        let y = guard(|| {
            let hold = mimo::hold_of(hold)?;
            match &x0 {
                Some(x0) => mimo::lsim(self.state_space_for_x0()?, &u, t, hold, Some(x0)),
                None => mimo::lsim(&self.state_space()?, &u, t, hold, None),
            }
        })?;
        Ok(array(py, y))
    }

    /// The free response from the initial state `x0` at the times `t` (a state-space model
    /// only): every output, flat \[output\]\[time\]; the times (automatic when `None`).
    #[pyo3(signature = (x0, t=None))]
    fn initial<'py>(
        &self,
        py: Python<'py>,
        x0: Vec<f64>,
        t: Option<Vec<f64>>,
    ) -> PyResult<Samples<'py>> {
        let (t, y) = guard(|| {
            let ss = self.state_space_for_x0()?;
            let t = self.whole_times(ss, t)?;
            let y = mimo::initial(ss, &x0, &t)?;
            Ok((t, y))
        })?;
        Ok((array(py, t), array(py, y)))
    }

    // ---- Routh and Jury -----------------------------------------------------------------

    /// The Routh–Hurwitz table of the characteristic polynomial (of D + K·N with `gain`),
    /// the root counts (exact for the coefficients as typed) and, with `gains`, the exact set
    /// of gains K for which the unity negative-feedback loop is stable (a dict).
    #[pyo3(signature = (gain=None, gains=true))]
    fn routh<'py>(
        &self,
        py: Python<'py>,
        gain: Option<f64>,
        gains: bool,
    ) -> PyResult<Bound<'py, PyAny>> {
        let doc = guard(|| {
            let (g, typed) = self.transfer_function("routh")?;
            tables::routh_doc(&g, typed, gain, gains)
        })?;
        to_py(py, &doc)
    }

    /// The Jury table of the characteristic polynomial in z (of D + K·N with `gain`), the
    /// counts inside, on and outside the unit circle and, with `gains`, the exact stabilising
    /// gains (a dict).
    #[pyo3(signature = (gain=None, gains=true))]
    fn jury<'py>(
        &self,
        py: Python<'py>,
        gain: Option<f64>,
        gains: bool,
    ) -> PyResult<Bound<'py, PyAny>> {
        let doc = guard(|| {
            let (g, typed) = self.transfer_function("jury")?;
            tables::jury_doc(&g, typed, gain, gains)
        })?;
        to_py(py, &doc)
    }

    // ---- the whole model (any numbers of inputs and outputs) ----------------------------

    /// The whole-model analysis of the state-space model (`analyze` of a state-space model:
    /// eigenvalues with multiplicities, controllability, observability, minimal order,
    /// invariant zeros with the Kronecker structure, dc gains, stability, modes) as a dict.
    fn whole_analysis<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        ser_to_py(py, self.whole()?)
    }

    /// The poles of the whole model: the eigenvalues of A, with repetition — the analysis's
    /// (snapped) values when it has been computed, otherwise the eigenvalues alone (the whole
    /// analysis is ten times the cost), sorted as the analysis sorts them.
    fn whole_poles<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray1<Complex64>>> {
        if let Some(Ok(a)) = self.whole.get() {
            return Ok(carray(py, mimo::poles(a)));
        }
        let mut ev = guard(|| self.state_space()?.eigenvalues())?;
        ev.sort_by(|x, y| y.re.total_cmp(&x.re).then(y.im.total_cmp(&x.im)));
        Ok(carray(py, ev))
    }

    /// The transmission zeros of the whole model (with repetition) and the Kronecker
    /// structure of the minimal system pencil (a dict).
    fn whole_zeros<'py>(
        &self,
        py: Python<'py>,
    ) -> PyResult<(Bound<'py, PyArray1<Complex64>>, Bound<'py, PyAny>)> {
        let (z, doc) = guard(|| mimo::zeros(&self.state_space()?))?;
        Ok((carray(py, z), to_py(py, &doc)?))
    }

    /// The dc-gain matrix, flat row by row (`inf` where a channel has a pole at 0): from the
    /// analysis once it exists, otherwise directly when A is clearly nonsingular (no pole at
    /// or near the dc point: the analysis would give the same finite values).
    fn whole_dc_gain<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray1<f64>>> {
        if self.whole.get().is_none() {
            let ss = guard(|| self.state_space())?;
            if !ss.has_delays()
                && let Some(g) = guard(|| mimo::dc_gain_direct(&ss))?
            {
                return Ok(array(py, g));
            }
        }
        Ok(array(py, mimo::dc_gain(self.whole()?)))
    }

    /// Internal and per-channel BIBO stability of the whole model (a dict).
    fn whole_stability<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        to_py(py, &mimo::stability(self.whole()?))
    }

    /// The frequency response of every channel: w, then |G|, the continuous phase (degrees)
    /// and G, each flat \[output\]\[input\]\[frequency\].
    #[pyo3(signature = (w=None))]
    fn whole_freq<'py>(&self, py: Python<'py>, w: Option<Vec<f64>>) -> PyResult<Response<'py>> {
        let (w, (mag, phase, g)) = guard(|| {
            let ss = self.state_space()?;
            let w = self.whole_frequencies(&ss, w)?;
            let r = mimo::freq(&ss, &w)?;
            Ok((w, r))
        })?;
        Ok((
            array(py, w),
            array(py, mag),
            array(py, phase),
            carray(py, g),
        ))
    }

    /// The unit-step (`impulse=True`: unit-impulse) response of every output to each input in
    /// turn: t, and y flat \[output\]\[input\]\[time\].
    #[pyo3(signature = (t=None, impulse=false))]
    fn whole_step<'py>(
        &self,
        py: Python<'py>,
        t: Option<Vec<f64>>,
        impulse: bool,
    ) -> PyResult<Samples<'py>> {
        let (t, y) = guard(|| {
            let ss = self.state_space()?;
            let t = self.whole_times(&ss, t)?;
            let y = mimo::per_input(&ss, &t, impulse)?;
            Ok((t, y))
        })?;
        Ok((array(py, t), array(py, y)))
    }

    /// The step metrics (MATLAB `stepinfo`) as `analyze --json` writes them, or `None` with
    /// the reason.
    fn step_info<'py>(&self, py: Python<'py>) -> PyResult<(Bound<'py, PyAny>, Option<String>)> {
        let f = self.factored()?;
        // the metrics alone; the whole analysis only to say why there are none
        if f.is_proper()
            && let Ok(Some(si)) = attempt(|| f.step_info())
        {
            return Ok((to_py(py, &step_info_json(&si))?, None));
        }
        let a = guard(|| f.analyze())?;
        let v = a
            .step_info
            .as_ref()
            .map_or(serde_json::Value::Null, step_info_json);
        Ok((to_py(py, &v)?, a.step_info_note))
    }

    /// Frequency response at `w` (rad/s; an automatic grid when `None`): w, |G|, the
    /// continuous phase in degrees, and G(jω) (G(e^(jωT)) in discrete time).
    #[pyo3(signature = (w=None))]
    fn freq<'py>(&self, py: Python<'py>, w: Option<Vec<f64>>) -> PyResult<Response<'py>> {
        let f = self.factored()?;
        let fr = guard(|| {
            let w = match w {
                Some(w) => w,
                None => auto_frequency_grid(f, AUTO_POINTS)?,
            };
            f.freq_response(&w)
        })?;
        let g: Vec<Complex64> = fr
            .magnitude
            .iter()
            .zip(&fr.phase_deg)
            .map(|(&m, &p)| Complex64::from_polar(m, p.to_radians()))
            .collect();
        Ok((
            array(py, fr.w),
            array(py, fr.magnitude),
            array(py, fr.phase_deg),
            carray(py, g),
        ))
    }

    /// Gain and phase margins, crossings, bandwidth, resonance, delay margin (a dict).
    fn margins<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let f = self.factored()?;
        let m = guard(|| f.margins())?;
        ser_to_py(py, &m)
    }

    /// The Nyquist contour: s (or z) on the contour, G there, and the counts (a dict).
    #[allow(clippy::type_complexity)]
    fn nyquist<'py>(
        &self,
        py: Python<'py>,
    ) -> PyResult<(
        Bound<'py, PyArray1<Complex64>>,
        Bound<'py, PyArray1<Complex64>>,
        Bound<'py, PyAny>,
    )> {
        let f = self.factored()?;
        let c = guard(|| f.nyquist())?;
        let s = c.points.iter().map(|p| p.s).collect();
        let g = c.points.iter().map(|p| p.g).collect();
        let meta = json!({
            "open_loop_rhp_poles": c.open_loop_rhp_poles,
            "encirclements": c.encirclements,
            "closed_loop_rhp_poles": c.closed_loop_rhp_poles,
            "g_at_infinity": finite(c.g_at_infinity),
            "axis_poles": c.axis_poles,
            "region": if c.dt.is_some() { "outside the unit circle" } else { "right half plane" },
        });
        Ok((carray(py, s), carray(py, g), to_py(py, &meta)?))
    }

    /// The root locus of 1 + K·G: gains, branches (one row per closed-loop pole, complex),
    /// and the rest of the locus (asymptotes, break points, crossings, angles) as a dict.
    #[allow(clippy::type_complexity)]
    #[pyo3(signature = (negative=false))]
    fn rlocus<'py>(
        &self,
        py: Python<'py>,
        negative: bool,
    ) -> PyResult<(
        Bound<'py, PyArray1<f64>>,
        Bound<'py, PyArray2<Complex64>>,
        Bound<'py, PyAny>,
    )> {
        let f = self.factored()?;
        let l = guard(|| {
            f.root_locus(&RootLocusOptions {
                negative,
                ..Default::default()
            })
        })?;
        let mut v = serde_json::to_value(&l).map_err(crate::lti_err)?;
        if let Some(o) = v.as_object_mut() {
            o.remove("gains");
            o.remove("branches");
        }
        let gains = array(py, l.branches.gains.clone());
        let branches = if l.branches.paths.is_empty() {
            PyArray2::zeros(py, [0, l.branches.gains.len()], false)
        } else {
            array2(py, &l.branches.paths)?
        };
        Ok((gains, branches, to_py(py, &v)?))
    }

    // ---- interconnections ---------------------------------------------------------------

    /// `self` then `other` (series).
    fn series(&self, other: &Model) -> PyResult<Model> {
        self.join(other, |a, b| a.series(b), |a, b| a.series(b))
    }

    /// `self + other` (parallel).
    fn parallel(&self, other: &Model) -> PyResult<Model> {
        self.join(other, |a, b| a.parallel(b), |a, b| a.parallel(b))
    }

    /// The loop closed through `h`: u = r + sign·h·y (sign −1: negative feedback).
    #[pyo3(signature = (h, sign=-1.0))]
    fn feedback(&self, h: &Model, sign: f64) -> PyResult<Model> {
        self.join(
            h,
            |a, b| Ok(a.feedback(b, sign)?.closed),
            |a, b| a.feedback(b, sign),
        )
    }

    // ---- sampling -----------------------------------------------------------------------

    /// The model sampled with period `dt` by `method` (`zoh`, `foh`, `tustin` with an
    /// optional `prewarp` frequency, `matched`, `impulse`): a state-space model's matrices, a
    /// transfer function's factored form (its poles mapped as e^(pT), not re-rooted).
    #[pyo3(signature = (dt, method="zoh", prewarp=None))]
    fn c2d(&self, dt: f64, method: &str, prewarp: Option<f64>) -> PyResult<Model> {
        let method = guard(|| ltikit::lti::Discretization::parse(method, prewarp))?;
        match &self.source {
            Source::Plant(p) if matches!(p.model, LtiModel::Ss(_)) => {
                guard(|| Plant::from_state_space(p.state_space()?.c2d(dt, method)?, None))
                    .map(Model::of_plant)
            }
            _ => {
                let f = self.factored()?;
                guard(|| f.c2d(dt, method)).map(Model::of_factored)
            }
        }
    }

    /// The continuous model whose `method` sampling is this discrete one (`zoh` by the matrix
    /// logarithm, `tustin` by the inverse bilinear map).
    #[pyo3(signature = (method="zoh", prewarp=None))]
    fn d2c(&self, method: &str, prewarp: Option<f64>) -> PyResult<Model> {
        let method = guard(|| ltikit::lti::Discretization::parse(method, prewarp))?;
        match &self.source {
            Source::Plant(p) if matches!(p.model, LtiModel::Ss(_)) => {
                guard(|| Plant::from_state_space(p.state_space()?.d2c(method)?, None))
                    .map(Model::of_plant)
            }
            _ => {
                let f = self.factored()?;
                guard(|| f.d2c(method)).map(Model::of_factored)
            }
        }
    }

    // ---- pictures -----------------------------------------------------------------------

    /// Bode diagram (PNG) with the margins marked.
    #[pyo3(signature = (path, w=None, margins=true, title=None, size=None))]
    fn bode_png(
        &self,
        path: &str,
        w: Option<Vec<f64>>,
        margins: bool,
        title: Option<String>,
        size: Option<(u32, u32)>,
    ) -> PyResult<()> {
        let f = self.factored()?;
        let label = self.name();
        guard(|| {
            let opts = plot_options(title, size)?;
            let w = match w {
                Some(w) => w,
                None => auto_frequency_grid(f, AUTO_POINTS)?,
            };
            let fr = f.freq_response(&w)?;
            // a plant whose margins cannot be computed is still drawn (without them)
            let m = if margins { f.margins().ok() } else { None };
            let mut s = ltikit::plot::BodeSeries::new(&fr).label(&label);
            if let Some(dt) = f.domain().dt() {
                s = s.sampling_period(dt);
            }
            if let Some(m) = &m {
                s = s.margins(m);
            }
            ltikit::plot::bode_png(path, &[s], &opts)
        })
    }

    /// Step (or `input`) response (PNG) with the step metrics marked.
    #[pyo3(signature = (path, input="step", t_end=None, title=None, size=None))]
    fn step_png(
        &self,
        path: &str,
        input: &str,
        t_end: Option<f64>,
        title: Option<String>,
        size: Option<(u32, u32)>,
    ) -> PyResult<()> {
        let f = self.factored()?;
        let label = self.name();
        guard(|| {
            let opts = plot_options(title, size)?;
            let input = input_of(input)?;
            let t_end = match t_end {
                Some(t) if t.is_finite() && t > 0.0 => t,
                Some(t) => {
                    return Err(LtiError::invalid(format!(
                        "`t_end` must be > 0, got {}",
                        ltikit::error::number(t)
                    )));
                }
                None => ltikit::analysis::auto_time_span(f)?.t_end,
            };
            let r = f.response_for_drawing(&input, t_end, 1001)?;
            let info = if matches!(input, Input::Step) {
                f.step_info().ok().flatten()
            } else {
                None
            };
            let mut s = ltikit::plot::StepSeries::new(&r)
                .label(&label)
                .input(input)
                .unstable(!f.stability().bibo_stable);
            if let Some(i) = &info {
                s = s.info(i);
            }
            ltikit::plot::step_png(path, &[s], &opts)
        })
    }

    /// Pole-zero map (PNG).
    #[pyo3(signature = (path, guides=true, title=None, size=None))]
    fn pzmap_png(
        &self,
        path: &str,
        guides: bool,
        title: Option<String>,
        size: Option<(u32, u32)>,
    ) -> PyResult<()> {
        let f = self.factored()?;
        let label = self.name();
        guard(|| {
            let opts = plot_options(title, size)?;
            let map = ltikit::plot::PzMap::new(f.pole_zero())
                .label(&label)
                .damping_guides(guides && !f.domain().is_discrete())
                .unit_circle(f.domain().is_discrete());
            ltikit::plot::pzmap_png(path, &map, &opts)
        })
    }

    /// Nyquist diagram (PNG).
    #[pyo3(signature = (path, title=None, size=None))]
    fn nyquist_png(
        &self,
        path: &str,
        title: Option<String>,
        size: Option<(u32, u32)>,
    ) -> PyResult<()> {
        let f = self.factored()?;
        let label = self.name();
        guard(|| {
            let opts = plot_options(title, size)?;
            let c = f.nyquist()?;
            ltikit::plot::nyquist_png(
                path,
                &[ltikit::plot::NyquistSeries::new(&c).label(&label)],
                &opts,
            )
        })
    }

    /// Root locus (PNG).
    #[pyo3(signature = (path, negative=false, title=None, size=None))]
    fn rlocus_png(
        &self,
        path: &str,
        negative: bool,
        title: Option<String>,
        size: Option<(u32, u32)>,
    ) -> PyResult<()> {
        let f = self.factored()?;
        let label = self.name();
        guard(|| {
            let opts = plot_options(title, size)?;
            let locus = f.root_locus(&RootLocusOptions {
                negative,
                ..Default::default()
            })?;
            ltikit::plot::rlocus_png(
                path,
                &ltikit::plot::RootLocusPlot {
                    locus: &locus,
                    label: Some(&label),
                    marked: None,
                },
                &opts,
            )
        })
    }

    /// The complex value G(s) at one point.
    fn eval(&self, s: Complex64) -> PyResult<Complex64> {
        Ok(self.factored()?.eval(s))
    }

    /// G(s) of every channel at one point (`values[output][input]`): the library's
    /// `transfer_matrix` (an error at a pole, naming the channel).
    fn eval_matrix<'py>(
        &self,
        py: Python<'py>,
        s: Complex64,
    ) -> PyResult<Bound<'py, PyArray2<Complex64>>> {
        let rows = match &self.source {
            // a MIMO model channel by channel
            Source::Plant(p) if !self.is_siso() => {
                guard(|| ltikit::analysis::point::transfer_matrix(&p.model, s))?
            }
            // one channel: its factored form, the dead time included
            _ => {
                let f = self.factored()?;
                vec![vec![guard(|| ltikit::analysis::point::value_at(f, s))?]]
            }
        };
        array2(py, &rows)
    }

    /// `[re, im]` pairs of the poles (the JSON contract's form), for tests and documents.
    fn pole_pairs(&self) -> PyResult<Vec<[f64; 2]>> {
        Ok(crate::convert::repeated(self.factored()?.poles())
            .into_iter()
            .map(pair)
            .collect())
    }
}

/// The names of the textbook models with their parameters and defaults.
#[pyfunction]
pub fn model_names() -> Vec<(String, Vec<(String, f64)>)> {
    let params = |ps: &[ltikit::lti::ModelParam]| -> Vec<(String, f64)> {
        ps.iter().map(|p| (p.name.to_string(), p.default)).collect()
    };
    ltikit::lti::plant_specs()
        .iter()
        .map(|s| (s.name.to_string(), params(s.params)))
        .chain(std::iter::once((
            "lattice".to_string(),
            params(ltikit::lti::lattice::LATTICE_PARAMS),
        )))
        .collect()
}
