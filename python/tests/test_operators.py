"""tvf.operators against an independent numpy assembly and against the command line's files
(Matrix Market and npz), on a mesh with unreferenced vertices too; on complexes with sparse
masses, the dense derived operators as LinearOperators against dense numpy algebra."""

import json

import numpy as np
import pytest
import scipy.io
import scipy.sparse as sp
import scipy.sparse.linalg as sla

import tvf
from reference import cotan_matrix, icosphere, max_difference, p1_cr_complex, torus, write_obj


def assert_entrywise(name, got, expected, relative=1e-12):
    difference, scale = max_difference(got, expected)
    assert difference <= relative * scale, f"{name}: max |difference| {difference:e} vs max entry {scale:e}"


def test_operators_equal_the_numpy_assembly():
    V, F = torus(n=14, m=8)
    ops = tvf.operators(tvf.Mesh(V, F), "conforming-barycentric")
    ref = p1_cr_complex(V, F)
    assert ops["d0"].shape == (2 * len(F), len(V))
    assert ops["d1"].shape == (len(ref["edges"]), 2 * len(F))
    for name in ("d0", "d1", "J"):
        assert_entrywise(name, ops[name], ref[name])
    for name in ("M0", "M1", "M2"):
        assert_entrywise(name, ops[name].diagonal(), ref[name])
    assert_entrywise("S0 (cotan)", ops["S0"], cotan_matrix(V, F))
    assert_entrywise("S2 (CR stiffness)", ops["S2"], (ref["Gs"].T @ sp.diags(ref["M1"]) @ ref["Gs"]).tocsr())
    # S = M_X (G M^-1 G^T - J G* M*^-1 G*^T J) M_X
    MX = sp.diags(ref["M1"])
    S = MX @ (ref["G"] @ sp.diags(1 / ref["M0"]) @ ref["G"].T - ref["J"] @ ref["Gs"] @ sp.diags(1 / ref["Ms"]) @ ref["Gs"].T @ ref["J"]) @ MX
    assert_entrywise("S", ops["S"], S.tocsr(), 1e-11)
    assert_entrywise("L", ops["L"], (sp.diags(1 / ref["M1"]) @ S).tocsr(), 1e-11)
    assert_entrywise("div", ops["div"], (-sp.diags(1 / ref["M0"]) @ ref["G"].T @ MX).tocsr())
    assert np.allclose(ops["frames"], ref["frames"], rtol=0, atol=1e-14)
    assert abs(ops["d1"] @ ops["d0"]).max() < 1e-12 * abs(ops["d1"]).max() * abs(ops["d0"]).max()


