"""tvf's generalized eigensolver on your own matrices: :func:`eigsh`."""

import numpy as np

from . import _native
from ._arrays import csr_parts, declared_shape, integer, mass
from ._native import TvfError


def eigsh(A, M, k, seed=None, progress=None, return_residuals=False):
    """The lowest ``k`` eigenpairs of ``A x = l M x``: a drop-in for
    ``scipy.sparse.linalg.eigsh(A, k, M=M, sigma=-eps, which="LM")`` on Laplacian-like
    pencils.

    - ``A``: ``n x n`` symmetric positive semi-definite ``scipy.sparse`` matrix (or dense),
      e.g. a stiffness (cotan) matrix; zero eigenvalues (one per connected component) are fine,
      mildly negative ones are found too. Only the upper triangle is read.
    - ``M``: the mass, symmetric positive definite: the ``n`` positive entries of a diagonal
      (a vector, or a diagonal matrix), or a sparse matrix with off-diagonal entries (any
      ``scipy.sparse`` format or a dense array, e.g. the consistent P1 mass
      ``|T| (1 + delta_ij) / 12`` per triangle), symmetric to round-off
      (``max|M - M^T| <= 1e-12 max|M|``) and positive definite (its sparse Cholesky
      factorization fails otherwise, a :class:`tvf.TvfError` naming ``M``).
    - ``k``: number of eigenpairs, ``k <= n``.

    Returns ``(eigenvalues, eigenvectors)`` as SciPy does: ``(k,)`` ascending and ``(n, k)``,
    ``M``-orthonormal columns (``X.T @ (M @ X) = I``); with ``return_residuals=True`` also the
    relative residuals ``|A x - l M x| / (|A|_1 |x|)``.

    How it differs from SciPy's shift-invert ``eigsh``: it returns *the lowest* ``k``
    eigenvalues with completeness verified by Sylvester's law of inertia (``LDL^T`` of
    ``A - s M`` counts the eigenvalues below ``s``), so no eigenvalue of a multiple cluster is
    skipped and zero eigenvalues need no shift; it handles large ``k`` (hundreds to thousands)
    by spectrum slicing (several shifts, one sparse factorization each) instead of one Krylov
    space; eigenvector signs (and the basis inside a multiple eigenvalue's eigenspace) are
    arbitrary, as in SciPy. A sparse ``M`` costs more than a diagonal one: the shifted
    matrices ``A - s M`` have the union of both patterns, and ``M^-1`` is a Cholesky solve.
    ``seed`` fixes the random start vectors. ``progress(stage, confirmed, wanted)`` is called
    as eigenpairs are confirmed. The GIL is released while it runs."""
    k = integer(k, "k")
    if k < 0:
        raise TvfError(f"k = {k}: ask for at least one eigenpair")
    seed = None if seed is None else integer(seed, "seed")
    shape = declared_shape(A)
    if len(shape) != 2 or shape[0] != shape[1]:
        raise TvfError(f"A: expected a square matrix, got shape {shape}")
    n, mass_shape = shape[0], declared_shape(M)
    if not mass_shape or mass_shape[0] != n:
        rows = mass_shape[0] if mass_shape else 0
        raise TvfError(f"M (the mass matrix) has {rows} rows, A has {n}")
    if mass_shape not in ((n,), (n, n)):
        raise TvfError(f"M (the mass matrix) has shape {mass_shape}: expected ({n},) or ({n}, {n})")
    parts = csr_parts(A, "A")
    values, vectors, residuals = _native.eigsh(parts, mass(M, "M"), k, seed, progress)
    values, vectors = np.asarray(values), np.asarray(vectors)
    if return_residuals:
        return values, vectors, np.asarray(residuals)
    return values, vectors
