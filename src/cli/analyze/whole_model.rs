//! The whole-model section of `ltikit analyze` on a state-space plant
//! ([`StateSpace::analysis`]): the text "State space (whole model)" and the JSON key
//! `"state_space"` (docs/ARCHITECTURE.md, "MIMO plants and state-space responses").

use num_complex::Complex64;
use serde::Serialize;

use super::super::output::pair;
use super::super::text::{complex_text, labelled_roots_text};
use crate::analysis::ss::{DcGain, MAX_ANALYSIS_STATES, SsAnalysis, SsEigenvalue, SsMode};
use crate::fmt::{fmt_num, fmt_root, fmt_sig};
use crate::lti::{Model, Plant, StateSpace};

/// Distinct eigenvalues (one per conjugate pair) above which the text gives a summary and
/// the modes table only with `--modes`.
pub const MAX_LISTED_MODES: usize = 20;

/// Entries of a summary list (on the axis, in the right half plane, defective) printed before
/// "… and k more".
const MAX_SUMMARY_ENTRIES: usize = 20;

/// Components of a mode shape printed with `--shapes` (the largest in modulus).
const SHAPE_COMPONENTS: usize = 4;

/// Components below this fraction of a shape's largest one are rounding and not printed.
const SHAPE_NEGLIGIBLE: f64 = 1e-12;

/// The whole-model analysis of a plant, or why there is none.
pub enum WholeModel {
    /// Computed.
    Computed(Box<SsAnalysis>),
    /// Not computed (too large, or the analysis failed): the reason, one line.
    Skipped(String),
}

impl WholeModel {
    /// The analysis of a state-space model, or the reason it is not computed: more than
    /// [`MAX_ANALYSIS_STATES`] states, or an error of the kernels (said, not raised: the
    /// per-channel analysis is still printed).
    pub fn of(ss: &StateSpace) -> WholeModel {
        let n = ss.order();
        if n > MAX_ANALYSIS_STATES {
            return WholeModel::Skipped(format!(
                "not computed: {n} states exceed {MAX_ANALYSIS_STATES}, the largest order \
                 analysed as a whole (O(n³): eigenvectors, staircases, invariant zeros and a \
                 minimal realisation per channel)"
            ));
        }
        match ss.analysis() {
            Ok(a) => WholeModel::Computed(Box::new(a)),
            Err(e) => WholeModel::Skipped(format!("not computed: {e}")),
        }
    }
}

/// The whole-model analysis `analyze` shows for `plant`: a state-space model analysed as a
/// whole — not a transfer function, not a loop with a controller, not one `--channel`.
pub fn for_plant(plant: &Plant, chosen_channel: bool) -> Option<WholeModel> {
    match &plant.model {
        Model::Ss(ss) if plant.selection.is_none() && !chosen_channel => Some(WholeModel::of(ss)),
        _ => None,
    }
}

/// The JSON keys of the whole-model analysis: `"state_space"` (the document, or `null` when
/// not computed) and `"state_space_note"` (`null`, or why it was not computed). Flattened
/// into the analyze document (SISO) or the channel wrapper (MIMO).
#[derive(Serialize)]
pub struct WholeModelJson {
    state_space: Option<SsJson>,
    state_space_note: Option<String>,
}

impl WholeModelJson {
    /// From the analysis; `shapes` adds every mode's shapes.
    pub fn new(w: &WholeModel, shapes: bool) -> WholeModelJson {
        match w {
            WholeModel::Computed(a) => WholeModelJson {
                state_space: Some(SsJson::new(a, shapes)),
                state_space_note: None,
            },
            WholeModel::Skipped(why) => WholeModelJson {
                state_space: None,
                state_space_note: Some(why.clone()),
            },
        }
    }
}

/// The `"state_space"` document.
#[derive(Serialize)]
struct SsJson {
    states: usize,
    inputs: usize,
    outputs: usize,
    eigenvalues: Vec<EigenJson>,
    controllability: RankJson,
    observability: RankJson,
    minimal_order: usize,
    uncontrollable_modes: Vec<[f64; 2]>,
    unobservable_modes: Vec<[f64; 2]>,
    invariant_zeros: Option<Vec<ZeroJson>>,
    invariant_zeros_note: Option<String>,
    system_pencil: Option<PencilJson>,
    dc_gain: Vec<Vec<Option<f64>>>,
    bibo_stable: Vec<Vec<bool>>,
    internally_stable: bool,
    internal_reason: String,
    modes: Vec<ModeJson>,
}

#[derive(Serialize)]
struct EigenJson {
    value: [f64; 2],
    algebraic: usize,
    geometric: usize,
    semisimple: bool,
}