def test_operators_match_the_command_line_with_unreferenced_vertices(tmp_path, run_tvf):
    V, F = torus(n=12, m=6)
    # The user's V: three stray vertices the faces do not use, at the start, middle and end.
    stray = np.array([[9.0, 9.0, 9.0], [8.0, 8.0, 8.0], [7.0, 7.0, 7.0]])
    at = [0, 40, len(V) + 2]
    V_user = V.copy()
    for position, p in zip(at, stray):
        V_user = np.insert(V_user, position, p, axis=0)
    keep = np.ones(len(V_user), bool)
    keep[at] = False
    old_to_user = np.flatnonzero(keep)  # user index of each original vertex
    F_user = old_to_user[F]
    path = tmp_path / "stray.obj"
    write_obj(path, V_user, F_user)

    mesh = tvf.Mesh(V_user, F_user)
    assert mesh.input_vertex_count == len(V_user)
    assert np.array_equal(mesh.vertex_map, old_to_user)
    ops = tvf.operators(mesh, "nonconforming-voronoi")

    out = tmp_path / "mtx"
    run_tvf("operators", path, "--discretization", "nonconforming-voronoi", "-o", out)
    npz = tmp_path / "npz"
    run_tvf("operators", path, "--discretization", "nonconforming-voronoi", "--format", "npz", "-o", npz)
    vertex_map = np.load(out / "vertex_map.npy")
    assert vertex_map.dtype == np.int64
    assert np.array_equal(vertex_map, mesh.vertex_map)
    assert np.array_equal(np.load(npz / "vertex_map.npy"), vertex_map)
    info = (out / "info.json").read_text()
    assert "3 unreferenced" in info and "vertex_map.npy[v] is the input index" in info
    for name in ("d0", "d1", "M0", "M1", "M2", "S0", "S2", "S", "B", "J"):
        from_mtx = sp.csr_matrix(scipy.io.mmread(out / f"{name}.mtx"))
        from_npz = sp.load_npz(npz / f"{name}.npz")
        assert from_npz.format == "csr"
        assert_entrywise(f"{name} (npz vs mtx)", from_npz, from_mtx, 0.0)
        assert_entrywise(f"{name} (python vs mtx)", ops[name], from_mtx, 1e-15)

    # With the vertex map, vertex-indexed matrices line up with the user's V: the P1 space is
    # the co-potential space of the nonconforming complex, S2 its stiffness (cotan matrix).
    S_user = sp.lil_matrix((len(V_user), len(V_user)))
    S_cli = sp.csr_matrix(scipy.io.mmread(out / "S2.mtx"))
    S_user[np.ix_(vertex_map, vertex_map)] = S_cli.toarray()
    assert_entrywise("cotan on the user's V", S_user.tocsr(), cotan_matrix(V_user, F_user))


def test_vertex_map_is_the_identity_without_stray_vertices(tmp_path, run_tvf):
    V, F = torus(n=8, m=6)
    path = tmp_path / "t.obj"
    write_obj(path, V, F)
    run_tvf("operators", path, "-o", tmp_path / "out")
    assert np.array_equal(np.load(tmp_path / "out" / "vertex_map.npy"), np.arange(len(V)))
    assert np.array_equal(tvf.Mesh(V, F).vertex_map, np.arange(len(V)))


# Which operators contain the inverse of a sparse mass (or M2 stored as its inverse) and are
# therefore dense: LinearOperators. Every other key is a csr_matrix.
COMPOSED = {
    "whitney-galerkin": {"S2", "S", "L", "B", "div"},
    "conforming-consistent": {"S", "L", "B", "div", "curl_other"},
    "nonconforming-consistent": {"M2", "S", "L", "B", "curl", "div_other"},
}


def dense_operators(ops):
    """Every derived operator from the five matrices by dense numpy algebra (small meshes)."""
    d0, d1, M0, M1 = (ops[name].toarray() for name in ("d0", "d1", "M0", "M1"))
    M2 = np.linalg.inv(ops["M2_inverse"].toarray()) if "M2_inverse" in ops else ops["M2"].toarray()
    iM0, iM1 = np.linalg.inv(M0), np.linalg.inv(M1)
    S = M1 @ d0 @ iM0 @ d0.T @ M1 + d1.T @ M2 @ d1
    out = {"M2": M2, "S0": d0.T @ M1 @ d0, "S2": d1 @ iM1 @ d1.T, "S": S, "L": iM1 @ S, "B": S @ iM1 @ S, "div": -iM0 @ d0.T @ M1, "curl": M2 @ d1}
    if "J" in ops:
        J = ops["J"].toarray()
        out["div_other"] = -M2 @ d1 @ iM1 @ J.T @ M1
        out["curl_other"] = iM0 @ d0.T @ J @ M1
    return out


