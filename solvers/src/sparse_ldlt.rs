//! Supernodal sparse `LDLᵀ` factorization (no pivoting) with a fill-reducing ordering (AMD by
//! default, nested dissection on request: [`FillOrdering`]), reusable symbolic analysis, blocked solves and the inertia of the factored matrix.
//!
//! This is the workhorse behind [`crate::SparseCholesky`] (which additionally insists on
//! positive pivots) and the shift-and-invert eigensolver (which factors the indefinite
//! `A − σM` and reads the number of eigenvalues below σ off the signs of `D`, by
//! Sylvester's law of inertia).
//!
//! `LDLᵀ` without pivoting is backward stable for positive-definite matrices. For an
//! indefinite `A − σM` it can lose accuracy when σ is extremely close to an eigenvalue;
//! the eigensolver guards against this by checking every computed eigenpair's true residual
//! and by never placing a shift closer than a safe relative distance to a known eigenvalue.

use crate::error::SolverError;
use crate::ordering::{inverse_permutation, is_permutation, nested_dissection, FillOrdering};
use crate::packed_ldlt_solve::{
    inverse_energy_rows, solve_packed, solve_packed_rows, PackedFactor,
};
use crate::packed_rows::{Row, WIDTH};
use crate::packed_solve_split::SolveSplit;
use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::cholesky::ldlt::factor::{LdltError, LdltRegularization};
use faer::perm::PermRef;
use faer::sparse::linalg::cholesky::supernodal::SymbolicSupernodalCholesky;
use faer::sparse::linalg::cholesky::{
    factorize_symbolic_cholesky, CholeskySymbolicParams, LdltRef, SymbolicCholesky,
    SymbolicCholeskyRaw, SymmetricOrdering,
};
use faer::sparse::linalg::SupernodalThreshold;
use faer::sparse::SparseColMatRef;
use faer::{Conj, Mat, MatMut, Par, Side};
use std::sync::OnceLock;

/// Counts of negative, zero and positive pivots of an `LDLᵀ` factorization.
///
/// By Sylvester's law of inertia these equal the numbers of negative, zero and positive
/// eigenvalues of the factored symmetric matrix; for `A − σM` with `M` SPD, `negative` is the
/// number of generalized eigenvalues of `(A, M)` strictly below σ.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Inertia {
    /// Number of negative pivots.
    pub negative: usize,
    /// Number of exactly zero pivots.
    pub zero: usize,
    /// Number of positive pivots.
    pub positive: usize,
}

/// The fill-reducing permutation of a [`SparseLdlt`] and the pattern it was analysed for
/// ([`SparseLdlt::pattern`]): a few integers per nonzero, far smaller than the factor.
#[derive(Debug, Clone)]
pub struct FactorPattern {
    forward: Vec<usize>,
    inverse: Vec<usize>,
    col_ptr: Vec<usize>,
    row_idx: Vec<usize>,
    ordering: FillOrdering,
}

impl FactorPattern {
    /// A factorization of `upper` (the pattern this was taken from) with the same fill-reducing
    /// permutation (the symbolic analysis is repeated, which is cheap next to the numeric work)
    /// and the given parallelism.
    ///
    /// Errors: [`SolverError::PatternMismatch`], [`SolverError::Singular`].
    pub fn factor(
        &self,
        upper: SparseColMatRef<'_, usize, f64>,
        parallelism: Par,
    ) -> Result<SparseLdlt, SolverError> {
        if upper.nrows() != self.forward.len()
            || upper.symbolic().col_ptr() != self.col_ptr.as_slice()
            || upper.symbolic().row_idx() != self.row_idx.as_slice()
        {
            return Err(SolverError::PatternMismatch);
        }
        let permutation = PermRef::new_checked(&self.forward, &self.inverse, self.forward.len());
        let symbolic = analyse(upper, SymmetricOrdering::Custom(permutation))?;
        SparseLdlt::factor_analysed(upper, symbolic, self.ordering, parallelism, |len| {
            vec![0.0; len]
        })
    }
}

/// Sparse symmetric `LDLᵀ` factorization of an `n × n` matrix given by its upper triangle.
#[derive(Debug)]
pub struct SparseLdlt {
    symbolic: SymbolicCholesky<usize>,
    values: Vec<f64>,
    col_ptr: Vec<usize>,
    row_idx: Vec<usize>,
    parallelism: Par,
    ordering: FillOrdering,
    /// The split of the packed solves between two threads, made on the first solve that
    /// can use it (`None` inside: no useful split; see `packed_solve_split.rs`).
    split: OnceLock<Option<SolveSplit>>,
}

impl SparseLdlt {
    /// Symbolic analysis (AMD ordering, supernodal structure) and numeric factorization of the
    /// symmetric matrix whose upper triangle (CSC, row ≤ column, sorted rows) is `upper`.
    ///
    /// Errors: [`SolverError::Singular`] on an exactly zero pivot, [`SolverError::Factorization`]
    /// if faer runs out of memory or indices.
    pub fn new(upper: SparseColMatRef<'_, usize, f64>) -> Result<Self, SolverError> {
        Self::with_ordering(upper, FillOrdering::Amd)
    }

