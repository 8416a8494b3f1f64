"""tvf.eigsh against scipy.sparse.linalg.eigsh on a generated cotan pencil."""

import numpy as np
import pytest
import scipy.sparse as sp
import scipy.sparse.linalg as sla

import tvf
from reference import cotan_matrix, icosphere, torus


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
