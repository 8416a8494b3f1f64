//! The core suite on meshes with boundary, for one catalog entry (of any catalog) and one
//! boundary condition
//! ([`open_mesh_suite`]), and the boundary behaviour of eigenfields
//! ([`check_essential_boundary_conditions`]).

use crate::algebra_checks::{
    check_d1_d0_zero, check_nodes_and_masses, measure_psd_operators_with,
    measure_symmetric_operators_with,
};
use crate::capability_checks::{check_point_evaluation, check_relative_sampling, check_sampling};
use crate::check_cache::CheckCache;
use crate::check_outcome::assert_outcomes;
use crate::corpus::{Corpus, CorpusMesh, DENSE_LIMIT, EIGENVECTOR_LIMIT};
use crate::decomposition_checks::{
    check_hodge_decomposition_with, check_kernel_is_2g_dense_with, check_kernel_is_2g_sparse_with,
};
use crate::spectral_checks::{
    check_basis_orthonormal_with, check_lemma1_with, check_spectrum_union_with,
    lemma1_eigenfields_of,
};
use tvf_core::discretization::{
    BoundaryCondition, DiscretizationError, HodgeComplex, HodgeOperators, NodeKind,
};
use tvf_core::geometry::{dot, norm, sub};
use tvf_core::mesh::Mesh;
use tvf_core::TriangleMesh;
use tvf_discretizations::CatalogEntry;

/// Runs every core check on every mesh of the open corpus of catalog entry `entry` (and the raw
/// `bunny.obj` where present, sparse checks only) with boundary condition `boundary`: shapes and
/// masses, `d1 d0 = 0`, symmetry, semi-definiteness, capabilities, the Hodge decomposition, `dim
/// ker L = 2g + b − 1` per component (dense and by harmonic projection), the spectrum union,
/// Lemma 1, the complete orthonormal basis, the essential boundary conditions and, for relative
/// forms, fields that vanish on the boundary edges and sample normal to the boundary. If the entry
/// does not offer `boundary`, checks that construction fails with
/// [`DiscretizationError::UnsupportedBoundaryCondition`] instead.
pub fn open_mesh_suite(entry: &CatalogEntry, boundary: BoundaryCondition) {
    let id = entry.id();
    let corpus = Corpus::open_for_catalog_entry(entry);
    for mesh in corpus.meshes(true) {
        eprintln!(
            "checking {id} ({}) on {} ({} faces)",
            boundary.name(),
            mesh.name,
            mesh.mesh.face_count()
        );
        let built = entry.build_with(&tvf_core::SurfaceMesh::from(mesh.mesh.clone()), boundary);
        if !entry.boundary_conditions().contains(&boundary) {
            match built {
                Err(DiscretizationError::UnsupportedBoundaryCondition { .. }) => continue,
                Err(e) => panic!("{}: unexpected error {e}", mesh.name),
                Ok(_) => panic!("{}: {id} built with unsupported {boundary:?}", mesh.name),
            }
        }
        let complex = built.unwrap_or_else(|e| panic!("{}: {e}", mesh.name));
        let complex = complex.as_ref();
        assert_eq!(complex.id(), format!("{id}+{}", boundary.name()), "id");
        assert_eq!(complex.topology().boundary_condition, boundary);
        run_core_checks(complex, &mesh);
    }
}

/// Every core check of `complex` on `mesh`, the spectra, eigenfields and decomposer they share
/// computed once ([`CheckCache`]).
fn run_core_checks(complex: &dyn HodgeComplex, mesh: &CorpusMesh) {
    let cache = CheckCache::new(complex);
    check_operator_algebra_with(&cache, mesh);
    check_sampling(complex, mesh);
    check_relative_sampling(complex, mesh);
    check_point_evaluation(complex, mesh);
    check_decomposition_and_spectrum_with(&cache, mesh);
    if complex.field_dimension() <= EIGENVECTOR_LIMIT {
        check_essential_boundary_conditions_with(&cache, mesh);
    }
}