#[derive(Serialize)]
struct RankJson {
    rank: usize,
    tol: f64,
}

#[derive(Serialize)]
struct ZeroJson {
    value: [f64; 2],
    multiplicity: usize,
    /// σ_{n+r} of the Rosenbrock matrix at the zero over its norm (`None` beyond
    /// `MAX_RESIDUAL_STATES`).
    residual: Option<f64>,
}

/// The Kronecker structure of the system pencil besides the finite zeros.
#[derive(Serialize)]
struct PencilJson {
    normal_rank: usize,
    infinite_zero_orders: Vec<usize>,
    left_kronecker_indices: Vec<usize>,
    right_kronecker_indices: Vec<usize>,
}

#[derive(Serialize)]
struct ModeJson {
    value: [f64; 2],
    algebraic: usize,
    wn: f64,
    zeta: Option<f64>,
    time_constant: Option<f64>,
    geometric: usize,
    residual_max: f64,
    #[serde(skip_serializing_if = "Option::is_none")]
    shapes: Option<Vec<Vec<[f64; 2]>>>,
}

impl SsJson {
    fn new(a: &SsAnalysis, shapes: bool) -> SsJson {
        let pairs = |v: &[Complex64]| v.iter().map(|&z| pair(z)).collect::<Vec<_>>();
        SsJson {
            states: a.n,
            inputs: a.m,
            outputs: a.p,
            eigenvalues: a
                .eigenvalues
                .iter()
                .map(|e| EigenJson {
                    value: pair(e.value),
                    algebraic: e.algebraic,
                    geometric: e.geometric,
                    semisimple: e.semisimple,
                })
                .collect(),
            controllability: RankJson {
                rank: a.controllability.rank,
                tol: a.controllability.tol,
            },
            observability: RankJson {
                rank: a.observability.rank,
                tol: a.observability.tol,
            },
            minimal_order: a.minimal_order,
            uncontrollable_modes: pairs(&a.uncontrollable_modes),
            unobservable_modes: pairs(&a.unobservable_modes),
            invariant_zeros: a.invariant_zeros.as_ref().map(|z| {
                let res = a.zero_structure.as_ref().map(|k| &k.residuals);
                z.iter()
                    .enumerate()
                    .map(|(i, &(v, k))| ZeroJson {
                        value: pair(v),
                        multiplicity: k,
                        residual: res.and_then(|r| r.get(i).copied()),
                    })
                    .collect()
            }),
            invariant_zeros_note: a.invariant_zeros_note.clone(),
            system_pencil: a.zero_structure.as_ref().map(|k| PencilJson {
                normal_rank: k.normal_rank,
                infinite_zero_orders: k.infinite_orders.clone(),
                left_kronecker_indices: k.left_indices.clone(),
                right_kronecker_indices: k.right_indices.clone(),
            }),
            dc_gain: a
                .dc_gain
                .iter()
                .map(|row| {
                    row.iter()
                        .map(|g| match g {
                            DcGain::Finite(x) => Some(*x),
                            DcGain::Infinite => None,
                        })
                        .collect()
                })
                .collect(),
            bibo_stable: a.bibo_stable.clone(),
            internally_stable: a.internally_stable,
            internal_reason: a.internal_reason.clone(),
            modes: a
                .modes
                .iter()
                .map(|m| ModeJson {
                    value: pair(m.value),
                    algebraic: m.algebraic,
                    wn: m.wn,
                    zeta: m.zeta.is_finite().then_some(m.zeta),
                    time_constant: m.tau,
                    geometric: m.shapes.len(),
                    residual_max: worst_residual(m),
                    shapes: shapes.then(|| {
                        m.shapes
                            .iter()
                            .map(|v| v.iter().map(|&z| pair(z)).collect())
                            .collect()
                    }),
                })
                .collect(),
        }
    }
}

/// The largest residual of a mode's shapes.
fn worst_residual(m: &SsMode) -> f64 {
    m.residuals.iter().copied().fold(0.0, f64::max)
}

/// What the text section prints beyond the summary.
#[derive(Clone, Copy, Debug, Default)]
pub struct Detail {
    /// The whole modes table even for a large model.
    pub modes: bool,
    /// The mode shapes (implies the modes table).
    pub shapes: bool,
}

