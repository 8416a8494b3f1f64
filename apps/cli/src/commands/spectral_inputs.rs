//! What `filter`, `analyze`, `compress`, `decompress`, `rate-distortion` and `coefficients`
//! share: a mesh with its basis (a basis file checked to belong to the mesh, or a cached or
//! computed basis, see [`crate::basis_source`]), and field files (one field, or a sequence of
//! frames) read as tangent fields.

use crate::basis_source::BasisOptions;
use crate::mesh_input::MeshInput;
use crate::output_rules::{commit, stage};
use anyhow::{bail, Context, Result};
use std::path::{Path, PathBuf};
use tvf_core::discretization::HodgeOperators;
use tvf_core::discretization::{FieldSampling, HodgeComplex};
use tvf_core::SurfaceMesh;
use tvf_discretizations::BoxedComplex;
use tvf_discretizations::HodgeDecomposer;
use tvf_spectral::BasisSize;
use tvf_spectral::{
    read_face_vector_sequence, read_tangent_field, write_face_vector_sequence, write_tangent_field,
    EnergySplit, FieldIoError, NpyDtype, SpectralBasis,
};

/// A mesh, its face fields and a basis that belongs to it.
pub struct SpectralSetup {
    /// The mesh.
    pub mesh: SurfaceMesh,
    /// The discretization the basis belongs to.
    pub complex: BoxedComplex,
    /// The basis (from `--basis`, the cache, or computed).
    pub basis: SpectralBasis,
    /// The discretization the basis was computed with (its id, as in basis files).
    pub discretization: String,
    /// [`mesh_fingerprint`] of the mesh.
    pub mesh_fingerprint: u64,
}

/// Loads the mesh and its basis: the `--basis` file (refused if computed for another mesh or
/// discretization) or a basis of `size` computed once and cached (see [`BasisOptions`]).
pub fn load_setup(
    input: &MeshInput,
    source: &BasisOptions,
    size: BasisSize,
) -> Result<SpectralSetup> {
    setup_for_mesh(input.load()?.mesh, input, source, size)
}

impl SpectralSetup {
    /// How fields of the discretization are read and written as per-face vectors.
    pub fn fields(&self) -> Result<&dyn FieldSampling> {
        Ok(self.complex.require_sampling()?)
    }
}

/// [`load_setup`] for a mesh already loaded from `input`.
pub fn setup_for_mesh(
    mesh: SurfaceMesh,
    input: &MeshInput,
    source: &BasisOptions,
    size: BasisSize,
) -> Result<SpectralSetup> {
    let resolved = source.resolve(&mesh, input, size)?;
    Ok(SpectralSetup {
        discretization: resolved.discretization.id().to_string(),
        complex: resolved.discretization,
        mesh_fingerprint: resolved.mesh_fingerprint,
        basis: resolved.basis,
        mesh,
    })
}

/// Reads one field file (`.npy` `F × 3` or text) as a tangent field (`2F` coefficients); notes
/// on stderr how large the dropped normal components were.
pub fn read_field(path: &Path, fields: &dyn FieldSampling) -> Result<Vec<f64>> {
    let projection = read_tangent_field(path, fields)?;
    let normal = projection.max_normal_part();
    if normal > 0.0 {
        crate::progress::note(format!(
            "note: {}: normal components up to {normal:.3e} were dropped (fields are tangent)",
            path.display()
        ));
    }
    check_magnitudes(path, &projection.field)?;
    Ok(projection.field)
}

/// Largest accepted field coefficient: its square (and a sum of a few of them) stays finite, so
/// magnitudes and energies of the field can be computed in `f64`.
pub const MAX_FIELD_COEFFICIENT: f64 = 1e150;

/// Refuses a field whose coefficients are too large to square in `f64` (magnitudes, energies and
/// everything computed from them would be infinite or NaN); the message names the file.
fn check_magnitudes(path: &Path, field: &[f64]) -> Result<()> {
    if let Some((k, x)) = field
        .iter()
        .enumerate()
        .find(|(_, x)| x.is_nan() || x.abs() > MAX_FIELD_COEFFICIENT)
    {
        anyhow::bail!(
            "{}: the vector of face {} has a component of {x:e}: too large for f64 arithmetic \
             (lengths and energies overflow; components must be at most {MAX_FIELD_COEFFICIENT:e})",
            path.display(),
            k / 2
        );
    }
    Ok(())
}

