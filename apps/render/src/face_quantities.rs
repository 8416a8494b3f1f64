//! Per-face scalars of a tangent field for colour maps and exports: magnitude, divergence,
//! curl and Dirichlet energy density, computed through the discretization traits so that they
//! follow the chosen decomposition.
//!
//! - **divergence**: the complex's own pointwise divergence `−M0⁻¹ d0ᵀ M1 x` (conforming: `div_h`
//!   at vertices; nonconforming: `div*_h` at edge midpoints), evaluated at each face's centroid
//!   by the potential space's interpolation (the mean of the face's three nodal values, for P1
//!   and for Crouzeix–Raviart alike). Pointwise, units 1/length × field.
//! - **curl**: likewise the complex's own pointwise curl `M2 d1 x` in the co-potential space
//!   (conforming: `curl*_h` at edge midpoints), at the centroid.
//! - **energy**: the Dirichlet energy density `ρ_t = mean_{i∈t} div_i² + mean_{j∈t} curl_j²`
//!   (pointwise, units 1/length² × field²). With barycentric lumping `Σ_t A_t ρ_t = xᵀ S x`
//!   exactly, because `xᵀ S x = Σ_i M0_i div_i² + Σ_j M2_j⁻¹ curl_j²` and each node's lumped mass is
//!   a third of its faces' areas; with Voronoi lumping the sum is an approximation.

use tvf_core::discretization::{
    DiscretizationError, HodgeComplex, HodgeOperators, PointEvaluation,
};
use tvf_core::geometry::norm;
use tvf_core::SurfaceMesh;

/// Which per-face scalar colours the surface.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FaceQuantity {
    /// Length of the field vector.
    Magnitude,
    /// Pointwise divergence at the face centroid.
    Divergence,
    /// Pointwise curl at the face centroid.
    Curl,
    /// Dirichlet energy density.
    Energy,
    /// No colour map (shaded grey).
    None,
}

impl FaceQuantity {
    /// Every quantity, in the order of [`FaceQuantity::NAMES`].
    pub const ALL: [FaceQuantity; 5] = [
        FaceQuantity::Magnitude,
        FaceQuantity::Divergence,
        FaceQuantity::Curl,
        FaceQuantity::Energy,
        FaceQuantity::None,
    ];

    /// The names command lines and files use, [`FaceQuantity::label`] of [`FaceQuantity::ALL`].
    pub const NAMES: [&'static str; 5] = ["magnitude", "divergence", "curl", "energy", "none"];

    /// The quantity called `name` (one of [`FaceQuantity::NAMES`]).
    pub fn from_name(name: &str) -> Option<FaceQuantity> {
        Self::ALL.into_iter().find(|q| q.label() == name)
    }

    /// Label for colour bars and exports.
    pub fn label(self) -> &'static str {
        match self {
            FaceQuantity::Magnitude => "magnitude",
            FaceQuantity::Divergence => "divergence",
            FaceQuantity::Curl => "curl",
            FaceQuantity::Energy => "energy",
            FaceQuantity::None => "none",
        }
    }

    /// Whether the quantity is signed (diverging colour map).
    pub fn is_signed(self) -> bool {
        matches!(self, FaceQuantity::Divergence | FaceQuantity::Curl)
    }
}

/// Which space a nodal function lives in.
#[derive(Clone, Copy)]
enum Space {
    Potentials,
    CoPotentials,
}

/// Values at each face's centroid of `mesh` of a nodal function of `space` (`F` entries).
fn at_centroids(
    evaluation: &dyn PointEvaluation,
    space: Space,
    nodal: &[f64],
    mesh: &SurfaceMesh,
) -> Vec<f64> {
    (0..mesh.face_count())
        .map(|t| {
            let centroid = mesh.centroid_point(t);
            let weights = match space {
                Space::Potentials => evaluation.potential_weights(&centroid),
                Space::CoPotentials => evaluation.co_potential_weights(&centroid),
            };
            weights.iter().map(|&(i, w)| w * nodal[i]).sum()
        })
        .collect()
}

/// Nodal pointwise divergence of `field` in the potential space (`n0` values).
fn nodal_divergence<H: HodgeComplex + ?Sized>(complex: &H, field: &[f64]) -> Vec<f64> {
    complex.potential_divergence().apply(field)
}

/// Nodal pointwise curl of `field` in the co-potential space (`n2` values).
fn nodal_curl<H: HodgeComplex + ?Sized>(complex: &H, field: &[f64]) -> Vec<f64> {
    complex.co_potential_curl().apply(field)
}

/// The per-face scalar `kind` of `field` (`n1` coefficients of the complex, built on `mesh`)
/// whose 3D vectors at the face centroids are `vectors`; `None` for [`FaceQuantity::None`].
/// Divergence, curl and energy need the complex's point evaluation.
pub fn face_scalar<H: HodgeComplex + ?Sized>(
    complex: &H,
    mesh: &SurfaceMesh,
    kind: FaceQuantity,
    field: &[f64],
    vectors: &[[f64; 3]],
) -> Result<Option<Vec<f64>>, DiscretizationError> {
    Ok(match kind {
        FaceQuantity::Magnitude => Some(vectors.iter().map(|&v| norm(v)).collect()),
        FaceQuantity::Divergence => Some(at_centroids(
            complex.require_point_evaluation()?,
            Space::Potentials,
            &nodal_divergence(complex, field),
            mesh,
        )),
        FaceQuantity::Curl => Some(at_centroids(
            complex.require_point_evaluation()?,
            Space::CoPotentials,
            &nodal_curl(complex, field),
            mesh,
        )),
        FaceQuantity::Energy => Some(energy_density(complex, field, mesh)?),
        FaceQuantity::None => None,
    })
}

