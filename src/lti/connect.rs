//! Interconnection by named signals (the `connect` of MATLAB and python-control): blocks with
//! named input and output signals, summing junctions `e = r - y`, and the external inputs and
//! outputs, closed into one state-space model.
//!
//! The algorithm: stack every block block-diagonally (x = \[x₁; x₂; …\], u and y the
//! concatenated block inputs and outputs), so ẋ = A x + B u and y = C x + D u. The *dependent*
//! signals v are the block outputs y and the sums s; the external inputs r are free. Each
//! block input is a signal, each sum a combination of signals: u = U_v v + U_r r and
//! s = S_v v + S_r r. Then v = \[C; 0\] x + F_v v + F_r r with F = \[D·U; S\], and
//! (I − F_v) v = \[C; 0\] x + F_r r. When I − F_v is singular the algebraic loop (through the
//! feedthroughs D and the sums) is not well posed: the error names the signals of its null
//! vector. Otherwise v = V_x x + V_r r and
//! A_cl = A + B·U_v·V_x, B_cl = B·(U_v·V_r + U_r), C_cl = O_v·V_x, D_cl = O_v·V_r + O_r for the
//! outputs z = O_v v + O_r r.
//!
//! ```
//! use ltikit::lti::connect::{Block, Sum, connect};
//! use ltikit::{StateSpace, TransferFunction};
//! let ss = |n: &[f64], d: &[f64]| {
//!     StateSpace::from_tf(&TransferFunction::from_descending(n, d).unwrap()).unwrap()
//! };
//! // unity feedback around 1/(s + 1): T = 1/(s + 2)
//! let blocks = vec![Block::new("P", ss(&[1.0], &[1.0, 1.0]), &["e"], &["y"])];
//! let sums = vec![Sum::parse("e", "r - y").unwrap()];
//! let t = connect(&blocks, &sums, &["r".into()], &["y".into()]).unwrap();
//! assert_eq!(t.to_tf().unwrap().den().coeffs(), &[1.0, 2.0]);
//! // e = r + e has no solution: the loop through `e` is not well posed
//! let bad = vec![Sum::parse("e", "r + e").unwrap()];
//! let err = connect(&[], &bad, &["r".into()], &["e".into()]).unwrap_err().to_string();
//! assert!(err.contains("not well posed") && err.contains("`e`"), "{err}");
//! ```

use std::collections::BTreeMap;

use nalgebra::DMatrix;

use crate::error::{LtiError, Result, abbreviate};
use crate::limits::{DIAGRAM_SIGNALS, MAX_STATES};
use crate::lti::StateSpace;

/// A block of a diagram: a model with one named signal per input and per output.
#[derive(Debug, Clone, PartialEq)]
pub struct Block {
    /// The block's name (in errors).
    pub name: String,
    /// Its model (any numbers of inputs and outputs; no dead time).
    pub model: StateSpace,
    /// The signal feeding each input, in order.
    pub inputs: Vec<String>,
    /// The signal each output drives, in order.
    pub outputs: Vec<String>,
}

impl Block {
    /// A block from its name, model and signal names.
    ///
    /// ```
    /// use ltikit::lti::connect::Block;
    /// use ltikit::StateSpace;
    /// use nalgebra::DMatrix;
    /// let k = StateSpace::new(DMatrix::zeros(0, 0), DMatrix::zeros(0, 1), DMatrix::zeros(1, 0),
    ///     DMatrix::from_element(1, 1, 2.0)).unwrap();
    /// assert_eq!(Block::new("K", k, &["e"], &["u"]).outputs, vec!["u".to_string()]);
    /// ```
    pub fn new(name: &str, model: StateSpace, inputs: &[&str], outputs: &[&str]) -> Block {
        Block {
            name: name.to_string(),
            model,
            inputs: inputs.iter().map(|s| s.to_string()).collect(),
            outputs: outputs.iter().map(|s| s.to_string()).collect(),
        }
    }
}

/// A summing junction: a signal defined as a combination of signals, `e = r - y`,
/// `u = 2*a + 0.5 b - c`.
#[derive(Debug, Clone, PartialEq)]
pub struct Sum {
    /// The signal it drives.
    pub name: String,
    /// (coefficient, signal) of each term.
    pub terms: Vec<(f64, String)>,
}

