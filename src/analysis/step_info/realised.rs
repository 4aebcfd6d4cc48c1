//! Step metrics of a state-space source checked against the realisation itself (issue 24
//! item 2): the metrics are found on the closed form built from the factors (poles,
//! transmission zeros, gain); at the instants they name (rise start and end, peak, settling
//! and transient times) the closed form is compared with the step response marched on the
//! minimal realisation (e^(Ah) by Van Loan blocks, `StateSpace::step_response_from`). A
//! disagreement beyond [`AGREE_REL`] of |y∞| becomes a note on those metrics. Minimal
//! realisations of order up to [`MAX_CHECK_ORDER`] are checked.

use super::{MetricNote, StepInfo};
use crate::analysis::closed_form::ClosedForm;
use crate::analysis::factored::SsSource;
use crate::lti::StateSpace;

/// Largest disagreement between the closed form and the realisation's march, relative to
/// |y∞|, that passes without a note.
pub(crate) const AGREE_REL: f64 = 1e-8;

/// Largest minimal order checked: beyond it the march's matrix exponentials (or its modal
/// form) would cost more than the metrics themselves.
pub(crate) const MAX_CHECK_ORDER: usize = 64;

/// The metrics' instants that are finite and positive, with their field names.
fn instants(info: &StepInfo) -> Vec<(&'static str, f64)> {
    [
        ("rise_start", info.rise_start),
        ("rise_end", info.rise_end),
        ("peak_time", info.peak_time),
        ("settling_time", info.settling_time),
        ("transient_time", info.transient_time),
    ]
    .into_iter()
    .filter_map(|(name, t)| t.filter(|t| t.is_finite() && *t > 0.0).map(|t| (name, t)))
    .collect()
}

/// The largest relative disagreement |y_closed(t) − y_march(t)|/|y∞| at the metrics'
/// instants (`None` when there is no instant or the march fails).
pub(crate) fn disagreement(
    ss: &SsSource,
    y: &ClosedForm,
    y_inf: f64,
    info: &StepInfo,
) -> Option<f64> {
    let at = instants(info);
    if at.is_empty() {
        return None;
    }
    let m = &ss.minimal;
    if m.order() > MAX_CHECK_ORDER {
        return None;
    }
    let model = StateSpace::new(m.a.clone(), m.b.clone(), m.c.clone(), m.d.clone()).ok()?;
    let mut t: Vec<f64> = at.iter().map(|&(_, t)| t).collect();
    t.sort_by(f64::total_cmp);
    t.dedup();
    let r = model.step_response_from(0, &t, false).ok()?;
    let worst = t
        .iter()
        .zip(r.y.first()?)
        .map(|(&ti, &ym)| (y.eval(ti) - ym).abs() / y_inf.abs())
        .fold(0.0, f64::max);
    worst.is_finite().then_some(worst)
}

/// Adds the note when the closed form and the realisation disagree beyond [`AGREE_REL`].
pub(crate) fn check(ss: &SsSource, y: &ClosedForm, y_inf: f64, info: &mut StepInfo) {
    let Some(worst) = disagreement(ss, y, y_inf, info) else {
        return;
    };
    if worst > AGREE_REL {
        let quantities = instants(info).into_iter().map(|(n, _)| n).collect();
        info.notes.push(MetricNote {
            quantities,
            reason: format!(
                "the closed form from the computed poles and zeros disagrees with the step \
                 response marched on the state-space realisation by {worst:.1e} of the final \
                 value at these instants: the metrics are only as accurate as that"
            ),
        });
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::DMatrix;

    #[test]
    fn a_dense_realisation_agrees_and_a_wrong_closed_form_is_noted() {
        // 2/((s + 1)(s + 2)) behind a similarity: the factors are exact, the check passes
        let t = DMatrix::from_row_slice(2, 2, &[1.0, 0.5, -0.25, 1.0]);
        let ti = t.clone().try_inverse().unwrap();
        let a = DMatrix::from_row_slice(2, 2, &[-1.0, 0.0, 1.0, -2.0]);
        let b = DMatrix::from_row_slice(2, 1, &[2.0, 0.0]);
        let c = DMatrix::from_row_slice(1, 2, &[0.0, 1.0]);
        let ss = StateSpace::new(&t * &a * &ti, &t * &b, &c * &ti, DMatrix::zeros(1, 1)).unwrap();
        let f = crate::analysis::Factored::from_state_space(&ss).unwrap();
        let src = f.source().state_space().unwrap();
        let y =
            crate::analysis::laplace::Decomposition::new(&f, &crate::analysis::Input::Step, &[])
                .unwrap()
                .closed_form()
                .unwrap()
                .closed_form;
        let mut info = f.step_info().unwrap().unwrap();
        let worst = disagreement(src, &y, 1.0, &info).unwrap();
        assert!(worst < 1e-13, "{worst}");
        assert!(info.notes.is_empty());
        // the closed form of another plant (2/((s + 1)(s + 3)), y∞ = 2/3) is caught
        let other = crate::TransferFunction::from_descending(&[2.0], &[1.0, 4.0, 3.0]).unwrap();
        let yo = other
            .inverse_laplace(&crate::analysis::Input::Step, &[])
            .unwrap()
            .closed_form;
        check(src, &yo, 1.0, &mut info);
        assert_eq!(info.notes.len(), 1);
        assert!(info.notes[0].reason.contains("disagrees"));
    }
}