    /// [`SparseLdlt::new`] of a matrix that must be positive definite, set to solve on one
    /// thread ([`Par::Seq`]).
    ///
    /// Errors: [`SolverError::MatrixNotPositiveDefinite`] naming `matrix` on a zero, negative or
    /// non-finite pivot (at its original row), else as [`SparseLdlt::new`].
    pub(crate) fn positive_definite(
        upper: SparseColMatRef<'_, usize, f64>,
        matrix: &'static str,
    ) -> Result<Self, SolverError> {
        let not_positive = |pivot, value| SolverError::MatrixNotPositiveDefinite {
            matrix,
            pivot,
            value,
        };
        let mut factor = Self::new(upper).map_err(|e| match e {
            SolverError::Singular { pivot } => not_positive(pivot, 0.0),
            other => other,
        })?;
        factor.set_parallelism(Par::Seq);
        let pivots = factor.pivots();
        if let Some(k) = pivots.iter().position(|&d| !(d > 0.0 && d.is_finite())) {
            return Err(not_positive(factor.original_index(k), pivots[k]));
        }
        Ok(factor)
    }

    /// The same as [`SparseLdlt::new`] with the fill-reducing `ordering` of choice.
    ///
    /// Errors: those of [`SparseLdlt::new`], and [`SolverError::Factorization`] if the
    /// nested-dissection ordering fails.
    pub fn with_ordering(
        upper: SparseColMatRef<'_, usize, f64>,
        ordering: FillOrdering,
    ) -> Result<Self, SolverError> {
        match ordering {
            FillOrdering::Amd => Self::analyse_and_factor(upper, SymmetricOrdering::Amd, ordering),
            FillOrdering::NestedDissection => {
                let forward = nested_dissection(upper.symbolic())?;
                Self::with_permutation_of(upper, &forward, ordering)
            }
        }
    }

    /// The same as [`SparseLdlt::new`] with a fill-reducing permutation computed by the caller:
    /// `permutation[k]` is the original row/column eliminated `k`-th (e.g. a nested dissection
    /// of a smaller graph the matrix is built on, expanded to its unknowns).
    /// [`SparseLdlt::ordering`] then reports [`FillOrdering::NestedDissection`].
    ///
    /// Errors: those of [`SparseLdlt::new`], and [`SolverError::Factorization`] if `permutation`
    /// is not a permutation of `0..n`.
    pub fn with_permutation(
        upper: SparseColMatRef<'_, usize, f64>,
        permutation: &[usize],
    ) -> Result<Self, SolverError> {
        Self::with_permutation_of(upper, permutation, FillOrdering::NestedDissection)
    }

    /// The same as [`SparseLdlt::with_permutation`], with the parallelism of the numeric
    /// factorizations and solves chosen by `choose` from the flop count of one numeric
    /// factorization ([`SparseLdlt::factor_flop_count`], known after the symbolic analysis and
    /// before any numeric work). Small factors are faster sequentially (thread synchronisation
    /// costs more than the small supernodes gain), large ones in parallel; faer's global
    /// setting is left alone. The factor's values are also zeroed by all available threads
    /// before the numeric factorization, so the page faults of a fresh (often 100 MB or larger)
    /// allocation are taken in parallel instead of one by one inside the sequential sweep.
    ///
    /// Errors: those of [`SparseLdlt::with_permutation`].
    pub fn with_permutation_and_parallelism(
        upper: SparseColMatRef<'_, usize, f64>,
        permutation: &[usize],
        choose: impl FnOnce(f64) -> Par,
    ) -> Result<Self, SolverError> {
        let symbolic = Self::analyse_permuted(upper, permutation)?;
        let parallelism = choose(flop_count(&symbolic));
        Self::factor_analysed(
            upper,
            symbolic,
            FillOrdering::NestedDissection,
            parallelism,
            zeroed_by_all_threads,
        )
    }

    /// The fill-reducing permutation and the pattern of this factorization, without its
    /// values: what [`FactorPattern::factor`] needs to factor other matrices of the same pattern
    /// (the shifts `A − σM` of an eigenproblem) without a new ordering.
    pub fn pattern(&self) -> FactorPattern {
        let forward = match self.symbolic.perm() {
            Some(perm) => perm.arrays().0.to_vec(),
            None => (0..self.dimension()).collect(),
        };
        FactorPattern {
            inverse: inverse_permutation(&forward),
            forward,
            col_ptr: self.col_ptr.clone(),
            row_idx: self.row_idx.clone(),
            ordering: self.ordering,
        }
    }

