//! A convergence study ([`crate::study`]) as text: one Markdown table row per
//! discretization, surface and level (errors of both families, the local order against the
//! previous level, the basis time) and one line per fitted order. `tvf convergence` prints it and
//! `papers/` writes it into its report.

use crate::study::{ConvergenceReport, LevelRow, Surface};
use tvf_spectral::FieldFamily;

/// `sphere`, `hemisphere (tangential)`, `hemisphere (normal)`.
pub fn surface_label(surface: Surface) -> String {
    match surface.boundary() {
        None => surface.name().to_string(),
        Some(b) => format!("{} ({})", surface.name(), b.name()),
    }
}

/// The local order of `family` between `previous` and `row`:
/// `log(e_prev / e) / log(h_prev / h)`.
pub fn local_order(previous: &LevelRow, row: &LevelRow, family: FieldFamily) -> f64 {
    (previous.error(family) / row.error(family)).ln() / (previous.h / row.h).ln()
}

/// The rows of `report` as a Markdown table with aligned columns.
pub fn markdown_table(report: &ConvergenceReport) -> String {
    let header = [
        "discretization",
        "surface",
        "level",
        "faces",
        "h",
        "integrable error",
        "order",
        "co-integrable error",
        "order",
        "basis time",
    ];
    let mut cells: Vec<Vec<String>> = vec![header.iter().map(|s| s.to_string()).collect()];
    let mut previous: Option<&LevelRow> = None;
    for row in &report.rows {
        let before =
            previous.filter(|p| p.discretization == row.discretization && p.surface == row.surface);
        let order = |family| {
            before.map_or("–".to_string(), |p| {
                format!("{:.2}", local_order(p, row, family))
            })
        };
        cells.push(vec![
            row.discretization.clone(),
            surface_label(row.surface),
            row.level.to_string(),
            row.faces.to_string(),
            format!("{:.4}", row.h),
            format!("{:.3e}", row.integrable_error),
            order(FieldFamily::Integrable),
            format!("{:.3e}", row.cointegrable_error),
            order(FieldFamily::Cointegrable),
            format!("{:.2} s", row.seconds),
        ]);
        previous = Some(row);
    }
    aligned(&cells)
}

/// One line per fitted order: `discretization, surface, family: order` (or why there is none:
/// an order needs two levels with non-zero errors).
pub fn orders_summary(report: &ConvergenceReport) -> String {
    let mut out = String::new();
    for order in &report.orders {
        let value = match order.order.is_finite() {
            true => format!("order {:.2}", order.order),
            false => "no order (it needs two levels or more with non-zero errors)".to_string(),
        };
        out.push_str(&format!(
            "{} on the {}, {}: {value}\n",
            order.discretization,
            surface_label(order.surface),
            order.family.name(),
        ));
    }
    out
}

/// `cells` (the first row the header) as a Markdown table, each column padded to its widest cell.
fn aligned(cells: &[Vec<String>]) -> String {
    let columns = cells.first().map_or(0, Vec::len);
    let widths: Vec<usize> = (0..columns)
        .map(|c| {
            cells
                .iter()
                .map(|r| r[c].chars().count())
                .max()
                .unwrap_or(0)
        })
        .collect();
    let line = |row: &[String]| {
        let padded: Vec<String> = row
            .iter()
            .zip(&widths)
            .map(|(cell, &w)| format!("{cell}{}", " ".repeat(w - cell.chars().count())))
            .collect();
        format!("| {} |\n", padded.join(" | "))
    };
    let mut out = String::new();
    for (i, row) in cells.iter().enumerate() {
        out.push_str(&line(row));
        if i == 0 {
            let rule: Vec<String> = widths.iter().map(|&w| "-".repeat(w)).collect();
            out.push_str(&format!("|-{}-|\n", rule.join("-|-")));
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::study::ObservedOrder;

    fn row(level: u32, h: f64, e: f64) -> LevelRow {
        LevelRow {
            discretization: "x".into(),
            surface: Surface::Sphere,
            level,
            faces: 80 << (2 * level),
            h,
            integrable_error: e,
            cointegrable_error: 2.0 * e,
            seconds: 0.5,
        }
    }

    #[test]
    fn the_table_has_local_orders_and_the_summary_the_fitted_ones() {
        let report = ConvergenceReport {
            rows: vec![row(1, 0.4, 0.16), row(2, 0.2, 0.04)],
            orders: vec![ObservedOrder {
                discretization: "x".into(),
                surface: Surface::Sphere,
                family: FieldFamily::Integrable,
                order: 2.0,
            }],
        };
        let table = markdown_table(&report);
        let lines: Vec<&str> = table.lines().collect();
        assert_eq!(lines.len(), 4, "{table}");
        assert!(lines[2].contains("| –"), "{table}");
        assert_eq!(lines[3].matches("2.00").count(), 2, "{table}");
        assert!(lines
            .iter()
            .all(|l| l.chars().count() == lines[0].chars().count()));
        assert_eq!(
            orders_summary(&report),
            "x on the sphere, integrable: order 2.00\n"
        );
    }

    /// One level fits no order: the summary says so instead of printing "order NaN".
    #[test]
    fn a_single_level_has_no_order_and_says_why() {
        let report = ConvergenceReport {
            rows: vec![row(1, 0.4, 0.16)],
            orders: vec![ObservedOrder {
                discretization: "x".into(),
                surface: Surface::Sphere,
                family: FieldFamily::Integrable,
                order: f64::NAN,
            }],
        };
        let summary = orders_summary(&report);
        assert!(!summary.contains("NaN"), "{summary}");
        assert!(summary.contains("needs two levels"), "{summary}");
    }
}