/// The core checks before the capability checks, on a mesh of any kind: shapes and masses,
/// `d1 d0 = 0`, symmetric operators.
pub fn check_operator_algebra<M: Mesh>(complex: &dyn HodgeComplex, mesh: &CorpusMesh<M>) {
    check_operator_algebra_with(&CheckCache::new(complex), mesh);
}

/// [`check_operator_algebra`], a composed `S` formed once for these and the later checks of
/// `cache`.
pub fn check_operator_algebra_with<M: Mesh>(
    cache: &CheckCache<'_, dyn HodgeComplex + '_>,
    mesh: &CorpusMesh<M>,
) {
    let complex = cache.complex();
    check_nodes_and_masses(complex, mesh);
    check_d1_d0_zero(complex);
    assert_outcomes(&measure_symmetric_operators_with(cache));
}

/// The core checks after the capability checks, on a mesh of any kind: the Hodge decomposition,
/// `dim ker L` by harmonic projection; up to [`DENSE_LIMIT`] field nodes semi-definiteness, the
/// dense kernel and the spectrum union; up to [`EIGENVECTOR_LIMIT`] Lemma 1, the complete
/// orthonormal basis and fields that vanish on fixed nodes.
pub fn check_decomposition_and_spectrum<M: Mesh>(complex: &dyn HodgeComplex, mesh: &CorpusMesh<M>) {
    check_decomposition_and_spectrum_with(&CheckCache::new(complex), mesh);
}

/// [`check_decomposition_and_spectrum`], each spectrum, the eigenfields and the decomposer
/// computed once for all of these checks (and those of `cache` before and after).
pub fn check_decomposition_and_spectrum_with<M: Mesh>(
    cache: &CheckCache<'_, dyn HodgeComplex + '_>,
    mesh: &CorpusMesh<M>,
) {
    check_hodge_decomposition_with(cache, 17);
    check_kernel_is_2g_sparse_with(cache, mesh, 23);
    let n1 = cache.complex().field_dimension();
    if n1 <= DENSE_LIMIT {
        assert_outcomes(&measure_psd_operators_with(cache));
        check_kernel_is_2g_dense_with(cache, mesh);
        check_spectrum_union_with(cache, mesh);
    }
    if n1 <= EIGENVECTOR_LIMIT {
        check_lemma1_with(cache);
        check_basis_orthonormal_with(cache, 29);
        check_fields_vanish_on_fixed_nodes_with(cache);
    }
}

/// Every boundary edge `(a, b)` of `mesh` as its one face and its unit direction from vertex `a`
/// to vertex `b` (`a < b`), in edge order.
pub fn boundary_edge_directions(mesh: &TriangleMesh) -> Vec<(usize, [f64; 3])> {
    mesh.boundary_edges()
        .into_iter()
        .map(|e| {
            let [a, b] = mesh.edges()[e];
            let t = mesh.edge_faces()[e]
                .into_iter()
                .find(|&t| t < mesh.face_count())
                .expect("a boundary edge has one face");
            let d = sub(mesh.positions()[b], mesh.positions()[a]);
            (t, d.map(|x| x / norm(d)))
        })
        .collect()
}

/// Where the complex fixes field nodes (relative forms: boundary edges), every eigenfield of
/// Lemma 1 and every harmonic basis field is zero there, to round-off (`1e-12` of its largest
/// coefficient); at least one field is checked.
pub fn check_fields_vanish_on_fixed_nodes(complex: &dyn HodgeComplex) {
    check_fields_vanish_on_fixed_nodes_with(&CheckCache::new(complex));
}

