//! The plant options shared by every command that takes a plant: coefficients (`--num/--den`,
//! repeatable for several plants), plant files (`--plant`), or a textbook model
//! (`--model NAME --param K=V`). The values are read by the one plant-specification module,
//! [`crate::lti::plant`]; this module only checks the combination of options.

use anyhow::Result;
use clap::Args;
use std::path::PathBuf;

use super::UsageError;
use crate::analysis::ClosedLoop;
use crate::lti::controller::LoopSystem;
use crate::lti::{Controller, Plant};

/// Plant selection.
#[derive(Args, Debug, Clone, Default)]
pub struct PlantArgs {
    /// Numerator coefficients in descending powers of s ("4" or "1 3" or "1,3"; use
    /// --num=-3,-12 for negative values). Repeat with --den for several plants. Default 1.
    #[arg(long, value_name = "COEFFS", allow_hyphen_values = true)]
    pub num: Vec<String>,
    /// Denominator (characteristic polynomial) coefficients in descending powers of s.
    #[arg(long, value_name = "COEFFS", allow_hyphen_values = true)]
    pub den: Vec<String>,
    /// A plant file (TOML with num/den or model/params; see data/plants/). Repeatable.
    #[arg(long, value_name = "FILE.toml")]
    pub plant: Vec<PathBuf>,
    /// A textbook model of the lecture notes: spring-mass-damper, second-order, tank, rc, rlc,
    /// two-dof, or lattice, the linear particle lattice (state space; --param N=16 --param
    /// output=5 …).
    #[arg(long, value_name = "NAME")]
    pub model: Option<String>,
    /// A model parameter, NAME=VALUE (repeatable), e.g. --param M=1 --param C=0.4.
    #[arg(long = "param", value_name = "NAME=VALUE", allow_hyphen_values = true)]
    pub params: Vec<String>,
    /// State matrix A of a state-space plant, rows separated by ';': --a "0 1; -4 -0.8".
    #[arg(long, value_name = "ROWS", allow_hyphen_values = true, requires_all = ["b", "c"])]
    pub a: Option<String>,
    /// Input matrix B (n × m): --b "0; 1".
    #[arg(long, value_name = "ROWS", allow_hyphen_values = true, requires = "a")]
    pub b: Option<String>,
    /// Output matrix C (p × n): --c "1 0".
    #[arg(long, value_name = "ROWS", allow_hyphen_values = true, requires = "a")]
    pub c: Option<String>,
    /// Feedthrough D (p × m; zero when absent).
    #[arg(long, value_name = "ROWS", allow_hyphen_values = true, requires = "a")]
    pub d: Option<String>,
    /// Sampling period in seconds: the plant is discrete-time, --num/--den in descending
    /// powers of z and --a…--d giving `x[k+1] = A x[k] + B u[k]` (also `dt = T` in a plant
    /// file).
    #[arg(long, value_name = "T", allow_hyphen_values = true)]
    pub dt: Option<f64>,
    /// Dead time in seconds: the plant is G(s)·e^(−sT), kept exact in every analysis (on
    /// every input of a state-space plant; `delay = T` in a plant file). A discrete plant
    /// takes a whole number of periods, as z^(−d).
    #[arg(long, value_name = "T", allow_hyphen_values = true)]
    pub delay: Option<f64>,
    /// Replace the dead time by its [N/N] Padé approximant (N = 1…20) for this analysis.
    #[arg(long, value_name = "N")]
    pub pade: Option<usize>,
    /// Sample the (continuous) plant with a zero-order hold at period T before the analysis:
    /// with a controller, the sampled-data loop — C discretised by --controller-method, the
    /// plant seen through its ZOH — analysed at the samples.
    #[arg(
        long,
        value_name = "T",
        allow_hyphen_values = true,
        conflicts_with = "dt"
    )]
    pub sample: Option<f64>,
    /// How a continuous controller becomes C(z) in front of a discrete-time plant (--dt or
    /// --sample): tustin (default), zoh, foh, matched or impulse.
    #[arg(long, value_name = "METHOD")]
    pub controller_method: Option<String>,
    /// The channel of a MIMO plant to analyse: INPUT,OUTPUT (1-based), e.g. --channel 1,2.
    #[arg(long, value_name = "INPUT,OUTPUT")]
    pub channel: Option<String>,
    /// A controller C in front of the plant, unity negative feedback: KIND:NAME=VALUE,… with
    /// p:kp | pi:kp,ki | pd:kp,kd,tf | pid:kp,ki,kd,tf (tf: derivative filter time constant,
    /// 0 = none) | lead:k,z,p (0<z<p) | lag:k,z,p (0<p<z), e.g. "pid:kp=2,ki=1,kd=0.5,tf=0.01";
    /// or tf:NUM/DEN, coefficients in the loop's own variable (in z for a discrete plant, used
    /// as given), e.g. "tf:0.5 -0.4/1 -1".
    /// With a controller, margins, bode and nyquist read the loop L = C·G and the other
    /// commands the closed loop T = L/(1+L) unless one of the options below is given.
    #[arg(long, value_name = "KIND:PARAMS")]
    pub controller: Option<String>,
    /// Analyse the loop L = C·G (C = 1 without --controller).
    #[arg(long = "loop", conflicts_with_all = ["closed_loop", "sensitivity", "control_sensitivity"])]
    pub open_loop: bool,
    /// Analyse the closed loop T = L/(1 + L).
    #[arg(long, conflicts_with_all = ["sensitivity", "control_sensitivity"])]
    pub closed_loop: bool,
    /// Analyse the sensitivity S = 1/(1 + L).
    #[arg(long, conflicts_with = "control_sensitivity")]
    pub sensitivity: bool,
    /// Analyse the control sensitivity C·S = C/(1 + L).
    #[arg(long)]
    pub control_sensitivity: bool,
    /// Cancel pole-zero pairs closer than this relative distance, |z − p| ≤ TOL·max(|z|, |p|)
    /// (MATLAB's and python-control's minreal(sys, tol); they use √eps ≈ 1.5e-8). Without it
    /// only exact common roots cancel, and near pairs are listed by `analyze`.
    #[arg(long, value_name = "TOL")]
    pub minreal: Option<f64>,
}

