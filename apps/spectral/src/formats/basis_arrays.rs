//! A basis as plain `.npy` arrays (`tvf basis --export DIR`; numpy reads them with `np.load`):
//! [`write_basis_arrays`] writes them into a staged folder, which the caller commits together
//! with its other outputs.

use crate::eigenfunction_basis::EigenfunctionBasis;
use crate::formats::folder_file::{write_folder_bytes, FieldFolderError};
use crate::formats::numpy_export::{npy_bytes, NpyData};
use tvf_core::discretization::{HodgeComplex, HodgeOperators};
use tvf_core::io::StagedFolder;

/// Writes `eigenvalues.npy` (`k`, float64, ascending), `families.npy` (`k` strings:
/// `harmonic`, `integrable`, `cointegrable`), `coefficients.npy` (`n1 × k`, the
/// discretization's own coefficients, `M1`-orthonormal) and, where the complex samples fields,
/// `fields.npy` (`F × 3 × k`, each field at the face centroids) and `frames.npy` (`F × 2 × 3`,
/// `[e1, e2]` of every face) of `basis` (a basis of `complex`) into the staged `folder`.
pub fn write_basis_arrays(
    basis: &EigenfunctionBasis,
    complex: &dyn HodgeComplex,
    folder: &StagedFolder,
) -> Result<(), FieldFolderError> {
    let k = basis.len();
    let n1 = complex.field_dimension();
    let eigenvalues = npy_bytes(&NpyData::F64(basis.eigenvalues()), &[k]);
    write_folder_bytes(folder, "eigenvalues.npy", &eigenvalues)?;
    let families: Vec<&str> = basis.families().iter().map(|f| f.name()).collect();
    let families = npy_bytes(&NpyData::Text(&families), &[k]);
    write_folder_bytes(folder, "families.npy", &families)?;
    let columns: Vec<Vec<f64>> = (0..k).map(|j| basis.field(complex, j)).collect();
    let coefficients: Vec<f64> = (0..n1)
        .flat_map(|i| columns.iter().map(move |column| column[i]))
        .collect();
    let coefficients = npy_bytes(&NpyData::F64(&coefficients), &[n1, k]);
    write_folder_bytes(folder, "coefficients.npy", &coefficients)?;
    if let Some(sampling) = complex.sampling() {
        let faces = sampling.face_count();
        let mut sampled = vec![0.0; faces * 3 * k];
        for (j, column) in columns.iter().enumerate() {
            for (t, v) in sampling.to_face_vectors(column)?.iter().enumerate() {
                for (c, x) in v.iter().enumerate() {
                    sampled[(t * 3 + c) * k + j] = *x;
                }
            }
        }
        let fields = npy_bytes(&NpyData::F64(&sampled), &[faces, 3, k]);
        write_folder_bytes(folder, "fields.npy", &fields)?;
        let frames: Vec<f64> = (0..faces)
            .flat_map(|t| sampling.frame(t).into_iter().flatten())
            .collect();
        let frames = npy_bytes(&NpyData::F64(&frames), &[faces, 2, 3]);
        write_folder_bytes(folder, "frames.npy", &frames)?;
    }
    Ok(())
}
