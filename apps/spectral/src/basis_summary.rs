//! What is said of a computed basis (`tvf basis`): how many fields of each family
//! ([`FamilyCounts`]), how the computation went ([`BasisReport::notes`]), and the whole summary —
//! counts, eigenvalues, labels, the cost of every phase, the files written — as one line and as
//! JSON ([`BasisSummary`]); its eigenvalues as a table (`tvf spectrum`,
//! [`EigenfunctionBasis::spectrum_table`]).

use crate::basis::FieldFamily;
use crate::compute_basis::BasisReport;
use crate::eigenfunction_basis::EigenfunctionBasis;
use serde_json::{json, Value};
use std::fmt::Write as _;
use std::path::Path;
use tvf_solvers::PhaseStatistics;

/// How many fields of each family a basis holds.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct FamilyCounts {
    /// Harmonic fields (`2g` on a closed mesh).
    pub harmonic: usize,
    /// Integrable (curl-free) eigenfields.
    pub integrable: usize,
    /// Co-integrable (divergence-free) eigenfields.
    pub cointegrable: usize,
}

impl FamilyCounts {
    /// The counts of the family labels `families` (one per basis field).
    pub fn of(families: &[FieldFamily]) -> Self {
        let count = |family| families.iter().filter(|&&f| f == family).count();
        Self {
            harmonic: count(FieldFamily::Harmonic),
            integrable: count(FieldFamily::Integrable),
            cointegrable: count(FieldFamily::Cointegrable),
        }
    }
}

impl BasisReport {
    /// What a person may want to know of the computation besides the counts of the basis
    /// (`kept`), one line each: the eigenpairs computed and the threshold that split the
    /// families (when inertia counts chose it) — computed pairs the basis does not keep (a
    /// cluster straddling its last eigenvalue is computed whole) are said to be dropped, so the
    /// two counts never read as two answers —, and the accuracy of the harmonic fields (when
    /// there are any).
    pub fn notes(&self, kept: FamilyCounts) -> Vec<String> {
        let mut notes = Vec::new();
        if let Some(threshold) = self.split_threshold {
            let dropped = (self.integrable_computed + self.cointegrable_computed)
                .saturating_sub(kept.integrable + kept.cointegrable);
            let keeping = if dropped == 0 {
                "all kept".to_string()
            } else {
                format!(
                    "the basis keeps the lowest {} + {} (the {dropped} above are dropped)",
                    kept.integrable, kept.cointegrable
                )
            };
            notes.push(format!(
                "eigenpairs computed: {} integrable + {} co-integrable, all below λ = \
                 {threshold:.6e} (split counted by {} inertia factorizations in {:.2} s); \
                 {keeping}",
                self.integrable_computed,
                self.cointegrable_computed,
                self.counting_factorizations,
                self.counting_seconds
            ));
        }
        if self.harmonic_dimension > 0 {
            notes.push(format!(
                "harmonic fields: dimension {}, orthonormality error {:.1e}, ‖L Γ‖ ≤ {:.1e}",
                self.harmonic_dimension,
                self.harmonic_orthonormality_error,
                self.harmonic_kernel_residual
            ));
        }
        notes
    }

    /// The cost of every phase, in order: counting (the threshold search; its processor time is
    /// the process's, the harmonic fields being computed beside it), boundaries (inertia
    /// counts at interval boundaries), solving, refinement, and `writing` (the caller's, e.g.
    /// saving the basis).
    pub fn phases(&self, writing: PhaseStatistics) -> [(&'static str, PhaseStatistics); 5] {
        let counting = PhaseStatistics {
            wall_seconds: self.counting_seconds,
            cpu_seconds: self.counting_cpu_seconds,
            factorizations: self.counting_factorizations,
            solves: 0,
        };
        let boundaries = PhaseStatistics {
            factorizations: self.solver.counting.factorizations - self.counting_factorizations,
            ..self.solver.counting
        };
        [
            ("counting", counting),
            ("boundaries", boundaries),
            ("solving", self.solver.solving),
            ("refinement", self.solver.refinement),
            ("writing", writing),
        ]
    }
}

impl EigenfunctionBasis {
    /// The eigenvalues as a table, one line each (every line ends in a newline): a header, then
    /// index, eigenvalue `λ`, frequency `√λ` and family of every field, ascending.
    pub fn spectrum_table(&self) -> String {
        let mut text = format!(
            "{:>6}  {:>22}  {:>14}  family\n",
            "index", "eigenvalue", "frequency"
        );
        for (i, (&lambda, family)) in self.eigenvalues().iter().zip(self.families()).enumerate() {
            let _ = writeln!(
                text,
                "{i:>6}  {lambda:>22.15e}  {:>14.6e}  {}",
                lambda.sqrt(),
                family.name()
            );
        }
        text
    }
}

/// A phase's cost as JSON: wall-clock and processor seconds, busy cores, factorizations, solves.
fn phase_json(statistics: &PhaseStatistics) -> Value {
    json!({
        "seconds": statistics.wall_seconds,
        "cpu_seconds": statistics.cpu_seconds,
        "cores_busy": statistics.utilisation(),
        "factorizations": statistics.factorizations,
        "solves": statistics.solves,
    })
}

/// A computed and saved basis, as `tvf basis` reports it.
#[derive(Debug, Clone, Copy)]
pub struct BasisSummary<'a> {
    /// The mesh, as named to the user (a path, or `example:NAME`).
    pub mesh: &'a str,
    /// The catalog id of the discretization.
    pub discretization: &'a str,
    /// The eigenvalues of the basis fields, ascending.
    pub eigenvalues: &'a [f64],
    /// The family of each basis field.
    pub families: &'a [FieldFamily],
    /// How its computation went.
    pub report: &'a BasisReport,
    /// The cost of saving it.
    pub writing: PhaseStatistics,
    /// The basis file written, if any.
    pub file: Option<&'a Path>,
    /// The folder of numpy arrays written, if any.
    pub arrays: Option<&'a Path>,
}

