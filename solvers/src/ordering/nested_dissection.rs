//! Nested-dissection ordering through METIS (`METIS_NodeND`, built from the vendored sources of
//! the `metis-sys` crate: no system library needed).

use super::graph::AdjacencyGraph;
use super::is_permutation;
use crate::error::SolverError;
use faer::sparse::SymbolicSparseColMatRef;
use metis_sys::idx_t;
use std::sync::Mutex;

/// Fixed seed of METIS's randomised matching and refinement: the ordering is deterministic.
const METIS_SEED: idx_t = 7;

/// METIS (GKlib) keeps its random-number state in process-wide globals: concurrent calls would
/// race on it and make the orderings depend on thread timing. Every call holds this lock.
static METIS_LOCK: Mutex<()> = Mutex::new(());

/// Nested-dissection fill-reducing permutation of the symmetric matrix with pattern `pattern`
/// (`n × n` CSC; upper, lower or full storage): `perm[k]` is the original row/column eliminated
/// `k`-th. Deterministic (fixed seed).
///
/// Errors: [`SolverError::NotSquare`]; [`SolverError::Factorization`] if the graph is too large
/// for METIS's 32-bit indices or METIS fails (out of memory).
pub fn nested_dissection(
    pattern: SymbolicSparseColMatRef<'_, usize>,
) -> Result<Vec<usize>, SolverError> {
    if pattern.nrows() != pattern.ncols() {
        return Err(SolverError::NotSquare {
            rows: pattern.nrows(),
            cols: pattern.ncols(),
        });
    }
    let graph = AdjacencyGraph::from_symmetric_pattern(pattern);
    order_graph(&graph)
}

/// Nested dissection of the quotient graph of `pattern` under `group` (`n` values in
/// `0..group_count`; see [`AdjacencyGraph::quotient_of_pattern`]): the order in which to
/// eliminate the **groups**, `order[k]` = the group eliminated `k`-th. The caller eliminates each
/// group's members together (consecutively). For unknowns that come in blocks with the same
/// couplings (several unknowns per mesh element) this is a smaller graph than the matrix's, is
/// ordered several times faster, and gives the factor dense supernodes at no extra fill.
///
/// Errors: as [`nested_dissection`].
///
/// # Panics
/// If `group.len() != n` or a group is `≥ group_count` (programming errors).
pub fn nested_dissection_of_groups(
    pattern: SymbolicSparseColMatRef<'_, usize>,
    group: &[usize],
    group_count: usize,
) -> Result<Vec<usize>, SolverError> {
    if pattern.nrows() != pattern.ncols() {
        return Err(SolverError::NotSquare {
            rows: pattern.nrows(),
            cols: pattern.ncols(),
        });
    }
    let graph = AdjacencyGraph::quotient_of_pattern(pattern, group, group_count);
    order_graph(&graph)
}

/// Nested-dissection permutation of a graph's vertices (see [`nested_dissection`]).
pub(crate) fn order_graph(graph: &AdjacencyGraph) -> Result<Vec<usize>, SolverError> {
    let n = graph.vertex_count();
    if n <= 1 {
        return Ok((0..n).collect());
    }
    let too_large =
        || SolverError::Factorization(format!("graph too large for METIS ({n} vertices)"));
    let to_idx = |v: usize| idx_t::try_from(v).map_err(|_| too_large());
    let mut xadj = graph
        .offsets
        .iter()
        .map(|&v| to_idx(v))
        .collect::<Result<Vec<_>, _>>()?;
    let mut adjncy = graph
        .neighbours
        .iter()
        .map(|&v| to_idx(v))
        .collect::<Result<Vec<_>, _>>()?;
    let mut nvtxs = to_idx(n)?;
    let mut options = [0 as idx_t; metis_sys::METIS_NOPTIONS as usize];
    let mut perm = vec![0 as idx_t; n];
    let mut iperm = vec![0 as idx_t; n];
    // A panic elsewhere while holding the lock leaves no METIS state behind: ignore poisoning.
    let _guard = METIS_LOCK
        .lock()
        .unwrap_or_else(|poisoned| poisoned.into_inner());
    // SAFETY: `options` has METIS_NOPTIONS entries; `xadj` has nvtxs + 1 entries whose last is
    // `adjncy.len()`, every entry of `adjncy` is a vertex in 0..nvtxs (AdjacencyGraph guarantees
    // both); `perm` and `iperm` have nvtxs entries; vertex weights are absent (null). METIS reads
    // the graph and writes only `perm` and `iperm`.
    let status = unsafe {
        metis_sys::METIS_SetDefaultOptions(options.as_mut_ptr());
        options[metis_sys::moptions_et_METIS_OPTION_NUMBERING as usize] = 0;
        options[metis_sys::moptions_et_METIS_OPTION_SEED as usize] = METIS_SEED;
        metis_sys::METIS_NodeND(
            &mut nvtxs,
            xadj.as_mut_ptr(),
            adjncy.as_mut_ptr(),
            std::ptr::null_mut(),
            options.as_mut_ptr(),
            perm.as_mut_ptr(),
            iperm.as_mut_ptr(),
        )
    };
    if status != metis_sys::rstatus_et_METIS_OK {
        return Err(SolverError::Factorization(format!(
            "METIS nested dissection failed (status {status})"
        )));
    }
    // METIS's output is trusted only after this check.
    let perm: Vec<usize> = perm.into_iter().map(|p| p as usize).collect();
    if !is_permutation(&perm, n) {
        return Err(SolverError::Factorization(
            "METIS returned an invalid permutation".into(),
        ));
    }
    Ok(perm)
}
