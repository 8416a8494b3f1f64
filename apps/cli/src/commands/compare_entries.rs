//! The entries of `tvf compare` on one mesh: what the flags name (catalog ids, then
//! `--complex` folders), the reference among them, and each entry built, its basis computed
//! (timed, with progress), sampled and measured (sizes, mass non-zeros, peak memory).

use super::compare::CompareArgs;
use crate::context::RunContext;
use crate::mesh_input::MeshInput;
use crate::progress::Progress;
use anyhow::{bail, Context, Result};
use std::path::PathBuf;
use std::time::Instant;
use tvf_core::discretization::HodgeOperators;
use tvf_core::SurfaceMesh;
use tvf_discretizations::BoxedComplex;
use tvf_spectral::{
    compute_basis, BasisRequest, ComparedEntry, EntryMeasurements, ResidentPeak, SampledBasis,
};

/// What the flags name: catalog ids first, then folders.
pub enum EntryName {
    Catalog(String),
    Folder(PathBuf),
}

impl EntryName {
    /// The entry as the user gave it.
    pub fn label(&self) -> String {
        match self {
            EntryName::Catalog(id) => id.clone(),
            EntryName::Folder(dir) => dir.display().to_string(),
        }
    }
}

/// The entries in order, at least two, none twice.
pub fn entry_names(args: &CompareArgs) -> Result<Vec<EntryName>> {
    let mut names: Vec<EntryName> = args
        .discretizations
        .iter()
        .cloned()
        .map(EntryName::Catalog)
        .collect();
    names.extend(args.complexes.iter().cloned().map(EntryName::Folder));
    if names.len() < 2 {
        bail!(
            "compare needs at least two entries: give --discretization ID (and/or --complex DIR) \
             two or more times"
        );
    }
    for (i, id) in args.discretizations.iter().enumerate() {
        if args.discretizations[..i].contains(id) {
            bail!("--discretization {id} is given twice");
        }
    }
    for (i, dir) in args.complexes.iter().enumerate() {
        if args.complexes[..i].contains(dir) {
            bail!("--complex {} is given twice", dir.display());
        }
    }
    Ok(names)
}

/// The position of `--reference` among `names` (0 without it).
pub fn reference_position(args: &CompareArgs, names: &[EntryName]) -> Result<usize> {
    let Some(wanted) = &args.reference else {
        return Ok(0);
    };
    let labels: Vec<String> = names.iter().map(EntryName::label).collect();
    labels.iter().position(|l| l == wanted).with_context(|| {
        format!(
            "--reference {wanted}: not one of the compared entries ({})",
            labels.join(", ")
        )
    })
}

/// The complex `name` names, built on `mesh` (a catalog entry) or read (a folder).
pub fn build_entry(
    name: &EntryName,
    args: &CompareArgs,
    context: &RunContext,
    mesh: &SurfaceMesh,
    original_vertex: &[usize],
    input: &MeshInput,
) -> Result<BoxedComplex> {
    Ok(match name {
        EntryName::Catalog(id) => context
            .catalog()
            .build_complex(id, Some(args.boundary.unwrap_or_default()), mesh)
            .with_context(|| input.label())?,
        EntryName::Folder(dir) => Box::new(
            tvf_spectral::read_complex_folder(dir, mesh, original_vertex)
                .with_context(|| format!("--complex {} on {}", dir.display(), input.label()))?,
        ),
    })
}

/// Computes the basis of `count` fields of `complex` (timed, with progress), samples it and
/// measures the entry; `label` names it in the report, `peak` was started before it was built.
pub fn measure_entry(
    complex: BoxedComplex,
    label: String,
    assembly_seconds: f64,
    peak: Option<ResidentPeak>,
    count: usize,
    input: &MeshInput,
) -> Result<ComparedEntry> {
    let progress = Progress::new(format!("compare {}", complex.id()));
    let start = Instant::now();
    let basis = {
        let callback = progress.basis_callback();
        let request =
            BasisRequest::lowest(count, complex.field_dimension()).with_progress(&callback);
        compute_basis(complex.as_ref(), &request).with_context(|| {
            format!(
                "{}: cannot compute the basis of '{}'",
                input.label(),
                complex.id()
            )
        })?
    };
    let basis_seconds = start.elapsed().as_secs_f64();
    progress.finish(format!(
        "{} fields of {} in {basis_seconds:.2} s",
        basis.len(),
        complex.id()
    ));
    let mut sampled = SampledBasis::new(complex.as_ref(), &basis)
        .with_context(|| format!("{}: '{}'", input.label(), complex.id()))?;
    sampled.id = label.clone();
    drop(basis);
    let peak_bytes = peak.and_then(|p| p.added_bytes());
    let measurements = EntryMeasurements::new(
        label,
        complex.as_ref(),
        assembly_seconds,
        basis_seconds,
        peak_bytes,
    );
    Ok(ComparedEntry {
        measurements,
        sampled,
    })
}
