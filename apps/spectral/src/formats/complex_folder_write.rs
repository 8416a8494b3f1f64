//! Writing a complex folder (`tvf operators MESH -o DIR`, read back by
//! [`crate::read_complex_folder`]): the five matrices `d0`, `d1`, `M0`, `M1`, `M2` (a mass stored
//! as its inverse gets the file name `M*_inverse`), the derived `S0`, and `S2`, `S`, `B` where
//! they are sparse, the rotation `J` where the complex has one, `vertex_map.npy`, the intrinsic
//! triangulation of a complex built on one, and `info.json` ([`crate::complex_folder_info`]).

use crate::formats::complex_folder_info::{complex_folder_info, mass_file_name, MatrixFileFormat};
use crate::formats::folder_file::{write_folder_bytes, write_folder_file, FolderFileError};
use crate::formats::numpy_export::{npy_bytes, write_sparse_npz, NpyData};
use serde_json::{json, Map, Value};
use sprs::CsMat;
use std::io::Write;
use tvf_core::discretization::{HodgeComplex, HodgeOperators};
use tvf_core::io::StagedFolder;
use tvf_core::mesh::ValidationReport;
use tvf_core::SurfaceMesh;

/// Writes every file of the complex folder of `complex` on `mesh` (loaded with `report`) into
/// the staged `folder`, the matrices in `format`; returns the number of matrix files. Errors
/// name the file in the output folder.
pub fn write_complex_folder(
    complex: &dyn HodgeComplex,
    mesh: &SurfaceMesh,
    report: &ValidationReport,
    format: MatrixFileFormat,
    folder: &StagedFolder,
) -> Result<usize, FolderFileError> {
    let (matrices, not_written) = folder_matrices(complex);
    for (name, matrix) in &matrices {
        let file = format!("{name}.{}", format.extension());
        write_folder_file(folder, &file, |w| match format {
            MatrixFileFormat::MatrixMarket => sprs::io::write_matrix_market_to_bufwrite(w, matrix),
            MatrixFileFormat::SparseNpz => {
                let mut buffer = std::io::Cursor::new(Vec::new());
                write_sparse_npz(&mut buffer, matrix)?;
                w.write_all(buffer.get_ref())
            }
        })?;
    }
    let vertex_map: Vec<i64> = report.original_vertex.iter().map(|&v| v as i64).collect();
    let npy = npy_bytes(&NpyData::I64(&vertex_map), &[vertex_map.len()]);
    write_folder_bytes(folder, "vertex_map.npy", &npy)?;
    write_intrinsic_triangulation(complex, folder)?;
    let info = complex_folder_info(complex, mesh, report, format, not_written);
    let text = serde_json::to_string_pretty(&info)
        .map_err(|e| FolderFileError::new(folder, "info.json", e))?
        + "\n";
    write_folder_bytes(folder, "info.json", text.as_bytes())?;
    Ok(matrices.len())
}

/// On a complex built on an intrinsic triangulation, its connectivity and lengths:
/// `intrinsic_faces.npy` (`F_i × 3` int64, counter-clockwise vertex triples),
/// `intrinsic_edges.npy` (`E_i × 2` int64, each edge's reference direction: `d0`'s `−1`, `+1`)
/// and `intrinsic_edge_lengths.npy` (`E_i` float64). Nothing otherwise.
fn write_intrinsic_triangulation(
    complex: &dyn HodgeComplex,
    folder: &StagedFolder,
) -> Result<(), FolderFileError> {
    let Some(tri) = complex.intrinsic_triangulation() else {
        return Ok(());
    };
    let faces: Vec<i64> = tri.faces().iter().flatten().map(|&v| v as i64).collect();
    let edges: Vec<i64> = (0..tri.edge_count())
        .flat_map(|e| tri.edge_vertices(e))
        .map(|v| v as i64)
        .collect();
    let files = [
        (
            "intrinsic_faces.npy",
            npy_bytes(&NpyData::I64(&faces), &[tri.face_count(), 3]),
        ),
        (
            "intrinsic_edges.npy",
            npy_bytes(&NpyData::I64(&edges), &[tri.edge_count(), 2]),
        ),
        (
            "intrinsic_edge_lengths.npy",
            npy_bytes(&NpyData::F64(tri.lengths()), &[tri.edge_count()]),
        ),
    ];
    for (name, bytes) in files {
        write_folder_bytes(folder, name, &bytes)?;
    }
    Ok(())
}

