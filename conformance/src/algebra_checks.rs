//! Algebraic core checks: the complex property `d1 · d0 = 0`, shapes, nodes and masses,
//! symmetry and semi-definiteness.

use crate::check_outcome::{assert_outcomes, CheckOutcome};
use crate::corpus::CorpusMesh;
use crate::dense::generalized_eigenvalues;
use sprs::CsMat;
use tvf_core::discretization::sparse::{product, scale_rows, transpose};
use tvf_core::discretization::{HodgeComplex, HodgeOperators, NodeKind, NodeSpace, NO_COMPONENT};
use tvf_core::SurfaceMesh;

/// Largest absolute entry of a sparse matrix (0 if empty).
pub fn max_abs(a: &CsMat<f64>) -> f64 {
    a.data().iter().fold(0.0, |m, x| m.max(x.abs()))
}

/// `max |A − Aᵀ| ≤ 1e-12 · max |A|`, measured (a non-square matrix fails).
pub fn measure_symmetric(what: &str, a: &CsMat<f64>) -> CheckOutcome {
    let name = format!("symmetric: {what}");
    if a.rows() != a.cols() {
        return CheckOutcome::failed(name, format!("{what}: not square {:?}", a.shape()));
    }
    let difference = &a.to_csr() - &transpose(a);
    let asymmetry = max_abs(&difference);
    let limit = 1e-12 * max_abs(a);
    let detail = format!(
        "{what}: asymmetry {asymmetry:e} vs max entry {:e}",
        max_abs(a)
    );
    CheckOutcome::at_most(name, asymmetry, limit, detail)
}

/// `max |A − Aᵀ| ≤ 1e-12 · max |A|`.
pub fn check_symmetric(what: &str, a: &CsMat<f64>) {
    assert_outcomes(&[measure_symmetric(what, a)]);
}

/// Smallest generalized eigenvalue of `(A, diag(mass))` is `≥ −1e-10 · largest` (dense),
/// measured as `−λ_min` against `1e-10 · |λ_max|`.
pub fn measure_psd(what: &str, a: &CsMat<f64>, mass: &[f64]) -> CheckOutcome {
    let eigenvalues = generalized_eigenvalues(a, mass);
    let (min, max) = (eigenvalues[0], eigenvalues[eigenvalues.len() - 1]);
    let detail = format!("{what}: eigenvalue {min:e} (largest {max:e})");
    CheckOutcome::at_most(
        format!("positive semi-definite: {what}"),
        -min,
        1e-10 * max.abs(),
        detail,
    )
}

/// Smallest generalized eigenvalue of `(A, diag(mass))` is `≥ −1e-10 · largest` (dense).
pub fn check_psd(what: &str, a: &CsMat<f64>, mass: &[f64]) {
    assert_outcomes(&[measure_psd(what, a, mass)]);
}

/// [`measure_symmetric`] of `S`, `B` and both stiffness matrices.
pub fn measure_symmetric_operators<H: HodgeComplex + ?Sized>(complex: &H) -> Vec<CheckOutcome> {
    vec![
        measure_symmetric(
            "potential stiffness d0ᵀ M1 d0",
            complex.potential_stiffness(),
        ),
        measure_symmetric(
            "co-potential stiffness d1 M1⁻¹ d1ᵀ",
            complex.co_potential_stiffness(),
        ),
        measure_symmetric("Dirichlet energy S", complex.dirichlet_energy()),
        measure_symmetric("biharmonic energy B", complex.biharmonic_energy()),
    ]
}