/// [`check_fields_vanish_on_fixed_nodes`] with the eigenfields and the decomposer of `cache`.
pub fn check_fields_vanish_on_fixed_nodes_with(cache: &CheckCache<'_, dyn HodgeComplex + '_>) {
    let complex = cache.complex();
    let nodes = complex.field_nodes();
    if nodes.dirichlet_count() == 0 {
        return;
    }
    let mut fields: Vec<Vec<f64>> = lemma1_eigenfields_of(cache)
        .iter()
        .map(|(_, u)| u.clone())
        .collect();
    fields.extend(
        cache
            .decomposer()
            .unwrap_or_else(|e| panic!("decomposer factors: {e}"))
            .harmonic_basis(31)
            .expect("harmonic basis"),
    );
    assert!(!fields.is_empty(), "no field to check");
    for (k, field) in fields.iter().enumerate() {
        let largest = field.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        let on_fixed = (0..field.len())
            .filter(|&i| nodes.dirichlet[i])
            .fold(0.0f64, |m, i| m.max(field[i].abs()));
        assert!(
            on_fixed <= 1e-12 * largest,
            "field {k} has {on_fixed:e} on a fixed field node (largest {largest:e})"
        );
    }
}

/// The boundary conditions that hold pointwise (essential ones): where a space is P1 with zero
/// boundary values (`S_h,0`, Dirichlet nodes on vertices), a function of it vanishes along every
/// boundary edge, so its gradient is normal to the edge. Hence every integrable eigenfield
/// `d0 φ / √λ` of a complex whose potentials are `S_h,0` is **normal** to each boundary edge, and
/// every co-integrable eigenfield `−M1⁻¹ d1ᵀ ψ / √μ = J ∇ψ / √μ` of a complex whose co-potentials
/// are `S_h,0` is **tangential** to it — to round-off: the component along (resp. across) the
/// edge is at most `1e-10` times the field's largest vector. Checked through sampling at the
/// centroid of the boundary face, for complexes with face-frame fields. (Natural conditions —
/// Neumann potentials, Crouzeix–Raviart values fixed at midpoints only — hold weakly and are not
/// pointwise.)
pub fn check_essential_boundary_conditions(complex: &dyn HodgeComplex, mesh: &CorpusMesh) {
    check_essential_boundary_conditions_with(&CheckCache::new(complex), mesh);
}

/// [`check_essential_boundary_conditions`] with the eigenfields of `cache`.
pub fn check_essential_boundary_conditions_with(
    cache: &CheckCache<'_, dyn HodgeComplex + '_>,
    mesh: &CorpusMesh,
) {
    let complex = cache.complex();
    let Some(sampling) = complex.sampling() else {
        return;
    };
    if complex.field_nodes().kind != NodeKind::FaceFrames {
        return;
    }
    let mesh = &mesh.mesh;
    let vertex_dirichlet = |nodes: &tvf_core::discretization::NodeSpace| {
        nodes.kind == NodeKind::Vertices && nodes.dirichlet_count() > 0
    };
    let integrable_normal = vertex_dirichlet(complex.potential_nodes());
    let cointegrable_tangential = vertex_dirichlet(complex.co_potential_nodes());
    if !integrable_normal && !cointegrable_tangential {
        return;
    }
    let fields = lemma1_eigenfields_of(cache);
    let integrable_count = {
        let p = complex.potential_nodes();
        p.free_count() - p.kernel_dimension()
    };
    let boundary = boundary_edge_directions(mesh);
    let mut checked = 0;
    for (k, (lambda, field)) in fields.iter().enumerate() {
        let integrable = k < integrable_count;
        if !((integrable && integrable_normal) || (!integrable && cointegrable_tangential)) {
            continue;
        }
        let vectors = sampling.to_face_vectors(field).expect("field length");
        let largest = vectors.iter().fold(0.0f64, |m, v| m.max(norm(*v)));
        for &(t, tangent) in &boundary {
            let v = vectors[t];
            let along = dot(v, tangent).abs();
            let normal = sampling.normal(t);
            let across_direction = tvf_core::geometry::cross(normal, tangent);
            let across = dot(v, across_direction).abs();
            let (what, value) = if integrable {
                ("tangential component of an integrable eigenfield", along)
            } else {
                ("normal component of a co-integrable eigenfield", across)
            };
            assert!(
                value <= 1e-10 * largest,
                "{what} (λ = {lambda}) on boundary face {t}: {value:e} (largest {largest:e})"
            );
        }
        checked += 1;
    }
    assert!(
        checked > 0,
        "no eigenfield with an essential boundary condition"
    );
}
