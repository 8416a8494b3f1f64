//! A discretization of your own in tvf's catalog, with every `tvf` command for it.
//!
//! The entry: the paper's conforming decomposition (P1 potentials, face fields,
//! Crouzeix–Raviart co-potentials) with **blended mass lumping** — each lumped mass the blend
//! `(1 − t) · barycentric + t · Voronoi` of tvf's two lumpings, `t ∈ [0, 1]`:
//!
//! - `M0 = (1 − t) · (barycentric vertex areas) + t · (mixed-Voronoi vertex areas)` (diagonal,
//!   area);
//! - the co-potential mass `(1 − t) · (barycentric edge areas) + t · (midpoint-Voronoi edge
//!   areas)` (diagonal, area), `M2` its inverse;
//! - `M1` the face areas (twice per face), which neither lumping changes;
//! - `d0`, `d1`, sampling and boundary conditions those of `conforming-barycentric`.
//!
//! `t = 0` is `conforming-barycentric`, `t = 1` is `conforming-voronoi`. The parameter is part
//! of the id, in percent: `blend-lumping-50` is `t = 0.5` (ids are kebab-case; basis files and
//! cache names carry them, so bases of different `t` never mix). This program registers
//! `t = 0.25, 0.5, 0.75` in the built-in catalog and runs tvf's command line with it:
//!
//! ```text
//! tvf-example-own-discretization discretizations
//! tvf-example-own-discretization spectrum mesh.obj -k 20 --discretization blend-lumping-50
//! tvf-example-own-discretization edit mesh.obj --discretization blend-lumping-25
//! ```
//!
//! A second entry, `dec-length-star` ([`length_star`]), is DEC-like: tvf's primal forms
//! (incidences, nodes, boundary conditions, Whitney sampling) with Hodge stars this crate
//! computes itself, from the edge lengths.
//!
//! Its tests: the conformance suite on each entry in one line (below; the accuracy checks
//! included), and every command run through the binary (`tests/commands.rs`).
#![forbid(unsafe_code)]

pub mod length_star;

use sprs::CsMat;
use std::process::ExitCode;
use tvf_core::discretization::{BoundaryCondition, DiscretizationError, NodeKind};
use tvf_core::TriangleMesh;
use tvf_discretizations::face_geometry::FaceGeometry;
use tvf_discretizations::{
    complex_id, BoxedComplex, Catalog, CatalogEntry, CrouzeixRaviart, FaceFields,
    FiniteElementComplex, FunctionSpace, LagrangeP1, MassLumping,
};

/// The blends this program registers, in percent of Voronoi.
const REGISTERED_PERCENTS: [u8; 3] = [25, 50, 75];

fn main() -> ExitCode {
    let mut catalog = Catalog::builtin();
    let entries = REGISTERED_PERCENTS
        .into_iter()
        .map(blend_lumping)
        .chain([length_star::length_star_entry()]);
    for entry in entries {
        if let Err(error) = catalog.add(entry) {
            eprintln!("error: {error}");
            return ExitCode::FAILURE;
        }
    }
    tvf_cli::run(catalog)
}

/// The catalog entry `blend-lumping-{percent}`: the conforming complex with every lumped mass
/// blended as `(1 − t) · barycentric + t · Voronoi`, `t = percent / 100`. Offers both boundary
/// conditions, as `conforming-barycentric` does. Panics if `percent > 100`.
pub fn blend_lumping(percent: u8) -> CatalogEntry {
    assert!(
        percent <= 100,
        "a blend is at most 100 % Voronoi, not {percent} %"
    );
    let id = format!("blend-lumping-{percent}");
    let t = f64::from(percent) / 100.0;
    let entry_id = id.clone();
    CatalogEntry::new(
        id,
        format!(
            "the conforming decomposition with lumped masses {:.2} · barycentric + {t:.2} · \
             Voronoi (vertex and edge masses; example crate own-discretization)",
            1.0 - t
        ),
        move |mesh, boundary| -> Result<BoxedComplex, _> {
            Ok(Box::new(blended_complex(&entry_id, mesh, boundary, t)?))
        },
    )
    .with_boundary_condition(
        BoundaryCondition::Tangential,
        "Crouzeix–Raviart co-potentials zero at boundary edge midpoints",
    )
    .with_boundary_condition(
        BoundaryCondition::Normal,
        "P1 potentials zero at boundary vertices",
    )
}

/// The conforming complex of `mesh` with masses blended by `t`, under the id the catalog
/// expects of entry `entry_id` ([`complex_id`]: `{entry_id}+{boundary}` on a mesh with
/// boundary).
fn blended_complex(
    entry_id: &str,
    mesh: &TriangleMesh,
    boundary: BoundaryCondition,
    t: f64,
) -> Result<FiniteElementComplex<Blended<LagrangeP1>, Blended<CrouzeixRaviart>>, DiscretizationError>
{
    let geometry = FaceGeometry::new(mesh)?;
    let p1 = |lumping| LagrangeP1::from_geometry(mesh, &geometry, lumping);
    let cr = |lumping| CrouzeixRaviart::from_geometry(mesh, &geometry, lumping);
    FiniteElementComplex::from_spaces_with_boundary(
        complex_id(entry_id, mesh.topology(), boundary),
        mesh,
        Blended::new(p1(MassLumping::Barycentric), &p1(MassLumping::Voronoi), t),
        Blended::new(cr(MassLumping::Barycentric), &cr(MassLumping::Voronoi), t),
        FaceFields::from_geometry(&geometry),
        boundary,
    )
}