/// [`measure_psd`] of `S` and `B` (w.r.t. `M1`) and both scalar eigenproblems (dense).
pub fn measure_psd_operators<H: HodgeComplex + ?Sized>(complex: &H) -> Vec<CheckOutcome> {
    let exact = complex.exact_eigenproblem();
    let co_exact = complex.co_exact_eigenproblem();
    vec![
        measure_psd("S", complex.dirichlet_energy(), complex.m1().values()),
        measure_psd("B", complex.biharmonic_energy(), complex.m1().values()),
        measure_psd("exact eigenproblem", &exact.stiffness, &exact.mass),
        measure_psd("co-exact eigenproblem", &co_exact.stiffness, &co_exact.mass),
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

/// `d1 · d0 = 0` up to round-off (`max |d1 d0| ≤ 1e-12 · max|d1| · max|d0|`), and, through the
/// co-gradient `−M1⁻¹ d1ᵀ` (a path that also involves `M1`), integrable ⟂ co-integrable:
/// `(−M1⁻¹ d1ᵀ)ᵀ M1 d0 = 0`; measured.
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
        1e-12 * scale,
        format!("|d1 d0| = {error:e}, scale {scale:e}"),
    );
    let co_gradient = complex.co_gradient();
    let weighted = scale_rows(complex.m1().values(), complex.d0());
    let cross = product(&transpose(co_gradient), &weighted);
    let scale = max_abs(co_gradient) * max_abs(&weighted);
    let error = max_abs(&cross);
    let second = CheckOutcome::at_most(
        "integrable_orthogonal_to_co_integrable",
        error,
        1e-12 * scale,
        format!("|(M1⁻¹ d1ᵀ)ᵀ M1 d0| = {error:e}, scale {scale:e}"),
    );
    vec![first, second]
}

/// `d1 · d0 = 0` and integrable ⟂ co-integrable ([`measure_d1_d0_zero`]).
pub fn check_d1_d0_zero<H: HodgeComplex + ?Sized>(complex: &H) {
    assert_outcomes(&measure_d1_d0_zero(complex));
}

/// The potential masses partition the area: `|Σ M0 − area| ≤ 1e-12 · area`; and every mass is
/// finite and positive on the nodes faces use (one outcome per mass).
pub fn measure_masses<H: HodgeComplex + ?Sized>(
    complex: &H,
    mesh: &SurfaceMesh,
) -> Vec<CheckOutcome> {
    let mut outcomes = Vec::new();
    for (what, mass, nodes) in [
        ("M0", complex.m0(), complex.potential_nodes()),
        ("M1", complex.m1(), complex.field_nodes()),
        ("M2", complex.m2(), complex.co_potential_nodes()),
    ] {
        let bad: Vec<usize> = (0..mass.len())
            .filter(|&i| {
                let m = mass.values()[i];
                let used = nodes.components.get(i) != Some(&NO_COMPONENT);
                !(m.is_finite() && (m > 0.0 || !used))
            })
            .collect();
        let detail = match bad.first() {
            Some(&i) => format!(
                "{what}[{i}] = {:e} on a used node ({} such)",
                mass.values()[i],
                bad.len()
            ),
            None => format!("{what}: every used node has a positive mass"),
        };
        outcomes.push(CheckOutcome::count(
            format!("positive_masses: {what}"),
            bad.len(),
            0,
            detail,
        ));
    }
    let area = mesh.total_area();
    let total = complex.total_area();
    outcomes.push(CheckOutcome::at_most(
        "potential_masses_sum_to_area",
        (total - area).abs(),
        1e-12 * area,
        format!("Σ M0 = {total}, the mesh's area is {area}"),
    ));
    outcomes
}

/// Number of nodes a space of kind `kind` has on `mesh`.
fn expected_node_count(kind: NodeKind, mesh: &CorpusMesh) -> usize {
    match kind {
        NodeKind::Vertices => mesh.mesh.vertex_count(),
        NodeKind::Edges => mesh.mesh.edge_count(),
        NodeKind::Faces => mesh.mesh.face_count(),
        NodeKind::FaceFrames => 2 * mesh.mesh.face_count(),
    }
}

fn check_node_space(what: &str, nodes: &NodeSpace, size: usize, mesh: &CorpusMesh) {
    let components = mesh.mesh.component_count();
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
    if mesh.mesh.is_closed() {
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
/// each node space has one node per row (as many as its kind says), every mass is positive on
/// the nodes faces use, the topology has the mesh's components, boundary and harmonic dimension
/// (`2g`, or `2g + b − 1` per component with boundary), and the
/// potential masses partition the area: `Σ M0 = total_area() = area` (relative 1e-12).
pub fn check_nodes_and_masses<H: HodgeComplex + ?Sized>(complex: &H, mesh: &CorpusMesh) {
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
        mesh.mesh.component_count(),
        "components"
    );
    assert_eq!(
        topology.harmonic_dimension, mesh.harmonic_dimension,
        "reported harmonic dimension"
    );
    assert_eq!(topology.has_boundary, !mesh.mesh.is_closed(), "boundary");
}
