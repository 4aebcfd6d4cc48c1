//! The plant of a design command (`place`, `lqr`, `lqe`, `lqg`): one plant as a state-space
//! model (a transfer function realised in controllable canonical form), continuous or
//! discrete (`--dt T`, or `--sample T` for a zero-order hold of a continuous plant); the loop
//! options are refused (the design is of the plant itself).

use anyhow::Result;

use super::{PlantArgs, UsageError};
use crate::lti::{Discretization, Plant, StateSpace};

/// The plant of a design command and its state-space model.
pub(super) fn design_plant(p: &PlantArgs, command: &str) -> Result<(Plant, StateSpace)> {
    let given = [
        (p.controller.is_some(), "--controller"),
        (p.controller_method.is_some(), "--controller-method"),
        (p.open_loop, "--loop"),
        (p.closed_loop, "--closed-loop"),
        (p.sensitivity, "--sensitivity"),
        (p.control_sensitivity, "--control-sensitivity"),
        (p.minreal.is_some(), "--minreal"),
        (p.channel.is_some(), "--channel"),
        (p.pade.is_some(), "--pade"),
    ];
    if let Some((_, flag)) = given.iter().find(|(on, _)| *on) {
        return Err(UsageError(format!(
            "{command} designs on the plant itself: {flag} is not taken"
        ))
        .into());
    }
    let mut plant = p.single()?;
    if plant.controller.is_some() {
        return Err(UsageError(format!(
            "{command} designs on the plant itself: the plant file's [controller] is not taken"
        ))
        .into());
    }
    if plant.delay() > 0.0 {
        anyhow::bail!(
            "{command}: the plant has a dead time of {} s; the design needs a delay-free \
             state-space model",
            crate::fmt::fmt_num(plant.delay())
        );
    }
    let mut ss = plant.state_space()?;
    if !ss.input_delays.is_empty() || !ss.output_delays.is_empty() {
        anyhow::bail!("{command}: the plant has dead times on its inputs or outputs");
    }
    if let Some(t) = p.sample {
        ss = ss.c2d(t, Discretization::Zoh)?;
        plant.name = format!(
            "{} sampled with a ZOH at T = {} s",
            plant.name,
            crate::fmt::fmt_num(t)
        );
    }
    super::output::set_document_dt(ss.domain.dt());
    if ss.order() == 0 {
        anyhow::bail!(
            "{command}: the plant has no states (a static gain): there is nothing to design"
        );
    }
    Ok((plant, ss))
}

/// A matrix as rows (JSON).
pub(super) fn rows(m: &nalgebra::DMatrix<f64>) -> Vec<Vec<f64>> {
    (0..m.nrows())
        .map(|i| (0..m.ncols()).map(|j| m[(i, j)]).collect())
        .collect()
}

/// "s" or "z".
pub(super) fn var(ss: &StateSpace) -> &'static str {
    if ss.domain.is_discrete() { "z" } else { "s" }
}

/// The title line naming the plant and its domain.
pub(super) fn title(what: &str, plant: &Plant, ss: &StateSpace) -> String {
    format!(
        "{what} for {}{}\n",
        plant.name,
        super::text::dt_suffix(ss.domain)
    )
}
