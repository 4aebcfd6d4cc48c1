//! The whole-model analyses of a state-space model (any numbers of inputs and outputs), each
//! a call of the library's state-space API: the analysis of `ltikit analyze` for a state-space
//! model ([`StateSpace::analysis`]), the transmission zeros with the pencil's Kronecker
//! structure ([`transmission_zeros`]), the frequency response of every channel
//! ([`StateSpace::freq_response_mimo`]), the step and impulse responses per input, the response
//! to sampled inputs and the free response from an initial state ([`StateSpace::lsim`],
//! [`StateSpace::initial_response`]). Arrays go back flat with their shape (the Python side
//! reshapes them, no copy).

use num_complex::Complex64;
use serde_json::{Value, json};

use ltikit::LtiError;
use ltikit::analysis::ss::{DcGain, SsAnalysis};
use ltikit::analysis::{Hold, InputSignal};
use ltikit::lti::StateSpace;
use ltikit::numeric::linalg::transmission_zeros;

/// The poles of the whole model: the eigenvalues of A with repetition (the analysis's snapped
/// values: one within its cluster radius of 0 or of the imaginary axis is put there).
pub fn poles(a: &SsAnalysis) -> Vec<Complex64> {
    a.eigenvalues
        .iter()
        .flat_map(|e| std::iter::repeat_n(e.value, e.algebraic))
        .collect()
}

/// Transmission zeros (of the minimal realisation, with repetition) and the rest of the
/// Kronecker structure of the minimal system pencil.
pub fn zeros(ss: &StateSpace) -> ltikit::Result<(Vec<Complex64>, Value)> {
    let z = transmission_zeros(&ss.a, &ss.b, &ss.c, &ss.d, None)?;
    let k = &z.structure;
    let doc = json!({
        "normal_rank": k.normal_rank,
        "infinite_orders": k.infinite_orders,
        "left_indices": k.left_indices,
        "right_indices": k.right_indices,
        "multiplicities": z.distinct.iter().map(|(v, m)| json!([[v.re, v.im], m])).collect::<Vec<_>>(),
    });
    Ok((z.zeros, doc))
}

/// The p×m dc-gain matrix, row by row (`inf` for a channel with a pole at 0).
pub fn dc_gain(a: &SsAnalysis) -> Vec<f64> {
    a.dc_gain
        .iter()
        .flatten()
        .map(|g| match g {
            DcGain::Finite(v) => *v,
            DcGain::Infinite => f64::INFINITY,
        })
        .collect()
}

/// The dc-gain matrix without the whole analysis, flat row by row
/// ([`StateSpace::dc_gain_direct`]); `None` when the analysis must decide channel by channel.
pub fn dc_gain_direct(ss: &StateSpace) -> ltikit::Result<Option<Vec<f64>>> {
    // row by row: the matrix is column-major
    Ok(ss
        .dc_gain_direct()?
        .map(|g| g.transpose().iter().copied().collect()))
}

/// Stability of the whole model: internal (every eigenvalue of A inside the region) with the
/// reason, and the BIBO stability of each channel (`bibo_stable[out][in]`).
pub fn stability(a: &SsAnalysis) -> Value {
    let bibo = a.bibo_stable.iter().flatten().all(|&b| b);
    let bibo_reason = if bibo {
        "every channel's minimal realisation has its poles inside the stability region".to_string()
    } else {
        let (j, i) = a
            .bibo_stable
            .iter()
            .enumerate()
            .find_map(|(j, row)| row.iter().position(|&b| !b).map(|i| (j, i)))
            .unwrap_or((0, 0));
        format!("channel [{j}, {i}] has a pole outside the stability region")
    };
    json!({
        "bibo_stable": bibo,
        "internally_stable": a.internally_stable,
        "reason": a.internal_reason,
        "bibo_reason": bibo_reason,
        "internal_reason": a.internal_reason,
        "channels_bibo_stable": a.bibo_stable,
    })
}

/// |G|, the continuous phase (degrees) and G itself of every channel at `w`, each flat in
/// the order \[output\]\[input\]\[frequency\].
pub fn freq(ss: &StateSpace, w: &[f64]) -> ltikit::Result<(Vec<f64>, Vec<f64>, Vec<Complex64>)> {
    let r = ss.freq_response_mimo(w)?;
    let mag: Vec<f64> = r.magnitude.into_iter().flatten().flatten().collect();
    let phase: Vec<f64> = r.phase_deg.into_iter().flatten().flatten().collect();
    let g = mag
        .iter()
        .zip(&phase)
        .map(|(&m, &p)| Complex64::from_polar(m, p.to_radians()))
        .collect();
    Ok((mag, phase, g))
}

/// The response of every output to a unit step (`impulse`: a unit impulse) on each input in
/// turn, flat in the order \[output\]\[input\]\[time\].
pub fn per_input(ss: &StateSpace, t: &[f64], impulse: bool) -> ltikit::Result<Vec<f64>> {
    let (m, p, k) = (ss.n_inputs(), ss.n_outputs(), t.len());
    let mut out = vec![0.0; p * m * k];
    for i in 0..m {
        let r = if impulse {
            ss.impulse_response_from(i, t, false)?
        } else {
            ss.step_response_from(i, t, false)?
        };
        for (j, row) in r.y.iter().enumerate() {
            out[(j * m + i) * k..(j * m + i + 1) * k].copy_from_slice(row);
        }
    }
    Ok(out)
}

/// The hold of sampled inputs by name.
pub fn hold_of(hold: &str) -> ltikit::Result<Hold> {
    match hold {
        "foh" => Ok(Hold::First),
        "zoh" => Ok(Hold::Zero),
        other => Err(LtiError::invalid(format!(
            "`hold` must be \"zoh\" or \"foh\" (found \"{}\")",
            ltikit::error::abbreviate(other)
        ))),
    }
}

/// The response to input samples `u` (flat, one row of m values per time of `t`) from `x0`
/// (zero when `None`): every output, flat in the order \[output\]\[time\].
pub fn lsim(
    ss: &StateSpace,
    u: &[f64],
    t: Vec<f64>,
    hold: Hold,
    x0: Option<&[f64]>,
) -> ltikit::Result<Vec<f64>> {
    let m = ss.n_inputs();
    if m == 0 || u.len() != t.len() * m {
        return Err(LtiError::invalid(format!(
            "`u` has {} values for {} times and {m} input{}: give one row of {m} per time \
             (shape (len(t), {m}))",
            u.len(),
            t.len(),
            if m == 1 { "" } else { "s" }
        )));
    }
    let sig = InputSignal {
        u: u.chunks(m).map(<[f64]>::to_vec).collect(),
        t,
    };
    let r = ss.lsim(&sig, hold, x0, false)?;
    Ok(r.y.into_iter().flatten().collect())
}

/// The free response from `x0` at `t` (u = 0): every output, flat \[output\]\[time\].
pub fn initial(ss: &StateSpace, x0: &[f64], t: &[f64]) -> ltikit::Result<Vec<f64>> {
    Ok(ss
        .initial_response(x0, t, false)?
        .y
        .into_iter()
        .flatten()
        .collect())
}
