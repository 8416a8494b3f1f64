"""Every function of the package on the catalog entries with sparse Galerkin masses: the basis
(orthonormal in the sparse M1), decomposition, coefficients, filters, compression, splines,
soft design and the conformance checks; on a closed mesh, and on a mesh with boundary with both
boundary conditions (the masses restricted to the free nodes)."""

import numpy as np
import pytest

import tvf
from reference import icosphere, torus

GALERKIN = ["whitney-galerkin", "conforming-consistent", "nonconforming-consistent"]


@pytest.fixture(scope="module")
def mesh():
    return tvf.Mesh(*torus(n=14, m=8))


@pytest.fixture(scope="module")
def bases(mesh):
    return {entry: tvf.basis(tvf.Complex(mesh, entry), 40, seed=4) for entry in GALERKIN}


def constraints_for(entry):
    """A vector at a face and a divergence where the entry's divergence lives (vertices for P1
    potentials, edges for Crouzeix-Raviart ones)."""
    where = {"edge": 11} if entry.startswith("nonconforming") else {"vertex": 10}
    return {"omega": 0.1, "constraints": [{"id": "v", "kind": "vector", "face": 3, "value": [0.0, 0.0, 1.0]}, {"id": "s", "kind": "divergence", "value": 0.5, **where}]}


@pytest.mark.parametrize("entry", GALERKIN)
def test_basis_is_orthonormal_in_the_sparse_mass(mesh, bases, entry):
    basis = bases[entry]
    ops = tvf.operators(mesh, entry)
    U = basis.coefficients
    assert np.max(np.abs(U.T @ (ops["M1"] @ U) - np.eye(len(basis)))) < 1e-10
    # Eigenfields of L = M1^-1 S: S U = M1 U diag(eigenvalues), S applied as an operator.
    residual = ops["S"] @ U - (ops["M1"] @ U) * basis.eigenvalues
    assert np.max(np.abs(residual)) < 1e-8 * basis.eigenvalues[-1] * np.max(np.abs(ops["M1"] @ U))
    assert list(basis.families[:2]) == ["harmonic", "harmonic"]
    assert basis.fields.shape == (mesh.faces.shape[0], 3, 40)
    if entry == "whitney-galerkin":
        assert tvf.Complex(mesh, entry).masses["M1"]["storage"] == "sparse"


@pytest.mark.parametrize("entry", GALERKIN)
def test_decomposition_coefficients_filter_and_compression(mesh, bases, entry):
    basis = bases[entry]
    complex_ = tvf.Complex(mesh, entry)
    M1 = tvf.operators(complex_)["M1"]
    field = basis.fields[:, :, 9] * 2.0 + basis.fields[:, :, 1]
    c, rest = tvf.coefficients(complex_, field, basis)
    expected = np.zeros(len(basis))
    expected[9], expected[1] = 2.0, 1.0
    assert np.allclose(c, expected, atol=1e-9) and rest < 1e-9

    noisy = np.random.default_rng(2).normal(size=field.shape)
    parts = tvf.decompose(complex_, noisy)
    assert parts["integrable"].shape == noisy.shape and parts["potential"].shape == (complex_.dimensions[0],)
    raw = np.random.default_rng(3).normal(size=complex_.dimensions[1])
    split = tvf.decompose(complex_, raw)
    pieces = [split[name] for name in ("integrable", "cointegrable", "harmonic")]
    assert np.allclose(sum(pieces), raw, atol=1e-9)
    for a in range(3):
        for b in range(a + 1, 3):
            assert abs(pieces[a] @ (M1 @ pieces[b])) < 1e-9 * (raw @ (M1 @ raw))
    # The parts are in their spaces: decomposing one gives it back.
    again = tvf.decompose(complex_, split["cointegrable"])
    assert np.allclose(again["cointegrable"], split["cointegrable"], atol=1e-9)
    assert np.max(np.abs(again["integrable"])) < 1e-9

    filtered, _ = tvf.filter(complex_, field, basis, integrable="cutoff:f=0", cointegrable="cutoff:f=0", harmonic_gain=0.5)
    assert np.allclose(filtered, 0.5 * basis.fields[:, :, 1], atol=1e-9)
    back = tvf.decompress(complex_, tvf.compress(complex_, [noisy, field], basis, pairs=19), basis)
    assert np.allclose(back[1], field, atol=1e-9)


@pytest.mark.parametrize("entry", GALERKIN)
def test_spline_and_design(mesh, bases, entry):
    basis = bases[entry]
    complex_ = tvf.Complex(mesh, entry)
    constraints = constraints_for(entry)
    spline = tvf.spline(complex_, constraints, basis=basis)
    assert spline["field"].shape == (mesh.faces.shape[0], 3)
    # Hard constraints are met (in the basis) to round-off.
    assert all(absolute < 1e-10 for absolute, _ in spline["residuals"].values()), spline["residuals"]
    # Soft design in the basis: the constraints pull, they are not met exactly.
    reduced = tvf.design(complex_, constraints, basis=basis)
    assert set(reduced["residuals"]) == {"v", "s"} and np.all(np.isfinite(reduced["coefficients"]))
    assert np.linalg.norm(reduced["field"]) > 0
    again = tvf.design(complex_, constraints, k=40, seed=4)
    assert np.allclose(again["coefficients"], reduced["coefficients"], atol=1e-12)
    # The full design (auxiliary unknowns for the sparse masses) agrees with the reduced design
    # in the complete basis.
    full = tvf.design(complex_, constraints)
    assert np.all(np.isfinite(full["field"])) and set(full["residuals"]) == {"v", "s"}
    complete = tvf.design(complex_, constraints, k=complex_.dimensions[1], seed=4)
    scale = np.linalg.norm(complete["field"])
    assert np.linalg.norm(full["field"] - complete["field"]) <= 1e-8 * scale


@pytest.mark.parametrize("entry", GALERKIN)
def test_conformance_checks_pass(mesh, entry):
    report = tvf.check(tvf.Complex(mesh, entry))
    assert report.passed, str(report)
    assert not [o for o in report.outcomes if o["status"] == "skipped"], str(report)


@pytest.mark.parametrize("boundary", ["tangential", "normal"])
@pytest.mark.parametrize("entry", GALERKIN)
def test_mesh_with_boundary(entry, boundary):
    V, F = icosphere(2)
    cap = F[V[F].mean(axis=1)[:, 2] > -0.3]  # a sphere with a hole: one boundary loop
    mesh = tvf.Mesh(V, cap)
    assert not mesh.is_closed
    complex_ = tvf.Complex(mesh, entry, boundary)
    ops = tvf.operators(complex_)
    basis = tvf.basis(complex_, 20, seed=1)
    U = basis.coefficients
    assert np.max(np.abs(U.T @ (ops["M1"] @ U) - np.eye(20))) < 1e-10
    assert basis.eigenvalues[0] > 0  # a disk: no harmonic fields
    report = tvf.check(complex_)
    assert report.passed, str(report)
    spline = tvf.spline(complex_, constraints_for(entry), basis=basis)
    assert all(absolute < 1e-10 for absolute, _ in spline["residuals"].values()), spline["residuals"]


def test_the_earlier_key_of_the_cointegrable_part_still_works(mesh):
    V, F = torus(n=14, m=8)
    field = np.random.default_rng(3).standard_normal((len(F), 3))
    split = tvf.decompose(mesh, field)
    assert split["co_integrable"] is split["cointegrable"]