    /// The same as [`SparseLdlt::with_ordering`], with the parallelism chosen as in
    /// [`SparseLdlt::with_permutation_and_parallelism`].
    ///
    /// Errors: those of [`SparseLdlt::with_ordering`].
    pub fn with_ordering_and_parallelism(
        upper: SparseColMatRef<'_, usize, f64>,
        ordering: FillOrdering,
        choose: impl FnOnce(f64) -> Par,
    ) -> Result<Self, SolverError> {
        let symbolic = match ordering {
            FillOrdering::Amd => analyse(upper, SymmetricOrdering::Amd)?,
            FillOrdering::NestedDissection => {
                let forward = nested_dissection(upper.symbolic())?;
                Self::analyse_permuted(upper, &forward)?
            }
        };
        let parallelism = choose(flop_count(&symbolic));
        Self::factor_analysed(
            upper,
            symbolic,
            ordering,
            parallelism,
            zeroed_by_all_threads,
        )
    }

    fn with_permutation_of(
        upper: SparseColMatRef<'_, usize, f64>,
        forward: &[usize],
        ordering: FillOrdering,
    ) -> Result<Self, SolverError> {
        let symbolic = Self::analyse_permuted(upper, forward)?;
        let parallelism = faer::get_global_parallelism();
        Self::factor_analysed(upper, symbolic, ordering, parallelism, |len| vec![0.0; len])
    }

    fn analyse_permuted(
        upper: SparseColMatRef<'_, usize, f64>,
        forward: &[usize],
    ) -> Result<SymbolicCholesky<usize>, SolverError> {
        let n = upper.ncols();
        if !is_permutation(forward, n) {
            return Err(SolverError::Factorization(format!(
                "the fill-reducing ordering is not a permutation of 0..{n}"
            )));
        }
        let inverse = inverse_permutation(forward);
        analyse(
            upper,
            SymmetricOrdering::Custom(PermRef::new_checked(forward, &inverse, n)),
        )
    }

    fn analyse_and_factor(
        upper: SparseColMatRef<'_, usize, f64>,
        symmetric_ordering: SymmetricOrdering<'_, usize>,
        ordering: FillOrdering,
    ) -> Result<Self, SolverError> {
        let symbolic = analyse(upper, symmetric_ordering)?;
        let parallelism = faer::get_global_parallelism();
        Self::factor_analysed(upper, symbolic, ordering, parallelism, |len| vec![0.0; len])
    }

    fn factor_analysed(
        upper: SparseColMatRef<'_, usize, f64>,
        symbolic: SymbolicCholesky<usize>,
        ordering: FillOrdering,
        parallelism: Par,
        zeroed: impl FnOnce(usize) -> Vec<f64>,
    ) -> Result<Self, SolverError> {
        let mut this = Self {
            values: zeroed(symbolic.len_val()),
            symbolic,
            col_ptr: upper.symbolic().col_ptr().to_vec(),
            row_idx: upper.symbolic().row_idx().to_vec(),
            parallelism,
            ordering,
            split: OnceLock::new(),
        };
        this.factor_numeric(upper)?;
        Ok(this)
    }

    /// The fill-reducing ordering this factorization was analysed with.
    pub fn ordering(&self) -> FillOrdering {
        self.ordering
    }

    /// Dimension `n` of the factored matrix.
    pub fn dimension(&self) -> usize {
        self.symbolic.nrows()
    }

    /// Sets the parallelism of later factorizations and solves (default: faer's global setting).
    /// For many small supernodes (2D meshes) `Par::Seq` solves are faster than parallel ones.
    pub fn set_parallelism(&mut self, parallelism: Par) {
        self.parallelism = parallelism;
    }

    /// The parallelism of numeric factorizations and solves (faer's global setting at
    /// construction, unless chosen otherwise).
    pub fn parallelism(&self) -> Par {
        self.parallelism
    }

    /// Number of stored values of the factor `L` (a measure of fill-in).
    pub fn factor_len(&self) -> usize {
        self.values.len()
    }

    /// Floating-point operations of one numeric factorization, `Σ_j c_j²` over the columns `j` of
    /// `L` with `c_j` stored entries on and below the diagonal (a deterministic measure of the
    /// numeric cost of an ordering, independent of the machine's load).
    pub fn factor_flop_count(&self) -> f64 {
        flop_count(&self.symbolic)
    }

    /// Whether `upper` has exactly the sparsity pattern analysed in [`SparseLdlt::new`].
    pub fn same_pattern(&self, upper: SparseColMatRef<'_, usize, f64>) -> bool {
        upper.nrows() == self.dimension()
            && upper.symbolic().col_ptr() == self.col_ptr.as_slice()
            && upper.symbolic().row_idx() == self.row_idx.as_slice()
    }

    /// Numeric refactorization of a matrix with the analysed pattern (symbolic analysis reused).
    ///
    /// Errors: [`SolverError::PatternMismatch`], [`SolverError::Singular`].
    pub fn refactor(&mut self, upper: SparseColMatRef<'_, usize, f64>) -> Result<(), SolverError> {
        if !self.same_pattern(upper) {
            return Err(SolverError::PatternMismatch);
        }
        self.factor_numeric(upper)
    }