/// A function space whose lumped mass is the blend `(1 − t) · barycentric + t · Voronoi` of the
/// same space under tvf's two lumpings; everything else (gradient, interpolation, nodes) is the
/// space's own, which the lumping does not change.
pub struct Blended<S> {
    space: S,
    mass: Vec<f64>,
}

impl<S: FunctionSpace> Blended<S> {
    /// Blends the masses of `barycentric` and `voronoi` (the same space, two lumpings).
    fn new(barycentric: S, voronoi: &S, t: f64) -> Self {
        let mass = barycentric
            .mass()
            .iter()
            .zip(voronoi.mass())
            .map(|(b, v)| (1.0 - t) * b + t * v)
            .collect();
        Self {
            space: barycentric,
            mass,
        }
    }
}

impl<S: FunctionSpace> FunctionSpace for Blended<S> {
    fn name(&self) -> &str {
        self.space.name()
    }
    fn node_kind(&self) -> NodeKind {
        self.space.node_kind()
    }
    fn dimension(&self) -> usize {
        self.space.dimension()
    }
    fn mass(&self) -> &[f64] {
        &self.mass
    }
    fn gradient(&self) -> &CsMat<f64> {
        self.space.gradient()
    }
    fn interpolation_weights(&self, face: usize, barycentric: [f64; 3]) -> Vec<(usize, f64)> {
        self.space.interpolation_weights(face, barycentric)
    }
    fn node_positions(&self) -> Vec<[f64; 3]> {
        self.space.node_positions()
    }
    fn node_components(&self) -> &[usize] {
        self.space.node_components()
    }
    fn component_count(&self) -> usize {
        self.space.component_count()
    }
}

// The whole conformance suite for the entry, closed meshes and both boundary conditions on
// meshes with boundary: one line.
#[cfg(test)]
tvf_conformance::conformance_suite!(blend_lumping_50, entry = blend_lumping(50));

#[cfg(test)]
tvf_conformance::conformance_suite!(dec_length_star, entry = length_star::length_star_entry());

#[cfg(test)]
mod tests {
    use super::*;
    use tvf_core::generate::{disk, genus_surface};
    use tvf_discretizations::build_complex;

    /// The diagonal of `M0` and of the co-potential mass `M2⁻¹` of `complex`.
    fn masses(complex: &BoxedComplex) -> (Vec<f64>, Vec<f64>) {
        let m0 = complex
            .m0()
            .diagonal_values()
            .expect("a lumped M0")
            .to_vec();
        let m2_inverse = complex.m2().inverse_diagonal().expect("a lumped M2");
        (m0, m2_inverse)
    }

    #[test]
    fn masses_are_the_blend_of_the_two_lumpings() {
        for mesh in [genus_surface(1, 3), disk(3)] {
            let barycentric =
                masses(&build_complex("conforming-barycentric", None, &mesh).unwrap());
            let voronoi = masses(&build_complex("conforming-voronoi", None, &mesh).unwrap());
            for percent in [0, 30, 100] {
                let t = f64::from(percent) / 100.0;
                let blended = masses(&blend_lumping(percent).build(&mesh).unwrap());
                for (what, b, v, got) in [
                    ("M0", &barycentric.0, &voronoi.0, &blended.0),
                    ("M2⁻¹", &barycentric.1, &voronoi.1, &blended.1),
                ] {
                    assert_eq!(got.len(), b.len());
                    let differs = b.iter().zip(v).any(|(b, v)| (b - v).abs() > 1e-6 * b.abs());
                    assert!(differs, "{what}: the two lumpings agree on this mesh");
                    for i in 0..b.len() {
                        let expected = (1.0 - t) * b[i] + t * v[i];
                        assert!(
                            (got[i] - expected).abs() <= 1e-14 * expected.abs(),
                            "{what}[{i}] at t = {t}: {} against {expected}",
                            got[i]
                        );
                    }
                }
            }
        }
    }

    #[test]
    fn ids_carry_the_parameter_and_the_boundary_condition() {
        let entry = blend_lumping(75);
        assert_eq!(entry.id(), "blend-lumping-75");
        let closed = entry.build(&genus_surface(1, 3)).unwrap();
        assert_eq!(closed.id(), "blend-lumping-75");
        let open = entry
            .build_with(&disk(3), BoundaryCondition::Normal)
            .unwrap();
        assert_eq!(open.id(), "blend-lumping-75+normal");
        let catalog = Catalog::builtin().with(entry).unwrap();
        assert!(catalog.clone().with(blend_lumping(75)).is_err());
        assert_eq!(catalog.len(), Catalog::builtin().len() + 1);
    }
}
