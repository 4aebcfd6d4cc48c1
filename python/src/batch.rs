//! `ltikit.batch`: many models analysed on all cores with the GIL released — what
//! `ltikit analyze --batch` writes per line (the `analyze` contract plus `margins`).

use pyo3::prelude::*;
use pyo3::types::PyList;
use rayon::prelude::*;
use serde_json::{Value, json};

use crate::analyze::analysis_json;
use crate::model::Model;

/// One model's record: the analysis and its margins (`null` with `margins_note` when they
/// cannot be computed), or `{"error": …}`.
fn record(m: &Model) -> Value {
    let result = crate::attempt(|| {
        let f = m.factored_or_message().map_err(ltikit::LtiError::invalid)?;
        let mut v = analysis_json(&f.analyze()?);
        if let Value::Object(map) = &mut v {
            // margins that cannot be computed do not take the analysis down
            match f.margins() {
                Ok(mg) => {
                    let mv = serde_json::to_value(&mg)
                        .map_err(|e| ltikit::LtiError::invalid(e.to_string()))?;
                    map.insert("margins".into(), mv);
                }
                Err(e) => {
                    map.insert("margins".into(), Value::Null);
                    map.insert("margins_note".into(), json!(format!("not computed: {e}")));
                }
            }
        }
        Ok(v)
    });
    result.unwrap_or_else(|e| json!({ "error": e }))
}

/// Analyses `models` on all cores (the GIL released while they are computed and written):
/// one JSON document per model, in order — the `analyze` document plus `margins`, or
/// `{"error": "…"}` — as text, which `ltikit.Analysis` reads when a field is first asked for.
#[pyfunction]
pub fn batch<'py>(py: Python<'py>, models: Vec<PyRef<'py, Model>>) -> PyResult<Bound<'py, PyList>> {
    let refs: Vec<&Model> = models.iter().map(|m| &**m).collect();
    let docs: Vec<String> = py.detach(|| {
        refs.par_iter()
            .map(|m| {
                serde_json::to_string(&record(m))
                    .unwrap_or_else(|e| json!({ "error": e.to_string() }).to_string())
            })
            .collect()
    });
    PyList::new(py, docs)
}
