//! `ltikit eval <plant> --s "-1+2j"` (`--z` for a discrete plant): G at one complex point,
//! every channel, through `analysis::point`; at a pole, an error naming it.

use anyhow::Result;
use clap::Args;
use num_complex::Complex64;
use serde::Serialize;

use super::{PlantArgs, UsageError};
use crate::analysis::point::complex_text;
use crate::fmt::fmt_sig;
use crate::lti::Model;

#[derive(Args, Debug)]
pub struct EvalArgs {
    #[command(flatten)]
    pub plant: PlantArgs,
    /// The point s of a continuous-time plant: "-1+2j", "2j", "0.5" (i or j).
    #[arg(long, value_name = "COMPLEX", allow_hyphen_values = true)]
    pub s: Option<String>,
    /// The point z of a discrete-time plant: "0.5-0.5j".
    #[arg(
        long,
        value_name = "COMPLEX",
        allow_hyphen_values = true,
        conflicts_with = "s"
    )]
    pub z: Option<String>,
    /// Print one JSON document: {"variable", "point", "channels": [{"input", "output",
    /// "value", "magnitude", "magnitude_db", "phase_deg"}]}.
    #[arg(long)]
    pub json: bool,
}

/// A complex number typed as `a+bj`, `a-bi`, `bj`, `j`, `a` (spaces allowed).
pub(crate) fn parse_complex(text: &str, flag: &str) -> Result<Complex64> {
    let t: String = text.chars().filter(|c| !c.is_whitespace()).collect();
    let bad = || {
        anyhow::anyhow!(
            "{flag} '{}' is not a complex number (write e.g. -1+2j, 2j or 0.5)",
            crate::error::abbreviate(text)
        )
    };
    let num = |s: &str| -> Result<f64> {
        let v = match s {
            "" | "+" => 1.0,
            "-" => -1.0,
            _ => s.parse::<f64>().map_err(|_| bad())?,
        };
        if v.is_finite() { Ok(v) } else { Err(bad()) }
    };
    if t.is_empty() {
        return Err(bad());
    }
    let Some(body) = t.strip_suffix(['j', 'i']) else {
        let re = t.parse::<f64>().map_err(|_| bad())?;
        return if re.is_finite() {
            Ok(Complex64::new(re, 0.0))
        } else {
            Err(bad())
        };
    };
    // the sign that starts the imaginary part: the last + or − not at the start and not in
    // an exponent
    let bytes = body.as_bytes();
    let split = (1..bytes.len())
        .rev()
        .find(|&k| matches!(bytes[k], b'+' | b'-') && !matches!(bytes[k - 1], b'e' | b'E'));
    match split {
        Some(k) => {
            let re = body[..k].parse::<f64>().map_err(|_| bad())?;
            if !re.is_finite() {
                return Err(bad());
            }
            Ok(Complex64::new(re, num(&body[k..])?))
        }
        None => Ok(Complex64::new(0.0, num(body)?)),
    }
}

#[derive(Serialize)]
struct ChannelValue {
    input: String,
    output: String,
    value: [f64; 2],
    magnitude: f64,
    magnitude_db: f64,
    phase_deg: f64,
}

#[derive(Serialize)]
struct EvalJson {
    variable: &'static str,
    point: [f64; 2],
    channels: Vec<ChannelValue>,
}

pub fn run(a: &EvalArgs) -> Result<()> {
    let plant = a.plant.single()?;
    let discrete = a.plant.sample.is_some() || plant.domain().is_discrete();
    let var = if discrete { "z" } else { "s" };
    let text = match (discrete, &a.s, &a.z) {
        (false, Some(s), None) => s,
        (true, None, Some(z)) => z,
        (false, None, Some(_)) => {
            return Err(UsageError(
                "--z is the point of a discrete-time plant; this one is continuous: give --s"
                    .into(),
            )
            .into());
        }
        (true, Some(_), None) => {
            return Err(UsageError(
                "--s is the point of a continuous-time plant; this one is discrete: give --z"
                    .into(),
            )
            .into());
        }
        _ => {
            return Err(UsageError(format!(
                "eval needs the point: --{var} COMPLEX, e.g. --{var} \"-1+2j\""
            ))
            .into());
        }
    };
    let point = parse_complex(text, &format!("--{var}"))?;
    // a loop, a chosen channel, a Padé approximant or sampling: the one transfer function
    // the options select; otherwise every channel of the model
    let options = plant.selection.is_some()
        || a.plant.channel.is_some()
        || a.plant.pade.is_some()
        || a.plant.sample.is_some()
        || a.plant.minreal.is_some();
    let mut rows = Vec::new();
    if options || plant.model.is_siso() {
        let f = a.plant.factored(&plant)?;
        let g = crate::analysis::point::value_at(&f, point)?;
        let (i, o) = a.plant.channel()?.unwrap_or((0, 0));
        rows.push((
            plant.signals.inputs.get(i).cloned().unwrap_or_default(),
            plant.signals.outputs.get(o).cloned().unwrap_or_default(),
            g,
        ));
    } else {
        let (m, p) = plant.model.dims();
        crate::limits::CHANNELS.check("`channel` (all channels at once)", (m * p) as u128)?;
        let values = crate::analysis::point::transfer_matrix(&plant.model, point)?;
        for (o, row) in values.iter().enumerate() {
            for (i, g) in row.iter().enumerate() {
                rows.push((
                    plant.signals.inputs[i].clone(),
                    plant.signals.outputs[o].clone(),
                    *g,
                ));
            }
        }
    }
    let channels: Vec<ChannelValue> = rows
        .into_iter()
        .map(|(input, output, g)| ChannelValue {
            input,
            output,
            value: super::output::pair(g),
            magnitude: g.norm(),
            magnitude_db: 20.0 * g.norm().log10(),
            phase_deg: g.arg().to_degrees(),
        })
        .collect();
    if a.json {
        return super::output::print_json(&EvalJson {
            variable: var,
            point: super::output::pair(point),
            channels,
        });
    }
    let mut s = format!(
        "{}\nG({var}) at {var} = {}\n",
        plant.name,
        complex_text(point)
    );
    let mimo = !matches!(plant.model, Model::Tf(_)) && !plant.model.is_siso() && !options;
    for c in &channels {
        let g = Complex64::new(c.value[0], c.value[1]);
        let label = if mimo {
            format!("  {} → {}: ", c.input, c.output)
        } else {
            "  ".to_string()
        };
        s.push_str(&format!(
            "{label}{}   |G| = {} ({} dB), phase {}°\n",
            complex_text(g),
            fmt_sig(c.magnitude, 10),
            fmt_sig(c.magnitude_db, 6),
            fmt_sig(c.phase_deg, 6)
        ));
    }
    super::output::print(&s)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn complex_text() {
        let p = |t: &str| parse_complex(t, "--s").unwrap();
        assert_eq!(p("-1+2j"), Complex64::new(-1.0, 2.0));
        assert_eq!(p("1 - 2i"), Complex64::new(1.0, -2.0));
        assert_eq!(p("2j"), Complex64::new(0.0, 2.0));
        assert_eq!(p("-j"), Complex64::new(0.0, -1.0));
        assert_eq!(p("0.5"), Complex64::new(0.5, 0.0));
        assert_eq!(p("1e-3+2e-1j"), Complex64::new(1e-3, 0.2));
        for bad in ["", "x", "1+2k", "nan", "1+infj", "--1j", "1+2jj"] {
            assert!(parse_complex(bad, "--s").is_err(), "{bad}");
        }
    }
}
