//! The folder of a Hodge decomposition (`tvf decompose FIELD -o DIR`): the three parts as face
//! vectors and the two potentials, one `.npy` file each ([`write_hodge_parts`]).

use crate::formats::field_io::{write_face_vectors, write_npy};
use crate::formats::folder_file::{FieldFolderError, FolderFileError};
use crate::formats::npy::{NpyArray, NpyDtype};
use tvf_core::discretization::{HodgeComplex, HodgeOperators};
use tvf_core::io::StagedFolder;
use tvf_discretizations::HodgeParts;

/// Writes `parts` (a decomposition by `complex`) into the staged `folder`: `integrable.npy`,
/// `cointegrable.npy` and `harmonic.npy` (`F × 3`, one vector per face, at the centroids), then
/// `potential.npy` and `co_potential.npy` (`n0` and `n2` values, one per node). After each
/// part is written, `on_part(name, energy)` is told its name and its squared norm
/// `‖·‖²_{M1}` ([`HodgeOperators::field_inner`]).
pub fn write_hodge_parts(
    folder: &StagedFolder,
    complex: &dyn HodgeComplex,
    parts: &HodgeParts,
    on_part: &mut dyn FnMut(&'static str, f64),
) -> Result<(), FieldFolderError> {
    for (name, part) in [
        ("integrable", &parts.integrable),
        ("cointegrable", &parts.cointegrable),
        ("harmonic", &parts.harmonic),
    ] {
        let file = format!("{name}.npy");
        let vectors = complex.require_sampling()?.to_face_vectors(part)?;
        write_face_vectors(&folder.path().join(&file), &vectors)
            .map_err(|e| FolderFileError::new(folder, &file, e))?;
        on_part(name, complex.field_inner(part, part));
    }
    for (name, values) in [
        ("potential", &parts.potential),
        ("co_potential", &parts.co_potential),
    ] {
        let file = format!("{name}.npy");
        let array = NpyArray {
            shape: vec![values.len()],
            data: values.clone(),
            dtype: NpyDtype::F64,
        };
        write_npy(&folder.path().join(&file), &array)
            .map_err(|e| FolderFileError::new(folder, &file, e))?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::formats::field_io::read_npy;
    use tvf_discretizations::{HodgeDecomposer, DEFAULT_DISCRETIZATION};

    #[test]
    fn the_parts_and_potentials_are_written_and_their_energies_add_up() {
        let (mesh, complex) = crate::test_torus::torus_complex(DEFAULT_DISCRETIZATION);
        let field: Vec<f64> = (0..complex.field_dimension())
            .map(|i| (0.37 * i as f64).sin())
            .collect();
        let parts = HodgeDecomposer::new(complex.as_ref())
            .and_then(|d| d.decompose(&field))
            .unwrap();
        let dir = tempfile::tempdir().unwrap();
        let folder = StagedFolder::new(&dir.path().join("parts")).unwrap();
        let mut energies = Vec::new();
        write_hodge_parts(&folder, complex.as_ref(), &parts, &mut |name, energy| {
            energies.push((name, energy))
        })
        .unwrap();
        let names: Vec<&str> = energies.iter().map(|(n, _)| *n).collect();
        assert_eq!(names, ["integrable", "cointegrable", "harmonic"]);
        // The parts are M1-orthogonal: their energies add up to the field's.
        let total: f64 = energies.iter().map(|(_, e)| e).sum();
        let field_energy = complex.field_inner(&field, &field);
        assert!(
            (total - field_energy).abs() <= 1e-8 * field_energy,
            "{total} {field_energy}"
        );
        let harmonic = read_npy(&folder.path().join("harmonic.npy")).unwrap();
        assert_eq!(harmonic.shape, [mesh.face_count(), 3]);
        let potential = read_npy(&folder.path().join("potential.npy")).unwrap();
        assert_eq!(potential.shape, [complex.potential_dimension()]);
    }
}