/// Dirichlet energy density per face of `mesh` (see the module documentation).
pub fn energy_density<H: HodgeComplex + ?Sized>(
    complex: &H,
    field: &[f64],
    mesh: &SurfaceMesh,
) -> Result<Vec<f64>, DiscretizationError> {
    let evaluation = complex.require_point_evaluation()?;
    let div2: Vec<f64> = nodal_divergence(complex, field)
        .iter()
        .map(|x| x * x)
        .collect();
    let curl2: Vec<f64> = nodal_curl(complex, field).iter().map(|x| x * x).collect();
    let a = at_centroids(evaluation, Space::Potentials, &div2, mesh);
    let b = at_centroids(evaluation, Space::CoPotentials, &curl2, mesh);
    Ok(a.iter().zip(&b).map(|(x, y)| x + y).collect())
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;
    use tvf_core::generate::{icosphere, torus};
    use tvf_discretizations::{catalog_entry, BoxedComplex};

    fn random_field(n: usize) -> Vec<f64> {
        let mut rng = ChaCha8Rng::seed_from_u64(4);
        (0..n).map(|_| rng.random_range(-1.0..1.0)).collect()
    }

    fn build(id: &str, mesh: &SurfaceMesh) -> BoxedComplex {
        catalog_entry(id).unwrap().build(mesh).unwrap()
    }

    fn check_energy(complex: &dyn HodgeComplex, mesh: &SurfaceMesh) {
        let field = random_field(complex.field_dimension());
        let density = energy_density(complex, &field, mesh).unwrap();
        let integrated: f64 = density
            .iter()
            .enumerate()
            .map(|(t, r)| r * mesh.face_area(t))
            .sum();
        let exact: f64 = field
            .iter()
            .zip(complex.dirichlet_energy().apply(&field))
            .map(|(a, b)| a * b)
            .sum();
        assert!(
            (integrated - exact).abs() <= 1e-9 * exact,
            "{}: Σ A ρ = {integrated}, xᵀSx = {exact}",
            complex.id()
        );
    }

    #[test]
    fn energy_density_integrates_to_the_dirichlet_energy() {
        let torus = SurfaceMesh::from(torus(1.0, 0.4, 16, 8).unwrap());
        for id in ["conforming-barycentric", "nonconforming-barycentric"] {
            check_energy(build(id, &torus).as_ref(), &torus);
        }
        // DEC needs a Delaunay mesh (the quad-grid torus has ⋆1 = 0 on its diagonals).
        let sphere = SurfaceMesh::from(icosphere(2));
        check_energy(build("dec-barycentric", &sphere).as_ref(), &sphere);
    }

    fn check_gradients(complex: &dyn HodgeComplex, mesh: &SurfaceMesh) {
        let sampling = complex.require_sampling().unwrap();
        let potential: Vec<f64> = complex
            .potential_nodes()
            .positions
            .iter()
            .map(|p| p[0] * p[2])
            .collect();
        let gradient = complex.gradient_field(&potential);
        let vectors = sampling.to_face_vectors(&gradient).unwrap();
        let curl = face_scalar(complex, mesh, FaceQuantity::Curl, &gradient, &vectors)
            .unwrap()
            .unwrap();
        let div = face_scalar(complex, mesh, FaceQuantity::Divergence, &gradient, &vectors)
            .unwrap()
            .unwrap();
        let largest = div.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        assert!(
            largest > 0.1,
            "{}: the gradient of x·z has divergence",
            complex.id()
        );
        assert!(curl.iter().all(|c| c.abs() <= 1e-10 * largest));
        // A co-gradient −M1⁻¹ d1ᵀ g has no divergence but a curl.
        let co_potential: Vec<f64> = complex
            .co_potential_nodes()
            .positions
            .iter()
            .map(|p| p[0] * p[2])
            .collect();
        let rotated = complex.co_gradient_field(&co_potential);
        let vectors = sampling.to_face_vectors(&rotated).unwrap();
        let div = face_scalar(complex, mesh, FaceQuantity::Divergence, &rotated, &vectors)
            .unwrap()
            .unwrap();
        let curl = face_scalar(complex, mesh, FaceQuantity::Curl, &rotated, &vectors)
            .unwrap()
            .unwrap();
        let largest = curl.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        assert!(largest > 0.1, "{}: the co-gradient has curl", complex.id());
        assert!(div.iter().all(|d| d.abs() <= 1e-10 * largest));
    }

    #[test]
    fn gradients_have_no_curl_and_co_gradients_no_divergence() {
        let torus = SurfaceMesh::from(torus(1.0, 0.4, 16, 8).unwrap());
        check_gradients(build("conforming-barycentric", &torus).as_ref(), &torus);
        check_gradients(build("nonconforming-voronoi", &torus).as_ref(), &torus);
        let sphere = SurfaceMesh::from(icosphere(2));
        check_gradients(build("dec-circumcentric", &sphere).as_ref(), &sphere);
        // Polygonal DEC on quads: gradients of x·z have no curl either.
        let quads = SurfaceMesh::from(tvf_core::generate::quad_torus(1.0, 0.4, 16, 8).unwrap());
        check_gradients(build("polygon-dec", &quads).as_ref(), &quads);
    }
}
