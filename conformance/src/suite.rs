//! The core suite: one function per test of [`crate::conformance_suite!`], each running one group
//! of core checks on every mesh of a corpus. Every complex must pass all of them.

use crate::accuracy::{accuracy_report, AccuracyRequest};
use crate::algebra_checks::{
    check_d1_d0_zero, check_nodes_and_masses, check_psd_operators, check_symmetric_operators,
};
use crate::capability_checks::{check_point_evaluation, check_sampling};
use crate::check_cache::CheckCache;
use crate::check_outcome::assert_outcomes;
use crate::corpus::{Corpus, CorpusMesh, DENSE_LIMIT, EIGENVECTOR_LIMIT};
use crate::decomposition_checks::{
    check_hodge_decomposition, check_hodge_decomposition_with, check_kernel_is_2g_dense,
    check_kernel_is_2g_dense_with, check_kernel_is_2g_sparse,
};
use crate::property_runner::{run_property, Counterexample, PropertyRequest};
use crate::spectral_checks::{
    check_basis_orthonormal, check_lemma1, check_rigid_motion_invariance, check_spectrum_union,
    check_spectrum_union_with,
};
use crate::strategies::MeshNeeds;
use crate::{build, for_each_mesh, Constructor};
use tvf_core::discretization::{HodgeComplex, HodgeOperators};
use tvf_core::mesh::Mesh;
use tvf_core::SurfaceMesh;

/// Cases per property of a suite line unless its `cases = N` says otherwise.
pub const DEFAULT_CASES: u32 = 64;

/// Seed of the mesh draws of [`generated_meshes`] (fixed: the suite is deterministic).
pub const GENERATED_MESHES_SEED: u64 = 2017;

/// The cases a property of a suite line runs: `cases`, lowered to proptest's default count when
/// that is smaller (proptest reads it from the environment variable `PROPTEST_CASES`; unset it
/// is 256), so that a quick run can ask for fewer.
pub fn property_cases(cases: u32) -> u32 {
    cases.min(proptest::test_runner::Config::default().cases)
}

/// Runs `check` on every mesh of `corpus` (and the shared meshes if `with_shared`) whose complex
/// has at most `limit` field coefficients.
fn for_each_complex(
    constructor: Constructor,
    corpus: Corpus,
    with_shared: bool,
    limit: usize,
    mut check: impl FnMut(&dyn HodgeComplex, &CorpusMesh),
) {
    for_each_mesh(corpus, with_shared, |mesh| {
        let complex = build(constructor, mesh);
        if complex.field_dimension() <= limit {
            check(complex.as_ref(), mesh);
        } else {
            eprintln!("  (too large for this dense check)");
        }
    });
}

/// Shapes, nodes, topology, positive definite masses and `1ᵀ M0 1 = area`
/// ([`check_nodes_and_masses`]).
pub fn nodes_and_masses(constructor: Constructor, corpus: Corpus) {
    for_each_complex(constructor, corpus, true, usize::MAX, |c, m| {
        check_nodes_and_masses(c, m)
    });
}

/// `d1 d0 = 0` and integrable ⟂ co-integrable ([`check_d1_d0_zero`]).
pub fn d1_d0_is_zero(constructor: Constructor, corpus: Corpus) {
    for_each_complex(constructor, corpus, true, usize::MAX, |c, _| {
        check_d1_d0_zero(c)
    });
}

/// `S`, `B` and both stiffness matrices symmetric ([`check_symmetric_operators`]).
pub fn symmetric_operators(constructor: Constructor, corpus: Corpus) {
    for_each_complex(constructor, corpus, true, usize::MAX, |c, _| {
        check_symmetric_operators(c)
    });
}

/// `S`, `B` and both scalar eigenproblems positive semi-definite, dense
/// ([`check_psd_operators`]).
pub fn positive_semidefinite_operators(constructor: Constructor, corpus: Corpus) {
    for_each_complex(constructor, corpus, false, DENSE_LIMIT, |c, _| {
        check_psd_operators(c)
    });
}

/// Sampling and point evaluation, where offered ([`check_sampling`],
/// [`check_point_evaluation`]).
pub fn capabilities(constructor: Constructor, corpus: Corpus) {
    for_each_complex(constructor, corpus, true, usize::MAX, |c, m| {
        check_sampling(c, m);
        check_point_evaluation(c, m);
    });
}

/// The Hodge decomposition of a random and of a composed field
/// ([`check_hodge_decomposition`]).
pub fn hodge_decomposition(constructor: Constructor, corpus: Corpus) {
    for_each_complex(constructor, corpus, true, usize::MAX, |c, _| {
        check_hodge_decomposition(c, 17)
    });
}

/// `dim ker L = 2g`, dense ([`check_kernel_is_2g_dense`]).
pub fn kernel_is_2g_dense(constructor: Constructor, corpus: Corpus) {
    for_each_complex(constructor, corpus, false, DENSE_LIMIT, |c, m| {
        check_kernel_is_2g_dense(c, m)
    });
}

/// `dim ker L = 2g` per component through harmonic projections, any size
/// ([`check_kernel_is_2g_sparse`]).
pub fn kernel_is_2g_by_harmonic_projection(constructor: Constructor, corpus: Corpus) {
    for_each_complex(constructor, corpus, true, usize::MAX, |c, m| {
        check_kernel_is_2g_sparse(c, m, 23)
    });
}