/// Matrices by file name (without extension), in the order they are written.
type NamedMatrices = Vec<(String, CsMat<f64>)>;

/// The matrices of the folder, by file name (without extension), in the order they are
/// written; and the derived matrices left out because they are dense, with the reason (the
/// `not_written` of `info.json`).
fn folder_matrices(complex: &dyn HodgeComplex) -> (NamedMatrices, Map<String, Value>) {
    let mut matrices: NamedMatrices = vec![
        ("d0".into(), complex.d0().clone()),
        ("d1".into(), complex.d1().clone()),
    ];
    for (name, mass) in [
        ("M0", complex.m0()),
        ("M1", complex.m1()),
        ("M2", complex.m2()),
    ] {
        matrices.push((mass_file_name(name, mass.form()), mass.stored_matrix()));
    }
    matrices.push(("S0".into(), complex.potential_stiffness().clone()));
    let mut not_written = Map::new();
    for (name, operator, why) in [
        (
            "S2",
            complex.co_potential_stiffness(),
            "d1 M1^-1 d1^T with a non-diagonal M1",
        ),
        (
            "S",
            complex.dirichlet_energy(),
            "it contains M0^-1 or M2 of a non-diagonal mass",
        ),
        (
            "B",
            complex.biharmonic_energy(),
            "S M1^-1 S with a non-diagonal M1 or a dense S",
        ),
    ] {
        match operator.as_sparse() {
            Some(matrix) => matrices.push((name.into(), matrix.clone())),
            None => {
                not_written.insert(name.into(), json!(format!("dense: {why}")));
            }
        }
    }
    if let Some(rotation) = complex.rotation() {
        matrices.push(("J".into(), rotation.rotation().clone()));
    }
    (matrices, not_written)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::formats::complex_folder::read_complex_folder;
    use tvf_core::generate::torus;
    use tvf_core::FaceList;
    use tvf_discretizations::{catalog_entry, DEFAULT_DISCRETIZATION};

    #[test]
    fn a_written_folder_lists_its_files_and_reads_back() {
        let raw = torus(1.0, 0.4, 12, 6).unwrap();
        let (mesh, report) = SurfaceMesh::validated(
            raw.positions().to_vec(),
            FaceList::from_triangles(raw.faces()),
        )
        .unwrap();
        let complex = catalog_entry(DEFAULT_DISCRETIZATION)
            .unwrap()
            .build(&mesh)
            .unwrap();
        for format in MatrixFileFormat::ALL {
            let dir = tempfile::tempdir().unwrap();
            let out = dir.path().join("complex");
            let folder = StagedFolder::new(&out).unwrap();
            let written =
                write_complex_folder(complex.as_ref(), &mesh, &report, format, &folder).unwrap();
            folder.commit().unwrap();
            // d0, d1, three masses, S0, and S2, S, B, J of the diagonal-mass default.
            assert_eq!(written, 10);
            for name in ["d0", "d1", "M0", "M1", "M2", "S0", "S2", "S", "B", "J"] {
                let file = out.join(format!("{name}.{}", format.extension()));
                assert!(file.is_file(), "{} missing", file.display());
            }
            assert!(out.join("vertex_map.npy").is_file());
            let info: Value =
                serde_json::from_str(&std::fs::read_to_string(out.join("info.json")).unwrap())
                    .unwrap();
            assert_eq!(info["discretization"], DEFAULT_DISCRETIZATION);
            assert_eq!(info["not_written"], json!({}));
            let read = read_complex_folder(&out, &mesh, &report.original_vertex).unwrap();
            assert_eq!(read.d0().nnz(), complex.d0().nnz());
        }
    }
}
