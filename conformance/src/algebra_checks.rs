//! Algebraic core checks: the complex property `d1 · d0 = 0`, shapes, nodes and masses
//! (positive diagonals, or sparse matrices positive definite on the free nodes), symmetry and
//! semi-definiteness of the derived operators.

use crate::check_cache::CheckCache;
use crate::check_outcome::{assert_outcomes, CheckOutcome};
use crate::corpus::{CorpusMesh, DENSE_LIMIT};
use crate::dense::{generalized_eigenvalues, restrict_to_free, DenseMass};
use faer::Mat;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use sprs::{CsMat, TriMat};
use tvf_core::discretization::sparse::{mul_transpose_vec, product, transpose};
use tvf_core::discretization::{
    HodgeComplex, HodgeOperators, LinearOperator, Mass, MassForm, MassStorage, NodeKind, NodeSpace,
    NO_COMPONENT,
};
use tvf_core::geometry::{add, cross, scale};
use tvf_core::mesh::Mesh;
use tvf_solvers::SparseCholesky;

/// Random probe vectors per check of an operator too large to form densely.
pub const PROBES: usize = 4;

/// Relative asymmetry allowed in a derived operator (round-off): `max |A − Aᵀ| ≤ this · max |A|`,
/// or on probes `|xᵀ A y − yᵀ A x| ≤ this · max(|x| |A y|, |y| |A x|)`.
pub const SYMMETRY_TOLERANCE: f64 = 1e-12;

/// Negative eigenvalue allowed in a positive semi-definite pencil, relative to the largest:
/// `λ_min ≥ −this · |λ_max|` (the dense eigensolver's round-off on the zero eigenvalues).
pub const SEMIDEFINITE_TOLERANCE: f64 = 1e-10;

/// `d1 · d0` and the cross products of the two families, relative to the product of the
/// factors' largest entries (round-off of exact integer or geometric cancellation).
pub const EXACTNESS_TOLERANCE: f64 = 1e-12;

/// Relative difference allowed between `1ᵀ M0 1` and the mesh's area.
pub const AREA_TOLERANCE: f64 = 1e-12;

/// Largest absolute entry of a sparse matrix (0 if empty).
pub fn max_abs(a: &CsMat<f64>) -> f64 {
    a.data().iter().fold(0.0, |m, x| m.max(x.abs()))
}

/// Largest absolute entry of a dense matrix (0 if empty).
pub fn max_abs_dense(a: &Mat<f64>) -> f64 {
    let mut largest = 0.0f64;
    for j in 0..a.ncols() {
        for i in 0..a.nrows() {
            largest = largest.max(a[(i, j)].abs());
        }
    }
    largest
}

fn max_abs_vec(x: &[f64]) -> f64 {
    x.iter().fold(0.0, |m, v| m.max(v.abs()))
}

fn norm(x: &[f64]) -> f64 {
    x.iter().map(|v| v * v).sum::<f64>().sqrt()
}

fn dot(x: &[f64], y: &[f64]) -> f64 {
    x.iter().zip(y).map(|(a, b)| a * b).sum()
}

/// `count` seeded random vectors of length `n`, uniform in `[−1, 1]`.
fn probes(n: usize, count: usize, seed: u64) -> Vec<Vec<f64>> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    (0..count)
        .map(|_| (0..n).map(|_| rng.random_range(-1.0..1.0)).collect())
        .collect()
}

/// `max |A − Aᵀ| ≤` [`SYMMETRY_TOLERANCE`] `· max |A|`, measured (a non-square matrix fails).
pub fn measure_symmetric(what: &str, a: &CsMat<f64>) -> CheckOutcome {
    let name = format!("symmetric: {what}");
    if a.rows() != a.cols() {
        return CheckOutcome::failed(name, format!("{what}: not square {:?}", a.shape()));
    }
    let asymmetry = largest_asymmetry(a);
    let limit = SYMMETRY_TOLERANCE * max_abs(a);
    let detail = format!(
        "{what}: asymmetry {asymmetry:e} vs max entry {:e}",
        max_abs(a)
    );
    CheckOutcome::at_most(name, asymmetry, limit, detail)
}

