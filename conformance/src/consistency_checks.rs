//! Consistency (patch) checks: what a discretization computes exactly for linear functions, on
//! flat and on curved patches. A linear function `φ(x) = ⟨a, x⟩` is given to a space by its
//! values at the space's node positions, which is its interpolant for nodal spaces (P1 on
//! vertices, Crouzeix–Raviart and DEC-like 0-forms alike); spaces of integrated values (2-forms
//! on faces) and face frames have no such values, and the checks report them as not applicable.
//!
//! What each check asserts:
//!
//! - `consistency:gradient_of_linear:{patch}` — the field `d0 φ` sampled at each face's
//!   centroid ([`FieldSampling::centroid`]) is `a` projected onto the face's plane
//!   (perpendicular to [`FieldSampling::normal`]), to [`GRADIENT_TOLERANCE`] of `|a|`: the
//!   discrete gradient of a linear function is exact on every face, flat or curved. Needs
//!   sampling and nodal potentials.
//! - `consistency:laplacian_of_linear:{patch}` — `(d0ᵀ M1 d0 φ)_i = 0` at every potential node
//!   inside a flat patch (every node it couples to on the same plane), to
//!   [`PATCH_TOLERANCE`] of `Σ_j |S_ij φ_j|`: the divergence of the constant field `∇φ` vanishes
//!   inside a flat region, the classic patch test of linear precision. Needs nodal potentials.
//! - `consistency:co_laplacian_of_linear:{patch}` — the same for the co-potential stiffness
//!   `d1 M1⁻¹ d1ᵀ` and a linear co-potential: the curl of the rotated constant field vanishes
//!   inside a flat region. Needs nodal co-potentials.
//! - `consistency:energy_of_linear:{patch}` — `φᵀ d0ᵀ M1 d0 φ = Σ_f A_f |a − ⟨a, n_f⟩ n_f|²`, the
//!   Dirichlet energy of the linear function on the piecewise flat surface, to
//!   [`PATCH_TOLERANCE`] relative, on flat and curved patches of planar faces (triangles always;
//!   a non-planar polygon has no exact energy to compare with). Needs nodal potentials.
//!
//! The mass-weighted energies and eigenvalues of smooth fields are what the convergence checks
//! ([`crate::convergence_checks`]) measure.

use crate::check_outcome::CheckOutcome;
use tvf_core::discretization::{
    FieldSampling, HodgeComplex, HodgeOperators, LinearOperator, NodeKind, NodeSpace,
};
use tvf_core::geometry::{dot, norm, scale, sub};
use tvf_core::SurfaceMesh;

/// Relative tolerance of the sampled gradient of a linear function.
pub const GRADIENT_TOLERANCE: f64 = 1e-10;

/// Relative tolerance of the patch tests and of the energy of a linear function (the residuals
/// of an exact discretization are round-off, ~1e-15 relative; a wrong star gives O(1)).
pub const PATCH_TOLERANCE: f64 = 1e-10;

/// The linear function's gradient `a` of every check (generic: no coordinate plane is special).
pub const GRADIENT: [f64; 3] = [0.3, -1.1, 0.6];

/// Whether a space holds nodal values, so that a linear function has an interpolant in it.
fn nodal(nodes: &NodeSpace) -> bool {
    matches!(nodes.kind, NodeKind::Vertices | NodeKind::Edges)
}

/// Why a linear function has no interpolant in the space of `nodes` (called `space`): its
/// nodes hold no values, or the boundary condition fixes some of them to zero; `None` if it has.
fn no_interpolant(space: &str, nodes: &NodeSpace) -> Option<String> {
    if !nodal(nodes) {
        return Some(format!(
            "the {space} nodes are {}: a linear function has no nodal values there",
            nodes.kind.name()
        ));
    }
    let fixed = nodes.dirichlet_count();
    (fixed > 0).then(|| {
        format!("the boundary condition fixes {fixed} {space} nodes: a linear function is not in the space")
    })
}

/// The linear function `⟨GRADIENT, x⟩` at the nodes of `nodes`.
fn linear_values(nodes: &NodeSpace) -> Vec<f64> {
    nodes.positions.iter().map(|&p| dot(GRADIENT, p)).collect()
}

/// `a` projected onto the plane perpendicular to the unit vector `n`.
fn tangential(a: [f64; 3], n: [f64; 3]) -> [f64; 3] {
    sub(a, scale(n, dot(a, n)))
}

/// `consistency:gradient_of_linear:{patch}` (see the module documentation).
pub fn measure_gradient_of_linear(
    complex: &dyn HodgeComplex,
    patch: &str,
    mesh: &SurfaceMesh,
) -> CheckOutcome {
    let name = format!("consistency:gradient_of_linear:{patch}");
    let potentials = complex.potential_nodes();
    if let Some(reason) = no_interpolant("potential", potentials) {
        return CheckOutcome::not_applicable(name, reason);
    }
    let Some(sampling) = complex.sampling() else {
        return CheckOutcome::not_applicable(name, "the complex does not sample fields".into());
    };
    let gradient = complex.gradient_field(&linear_values(potentials));
    let (mut worst, mut face) = (0.0f64, 0);
    for f in 0..mesh.face_count() {
        let sampled = sampled_at_centroid(sampling, &gradient, f);
        let error = norm(sub(sampled, tangential(GRADIENT, sampling.normal(f))));
        if error > worst {
            (worst, face) = (error, f);
        }
    }
    CheckOutcome::at_most(
        name,
        worst / norm(GRADIENT),
        GRADIENT_TOLERANCE,
        format!(
            "|sampled d0 φ − a_tangent| / |a| at face centroids, φ = ⟨a, x⟩ (worst: face {face} of {})",
            mesh.face_count()
        ),
    )
}

