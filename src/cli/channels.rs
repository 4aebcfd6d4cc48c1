//! The channels of a plant a command analyses: the plant itself when it is SISO, the channel
//! chosen with `--channel`, or — for a MIMO plant without `--channel` — every channel
//! input i → output j, each factored once. The text reports give one block per channel headed
//! "input u1 → output y2" (the plant's signal names, with their units); the JSON documents
//! wrap the SISO document of each channel (see docs/ARCHITECTURE.md, "MIMO plants").

use anyhow::Result;
use serde::Serialize;

use super::PlantArgs;
use crate::analysis::Factored;
use crate::lti::{Model, Plant};

pub use crate::limits::MAX_CHANNELS;

/// One SISO channel of a plant, factored.
pub struct Channel {
    /// Input index (0-based).
    pub input: usize,
    /// Output index (0-based).
    pub output: usize,
    /// Its factored form.
    pub factored: Factored,
}

/// The channels of a plant to analyse.
pub struct Channels {
    /// True when every channel of a MIMO plant is analysed (the per-channel report and JSON);
    /// false for a SISO plant or a chosen channel (the SISO report and JSON, as before).
    pub per_channel: bool,
    /// The channels, inputs outer, outputs inner.
    pub list: Vec<Channel>,
}

impl PlantArgs {
    /// The channels of `plant` to analyse (see `Channels`).
    pub fn channels(&self, plant: &Plant) -> Result<Channels> {
        if plant.selection.is_some() {
            // A loop with a controller: one SISO system (the chosen channel of a MIMO plant).
            let (input, output) = self.channel()?.unwrap_or((0, 0));
            return Ok(Channels {
                per_channel: false,
                list: vec![Channel {
                    input,
                    output,
                    factored: self.factored(plant)?,
                }],
            });
        }
        if let Some((i, o)) = self.channel()? {
            return Ok(Channels {
                per_channel: false,
                list: vec![Channel {
                    input: i,
                    output: o,
                    factored: self.minreal(self.pade_of(plant.factored_channel(i, o)?)?)?,
                }],
            });
        }
        let (m, p) = plant.model.dims();
        if m == 1 && p == 1 {
            return Ok(Channels {
                per_channel: false,
                list: vec![Channel {
                    input: 0,
                    output: 0,
                    factored: self.minreal(self.pade_of(plant.factored()?)?)?,
                }],
            });
        }
        if m * p > MAX_CHANNELS {
            anyhow::bail!(
                "the plant has {m} inputs and {p} outputs ({} channels, at most {MAX_CHANNELS} \
                 are analysed at once): choose one with --channel INPUT,OUTPUT",
                m * p
            );
        }
        let mut list = Vec::with_capacity(m * p);
        for i in 0..m {
            for o in 0..p {
                list.push(Channel {
                    input: i,
                    output: o,
                    factored: self.minreal(self.pade_of(plant.factored_channel(i, o)?)?)?,
                });
            }
        }
        Ok(Channels {
            per_channel: true,
            list,
        })
    }
}

/// "input u1 → output y2" with the plant's signal names.
pub fn heading(plant: &Plant, input: usize, output: usize) -> String {
    format!(
        "input {} → output {}",
        name_of(&plant.signals.inputs, input, "u"),
        name_of(&plant.signals.outputs, output, "y")
    )
}

fn name_of(names: &[String], k: usize, stem: &str) -> String {
    names
        .get(k)
        .cloned()
        .unwrap_or_else(|| format!("{stem}{}", k + 1))
}

/// The text header of a per-channel report: the plant, its size and signal names.
pub fn plant_header(plant: &Plant) -> String {
    let (m, p) = plant.model.dims();
    let mut s = format!("{}\n", plant.name);
    if let Some(d) = &plant.description {
        s.push_str(&format!("  {d}\n"));
    }
    let count = |k: usize, what: &str| format!("{k} {what}{}", if k == 1 { "" } else { "s" });
    s.push_str(&format!(
        "  state space: {}, {}, {}\n",
        count(plant.model.order(), "state"),
        count(m, "input"),
        count(p, "output")
    ));
    s.push_str(&format!("  inputs:  {}\n", plant.signals.inputs.join(", ")));
    s.push_str(&format!(
        "  outputs: {}\n",
        plant.signals.outputs.join(", ")
    ));
    if !plant.signals.states.is_empty() {
        s.push_str(&format!(
            "  states:  {}\n",
            abbreviated_list(&plant.signals.states)
        ));
    }
    s
}

/// Names joined with ", ", the middle left out beyond 12.
fn abbreviated_list(v: &[String]) -> String {
    if v.len() <= 12 {
        return v.join(", ");
    }
    format!("{}, … , {}", v[..6].join(", "), v[v.len() - 3..].join(", "))
}

/// The block heading of one channel in a per-channel text report.
pub fn block_heading(plant: &Plant, ch: &Channel) -> String {
    let h = heading(plant, ch.input, ch.output);
    format!(
        "\n── {h} {}\n",
        "─".repeat(60usize.saturating_sub(h.chars().count()))
    )
}

