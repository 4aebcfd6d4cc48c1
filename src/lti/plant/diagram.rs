//! Diagram files: a plant built from named blocks joined by named signals — a TOML file with a
//! `[blocks]` table, read wherever a plant file is (`--plant loop.toml`), closed into one
//! state-space model by [`crate::lti::connect::connect`].
//!
//! ```toml
//! name = "PI loop around a motor"     # optional, as are `description` and `dt`
//! inputs = ["r"]                      # the diagram's external inputs
//! outputs = ["y"]                     # what it outputs (any signals)
//!
//! [blocks.C]                          # a block by its coefficients (descending powers)
//! num = [1, 2]
//! den = [1, 0]
//! input = "e"                         # the signal feeding it
//! output = "u"                        # the signal it drives
//!
//! [blocks.P]                          # a plant file, its path relative to the diagram
//! plant = "motor.toml"
//! input = "u"
//! output = "y"
//!
//! [sums]                              # summing junctions: terms [+|-] [NUMBER [*]] SIGNAL
//! e = "r - y"
//! ```
//! A block is one of: `num`/`den` (a transfer function), `a`, `b`, `c` (and `d`) (state
//! space, MIMO allowed: `input = ["u1", "u2"]`, one signal per input and per output, in
//! order), `plant = "FILE.toml"` (any plant file, a diagram file too) or
//! `controller = "pid:kp=2,ki=1,kd=0.5,tf=0.01"` (the controller specifications of
//! `--controller`: p, pi, pd, pid, lead, lag, tf:NUM/DEN). With `dt = T` the coefficient,
//! matrix and controller blocks are discrete-time (a continuous controller is sampled by
//! Tustin, as in front of a discrete plant); plant files carry their own `dt`, and every block
//! must end in the same domain. A signal is driven by exactly one of: a diagram input, a block
//! output, a sum; the states of the result are the blocks' in the order of the block names,
//! named `BLOCK.x1`, ….
//!
//! Errors name the file, the key's line and column, and the block or signal: a signal driven
//! twice or never, a block that is not one of the kinds above, signal lists that do not match
//! the block's inputs and outputs, mixed domains, a dead time, an ill-posed algebraic loop
//! (naming its signals), and the limits `MAX_DIAGRAM_SIGNALS` and `MAX_DIAGRAM_DEPTH`.
//!
//! ```
//! use ltikit::lti::Plant;
//! let dir = std::env::temp_dir().join(format!("ltikit-diagram-doc-{}", std::process::id()));
//! std::fs::create_dir_all(&dir).unwrap();
//! let path = dir.join("loop.toml");
//! std::fs::write(&path, "inputs = [\"r\"]\noutputs = [\"y\"]\n\
//!     [blocks.P]\nnum = [1]\nden = [1, 1]\ninput = \"e\"\noutput = \"y\"\n\
//!     [sums]\ne = \"r - y\"\n").unwrap();
//! let p = Plant::from_file(&path).unwrap();   // 1/(s + 1) in unity feedback: 1/(s + 2)
//! assert!((p.factored().unwrap().dc_gain().unwrap() - 0.5).abs() < 1e-15);
//! std::fs::write(&path, "inputs = [\"r\"]\noutputs = [\"y\"]\n\
//!     [blocks.P]\nnum = [1]\nden = [1, 1]\ninput = \"e\"\noutput = \"y\"\n").unwrap();
//! let e = Plant::from_file(&path).unwrap_err().to_string();
//! assert!(e.contains("loop.toml, line 3, column 9: the signal `e`"), "{e}");
//! ```

use serde::Deserialize;
use std::collections::BTreeMap;
use std::path::Path;

use super::Plant;
use super::file::{self, CoeffList, MatrixSpec};
use super::located;
use crate::error::{LtiError, Result, abbreviate};
use crate::lti::connect::{Block, Sum, connect, state_space_of};
use crate::lti::{Controller, Domain, Model, Signals, StateSpace, TransferFunction};

/// One signal or a list of signals.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(untagged)]
enum SignalList {
    One(String),
    Many(Vec<String>),
}

impl SignalList {
    fn names(&self) -> Vec<String> {
        match self {
            SignalList::One(s) => vec![s.clone()],
            SignalList::Many(v) => v.clone(),
        }
    }
}

