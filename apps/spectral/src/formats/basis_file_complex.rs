//! [`open_basis_file`]: a basis file together with the complex it was computed for, rebuilt
//! from the complex id stored in its header through the catalog the basis was made with (an
//! entry of a program's own catalog reopens only through that catalog); [`open_basis_file_with`]
//! for a complex the caller has (one read from a complex folder, whose matrices no id can
//! rebuild).

use crate::{load_basis, read_basis_header, BasisFileError, BasisFileKey, SpectralBasis};
use std::path::{Path, PathBuf};
use thiserror::Error;
use tvf_core::discretization::BoundaryCondition;
use tvf_core::mesh::Mesh;
use tvf_discretizations::{split_complex_id, BoxedComplex, Catalog, CatalogBuildError};

/// Why a basis file cannot be used on a mesh (every variant names the file).
#[derive(Debug, Error)]
pub enum BasisFileUseError {
    /// The file cannot be read, or belongs to another mesh.
    #[error(transparent)]
    File(#[from] BasisFileError),
    /// The file's discretization is not the one asked for.
    #[error("{}: the basis was computed with the discretization '{stored}', but '{wanted}' was asked for", path.display())]
    OtherDiscretization {
        /// The basis file.
        path: PathBuf,
        /// The complex id in the file.
        stored: String,
        /// The catalog id asked for.
        wanted: String,
    },
    /// The file's boundary condition is not the one asked for.
    #[error("{}: the basis was computed with the boundary condition '{}', but '{}' was asked for", path.display(), stored.name(), wanted.name())]
    OtherBoundaryCondition {
        /// The basis file.
        path: PathBuf,
        /// The condition in the file.
        stored: BoundaryCondition,
        /// The condition asked for.
        wanted: BoundaryCondition,
    },
    /// The file was computed for matrices read from a complex folder, which its id cannot
    /// rebuild.
    #[error("{}: the basis was computed from the matrices of a complex folder ('{stored}'): give that folder again (tvf: --complex DIR)", path.display())]
    NeedsComplexFolder {
        /// The basis file.
        path: PathBuf,
        /// The complex id in the file.
        stored: String,
    },
    /// The file's discretization cannot be built on the mesh.
    #[error("{}: {source}", path.display())]
    Complex {
        /// The basis file.
        path: PathBuf,
        /// Why the catalog could not build it (boxed: the error is large).
        source: Box<CatalogBuildError>,
    },
}

/// The complex id stored in the basis file `path`, checked against what the caller asks for:
/// `entry` a catalog id, `boundary` a boundary condition (`None`: whatever the file has).
pub fn basis_file_complex_id(
    path: &Path,
    entry: Option<&str>,
    boundary: Option<BoundaryCondition>,
) -> Result<String, BasisFileUseError> {
    let stored = read_basis_header(path)?.key.discretization;
    // On a mesh with boundary the stored id is `{catalog id}+{boundary}`.
    let (stored_entry, stored_boundary) = split_complex_id(&stored);
    if stored_entry == crate::COMPLEX_FOLDER_ID {
        return Err(BasisFileUseError::NeedsComplexFolder {
            path: path.to_path_buf(),
            stored: stored.clone(),
        });
    }
    if let Some(wanted) = entry.filter(|&wanted| wanted != stored_entry) {
        return Err(BasisFileUseError::OtherDiscretization {
            path: path.to_path_buf(),
            stored: stored.clone(),
            wanted: wanted.to_string(),
        });
    }
    if let (Some(stored), Some(wanted)) = (stored_boundary, boundary) {
        if stored != wanted {
            return Err(BasisFileUseError::OtherBoundaryCondition {
                path: path.to_path_buf(),
                stored,
                wanted,
            });
        }
    }
    Ok(stored)
}

/// The complex a basis file was computed for, built on `mesh` by the entry of `catalog` its
/// stored id names (see [`basis_file_complex_id`] for `entry` and `boundary`).
pub fn basis_file_complex<M: Mesh>(
    catalog: &Catalog,
    path: &Path,
    mesh: &M,
    entry: Option<&str>,
    boundary: Option<BoundaryCondition>,
) -> Result<BoxedComplex, BasisFileUseError> {
    let id = basis_file_complex_id(path, entry, boundary)?;
    catalog
        .build_complex(&id, None, mesh)
        .map_err(|source| BasisFileUseError::Complex {
            path: path.to_path_buf(),
            source: Box::new(source),
        })
}

/// Reads the basis file `path` for `mesh`: its complex, built through `catalog` (see
/// [`basis_file_complex`]), and the
/// basis, checked to belong to the mesh and the complex — for a file of format version 3 to the
/// complex's matrices too ([`BasisFileError::WrongMatrices`] otherwise; earlier files carry no
/// matrix hash, see [`crate::formats::basis_file`]).
pub fn open_basis_file<M: Mesh>(
    catalog: &Catalog,
    path: &Path,
    mesh: &M,
    entry: Option<&str>,
    boundary: Option<BoundaryCondition>,
) -> Result<(BoxedComplex, SpectralBasis), BasisFileUseError> {
    let complex = basis_file_complex(catalog, path, mesh, entry, boundary)?;
    open_basis_file_with(path, mesh, complex)
}

/// Reads the basis file `path` for `complex` on `mesh`: checked to belong to the mesh, to the
/// complex's id and, for a file of format version 3, to its matrices
/// ([`BasisFileError::WrongMatrices`] names the matrices that differ).
pub fn open_basis_file_with<M: Mesh + ?Sized>(
    path: &Path,
    mesh: &M,
    complex: BoxedComplex,
) -> Result<(BoxedComplex, SpectralBasis), BasisFileUseError> {
    let basis = load_basis(
        path,
        &BasisFileKey::new(mesh, complex.as_ref()),
        complex.as_ref(),
    )?;
    Ok((complex, basis))
}