/// The text section "State space (whole model)".
pub fn text(plant: &Plant, w: &WholeModel, detail: Detail) -> String {
    let a = match w {
        WholeModel::Computed(a) => a,
        WholeModel::Skipped(why) => return format!("State space (whole model): {why}\n"),
    };
    let mut s = String::from("State space (whole model)\n");
    let line = |s: &mut String, label: &str, value: &str| {
        s.push_str(&format!("  {label:<20}{value}\n"));
    };
    line(
        &mut s,
        "size:",
        &format!(
            "{}, {}, {}",
            counted(a.n, "state"),
            counted(a.m, "input"),
            counted(a.p, "output")
        ),
    );
    let upper: Vec<&SsEigenvalue> = a.eigenvalues.iter().filter(|e| e.value.im >= 0.0).collect();
    let large = upper.len() > MAX_LISTED_MODES;
    if large {
        eigen_summary(&mut s, &upper);
    } else {
        line(
            &mut s,
            "eigenvalues of A:",
            &labelled_roots_text(&labelled(&upper, true)),
        );
    }
    line(
        &mut s,
        "controllability:",
        &format!(
            "rank {} of {} (tolerance {})",
            a.controllability.rank,
            a.n,
            fmt_sig(a.controllability.tol, 3)
        ),
    );
    line(
        &mut s,
        "observability:",
        &format!(
            "rank {} of {} (tolerance {})",
            a.observability.rank,
            a.n,
            fmt_sig(a.observability.tol, 3)
        ),
    );
    let removed = a.n - a.minimal_order;
    line(
        &mut s,
        "minimal order:",
        &if removed == 0 {
            format!("{} (minimal: nothing removed)", a.minimal_order)
        } else {
            format!("{} ({} removed)", a.minimal_order, counted(removed, "mode"))
        },
    );
    if removed > 0 {
        line(
            &mut s,
            "  uncontrollable:",
            &capped(&grouped(&a.uncontrollable_modes)),
        );
        line(
            &mut s,
            "  unobservable:",
            &capped(&grouped(&a.unobservable_modes)),
        );
    }
    let zeros = match (&a.invariant_zeros, &a.invariant_zeros_note) {
        (Some(z), _) => {
            let items: Vec<(Complex64, String)> = z
                .iter()
                .filter(|(v, _)| v.im >= 0.0)
                .map(|&(v, k)| (v, multiplicity(k)))
                .collect();
            capped(&items)
        }
        (None, Some(why)) => format!("none defined: {why}"),
        (None, None) => "none defined".into(),
    };
    line(&mut s, "invariant zeros:", &zeros);
    if let Some(k) = &a.zero_structure {
        if let Some(worst) = k.residuals.iter().copied().reduce(f64::max) {
            line(
                &mut s,
                "  residual:",
                &format!(
                    "{} at most (σ of [A − zI B; C D] at each zero over its norm, rank n + {})",
                    fmt_sig(worst.max(f64::EPSILON * f64::EPSILON), 2),
                    k.normal_rank
                ),
            );
        }
        let list = |v: &[usize]| {
            if v.is_empty() {
                "none".to_string()
            } else {
                v.iter()
                    .map(usize::to_string)
                    .collect::<Vec<_>>()
                    .join(", ")
            }
        };
        line(
            &mut s,
            "system pencil:",
            &format!(
                "normal rank {} of {}; infinite zeros of order {}; left indices {}; right indices {}",
                k.normal_rank,
                a.m.min(a.p),
                list(&k.infinite_orders),
                list(&k.left_indices),
                list(&k.right_indices)
            ),
        );
    }
    // "stable: every eigenvalue …" reads as "stable — every eigenvalue …" after a label.
    line(
        &mut s,
        "internal stability:",
        &a.internal_reason.replacen(": ", " — ", 1),
    );
    s.push('\n');
    let gains: Vec<Vec<String>> = a
        .dc_gain
        .iter()
        .map(|row| {
            row.iter()
                .map(|g| match g {
                    DcGain::Finite(x) => fmt_num(*x),
                    DcGain::Infinite => "∞".into(),
                })
                .collect()
        })
        .collect();
    s.push_str("  dc gain (rows = outputs, columns = inputs):\n");
    s.push_str(&matrix_text(plant, &gains));
    let bibo: Vec<Vec<String>> = a
        .bibo_stable
        .iter()
        .map(|row| {
            row.iter()
                .map(|&b| if b { "yes" } else { "no" }.to_string())
                .collect()
        })
        .collect();
    s.push_str("\n  BIBO stable (rows = outputs, columns = inputs):\n");
    s.push_str(&matrix_text(plant, &bibo));
    if large && !(detail.modes || detail.shapes) {
        s.push_str(&format!(
            "\n  {} modes: the table with --modes, their shapes with --shapes\n",
            a.modes.len()
        ));
        return s;
    }
    s.push('\n');
    s.push_str(&modes_table(&a.modes));
    if detail.shapes {
        s.push('\n');
        s.push_str(&shapes_text(plant, &a.modes));
    }
    s
}