/// A block of a diagram file.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
struct BlockSpec {
    #[serde(default)]
    num: Option<CoeffList>,
    #[serde(default)]
    den: Option<CoeffList>,
    #[serde(default)]
    a: Option<MatrixSpec>,
    #[serde(default)]
    b: Option<MatrixSpec>,
    #[serde(default)]
    c: Option<MatrixSpec>,
    #[serde(default)]
    d: Option<MatrixSpec>,
    #[serde(default)]
    plant: Option<String>,
    #[serde(default)]
    controller: Option<String>,
    input: SignalList,
    output: SignalList,
}

/// A diagram file.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
struct DiagramFile {
    #[serde(default)]
    name: Option<String>,
    #[serde(default)]
    description: Option<String>,
    #[serde(default)]
    dt: Option<f64>,
    inputs: Vec<String>,
    outputs: Vec<String>,
    blocks: BTreeMap<String, BlockSpec>,
    #[serde(default)]
    sums: BTreeMap<String, String>,
}

/// True when plant-file text is a diagram (it has a top-level `blocks` key).
pub(super) fn is_diagram(text: &str) -> bool {
    text.parse::<toml::Table>()
        .is_ok_and(|t| t.contains_key("blocks"))
}

/// The diagram file at `path` (its text `text`) as a plant, `depth` diagrams deep.
pub(super) fn load(path: &Path, text: &str, depth: usize) -> Result<Plant> {
    crate::limits::DIAGRAM_DEPTH.check(
        &format!(
            "`plant` {} (diagrams inside diagrams)",
            abbreviate(&path.display().to_string())
        ),
        depth as u128,
    )?;
    let f: DiagramFile = toml::from_str(text).map_err(|e| {
        let (at, message) = located::toml_error(text, &e);
        file::in_file(path, located::bad_record(at.unwrap_or_default(), message))
    })?;
    let at = |key: &str, e: LtiError| file::at_key_in_file(path, text, Some(key), e);
    let domain = match f.dt {
        Some(dt) => Domain::discrete(dt).map_err(|e| at("dt", e))?,
        None => Domain::Continuous,
    };
    crate::limits::DIAGRAM_SIGNALS.check("the diagram's blocks", f.blocks.len() as u128)?;
    let mut blocks = Vec::with_capacity(f.blocks.len());
    for (name, spec) in &f.blocks {
        let key = format!("blocks.{name}");
        let model = block_model(path, name, spec, domain, depth).map_err(|e| {
            // the nesting limit as it is (not once more per level)
            if matches!(&e, LtiError::LimitExceeded { limit, .. } if limit == "MAX_DIAGRAM_DEPTH") {
                return e;
            }
            let e = if e.to_string().contains("block `") {
                e
            } else {
                LtiError::invalid(format!("block `{}`: {e}", abbreviate(name)))
            };
            at(&key, e)
        })?;
        blocks.push(Block {
            name: name.clone(),
            model,
            inputs: spec.input.names(),
            outputs: spec.output.names(),
        });
    }
    let mut sums = Vec::with_capacity(f.sums.len());
    for (name, expr) in &f.sums {
        sums.push(Sum::parse(name, expr).map_err(|e| at(&format!("sums.{name}"), e))?);
    }
    let ss = connect(&blocks, &sums, &f.inputs, &f.outputs).map_err(|e| {
        // place the error at the key it names, when it names one
        let msg = e.to_string();
        let key = named_key(&msg, &f);
        at(&key, e)
    })?;
    let states = blocks
        .iter()
        .flat_map(|b| (1..=b.model.order()).map(move |k| format!("{}.x{k}", b.name)))
        .collect();
    let name = f.name.clone().unwrap_or_else(|| {
        format!(
            "diagram {} ({} blocks)",
            abbreviate(&path.file_name().map_or_else(
                || path.display().to_string(),
                |n| n.to_string_lossy().into()
            )),
            blocks.len()
        )
    });
    let mut plant = Plant::from_state_space(ss, Some(name))?;
    plant.signals = Signals::for_model(&plant.model, f.inputs.clone(), f.outputs.clone(), states)?;
    plant.description = f.description.clone();
    Ok(plant)
}

