//! The demo's web page: sections of pictures, number tables and step times, written as one
//! self-contained `index.html` (inline CSS, pictures referenced by relative file name).

use crate::error::FigureError;
use crate::finding::Finding;
use std::fmt::Write as _;
use std::io::Write as _;
use std::path::Path;
use tvf_core::io::write_atomically;

/// Escapes text for HTML.
pub fn escape(text: &str) -> String {
    text.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// One picture of a section.
pub struct Figure {
    /// File name of the PNG inside the output folder.
    pub file: String,
    /// Caption.
    pub caption: String,
}

/// One section of the page (one demo step).
pub struct Section {
    /// Heading.
    pub title: String,
    /// Paragraph under the heading (plain text).
    pub text: String,
    /// Pictures.
    pub figures: Vec<Figure>,
    /// Name–value rows.
    pub numbers: Vec<(String, String)>,
    /// Wall-clock seconds of the step.
    pub seconds: f64,
}

impl Section {
    /// An empty section.
    pub fn new(title: impl Into<String>, text: impl Into<String>) -> Self {
        Section {
            title: title.into(),
            text: text.into(),
            figures: Vec::new(),
            numbers: Vec::new(),
            seconds: 0.0,
        }
    }

    /// Adds a picture.
    pub fn figure(&mut self, file: impl Into<String>, caption: impl Into<String>) {
        self.figures.push(Figure {
            file: file.into(),
            caption: caption.into(),
        });
    }

    /// The section showing a reproduced figure of papers/: its pictures (captioned with its
    /// title), its numbers, and what the paper reports beside how this run compares.
    pub fn from_finding(finding: &Finding) -> Self {
        let mut section = Section::new(
            format!("{} ({})", finding.title, finding.id),
            format!(
                "The paper: {} This run: {}",
                finding.paper, finding.comparison
            ),
        );
        for file in &finding.files {
            section.figure(file.clone(), format!("{}: {}", finding.id, finding.title));
        }
        section.numbers.extend(finding.numbers.iter().cloned());
        section
    }

    /// Adds a row of numbers.
    pub fn number(&mut self, name: impl Into<String>, value: impl Into<String>) {
        self.numbers.push((name.into(), value.into()));
    }
}

const STYLE: &str = "body{font-family:system-ui,sans-serif;max-width:1100px;margin:2em auto;\
padding:0 1em;color:#222;line-height:1.45}h1{margin-bottom:.2em}h2{border-bottom:1px solid #ccc;\
padding-bottom:.2em;margin-top:2em}figure{display:inline-block;margin:.5em;vertical-align:top;\
max-width:100%}figure img{max-width:100%;border:1px solid #ddd}figcaption{font-size:.9em;color:#555;\
max-width:800px}table{border-collapse:collapse;margin:.6em 0}td,th{border:1px solid #ddd;\
padding:.2em .6em;text-align:left;font-variant-numeric:tabular-nums}.time{color:#777;font-size:.9em}";

/// Renders the page: a header with `intro`, the step-time table, and every section.
pub fn html(title: &str, intro: &[(String, String)], sections: &[Section], total: f64) -> String {
    let mut out = String::new();
    let _ = write!(
        out,
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>{}</title>\n\
         <style>{STYLE}</style>\n</head>\n<body>\n<h1>{}</h1>\n",
        escape(title),
        escape(title)
    );
    out.push_str("<table>\n");
    for (name, value) in intro {
        let _ = writeln!(
            out,
            "<tr><th>{}</th><td>{}</td></tr>",
            escape(name),
            escape(value)
        );
    }
    out.push_str("</table>\n<h2>Steps and times</h2>\n<table id=\"steps\">\n<tr><th>step</th><th>seconds</th></tr>\n");
    for s in sections {
        let _ = writeln!(
            out,
            "<tr><td>{}</td><td>{:.2}</td></tr>",
            escape(&s.title),
            s.seconds
        );
    }
    let _ = writeln!(out, "<tr><th>total</th><th>{total:.2}</th></tr>\n</table>");
    for s in sections {
        let _ = write!(
            out,
            "<section>\n<h2>{}</h2>\n<p>{}</p>\n<p class=\"time\">step time: {:.2} s</p>\n",
            escape(&s.title),
            escape(&s.text),
            s.seconds
        );
        for f in &s.figures {
            let _ = writeln!(
                out,
                "<figure><img src=\"{}\" alt=\"{}\"><figcaption>{}</figcaption></figure>",
                escape(&f.file),
                escape(&f.caption),
                escape(&f.caption)
            );
        }
        if !s.numbers.is_empty() {
            out.push_str("<table>\n");
            for (name, value) in &s.numbers {
                let _ = writeln!(
                    out,
                    "<tr><td>{}</td><td>{}</td></tr>",
                    escape(name),
                    escape(value)
                );
            }
            out.push_str("</table>\n");
        }
        out.push_str("</section>\n");
    }
    out.push_str("</body>\n</html>\n");
    out
}

/// Writes the page to `dir/index.html` atomically.
pub fn write_page(dir: &Path, page: &str) -> Result<(), FigureError> {
    let path = dir.join("index.html");
    write_atomically(&path, |w| w.write_all(page.as_bytes()))
        .map_err(|source| FigureError::Write { path, source })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_page_lists_steps_figures_and_escapes_text() {
        let mut section = Section::new("Filter <low-pass>", "a & b");
        section.figure("noisy.png", "noisy \"field\"");
        section.number("error", "0.1");
        section.seconds = 1.5;
        let page = html(
            "tvf demo",
            &[("mesh".into(), "torus".into())],
            &[section],
            2.0,
        );
        assert!(page.contains("<img src=\"noisy.png\""));
        assert!(page.contains("Filter &lt;low-pass&gt;"));
        assert!(page.contains("a &amp; b"));
        assert!(page.contains("<td>1.50</td>"));
        assert!(page.contains("<th>2.00</th>"));
    }
}