    fn factor_numeric(
        &mut self,
        upper: SparseColMatRef<'_, usize, f64>,
    ) -> Result<(), SolverError> {
        let par = self.parallelism;
        let req = self
            .symbolic
            .factorize_numeric_ldlt_scratch::<f64>(par, Default::default());
        let mut buffer = MemBuffer::try_new(req)
            .map_err(|_| SolverError::Factorization("out of memory".into()))?;
        let result = self.symbolic.factorize_numeric_ldlt::<f64>(
            &mut self.values,
            upper,
            Side::Upper,
            LdltRegularization::default(),
            par,
            MemStack::new(&mut buffer),
            Default::default(),
        );
        match result {
            Ok(_) => Ok(()),
            // faer numbers the failed pivot from one in its simplicial factorization and from
            // zero in its supernodal one.
            Err(LdltError::ZeroPivot { index }) => {
                let index = match self.symbolic.raw() {
                    SymbolicCholeskyRaw::Simplicial(_) => index.saturating_sub(1),
                    SymbolicCholeskyRaw::Supernodal(_) => index,
                };
                Err(SolverError::Singular {
                    pivot: self.original_index(index),
                })
            }
        }
    }

    /// Original row/column number of the `permuted`-th pivot.
    pub fn original_index(&self, permuted: usize) -> usize {
        match self.symbolic.perm() {
            Some(perm) => perm.arrays().0.get(permuted).copied().unwrap_or(permuted),
            None => permuted,
        }
    }

    /// The pivots `D` in elimination (permuted) order; use [`SparseLdlt::original_index`] to
    /// map a position back to the input numbering.
    pub fn pivots(&self) -> Vec<f64> {
        let mut d = vec![0.0; self.dimension()];
        if let SymbolicCholeskyRaw::Supernodal(sym) = self.symbolic.raw() {
            let col_ptr_val = sym.col_ptr_for_val();
            let begin = sym.supernode_begin();
            let end = sym.supernode_end();
            for s in 0..sym.n_supernodes() {
                let ncols = end[s] - begin[s];
                let block = &self.values[col_ptr_val[s]..col_ptr_val[s + 1]];
                let nrows = block.len() / ncols.max(1);
                for c in 0..ncols {
                    d[begin[s] + c] = block[c * nrows + c];
                }
            }
        }
        if let SymbolicCholeskyRaw::Simplicial(sym) = self.symbolic.raw() {
            // faer picks the simplicial factor for very sparse patterns (e.g. a diagonal
            // matrix); each column of `L` stores its diagonal entry, which holds `D`, first.
            let col_ptr = sym.col_ptr();
            for (j, pivot) in d.iter_mut().enumerate() {
                *pivot = self.values[col_ptr[j]];
            }
        }
        d
    }

    /// Signs of the pivots: the inertia of the factored matrix.
    pub fn inertia(&self) -> Inertia {
        let mut inertia = Inertia {
            negative: 0,
            zero: 0,
            positive: 0,
        };
        for d in self.pivots() {
            if d < 0.0 {
                inertia.negative += 1;
            } else if d > 0.0 {
                inertia.positive += 1;
            } else {
                inertia.zero += 1;
            }
        }
        inertia
    }

    /// Overwrites the `n × r` block `rhs` with the solution `X` of `(L D Lᵀ) X = rhs`.
    /// The right-hand sides go through the supernodal triangular solves eight at a time, packed
    /// in rows (`packed_ldlt_solve.rs`). With a
    /// parallelism of `t > 1` threads and `r ≥ 2`, the columns are split into `min(t, r)` groups
    /// solved concurrently, each by a sequential supernodal solve: faer's parallel solve
    /// synchronises its threads at every supernode, which on surface meshes costs more than it
    /// gains, while independent columns need no synchronisation (the result does not depend on the
    /// split). A single right-hand side uses faer's parallel solve.
    ///
    /// # Panics
    /// If `rhs.nrows() != self.dimension()` (a programming error).
    pub fn solve_in_place(&self, rhs: MatMut<'_, f64>) {
        assert_eq!(
            rhs.nrows(),
            self.dimension(),
            "right-hand side has the wrong number of rows"
        );
        let groups = self.parallelism.degree().min(rhs.ncols());
        if groups >= 2 {
            self.solve_column_groups(rhs, groups);
        } else {
            self.solve_with(rhs, self.parallelism);
        }
    }

    /// The elimination order of the factorization: row `i` of the factored (permuted) system is
    /// row `order[i]` of the input numbering (`None`: the input order itself).
    pub fn elimination_order(&self) -> Option<&[usize]> {
        self.symbolic.perm().map(|perm| perm.arrays().0)
    }

    /// [`solve_in_place`](Self::solve_in_place) for right-hand sides whose rows are in
    /// [elimination order](Self::elimination_order) (row `i` holds input row `order[i]`); the
    /// solutions come back in the same order. A caller that keeps its vectors in this order
    /// (the Krylov slices) saves the gather and scatter through the permutation on every solve.
    ///
    /// # Panics
    /// If `rhs.nrows() != self.dimension()` (a programming error).
    pub fn solve_in_elimination_order(&self, mut rhs: MatMut<'_, f64>) {
        if let Some(factor) = self.packed_factor(rhs.nrows()) {
            solve_packed(factor, None, rhs);
            return;
        }
        let Some(order) = self.elimination_order() else {
            self.solve_in_place(rhs);
            return;
        };
        // Other factorizations solve in the input numbering.
        let mut input = Mat::<f64>::zeros(rhs.nrows(), rhs.ncols());
        for j in 0..rhs.ncols() {
            for (i, &row) in order.iter().enumerate() {
                input[(row, j)] = rhs[(i, j)];
            }
        }
        self.solve_in_place(input.as_mut());
        for j in 0..rhs.ncols() {
            for (i, &row) in order.iter().enumerate() {
                rhs[(i, j)] = input[(row, j)];
            }
        }
    }

