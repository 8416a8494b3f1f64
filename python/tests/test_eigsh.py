"""tvf.eigsh against scipy.sparse.linalg.eigsh on a generated cotan pencil, and with a sparse
mass (the consistent P1 mass) against scipy.linalg.eigh."""

import numpy as np
import pytest
import scipy.sparse as sp
import scipy.linalg as la
import scipy.sparse.linalg as sla

import tvf
from reference import consistent_p1_mass, cotan_matrix, icosphere, torus


def lumped_mass(V, F):
    p0, p1, p2 = V[F[:, 0]], V[F[:, 1]], V[F[:, 2]]
    area = 0.5 * np.linalg.norm(np.cross(p1 - p0, p2 - p0), axis=1)
    return np.bincount(F.ravel(), weights=np.repeat(area / 3, 3), minlength=len(V))


@pytest.mark.parametrize("mesh", ["torus", "icosphere"])
def test_eigsh_matches_scipy_on_a_cotan_pencil(mesh):
    V, F = torus(n=40, m=20) if mesh == "torus" else icosphere(3)
    A = cotan_matrix(V, F)
    m = lumped_mass(V, F)
    k = 40
    values, vectors, residuals = tvf.eigsh(A, m, k, return_residuals=True)
    reference = sla.eigsh(A.tocsc(), k=k, M=sp.diags(m).tocsc(), sigma=-1e-3, which="LM", tol=1e-14)[0]
    reference = np.sort(reference)
    assert values.shape == (k,) and vectors.shape == (len(V), k)
    assert np.all(np.diff(values) >= 0)
    assert np.max(np.abs(values - reference)) <= 1e-10 * max(1.0, reference[-1]), (values - reference)
    assert abs(values[0]) < 1e-10  # the constants: one component
    gram = vectors.T @ (m[:, None] * vectors)
    assert np.max(np.abs(gram - np.eye(k))) < 1e-10
    residual = A @ vectors - (m[:, None] * vectors) * values
    assert np.max(np.abs(residual)) < 1e-9 * abs(A).max()
    assert np.all(residuals < 1e-10)
    # Eigenvectors agree with SciPy's up to a rotation inside each eigenspace: the spans match.
    _, scipy_vectors = sla.eigsh(A.tocsc(), k=k, M=sp.diags(m).tocsc(), sigma=-1e-3, which="LM", tol=1e-14)
    projection = vectors.T @ (m[:, None] * scipy_vectors[:, : k - 8])
    assert np.allclose(np.linalg.svd(projection, compute_uv=False), 1.0, atol=1e-8)


def test_eigsh_refuses_bad_pencils():
    A = cotan_matrix(*icosphere(1))
    n = A.shape[0]
    with pytest.raises(tvf.TvfError, match="mass"):
        tvf.eigsh(A, -np.ones(n), 3)
    with pytest.raises(tvf.TvfError, match="square"):
        tvf.eigsh(sp.random(4, 5, density=0.5, format="csr"), np.ones(4), 2)
    with pytest.raises(tvf.TvfError):
        tvf.eigsh(A, np.ones(n), n + 1)
    bad = A.copy()
    bad.data[0] = np.nan
    with pytest.raises(tvf.TvfError, match="non-finite"):
        tvf.eigsh(bad, np.ones(n), 3)


@pytest.mark.parametrize("k", [12, 60, 162])
def test_eigsh_with_a_sparse_mass_matches_dense_eigh(k):
    V, F = icosphere(2)  # 162 vertices: k = 162 is the whole spectrum
    A = cotan_matrix(V, F)
    M = consistent_p1_mass(V, F)
    values, vectors, residuals = tvf.eigsh(A, M.tocsc(), k, return_residuals=True)
    reference = la.eigh(A.toarray(), M.toarray(), eigvals_only=True)[:k]
    assert values.shape == (k,) and vectors.shape == (len(V), k)
    assert np.max(np.abs(values - reference)) <= 1e-10 * reference[-1], values - reference
    assert np.max(np.abs(vectors.T @ (M @ vectors) - np.eye(k))) < 1e-10
    assert np.max(np.abs(A @ vectors - (M @ vectors) * values)) < 1e-9 * abs(A).max()
    assert np.all(residuals < 1e-10)
    # The consistent mass is not the lumped one: the spectra differ.
    lumped = tvf.eigsh(A, lumped_mass(V, F), k)[0]
    assert np.max(np.abs(lumped - values)) > 1e-3 * values[-1]


def test_eigsh_refuses_broken_sparse_masses():
    V, F = icosphere(1)
    A = cotan_matrix(V, F)
    M = consistent_p1_mass(V, F)
    asymmetric = M.tolil()
    asymmetric[0, 1] += 1e-3 * abs(M).max()
    with pytest.raises(tvf.TvfError, match=r"M \(the mass matrix\) is not symmetric"):
        tvf.eigsh(A, asymmetric, 3)
    with pytest.raises(tvf.TvfError, match="mass matrix is not positive definite"):
        tvf.eigsh(A, M - 0.6 * sp.diags(M.diagonal()), 3)
    with pytest.raises(tvf.TvfError, match=r"M \(the mass matrix\) has 41 rows, A has 42"):
        tvf.eigsh(A, M[1:, 1:], 3)


def test_k_must_be_an_integer():
    """eigsh(k=3.5) once returned 3 eigenpairs."""
    A = cotan_matrix(*icosphere(1))
    n = A.shape[0]
    for bad in (3.5, 3.0, "3"):
        with pytest.raises(TypeError, match="k must be an integer"):
            tvf.eigsh(A, np.ones(n), bad)
    assert len(tvf.eigsh(A, np.ones(n), np.int64(3))[0]) == 3