@pytest.mark.parametrize("entry", sorted(COMPOSED))
def test_operators_of_galerkin_complexes(entry):
    V, F = icosphere(1)
    complex_ = tvf.Complex(tvf.Mesh(V, F), entry)
    ops = tvf.operators(complex_)
    composed = {name for name, value in ops.items() if isinstance(value, tvf.ComposedOperator)}
    assert composed == COMPOSED[entry]
    for name, value in ops.items():
        if name != "frames" and name not in composed:
            assert sp.isspmatrix_csr(value), name
    # The stored form of each mass, and M2_inverse exactly where M2 is dense.
    assert ("M2_inverse" in ops) == (complex_.masses["M2"]["form"] == "inverse")
    for name, mass in complex_.masses.items():
        assert sp.isspmatrix_csr(ops[mass["key"]])
        assert (ops[mass["key"]].nnz > ops[mass["key"]].shape[0]) == (mass["storage"] == "sparse")
    rng = np.random.default_rng(1)
    for name, dense in dense_operators(ops).items():
        operator = ops[name]
        assert operator.shape == dense.shape, name
        scale = np.max(np.abs(dense))
        x = rng.normal(size=dense.shape[1])
        y = rng.normal(size=dense.shape[0])
        X = rng.normal(size=(dense.shape[1], 3))
        assert np.max(np.abs(operator @ x - dense @ x)) <= 1e-12 * scale * np.max(np.abs(x)) * dense.shape[1], name
        assert np.max(np.abs(operator.T @ y - dense.T @ y)) <= 1e-12 * scale * np.max(np.abs(y)) * dense.shape[0], name
        assert np.max(np.abs(operator @ X - dense @ X)) <= 1e-12 * scale * np.max(np.abs(X)) * dense.shape[1], name
        if isinstance(operator, tvf.ComposedOperator):
            assert operator.name == name and operator.dtype == np.float64
            assert np.max(np.abs(operator.rmatvec(y) - dense.T @ y)) <= 1e-12 * scale * np.max(np.abs(y)) * dense.shape[0], name
            assert np.max(np.abs(operator @ np.eye(dense.shape[1]) - dense)) <= 1e-13 * scale, name
    # A LinearOperator works with SciPy's solvers: (S + M1) x = b by conjugate gradients.
    system = sla.aslinearoperator(ops["S"]) + sla.aslinearoperator(ops["M1"])
    b = rng.normal(size=system.shape[0])
    x, info = sla.cg(system, b, rtol=1e-12, maxiter=2000)
    expected = np.linalg.solve(dense_operators(ops)["S"] + ops["M1"].toarray(), b)
    assert info == 0 and np.max(np.abs(x - expected)) <= 1e-8 * np.max(np.abs(expected))


def test_composed_operators_check_their_input():
    ops = tvf.operators(tvf.Mesh(*icosphere(1)), "whitney-galerkin")
    S = ops["S"]
    with pytest.raises(tvf.TvfError, match="S: matvec: the vector has a non-finite value at entry 0"):
        S @ np.full(S.shape[1], np.nan)
    with pytest.raises(ValueError):
        S @ np.ones(3)
    z = S @ np.full(S.shape[1], 1 + 2j)
    assert np.allclose(z, (1 + 2j) * (S @ np.ones(S.shape[1])))


def test_galerkin_operators_match_the_command_line(tmp_path, run_tvf):
    V, F = torus(n=10, m=6)
    path = tmp_path / "t.obj"
    write_obj(path, V, F)
    ops = tvf.operators(tvf.Mesh(V, F), "nonconforming-consistent")
    out = tmp_path / "npz"
    run_tvf("operators", path, "--discretization", "nonconforming-consistent", "--format", "npz", "-o", out)
    info = json.loads((out / "info.json").read_text())
    assert info["masses"]["M2"] == {"file": "M2_inverse", "form": "inverse", "storage": "sparse"}
    assert set(info["not_written"]) == {"S", "B"}
    written = {p.stem for p in out.glob("*.npz")}
    assert written == {"d0", "d1", "M0", "M1", "M2_inverse", "S0", "S2", "J"}
    for name in written:
        assert_entrywise(f"{name} (python vs npz)", ops[name], sp.load_npz(out / f"{name}.npz"), 1e-15)
