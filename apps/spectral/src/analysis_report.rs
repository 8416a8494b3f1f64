//! A field's spectral analysis as `tvf analyze` reports it ([`AnalysisReport`]): its energy, how
//! the energy splits over the families of the basis and over the exact Hodge decomposition, as
//! JSON (the content of `energy.json`) or as text lines.

use crate::analysis::{EnergySplit, SpectralAnalysis};
use serde_json::{json, Value};
use std::fmt::Write as _;
use std::path::Path;

impl EnergySplit {
    /// The split as JSON: `integrable`, `cointegrable`, `harmonic`, `rest` and `total`.
    pub fn to_json(&self) -> Value {
        json!({
            "integrable": self.integrable,
            "cointegrable": self.cointegrable,
            "harmonic": self.harmonic,
            "rest": self.rest,
            "total": self.total(),
        })
    }
}

/// The analysis of one field, with what it was made of.
#[derive(Debug, Clone, Copy)]
pub struct AnalysisReport<'a> {
    /// The mesh, as named to the user (a path, or `example:NAME`).
    pub mesh: &'a str,
    /// The field file.
    pub field: &'a Path,
    /// The catalog id of the discretization.
    pub discretization: &'a str,
    /// Fields of the basis the analysis was made in.
    pub basis_fields: usize,
    /// The analysis in the basis.
    pub analysis: &'a SpectralAnalysis,
    /// The energies of the exact Hodge decomposition of the field (`rest` 0).
    pub hodge: &'a EnergySplit,
}

impl AnalysisReport<'_> {
    /// The report as JSON: `mesh`, `field`, `discretization`, `basis_fields`, `field_energy`,
    /// `relative_rest_norm`, `represented_dirichlet_energy`, `basis` (the split in the basis)
    /// and `hodge` (the exact split), each split as [`EnergySplit::to_json`].
    pub fn to_json(&self) -> Value {
        let analysis = self.analysis;
        json!({
            "mesh": self.mesh,
            "field": self.field.display().to_string(),
            "discretization": self.discretization,
            "basis_fields": self.basis_fields,
            "field_energy": analysis.field_energy,
            "relative_rest_norm": analysis.relative_rest_norm(),
            "represented_dirichlet_energy": analysis.represented_dirichlet_energy,
            "basis": analysis.energy.to_json(),
            "hodge": self.hodge.to_json(),
        })
    }

    /// The energies as aligned text lines, each ending in a newline: the field's, its split in
    /// the basis and its exact Hodge split.
    pub fn text(&self) -> String {
        let (e, x) = (&self.analysis.energy, self.hodge);
        let mut text = String::new();
        let _ = writeln!(
            text,
            "field energy ‖v‖²     {:.6e}",
            self.analysis.field_energy
        );
        let _ = writeln!(
            text,
            "in the basis          integrable {:.6e}, co-integrable {:.6e}, harmonic {:.6e}, \
             rest {:.6e}",
            e.integrable, e.cointegrable, e.harmonic, e.rest
        );
        let _ = writeln!(
            text,
            "Hodge decomposition   integrable {:.6e}, co-integrable {:.6e}, harmonic {:.6e}",
            x.integrable, x.cointegrable, x.harmonic
        );
        text
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{compute_basis, BasisRequest};
    use tvf_discretizations::DEFAULT_DISCRETIZATION;

    #[test]
    fn the_report_holds_both_splits_and_three_lines() {
        let (_, complex) = crate::test_torus::torus_complex(DEFAULT_DISCRETIZATION);
        let basis = compute_basis(complex.as_ref(), &BasisRequest::fields(6)).unwrap();
        let field: Vec<f64> = (0..basis.field_dimension())
            .map(|i| 2.0 * basis.fields()[(i, 0)])
            .collect();
        let analysis = SpectralAnalysis::new(&basis, &field).unwrap();
        let hodge = EnergySplit {
            harmonic: 4.0,
            ..EnergySplit::default()
        };
        let report = AnalysisReport {
            mesh: "example:torus",
            field: Path::new("f.npy"),
            discretization: DEFAULT_DISCRETIZATION,
            basis_fields: basis.len(),
            analysis: &analysis,
            hodge: &hodge,
        };
        let json = report.to_json();
        // Twice the first (harmonic) basis field: energy 4, all of it harmonic.
        assert!((json["field_energy"].as_f64().unwrap() - 4.0).abs() < 1e-9);
        assert!((json["basis"]["harmonic"].as_f64().unwrap() - 4.0).abs() < 1e-9);
        assert_eq!(json["hodge"]["total"], 4.0);
        assert_eq!(json["field"], "f.npy");
        let text = report.text();
        assert_eq!(text.lines().count(), 3);
        assert!(text.starts_with("field energy ‖v‖²     4.0"), "{text}");
    }
}
