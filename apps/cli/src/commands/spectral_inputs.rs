//! What `filter`, `analyze`, `compress`, `decompress`, `rate-distortion` and `coefficients`
//! share: their `MESH FIELD` and basis flags ([`FieldArgs`]); a mesh with its discretization, against which the other inputs are checked first
//! ([`SpectralInputs`]), then its basis (a basis file checked to belong to the mesh, or a cached
//! or computed basis, see [`crate::basis_source`]; for the commands that only project and
//! synthesise, a basis file of eigenfunctions read in blocks: [`ProjectionBasis`], with blocks of
//! at most `$TVF_BASIS_BLOCK_BYTES`); field files
//! (one field, or a sequence of frames) read as tangent fields.

use crate::basis_file_progress::basis_file_observer;
use crate::basis_source::{BasisOptions, BasisSource};
use crate::mesh_input::MeshInput;
use crate::output_rules::{check_file_output, check_output};
use crate::progress::note;
use anyhow::Result;
use clap::Args;
use std::path::{Path, PathBuf};
use tvf_core::discretization::{FieldSampling, HodgeOperators};
use tvf_core::SurfaceMesh;
use tvf_discretizations::{BoxedComplex, Catalog};
pub use tvf_spectral::exact_hodge_energies;
use tvf_spectral::{
    read_basis_header, read_field_file, read_field_frames, BasisFileBlocks, BasisFileKey,
    BasisFileLayout, BasisSize, FieldBasis, FrameSource, SpectralBasis,
};

/// `MESH FIELD` (or `--example NAME FIELD`) and where the basis comes from.
#[derive(Args)]
pub struct FieldArgs {
    #[command(flatten)]
    pub input: MeshInput,
    /// The field: one 3D vector per face (.npy F×3, or text `x y z` per line; `tvf compress`
    /// also takes a sequence, see below).
    #[arg(value_name = "FIELD", required_unless_present = "example")]
    field: Option<PathBuf>,
    #[command(flatten)]
    pub basis: BasisSource,
}

impl FieldArgs {
    /// The field file (moved out of `MESH` with `--example`).
    pub fn field_path(&mut self) -> PathBuf {
        self.input.required_second(self.field.take(), "FIELD")
    }

    /// The field file, once the output rules hold for `output` against the inputs: the mesh,
    /// the field, the `--basis` file and `others` ([`check_output`]).
    pub fn field_path_for(&mut self, output: &Path, others: &[Option<&Path>]) -> Result<PathBuf> {
        let field = self.field_path();
        let mut inputs = vec![Some(field.as_path()), self.basis_file()];
        inputs.extend_from_slice(others);
        check_output(output, &self.input, &inputs)?;
        Ok(field)
    }

    /// [`FieldArgs::field_path_for`] for an output that is one file, which must not be an
    /// existing folder either ([`check_file_output`]).
    pub fn field_path_for_file(
        &mut self,
        output: &Path,
        others: &[Option<&Path>],
    ) -> Result<PathBuf> {
        let field = self.field_path_for(output, others)?;
        check_file_output(output, &self.input, &[])?;
        Ok(field)
    }

    /// The `--basis` file, if given.
    pub fn basis_file(&self) -> Option<&Path> {
        self.basis.options.basis.as_deref()
    }

    /// Loads the mesh and builds its discretization ([`inputs_for_mesh`]).
    pub fn load(&self, catalog: &Catalog) -> Result<SpectralInputs> {
        let mesh = self.input.load()?.mesh;
        inputs_for_mesh(catalog, mesh, &self.input, &self.basis.options)
    }

    /// The basis of `size` for `inputs` ([`SpectralInputs::with_basis`]).
    pub fn setup(
        &self,
        catalog: &Catalog,
        inputs: SpectralInputs,
        size: BasisSize,
    ) -> Result<SpectralSetup> {
        inputs.with_basis(catalog, &self.input, &self.basis.options, size)
    }

    /// The basis of a command that only projects fields on it and synthesises fields from it
    /// ([`projection_basis`]).
    pub fn projection_basis(
        &self,
        catalog: &Catalog,
        inputs: SpectralInputs,
        size: BasisSize,
    ) -> Result<ProjectionBasis> {
        projection_basis(catalog, &self.input, &self.basis.options, inputs, size)
    }

    /// The basis of a command that writes compressed files ([`identified_basis`]).
    pub fn identified_basis(
        &self,
        catalog: &Catalog,
        inputs: SpectralInputs,
        size: BasisSize,
    ) -> Result<ProjectionBasis> {
        identified_basis(catalog, &self.input, &self.basis.options, inputs, size)
    }
}

