//! What a subcommand prints on stdout: aligned text lines for people, or (with `--json`) one
//! JSON object for programs. Commands add each number once, with its text line and its key:
//!
//! ```text
//! let mut report = Report::new(args.json);
//! report.line(format!("spline setup    {setup_ms:.3} ms"));
//! report.set("setup_ms", setup_ms);
//! report.finish()?; // prints the JSON object when --json was given
//! ```

use anyhow::Result;
use serde::Serialize;
use serde_json::{Map, Value};

/// The stdout report of one subcommand.
pub struct Report {
    json: bool,
    values: Map<String, Value>,
}

impl Report {
    /// A report printed as text, or collected and printed as JSON by [`Report::finish`].
    pub fn new(json: bool) -> Self {
        Report {
            json,
            values: Map::new(),
        }
    }

    /// Prints `text` now, unless the report is JSON.
    pub fn line(&self, text: impl AsRef<str>) {
        if !self.json {
            println!("{}", text.as_ref());
        }
    }

    /// Prints `lines` now (unless the report is JSON) and records every key of `keys`, a value
    /// that serializes as a JSON object: a report part of a library, such as
    /// `tvf_design::ResidualReport`, with its text lines.
    pub fn add(&mut self, lines: Vec<String>, keys: impl Serialize) {
        lines.iter().for_each(|line| self.line(line));
        if let Ok(Value::Object(keys)) = serde_json::to_value(keys) {
            self.values.extend(keys);
        }
    }

    /// Records `value` under `key` for the JSON report.
    pub fn set(&mut self, key: &str, value: impl Serialize) {
        let value = serde_json::to_value(value).unwrap_or(Value::Null);
        self.values.insert(key.to_string(), value);
    }

    /// Prints the JSON object (with `--json`); nothing otherwise.
    pub fn finish(self) -> Result<()> {
        if self.json {
            println!(
                "{}",
                serde_json::to_string_pretty(&Value::Object(self.values))?
            );
        }
        Ok(())
    }
}