/// `max |A − Aᵀ|` of a square sparse matrix, row by row: row `i` of `A` minus row `i` of `Aᵀ`
/// accumulated in a dense row (the entries `a_ij − a_ji` of the difference, without forming it:
/// on the raw bunny's `B` forming `A − Aᵀ` was a fifth of an open-mesh test).
fn largest_asymmetry(a: &CsMat<f64>) -> f64 {
    let a = a.to_csr();
    let t = transpose(&a);
    let mut row = vec![0.0; a.cols()];
    let mut largest = 0.0f64;
    for (a_row, t_row) in a.outer_iterator().zip(t.outer_iterator()) {
        for (j, &v) in a_row.iter() {
            row[j] += v;
        }
        for (j, &v) in t_row.iter() {
            row[j] -= v;
        }
        for j in a_row.indices().iter().chain(t_row.indices()) {
            largest = largest.max(row[*j].abs());
            row[*j] = 0.0;
        }
    }
    largest
}

/// A derived operator is symmetric: a sparse matrix entry by entry ([`measure_symmetric`]); a
/// composed one formed densely when it has at most [`DENSE_LIMIT`] columns (`max |A − Aᵀ| ≤
/// tol · max |A|`, the same criterion), else on [`PROBES`] seeded random pairs `x`, `y`:
/// `|xᵀ A y − yᵀ A x| ≤ tol · max(|x| |A y|, |y| |A x|)` (the same relative round-off, measured
/// on products instead of entries); `tol` is [`SYMMETRY_TOLERANCE`].
pub fn measure_symmetric_operator(what: &str, a: &LinearOperator) -> CheckOutcome {
    measure_symmetric_operator_formed(what, a, None)
}

/// [`measure_symmetric_operator`], with the composed operator's dense form given if it was
/// formed already (`a.to_dense()`).
fn measure_symmetric_operator_formed(
    what: &str,
    a: &LinearOperator,
    formed: Option<&Mat<f64>>,
) -> CheckOutcome {
    if let Some(sparse) = a.as_sparse() {
        return measure_symmetric(what, sparse);
    }
    let name = format!("symmetric: {what}");
    let (rows, cols) = a.shape();
    if rows != cols {
        return CheckOutcome::failed(name, format!("{what}: not square {:?}", a.shape()));
    }
    if cols <= DENSE_LIMIT {
        let owned;
        let dense = match formed {
            Some(dense) => dense,
            None => {
                owned = a.to_dense();
                &owned
            }
        };
        let asymmetry = max_abs_dense(&(dense - dense.transpose()));
        let scale = max_abs_dense(dense);
        let detail = format!("{what} (dense): asymmetry {asymmetry:e} vs max entry {scale:e}");
        return CheckOutcome::at_most(name, asymmetry, SYMMETRY_TOLERANCE * scale, detail);
    }
    let vectors = probes(cols, 2 * PROBES, 0x5e11);
    // Every probe through the operator as one block: a mass inverse in it is one multi-column
    // solve instead of one solve per probe.
    let block = Mat::from_fn(cols, vectors.len(), |i, j| vectors[j][i]);
    let applied = a.apply_block(block.as_ref());
    let products: Vec<Vec<f64>> = (0..vectors.len())
        .map(|j| (0..rows).map(|i| applied[(i, j)]).collect())
        .collect();
    let (mut asymmetry, mut scale) = (0.0f64, 0.0f64);
    for (pair, applied) in vectors.chunks(2).zip(products.chunks(2)) {
        let (x, y) = (&pair[0], &pair[1]);
        let (ax, ay) = (&applied[0], &applied[1]);
        asymmetry = asymmetry.max((dot(x, ay) - dot(y, ax)).abs());
        scale = scale.max((norm(x) * norm(ay)).max(norm(y) * norm(ax)));
    }
    let detail = format!("{what} (probes): |xᵀAy − yᵀAx| = {asymmetry:e} vs |x| |Ay| = {scale:e}");
    CheckOutcome::at_most(name, asymmetry, SYMMETRY_TOLERANCE * scale, detail)
}

/// Smallest generalized eigenvalue of `(A, M)` (dense, symmetric-definite) is `≥ −tol ·
/// largest`, measured as `−λ_min` against `tol · |λ_max|` (`tol` is [`SEMIDEFINITE_TOLERANCE`]). An empty problem (a space without
/// free nodes, e.g. P1 co-potentials zero on the boundary of a mesh without interior vertices)
/// passes with nothing measured.
pub fn measure_psd(what: &str, a: &Mat<f64>, mass: &DenseMass) -> CheckOutcome {
    psd_outcome(what, generalized_eigenvalues(a, mass).as_deref())
}

