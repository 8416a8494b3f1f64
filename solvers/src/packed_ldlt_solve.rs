//! The triangular solves of a supernodal `LDLᵀ` factor with right-hand sides packed in rows of
//! [`WIDTH`] (one 64-byte cache line per unknown), written by hand.
//!
//! Why: faer's supernodal solve (0.24) handles each supernode with a dense triangular solve and
//! a matrix product through its general kernels, then scatters the product into the
//! column-major right-hand side one column at a time, and applies the fill-reducing
//! permutation column by column before and after. On surface meshes most supernodes have a
//! handful of columns, so the per-supernode dispatch and the column-wise scatters dominate: for
//! the Crouzeix–Raviart bunny (104,499 unknowns) a solve with 8 right-hand sides took about
//! 37 ms. Here every update of an unknown is one 8-wide multiply–add on its packed row, the
//! permutation is applied while packing, and the loops are compiled with and without AVX2 +
//! FMA (chosen at run time).

use faer::perm::PermRef;
use faer::reborrow::{Reborrow, ReborrowMut};
use faer::sparse::linalg::cholesky::supernodal::{SupernodalLdltRef, SymbolicSupernodalCholesky};
use faer::MatMut;

use crate::packed_rows::{has_avx2_fma, multiply_add, Row, WIDTH};

/// Overwrites `rhs` (`n × r`) with the solution of `P L D Lᵀ Pᵀ X = rhs` for the supernodal
/// factor (`symbolic`, `values`) and the fill-reducing permutation `perm` (`None`: identity;
/// faer's convention: row `i` of the permuted system is row `perm.forward[i]` of the original),
/// [`WIDTH`] columns at a time.
pub(crate) fn solve_packed(
    symbolic: &SymbolicSupernodalCholesky<usize>,
    values: &[f64],
    perm: Option<PermRef<'_, usize>>,
    rhs: MatMut<'_, f64>,
) {
    solve_packed_with(symbolic, values, perm, rhs, solve_rows);
}

/// [`solve_packed`] with the portable loops whatever the CPU (to test them where FMA exists).
#[cfg(test)]
pub(crate) fn solve_packed_portable(
    symbolic: &SymbolicSupernodalCholesky<usize>,
    values: &[f64],
    perm: Option<PermRef<'_, usize>>,
    rhs: MatMut<'_, f64>,
) {
    solve_packed_with(symbolic, values, perm, rhs, solve_rows_body::<false>);
}

/// [`solve_packed`] with `solve` for the packed triangular solves.
fn solve_packed_with(
    symbolic: &SymbolicSupernodalCholesky<usize>,
    values: &[f64],
    perm: Option<PermRef<'_, usize>>,
    mut rhs: MatMut<'_, f64>,
    solve: fn(SupernodalLdltRef<'_, usize, f64>, &mut [Row]),
) {
    let n = rhs.nrows();
    let factor = SupernodalLdltRef::new(symbolic, values);
    let mut x: Vec<Row> = vec![[0.0; WIDTH]; n];
    let mut first = 0;
    while first < rhs.ncols() {
        let width = WIDTH.min(rhs.ncols() - first);
        // Row i of the permuted system is row forward[i] of rhs; one column at a time, so the
        // random accesses stay inside one contiguous column.
        let forward = perm.map(|p| p.arrays().0);
        x.iter_mut().for_each(|row| *row = [0.0; WIDTH]);
        for j in 0..width {
            let column = rhs.rb().col(first + j);
            match forward {
                Some(forward) => {
                    for (row, &from) in x.iter_mut().zip(forward) {
                        row[j] = column[from];
                    }
                }
                None => {
                    for (row, value) in x.iter_mut().zip(column.iter()) {
                        row[j] = *value;
                    }
                }
            }
        }
        solve(factor, &mut x);
        for j in 0..width {
            let mut column = rhs.rb_mut().col_mut(first + j);
            match forward {
                Some(forward) => {
                    for (row, &to) in x.iter().zip(forward) {
                        column[to] = row[j];
                    }
                }
                None => {
                    for (row, value) in x.iter().zip(column.iter_mut()) {
                        *value = row[j];
                    }
                }
            }
        }
        first += width;
    }
}

/// `x ← (L D Lᵀ)⁻¹ x` on packed rows.
fn solve_rows(factor: SupernodalLdltRef<'_, usize, f64>, x: &mut [Row]) {
    #[cfg(target_arch = "x86_64")]
    if has_avx2_fma() {
        // SAFETY: the CPU supports the features the function is compiled for.
        unsafe { solve_rows_fma(factor, x) };
        return;
    }
    solve_rows_body::<false>(factor, x);
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2,fma")]
fn solve_rows_fma(factor: SupernodalLdltRef<'_, usize, f64>, x: &mut [Row]) {
    solve_rows_body::<true>(factor, x);
}

/// `target − l · source` row-wise, fused when `FUSED` (only in functions compiled with FMA).
#[inline(always)]
fn subtract_scaled<const FUSED: bool>(target: &mut Row, l: f64, source: &Row) {
    for j in 0..WIDTH {
        target[j] = multiply_add::<FUSED>(-l, source[j], target[j]);
    }
}

#[inline(always)]
fn solve_rows_body<const FUSED: bool>(factor: SupernodalLdltRef<'_, usize, f64>, x: &mut [Row]) {
    let supernodes = factor.symbolic().n_supernodes();
    // Forward: L y = b, supernode by supernode, column by column (each column of a supernode's
    // block is contiguous: its unit lower-triangular part, then the rows of its pattern).
    for s in 0..supernodes {
        let node = factor.supernode(s);
        let (start, pattern, block) = (node.start(), node.pattern(), node.val());
        let size = block.ncols();
        for c in 0..size {
            let column = block
                .col(c)
                .try_as_col_major()
                .expect("contiguous supernode");
            let column = column.as_slice();
            let value = x[start + c];
            for (r, &l) in column.iter().enumerate().take(size).skip(c + 1) {
                subtract_scaled::<FUSED>(&mut x[start + r], l, &value);
            }
            for (&l, &row) in column[size..].iter().zip(pattern) {
                subtract_scaled::<FUSED>(&mut x[row], l, &value);
            }
        }
    }
    // Diagonal: D z = y (D is stored on the diagonal of the blocks).
    for s in 0..supernodes {
        let node = factor.supernode(s);
        let (start, block) = (node.start(), node.val());
        for c in 0..block.ncols() {
            let inverse = block[(c, c)].recip();
            x[start + c].iter_mut().for_each(|v| *v *= inverse);
        }
    }
    // Backward: Lᵀ x = z, supernodes and columns in reverse.
    for s in (0..supernodes).rev() {
        let node = factor.supernode(s);
        let (start, pattern, block) = (node.start(), node.pattern(), node.val());
        let size = block.ncols();
        for c in (0..size).rev() {
            let column = block
                .col(c)
                .try_as_col_major()
                .expect("contiguous supernode");
            let column = column.as_slice();
            let mut value = x[start + c];
            for (r, &l) in column.iter().enumerate().take(size).skip(c + 1) {
                subtract_scaled::<FUSED>(&mut value, l, &x[start + r]);
            }
            for (&l, &row) in column[size..].iter().zip(pattern) {
                subtract_scaled::<FUSED>(&mut value, l, &x[row]);
            }
            x[start + c] = value;
        }
    }
}