/// "1 input", "2 inputs".
fn counted(k: usize, what: &str) -> String {
    format!("{k} {what}{}", if k == 1 { "" } else { "s" })
}

/// " (×m)" for m > 1.
fn multiplicity(m: usize) -> String {
    if m > 1 {
        format!(" (×{m})")
    } else {
        String::new()
    }
}

/// Eigenvalues with their multiplicity and structure: "0 (×2, defective: algebraic 2,
/// geometric 1)", "±1.41421j (×2, semisimple)" (" (×2)" when not `long`), "-1".
fn labelled(ev: &[&SsEigenvalue], long: bool) -> Vec<(Complex64, String)> {
    ev.iter()
        .map(|e| {
            let label = if e.algebraic == 1 {
                String::new()
            } else if e.semisimple && !long {
                multiplicity(e.algebraic)
            } else if e.semisimple {
                format!(" (×{}, semisimple)", e.algebraic)
            } else {
                format!(
                    " (×{}, defective: algebraic {}, geometric {})",
                    e.algebraic, e.algebraic, e.geometric
                )
            };
            (e.value, label)
        })
        .collect()
}

/// The summary of a large model's eigenvalues: counts, then the defective ones and those on
/// the axis or in the right half plane.
fn eigen_summary(s: &mut String, upper: &[&SsEigenvalue]) {
    let simple = upper.iter().filter(|e| e.algebraic == 1).count();
    let semisimple = upper
        .iter()
        .filter(|e| e.algebraic > 1 && e.semisimple)
        .count();
    let defective = upper.iter().filter(|e| !e.semisimple).count();
    s.push_str(&format!(
        "  {:<20}{} distinct up to conjugation: {simple} simple, {semisimple} multiple \
         semisimple, {defective} defective\n",
        "eigenvalues of A:",
        upper.len()
    ));
    let list = |pick: &dyn Fn(&SsEigenvalue) -> bool| -> String {
        let chosen: Vec<&SsEigenvalue> = upper.iter().copied().filter(|e| pick(e)).collect();
        capped(&labelled(&chosen, false))
    };
    use crate::poly::{HalfPlane, half_plane};
    s.push_str(&format!(
        "  {:<20}{}\n",
        "  defective:",
        list(&|e| !e.semisimple)
    ));
    s.push_str(&format!(
        "  {:<20}{}\n",
        "  on the axis:",
        list(&|e| half_plane(e.value) == HalfPlane::Axis)
    ));
    s.push_str(&format!(
        "  {:<20}{}\n",
        "  right half plane:",
        list(&|e| half_plane(e.value) == HalfPlane::Right)
    ));
}

/// Values with repetition grouped into distinct upper values with " (×k)".
fn grouped(v: &[Complex64]) -> Vec<(Complex64, String)> {
    let mut out: Vec<(Complex64, usize)> = Vec::new();
    for &z in v.iter().filter(|z| z.im >= 0.0) {
        match out.iter_mut().find(|(w, _)| *w == z) {
            Some((_, k)) => *k += 1,
            None => out.push((z, 1)),
        }
    }
    out.sort_by(|x, y| y.0.re.total_cmp(&x.0.re).then(y.0.im.total_cmp(&x.0.im)));
    out.into_iter().map(|(z, k)| (z, multiplicity(k))).collect()
}

/// A labelled list cut after [`MAX_SUMMARY_ENTRIES`] entries ("…, and 12 more").
fn capped(items: &[(Complex64, String)]) -> String {
    if items.len() <= MAX_SUMMARY_ENTRIES {
        return labelled_roots_text(items);
    }
    format!(
        "{}, … and {} more",
        labelled_roots_text(&items[..MAX_SUMMARY_ENTRIES]),
        items.len() - MAX_SUMMARY_ENTRIES
    )
}