/// Spectrum of `L` = union of the two scalar spectra + `2g` zeros, dense
/// ([`check_spectrum_union`]).
pub fn spectrum_is_union_of_scalar_spectra(constructor: Constructor, corpus: Corpus) {
    for_each_complex(constructor, corpus, false, DENSE_LIMIT, |c, m| {
        check_spectrum_union(c, m)
    });
}

/// Lemma 1 eigenfields, dense ([`check_lemma1`]).
pub fn lemma1_eigenfields(constructor: Constructor, corpus: Corpus) {
    for_each_complex(constructor, corpus, false, EIGENVECTOR_LIMIT, |c, _| {
        check_lemma1(c)
    });
}

/// The assembled eigenfield + harmonic basis is complete and orthonormal, dense
/// ([`check_basis_orthonormal`]).
pub fn basis_is_orthonormal(constructor: Constructor, corpus: Corpus) {
    for_each_complex(constructor, corpus, false, EIGENVECTOR_LIMIT, |c, _| {
        check_basis_orthonormal(c, 29)
    });
}

/// The complexes of [`Corpus::motion_meshes`] and of their copies moved by the rotation of
/// `angle` about `axis` and the translation `translation` have equal stiffness matrices, masses
/// and spectra ([`check_rigid_motion_invariance`]).
pub fn rigid_motion_invariance(
    constructor: Constructor,
    corpus: Corpus,
    axis: [f64; 3],
    angle: f64,
    translation: [f64; 3],
) {
    for mesh in corpus.motion_meshes() {
        let moved = tvf_core::generate::rigid_motion(&mesh.mesh, axis, angle, translation)
            .expect("finite motion");
        let moved = CorpusMesh {
            name: format!("{} moved", mesh.name),
            mesh: moved,
            ..mesh.clone()
        };
        let original = build(constructor, &mesh);
        let moved = build(constructor, &moved);
        check_rigid_motion_invariance(original.as_ref(), moved.as_ref(), true);
    }
}

/// On the jittered mesh of [`Corpus::jittered_mesh`] for `seed`: `d1 d0 = 0`, masses, the kernel
/// (dense), the Hodge decomposition and the spectrum union.
pub fn jittered_mesh(constructor: Constructor, corpus: Corpus, seed: u64) {
    let mesh = corpus.jittered_mesh(seed);
    let complex = build(constructor, &mesh);
    let complex = complex.as_ref();
    // The spectrum of L is computed once for the kernel and the union.
    let cache = CheckCache::new(complex);
    check_d1_d0_zero(complex);
    check_nodes_and_masses(complex, &mesh);
    check_kernel_is_2g_dense_with(&cache, &mesh);
    check_hodge_decomposition_with(&cache, seed);
    check_spectrum_union_with(&cache, &mesh);
}

/// The core checks on `cases` meshes drawn from [`crate::strategies::mesh_specs`] (Delaunay ones
/// for the Delaunay corpora; closed and open ones); panics with the shrunk minimal failing mesh
/// and its failed checks.
pub fn generated_meshes(constructor: Constructor, corpus: Corpus, cases: u32) {
    let needs = MeshNeeds {
        delaunay: matches!(corpus, Corpus::Delaunay | Corpus::OpenDelaunay),
        closed_only: false,
    };
    let request = PropertyRequest::new(cases, GENERATED_MESHES_SEED, needs);
    let report = run_property(constructor, &request, &|_| {});
    if let Some(aborted) = report.aborted {
        panic!("the property run stopped: {aborted}");
    }
    panic_with_counterexample(report.counterexample, "mesh");
}

/// Panics with the shrunk minimal failing `what` (e.g. `"polygon mesh"`) of a property run, if
/// there is one: its face count, its name and its failed checks, one a line.
pub(crate) fn panic_with_counterexample<Spec, M: Mesh>(
    counterexample: Option<Counterexample<Spec, M>>,
    what: &str,
) {
    if let Some(counterexample) = counterexample {
        let failures = counterexample.report.failure_lines();
        panic!(
            "minimal failing {what} ({} faces): {}\n{}",
            counterexample.mesh.mesh.face_count(),
            counterexample.mesh.name,
            failures.join("\n")
        );
    }
}

/// The accuracy checks ([`accuracy_report`]) of the complexes `constructor` makes, on triangle
/// meshes (with boundary too): consistency on flat and curved patches, convergence on regular
/// and jittered refinements of the sphere and the hemisphere; panics naming every failed check
/// with its numbers.
pub fn accuracy(constructor: Constructor) {
    let builder = |mesh: &SurfaceMesh| match mesh.as_triangles() {
        Some(triangles) => constructor(triangles),
        None => Err("the suite line's constructor builds on triangle meshes".to_string()),
    };
    let report = accuracy_report(&builder, &AccuracyRequest::new(false));
    for outcome in &report.outcomes {
        eprintln!(
            "  {} {}: {:.3e} ({})",
            outcome.status.name(),
            outcome.name,
            outcome.measured,
            outcome.detail
        );
    }
    assert_outcomes(&report.outcomes);
}
