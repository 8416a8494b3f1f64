//! Whether a `.tvfc` file fits a mesh and a complex, checked from its header before any basis
//! is computed ([`TvfcHeader::check_fits`]); the basis it was made with is checked by its id
//! once it is there ([`crate::FieldCodec::for_file`]).

use crate::codec::compression_error::CompressionError;
use crate::formats::compressed_file::TvfcHeader;
use tvf_core::discretization::{HodgeComplex, HodgeOperators};
use tvf_core::SurfaceMesh;

impl TvfcHeader {
    /// Refuses a file made for another mesh (by fingerprint) or for fields of another size
    /// than those of `complex` on `mesh`.
    pub fn check_fits(
        &self,
        mesh: &SurfaceMesh,
        complex: &dyn HodgeComplex,
    ) -> Result<(), CompressionError> {
        let fingerprint = mesh.fingerprint();
        if self.mesh_fingerprint != fingerprint {
            return Err(CompressionError::MeshMismatch {
                file: self.mesh_fingerprint,
                mesh: fingerprint,
            });
        }
        let dimension = complex.field_dimension();
        if self.field_dimension != dimension as u64 {
            return Err(CompressionError::FieldDimensionMismatch {
                file: self.field_dimension,
                complex: complex.id().to_string(),
                dimension,
            });
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::CoefficientCoding;
    use tvf_core::generate::icosphere;
    use tvf_discretizations::catalog_entry;

    #[test]
    fn a_file_of_another_mesh_or_field_size_is_refused() {
        let (mesh, faces) = crate::test_torus::torus_complex("conforming-barycentric");
        let edges = catalog_entry("whitney-galerkin")
            .unwrap()
            .build(&mesh)
            .unwrap();
        let header = TvfcHeader {
            mesh_fingerprint: mesh.fingerprint(),
            basis_id: 0,
            field_dimension: 2 * mesh.face_count() as u64,
            pairs: 1,
            coefficients: 4,
            coding: CoefficientCoding::Float64,
        };
        assert!(header.check_fits(&mesh, faces.as_ref()).is_ok());
        let error = header.check_fits(&mesh, edges.as_ref()).unwrap_err();
        assert!(
            matches!(error, CompressionError::FieldDimensionMismatch { .. }),
            "{error}"
        );
        assert!(error.to_string().contains("whitney-galerkin"), "{error}");
        let other = SurfaceMesh::from(icosphere(1));
        let error = header.check_fits(&other, faces.as_ref()).unwrap_err();
        assert!(
            matches!(error, CompressionError::MeshMismatch { .. }),
            "{error}"
        );
    }
}
