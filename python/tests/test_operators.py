"""tvf.operators against an independent numpy assembly and against the command line's files
(Matrix Market and npz), on a mesh with unreferenced vertices too."""

import numpy as np
import scipy.io
import scipy.sparse as sp

import tvf
from reference import cotan_matrix, max_difference, p1_cr_complex, torus, write_obj


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