/// [`measure_psd`] of a pencil whose eigenvalues (ascending) are given, or why they could not be
/// computed.
fn psd_outcome(what: &str, eigenvalues: Result<&[f64], &String>) -> CheckOutcome {
    let eigenvalues = match eigenvalues {
        Ok(eigenvalues) => eigenvalues,
        Err(reason) => {
            let detail = format!("{what}: the eigenvalues cannot be computed: {reason}");
            return CheckOutcome::failed(format!("positive semi-definite: {what}"), detail);
        }
    };
    if eigenvalues.is_empty() {
        let detail = format!("{what}: no free nodes, no eigenvalues");
        return CheckOutcome::at_most(format!("positive semi-definite: {what}"), 0.0, 0.0, detail);
    }
    let (min, max) = (eigenvalues[0], eigenvalues[eigenvalues.len() - 1]);
    let detail = format!("{what}: lowest eigenvalue {min:e} (largest {max:e})");
    CheckOutcome::at_least(
        format!("positive semi-definite: {what}"),
        min,
        -SEMIDEFINITE_TOLERANCE * max.abs(),
        detail,
    )
}

/// [`measure_symmetric`] of the potential stiffness (always sparse) and
/// [`measure_symmetric_operator`] of the co-potential stiffness, `S` and `B`.
pub fn measure_symmetric_operators<H: HodgeComplex + ?Sized>(complex: &H) -> Vec<CheckOutcome> {
    measure_symmetric_operators_with(&CheckCache::new(complex))
}

/// [`measure_symmetric_operators`], a composed `S` and `B` formed once for this and the other
/// checks of `cache`.
pub fn measure_symmetric_operators_with<H: HodgeComplex + ?Sized>(
    cache: &CheckCache<'_, H>,
) -> Vec<CheckOutcome> {
    let complex = cache.complex();
    let (s, b) = (complex.dirichlet_energy(), complex.biharmonic_energy());
    let composed = |a: &LinearOperator| a.as_sparse().is_none() && a.shape().1 <= DENSE_LIMIT;
    let formed_s = composed(s).then(|| cache.dirichlet_energy());
    let formed_b = composed(b).then(|| cache.biharmonic_energy());
    vec![
        measure_symmetric(
            "potential stiffness d0ᵀ M1 d0",
            complex.potential_stiffness(),
        ),
        measure_symmetric_operator(
            "co-potential stiffness d1 M1⁻¹ d1ᵀ",
            complex.co_potential_stiffness(),
        ),
        measure_symmetric_operator_formed("Dirichlet energy S", s, formed_s),
        measure_symmetric_operator_formed("biharmonic energy B", b, formed_b),
    ]
}

/// [`measure_psd`] of `S` and `B` (w.r.t. `M1`, on the free field nodes) and of both scalar
/// eigenproblems (on the free nodes of their spaces), all formed densely.
pub fn measure_psd_operators<H: HodgeComplex + ?Sized>(complex: &H) -> Vec<CheckOutcome> {
    measure_psd_operators_with(&CheckCache::new(complex))
}

/// [`measure_psd_operators`] on the spectra of `cache` (shared with the kernel and spectrum
/// union checks).
pub fn measure_psd_operators_with<H: HodgeComplex + ?Sized>(
    cache: &CheckCache<'_, H>,
) -> Vec<CheckOutcome> {
    let complex = cache.complex();
    let (b, m1, _) = restrict_to_free(
        cache.biharmonic_energy(),
        &DenseMass::of(complex.m1()),
        complex.field_nodes(),
    );
    vec![
        psd_outcome("S", cache.hodge_spectrum().as_ref().map(|v| *v)),
        measure_psd("B", &b, &m1),
        psd_outcome(
            "exact eigenproblem",
            cache.exact_spectrum().as_ref().map(|v| *v),
        ),
        psd_outcome(
            "co-exact eigenproblem",
            cache.co_exact_spectrum().as_ref().map(|v| *v),
        ),
    ]
}

/// `S`, `B` and both stiffness matrices are symmetric.
pub fn check_symmetric_operators<H: HodgeComplex + ?Sized>(complex: &H) {
    assert_outcomes(&measure_symmetric_operators(complex));
}

