//! [`MatrixHash`]: 64-bit hashes of what a complex's spectra are computed from — its five
//! matrices and the nodes its boundary condition fixes — which tie basis files and cached bases
//! to the matrices they were computed for.

use super::sparse::as_csr;
use super::{ComplexParts, Mass, MassForm, MassStorage, NodeSpace, NO_COMPONENT};
use crate::hash64::Hash64;
use sprs::CsMat;

/// Hashes ([`Hash64`]) of the parts of a complex ([`ComplexParts::matrix_hash`]), one per part
/// so that a mismatch can say which part differs; [`MatrixHash::value`] combines them.
///
/// - `d0`, `d1`: the shape, then every stored entry in row-major order — its row, column and the
///   bit pattern of its value (so `0.0` and `-0.0` differ, and an explicitly stored zero counts).
///   Canonical: the same matrix hashes alike in CSR and in CSC storage.
/// - `M0`, `M1`, `M2` ([`MatrixHash::of_mass`]): the size `n`, the storage kind (diagonal or
///   sparse), the form (`M` or `M⁻¹`, [`MassForm`]) and the stored values — the `n` diagonal
///   entries' bits, or the stored sparse matrix as above.
/// - `nodes`: for each of the three spaces its size, its fixed nodes (the Dirichlet nodes of the
///   boundary condition, and the nodes no face uses) and which components have constants in the
///   kernel of its stiffness; then the component count and the harmonic dimension. This is where
///   the boundary condition lives: on a closed mesh both conditions give the same complex and
///   hash alike.
///
/// Node positions, capabilities and the id are not hashed. Equal parts give equal hashes on
/// every machine; a change of any listed bit changes the hash with overwhelming probability
/// (not a cryptographic hash).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct MatrixHash {
    /// Hash of `d0`.
    pub d0: u64,
    /// Hash of `d1`.
    pub d1: u64,
    /// Hash of `M0`.
    pub m0: u64,
    /// Hash of `M1`.
    pub m1: u64,
    /// Hash of `M2`.
    pub m2: u64,
    /// Hash of the fixed nodes of the three spaces and the topology.
    pub nodes: u64,
}

impl MatrixHash {
    /// Names of the parts, in the order of [`MatrixHash::parts`].
    pub const PART_NAMES: [&'static str; 6] = ["d0", "d1", "M0", "M1", "M2", "fixed nodes"];

    /// The hashes of `parts` (computed once per complex by [`ComplexParts::matrix_hash`]).
    pub(crate) fn of(parts: &ComplexParts) -> Self {
        let nodes = [
            parts.potential_nodes(),
            parts.field_nodes(),
            parts.co_potential_nodes(),
        ];
        Self {
            d0: sparse_hash(parts.d0()),
            d1: sparse_hash(parts.d1()),
            m0: Self::of_mass(parts.m0()),
            m1: Self::of_mass(parts.m1()),
            m2: Self::of_mass(parts.m2()),
            nodes: nodes_hash(
                &nodes,
                parts.topology().component_count,
                parts.topology().harmonic_dimension,
            ),
        }
    }

    /// The hash of one mass: its size, storage kind, form and stored values (not its free
    /// nodes, which the `nodes` part covers).
    pub fn of_mass(mass: &Mass) -> u64 {
        let mut h = Hash64::new();
        h.update(b"tvf-mass");
        h.update_u64(mass.len() as u64);
        h.update_u64(match mass.form() {
            MassForm::Direct => 0,
            MassForm::Inverse => 1,
        });
        match mass.storage() {
            MassStorage::Diagonal(values) => {
                h.update_u64(0);
                values.iter().for_each(|&m| h.update_f64(m));
            }
            MassStorage::Sparse(matrix) => {
                h.update_u64(1);
                h.update_u64(sparse_hash(matrix));
            }
        }
        h.finish()
    }

    /// The six part hashes: `d0`, `d1`, `M0`, `M1`, `M2`, nodes (see [`MatrixHash::PART_NAMES`]).
    pub fn parts(&self) -> [u64; 6] {
        [self.d0, self.d1, self.m0, self.m1, self.m2, self.nodes]
    }

    /// The hash with these six part hashes (as [`MatrixHash::parts`] gives them).
    pub fn from_parts(parts: [u64; 6]) -> Self {
        let [d0, d1, m0, m1, m2, nodes] = parts;
        Self {
            d0,
            d1,
            m0,
            m1,
            m2,
            nodes,
        }
    }

    /// The 64-bit hash of the whole complex: the [`Hash64`] of the six part hashes. Cache names
    /// carry it.
    pub fn value(&self) -> u64 {
        let mut h = Hash64::new();
        h.update(b"tvf-complex-matrices");
        self.parts().iter().for_each(|&part| h.update_u64(part));
        h.finish()
    }

    /// Names of the parts whose hashes differ from `other`'s (empty if none does).
    pub fn differing_parts(&self, other: &MatrixHash) -> Vec<&'static str> {
        Self::PART_NAMES
            .iter()
            .zip(self.parts().iter().zip(other.parts()))
            .filter(|(_, (a, b))| *a != b)
            .map(|(&name, _)| name)
            .collect()
    }
}

