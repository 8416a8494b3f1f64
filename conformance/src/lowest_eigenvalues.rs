//! The lowest eigenvalues of a scalar eigenproblem of a complex on the free nodes of its space,
//! by the sparse eigensolver ([`tvf_solvers::lowest_eigenpairs_of`]: spectrum slicing with
//! inertia counts, shift-and-invert block Krylov–Schur), for checks that need only the low end
//! of a spectrum: the convergence checks ([`crate::convergence_checks`]) compare the lowest
//! eigenvalues with the exact ones.
//!
//! Why not dense, as the checks of the whole spectrum are: on the finest levels of the
//! convergence sequences the pencils have up to 1,920 free nodes, and tridiagonalising each of
//! them (plus, for a sparse mass, a dense Cholesky transform, and for the mixed co-exact
//! stiffness `d1 M1⁻¹ d1ᵀ`, one solve with `M1` per column to form it) was about three quarters
//! of an accuracy test. The sparse solver returns every eigenvalue up to the `k`-th with its
//! completeness verified by an inertia count; it is tested against the dense solver in
//! `tvf-solvers`' own tests (diagonal, sparse and mixed pencils), and its eigenvalues are
//! Rayleigh quotients accurate to far below the discretization errors measured here (`1e-10`
//! relative at the least against errors of `1e-4` and above).

use sprs::CsMat;
use tvf_core::discretization::sparse::restricted_to;
use tvf_core::discretization::{EigenStiffness, Eigenproblem, NodeSpace};
use tvf_solvers::{lowest_eigenpairs_of, EigenOptions, EigenRequest, MassMatrix, Pencil};

/// Seed of the eigensolver's start blocks (fixed: the checks are deterministic).
const SEED: u64 = 2017;

/// The lowest `count` eigenvalues (ascending, with multiplicity, the kernel included) of
/// `problem` restricted to the free nodes of `nodes`; a mixed stiffness `d1 W⁻¹ d1ᵀ` is
/// restricted to the free field nodes `field_nodes` for `W`. Fewer than `count` when the space
/// has fewer free nodes. An error says why the solver failed (a mass that is not positive
/// definite, no convergence).
pub fn lowest_free_eigenvalues(
    problem: &Eigenproblem,
    nodes: &NodeSpace,
    field_nodes: &NodeSpace,
    count: usize,
) -> Result<Vec<f64>, String> {
    let free = positions(nodes);
    let n = free.iter().filter(|&&p| p != usize::MAX).count();
    let count = count.min(n);
    if count == 0 {
        return Ok(Vec::new());
    }
    let diagonal: Vec<f64>;
    let sparse_mass: CsMat<f64>;
    let mass = match (problem.mass.diagonal_values(), problem.mass.sparse_matrix()) {
        (Some(values), _) => {
            diagonal = (0..values.len())
                .filter(|&i| free[i] != usize::MAX)
                .map(|i| values[i])
                .collect();
            MassMatrix::Diagonal(&diagonal)
        }
        (None, Some(m)) => {
            sparse_mass = restricted_to(&m, &free, &free, (n, n));
            MassMatrix::Sparse(&sparse_mass)
        }
        (None, None) => return Err("the eigenproblem's mass is stored as its inverse".into()),
    };
    let stiffness: CsMat<f64>;
    let pencil = match &problem.stiffness {
        EigenStiffness::Sparse(a) => {
            stiffness = restricted_to(a, &free, &free, (n, n));
            Pencil::with_mass(&stiffness, mass)
        }
        EigenStiffness::Mixed { field_mass, d1 } => {
            let fields = positions(field_nodes);
            let n1 = fields.iter().filter(|&&p| p != usize::MAX).count();
            let w = field_mass
                .sparse_matrix()
                .ok_or("the field mass of a mixed stiffness is stored as its inverse")?;
            let w = restricted_to(&w, &fields, &fields, (n1, n1));
            Pencil::mixed(&w, &restricted_to(d1, &free, &fields, (n, n1)), mass)
        }
    }
    .map_err(|e| e.to_string())?;
    // One thread per call: the test harness runs checks side by side already.
    let options = EigenOptions {
        parallelism: faer::Par::Seq,
        threads: 1,
        ..EigenOptions::default()
    };
    let request = EigenRequest {
        pencil: &pencil,
        count,
        top: None,
        seed: SEED,
    };
    let mut solution = lowest_eigenpairs_of(&[request], &options).map_err(|e| e.to_string())?;
    let pairs = solution
        .pairs
        .pop()
        .ok_or("the eigensolver returned nothing")?;
    Ok(pairs.values)
}

/// The position of every node of `nodes` among its free nodes, `usize::MAX` for the others.
fn positions(nodes: &NodeSpace) -> Vec<usize> {
    let mut next = 0;
    (0..nodes.len())
        .map(|i| {
            if nodes.is_free(i) {
                next += 1;
                next - 1
            } else {
                usize::MAX
            }
        })
        .collect()
}