/// `S` and `B` (w.r.t. `M1`) and both scalar eigenproblems are positive semi-definite (dense;
/// small meshes).
pub fn check_psd_operators<H: HodgeComplex + ?Sized>(complex: &H) {
    assert_outcomes(&measure_psd_operators(complex));
}

/// `d1 · d0 = 0` up to round-off (`max |d1 d0| ≤ tol · max|d1| · max|d0|`), and, through the
/// co-gradient `−M1⁻¹ d1ᵀ` (a path that also involves `M1`), integrable ⟂ co-integrable:
/// `(−M1⁻¹ d1ᵀ)ᵀ M1 d0 = 0` (`max` entry `≤ tol · max |co-gradient| · max |M1 d0|`; for a
/// composed co-gradient measured on [`PROBES`] seeded random co-potentials `r`:
/// `max |(M1 d0)ᵀ (−M1⁻¹ d1ᵀ r)| ≤ tol · max |M1 d0| · max |−M1⁻¹ d1ᵀ r|`); `tol` is
/// [`EXACTNESS_TOLERANCE`].
pub fn measure_d1_d0_zero<H: HodgeComplex + ?Sized>(complex: &H) -> Vec<CheckOutcome> {
    if complex.d1().cols() != complex.d0().rows() {
        return vec![CheckOutcome::failed(
            "d1_d0_zero",
            format!(
                "d1 and d0 do not compose: d1 is {:?}, d0 is {:?}",
                complex.d1().shape(),
                complex.d0().shape()
            ),
        )];
    }
    let composed = product(complex.d1(), complex.d0());
    let scale = max_abs(complex.d1()) * max_abs(complex.d0());
    let error = max_abs(&composed);
    let first = CheckOutcome::at_most(
        "d1_d0_zero",
        error,
        EXACTNESS_TOLERANCE * scale,
        format!("|d1 d0| = {error:e}, scale {scale:e}"),
    );
    let m1 = complex
        .m1()
        .sparse_matrix()
        .expect("the field mass M1 is stored directly");
    let weighted = product(&m1, complex.d0());
    let (error, scale) = match complex.co_gradient().as_sparse() {
        Some(co_gradient) => {
            let cross = product(&transpose(co_gradient), &weighted);
            (max_abs(&cross), max_abs(co_gradient) * max_abs(&weighted))
        }
        None => {
            let (mut error, mut largest) = (0.0f64, 0.0f64);
            for r in probes(complex.co_potential_dimension(), PROBES, 0xd1d0) {
                let field = complex.co_gradient_field(&r);
                error = error.max(max_abs_vec(&mul_transpose_vec(&weighted, &field)));
                largest = largest.max(max_abs_vec(&field));
            }
            (error, largest * max_abs(&weighted))
        }
    };
    let second = CheckOutcome::at_most(
        "integrable_orthogonal_to_cointegrable",
        error,
        EXACTNESS_TOLERANCE * scale,
        format!("|(M1⁻¹ d1ᵀ)ᵀ M1 d0| = {error:e}, scale {scale:e}"),
    );
    vec![first, second]
}

/// `d1 · d0 = 0` and integrable ⟂ co-integrable ([`measure_d1_d0_zero`]).
pub fn check_d1_d0_zero<H: HodgeComplex + ?Sized>(complex: &H) {
    assert_outcomes(&measure_d1_d0_zero(complex));
}

/// Whether a diagonal mass is finite and positive on the nodes faces use: the bad nodes.
fn bad_diagonal_nodes(values: &[f64], nodes: &NodeSpace) -> Vec<usize> {
    (0..values.len())
        .filter(|&i| {
            let m = values[i];
            let used = nodes.components.get(i) != Some(&NO_COMPONENT);
            !(m.is_finite() && (m > 0.0 || !used))
        })
        .collect()
}

