//! Direct CSR assembly of a `2F × n` gradient matrix with (up to) three entries per row.

use sprs::CsMat;

/// Builds the `2F × columns` gradient whose face `t` has the three nodes `nodes[t]` with in-frame
/// gradients `gradients[t]`; rows `2t` and `2t+1` hold the `e1` and `e2` components. Assembled
/// straight into CSR (column indices sorted per row), no triplet pass; a node that appears twice
/// in a face (a face of an intrinsic triangulation may repeat a corner or a side) gets the sum of
/// its gradients.
pub fn assemble_gradient(
    columns: usize,
    nodes: impl Iterator<Item = [usize; 3]>,
    gradients: impl Iterator<Item = [[f64; 2]; 3]>,
) -> CsMat<f64> {
    let mut indptr = vec![0];
    let mut indices = Vec::new();
    let mut data = Vec::new();
    for (face_nodes, grads) in nodes.zip(gradients) {
        let mut order = [0usize, 1, 2];
        order.sort_unstable_by_key(|&c| face_nodes[c]);
        for component in [0, 1] {
            let row_start = indices.len();
            for &c in &order {
                if indices.len() > row_start && indices.last() == Some(&face_nodes[c]) {
                    *data.last_mut().expect("a value per index") += grads[c][component];
                } else {
                    indices.push(face_nodes[c]);
                    data.push(grads[c][component]);
                }
            }
            indptr.push(indices.len());
        }
    }
    let rows = indptr.len() - 1;
    CsMat::new((rows, columns), indptr, indices, data)
}
