//! [`ComparisonReport`]: the table of `tvf compare` and `tvf.compare` — per entry its sizes,
//! the non-zeros of its masses, its assembly and basis times (seconds, and ratios to the
//! reference's in the same run), its peak memory ([`crate::ResidentPeak`]), its family counts,
//! and against the reference ([`BasisComparison`]) its eigenvalues' relative differences
//! (overall and per family), the principal angles of every eigenvalue cluster and the shares of
//! each eigenfield in the other's span. Written as Markdown, CSV and JSON.

use crate::basis::FieldFamily;
use crate::basis_comparison::{
    BasisComparison, BasisComparisonError, ClusterComparison, SampledBasis,
};
use serde_json::{json, Value};
use std::fmt::Write;
use tvf_core::discretization::{HodgeComplex, Mass, MassStorage};
use tvf_core::SurfaceMesh;

/// What was measured of one entry besides its basis.
#[derive(Debug, Clone)]
pub struct EntryMeasurements {
    /// The entry as the user named it (a catalog id, a folder, a builder's name).
    pub label: String,
    /// The complex's own id.
    pub id: String,
    /// `n0, n1, n2`: potential, field and co-potential coefficients.
    pub sizes: [usize; 3],
    /// Stored non-zeros of `M0, M1, M2` (a diagonal mass: its length).
    pub mass_nonzeros: [usize; 3],
    /// Seconds to build the complex (assemble its matrices, or read them).
    pub assembly_seconds: f64,
    /// Seconds to compute its basis.
    pub basis_seconds: f64,
    /// Resident bytes added at the peak while the entry was built and its basis computed and
    /// sampled ([`crate::ResidentPeak`]); `None` where it cannot be measured.
    pub peak_bytes: Option<u64>,
}

impl EntryMeasurements {
    /// The sizes and mass non-zeros of `complex`, named `label`, with the times and peak
    /// measured around it.
    pub fn new(
        label: String,
        complex: &dyn HodgeComplex,
        assembly_seconds: f64,
        basis_seconds: f64,
        peak_bytes: Option<u64>,
    ) -> Self {
        EntryMeasurements {
            label,
            id: complex.id().to_string(),
            sizes: [
                complex.d0().cols(),
                complex.d0().rows(),
                complex.d1().rows(),
            ],
            mass_nonzeros: [complex.m0(), complex.m1(), complex.m2()].map(stored_nonzeros),
            assembly_seconds,
            basis_seconds,
            peak_bytes,
        }
    }
}

/// The non-zeros of a mass as stored (`M` or `M⁻¹`): a diagonal's non-zero entries, a sparse
/// matrix's stored entries.
fn stored_nonzeros(mass: &Mass) -> usize {
    match mass.storage() {
        MassStorage::Diagonal(values) => values.iter().filter(|&&x| x != 0.0).count(),
        MassStorage::Sparse(matrix) => matrix.nnz(),
    }
}

/// One compared entry: its measurements and its sampled basis.
pub struct ComparedEntry {
    /// Sizes, times, memory.
    pub measurements: EntryMeasurements,
    /// The basis as vectors on the surface.
    pub sampled: SampledBasis,
}

/// The comparison of every entry with the reference.
pub struct ComparisonReport {
    /// The mesh as named in the report.
    pub mesh: String,
    /// Its faces.
    pub faces: usize,
    /// The basis size `K` asked for.
    pub fields: usize,
    /// The largest relative eigenvalue gap inside a cluster.
    pub cluster_tolerance: f64,
    /// Position of the reference in `entries`.
    pub reference: usize,
    /// The entries in the order given.
    pub entries: Vec<ComparedEntry>,
    /// Per entry (the reference included, compared with itself) its comparison with the
    /// reference: `comparisons[i]` is the reference against `entries[i]`.
    pub comparisons: Vec<BasisComparison>,
}

/// The families with eigenvalues of their own, as named in tables.
const FAMILIES: [(FieldFamily, &str); 2] = [
    (FieldFamily::Integrable, "integrable"),
    (FieldFamily::Cointegrable, "cointegrable"),
];