impl PlantArgs {
    /// All plants selected, in the order: coefficient pairs, files, model; with a controller
    /// (or a loop option) the closed loop T is selected unless an option says otherwise.
    pub fn resolve(&self) -> Result<Vec<Plant>> {
        self.resolve_for(LoopSystem::ClosedLoop)
    }

    /// The loop option given, if any.
    fn loop_flag(&self) -> Option<LoopSystem> {
        [
            (self.open_loop, LoopSystem::Loop),
            (self.closed_loop, LoopSystem::ClosedLoop),
            (self.sensitivity, LoopSystem::Sensitivity),
            (self.control_sensitivity, LoopSystem::ControlSensitivity),
        ]
        .into_iter()
        .find_map(|(on, s)| on.then_some(s))
    }

    /// [`PlantArgs::resolve`] with the command's default loop selection `default` (used when
    /// a controller is given, on the command line or in a plant file, and no loop option).
    pub fn resolve_for(&self, default: LoopSystem) -> Result<Vec<Plant>> {
        let mut out = self.plants()?;
        if let Some(t) = self.sample {
            crate::lti::Domain::discrete(t)?;
            for p in &out {
                p.domain()
                    .require_continuous("--sample (a zero-order hold of a continuous plant)")?;
            }
        }
        super::output::set_document_dt(
            self.sample
                .or_else(|| out.first().and_then(|p| p.domain().dt())),
        );
        super::output::set_document_delay(if self.pade.is_some() {
            0.0
        } else {
            out.first().map_or(0.0, Plant::delay)
        });
        let method = self
            .controller_method
            .as_deref()
            .map(|m| crate::lti::Discretization::parse(m, None))
            .transpose()?;
        let controller = self
            .controller
            .as_deref()
            .map(Controller::parse)
            .transpose()?;
        for p in &mut out {
            if let Some(c) = &controller {
                p.controller = Some(c.clone());
            }
            if let Some(m) = method
                && let Some(c) = p.controller.take()
            {
                p.controller = Some(c.with_method(m));
            }
            if let Some(t) = self.sample {
                p.name = format!(
                    "{} sampled with a ZOH at T = {} s",
                    p.name,
                    crate::fmt::fmt_num(t)
                );
            }
            if let Some(n) = self.pade
                && p.delay() > 0.0
            {
                p.name = format!("{} (the delay as its [{n}/{n}] Padé approximant)", p.name);
            }
            p.selection = self
                .loop_flag()
                .or_else(|| p.controller.is_some().then_some(default));
            if let Some(which) = p.selection {
                let discrete = self.sample.is_some() || p.domain().is_discrete();
                let c = p.controller.as_ref().map_or_else(
                    || "1".to_string(),
                    |c| {
                        if discrete && c.is_given_in_loop_variable() {
                            format!("{c} (given in z)")
                        } else if discrete {
                            format!("{c} ({}, in z)", c.method().name())
                        } else {
                            c.to_string()
                        }
                    },
                );
                p.name = format!("{} with C = {c}, G = {}", which.formula(), p.name);
            }
        }
        Ok(out)
    }