/// The hash of a sparse matrix: shape, then each row's stored entries (column and value bits)
/// in row-major order, whatever its storage.
fn sparse_hash(matrix: &CsMat<f64>) -> u64 {
    let matrix = as_csr(matrix);
    let mut h = Hash64::new();
    h.update(b"tvf-sparse");
    h.update_u64(matrix.rows() as u64);
    h.update_u64(matrix.cols() as u64);
    h.update_u64(matrix.nnz() as u64);
    for row in matrix.outer_iterator() {
        h.update_u64(row.nnz() as u64);
        for (column, &value) in row.iter() {
            h.update_u64(column as u64);
            h.update_f64(value);
        }
    }
    h.finish()
}

/// The hash of the fixed nodes and constant kernels of `spaces`, and the topology counts.
fn nodes_hash(spaces: &[&NodeSpace], component_count: usize, harmonic_dimension: usize) -> u64 {
    let mut h = Hash64::new();
    h.update(b"tvf-nodes");
    for space in spaces {
        h.update_u64(space.len() as u64);
        let dirichlet = (0..space.len()).filter(|&i| space.dirichlet.get(i) == Some(&true));
        let unused = (0..space.len()).filter(|&i| space.components[i] == NO_COMPONENT);
        for fixed in [dirichlet.collect::<Vec<_>>(), unused.collect()] {
            h.update_u64(fixed.len() as u64);
            fixed.iter().for_each(|&i| h.update_u64(i as u64));
        }
        h.update_u64(space.constant_kernel.len() as u64);
        for &kernel in &space.constant_kernel {
            h.update_u64(u64::from(kernel));
        }
    }
    h.update_u64(component_count as u64);
    h.update_u64(harmonic_dimension as u64);
    h.finish()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::discretization::{ComplexTopology, NodeKind};
    use sprs::TriMat;

    fn space(n: usize, dirichlet: Vec<bool>) -> NodeSpace {
        NodeSpace {
            kind: NodeKind::Vertices,
            positions: vec![[0.0; 3]; n],
            components: vec![0; n],
            dirichlet,
            constant_kernel: vec![true],
        }
    }

    /// A path of 3 potentials and 2 fields: `d0` the difference matrix, `d1` empty.
    fn parts(m1: Mass, field_dirichlet: Vec<bool>) -> ComplexParts {
        let mut d0 = TriMat::new((2, 3));
        for (row, (a, b)) in [(0, 1), (1, 2)].into_iter().enumerate() {
            d0.add_triplet(row, a, -1.0);
            d0.add_triplet(row, b, 1.0);
        }
        ComplexParts::new(
            "path",
            d0.to_csr(),
            CsMat::zero((0, 2)),
            [
                Mass::diagonal("M0", vec![1.0, 2.0, 1.0]).unwrap(),
                m1,
                Mass::diagonal("M2", vec![]).unwrap(),
            ],
            [
                space(3, vec![]),
                space(2, field_dirichlet),
                space(0, vec![]),
            ],
            ComplexTopology {
                component_count: 1,
                harmonic_dimension: 0,
                has_boundary: false,
                boundary_condition: Default::default(),
            },
        )
        .unwrap()
    }

    fn sparse_m1(off_diagonal: f64) -> Mass {
        let mut t = TriMat::new((2, 2));
        t.add_triplet(0, 0, 2.0);
        t.add_triplet(1, 1, 2.0);
        t.add_triplet(0, 1, off_diagonal);
        t.add_triplet(1, 0, off_diagonal);
        Mass::sparse("M1", t.to_csr()).unwrap()
    }

    #[test]
    fn every_part_is_seen_and_named() {
        let diagonal = || Mass::diagonal("M1", vec![1.0, 1.0]).unwrap();
        let base = parts(diagonal(), vec![]).matrix_hash();
        assert_eq!(base, parts(diagonal(), vec![]).matrix_hash());
        let sparse = parts(sparse_m1(0.5), vec![]).matrix_hash();
        assert_eq!(base.differing_parts(&sparse), vec!["M1"]);
        let changed = parts(sparse_m1(0.25), vec![]).matrix_hash();
        assert_eq!(sparse.differing_parts(&changed), vec!["M1"]);
        assert_ne!(sparse.value(), changed.value());
        let fixed = parts(diagonal(), vec![false, true]).matrix_hash();
        assert_eq!(base.differing_parts(&fixed), vec!["fixed nodes"]);
        assert_eq!(MatrixHash::from_parts(base.parts()), base);
    }

    #[test]
    fn storage_order_and_form_are_canonical_or_counted() {
        let m1 = sparse_m1(0.5);
        let MassStorage::Sparse(csr) = m1.storage() else {
            unreachable!("a sparse mass")
        };
        assert_eq!(sparse_hash(csr), sparse_hash(&csr.to_csc()));
        assert_ne!(MatrixHash::of_mass(&m1), MatrixHash::of_mass(&m1.inverse()));
        let diagonal = Mass::diagonal("M", vec![2.0, 2.0]).unwrap();
        let as_sparse = Mass::sparse("M", diagonal.stored_matrix()).unwrap();
        assert_ne!(
            MatrixHash::of_mass(&diagonal),
            MatrixHash::of_mass(&as_sparse)
        );
        let negative_zero = Mass::diagonal("M", vec![2.0, -0.0]).unwrap();
        let zero = Mass::diagonal("M", vec![2.0, 0.0]).unwrap();
        assert_ne!(
            MatrixHash::of_mass(&negative_zero),
            MatrixHash::of_mass(&zero)
        );
    }
}
