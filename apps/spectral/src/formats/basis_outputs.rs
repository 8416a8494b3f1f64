//! The outputs of a computed basis (`tvf basis -o FILE --export DIR`): the basis file (`.tvfb`)
//! and/or its numpy arrays, written so that both appear together or neither does
//! ([`save_basis_outputs`]).

use crate::eigenfunction_basis::EigenfunctionBasis;
use crate::formats::basis_arrays::write_basis_arrays;
use crate::formats::basis_file::save_eigenfunction_basis;
use crate::formats::basis_file_header::BasisFileKey;
use crate::formats::folder_file::FieldFolderError;
use std::error::Error as StdError;
use std::path::{Path, PathBuf};
use std::time::Instant;
use thiserror::Error;
use tvf_core::discretization::HodgeComplex;
use tvf_core::io::temporaries::commit_uninterrupted;
use tvf_core::io::{StagedFile, StagedFolder};
use tvf_solvers::{process_cpu_seconds, PhaseStatistics};

/// Why the outputs of a basis could not be written.
#[derive(Debug, Error)]
pub enum BasisOutputError {
    /// The basis file could not be written.
    #[error("cannot write {}: {source}", path.display())]
    File {
        /// The basis file.
        path: PathBuf,
        /// Why.
        #[source]
        source: Box<dyn StdError + Send + Sync>,
    },
    /// The folder of arrays could not be created or put into place.
    #[error("cannot write the folder {}: {source}", path.display())]
    Folder {
        /// The folder.
        path: PathBuf,
        /// Why.
        #[source]
        source: std::io::Error,
    },
    /// An array of the folder could not be written.
    #[error(transparent)]
    Arrays(#[from] FieldFolderError),
}

/// Writes `basis` (computed for `complex`, identified by `key`) as the basis file `file`
/// ([`crate::save_eigenfunction_basis`]) and/or as the numpy arrays of the folder `arrays`
/// ([`crate::write_basis_arrays`]); with both, the file waits, staged, until the folder is
/// complete, and both are put into place together (uninterrupted). Returns the cost of the
/// writing (wall-clock and processor seconds).
pub fn save_basis_outputs(
    basis: &EigenfunctionBasis,
    complex: &dyn HodgeComplex,
    key: &BasisFileKey,
    file: Option<&Path>,
    arrays: Option<&Path>,
) -> Result<PhaseStatistics, BasisOutputError> {
    let (start, cpu) = (Instant::now(), process_cpu_seconds());
    // Both outputs appear together or neither: the file waits, staged, for the folder.
    let staged_file = match (file, arrays) {
        (Some(file), Some(_)) => Some(StagedFile::new(file).map_err(file_error(file))?),
        _ => None,
    };
    if let Some(file) = file {
        let path = staged_file
            .as_ref()
            .map_or(file.to_path_buf(), StagedFile::path);
        save_eigenfunction_basis(&path, basis, complex, key).map_err(file_error(file))?;
    }
    let staged_arrays = match arrays {
        Some(dir) => {
            let folder = StagedFolder::new(dir).map_err(folder_error(dir))?;
            write_basis_arrays(basis, complex, &folder)?;
            Some(folder)
        }
        None => None,
    };
    commit_uninterrupted(|| {
        if let (Some(folder), Some(dir)) = (staged_arrays, arrays) {
            folder.commit().map_err(folder_error(dir))?;
        }
        if let (Some(staged), Some(file)) = (staged_file, file) {
            staged.commit().map_err(file_error(file))?;
        }
        Ok::<_, BasisOutputError>(())
    })?;
    Ok(PhaseStatistics {
        wall_seconds: start.elapsed().as_secs_f64(),
        cpu_seconds: process_cpu_seconds() - cpu,
        ..PhaseStatistics::default()
    })
}

/// The error of the basis file `path`, made from its cause.
fn file_error<E: Into<Box<dyn StdError + Send + Sync>>>(
    path: &Path,
) -> impl FnOnce(E) -> BasisOutputError {
    let path = path.to_path_buf();
    move |source| BasisOutputError::File {
        path,
        source: source.into(),
    }
}

/// The error of the folder `path`, made from its cause.
fn folder_error(path: &Path) -> impl FnOnce(std::io::Error) -> BasisOutputError {
    let path = path.to_path_buf();
    move |source| BasisOutputError::Folder { path, source }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::basis_request::BasisRequest;
    use crate::compute_basis::compute_eigenfunction_basis;
    use crate::formats::basis_file::load_basis;
    use tvf_discretizations::DEFAULT_DISCRETIZATION;

    #[test]
    fn the_file_and_the_arrays_are_written_together() {
        let (mesh, complex) = crate::test_torus::torus_complex(DEFAULT_DISCRETIZATION);
        let (basis, _) =
            compute_eigenfunction_basis(complex.as_ref(), &BasisRequest::fields(6)).unwrap();
        let key = BasisFileKey::new(&mesh, complex.as_ref());
        let dir = tempfile::tempdir().unwrap();
        let (file, arrays) = (dir.path().join("b.tvfb"), dir.path().join("arrays"));
        let writing =
            save_basis_outputs(&basis, complex.as_ref(), &key, Some(&file), Some(&arrays)).unwrap();
        assert!(writing.wall_seconds >= 0.0);
        assert_eq!(load_basis(&file, &key, complex.as_ref()).unwrap().len(), 6);
        let names = [
            "eigenvalues",
            "families",
            "coefficients",
            "fields",
            "frames",
        ];
        for name in names {
            assert!(arrays.join(format!("{name}.npy")).is_file(), "{name}.npy");
        }
        let fields = crate::read_npy(&arrays.join("fields.npy")).unwrap();
        assert_eq!(fields.shape, [mesh.face_count(), 3, 6]);
        // A folder that cannot be made (its parent is missing): neither output appears.
        let (file, arrays) = (dir.path().join("c.tvfb"), dir.path().join("no/arrays"));
        let error = save_basis_outputs(&basis, complex.as_ref(), &key, Some(&file), Some(&arrays))
            .unwrap_err();
        assert!(
            error.to_string().starts_with("cannot write the folder"),
            "{error}"
        );
        assert!(!file.exists());
    }
}
