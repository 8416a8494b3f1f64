//! The small torus the unit tests of this crate run on (12 × 6 quads, 144 faces, genus 1: two
//! harmonic fields) and a catalog entry built on it.

use tvf_core::generate::torus;
use tvf_core::SurfaceMesh;
use tvf_discretizations::{catalog_entry, BoxedComplex};

/// The torus of radii 1 and 0.4 with 12 × 6 quads, and the catalog entry `id` built on it.
pub fn torus_complex(id: &str) -> (SurfaceMesh, BoxedComplex) {
    let mesh = SurfaceMesh::from(torus(1.0, 0.4, 12, 6).unwrap());
    let complex = catalog_entry(id).unwrap().build(&mesh).unwrap();
    (mesh, complex)
}