    /// [`Self::solve_in_elimination_order`] on packed rows: `rows` (`n` rows of [`WIDTH`]
    /// right-hand sides, in elimination order) is overwritten with the solutions. A caller that
    /// packs its block anyway (the Krylov expansion scales it by `M` while packing) saves the
    /// packing and unpacking of the column-major solve.
    ///
    /// # Panics
    /// If `rows.len() != self.dimension()` (a programming error).
    pub(crate) fn solve_rows_in_elimination_order(&self, rows: &mut [Row]) {
        if let Some(factor) = self.packed_factor(rows.len()) {
            solve_packed_rows(factor, rows);
            return;
        }
        let mut block = Mat::from_fn(rows.len(), WIDTH, |i, j| rows[i][j]);
        self.solve_in_elimination_order(block.as_mut());
        for (i, row) in rows.iter_mut().enumerate() {
            *row = std::array::from_fn(|j| block[(i, j)]);
        }
    }

    /// `bᵀ A⁻¹ b` for each packed column `b` of `rows` (`n` rows in elimination order, as
    /// [`Self::solve_rows_in_elimination_order`] takes them; overwritten with scratch values),
    /// `A = L D Lᵀ` the factored matrix: on one thread the forward pass alone
    /// ([`inverse_energy_rows`]), otherwise a solve and the products.
    pub(crate) fn inverse_energy_rows_in_elimination_order(&self, rows: &mut [Row]) -> Row {
        if let Some(factor) = self.packed_factor(rows.len()) {
            return inverse_energy_rows(factor, rows);
        }
        let right = rows.to_vec();
        self.solve_rows_in_elimination_order(rows);
        let mut energy = [0.0; WIDTH];
        for (b, x) in right.iter().zip(rows.iter()) {
            for j in 0..WIDTH {
                energy[j] += b[j] * x[j];
            }
        }
        energy
    }

    /// A supernodal factor solved on one thread, which the packed loops handle (`None`:
    /// another kind of factor or solve), after checking that right-hand sides of `rows` rows
    /// fit.
    ///
    /// # Panics
    /// If `rows != self.dimension()` (a programming error).
    fn packed_factor(&self, rows: usize) -> Option<PackedFactor<'_>> {
        assert_eq!(
            rows,
            self.dimension(),
            "right-hand side has the wrong number of rows"
        );
        match (self.symbolic.raw(), self.parallelism.degree()) {
            (SymbolicCholeskyRaw::Supernodal(symbolic), 1) => Some(self.packed(symbolic)),
            _ => None,
        }
    }

    /// This factor's values on `symbolic` (its supernodal structure) for the packed loops, with
    /// its split between two threads (made on first use: the packed loops give the same bits
    /// with it, on one thread or two).
    fn packed<'a>(&'a self, symbolic: &'a SymbolicSupernodalCholesky<usize>) -> PackedFactor<'a> {
        PackedFactor {
            symbolic,
            values: &self.values,
            split: self.split.get_or_init(|| SolveSplit::of(symbolic)).as_ref(),
        }
    }

    /// Solves the columns of `rhs` in `groups` concurrent groups, each sequentially.
    fn solve_column_groups(&self, rhs: MatMut<'_, f64>, groups: usize) {
        if groups <= 1 {
            self.solve_with(rhs, Par::Seq);
            return;
        }
        let left_groups = groups / 2;
        let split = rhs.ncols() * left_groups / groups;
        let (left, right) = rhs.split_at_col_mut(split);
        rayon::join(
            || self.solve_column_groups(left, left_groups),
            || self.solve_column_groups(right, groups - left_groups),
        );
    }

    /// One solve of all columns of `rhs`: on one thread, a supernodal factor is solved by
    /// [`solve_packed`] (right-hand sides packed in rows); otherwise faer's solve with its
    /// parallelism `par`.
    fn solve_with(&self, rhs: MatMut<'_, f64>, par: Par) {
        if let (SymbolicCholeskyRaw::Supernodal(symbolic), 1) = (self.symbolic.raw(), par.degree())
        {
            solve_packed(self.packed(symbolic), self.symbolic.perm(), rhs);
            return;
        }
        let req = self
            .symbolic
            .solve_in_place_scratch::<f64>(rhs.ncols(), par);
        let mut buffer = MemBuffer::new(req);
        LdltRef::new(&self.symbolic, &self.values).solve_in_place_with_conj(
            Conj::No,
            rhs,
            par,
            MemStack::new(&mut buffer),
        );
    }
}