/// The basis of a command that only projects fields on it and synthesises fields from it
/// (`filter`, `coefficients`, `rate-distortion`): a `--basis` file in the eigenfunctions layout
/// (format version 3) is checked whole and then read a block of columns at a time, never
/// loaded; any other basis as [`SpectralInputs::with_basis`] gives it.
pub fn projection_basis(
    catalog: &Catalog,
    input: &MeshInput,
    options: &BasisOptions,
    inputs: SpectralInputs,
    size: BasisSize,
) -> Result<ProjectionBasis> {
    match options.basis.as_deref() {
        Some(path) if readable_in_blocks(path)? => {
            let blocks = open_basis_blocks(path, &inputs.mesh, inputs.complex)?;
            Ok(ProjectionBasis::Blocks(Box::new(blocks)))
        }
        _ => Ok(ProjectionBasis::Whole(Box::new(
            inputs.with_basis(catalog, input, options, size)?,
        ))),
    }
}

/// The basis of a command whose compressed files carry the basis id (`compress`,
/// `decompress`): [`projection_basis`], except that a file read in blocks whose fields would
/// not get the id of the loaded basis (a non-diagonal `M1` whose co-potentials do not fit one
/// block: [`BasisFileBlocks::forms_fields_as_loaded`]) is loaded whole instead, with a note, so
/// that a file compressed in blocks decodes with the basis loaded whole and the other way round.
pub fn identified_basis(
    catalog: &Catalog,
    input: &MeshInput,
    options: &BasisOptions,
    inputs: SpectralInputs,
    size: BasisSize,
) -> Result<ProjectionBasis> {
    let path = match options.basis.as_deref() {
        Some(path) if readable_in_blocks(path)? => path,
        _ => return projection_basis(catalog, input, options, inputs, size),
    };
    let blocks = open_basis_blocks(path, &inputs.mesh, inputs.complex)?;
    if blocks.forms_fields_as_loaded() {
        return Ok(ProjectionBasis::Blocks(Box::new(blocks)));
    }
    note(
        "the basis has a non-diagonal M1 and more co-integrable fields than one block holds: \
         loaded whole, so that its id is the loaded basis's (the one compressed files carry)",
    );
    let inputs = SpectralInputs {
        mesh: inputs.mesh,
        complex: blocks.into_complex(),
    };
    Ok(ProjectionBasis::Whole(Box::new(
        inputs.with_basis(catalog, input, options, size)?,
    )))
}

/// Whether the basis file `path` is read in blocks ([`BasisFileBlocks`]): a file in the
/// eigenfunctions layout with matrix hashes (format version 3); any other is loaded whole.
pub fn readable_in_blocks(path: &Path) -> Result<bool> {
    let header = read_basis_header(path)?;
    Ok(
        matches!(header.layout, BasisFileLayout::Eigenfunctions { .. })
            && header.key.matrix_hash.is_some(),
    )
}

/// The basis file `path` of `mesh` and `complex` (one [`readable_in_blocks`]), checked and
/// opened to be read in blocks; noted on stderr, and the progress of its passes shown there
/// ([`basis_file_observer`]).
pub fn open_basis_blocks(
    path: &Path,
    mesh: &SurfaceMesh,
    complex: BoxedComplex,
) -> Result<BasisFileBlocks> {
    let key = BasisFileKey::new(mesh, complex.as_ref());
    let start = std::time::Instant::now();
    let id = complex.id().to_string();
    let block_bytes = block_bytes()?;
    match BasisFileBlocks::open_with_observer(path, &key, complex, basis_file_observer())? {
        Some(blocks) => {
            let blocks = blocks.with_block_bytes(block_bytes);
            note(format!(
                "using basis {} ({} fields, {id}, checked in {:.2} s, read in blocks)",
                path.display(),
                blocks.len(),
                start.elapsed().as_secs_f64()
            ));
            Ok(blocks)
        }
        None => anyhow::bail!(
            "{}: the basis file changed while it was read (its layout)",
            path.display()
        ),
    }
}

/// Environment variable setting the largest block, in bytes, in which a basis file is read
/// (default [`tvf_spectral::BLOCK_BYTES`], 64 MiB; at least one stored column is read at a time
/// whatever it says): less memory for slower reading, or the other way round.
pub const BLOCK_BYTES_VARIABLE: &str = "TVF_BASIS_BLOCK_BYTES";

/// The block size of [`BLOCK_BYTES_VARIABLE`], else the default; a value that is not a positive
/// whole number of bytes is an error.
fn block_bytes() -> Result<usize> {
    let Some(raw) = std::env::var_os(BLOCK_BYTES_VARIABLE) else {
        return Ok(tvf_spectral::BLOCK_BYTES);
    };
    let value = raw.to_string_lossy().into_owned();
    match value.trim().parse::<usize>() {
        Ok(bytes) if bytes > 0 => Ok(bytes),
        _ => anyhow::bail!(
            "environment variable {BLOCK_BYTES_VARIABLE} = '{value}': a positive number of \
             bytes, e.g. 67108864"
        ),
    }
}