impl Sum {
    /// Reads `name = expression`: terms `[+|-] [NUMBER [*]] SIGNAL` (a signal name is letters,
    /// digits and `_`, not starting with a digit).
    ///
    /// Errors: an empty expression, a bad signal name or number, a dangling sign.
    ///
    /// ```
    /// use ltikit::lti::connect::Sum;
    /// let s = Sum::parse("e", "r - 0.5*y + 2 w").unwrap();
    /// assert_eq!(s.terms, vec![(1.0, "r".into()), (-0.5, "y".into()), (2.0, "w".into())]);
    /// assert!(Sum::parse("e", "r -").is_err());
    /// assert!(Sum::parse("e", "r y").is_err());
    /// ```
    pub fn parse(name: &str, expression: &str) -> Result<Sum> {
        check_signal_name(name)?;
        let bad = |why: &str| {
            LtiError::invalid(format!(
                "sum `{}` = \"{}\": {why} (write terms such as \"r - y\" or \"2*a + 0.5*b\")",
                abbreviate(name),
                abbreviate(expression)
            ))
        };
        let chars: Vec<char> = expression.chars().collect();
        let mut i = 0;
        let mut terms = Vec::new();
        let skip = |i: &mut usize| {
            while *i < chars.len() && chars[*i].is_whitespace() {
                *i += 1;
            }
        };
        loop {
            skip(&mut i);
            if i >= chars.len() {
                break;
            }
            let mut sign = 1.0;
            let mut signed = false;
            while i < chars.len() && matches!(chars[i], '+' | '-') {
                if chars[i] == '-' {
                    sign = -sign;
                }
                signed = true;
                i += 1;
                skip(&mut i);
            }
            if !signed && !terms.is_empty() {
                return Err(bad("terms must be joined by + or -"));
            }
            let mut coef = 1.0;
            if i < chars.len() && (chars[i].is_ascii_digit() || chars[i] == '.') {
                let start = i;
                while i < chars.len()
                    && (chars[i].is_ascii_digit()
                        || chars[i] == '.'
                        || ((chars[i] == 'e' || chars[i] == 'E')
                            && i + 1 < chars.len()
                            && (chars[i + 1].is_ascii_digit()
                                || matches!(chars[i + 1], '+' | '-'))))
                {
                    if matches!(chars[i], 'e' | 'E') {
                        i += 1; // the exponent's sign
                    }
                    i += 1;
                }
                let text: String = chars[start..i].iter().collect();
                coef = text
                    .parse::<f64>()
                    .ok()
                    .filter(|c| c.is_finite())
                    .ok_or_else(|| bad(&format!("'{}' is not a number", abbreviate(&text))))?;
                skip(&mut i);
                if i < chars.len() && chars[i] == '*' {
                    i += 1;
                    skip(&mut i);
                }
            }
            let start = i;
            while i < chars.len() && (chars[i].is_alphanumeric() || chars[i] == '_') {
                i += 1;
            }
            if start == i {
                return Err(bad(if i >= chars.len() {
                    "a term has no signal"
                } else {
                    "expected a signal name"
                }));
            }
            let signal: String = chars[start..i].iter().collect();
            check_signal_name(&signal)?;
            terms.push((sign * coef, signal));
        }
        if terms.is_empty() {
            return Err(bad("no terms"));
        }
        Ok(Sum {
            name: name.to_string(),
            terms,
        })
    }
}

/// Errors unless `name` is a signal name: letters, digits and `_`, not starting with a digit.
pub fn check_signal_name(name: &str) -> Result<()> {
    let ok = name
        .chars()
        .next()
        .is_some_and(|c| c.is_alphabetic() || c == '_')
        && name.chars().all(|c| c.is_alphanumeric() || c == '_');
    if ok {
        Ok(())
    } else {
        Err(LtiError::invalid(format!(
            "'{}' is not a signal name (letters, digits and _, not starting with a digit)",
            abbreviate(name)
        )))
    }
}

/// A model as a state-space block: a transfer function in controllable canonical form, a
/// state-space model as it is. `what` names it in errors.
///
/// Errors: a dead time (a diagram and the interconnections of state space are rational: the
/// delay would be lost), an improper transfer function.
///
/// ```
/// use ltikit::lti::{Model, connect::state_space_of};
/// use ltikit::TransferFunction;
/// let g = TransferFunction::from_descending(&[1.0], &[1.0, 1.0]).unwrap();
/// assert_eq!(state_space_of(&Model::Tf(g.clone()), "block `P`").unwrap().order(), 1);
/// let e = state_space_of(&Model::Tf(g.with_delay(0.5).unwrap()), "block `P`").unwrap_err();
/// assert!(e.to_string().contains("block `P` has a dead time"));
/// ```
pub fn state_space_of(model: &crate::lti::Model, what: &str) -> Result<StateSpace> {
    let delayed = match model {
        crate::lti::Model::Tf(g) => g.delay() > 0.0,
        crate::lti::Model::Ss(ss) => ss.has_delays(),
    };
    if delayed {
        return Err(LtiError::invalid(format!(
            "{what} has a dead time: it is connected exactly only as a rational model (replace \
             the delay by a Padé approximant, `ltikit pade`)"
        )));
    }
    match model {
        crate::lti::Model::Tf(g) => StateSpace::from_tf(g),
        crate::lti::Model::Ss(ss) => Ok(ss.clone()),
    }
}

