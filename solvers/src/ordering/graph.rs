//! [`AdjacencyGraph`]: the graph of a symmetric sparsity pattern (vertices = rows/columns, an
//! edge `i–j` for every stored off-diagonal entry), in the compressed form graph partitioners take.

use faer::sparse::SymbolicSparseColMatRef;

/// Undirected graph in compressed adjacency form: the neighbours of vertex `v` are
/// `neighbours[offsets[v]..offsets[v + 1]]`, sorted, without `v` itself and without repeats.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct AdjacencyGraph {
    /// `n + 1` offsets into `neighbours`.
    pub offsets: Vec<usize>,
    /// Concatenated sorted neighbour lists (every edge appears twice, once per endpoint).
    pub neighbours: Vec<usize>,
}

impl AdjacencyGraph {
    /// The graph of the symmetric matrix whose pattern is `pattern` (`n × n`, CSC): upper, lower
    /// or full storage all give the same graph, since every entry `(i, j)`, `i ≠ j`, adds the edge
    /// `i–j`. Duplicate and unsorted entries are allowed.
    pub fn from_symmetric_pattern(pattern: SymbolicSparseColMatRef<'_, usize>) -> Self {
        let n = pattern.ncols();
        let mut degree = vec![0usize; n];
        for j in 0..n {
            for &i in column_rows(pattern, j) {
                if i != j {
                    degree[i] += 1;
                    degree[j] += 1;
                }
            }
        }
        let mut offsets = Vec::with_capacity(n + 1);
        offsets.push(0);
        for d in &degree {
            offsets.push(offsets[offsets.len() - 1] + d);
        }
        let mut fill = offsets[..n].to_vec();
        let mut neighbours = vec![0usize; offsets[n]];
        for j in 0..n {
            for &i in column_rows(pattern, j) {
                if i != j {
                    neighbours[fill[i]] = j;
                    fill[i] += 1;
                    neighbours[fill[j]] = i;
                    fill[j] += 1;
                }
            }
        }
        // Sort and remove repeats (full storage lists every edge from both sides).
        let mut compact = Vec::with_capacity(neighbours.len());
        let mut compact_offsets = Vec::with_capacity(n + 1);
        compact_offsets.push(0);
        for v in 0..n {
            let list = &mut neighbours[offsets[v]..offsets[v + 1]];
            list.sort_unstable();
            let mut last = usize::MAX;
            for &w in list.iter() {
                if w != last {
                    compact.push(w);
                    last = w;
                }
            }
            compact_offsets.push(compact.len());
        }
        Self {
            offsets: compact_offsets,
            neighbours: compact,
        }
    }

    /// The quotient graph of the symmetric pattern `pattern` (`n × n` CSC, any storage) under
    /// `group` (`n` values in `0..group_count`): one vertex per group, an edge between two groups
    /// when an entry couples two of their members. Entries inside a group are dropped.
    ///
    /// # Panics
    /// If `group.len() != n` or a group is `≥ group_count` (programming errors).
    pub fn quotient_of_pattern(
        pattern: SymbolicSparseColMatRef<'_, usize>,
        group: &[usize],
        group_count: usize,
    ) -> Self {
        assert_eq!(group.len(), pattern.ncols(), "one group per row/column");
        let n = pattern.ncols();
        // Straight from the entries to the groups (no graph of the n unknowns): every entry
        // coupling two groups lists each in the other's bucket, repeats included.
        let mut bucket_ptr = vec![0usize; group_count + 1];
        for j in 0..n {
            for &i in column_rows(pattern, j) {
                if group[i] != group[j] {
                    bucket_ptr[group[i] + 1] += 1;
                    bucket_ptr[group[j] + 1] += 1;
                }
            }
        }
        for g in 0..group_count {
            bucket_ptr[g + 1] += bucket_ptr[g];
        }
        let mut fill = bucket_ptr[..group_count].to_vec();
        let mut bucket = vec![0usize; bucket_ptr[group_count]];
        for j in 0..n {
            for &i in column_rows(pattern, j) {
                let (gi, gj) = (group[i], group[j]);
                if gi != gj {
                    bucket[fill[gi]] = gj;
                    fill[gi] += 1;
                    bucket[fill[gj]] = gi;
                    fill[gj] += 1;
                }
            }
        }
        // Drop the repeats with a marker, then sort each (short) list.
        let mut marker = vec![usize::MAX; group_count];
        let mut offsets = Vec::with_capacity(group_count + 1);
        let mut neighbours = Vec::new();
        offsets.push(0);
        for g in 0..group_count {
            let start = neighbours.len();
            for &h in &bucket[bucket_ptr[g]..bucket_ptr[g + 1]] {
                if marker[h] != g {
                    marker[h] = g;
                    neighbours.push(h);
                }
            }
            neighbours[start..].sort_unstable();
            offsets.push(neighbours.len());
        }
        Self {
            offsets,
            neighbours,
        }
    }

    /// Number of vertices.
    pub fn vertex_count(&self) -> usize {
        self.offsets.len() - 1
    }

    /// Sorted neighbours of `v`.
    pub fn neighbours_of(&self, v: usize) -> &[usize] {
        &self.neighbours[self.offsets[v]..self.offsets[v + 1]]
    }
}

/// Row indices of the stored entries of column `j` of `pattern` (honouring `col_nnz` when the
/// columns are not packed).
fn column_rows(pattern: SymbolicSparseColMatRef<'_, usize>, j: usize) -> &[usize] {
    let start = pattern.col_ptr()[j];
    let end = match pattern.col_nnz() {
        Some(nnz) => start + nnz[j],
        None => pattern.col_ptr()[j + 1],
    };
    &pattern.row_idx()[start..end]
}