impl BasisSummary<'_> {
    /// One line: the fields by family, the discretization, the seconds, the outputs.
    pub fn headline(&self) -> String {
        let counts = FamilyCounts::of(self.families);
        let written: Vec<String> = self
            .file
            .iter()
            .chain(&self.arrays)
            .map(|p| p.display().to_string())
            .collect();
        format!(
            "{} fields ({} harmonic, {} integrable, {} co-integrable; {}) in {:.2} s -> {}",
            self.eigenvalues.len(),
            counts.harmonic,
            counts.integrable,
            counts.cointegrable,
            self.discretization,
            self.report.seconds,
            written.join(" and ")
        )
    }

    /// Everything as one JSON object: `mesh`, `discretization`, `fields`, the counts per family
    /// (`harmonic`, `integrable`, `cointegrable`), `eigenvalues`, `labels`, `seconds`,
    /// `computed` (eigenpairs per family), `split_threshold`, `counting_seconds`, `phases`
    /// (each with `seconds`, `cpu_seconds`, `cores_busy`, `factorizations`, `solves`),
    /// `factorizations`, `distinct_shifts`, `refined_pairs`, `max_field_residual`,
    /// `max_field_residual_floor`, `output` and `export` (paths or null).
    pub fn to_json(&self) -> Value {
        let report = self.report;
        let counts = FamilyCounts::of(self.families);
        let labels: Vec<&str> = self.families.iter().map(|f| f.name()).collect();
        let phases: serde_json::Map<String, Value> = report
            .phases(self.writing)
            .iter()
            .map(|(name, phase)| (name.to_string(), phase_json(phase)))
            .collect();
        let path = |p: Option<&Path>| p.map(|p| p.display().to_string());
        json!({
            "mesh": self.mesh,
            "discretization": self.discretization,
            "fields": self.eigenvalues.len(),
            "harmonic": counts.harmonic,
            "integrable": counts.integrable,
            "cointegrable": counts.cointegrable,
            "eigenvalues": self.eigenvalues,
            "labels": labels,
            "seconds": report.seconds,
            "computed": {
                "integrable": report.integrable_computed,
                "cointegrable": report.cointegrable_computed,
            },
            "split_threshold": report.split_threshold,
            "counting_seconds": report.counting_seconds,
            "phases": phases,
            "factorizations": report.factorizations,
            "distinct_shifts": report.distinct_shifts,
            "refined_pairs": report.solver.refined_pairs,
            "max_field_residual": report.max_field_residual,
            "max_field_residual_floor": report.max_field_residual_floor,
            "output": path(self.file),
            "export": path(self.arrays),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::basis_request::BasisRequest;
    use crate::compute_basis::compute_eigenfunction_basis;
    use tvf_discretizations::DEFAULT_DISCRETIZATION;

    #[test]
    fn the_summary_counts_the_families_and_lists_every_phase() {
        let (_, complex) = crate::test_torus::torus_complex(DEFAULT_DISCRETIZATION);
        let (basis, report) =
            compute_eigenfunction_basis(complex.as_ref(), &BasisRequest::fields(8)).unwrap();
        let counts = FamilyCounts::of(basis.families());
        assert_eq!(counts.harmonic, 2);
        assert_eq!(counts.harmonic + counts.integrable + counts.cointegrable, 8);
        let summary = BasisSummary {
            mesh: "example:torus",
            discretization: DEFAULT_DISCRETIZATION,
            eigenvalues: basis.eigenvalues(),
            families: basis.families(),
            report: &report,
            writing: PhaseStatistics::default(),
            file: Some(Path::new("b.tvfb")),
            arrays: None,
        };
        let headline = summary.headline();
        assert!(headline.starts_with("8 fields (2 harmonic, "), "{headline}");
        assert!(headline.ends_with("-> b.tvfb"), "{headline}");
        let json = summary.to_json();
        assert_eq!(json["fields"], 8);
        assert_eq!(json["labels"][0], "harmonic");
        assert_eq!(json["output"], "b.tvfb");
        assert_eq!(json["export"], Value::Null);
        let phases = json["phases"].as_object().unwrap();
        let names = ["boundaries", "counting", "refinement", "solving", "writing"];
        assert_eq!(phases.keys().collect::<Vec<_>>(), names);
        // The counting factorizations are not counted again at the boundaries.
        let factorizations: u64 = phases
            .values()
            .map(|p| p["factorizations"].as_u64().unwrap())
            .sum();
        assert_eq!(factorizations as usize, report.solver.factorizations());
        let table = basis.spectrum_table();
        assert_eq!(table.lines().count(), 9);
        assert!(
            table.lines().nth(1).unwrap().ends_with("  harmonic"),
            "{table}"
        );
        // A genus-1 torus: the harmonic fields' accuracy is noted.
        assert!(report
            .notes(counts)
            .iter()
            .any(|n| n.starts_with("harmonic fields: dimension 2")));
        // Computed pairs above the basis are said to be dropped, with the kept counts.
        let mut more = report.clone();
        more.split_threshold = Some(10.0);
        more.integrable_computed = counts.integrable + 1;
        more.cointegrable_computed = counts.cointegrable;
        let note = more.notes(counts).remove(0);
        assert!(
            note.contains(&format!(
                "the basis keeps the lowest {} + {} (the 1 above are dropped)",
                counts.integrable, counts.cointegrable
            )),
            "{note}"
        );
    }
}
