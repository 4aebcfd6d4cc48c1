//! A small Markdown writer for the demo report.

/// Markdown text under construction.
#[derive(Default)]
pub struct Md {
    s: String,
}

impl Md {
    pub fn h1(&mut self, t: &str) {
        self.s.push_str(&format!("# {t}\n\n"));
    }
    pub fn h2(&mut self, t: &str) {
        self.s.push_str(&format!("## {t}\n\n"));
    }
    pub fn h3(&mut self, t: &str) {
        self.s.push_str(&format!("### {t}\n\n"));
    }
    /// A paragraph.
    pub fn p(&mut self, t: &str) {
        self.s.push_str(t.trim_end());
        self.s.push_str("\n\n");
    }
    /// A bullet list.
    pub fn bullets<S: AsRef<str>>(&mut self, items: &[S]) {
        for i in items {
            self.s.push_str(&format!("- {}\n", i.as_ref()));
        }
        self.s.push('\n');
    }
    /// A fenced block (formulas are shown as code so that every character survives).
    pub fn code(&mut self, t: &str) {
        self.s.push_str("```text\n");
        self.s.push_str(t.trim_end());
        self.s.push_str("\n```\n\n");
    }
    /// A table.
    pub fn table<S: AsRef<str>>(&mut self, header: &[&str], rows: &[Vec<S>]) {
        self.s.push_str(&format!("| {} |\n", header.join(" | ")));
        self.s.push_str(&format!(
            "|{}|\n",
            header.iter().map(|_| "---").collect::<Vec<_>>().join("|")
        ));
        for r in rows {
            let cells: Vec<String> = r.iter().map(|c| c.as_ref().replace('|', "\\|")).collect();
            self.s.push_str(&format!("| {} |\n", cells.join(" | ")));
        }
        self.s.push('\n');
    }
    /// An image with a relative link.
    pub fn image(&mut self, alt: &str, file: &str) {
        self.s.push_str(&format!("![{alt}]({file})\n\n"));
    }
    pub fn into_string(self) -> String {
        self.s
    }
}