impl ComparisonReport {
    /// Compares every entry with `entries[reference]` on `mesh` (named `mesh_label`), bases of
    /// `fields` fields, clusters of relative gap at most `cluster_tolerance`.
    pub fn new(
        mesh_label: String,
        mesh: &SurfaceMesh,
        fields: usize,
        cluster_tolerance: f64,
        reference: usize,
        entries: Vec<ComparedEntry>,
    ) -> Result<Self, BasisComparisonError> {
        let comparisons = entries
            .iter()
            .map(|e| {
                BasisComparison::new(
                    mesh,
                    &entries[reference].sampled,
                    &e.sampled,
                    cluster_tolerance,
                )
            })
            .collect::<Result<Vec<_>, _>>()?;
        Ok(Self {
            mesh: mesh_label,
            faces: mesh.face_count(),
            fields,
            cluster_tolerance,
            reference,
            entries,
            comparisons,
        })
    }

    fn reference_entry(&self) -> &ComparedEntry {
        &self.entries[self.reference]
    }

    /// The report as one JSON object: `reference`, `entries` (per entry `discretization`, `id`,
    /// sizes, `mass_nonzeros`, times, ratios, `peak_bytes`, family counts, `eigenvalues`,
    /// `relative_difference`, `families`, `principal_angles` (every cluster's angles in cluster
    /// order), `clusters`, and the span shares) and the clustering rule.
    pub fn to_json(&self) -> Value {
        let reference = &self.reference_entry().measurements;
        let entries: Vec<Value> = self
            .entries
            .iter()
            .zip(&self.comparisons)
            .map(|(entry, comparison)| entry_json(entry, comparison, reference))
            .collect();
        json!({
            "mesh": self.mesh,
            "faces": self.faces,
            "fields": self.fields,
            "reference": reference.label,
            "cluster_tolerance": self.cluster_tolerance,
            "peak_bytes_measures": "resident bytes added at the peak while the entry ran \
                (Linux VmHWM reset through /proc/self/clear_refs, minus VmRSS at its start)",
            "entries": entries,
        })
    }

    /// The per-entry table as CSV (one header line, one line per entry).
    pub fn entries_csv(&self) -> String {
        let mut out = String::from(
            "entry,id,n0,n1,n2,nnz_m0,nnz_m1,nnz_m2,assembly_seconds,assembly_ratio,\
             basis_seconds,basis_ratio,peak_bytes,harmonic,integrable,cointegrable,\
             integrable_difference_median,integrable_difference_max,\
             cointegrable_difference_median,cointegrable_difference_max,\
             largest_angle,median_cluster_angle,clusters_compared,clusters\n",
        );
        for row in self.rows() {
            let optional = |x: Option<f64>| x.map_or(String::new(), |x| format!("{x:e}"));
            let _ = writeln!(
                out,
                "{},{},{},{},{},{},{},{},{:e},{:e},{:e},{:e},{},{},{},{},{},{},{},{},{},{},{},{}",
                csv_field(&row.m.label),
                csv_field(&row.m.id),
                row.m.sizes[0],
                row.m.sizes[1],
                row.m.sizes[2],
                row.m.mass_nonzeros[0],
                row.m.mass_nonzeros[1],
                row.m.mass_nonzeros[2],
                row.m.assembly_seconds,
                row.assembly_ratio,
                row.m.basis_seconds,
                row.basis_ratio,
                row.m.peak_bytes.map_or(String::new(), |b| b.to_string()),
                row.counts[0],
                row.counts[1],
                row.counts[2],
                optional(row.family_differences[0].map(|d| d.0)),
                optional(row.family_differences[0].map(|d| d.1)),
                optional(row.family_differences[1].map(|d| d.0)),
                optional(row.family_differences[1].map(|d| d.1)),
                optional(row.largest_angle),
                optional(row.median_angle),
                row.clusters_compared,
                row.clusters,
            );
        }
        out
    }

    /// Every family eigenvalue of every entry as CSV: `family,position,` then per entry its
    /// eigenvalue and relative difference to the reference (empty past an entry's count).
    pub fn eigenvalues_csv(&self) -> String {
        let mut out = String::from("family,position");
        for entry in &self.entries {
            let label = &entry.measurements.label;
            let _ = write!(
                out,
                ",{},{}",
                csv_field(&format!("{label} eigenvalue")),
                csv_field(&format!("{label} relative difference"))
            );
        }
        out.push('\n');
        for (family, name) in FAMILIES {
            let values: Vec<Vec<f64>> = self
                .entries
                .iter()
                .map(|e| e.sampled.family_eigenvalues(family))
                .collect();
            let count = values.iter().map(Vec::len).max().unwrap_or(0);
            for position in 0..count {
                let _ = write!(out, "{name},{position}");
                for (i, comparison) in self.comparisons.iter().enumerate() {
                    let differences = match family {
                        FieldFamily::Integrable => &comparison.integrable_differences,
                        _ => &comparison.cointegrable_differences,
                    };
                    let value = values[i].get(position).map(|x| format!("{x:e}"));
                    let difference = differences.get(position).map(|x| format!("{x:e}"));
                    let _ = write!(
                        out,
                        ",{},{}",
                        value.unwrap_or_default(),
                        difference.unwrap_or_default()
                    );
                }
                out.push('\n');
            }
        }
        out
    }

