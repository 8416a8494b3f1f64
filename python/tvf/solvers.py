"""tvf's generalized eigensolver on your own matrices: :func:`eigsh`."""

import numpy as np

from . import _native
from ._arrays import csr_parts, diagonal
from ._native import TvfError


def eigsh(A, M_diag, k, seed=None, progress=None, return_residuals=False):
    """The lowest ``k`` eigenpairs of ``A x = l M x``, ``M = diag(M_diag)``: a drop-in for
    ``scipy.sparse.linalg.eigsh(A, k, M=diags(M_diag), sigma=-eps, which="LM")`` on
    Laplacian-like pencils.

    - ``A``: ``n x n`` symmetric positive semi-definite ``scipy.sparse`` matrix (or dense),
      e.g. a stiffness (cotan) matrix; zero eigenvalues (one per connected component) are fine,
      mildly negative ones are found too. Only the upper triangle is read.
    - ``M_diag``: the ``n`` positive masses (a vector or a diagonal matrix).
    - ``k``: number of eigenpairs, ``k <= n``.

    Returns ``(eigenvalues, eigenvectors)`` as SciPy does: ``(k,)`` ascending and ``(n, k)``,
    ``M``-orthonormal columns (``X.T @ (M_diag[:, None] * X) = I``); with
    ``return_residuals=True`` also the relative residuals ``|A x - l M x| / (|A|_1 |x|)``.

    How it differs from SciPy's shift-invert ``eigsh``: it returns *the lowest* ``k``
    eigenvalues with completeness verified by Sylvester's law of inertia (``LDL^T`` of
    ``A - s M`` counts the eigenvalues below ``s``), so no eigenvalue of a multiple cluster is
    skipped and zero eigenvalues need no shift; it handles large ``k`` (hundreds to thousands)
    by spectrum slicing (several shifts, one sparse factorization each) instead of one Krylov
    space; ``M`` must be diagonal; eigenvector signs (and the basis inside a multiple
    eigenvalue's eigenspace) are arbitrary, as in SciPy. ``seed`` fixes the random start
    vectors. ``progress(stage, confirmed, wanted)`` is called as eigenpairs are confirmed. The
    GIL is released while it runs."""
    parts = csr_parts(A, "A")
    if parts[3][0] != parts[3][1]:
        raise TvfError(f"A: expected a square matrix, got shape {parts[3]}")
    mass = diagonal(M_diag, "M_diag")
    k = int(k)
    if k < 0:
        raise TvfError(f"k = {k}: ask for at least one eigenpair")
    values, vectors, residuals = _native.eigsh(parts, mass, k, None if seed is None else int(seed), progress)
    values, vectors = np.asarray(values), np.asarray(vectors)
    if return_residuals:
        return values, vectors, np.asarray(residuals)
    return values, vectors