/// What drives a signal.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Driver {
    /// External input k.
    External(usize),
    /// Output j of the stacked blocks.
    Output(usize),
    /// Sum i.
    Sum(usize),
}

/// Who drives a signal, in words (errors).
fn describe(driver: Driver, blocks: &[Block], sums: &[Sum]) -> String {
    match driver {
        Driver::External(_) => "the diagram's inputs".into(),
        Driver::Output(j) => {
            let mut k = j;
            for b in blocks {
                if k < b.outputs.len() {
                    return format!("block `{}`", abbreviate(&b.name));
                }
                k -= b.outputs.len();
            }
            "a block".into()
        }
        Driver::Sum(i) => format!("the sum `{}`", abbreviate(&sums[i].name)),
    }
}

/// The blocks, sums, external `inputs` and `outputs` closed into one state-space model (see
/// the [module docs](self)), in the blocks' common domain; the states in block order.
///
/// Errors (each naming the signal or block): a block whose signal lists do not match its
/// model's inputs and outputs, a signal driven twice (by two blocks, a block and a sum, an
/// input and anything), a signal used but driven by nothing, blocks of different domains, a
/// block with a dead time, an algebraic loop that is not well posed, more than
/// [`MAX_STATES`] states or [`crate::limits::MAX_DIAGRAM_SIGNALS`] signals, no output.
pub fn connect(
    blocks: &[Block],
    sums: &[Sum],
    inputs: &[String],
    outputs: &[String],
) -> Result<StateSpace> {
    if outputs.is_empty() {
        return Err(LtiError::invalid(
            "a diagram needs at least one output signal (`outputs`)",
        ));
    }
    let mut domain: Option<crate::lti::Domain> = None;
    let (mut n, mut m, mut p) = (0usize, 0usize, 0usize);
    for b in blocks {
        let ss = &b.model;
        let name = abbreviate(&b.name);
        if ss.has_delays() {
            return Err(LtiError::invalid(format!(
                "block `{name}` has a dead time: a diagram is connected exactly only for \
                 rational blocks (replace the delay by a Padé approximant, `ltikit pade`)"
            )));
        }
        if b.inputs.len() != ss.n_inputs() || b.outputs.len() != ss.n_outputs() {
            return Err(LtiError::invalid(format!(
                "block `{name}` has {} inputs and {} outputs, but {} input and {} output \
                 signals are named",
                ss.n_inputs(),
                ss.n_outputs(),
                b.inputs.len(),
                b.outputs.len()
            )));
        }
        domain = Some(match domain {
            None => ss.domain,
            Some(d) => d.join(ss.domain, &format!("block `{name}`"))?,
        });
        n += ss.order();
        m += ss.n_inputs();
        p += ss.n_outputs();
    }
    crate::limits::STATES.check("the diagram's states", n as u128)?;
    let q = p + sums.len();
    let k = inputs.len();
    DIAGRAM_SIGNALS.check("the diagram's signals", (q + k + m) as u128)?;
    debug_assert!(n <= MAX_STATES);

    // who drives each signal
    let mut order: Vec<(&str, Driver)> = Vec::new();
    for (i, r) in inputs.iter().enumerate() {
        order.push((r, Driver::External(i)));
    }
    let mut j = 0;
    for b in blocks {
        for y in &b.outputs {
            order.push((y, Driver::Output(j)));
            j += 1;
        }
    }
    for (i, s) in sums.iter().enumerate() {
        order.push((&s.name, Driver::Sum(i)));
    }
    let mut drivers: BTreeMap<&str, Driver> = BTreeMap::new();
    for (name, d) in order {
        check_signal_name(name)?;
        if let Some(&first) = drivers.get(name) {
            return Err(LtiError::invalid(format!(
                "the signal `{}` is driven twice: by {} and by {}",
                abbreviate(name),
                describe(first, blocks, sums),
                describe(d, blocks, sums)
            )));
        }
        drivers.insert(name, d);
    }
    // the column of a signal in [v; r]
    let column = |name: &str, used_by: &str| -> Result<usize> {
        check_signal_name(name)?;
        match drivers.get(name) {
            Some(Driver::Output(j)) => Ok(*j),
            Some(Driver::Sum(i)) => Ok(p + i),
            Some(Driver::External(i)) => Ok(q + i),
            None => Err(LtiError::invalid(format!(
                "the signal `{}` ({used_by}) is driven by nothing: no block output, sum or \
                 diagram input has that name",
                abbreviate(name)
            ))),
        }
    };

    // stacked blocks
    let mut a = DMatrix::zeros(n, n);
    let mut b_all = DMatrix::zeros(n, m);
    let mut c_all = DMatrix::zeros(p, n);
    let mut d_all = DMatrix::zeros(p, m);
    let mut u_sel = DMatrix::zeros(m, q + k);
    let (mut x0, mut u0, mut y0) = (0, 0, 0);
    for blk in blocks {
        let ss = &blk.model;
        let (bn, bm, bp) = (ss.order(), ss.n_inputs(), ss.n_outputs());
        a.view_mut((x0, x0), (bn, bn)).copy_from(&ss.a);
        b_all.view_mut((x0, u0), (bn, bm)).copy_from(&ss.b);
        c_all.view_mut((y0, x0), (bp, bn)).copy_from(&ss.c);
        d_all.view_mut((y0, u0), (bp, bm)).copy_from(&ss.d);
        for (i, s) in blk.inputs.iter().enumerate() {
            let used = format!("input {} of block `{}`", i + 1, abbreviate(&blk.name));
            u_sel[(u0 + i, column(s, &used)?)] = 1.0;
        }
        x0 += bn;
        u0 += bm;
        y0 += bp;
    }
    // F = [D·U; S]
    let mut f = DMatrix::zeros(q, q + k);
    f.view_mut((0, 0), (p, q + k)).copy_from(&(&d_all * &u_sel));
    for (i, s) in sums.iter().enumerate() {
        let used = format!("in the sum `{}`", abbreviate(&s.name));
        for (coef, name) in &s.terms {
            f[(p + i, column(name, &used)?)] += coef;
        }
    }
    let mut out_sel = DMatrix::zeros(outputs.len(), q + k);
    for (i, z) in outputs.iter().enumerate() {
        out_sel[(i, column(z, "a diagram output")?)] = 1.0;
    }
    let i_minus = DMatrix::<f64>::identity(q, q) - f.columns(0, q);
    let names: Vec<&str> = {
        let mut v = vec![""; q];
        for (name, d) in &drivers {
            match d {
                Driver::Output(j) => v[*j] = name,
                Driver::Sum(i) => v[p + i] = name,
                Driver::External(_) => {}
            }
        }
        v
    };
    well_posed(&i_minus, &names)?;
    // v = V_x x + V_r r
    let mut rhs = DMatrix::zeros(q, n + k);
    rhs.view_mut((0, 0), (p, n)).copy_from(&c_all);
    rhs.view_mut((0, n), (q, k)).copy_from(&f.columns(q, k));
    let v = i_minus.lu().solve(&rhs).ok_or_else(|| {
        LtiError::invalid("the diagram's algebraic loop is not well posed (I − D·M is singular)")
    })?;
    let (vx, vr) = (v.columns(0, n), v.columns(n, k));
    let uv = u_sel.columns(0, q);
    let ur = u_sel.columns(q, k);
    let a_cl = &a + &b_all * (uv * vx);
    let b_cl = &b_all * (uv * vr + ur);
    let ov = out_sel.columns(0, q);
    let c_cl = ov * vx;
    let d_cl = ov * vr + out_sel.columns(q, k);
    let ss = StateSpace::new(a_cl, b_cl, c_cl, d_cl)?;
    for (x, what) in [(&ss.a, "A"), (&ss.b, "B"), (&ss.c, "C"), (&ss.d, "D")] {
        if x.iter().any(|v| !v.is_finite()) {
            return Err(LtiError::invalid(format!(
                "the connected diagram's {what} matrix overflows (the algebraic loop is nearly \
                 singular)"
            )));
        }
    }
    Ok(match domain {
        Some(d) => ss.with_domain(d),
        None => ss,
    })
}