    /// Every cluster of the reference as CSV: `family,first,size,lowest,highest,gap_above,`
    /// then per entry the largest principal angle (radians; empty where not compared).
    pub fn clusters_csv(&self) -> String {
        let mut out = String::from("family,first,size,lowest,highest,gap_above");
        for entry in &self.entries {
            let header = format!("{} largest angle", entry.measurements.label);
            let _ = write!(out, ",{}", csv_field(&header));
        }
        out.push('\n');
        let reference = &self.comparisons[self.reference];
        for (k, c) in reference.clusters.iter().enumerate() {
            let cluster = &c.cluster;
            let _ = write!(
                out,
                "{},{},{},{:e},{:e},{}",
                cluster.family.name(),
                cluster.first,
                cluster.size(),
                cluster.eigenvalues.0,
                cluster.eigenvalues.1,
                cluster
                    .gap_above
                    .map_or(String::new(), |g| format!("{g:e}"))
            );
            for comparison in &self.comparisons {
                let angle = comparison.clusters[k].largest_angle();
                let _ = write!(
                    out,
                    ",{}",
                    angle.map_or(String::new(), |a| format!("{a:e}"))
                );
            }
            out.push('\n');
        }
        out
    }

    /// The report as Markdown: the per-entry table, then what each column measures.
    pub fn markdown(&self) -> String {
        let reference = &self.reference_entry().measurements.label;
        let mut out = format!(
            "# tvf compare: {} ({} faces), K = {} fields, reference {}\n\n",
            self.mesh, self.faces, self.fields, reference
        );
        out.push_str(
            "| entry | n0 | n1 | n2 | nnz M0 / M1 / M2 | assembly s (× ref) | basis s (× ref) \
             | peak MB | h / int / co | Δλ int med / max | Δλ co med / max | angle max / med \
             (rad) | clusters |\n|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n",
        );
        for row in self.rows() {
            let m = row.m;
            let pair = |x: Option<(f64, f64)>| {
                x.map_or("–".into(), |(a, b)| format!("{a:.2e} / {b:.2e}"))
            };
            let angles = match (row.largest_angle, row.median_angle) {
                (Some(a), Some(b)) => format!("{a:.3} / {b:.3}"),
                _ => "–".into(),
            };
            let _ = writeln!(
                out,
                "| {} | {} | {} | {} | {} / {} / {} | {:.3} ({:.2}×) | {:.3} ({:.2}×) | {} | {} \
                 / {} / {} | {} | {} | {} | {} of {} |",
                markdown_cell(&m.label),
                m.sizes[0],
                m.sizes[1],
                m.sizes[2],
                m.mass_nonzeros[0],
                m.mass_nonzeros[1],
                m.mass_nonzeros[2],
                m.assembly_seconds,
                row.assembly_ratio,
                m.basis_seconds,
                row.basis_ratio,
                m.peak_bytes
                    .map_or("–".into(), |b| format!("{:.1}", b as f64 / 1e6)),
                row.counts[0],
                row.counts[1],
                row.counts[2],
                pair(row.family_differences[0]),
                pair(row.family_differences[1]),
                angles,
                row.clusters_compared,
                row.clusters
            );
        }
        out.push_str(&self.cluster_markdown());
        out
    }