    fn plants(&self) -> Result<Vec<Plant>> {
        let mut out = Vec::new();
        if !self.num.is_empty() || !self.den.is_empty() {
            if self.den.is_empty() {
                return Err(UsageError("--num needs --den (the denominator)".into()).into());
            }
            if !self.num.is_empty() && self.num.len() != self.den.len() {
                return Err(UsageError(format!(
                    "{} --num but {} --den: give one numerator per denominator (or none for 1)",
                    self.num.len(),
                    self.den.len()
                ))
                .into());
            }
            for (i, d) in self.den.iter().enumerate() {
                out.push(Plant::from_text(self.num.get(i).map(String::as_str), d)?);
            }
        }
        if let (Some(a), Some(b), Some(c)) = (&self.a, &self.b, &self.c) {
            out.push(Plant::from_matrices_text(a, b, c, self.d.as_deref())?);
        }
        for path in &self.plant {
            out.push(Plant::from_file(path)?);
        }
        if let Some(m) = &self.model {
            let params = crate::lti::plant::parse_params(&self.params)?;
            out.push(Plant::from_model(m, &params)?);
        } else if !self.params.is_empty() {
            return Err(UsageError("--param needs --model".into()).into());
        }
        if let Some(dt) = self.dt {
            if self.model.is_some() {
                return Err(crate::lti::plant::physical_model_has_no_dt().into());
            }
            let domain = crate::lti::Domain::discrete(dt)?;
            out = out
                .into_iter()
                .map(|p| {
                    if p.domain().is_discrete() && p.domain() != domain {
                        return Err(crate::error::LtiError::invalid(format!(
                            "--dt {}: the plant `{}` is already {}",
                            crate::fmt::fmt_num(dt),
                            crate::error::abbreviate(&p.name),
                            p.domain().describe()
                        )));
                    }
                    p.with_domain(domain)
                })
                .collect::<crate::error::Result<_>>()?;
        }
        if let Some(t) = self.delay {
            out = out
                .into_iter()
                .map(|p| p.with_delay(t))
                .collect::<crate::error::Result<_>>()?;
        }
        if out.is_empty() {
            return Err(UsageError(
                "no plant given: use --num/--den, --a/--b/--c, --plant FILE.toml or --model NAME"
                    .into(),
            )
            .into());
        }
        Ok(out)
    }

