"""Derived operators of a complex that are dense matrices: :class:`ComposedOperator`, a
``scipy.sparse.linalg.LinearOperator`` applied by tvf's Rust code."""

import numpy as np
import scipy.sparse.linalg as spla

from ._arrays import float_array


class ComposedOperator(spla.LinearOperator):
    """An operator of :func:`tvf.operators` that is not a sparse matrix: it contains the
    inverse of a sparse mass (``M0^-1`` of the consistent P1 mass, ``M1^-1`` of the Whitney
    mass) or a mass given by its sparse inverse (``M2`` of ``nonconforming-consistent``), so
    as a matrix it is dense. It is applied factor by factor in Rust — sparse products and the
    mass's sparse Cholesky factorization, computed once — and never formed.

    A ``scipy.sparse.linalg.LinearOperator`` of dtype float64: ``A @ x``, ``A.matvec(x)``,
    ``A.rmatvec(y)`` (``A^T y``), ``A @ X`` for a block ``X`` (``n x r``), ``A.T``, sums and
    products with other operators, and every SciPy solver that takes a LinearOperator
    (``scipy.sparse.linalg.cg``, ``eigsh``, ...). ``name`` is its key in :func:`tvf.operators`.
    To see a small one as a dense matrix: ``A @ np.eye(A.shape[1])`` (small meshes only).
    Inputs must be finite; the GIL is released while it runs."""

    def __init__(self, native):
        self._native = native
        self.name = native.name
        super().__init__(dtype=np.dtype(np.float64), shape=tuple(native.shape))

    def _matvec(self, x):
        return self._apply(self._native.matvec, np.asarray(x).reshape(-1))

    def _rmatvec(self, x):
        return self._apply(self._native.rmatvec, np.asarray(x).reshape(-1))

    def _matmat(self, X):
        return self._apply(self._native.matmat, X)

    def _rmatmat(self, X):
        return self._apply(self._native.rmatmat, X)

    def _apply(self, apply, x):
        x = np.asarray(x)
        if np.iscomplexobj(x):
            return self._apply(apply, x.real) + 1j * self._apply(apply, x.imag)
        return np.asarray(apply(float_array(x, self.name)))

    def __repr__(self):
        return f"<{self.shape[0]}x{self.shape[1]} tvf.ComposedOperator '{self.name}'>"