    /// The clusters of the reference with the largest angle of each entry, as Markdown.
    fn cluster_markdown(&self) -> String {
        let mut out = format!(
            "\n## Eigenspace clusters of the reference (relative gap ≤ {}) and the largest \
             principal angle of each entry (radians)\n\n| family | positions | λ | gap above |",
            self.cluster_tolerance
        );
        for entry in &self.entries {
            let _ = write!(out, " {} |", markdown_cell(&entry.measurements.label));
        }
        out.push_str("\n|---|---|---|---|");
        out.push_str(&"---:|".repeat(self.entries.len()));
        out.push('\n');
        let reference = &self.comparisons[self.reference];
        for (k, c) in reference.clusters.iter().enumerate() {
            let cluster = &c.cluster;
            let (lo, hi) = cluster.eigenvalues;
            let _ = write!(
                out,
                "| {} | {}–{} | {} | {} |",
                cluster.family.name(),
                cluster.first,
                cluster.first + cluster.size() - 1,
                if lo == hi {
                    format!("{lo:.5}")
                } else {
                    format!("{lo:.5}–{hi:.5}")
                },
                cluster
                    .gap_above
                    .map_or("(basis ends)".into(), |g| format!("{g:.3}"))
            );
            for comparison in &self.comparisons {
                let angle = comparison.clusters[k].largest_angle();
                let _ = write!(
                    out,
                    " {} |",
                    angle.map_or("–".into(), |a| format!("{a:.2e}"))
                );
            }
            out.push('\n');
        }
        out
    }

    /// The summary row of every entry.
    fn rows(&self) -> Vec<SummaryRow<'_>> {
        let reference = &self.reference_entry().measurements;
        self.entries
            .iter()
            .zip(&self.comparisons)
            .map(|(entry, comparison)| SummaryRow::new(entry, comparison, reference))
            .collect()
    }
}

/// One entry's line of the tables.
struct SummaryRow<'a> {
    m: &'a EntryMeasurements,
    assembly_ratio: f64,
    basis_ratio: f64,
    /// Harmonic, integrable, co-integrable fields.
    counts: [usize; 3],
    /// Median and largest relative eigenvalue difference per family (`None`: no eigenvalue).
    family_differences: [Option<(f64, f64)>; 2],
    largest_angle: Option<f64>,
    /// The median over the compared clusters of each cluster's largest angle.
    median_angle: Option<f64>,
    clusters_compared: usize,
    clusters: usize,
}

impl<'a> SummaryRow<'a> {
    fn new(
        entry: &'a ComparedEntry,
        comparison: &BasisComparison,
        reference: &EntryMeasurements,
    ) -> Self {
        let m = &entry.measurements;
        let count = |family| {
            entry
                .sampled
                .families
                .iter()
                .filter(|&&f| f == family)
                .count()
        };
        let largest: Vec<f64> = comparison
            .clusters
            .iter()
            .filter_map(ClusterComparison::largest_angle)
            .collect();
        SummaryRow {
            m,
            assembly_ratio: m.assembly_seconds / reference.assembly_seconds,
            basis_ratio: m.basis_seconds / reference.basis_seconds,
            counts: [
                count(FieldFamily::Harmonic),
                count(FieldFamily::Integrable),
                count(FieldFamily::Cointegrable),
            ],
            family_differences: [
                median_and_max(&comparison.integrable_differences),
                median_and_max(&comparison.cointegrable_differences),
            ],
            largest_angle: largest.iter().copied().reduce(f64::max),
            median_angle: median_and_max(&largest).map(|(median, _)| median),
            clusters_compared: largest.len(),
            clusters: comparison.clusters.len(),
        }
    }
}

