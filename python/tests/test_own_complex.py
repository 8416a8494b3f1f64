"""Bring your own discretization: the P1 / Crouzeix-Raviart complex assembled in numpy runs
through tvf's code, passes the conformance checks and has the built-in spectrum; so do complexes
with sparse Galerkin masses (the consistent P1 mass, the Whitney mass assembled in numpy, each
Galerkin catalog entry rebuilt from its own matrices); a broken entry is named by the report, a
broken mass by the error."""

import numpy as np
import pytest
import scipy.sparse as sp

import tvf
from reference import consistent_p1_mass, icosphere, max_difference, p1_cr_complex, torus, whitney_complex


def own_complex(mesh, V, F, **changes):
    ref = p1_cr_complex(V, F)
    ref.update(changes)
    return tvf.Complex.from_matrices(mesh, ref["d0"], ref["d1"], ref["M0"], ref["M1"], sp.diags(ref["M2"]), sampling="face-frames", id="numpy-p1-cr")


@pytest.fixture(scope="module")
def torus_mesh():
    V, F = torus(n=12, m=6)
    return V, F, tvf.Mesh(V, F)


def test_numpy_complex_passes_the_conformance_checks(torus_mesh):
    V, F, mesh = torus_mesh
    complex_ = own_complex(mesh, V, F)
    assert complex_.node_kinds == ("vertices", "face-frames", "edges")
    assert complex_.harmonic_dimension == 2
    report = tvf.check(complex_)
    assert report.passed, str(report)
    names = {o["name"] for o in report.outcomes}
    assert {"d1_d0_zero", "spectrum union", "kernel dimension", "potential_masses_sum_to_area"} <= names
    assert all(o["status"] == "passed" for o in report.outcomes), str(report)


def test_numpy_complex_has_the_built_in_spectrum_and_results(torus_mesh):
    V, F, mesh = torus_mesh
    complex_ = own_complex(mesh, V, F)
    built_in = tvf.Complex(mesh, "conforming-barycentric")
    ours = tvf.basis(complex_, 40, seed=3)
    theirs = tvf.basis(built_in, 40, seed=3)
    assert np.max(np.abs(ours.eigenvalues - theirs.eigenvalues)) <= 1e-10 * theirs.eigenvalues[-1]
    assert list(ours.families) == list(theirs.families)
    field = np.random.default_rng(1).normal(size=(len(F), 3))
    a = tvf.decompose(complex_, field)
    b = tvf.decompose(built_in, field)
    for part in ("integrable", "cointegrable", "harmonic"):
        assert np.allclose(a[part], b[part], atol=1e-10)
    constraints = {"constraints": [{"id": "v", "kind": "vector", "face": 3, "value": [0.0, 0.0, 1.0]}, {"id": "s", "kind": "divergence", "vertex": 10, "value": 1.0}]}
    ours_spline = tvf.spline(complex_, constraints, basis=ours)
    theirs_spline = tvf.spline(built_in, constraints, basis=theirs)
    assert np.allclose(ours_spline["field"], theirs_spline["field"], atol=1e-8)
    filtered, _ = tvf.filter(complex_, field, ours, integrable="lowpass:t=0.01")
    assert filtered.shape == field.shape


def test_a_broken_entry_is_named(torus_mesh):
    V, F, mesh = torus_mesh
    ref = p1_cr_complex(V, F)
    M0 = ref["M0"].copy()
    M0[7] *= 3.0  # the potential masses no longer partition the area
    report = tvf.check(own_complex(mesh, V, F, M0=M0))
    assert not report.passed
    failed = [o["name"] for o in report.failures]
    assert "potential_masses_sum_to_area" in failed, str(report)
    assert "d1_d0_zero" not in failed

    d1 = ref["d1"].tolil()
    d1[4, 9] += 1e-3 * abs(ref["d1"]).max()  # d1 d0 = 0 broken: refused at construction
    with pytest.raises(tvf.TvfError, match=r"d1 · d0 is not zero"):
        own_complex(mesh, V, F, d1=d1.tocsr())

    # The gradient of one vertex dropped (its column of d0 zeroed): still d1 d0 = 0, but the
    # constants leave the kernel of d0, so the harmonic dimension the matrices give no longer
    # matches the torus's 2: refused at construction, naming both counts.
    d0 = ref["d0"].tolil()
    d0[:, 17] = 0.0
    with pytest.raises(tvf.TvfError, match=r"harmonic fields .* topology has 2"):
        own_complex(mesh, V, F, d0=d0.tocsr())