    /// The channel chosen with `--channel` (0-based input, output), if any.
    pub fn channel(&self) -> Result<Option<(usize, usize)>> {
        let Some(text) = &self.channel else {
            return Ok(None);
        };
        let bad = || {
            UsageError(format!(
                "--channel '{}': expected INPUT,OUTPUT with 1-based indices, e.g. --channel 1,2",
                crate::error::abbreviate(text)
            ))
        };
        let (i, o) = text.split_once(',').ok_or_else(bad)?;
        let i: usize = i.trim().parse().map_err(|_| bad())?;
        let o: usize = o.trim().parse().map_err(|_| bad())?;
        if i == 0 || o == 0 {
            return Err(bad().into());
        }
        Ok(Some((i - 1, o - 1)))
    }

    /// The factored form of a plant: the chosen channel, or the plant itself when SISO; with
    /// a loop selection, that transfer function of the loop (a note on stderr names the
    /// system and any unstable hidden mode).
    pub fn factored(&self, plant: &Plant) -> Result<crate::analysis::Factored> {
        Ok(self.factored_with_loop(plant)?.0)
    }

    /// [`PlantArgs::factored`] and the loop, when one is selected.
    pub fn factored_with_loop(
        &self,
        plant: &Plant,
    ) -> Result<(crate::analysis::Factored, Option<ClosedLoop>)> {
        let g = match self.channel()? {
            Some((i, o)) => plant.factored_channel(i, o)?,
            None => plant.factored()?,
        };
        let g = self.pade_of(g)?;
        let g = match self.sample {
            Some(t) => g.c2d(t, crate::lti::Discretization::Zoh)?,
            None => g,
        };
        let g = self.minreal(g)?;
        let (f, cl) = crate::analysis::closed_loop::select(plant, g)?;
        if let Some(cl) = &cl {
            let st = cl.internal_stability();
            if !st.unstable_hidden.is_empty() {
                super::warn(st.reason.clone());
            }
        }
        Ok((f, cl))
    }

    /// `g` with its dead time replaced by the `--pade N` approximant (a note on stderr says
    /// so); `g` itself without the option.
    pub fn pade_of(&self, g: crate::analysis::Factored) -> Result<crate::analysis::Factored> {
        let Some(n) = self.pade else {
            return Ok(g);
        };
        let delay = g.delay();
        let approx = g.pade(n)?;
        if delay > 0.0 {
            super::warn(format!(
                "--pade {n}: the dead time e^(-{} s) is replaced by its [{n}/{n}] Padé approximant",
                crate::fmt::fmt_num(delay)
            ));
        }
        Ok(approx)
    }

    /// `f` with the pole-zero pairs within `--minreal TOL` cancelled (a warning names each
    /// pair); `f` itself without the option.
    pub fn minreal(&self, f: crate::analysis::Factored) -> Result<crate::analysis::Factored> {
        let Some(tol) = self.minreal else {
            return Ok(f);
        };
        let (g, removed) = f.minreal(tol)?;
        for n in &removed {
            let sig = super::text::distinguishing_digits(&[n.zero, n.pole], 6);
            super::warn(format!(
                "--minreal {}: cancelled zero {} against pole {}{} (distance {})",
                crate::fmt::fmt_sig(tol, 6),
                crate::fmt::fmt_root(n.zero, sig),
                crate::fmt::fmt_root(n.pole, sig),
                if n.multiplicity > 1 {
                    format!(" (×{})", n.multiplicity)
                } else {
                    String::new()
                },
                crate::fmt::fmt_sig(n.distance, 3)
            ));
        }
        Ok(g)
    }

    /// Exactly one plant.
    pub fn single(&self) -> Result<Plant> {
        self.single_for(LoopSystem::ClosedLoop)
    }

    /// Exactly one plant, with the command's default loop selection (see
    /// [`PlantArgs::resolve_for`]).
    pub fn single_for(&self, default: LoopSystem) -> Result<Plant> {
        let mut v = self.resolve_for(default)?;
        if v.len() != 1 {
            return Err(UsageError(format!(
                "this command takes one plant, {} were given",
                v.len()
            ))
            .into());
        }
        Ok(v.remove(0))
    }
}