/// The stored sparse matrix of a mass restricted to the free nodes of `nodes`, factored by a
/// sparse Cholesky factorization of its own: `Ok(free count)` if it is finite and positive
/// definite there, else what failed.
fn sparse_mass_positive_definite(matrix: &CsMat<f64>, nodes: &NodeSpace) -> Result<usize, String> {
    if let Some(index) = matrix.data().iter().position(|x| !x.is_finite()) {
        return Err(format!("stored entry {index} is not finite"));
    }
    let free: Vec<usize> = (0..nodes.len()).filter(|&i| nodes.is_free(i)).collect();
    let mut position = vec![usize::MAX; nodes.len()];
    for (k, &i) in free.iter().enumerate() {
        position[i] = k;
    }
    let mut block = TriMat::new((free.len(), free.len()));
    for (&value, (i, j)) in matrix.iter() {
        if position[i] != usize::MAX && position[j] != usize::MAX {
            block.add_triplet(position[i], position[j], value);
        }
    }
    let block: CsMat<f64> = block.to_csc();
    SparseCholesky::new(&block)
        .map(|_| free.len())
        .map_err(|e| format!("not positive definite on its free nodes: {e}"))
}

/// One outcome per mass: a diagonal is finite and positive on every node faces use; a sparse
/// matrix (`M`, or `M⁻¹` for a mass stored as its inverse) is finite, exactly symmetric as
/// stored, and positive definite on the free nodes of its space (its own sparse Cholesky
/// factorization there).
fn measure_mass(what: &str, mass: &Mass, nodes: &NodeSpace) -> CheckOutcome {
    let name = format!("positive_masses: {what}");
    match mass.storage() {
        MassStorage::Diagonal(values) => {
            let bad = bad_diagonal_nodes(values, nodes);
            let detail = match bad.first() {
                Some(&i) => format!(
                    "{what}[{i}] = {:e} on a used node ({} such)",
                    values[i],
                    bad.len()
                ),
                None => format!("{what}: every used node has a positive mass"),
            };
            CheckOutcome::count(name, bad.len(), 0, detail)
        }
        MassStorage::Sparse(matrix) => {
            let stored = match mass.form() {
                MassForm::Direct => what.to_string(),
                MassForm::Inverse => format!("{what}⁻¹ (the stored form)"),
            };
            let asymmetry = max_abs(&(&matrix.to_csr() - &transpose(matrix)));
            let result = if asymmetry > 0.0 {
                Err(format!("not symmetric as stored (asymmetry {asymmetry:e})"))
            } else {
                sparse_mass_positive_definite(matrix, nodes)
            };
            match result {
                Ok(free) => CheckOutcome::count(
                    name,
                    0,
                    0,
                    format!(
                        "{stored}: sparse, symmetric, positive definite on its {free} free nodes"
                    ),
                ),
                Err(reason) => CheckOutcome::count(name, 1, 0, format!("{stored}: {reason}")),
            }
        }
    }
}

/// The potential masses partition the area: `|1ᵀ M0 1 − area| ≤` [`AREA_TOLERANCE`] `· area`; and every mass is
/// a positive diagonal on the nodes faces use, or a sparse matrix positive definite on the free
/// nodes (one outcome per mass).
pub fn measure_masses<H: HodgeComplex + ?Sized, M: Mesh + ?Sized>(
    complex: &H,
    mesh: &M,
) -> Vec<CheckOutcome> {
    let mut outcomes: Vec<CheckOutcome> = [
        ("M0", complex.m0(), complex.potential_nodes()),
        ("M1", complex.m1(), complex.field_nodes()),
        ("M2", complex.m2(), complex.co_potential_nodes()),
    ]
    .into_iter()
    .map(|(what, mass, nodes)| measure_mass(what, mass, nodes))
    .collect();
    let area = surface_area(mesh);
    let total = complex.total_area();
    outcomes.push(CheckOutcome::at_most(
        "potential_masses_sum_to_area",
        (total - area).abs(),
        AREA_TOLERANCE * area,
        format!("1ᵀ M0 1 = {total}, the mesh's area is {area}"),
    ));
    outcomes
}

/// The mesh's area: a triangle mesh's [`tvf_core::TriangleMesh::total_area`], otherwise the sum of the
/// faces' vector-area lengths `|½ Σ_c p_c × p_{c+1}|` (units of length²).
pub fn surface_area<M: Mesh + ?Sized>(mesh: &M) -> f64 {
    if let Some(triangles) = mesh.as_triangles() {
        return triangles.total_area();
    }
    let faces = mesh.face_corners();
    (0..faces.face_count())
        .map(|f| {
            let corners = faces.corners(f);
            let vector_area = (0..corners.len()).fold([0.0; 3], |sum, c| {
                let p = mesh.positions()[corners[c]];
                let q = mesh.positions()[corners[(c + 1) % corners.len()]];
                add(sum, scale(cross(p, q), 0.5))
            });
            tvf_core::geometry::norm(vector_area)
        })
        .sum()
}

