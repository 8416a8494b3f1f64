//! Markdown tables for the reports (numbers are formatted by `tvf_figures::numbers`).

/// A Markdown table: a header row and data rows of already formatted cells.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Table {
    /// Column titles.
    pub header: Vec<String>,
    /// Column alignment: `true` for right-aligned (numbers).
    pub right_aligned: Vec<bool>,
    /// Rows, each as long as the header.
    pub rows: Vec<Vec<String>>,
}

impl Table {
    /// A table with these column titles; columns after the first are right-aligned.
    pub fn new<S: Into<String>>(header: impl IntoIterator<Item = S>) -> Self {
        let header: Vec<String> = header.into_iter().map(Into::into).collect();
        let right_aligned = (0..header.len()).map(|i| i > 0).collect();
        Self {
            header,
            right_aligned,
            rows: Vec::new(),
        }
    }

    /// Appends a row (short rows are padded with empty cells).
    pub fn row<S: Into<String>>(&mut self, cells: impl IntoIterator<Item = S>) {
        let mut row: Vec<String> = cells.into_iter().map(Into::into).collect();
        row.resize(self.header.len(), String::new());
        self.rows.push(row);
    }

    /// The table as GitHub-flavoured Markdown (ends with a newline).
    pub fn to_markdown(&self) -> String {
        let escape = |s: &str| s.replace('|', "\\|");
        let line = |cells: &[String]| {
            let inner: Vec<String> = cells.iter().map(|c| escape(c)).collect();
            format!("| {} |\n", inner.join(" | "))
        };
        let mut out = line(&self.header);
        let rule: Vec<String> = self
            .right_aligned
            .iter()
            .map(|&r| if r { "---:" } else { "---" }.to_string())
            .collect();
        out.push_str(&format!("|{}|\n", rule.join("|")));
        for row in &self.rows {
            out.push_str(&line(row));
        }
        out
    }
}