/// Symbolic analysis (supernodal) of the symmetric matrix with upper triangle `upper`.
fn analyse(
    upper: SparseColMatRef<'_, usize, f64>,
    symmetric_ordering: SymmetricOrdering<'_, usize>,
) -> Result<SymbolicCholesky<usize>, SolverError> {
    let params = CholeskySymbolicParams {
        supernodal_flop_ratio_threshold: SupernodalThreshold::FORCE_SUPERNODAL,
        ..Default::default()
    };
    factorize_symbolic_cholesky(upper.symbolic(), Side::Upper, symmetric_ordering, params)
        .map_err(|e| SolverError::Factorization(format!("{e:?}")))
}

/// `Σ_j c_j²` over the columns of the supernodal factor (see [`SparseLdlt::factor_flop_count`]).
fn flop_count(symbolic: &SymbolicCholesky<usize>) -> f64 {
    let mut flops = 0.0;
    if let SymbolicCholeskyRaw::Supernodal(sym) = symbolic.raw() {
        let col_ptr_val = sym.col_ptr_for_val();
        let begin = sym.supernode_begin();
        let end = sym.supernode_end();
        for s in 0..sym.n_supernodes() {
            let ncols = end[s] - begin[s];
            let nrows = (col_ptr_val[s + 1] - col_ptr_val[s]) / ncols.max(1);
            for c in 0..ncols {
                let count = (nrows - c) as f64;
                flops += count * count;
            }
        }
    }
    flops
}

/// Below this many values (8 MB) one thread zeroes faster than spawning others.
const PARALLEL_ZEROING_MIN_LEN: usize = 1 << 20;