/// The per-channel JSON document: `{"model": "state-space", "name", "states", "inputs",
/// "outputs", "channels": [{"input": 1, "output": 2, "input_name", "output_name", …the SISO
/// document…}]}` (indices 1-based).
pub fn mimo_json<T: Serialize>(plant: &Plant, docs: &[(usize, usize, T)]) -> Result<MimoJson> {
    let mut channels = Vec::with_capacity(docs.len());
    for (i, o, doc) in docs {
        let mut map = serde_json::Map::new();
        map.insert("input".into(), (*i + 1).into());
        map.insert("output".into(), (*o + 1).into());
        map.insert(
            "input_name".into(),
            name_of(&plant.signals.inputs, *i, "u").into(),
        );
        map.insert(
            "output_name".into(),
            name_of(&plant.signals.outputs, *o, "y").into(),
        );
        match serde_json::to_value(doc)? {
            serde_json::Value::Object(rest) => map.extend(rest),
            other => {
                map.insert("value".into(), other);
            }
        }
        channels.push(serde_json::Value::Object(map));
    }
    Ok(MimoJson {
        model: match plant.model {
            Model::Ss(_) => "state-space",
            Model::Tf(_) => "transfer-function",
        },
        name: plant.name.clone(),
        states: plant.model.order(),
        inputs: plant.signals.inputs.clone(),
        outputs: plant.signals.outputs.clone(),
        whole_model: None,
        channels,
    })
}

/// The per-channel JSON contract (see [`mimo_json`]).
#[derive(Serialize)]
pub struct MimoJson {
    model: &'static str,
    name: String,
    states: usize,
    inputs: Vec<String>,
    outputs: Vec<String>,
    /// `analyze` on a state-space plant: `"state_space"` and `"state_space_note"` before the
    /// channels (see `with_whole_model`); absent for the other commands.
    #[serde(flatten, skip_serializing_if = "Option::is_none")]
    whole_model: Option<serde_json::Value>,
    channels: Vec<serde_json::Value>,
}

impl MimoJson {
    /// The document with the whole-model keys of `analyze` (an object whose keys are put
    /// before `"channels"`; `None` leaves the document as it was).
    pub fn with_whole_model<T: Serialize>(mut self, w: Option<T>) -> Result<MimoJson> {
        self.whole_model = w.map(serde_json::to_value).transpose()?;
        Ok(self)
    }
}

/// Runs a SISO analysis on every channel and prints it: `doc` computes a channel's result
/// (its JSON document), `text` writes it. A SISO plant or a chosen channel prints as before
/// ("G(s) = …", a blank line, the text; or the document itself).
pub fn print_each<T: Serialize>(
    plant: &Plant,
    chans: &Channels,
    json: bool,
    doc: impl Fn(&Factored) -> crate::Result<T>,
    text: impl Fn(&T) -> String,
) -> Result<()> {
    use super::output::{print, print_json};
    if !chans.per_channel {
        let Some(ch) = chans.list.first() else {
            anyhow::bail!("no channel to analyse");
        };
        let d = doc(&ch.factored)?;
        return if json {
            print_json(&d)
        } else {
            print(&format!(
                "{}\n\n{}",
                super::text::g_text(plant, &ch.factored),
                text(&d)
            ))
        };
    }
    let mut docs = Vec::with_capacity(chans.list.len());
    let mut out = plant_header(plant);
    for ch in &chans.list {
        let d = doc(&ch.factored)?;
        if !json {
            out.push_str(&block_heading(plant, ch));
            out.push_str(&format!(
                "{}\n\n{}",
                super::text::channel_g_text(&ch.factored),
                text(&d)
            ));
        }
        docs.push((ch.input, ch.output, d));
    }
    if json {
        print_json(&mimo_json(plant, &docs)?)
    } else {
        print(&out)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_channel_of_a_mimo_plant_in_order() {
        let p = Plant::from_json_line(
            r#"{"a": "-1 0; 0 -2", "b": [[1, 0], [0, 1]], "c": [[1, 1]], "outputs": ["sum [m]"]}"#,
        )
        .unwrap();
        let args = PlantArgs::default();
        let ch = args.channels(&p).unwrap();
        assert!(ch.per_channel);
        let idx: Vec<_> = ch.list.iter().map(|c| (c.input, c.output)).collect();
        assert_eq!(idx, vec![(0, 0), (1, 0)]);
        assert_eq!(heading(&p, 1, 0), "input u2 → output sum [m]");
        // 1/(s + 2): the dc gain of the second channel.
        assert!((ch.list[1].factored.dc_gain().unwrap() - 0.5).abs() < 1e-14);
        let chosen = PlantArgs {
            channel: Some("2,1".into()),
            ..Default::default()
        };
        let one = chosen.channels(&p).unwrap();
        assert!(!one.per_channel && one.list.len() == 1 && one.list[0].input == 1);
        let json = mimo_json(&p, &[(1, 0, serde_json::json!({"x": 1}))]).unwrap();
        let v = serde_json::to_value(&json).unwrap();
        assert_eq!(v["channels"][0]["input"], 2);
        assert_eq!(v["channels"][0]["x"], 1);
        assert_eq!(v["outputs"][0], "sum [m]");
    }
}