/// The field sampled at the centroid of face `f`.
fn sampled_at_centroid(sampling: &dyn FieldSampling, field: &[f64], f: usize) -> [f64; 3] {
    let mut v = [0.0; 3];
    for (i, w) in sampling.sample_weights(&sampling.centroid(f)) {
        for k in 0..3 {
            v[k] += w[k] * field[i];
        }
    }
    v
}

/// `consistency:laplacian_of_linear:{patch}` (potentials) or
/// `consistency:co_laplacian_of_linear:{patch}` (co-potentials, `co = true`): the stiffness of
/// the space applied to a linear function vanishes at the nodes `inside` accepts (see the
/// module documentation).
pub fn measure_patch_test(
    complex: &dyn HodgeComplex,
    co: bool,
    patch: &str,
    inside: &dyn Fn([f64; 3]) -> bool,
) -> CheckOutcome {
    let (which, space, nodes) = if co {
        ("co_laplacian", "co-potential", complex.co_potential_nodes())
    } else {
        ("laplacian", "potential", complex.potential_nodes())
    };
    let name = format!("consistency:{which}_of_linear:{patch}");
    if !nodal(nodes) {
        let reason = no_interpolant(space, nodes).unwrap_or_default();
        return CheckOutcome::not_applicable(name, reason);
    }
    let potential_stiffness;
    let stiffness = if co {
        complex.co_potential_stiffness()
    } else {
        potential_stiffness = LinearOperator::Sparse(complex.potential_stiffness().clone());
        &potential_stiffness
    };
    let values = linear_values(nodes);
    let residual = stiffness.apply(&values);
    let checked: Vec<usize> = (0..nodes.len())
        .filter(|&i| nodes.is_free(i) && inside(nodes.positions[i]))
        .collect();
    if checked.is_empty() {
        return CheckOutcome::failed(name, format!("no {space} node lies inside the flat patch"));
    }
    let (mut worst, mut node) = (0.0f64, checked[0]);
    for &i in &checked {
        let row = stiffness.row(i);
        let size: f64 = row.iter().zip(&values).map(|(s, v)| (s * v).abs()).sum();
        let relative = residual[i].abs() / size.max(f64::MIN_POSITIVE);
        if relative > worst {
            (worst, node) = (relative, i);
        }
    }
    CheckOutcome::at_most(
        name,
        worst,
        PATCH_TOLERANCE,
        format!(
            "|(S φ)_i| / Σ_j |S_ij φ_j| at the {} {space} nodes inside flat faces, φ linear \
             (worst: node {node})",
            checked.len()
        ),
    )
}

/// `consistency:energy_of_linear:{patch}` (see the module documentation).
pub fn measure_energy_of_linear(
    complex: &dyn HodgeComplex,
    patch: &str,
    mesh: &SurfaceMesh,
) -> CheckOutcome {
    let name = format!("consistency:energy_of_linear:{patch}");
    let potentials = complex.potential_nodes();
    if let Some(reason) = no_interpolant("potential", potentials) {
        return CheckOutcome::not_applicable(name, reason);
    }
    if let Some(f) = (0..mesh.face_count()).find(|&f| !planar(mesh, f)) {
        return CheckOutcome::not_applicable(
            name,
            format!("face {f} is not planar: the energy of a linear function has no exact value"),
        );
    }
    let values = linear_values(potentials);
    let discrete = dot_vec(&values, &mul(complex.potential_stiffness(), &values));
    let exact: f64 = (0..mesh.face_count())
        .map(|f| {
            let t = tangential(GRADIENT, mesh.face_normal(f));
            mesh.face_area(f) * dot(t, t)
        })
        .sum();
    CheckOutcome::at_most(
        name,
        (discrete - exact).abs() / exact,
        PATCH_TOLERANCE,
        format!(
            "|φᵀ S φ − Σ_f A_f |a_tangent|²| relative, φ = ⟨a, x⟩: {discrete:.6e} vs {exact:.6e}"
        ),
    )
}

/// Whether every corner of face `f` lies on the plane through its centroid normal to its vector
/// area (to `1e-12` of the face's size).
fn planar(mesh: &SurfaceMesh, f: usize) -> bool {
    let corners = mesh.face(f);
    if corners.len() == 3 {
        return true;
    }
    let (n, c) = (mesh.face_normal(f), mesh.face_centroid(f));
    let size = mesh.face_area(f).sqrt();
    let p = mesh.positions();
    corners
        .iter()
        .all(|&v| dot(sub(p[v], c), n).abs() <= 1e-12 * size)
}

fn mul(a: &sprs::CsMat<f64>, x: &[f64]) -> Vec<f64> {
    tvf_core::discretization::sparse::mul_vec(a, x)
}

fn dot_vec(x: &[f64], y: &[f64]) -> f64 {
    x.iter().zip(y).map(|(a, b)| a * b).sum()
}

/// The consistency checks of `complex` built on `mesh`, a patch called `patch`: the gradient and
/// the energy of a linear function, and, where `flat_inside` marks the nodes inside flat faces,
/// both patch tests.
pub fn measure_consistency(
    complex: &dyn HodgeComplex,
    patch: &str,
    mesh: &SurfaceMesh,
    flat_inside: Option<&dyn Fn([f64; 3]) -> bool>,
) -> Vec<CheckOutcome> {
    let mut outcomes = vec![measure_gradient_of_linear(complex, patch, mesh)];
    if let Some(inside) = flat_inside {
        outcomes.push(measure_patch_test(complex, false, patch, inside));
        outcomes.push(measure_patch_test(complex, true, patch, inside));
    }
    outcomes.push(measure_energy_of_linear(complex, patch, mesh));
    outcomes
}