def test_from_matrices_validates_its_input(torus_mesh):
    V, F, mesh = torus_mesh
    ref = p1_cr_complex(V, F)
    with pytest.raises(tvf.TvfError, match="M1 must be positive"):
        own_complex(mesh, V, F, M1=-ref["M1"])
    with pytest.raises(tvf.TvfError, match=r"M0 \(one entry per column of d0\): expected %d entries, found %d" % (len(V), len(V) - 1)):
        own_complex(mesh, V, F, M0=ref["M0"][1:])
    nan = ref["d0"].copy()
    nan.data[3] = np.nan
    with pytest.raises(tvf.TvfError, match="d0 contains a non-finite value"):
        own_complex(mesh, V, F, d0=nan)
    with pytest.raises(tvf.TvfError, match="has 7 nodes"):
        tvf.Complex.from_matrices(mesh, sp.csr_matrix((2 * len(F), 7)), sp.csr_matrix((3, 2 * len(F))), np.ones(7), ref["M1"], np.ones(3))
    with pytest.raises(tvf.TvfError, match="not a sampling"):
        tvf.Complex.from_matrices(mesh, ref["d0"], ref["d1"], ref["M0"], ref["M1"], ref["M2"], sampling="nearest")
    # A matrix with off-diagonal entries is a sparse mass: this one has rank one.
    with pytest.raises(tvf.TvfError, match="M0 is not positive definite"):
        own_complex(mesh, V, F, M0=sp.csr_matrix(np.ones((len(V), len(V)))))


def test_dec_from_matrices_with_whitney_sampling():
    V, F = icosphere(2)
    mesh = tvf.Mesh(V, F)
    ops = tvf.operators(mesh, "dec-circumcentric")
    complex_ = tvf.Complex.from_matrices(mesh, ops["d0"], ops["d1"], ops["M0"], ops["M1"], ops["M2"], sampling="whitney", id="my-dec")
    assert complex_.node_kinds == ("vertices", "edges", "faces")
    assert tvf.check(complex_).passed
    ours = tvf.basis(complex_, 20)
    theirs = tvf.basis(mesh, 20, discretization="dec-circumcentric")
    assert np.allclose(ours.eigenvalues, theirs.eigenvalues, rtol=0, atol=1e-10 * theirs.eigenvalues[-1])
    assert ours.fields.shape == (len(F), 3, 20)


def same_spectrum(a, b, k=40):
    ours = tvf.basis(a, k, seed=3).eigenvalues
    theirs = tvf.basis(b, k, seed=3).eigenvalues
    assert np.max(np.abs(ours - theirs)) <= 1e-10 * theirs[-1], ours - theirs


@pytest.mark.parametrize("entry, sampling", [("whitney-galerkin", "whitney"), ("conforming-consistent", "face-frames"), ("nonconforming-consistent", "face-frames")])
def test_galerkin_entry_rebuilt_from_its_own_matrices(torus_mesh, entry, sampling):
    _, _, mesh = torus_mesh
    built_in = tvf.Complex(mesh, entry)
    ops = tvf.operators(built_in)
    # M2 is given by its sparse inverse where that is what the entry stores.
    m2 = {"M2_inverse": ops["M2_inverse"]} if built_in.masses["M2"]["form"] == "inverse" else {"M2": ops["M2"]}
    assert ("M2_inverse" in m2) == (entry == "nonconforming-consistent")
    # Any scipy.sparse format.
    ours = tvf.Complex.from_matrices(mesh, ops["d0"], ops["d1"], ops["M0"].tocoo(), ops["M1"].tocsc(), sampling=sampling, id="rebuilt", **m2)
    assert ours.masses == built_in.masses
    same_spectrum(ours, built_in)
    report = tvf.check(ours)
    assert report.passed, str(report)


def test_consistent_p1_mass_from_numpy(torus_mesh):
    V, F, mesh = torus_mesh
    M0 = consistent_p1_mass(V, F)
    assert M0.nnz > len(V)
    complex_ = own_complex(mesh, V, F, M0=M0)
    assert complex_.masses["M0"] == {"storage": "sparse", "form": "direct", "key": "M0"}
    # The numpy assembly is tvf's conforming-consistent entry.
    same_spectrum(complex_, tvf.Complex(mesh, "conforming-consistent"))
    assert tvf.check(complex_).passed


def test_whitney_complex_assembled_in_numpy(torus_mesh):
    V, F, mesh = torus_mesh
    ref = whitney_complex(V, F)
    built_in = tvf.Complex(mesh, "whitney-galerkin")
    ops = tvf.operators(built_in)
    for name in ("d0", "d1", "M0", "M1"):
        difference, scale = max_difference(ops[name], ref[name])
        assert difference <= 1e-14 * scale, name
    ours = tvf.Complex.from_matrices(mesh, ref["d0"], ref["d1"], ref["M0"], ref["M1"], ref["M2"], sampling="whitney", id="numpy-whitney")
    assert ours.node_kinds == ("vertices", "edges", "faces")
    assert ours.masses["M1"]["storage"] == "sparse" and ours.masses["M2"]["storage"] == "diagonal"
    same_spectrum(ours, built_in)
    report = tvf.check(ours)
    assert report.passed, str(report)