/// Where a sequence of frames came from (and how decompression writes it back by default).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FrameSource {
    /// One field file.
    Single,
    /// One `.npy` array `F × 3 × T`.
    Array,
    /// A folder of field files, one per frame, in file-name order.
    Folder,
}

/// Reads a field or a sequence: a folder of field files (`.npy` or `.txt`, sorted by name), an
/// `.npy` array `F × 3 × T`, or one field file.
pub fn read_frames(
    path: &Path,
    fields: &dyn FieldSampling,
) -> Result<(Vec<Vec<f64>>, FrameSource)> {
    if path.is_dir() {
        let mut files: Vec<PathBuf> = std::fs::read_dir(path)
            .with_context(|| format!("cannot list the frame folder {}", path.display()))?
            .filter_map(|entry| entry.ok().map(|e| e.path()))
            .filter(|p| {
                p.is_file() && matches!(p.extension().and_then(|e| e.to_str()), Some("npy" | "txt"))
            })
            .collect();
        files.sort();
        if files.is_empty() {
            bail!("{}: the folder holds no .npy or .txt frame", path.display());
        }
        let frames = files
            .iter()
            .map(|file| read_field(file, fields))
            .collect::<Result<Vec<_>>>()?;
        return Ok((frames, FrameSource::Folder));
    }
    let is_npy = path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("npy"));
    if is_npy {
        match read_face_vector_sequence(path) {
            Ok(sequence) => {
                let mut frames = Vec::with_capacity(sequence.len());
                for (k, vectors) in sequence.iter().enumerate() {
                    if vectors.len() != fields.face_count() {
                        bail!(
                            "{}: frames have {} vectors, the mesh has {} faces",
                            path.display(),
                            vectors.len(),
                            fields.face_count()
                        );
                    }
                    let projection = fields
                        .from_face_vectors(vectors)
                        .with_context(|| format!("{}: frame {k}", path.display()))?;
                    frames.push(projection.field);
                }
                return Ok((frames, FrameSource::Array));
            }
            Err(FieldIoError::Shape { found, .. }) if found.len() == 2 => {}
            Err(error) => return Err(error.into()),
        }
    }
    Ok((vec![read_field(path, fields)?], FrameSource::Single))
}

/// Writes frames: one frame to the file `out` (format by extension); several to one `.npy`
/// array `F × 3 × T` if `out` ends in `.npy`, otherwise into the folder `out` as
/// `frame_00000.npy`, `frame_00001.npy`, ...
pub fn write_frames(out: &Path, fields: &dyn FieldSampling, frames: &[Vec<f64>]) -> Result<()> {
    if let [single] = frames {
        write_tangent_field(out, fields, single)?;
        return Ok(());
    }
    let vectors = frames
        .iter()
        .map(|f| fields.to_face_vectors(f))
        .collect::<Result<Vec<_>, _>>()?;
    if out
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("npy"))
    {
        write_face_vector_sequence(out, &vectors, NpyDtype::F64)?;
    } else {
        let staged = stage(out)?;
        for (k, frame) in frames.iter().enumerate() {
            let name = format!("frame_{k:05}.npy");
            write_tangent_field(&staged.path().join(&name), fields, frame)
                .with_context(|| format!("cannot write {}", out.join(&name).display()))?;
        }
        commit(staged)?;
    }
    Ok(())
}

/// Energies of the exact Hodge decomposition of `field` by `complex`.
pub fn exact_hodge_energies(complex: &dyn HodgeComplex, field: &[f64]) -> Result<EnergySplit> {
    let parts = HodgeDecomposer::new(complex)?.decompose(field)?;
    Ok(EnergySplit::of_hodge_parts(&parts, complex.m1().values()))
}