/// A matrix of cells with the plant's output names as row labels and its input names as
/// column heads, indented by four spaces.
fn matrix_text(plant: &Plant, cells: &[Vec<String>]) -> String {
    let name = |names: &[String], k: usize, stem: &str| {
        names
            .get(k)
            .cloned()
            .unwrap_or_else(|| format!("{stem}{}", k + 1))
    };
    let m = cells.first().map_or(0, Vec::len);
    let rows: Vec<String> = (0..cells.len())
        .map(|j| name(&plant.signals.outputs, j, "y"))
        .collect();
    let cols: Vec<String> = (0..m)
        .map(|i| name(&plant.signals.inputs, i, "u"))
        .collect();
    let lw = rows.iter().map(|r| r.chars().count()).max().unwrap_or(0);
    let widths: Vec<usize> = (0..m)
        .map(|i| {
            cells
                .iter()
                .map(|row| row[i].chars().count())
                .chain([cols[i].chars().count(), 10])
                .max()
                .unwrap_or(10)
        })
        .collect();
    let pad_left = |text: &str, w: usize| {
        format!(
            "{}{text}",
            " ".repeat(w.saturating_sub(text.chars().count()))
        )
    };
    let mut s = format!("    {}", " ".repeat(lw));
    for (c, w) in cols.iter().zip(&widths) {
        s.push_str("  ");
        s.push_str(&pad_left(c, *w));
    }
    s.push('\n');
    for (r, row) in rows.iter().zip(cells) {
        s.push_str(&format!("    {r}{}", " ".repeat(lw - r.chars().count())));
        for (cell, w) in row.iter().zip(&widths) {
            s.push_str("  ");
            s.push_str(&pad_left(cell, *w));
        }
        s.push('\n');
    }
    s
}

/// The modes table: eigenvalue (upper member of a pair), ωn, ζ, τ, geometric multiplicity and
/// the worst residual of its shapes.
fn modes_table(modes: &[SsMode]) -> String {
    let mut s = String::from("  Modes:\n");
    s.push_str(&format!(
        "    {:<28} {:>12} {:>10} {:>14} {:>10} {:>10}\n",
        "eigenvalue", "wn [rad/s]", "zeta", "tau [s]", "geometric", "residual"
    ));
    for m in modes {
        s.push_str(&format!(
            "    {:<28} {:>12} {:>10} {:>14} {:>10} {:>10}\n",
            format!("{}{}", fmt_root(m.value, 6), multiplicity(m.algebraic)),
            fmt_sig(m.wn, 6),
            if m.zeta.is_finite() {
                fmt_sig(m.zeta, 6)
            } else {
                "-".into()
            },
            m.tau.map(|t| fmt_sig(t, 6)).unwrap_or_else(|| "-".into()),
            m.shapes.len(),
            fmt_sig(worst_residual(m), 2)
        ));
    }
    s
}

/// Every mode's shapes, each as its largest components (modulus) with the state names.
fn shapes_text(plant: &Plant, modes: &[SsMode]) -> String {
    let mut s = format!(
        "  Mode shapes (unit eigenvectors; the {SHAPE_COMPONENTS} largest components, those \
         below {} of the largest left out):\n",
        fmt_sig(SHAPE_NEGLIGIBLE, 1)
    );
    for m in modes {
        let head = format!("{}{}", fmt_root(m.value, 6), multiplicity(m.algebraic));
        for (k, v) in m.shapes.iter().enumerate() {
            let tag = if m.shapes.len() > 1 {
                format!("{head} [{}]", k + 1)
            } else {
                head.clone()
            };
            s.push_str(&format!("    {tag}: {}\n", shape_text(plant, v)));
        }
    }
    s
}

/// "x1 0.707107, v1 0.707107j" — the largest components of one shape, "(and 3 more)" when
/// more are not negligible.
fn shape_text(plant: &Plant, v: &[Complex64]) -> String {
    let largest = v.iter().map(|z| z.norm()).fold(0.0, f64::max);
    let tol = SHAPE_NEGLIGIBLE * largest;
    // Real and imaginary parts at rounding level are 0 (a real shape in a complex basis).
    let clean = |x: f64| if x.abs() <= tol { 0.0 } else { x };
    let v: Vec<Complex64> = v
        .iter()
        .map(|z| Complex64::new(clean(z.re), clean(z.im)))
        .collect();
    let mut idx: Vec<usize> = (0..v.len()).filter(|&i| v[i].norm() > tol).collect();
    // Largest first; moduli equal to nine digits (a symmetric shape) in the states' order.
    let key = |i: usize| (v[i].norm() / largest * 1e9).round();
    idx.sort_by(|&i, &j| key(j).total_cmp(&key(i)).then(i.cmp(&j)));
    let more = idx.len().saturating_sub(SHAPE_COMPONENTS);
    idx.truncate(SHAPE_COMPONENTS);
    let name = |i: usize| {
        plant
            .signals
            .states
            .get(i)
            .cloned()
            .unwrap_or_else(|| format!("x{}", i + 1))
    };
    let mut text = idx
        .iter()
        .map(|&i| format!("{} {}", name(i), complex_text(v[i])))
        .collect::<Vec<_>>()
        .join(", ");
    if more > 0 {
        text.push_str(&format!(" (and {more} more)"));
    }
    text
}