/// A basis for projections and syntheses ([`projection_basis`]).
pub enum ProjectionBasis {
    /// A basis file read a block of columns at a time.
    Blocks(Box<BasisFileBlocks>),
    /// A basis in memory, with its mesh and discretization.
    Whole(Box<SpectralSetup>),
}

impl ProjectionBasis {
    /// The basis.
    pub fn basis(&self) -> &dyn FieldBasis {
        match self {
            Self::Blocks(blocks) => blocks.as_ref(),
            Self::Whole(setup) => &setup.basis,
        }
    }

    /// How fields of the discretization are read and written as per-face vectors.
    pub fn fields(&self) -> Result<&dyn FieldSampling> {
        match self {
            Self::Blocks(blocks) => Ok(blocks.complex().require_sampling()?),
            Self::Whole(setup) => setup.fields(),
        }
    }

    /// The discretization the basis was computed with (its id, as in basis files).
    pub fn discretization(&self) -> String {
        match self {
            Self::Blocks(blocks) => blocks.complex().id().to_string(),
            Self::Whole(setup) => setup.discretization.clone(),
        }
    }
}

/// A basis that belongs to a mesh, with the mesh's discretization.
pub struct SpectralSetup {
    /// The discretization the basis belongs to.
    pub complex: BoxedComplex,
    /// The basis (from `--basis`, the cache, or computed).
    pub basis: SpectralBasis,
    /// The discretization the basis was computed with (its id, as in basis files).
    pub discretization: String,
}

/// A mesh and the discretization its basis will have, before the basis is loaded or
/// computed: every other input (fields, compressed files) is checked against these first, so
/// that a bad input is refused before the expensive step and leaves no basis in the cache.
pub struct SpectralInputs {
    /// The mesh.
    pub mesh: SurfaceMesh,
    /// The discretization (the `--basis` file's, read from its header, or the flags').
    pub complex: BoxedComplex,
}

/// The inputs of a mesh already loaded from `input`: its discretization, an entry of `catalog`
/// (see [`SpectralInputs`]).
pub fn inputs_for_mesh(
    catalog: &Catalog,
    mesh: SurfaceMesh,
    input: &MeshInput,
    source: &BasisOptions,
) -> Result<SpectralInputs> {
    let complex = source.discretization(catalog, &mesh, input)?;
    Ok(SpectralInputs { mesh, complex })
}

impl SpectralInputs {
    /// How fields of the discretization are read and written as per-face vectors.
    pub fn fields(&self) -> Result<&dyn FieldSampling> {
        Ok(self.complex.require_sampling()?)
    }

    /// The basis of `size` for the mesh: the `--basis` file (refused if computed for another
    /// mesh or discretization) or a basis computed once and cached (see [`BasisOptions`]).
    pub fn with_basis(
        self,
        catalog: &Catalog,
        input: &MeshInput,
        source: &BasisOptions,
        size: BasisSize,
    ) -> Result<SpectralSetup> {
        let computed_with = source.basis.is_none().then_some(self.complex);
        let resolved = source.resolve_with(catalog, &self.mesh, input, size, computed_with)?;
        Ok(SpectralSetup {
            discretization: resolved.discretization.id().to_string(),
            complex: resolved.discretization,
            basis: resolved.basis,
        })
    }
}

impl SpectralSetup {
    /// How fields of the discretization are read and written as per-face vectors.
    pub fn fields(&self) -> Result<&dyn FieldSampling> {
        Ok(self.complex.require_sampling()?)
    }
}

/// Reads one field file (`.npy` `F × 3` or text) as a tangent field (`n1` coefficients); notes
/// on stderr how large the dropped normal components were.
pub fn read_field(path: &Path, fields: &dyn FieldSampling) -> Result<Vec<f64>> {
    let read = read_field_file(path, fields)?;
    if let Some(text) = read.dropped_normal_note(path) {
        note(format!("note: {text}"));
    }
    Ok(read.field)
}

/// Reads a field or a sequence of frames ([`read_field_frames`]); notes on stderr how large the
/// dropped normal components were.
pub fn read_frames(
    path: &Path,
    fields: &dyn FieldSampling,
) -> Result<(Vec<Vec<f64>>, FrameSource)> {
    let read = read_field_frames(path, fields)?;
    if let Some(text) = read.dropped_normal_note(path) {
        note(format!("note: {text}"));
    }
    Ok((read.frames, read.source))
}