/// One entry as JSON (see [`ComparisonReport::to_json`]).
fn entry_json(
    entry: &ComparedEntry,
    comparison: &BasisComparison,
    reference: &EntryMeasurements,
) -> Value {
    let m = &entry.measurements;
    let row = SummaryRow::new(entry, comparison, reference);
    let clusters: Vec<Value> = comparison
        .clusters
        .iter()
        .map(|c| {
            json!({
                "family": c.cluster.family.name(),
                "first": c.cluster.first,
                "size": c.cluster.size(),
                "eigenvalues": [c.cluster.eigenvalues.0, c.cluster.eigenvalues.1],
                "gap_above": c.cluster.gap_above,
                "columns": c.cluster.columns,
                "other_columns": c.other_columns,
                "angles": (c.other_columns.is_some()).then_some(&c.angles),
            })
        })
        .collect();
    let principal_angles: Vec<f64> = comparison
        .clusters
        .iter()
        .flat_map(|c| c.angles.iter().copied())
        .collect();
    let family = |f: FieldFamily, differences: &[f64]| {
        json!({
            "eigenvalues": entry.sampled.family_eigenvalues(f),
            "relative_difference": differences,
        })
    };
    json!({
        "discretization": m.label,
        "id": m.id,
        "n0": m.sizes[0],
        "n1": m.sizes[1],
        "n2": m.sizes[2],
        "mass_nonzeros": m.mass_nonzeros,
        "assembly_seconds": m.assembly_seconds,
        "assembly_ratio": row.assembly_ratio,
        "basis_seconds": m.basis_seconds,
        "basis_ratio": row.basis_ratio,
        "peak_bytes": m.peak_bytes,
        "harmonic": row.counts[0],
        "integrable": row.counts[1],
        "cointegrable": row.counts[2],
        "eigenvalues": entry.sampled.eigenvalues,
        "relative_difference": comparison.eigenvalue_differences,
        "families": {
            "integrable": family(FieldFamily::Integrable, &comparison.integrable_differences),
            "cointegrable": family(FieldFamily::Cointegrable, &comparison.cointegrable_differences),
        },
        "principal_angles": principal_angles,
        "clusters": clusters,
        "in_reference_span": comparison.second_in_first,
        "reference_in_span": comparison.first_in_second,
    })
}

/// Median and largest of `values` (`None` if empty).
fn median_and_max(values: &[f64]) -> Option<(f64, f64)> {
    let mut sorted = values.to_vec();
    sorted.sort_by(f64::total_cmp);
    Some((*sorted.get(sorted.len() / 2)?, *sorted.last()?))
}

/// `text` as one cell of a Markdown table (its `|` escaped).
fn markdown_cell(text: &str) -> String {
    text.replace('|', "\\|")
}

/// `text` as one CSV field (quoted where it holds a comma, quote or line break).
fn csv_field(text: &str) -> String {
    if text.contains([',', '"', '\n', '\r']) {
        format!("\"{}\"", text.replace('"', "\"\""))
    } else {
        text.to_string()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{compute_basis, BasisRequest};
    use tvf_core::generate::icosphere;
    use tvf_discretizations::catalog_entry;

    fn entry(id: &str, mesh: &SurfaceMesh, seconds: f64) -> ComparedEntry {
        let complex = catalog_entry(id).unwrap().build(mesh).unwrap();
        let basis = compute_basis(complex.as_ref(), &BasisRequest::fields(6)).unwrap();
        let sampled = SampledBasis::new(complex.as_ref(), &basis).unwrap();
        let measurements =
            EntryMeasurements::new(id.to_string(), complex.as_ref(), seconds, seconds, None);
        ComparedEntry {
            measurements,
            sampled,
        }
    }

    #[test]
    fn the_tables_have_one_line_per_entry_and_ratios_to_the_reference() {
        let mesh = SurfaceMesh::from(icosphere(2));
        let entries = vec![
            entry("conforming-barycentric", &mesh, 2.0),
            entry("dec-circumcentric", &mesh, 1.0),
        ];
        let report = ComparisonReport::new("sphere".into(), &mesh, 6, 0.01, 1, entries).unwrap();
        let json = report.to_json();
        assert_eq!(json["reference"], "dec-circumcentric");
        let first = &json["entries"][0];
        assert_eq!(first["basis_ratio"], 2.0);
        assert_eq!(first["n0"], mesh.vertex_count());
        assert_eq!(first["n1"], 2 * mesh.face_count());
        assert_eq!(first["peak_bytes"], Value::Null);
        // K = 6 fields: the l = 1 eigenspace of each family, one cluster of 3 each.
        assert_eq!(first["principal_angles"].as_array().unwrap().len(), 6);
        assert_eq!(first["clusters"].as_array().unwrap().len(), 2);
        let csv = report.entries_csv();
        let lines: Vec<&str> = csv.lines().collect();
        assert_eq!(lines.len(), 3);
        let columns = lines[0].split(',').count();
        assert!(
            lines.iter().all(|l| l.split(',').count() == columns),
            "{csv}"
        );
        let markdown = report.markdown();
        assert!(
            markdown.contains("| dec-circumcentric | 162 |"),
            "{markdown}"
        );
        assert!(markdown.contains("(2.00×)"), "{markdown}");
        assert_eq!(report.eigenvalues_csv().lines().count(), 1 + 3 + 3);
        assert_eq!(report.clusters_csv().lines().count(), 1 + 2);
    }
}
