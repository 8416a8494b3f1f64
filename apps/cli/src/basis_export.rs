//! `tvf basis --export DIR`: a basis as plain `.npy` arrays (numpy reads them with `np.load`),
//! written into a staged folder that appears whole or not at all (committed by the caller,
//! together with its other outputs).

use crate::output_rules::stage;
use anyhow::{Context, Result};
use std::io::Write;
use std::path::Path;
use tvf_core::discretization::{HodgeComplex, HodgeOperators};
use tvf_core::io::StagedFolder;
use tvf_spectral::{npy_bytes, EigenfunctionBasis, NpyData};

/// Writes `eigenvalues.npy` (`k`, float64, ascending), `families.npy` (`k` strings:
/// `harmonic`, `integrable`, `cointegrable`), `coefficients.npy` (`n1 × k`, the
/// discretization's own coefficients, `M1`-orthonormal) and, where the complex samples fields,
/// `fields.npy` (`F × 3 × k`, each field at the face centroids) and `frames.npy` (`F × 2 × 3`,
/// `[e1, e2]` of every face) into the staged folder `dir`, returned uncommitted.
pub fn stage_basis_export(
    basis: &EigenfunctionBasis,
    complex: &dyn HodgeComplex,
    dir: &Path,
) -> Result<StagedFolder> {
    let staged = stage(dir)?;
    let write = |name: &str, bytes: Vec<u8>| -> Result<()> {
        tvf_core::io::write_atomically(&staged.path().join(name), |w| w.write_all(&bytes))
            .with_context(|| format!("cannot write {}", dir.join(name).display()))
    };
    let k = basis.len();
    let n1 = complex.field_dimension();
    write(
        "eigenvalues.npy",
        npy_bytes(&NpyData::F64(basis.eigenvalues()), &[k]),
    )?;
    let families: Vec<&str> = basis.families().iter().map(|f| f.name()).collect();
    write("families.npy", npy_bytes(&NpyData::Text(&families), &[k]))?;
    let columns: Vec<Vec<f64>> = (0..k).map(|j| basis.field(complex, j)).collect();
    let coefficients: Vec<f64> = (0..n1)
        .flat_map(|i| columns.iter().map(move |column| column[i]))
        .collect();
    write(
        "coefficients.npy",
        npy_bytes(&NpyData::F64(&coefficients), &[n1, k]),
    )?;
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
        write(
            "fields.npy",
            npy_bytes(&NpyData::F64(&sampled), &[faces, 3, k]),
        )?;
        let frames: Vec<f64> = (0..faces)
            .flat_map(|t| sampling.frame(t).into_iter().flatten())
            .collect();
        write(
            "frames.npy",
            npy_bytes(&NpyData::F64(&frames), &[faces, 2, 3]),
        )?;
    }
    Ok(staged)
}