/// The key of the diagram an error of [`connect`] is about: the block or sum it names (first
/// `block \`X\`` or `sum \`X\``), else the signal lists.
fn named_key(msg: &str, f: &DiagramFile) -> String {
    let after = |tag: &str| {
        msg.find(tag)
            .map(|i| &msg[i + tag.len()..])
            .and_then(|rest| rest.split('`').next())
            .map(str::to_string)
    };
    if let Some(b) = after("block `").filter(|b| f.blocks.contains_key(b)) {
        return format!("blocks.{b}");
    }
    if let Some(s) = after("sum `").filter(|s| f.sums.contains_key(s)) {
        return format!("sums.{s}");
    }
    if msg.contains("diagram output") {
        return "outputs".into();
    }
    // the signal named first: the block or sum that uses it
    if let Some(sig) = after("signal `") {
        for (name, b) in &f.blocks {
            if b.input.names().contains(&sig) || b.output.names().contains(&sig) {
                return format!("blocks.{name}");
            }
        }
        if f.sums.contains_key(&sig) {
            return format!("sums.{sig}");
        }
    }
    "inputs".into()
}

/// The model of one block, in the diagram's `domain` (coefficients, matrices, controllers) or
/// its plant file's.
fn block_model(
    path: &Path,
    name: &str,
    spec: &BlockSpec,
    domain: Domain,
    depth: usize,
) -> Result<StateSpace> {
    let what = format!("block `{}`", abbreviate(name));
    let coeffs = spec.den.is_some() || spec.num.is_some();
    let matrices = spec.a.is_some() || spec.b.is_some() || spec.c.is_some() || spec.d.is_some();
    let kinds = [
        coeffs,
        matrices,
        spec.plant.is_some(),
        spec.controller.is_some(),
    ];
    let complete = (!coeffs || spec.den.is_some())
        && (!matrices || (spec.a.is_some() && spec.b.is_some() && spec.c.is_some()));
    if kinds.iter().filter(|&&k| k).count() != 1 || !complete {
        return Err(LtiError::invalid(format!(
            "{what} needs exactly one of: `den` (with an optional `num`), `a`, `b`, `c` (with an \
             optional `d`), `plant` (a plant file) or `controller` (e.g. \"pid:kp=2,ki=1\")"
        )));
    }
    if let Some(den) = &spec.den {
        let values = |c: Vec<super::Coefficient>| c.iter().map(|x| x.value).collect::<Vec<_>>();
        let den = values(den.coefficients("`den`")?);
        let num = match &spec.num {
            Some(n) => values(n.coefficients("`num`")?),
            None => vec![1.0],
        };
        let g = TransferFunction::from_descending(&num, &den)?.with_domain(domain);
        return state_space_of(&Model::Tf(g), &what);
    }
    if let (Some(a), Some(b), Some(c)) = (&spec.a, &spec.b, &spec.c) {
        let a = a.matrix("`a`")?;
        let b = b.matrix("`b`")?;
        let c = c.matrix("`c`")?;
        let d = match &spec.d {
            Some(d) => d.matrix("`d`")?,
            None => nalgebra::DMatrix::zeros(c.nrows(), b.ncols()),
        };
        let ss = StateSpace::new(a, b, c, d)?;
        ss.check_size()?;
        return Ok(ss.with_domain(domain));
    }
    if let Some(spec) = &spec.controller {
        let c = Controller::parse(spec)?;
        let g = c.tf()?;
        let g = match domain.dt() {
            Some(_) if c.is_given_in_loop_variable() => g.with_domain(domain),
            Some(dt) => g.c2d(dt, c.method())?,
            None => g,
        };
        return state_space_of(&Model::Tf(g), &what);
    }
    let file = spec.plant.as_deref().unwrap_or_default();
    let full = path.parent().unwrap_or(Path::new("")).join(file);
    let plant = Plant::from_file_at_depth(&full, depth + 1)?;
    if plant.controller.is_some() {
        return Err(LtiError::invalid(format!(
            "{what}: the plant file {} has a [controller] section; make the controller a block \
             of the diagram",
            abbreviate(file)
        )));
    }
    state_space_of(&plant.model, &what)
}
