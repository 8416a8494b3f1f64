//! Fill-reducing symmetric orderings for the sparse factorizations.
//!
//! A sparse `LDLᵀ` of `P A Pᵀ` fills in differently for every permutation `P`. Two orderings are
//! offered:
//! - [`FillOrdering::Amd`]: approximate minimum degree (faer's own), a greedy local heuristic.
//!   Cheap to compute and best for small or very sparse matrices.
//! - [`FillOrdering::NestedDissection`]: METIS's multilevel nested dissection
//!   ([`nested_dissection`]): recursively removes small vertex separators of the matrix graph and
//!   numbers them last. For matrices from surface meshes (2D-like graphs) it gives
//!   `O(n log n)` fill and wide, dense supernodes near the root of the elimination tree, which is
//!   what makes the numeric factorization of large, denser systems (soft design) fast.
//!
//! A permutation is given as `perm` with `perm[k]` = the original row/column eliminated `k`-th
//! (faer's "forward" array, METIS's `perm`).

mod graph;
mod nested_dissection;

pub use graph::AdjacencyGraph;
pub use nested_dissection::{nested_dissection, nested_dissection_of_groups};

/// Which fill-reducing ordering a sparse factorization uses.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum FillOrdering {
    /// Approximate minimum degree (faer).
    #[default]
    Amd,
    /// Multilevel nested dissection (METIS `NodeND`, deterministic: fixed seed).
    NestedDissection,
}

impl FillOrdering {
    /// Short lower-case name (`"amd"`, `"nd"`), e.g. for command-line flags and reports.
    pub fn name(self) -> &'static str {
        match self {
            FillOrdering::Amd => "amd",
            FillOrdering::NestedDissection => "nd",
        }
    }

    /// Parses [`FillOrdering::name`] (also accepts `"nested-dissection"` and `"metis"`).
    pub fn from_name(name: &str) -> Option<Self> {
        match name.to_ascii_lowercase().as_str() {
            "amd" => Some(FillOrdering::Amd),
            "nd" | "nested-dissection" | "metis" => Some(FillOrdering::NestedDissection),
            _ => None,
        }
    }
}

/// `inverse[perm[k]] = k`: the position of every original index in the elimination order.
/// `perm` must be a permutation of `0..perm.len()`.
pub fn inverse_permutation(perm: &[usize]) -> Vec<usize> {
    let mut inverse = vec![0; perm.len()];
    for (k, &p) in perm.iter().enumerate() {
        inverse[p] = k;
    }
    inverse
}

/// Whether `perm` holds every index of `0..n` exactly once.
pub fn is_permutation(perm: &[usize], n: usize) -> bool {
    if perm.len() != n {
        return false;
    }
    let mut seen = vec![false; n];
    perm.iter()
        .all(|&p| p < n && !std::mem::replace(&mut seen[p], true))
}
