//! A tangent field made ready for other tools (`tvf export`): its per-face data for VTK and PLY
//! ([`FaceData::of_field`]) and its streamlines as polylines for OBJ ([`streamline_polylines`]).

use super::FaceData;
use crate::error::RenderError;
use crate::face_quantities::{face_scalar, FaceQuantity};
use crate::streamlines::{trace_streamlines, StreamlineOptions};
use tvf_core::discretization::{DiscretizationError, HodgeComplex};
use tvf_core::SurfaceMesh;

impl FaceData {
    /// The per-face data of `field` (`n1` coefficients of `complex`, built on `mesh`), whose 3D
    /// vectors at the face centroids are `vectors`: the vector `field`, then the scalars
    /// `magnitude`, `divergence`, `curl` and `energy` (as `tvf render --color` draws them,
    /// [`face_scalar`]).
    pub fn of_field<H: HodgeComplex + ?Sized>(
        complex: &H,
        mesh: &SurfaceMesh,
        field: &[f64],
        vectors: Vec<[f64; 3]>,
    ) -> Result<Self, DiscretizationError> {
        let mut scalars = Vec::new();
        for kind in [
            FaceQuantity::Magnitude,
            FaceQuantity::Divergence,
            FaceQuantity::Curl,
            FaceQuantity::Energy,
        ] {
            let values = face_scalar(complex, mesh, kind, field, &vectors)?;
            scalars.extend(values.map(|v| (kind.label().to_string(), v)));
        }
        Ok(Self {
            vectors: vec![("field".to_string(), vectors)],
            scalars,
        })
    }
}

/// The streamlines of the face vectors `vectors` (one per face of `mesh`) as polylines (points
/// on the surface, in the direction of the field; traced on the display triangulation),
/// `count` their density ([`StreamlineOptions::count`]; the other options are the defaults).
pub fn streamline_polylines(
    mesh: &SurfaceMesh,
    vectors: &[[f64; 3]],
    count: usize,
) -> Result<Vec<Vec<[f64; 3]>>, RenderError> {
    let options = StreamlineOptions {
        count,
        ..Default::default()
    };
    let lines = trace_streamlines(mesh.display(), &mesh.on_display(vectors), &options)?;
    Ok(lines.into_iter().map(|line| line.points).collect())
}

#[cfg(test)]
mod tests {
    use super::*;
    use tvf_core::discretization::HodgeOperators;
    use tvf_core::generate::torus;
    use tvf_discretizations::{catalog_entry, DEFAULT_DISCRETIZATION};

    #[test]
    fn a_field_gives_its_vectors_four_scalars_and_streamlines() {
        let mesh = SurfaceMesh::from(torus(1.0, 0.4, 16, 8).unwrap());
        let complex = catalog_entry(DEFAULT_DISCRETIZATION)
            .unwrap()
            .build(&mesh)
            .unwrap();
        let sampling = complex.require_sampling().unwrap();
        // The field along the torus's axis of revolution, tangent to the tube's circles.
        let vectors: Vec<[f64; 3]> = (0..mesh.face_count())
            .map(|t| {
                let c = mesh.face_centroid(t);
                [-c[1], c[0], 0.0]
            })
            .collect();
        let field = sampling.from_face_vectors(&vectors).unwrap().field;
        let tangent = sampling.to_face_vectors(&field).unwrap();
        let data = FaceData::of_field(complex.as_ref(), &mesh, &field, tangent.clone()).unwrap();
        assert_eq!(data.vectors, vec![("field".to_string(), tangent.clone())]);
        let names: Vec<&str> = data.scalars.iter().map(|(n, _)| n.as_str()).collect();
        assert_eq!(names, ["magnitude", "divergence", "curl", "energy"]);
        assert!(data
            .scalars
            .iter()
            .all(|(_, v)| v.len() == mesh.face_count()));
        let lines = streamline_polylines(&mesh, &tangent, 50).unwrap();
        assert!(lines.iter().any(|l| l.len() >= 2));
    }
}