/// Number of nodes a space of kind `kind` has on `mesh`.
fn expected_node_count<M: Mesh>(kind: NodeKind, mesh: &CorpusMesh<M>) -> usize {
    match kind {
        NodeKind::Vertices => mesh.mesh.vertex_count(),
        NodeKind::Edges => mesh.mesh.edge_count(),
        NodeKind::Faces => mesh.mesh.face_count(),
        NodeKind::FaceFrames => 2 * mesh.mesh.face_count(),
    }
}

fn check_node_space<M: Mesh>(what: &str, nodes: &NodeSpace, size: usize, mesh: &CorpusMesh<M>) {
    let components = mesh.mesh.topology().component_count();
    assert_eq!(nodes.len(), size, "{what}: one node per row/column");
    assert_eq!(nodes.positions.len(), size, "{what}: one position per node");
    assert_eq!(
        size,
        expected_node_count(nodes.kind, mesh),
        "{what}: node count of kind {}",
        nodes.kind.name()
    );
    assert!(
        nodes.positions.iter().flatten().all(|x| x.is_finite()),
        "{what}: non-finite node position"
    );
    assert!(
        nodes
            .components
            .iter()
            .all(|&c| c < components || c == NO_COMPONENT),
        "{what}: component out of range"
    );
    assert_eq!(
        nodes.dirichlet.len(),
        size,
        "{what}: one Dirichlet flag per node"
    );
    assert_eq!(
        nodes.constant_kernel.len(),
        components,
        "{what}: one constant-kernel flag per component"
    );
    if mesh.mesh.topology().is_closed() {
        assert_eq!(
            nodes.dirichlet_count(),
            0,
            "{what}: Dirichlet nodes on a closed mesh"
        );
        assert!(
            nodes.constant_kernel.iter().all(|&k| k),
            "{what}: constants not in the kernel on a closed mesh"
        );
    }
}

/// Shapes, nodes, topology and masses agree with the mesh: `d0` is `n1 × n0`, `d1` is `n2 × n1`,
/// each node space has one node per row (as many as its kind says), every mass is a positive
/// diagonal on the nodes faces use or a sparse matrix positive definite on the free nodes, the
/// topology has the mesh's components, boundary and harmonic dimension
/// (`2g`, or `2g + b − 1` per component with boundary), and the
/// potential masses partition the area: `1ᵀ M0 1 = total_area() = area` (relative
/// [`AREA_TOLERANCE`]).
pub fn check_nodes_and_masses<H: HodgeComplex + ?Sized, M: Mesh>(
    complex: &H,
    mesh: &CorpusMesh<M>,
) {
    let (n0, n1, n2) = (
        complex.potential_dimension(),
        complex.field_dimension(),
        complex.co_potential_dimension(),
    );
    assert_eq!(complex.d0().shape(), (n1, n0), "d0 shape");
    assert_eq!(complex.d1().shape(), (n2, n1), "d1 shape");
    for (what, nodes, size) in [
        ("potential nodes", complex.potential_nodes(), n0),
        ("field nodes", complex.field_nodes(), n1),
        ("co-potential nodes", complex.co_potential_nodes(), n2),
    ] {
        check_node_space(what, nodes, size, mesh);
    }
    for (what, mass, nodes) in [
        ("M0", complex.m0(), complex.potential_nodes()),
        ("M1", complex.m1(), complex.field_nodes()),
        ("M2", complex.m2(), complex.co_potential_nodes()),
    ] {
        assert_eq!(mass.len(), nodes.len(), "{what}: one entry per node");
    }
    assert_outcomes(&measure_masses(complex, &mesh.mesh));
    let topology = complex.topology();
    assert_eq!(
        topology.component_count,
        mesh.mesh.topology().component_count(),
        "components"
    );
    assert_eq!(
        topology.harmonic_dimension, mesh.harmonic_dimension,
        "reported harmonic dimension"
    );
    assert_eq!(
        topology.has_boundary,
        !mesh.mesh.topology().is_closed(),
        "boundary"
    );
}
