//! The state of a demo run that every section shares: where the files go, the figures
//! written, the checks recorded, the progress line; and the report's plot options.

use std::path::PathBuf;

use super::verify::Checks;

/// Run state: where files go, what was written, the checks, the progress line.
pub struct Ctx {
    pub out: PathBuf,
    pub figures: Vec<String>,
    pub checks: Checks,
    pub(super) step: usize,
    pub(super) steps: usize,
    pub(super) tty: bool,
}

impl Ctx {
    /// Shows "[k/n] what" on stderr when it is a terminal.
    pub(super) fn progress(&mut self, what: &str) {
        self.step += 1;
        if self.tty {
            eprint!("\r\x1b[2K[{}/{}] {what}", self.step, self.steps);
        }
    }

    /// Path of a figure file in the output directory; remembers it for the summary.
    pub fn figure(&mut self, file: &str) -> PathBuf {
        self.figures.push(file.to_string());
        self.out.join(file)
    }
}

/// Plot options for the report's figures.
pub fn fig(title: impl Into<String>) -> crate::plot::PlotOptions {
    crate::plot::PlotOptions {
        size: (1000, 650),
        title: Some(title.into()),
        ..Default::default()
    }
}