/// Nothing when I − F_v is far from singular, else an error naming the signals of the algebraic loop that is
/// not well posed (those with a large entry in the null vector).
fn well_posed(m: &DMatrix<f64>, names: &[&str]) -> Result<()> {
    let q = m.nrows();
    let svd = m
        .clone()
        .try_svd(true, true, f64::EPSILON, 10_000)
        .ok_or_else(|| {
            LtiError::invalid("the diagram's algebraic loop: the SVD did not converge")
        })?;
    let sv = &svd.singular_values;
    let (imin, smin) = sv
        .iter()
        .enumerate()
        .min_by(|a, b| a.1.total_cmp(b.1))
        .map_or((0, f64::INFINITY), |(i, s)| (i, *s));
    let smax = sv.iter().copied().fold(0.0, f64::max);
    if q > 0 && smin <= 1e-12 * smax.max(1.0) * q as f64 {
        let vt = svd.v_t.as_ref();
        let loop_names: Vec<String> = match vt {
            Some(vt) => {
                let row = vt.row(imin);
                let big = row.iter().fold(0.0f64, |a, x| a.max(x.abs()));
                row.iter()
                    .enumerate()
                    .filter(|(_, x)| x.abs() >= 0.1 * big)
                    .map(|(i, _)| format!("`{}`", abbreviate(names[i])))
                    .collect()
            }
            None => Vec::new(),
        };
        return Err(LtiError::invalid(format!(
            "the algebraic loop through {} is not well posed: I − D·M is singular (the \
             feedthroughs and sums around it cancel; a loop needs 1 + loop gain ≠ 0 at infinite \
             frequency)",
            loop_names.join(", ")
        )));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lti::TransferFunction;
    use num_complex::Complex64;

    fn ss(n: &[f64], d: &[f64]) -> StateSpace {
        StateSpace::from_tf(&TransferFunction::from_descending(n, d).unwrap()).unwrap()
    }

    #[test]
    fn feedthrough_loop_solved_and_ill_posed_named() {
        // K = 2 static in the loop: e = r - y, y = 2 e -> y = 2/3 r
        let k = ss(&[2.0], &[1.0]);
        let blocks = vec![Block::new("K", k.clone(), &["e"], &["y"])];
        let sums = vec![Sum::parse("e", "r - y").unwrap()];
        let t = connect(&blocks, &sums, &["r".into()], &["y".into()]).unwrap();
        assert!((t.d[(0, 0)] - 2.0 / 3.0).abs() < 1e-15);
        // positive feedback with K = 1: 1 - 1 = 0
        let one = ss(&[1.0], &[1.0]);
        let blocks = vec![Block::new("K", one, &["e"], &["y"])];
        let sums = vec![Sum::parse("e", "r + y").unwrap()];
        let e = connect(&blocks, &sums, &["r".into()], &["y".into()])
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("`y`") && e.contains("`e`") && e.contains("not well posed"),
            "{e}"
        );
    }

    #[test]
    fn drivers_checked() {
        let g = ss(&[1.0], &[1.0, 1.0]);
        let two = vec![
            Block::new("A", g.clone(), &["r"], &["y"]),
            Block::new("B", g.clone(), &["r"], &["y"]),
        ];
        let e = connect(&two, &[], &["r".into()], &["y".into()])
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("`y` is driven twice: by block `A` and by block `B`"),
            "{e}"
        );
        let one = vec![Block::new("A", g.clone(), &["w"], &["y"])];
        let e = connect(&one, &[], &["r".into()], &["y".into()])
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("`w` (input 1 of block `A`) is driven by nothing"),
            "{e}"
        );
        let e = connect(&one, &[], &["w".into()], &["z".into()])
            .unwrap_err()
            .to_string();
        assert!(e.contains("`z` (a diagram output)"), "{e}");
        let wrong = vec![Block::new("A", g, &["r", "q"], &["y"])];
        let e = connect(&wrong, &[], &["r".into()], &["y".into()])
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("block `A` has 1 inputs and 1 outputs, but 2 input"),
            "{e}"
        );
    }

    #[test]
    fn series_of_blocks_is_the_product() {
        let g1 = ss(&[1.0], &[1.0, 1.0]);
        let g2 = ss(&[3.0, 1.0], &[1.0, 2.0]);
        let blocks = vec![
            Block::new("G1", g1.clone(), &["u"], &["w"]),
            Block::new("G2", g2.clone(), &["w"], &["y"]),
        ];
        let t = connect(&blocks, &[], &["u".into()], &["y".into()]).unwrap();
        let (a, b) = (t.to_tf().unwrap(), g1.series(&g2).unwrap().to_tf().unwrap());
        let s = Complex64::new(0.3, 0.7);
        assert!((a.eval(s) - b.eval(s)).norm() < 1e-14);
    }
}