def test_broken_masses_are_refused_naming_the_matrix(torus_mesh):
    V, F, mesh = torus_mesh
    ref = whitney_complex(V, F)

    def build(**changes):
        parts = {"d0": ref["d0"], "d1": ref["d1"], "M0": ref["M0"], "M1": ref["M1"], "M2": ref["M2"]}
        parts.update(changes)
        return tvf.Complex.from_matrices(mesh, sampling="whitney", **parts)

    asymmetric = ref["M1"].tolil()
    asymmetric[3, 5] += 1e-3 * abs(ref["M1"]).max()
    with pytest.raises(tvf.TvfError, match=r"M1 is not symmetric: the largest \|M − Mᵀ\| entry is"):
        build(M1=asymmetric.tocsr())
    # Symmetric to round-off is fine (the mass is used as (M + M^T)/2).
    rounded = ref["M1"].tolil()
    rounded[3, 5] *= 1 + 1e-15
    build(M1=rounded.tocsr())
    # Indefinite: the Cholesky factorization of the seam names the matrix and the pivot.
    indefinite = ref["M0"] - 0.5 * sp.diags(ref["M0"].diagonal())
    with pytest.raises(tvf.TvfError, match=r"M0 is not positive definite on its free nodes: .*Cholesky.* pivot"):
        build(M0=indefinite)
    with pytest.raises(tvf.TvfError, match=r"M1 is not positive definite"):
        build(M1=-ref["M1"])
    ne = len(ref["edges"])
    with pytest.raises(tvf.TvfError, match=f"M1 is {ne} × {ne - 1}, not square"):
        build(M1=ref["M1"][:, :-1])
    nan = ref["M1"].copy()
    nan.data[2] = np.inf
    with pytest.raises(tvf.TvfError, match="M1 contains a non-finite value"):
        build(M1=nan)
    with pytest.raises(TypeError, match="M1: expected a real sparse matrix"):
        build(M1=ref["M1"].astype(complex))

    # M2 given by its inverse: refused by its own name.
    area = 1.0 / ref["M2"]
    inverse = sp.diags(area) + 0.01 * sp.random(len(F), len(F), density=0.02, random_state=0)
    with pytest.raises(tvf.TvfError, match=r"M2_inverse \(M2⁻¹\) is not symmetric"):
        build(M2=None, M2_inverse=inverse)
    with pytest.raises(tvf.TvfError, match=r"M2_inverse \(M2⁻¹\) is not positive definite"):
        build(M2=None, M2_inverse=sp.diags(area) - 3 * sp.eye(len(F)) + sp.eye(len(F), k=1) + sp.eye(len(F), k=-1))
    zero = area.copy()
    zero[4] = 0.0
    with pytest.raises(tvf.TvfError, match=r"M2_inverse \(M2⁻¹\) must be positive: 1 entries are not \(the first, entry 4"):
        build(M2=None, M2_inverse=zero)
    # A diagonal inverse is the diagonal of reciprocals: every operator stays sparse.
    diagonal = build(M2=None, M2_inverse=area)
    assert diagonal.masses["M2"] == {"storage": "diagonal", "form": "direct", "key": "M2"}
    with pytest.raises(tvf.TvfError, match="not both"):
        build(M2_inverse=area)
    with pytest.raises(tvf.TvfError, match="give the co-potential mass as M2 or as its inverse M2_inverse"):
        build(M2=None)
    # M2 with off-diagonal entries has a dense inverse: the co-potential mass must be sparse.
    coupled = sp.diags(ref["M2"]) + 0.01 * sp.diags(np.sqrt(ref["M2"][1:] * ref["M2"][:-1]), 1, shape=(len(F), len(F)))
    with pytest.raises(tvf.TvfError, match="M2 has off-diagonal entries, so its inverse, the co-potential mass, is dense"):
        build(M2=coupled + coupled.T - sp.diags(ref["M2"]))
    # Given as M2_inverse the same matrix is a sparse co-potential mass: with the sparse
    # Whitney M1 the co-exact problem is a mixed pencil with a sparse mass.
    mixed = build(M2=None, M2_inverse=coupled + coupled.T - sp.diags(ref["M2"]))
    assert mixed.masses["M2"] == {"storage": "sparse", "form": "inverse", "key": "M2_inverse"}
    basis = tvf.basis(mixed, 30, seed=1)
    U = basis.coefficients
    assert np.max(np.abs(U.T @ (ref["M1"] @ U) - np.eye(30))) < 1e-10
    assert tvf.check(mixed).passed
    dense_m2 = tvf.operators(mesh, "nonconforming-consistent")["M2"]
    with pytest.raises(TypeError, match="got a LinearOperator .* as M2_inverse"):
        build(M2=dense_m2)
