//! Markdown tables and number formatting for the reports.

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

/// A duration in the unit that suits it: `850 µs`, `12.3 ms`, `4.56 s`, `123 s`.
pub fn seconds(value: f64) -> String {
    if !value.is_finite() {
        "–".to_string()
    } else if value < 1e-3 {
        format!("{:.0} µs", value * 1e6)
    } else if value < 0.1 {
        format!("{:.2} ms", value * 1e3)
    } else if value < 1.0 {
        format!("{:.0} ms", value * 1e3)
    } else if value < 100.0 {
        format!("{value:.2} s")
    } else {
        format!("{value:.0} s")
    }
}

/// `paper / ours` as `×1.23`, or `–` when either is missing.
pub fn ratio(paper: Option<f64>, ours: Option<f64>) -> String {
    match (paper, ours) {
        (Some(p), Some(o)) if o > 0.0 && p.is_finite() => {
            let r = p / o;
            if r >= 100.0 {
                format!("×{r:.0}")
            } else if r >= 10.0 {
                format!("×{r:.1}")
            } else {
                format!("×{r:.2}")
            }
        }
        _ => "–".to_string(),
    }
}

/// An integer with thousands separators: `69,666`.
pub fn thousands(value: usize) -> String {
    let digits = value.to_string();
    let mut out = String::new();
    for (i, c) in digits.chars().enumerate() {
        if i > 0 && (digits.len() - i).is_multiple_of(3) {
            out.push(',');
        }
        out.push(c);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tables_render_with_alignment_and_padding() {
        let mut table = Table::new(["mesh", "time"]);
        table.row(["a|b", "1 s"]);
        table.row(["c"]);
        let text = table.to_markdown();
        assert_eq!(
            text,
            "| mesh | time |\n|---|---:|\n| a\\|b | 1 s |\n| c |  |\n"
        );
    }

    #[test]
    fn numbers_are_formatted_for_reading() {
        assert_eq!(seconds(0.0005), "500 µs");
        assert_eq!(seconds(0.0123), "12.30 ms");
        assert_eq!(seconds(4.561), "4.56 s");
        assert_eq!(seconds(1246.0), "1246 s");
        assert_eq!(ratio(Some(23.0), Some(11.5)), "×2.00");
        assert_eq!(ratio(None, Some(1.0)), "–");
        assert_eq!(thousands(69666), "69,666");
        assert_eq!(thousands(331904), "331,904");
        assert_eq!(thousands(12), "12");
    }
}