/// `len` zeros, written once more by all available threads (one contiguous slice each): a
/// large `vec![0.0; len]` is fresh zero pages mapped lazily, so this write takes the
/// first-touch page faults in parallel instead of inside the (possibly sequential) numeric
/// factorization.
fn zeroed_by_all_threads(len: usize) -> Vec<f64> {
    let mut values = vec![0.0; len];
    let threads = std::thread::available_parallelism().map_or(1, |t| t.get());
    if threads > 1 && len >= PARALLEL_ZEROING_MIN_LEN {
        std::thread::scope(|scope| {
            for part in values.chunks_mut(len.div_ceil(threads)) {
                scope.spawn(move || part.fill(0.0));
            }
        });
    }
    values
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::packed_solve_split::NOT_KEPT;
    use faer::sparse::Triplet;
    use faer::Mat;

    /// Upper triangle of `L − σI` for the 5-point Laplacian `L` of a `side × side` grid with
    /// varying weights (indefinite for σ inside the spectrum).
    fn shifted_grid(side: usize, sigma: f64) -> faer::sparse::SparseColMat<usize, f64> {
        let index = |i: usize, j: usize| i * side + j;
        let mut diagonal = vec![-sigma; side * side];
        let mut triplets = Vec::new();
        for i in 0..side {
            for j in 0..side {
                for (di, dj) in [(1, 0), (0, 1)] {
                    if i + di < side && j + dj < side {
                        let (a, b) = (index(i, j), index(i + di, j + dj));
                        let w = 1.0 + ((a * 7 + b * 3) % 5) as f64 / 4.0;
                        triplets.push(Triplet::new(a.min(b), a.max(b), -w));
                        diagonal[a] += w;
                        diagonal[b] += w;
                    }
                }
            }
        }
        triplets.extend(
            diagonal
                .iter()
                .enumerate()
                .map(|(k, &d)| Triplet::new(k, k, d)),
        );
        faer::sparse::SparseColMat::try_new_from_triplets(side * side, side * side, &triplets)
            .expect("valid triplets")
    }

    /// faer's own supernodal solve of `rhs` with `ldlt` (the reference of the packed solves).
    fn faer_solution(ldlt: &SparseLdlt, rhs: &Mat<f64>) -> Mat<f64> {
        let mut solution = rhs.clone();
        let req = ldlt
            .symbolic
            .solve_in_place_scratch::<f64>(rhs.ncols(), Par::Seq);
        let mut buffer = MemBuffer::new(req);
        LdltRef::new(&ldlt.symbolic, &ldlt.values).solve_in_place_with_conj(
            Conj::No,
            solution.as_mut(),
            Par::Seq,
            MemStack::new(&mut buffer),
        );
        solution
    }

    /// The supernodal structure of `ldlt` (every factor here is supernodal).
    fn supernodal_of(ldlt: &SparseLdlt) -> &SymbolicSupernodalCholesky<usize> {
        let SymbolicCholeskyRaw::Supernodal(symbolic) = ldlt.symbolic.raw() else {
            panic!("factors are supernodal");
        };
        symbolic
    }

    /// The dense symmetric matrix whose upper triangle is `upper`.
    fn full_symmetric(upper: &faer::sparse::SparseColMat<usize, f64>) -> Mat<f64> {
        let n = upper.nrows();
        let upper = upper.to_dense();
        Mat::from_fn(
            n,
            n,
            |i, j| if i <= j { upper[(i, j)] } else { upper[(j, i)] },
        )
    }

    #[test]
    fn split_packed_solves_give_the_same_bits_as_one_thread() {
        let upper = shifted_grid(70, 0.61);
        let n = upper.nrows();
        for ordering in [FillOrdering::Amd, FillOrdering::NestedDissection] {
            let ldlt = SparseLdlt::with_ordering(upper.as_ref(), ordering).expect("factors");
            let split = ldlt.packed(supernodal_of(&ldlt));
            let whole = PackedFactor {
                split: None,
                ..split
            };
            let parts = split.split.expect("a 4900-unknown grid factor is split");
            assert!(!parts.first_nodes().is_empty() && !parts.second_nodes().is_empty());
            assert!(
                parts.kept_bases().iter().any(|&base| base != NOT_KEPT),
                "{ordering:?}: the parts reach the top"
            );
            // 11 columns: a packed chunk of 8 and a partial one, through the permutation.
            let rhs = Mat::from_fn(n, 11, |i, j| ((i * 13 + j * 7) % 23) as f64 / 11.0 - 1.0);
            let (mut one, mut two) = (rhs.clone(), rhs.clone());
            solve_packed(whole, ldlt.symbolic.perm(), one.as_mut());
            solve_packed(split, ldlt.symbolic.perm(), two.as_mut());
            let bits = |x: &Mat<f64>| -> Vec<u64> {
                (0..x.ncols())
                    .flat_map(|j| (0..x.nrows()).map(move |i| (i, j)))
                    .map(|(i, j)| x[(i, j)].to_bits())
                    .collect()
            };
            assert_eq!(bits(&one), bits(&two), "{ordering:?}: solutions differ");
            // And it is a solution: a residual within 4× of faer's own solve's.
            let reference = faer_solution(&ldlt, &rhs);
            let full = full_symmetric(&upper);
            let residual =
                |x: &Mat<f64>| (&full * x - &rhs).norm_max() / (full.norm_max() * x.norm_max());
            let (ours, faers) = (residual(&two), residual(&reference));
            assert!(
                ours <= 4.0 * faers + 1e-15,
                "{ordering:?}: residual {ours:e}, faer {faers:e}"
            );
            // The forward pass alone (inverse energies) too.
            let rows: Vec<Row> = (0..n)
                .map(|i| std::array::from_fn(|j| ((i * 5 + j * 3) % 17) as f64 - 8.0))
                .collect();
            let (mut one, mut two) = (rows.clone(), rows);
            let (e1, e2) = (
                inverse_energy_rows(whole, &mut one),
                inverse_energy_rows(split, &mut two),
            );
            assert_eq!(e1.map(f64::to_bits), e2.map(f64::to_bits));
            assert!(one
                .iter()
                .zip(&two)
                .all(|(a, b)| a.map(f64::to_bits) == b.map(f64::to_bits)));
        }
    }

    #[test]
    fn small_factors_are_not_split() {
        let upper = shifted_grid(8, 0.61);
        let ldlt = SparseLdlt::new(upper.as_ref()).expect("factors");
        assert!(ldlt.packed(supernodal_of(&ldlt)).split.is_none());
    }

    #[test]
    fn packed_solve_matches_faer_and_has_a_small_residual() {
        let upper = shifted_grid(37, 0.61);
        let n = upper.nrows();
        for ordering in [FillOrdering::Amd, FillOrdering::NestedDissection] {
            let ldlt = SparseLdlt::with_ordering(upper.as_ref(), ordering).expect("factors");
            assert!(ldlt.inertia().negative > 0, "the test matrix is indefinite");
            // 19 columns: two packed chunks of 8 and a partial one.
            let rhs = Mat::from_fn(n, 19, |i, j| ((i * 13 + j * 7) % 23) as f64 / 11.0 - 1.0);
            let mut packed = rhs.clone();
            ldlt.solve_with(packed.as_mut(), Par::Seq);
            let reference = faer_solution(&ldlt, &rhs);
            let mut portable = rhs.clone();
            crate::packed_ldlt_solve::solve_packed_portable(
                PackedFactor {
                    symbolic: supernodal_of(&ldlt),
                    values: &ldlt.values,
                    split: None,
                },
                ldlt.symbolic.perm(),
                portable.as_mut(),
            );
            let scale = reference.norm_max();
            assert!((&packed - &reference).norm_max() <= 1e-12 * scale);
            // Residuals, with the full symmetric matrix. The portable loops round differently
            // (no fused multiply–add), and on this indefinite matrix the forward difference
            // scales with its condition number (measured 1.8e-12 relative), so they are held to
            // the residual, as the others.
            let full = full_symmetric(&upper);
            let residual =
                |x: &Mat<f64>| (&full * x - &rhs).norm_max() / (full.norm_max() * x.norm_max());
            let faers = residual(&reference);
            for (name, x) in [("packed", &packed), ("portable", &portable)] {
                let ours = residual(x);
                // faer's own solve reaches 1.8e-13 on this matrix: within 4× of it, and 1e-12.
                assert!(
                    ours <= 1e-12 && ours <= 4.0 * faers + 1e-15,
                    "{name} {ours:e}, faer {faers:e}"
                );
            }
        }
    }

    /// Solving in elimination order gives the solution of the input-order solve, permuted: on
    /// one thread (the packed solve without the permutation) and on two (through faer's solve in
    /// the input numbering), column-major and on packed rows.
    #[test]
    fn solve_in_elimination_order_is_the_permuted_solve() {
        let upper = shifted_grid(29, 0.47);
        let n = upper.nrows();
        let rhs = Mat::from_fn(n, 11, |i, j| ((i * 5 + j * 17) % 19) as f64 / 9.0 - 1.0);
        for parallelism in [Par::Seq, Par::rayon(2)] {
            let mut ldlt =
                SparseLdlt::with_ordering(upper.as_ref(), FillOrdering::NestedDissection)
                    .expect("factors");
            ldlt.set_parallelism(parallelism);
            let order = ldlt.elimination_order().expect("a fill ordering").to_vec();
            assert!(order.iter().enumerate().any(|(i, &row)| i != row));
            let mut input = rhs.clone();
            ldlt.solve_in_place(input.as_mut());
            let mut permuted = Mat::from_fn(n, rhs.ncols(), |i, j| rhs[(order[i], j)]);
            ldlt.solve_in_elimination_order(permuted.as_mut());
            let expected = Mat::from_fn(n, rhs.ncols(), |i, j| input[(order[i], j)]);
            let difference = (&permuted - &expected).norm_max();
            assert!(
                difference <= 1e-12 * expected.norm_max(),
                "{parallelism:?}: {difference:e}"
            );
            // The same solve on packed rows (the first WIDTH columns).
            let mut rows: Vec<Row> = (0..n)
                .map(|i| std::array::from_fn(|j| rhs[(order[i], j)]))
                .collect();
            ldlt.solve_rows_in_elimination_order(&mut rows);
            let packed_difference = (0..n)
                .flat_map(|i| (0..WIDTH).map(move |j| (i, j)))
                .map(|(i, j)| (rows[i][j] - expected[(i, j)]).abs())
                .fold(0.0f64, f64::max);
            assert!(
                packed_difference <= 1e-12 * expected.norm_max(),
                "{parallelism:?}, packed rows: {packed_difference:e}"
            );
        }
    }

    /// A refactorization gives the same values as the first factorization, and a zero pivot is
    /// named by its row in faer's simplicial and supernodal factorizations alike.
    #[test]
    fn refactorization_and_the_row_of_a_zero_pivot() {
        let upper = shifted_grid(17, 0.47);
        let mut ldlt = SparseLdlt::with_ordering(upper.as_ref(), FillOrdering::NestedDissection)
            .expect("factors");
        ldlt.set_parallelism(Par::Seq);
        let first = ldlt.values.clone();
        ldlt.refactor(upper.as_ref()).expect("refactors");
        assert_eq!(ldlt.values, first);

        // A zero pivot, named by its row: an isolated row with a zero diagonal, in a small
        // matrix (faer's simplicial factorization) and in the grid (supernodal or not).
        let with_isolated_row = |matrix: &faer::sparse::SparseColMat<usize, f64>, row: usize| {
            let mut triplets = Vec::new();
            for j in 0..matrix.ncols() {
                let column = matrix.as_ref().col_range(j);
                let rows = &matrix.symbolic().row_idx()[column.clone()];
                for (&i, &value) in rows.iter().zip(&matrix.val()[column]) {
                    let value = if i == row || j == row { 0.0 } else { value };
                    triplets.push(Triplet::new(i, j, value));
                }
            }
            let n = matrix.nrows();
            faer::sparse::SparseColMat::<usize, f64>::try_new_from_triplets(n, n, &triplets)
                .expect("the same pattern")
        };
        let diagonal = |n: usize| {
            let triplets: Vec<_> = (0..n).map(|i| Triplet::new(i, i, 1.0 + i as f64)).collect();
            faer::sparse::SparseColMat::<usize, f64>::try_new_from_triplets(n, n, &triplets)
                .expect("a diagonal matrix")
        };
        let mut supernodal = Vec::new();
        let cases = [
            (diagonal(1), 0, FillOrdering::Amd),
            (diagonal(3), 1, FillOrdering::Amd),
            (upper.clone(), 100, FillOrdering::NestedDissection),
        ];
        for (matrix, row, ordering) in cases {
            let mut factor = SparseLdlt::with_ordering(matrix.as_ref(), ordering).expect("factors");
            factor.set_parallelism(Par::Seq);
            supernodal.push(matches!(
                factor.symbolic.raw(),
                SymbolicCholeskyRaw::Supernodal(_)
            ));
            let singular = with_isolated_row(&matrix, row);
            let refactored = factor.refactor(singular.as_ref());
            assert!(
                matches!(refactored, Err(SolverError::Singular { pivot }) if pivot == row),
                "row {row} of {}: {refactored:?}",
                matrix.nrows()
            );
        }
        assert_eq!(
            supernodal,
            [false, false, true],
            "both of faer's factorizations"
        );
    }
}
