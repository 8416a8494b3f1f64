"""Polygon meshes from Python: ``tvf.Mesh`` from a list of polygons, ``polygon-dec`` the
default on them with its stabilisation ``beta``, every function running on them, your own
matrices on a polygon mesh, and the five matrices against an independent implementation
(Adobe Lagrange's ``lagrange.polyddg``)."""

import numpy as np
import pytest
import scipy.sparse as sp

import tvf
from polygon_meshes import cube_sphere, icosphere_dual, jittered, quad_torus

MESHES = {
    "quad-torus": quad_torus(),
    "cube-sphere": cube_sphere(3),
    "icosphere-dual": icosphere_dual(1),
    "jittered-dual": jittered(*icosphere_dual(1)),
}


def test_a_list_of_polygons_makes_a_polygon_mesh_with_polygon_dec_by_default():
    V, faces = MESHES["cube-sphere"]
    mesh = tvf.Mesh(V, faces)
    assert isinstance(mesh.faces, list) and len(mesh.faces) == 54
    assert [list(f) for f in mesh.faces] == faces
    assert mesh.genus == 0 and mesh.is_closed
    complex_ = tvf.Complex(mesh)
    assert complex_.id == "polygon-dec"
    assert complex_.dimensions == (len(V), len(mesh.edges), len(faces))
    # An m x 4 array is the same mesh.
    same = tvf.Mesh(V, np.array(faces))
    assert same.fingerprint == mesh.fingerprint
    with pytest.raises(tvf.TvfError, match="--triangulate"):
        tvf.Complex(mesh, "conforming-barycentric")
    with pytest.raises(tvf.TvfError, match="stabilisation weight of polygon-dec"):
        tvf.Complex(mesh, "conforming-barycentric", beta=0.5)
    with pytest.raises(tvf.TvfError, match="positive"):
        tvf.Complex(mesh, "polygon-dec", beta=-1.0)


def test_beta_changes_only_the_stabilisation_part_of_m1():
    mesh = tvf.Mesh(*MESHES["jittered-dual"])
    one = tvf.operators(mesh)
    half = tvf.operators(mesh, beta=0.5)
    two = tvf.operators(mesh, "polygon-dec", beta=2.0)
    for name in ("d0", "d1", "M0", "M2"):
        assert abs(one[name] - half[name]).max() == 0.0, name
    # M1 = A + beta P: affine in beta, and beta matters on non-planar polygons.
    A = 2 * half["M1"] - one["M1"]
    assert abs(A + 2.0 * (one["M1"] - A) - two["M1"]).max() <= 1e-12 * abs(one["M1"]).max()
    assert abs(one["M1"] - half["M1"]).max() > 1e-6 * abs(one["M1"]).max()
    assert tvf.Complex(mesh, beta=0.5).id.startswith("polygon-dec-beta-")


def test_every_function_runs_on_a_quad_torus():
    mesh = tvf.Mesh(*MESHES["quad-torus"])
    basis = tvf.basis(mesh, 12)
    assert basis.discretization == "polygon-dec"
    # The torus: two harmonic fields, then positive eigenvalues.
    assert np.all(np.abs(basis.eigenvalues[:2]) < 1e-8)
    assert np.all(basis.eigenvalues[2:] > 1e-3)
    assert basis.fields.shape == (len(mesh.faces), 3, 12)
    c = np.array([np.mean(mesh.positions[f], axis=0) for f in mesh.faces])
    field = np.stack([-c[:, 1], c[:, 0], 0.2 * c[:, 2]], axis=1)
    parts = tvf.decompose(mesh, field)
    assert parts["harmonic"].shape == field.shape
    # On coefficients (E edge integrals): the three parts sum to the 1-form and are
    # M1-orthogonal.
    M1 = tvf.operators(mesh)["M1"]
    x = np.random.default_rng(0).normal(size=len(mesh.edges))
    parts = tvf.decompose(mesh, x)
    pieces = [parts[name] for name in ("integrable", "cointegrable", "harmonic")]
    assert np.abs(sum(pieces) - x).max() <= 1e-9 * np.abs(x).max()
    norm = x @ (M1 @ x)
    for i in range(3):
        for j in range(i + 1, 3):
            assert abs(pieces[i] @ (M1 @ pieces[j])) <= 1e-9 * norm, (i, j)
    assert all(pieces[i] @ (M1 @ pieces[i]) > 1e-6 * norm for i in range(3))
    # Coefficients, filters and compression in the basis: a field in the span of the basis
    # comes back whole.
    inside = basis.coefficients @ np.arange(1.0, 13.0)
    c, rest = tvf.coefficients(mesh, inside, basis)
    assert rest <= 1e-9 and np.abs(c - np.arange(1.0, 13.0)).max() <= 1e-9 * 12
    filtered, _ = tvf.filter(mesh, inside, basis)
    assert np.abs(filtered - inside).max() <= 1e-9 * np.abs(inside).max()
    # Compression keeps the harmonic fields and the lowest `pairs` of each family.
    kept = np.zeros(12, dtype=bool)
    for family in set(basis.families):
        where = np.nonzero(basis.families == family)[0]
        kept[where if family == "harmonic" else where[:3]] = True
    compressible = basis.coefficients @ np.where(kept, np.arange(1.0, 13.0), 0.0)
    data = tvf.compress(mesh, [compressible], basis, pairs=3)
    back = tvf.decompress(mesh, data, basis, as_vectors=False)
    assert np.abs(back[0] - compressible).max() <= 1e-9 * np.abs(compressible).max()
    constraints = {"omega": 0.1, "constraints": [{"id": "a", "kind": "vector", "face": 3, "value": [0.0, 0.0, 1.0]}]}
    spline = tvf.spline(mesh, constraints, basis=basis)
    assert spline["field"].shape == (len(mesh.faces), 3)
    design = tvf.design(mesh, constraints)
    assert np.all(np.isfinite(design["field"]))


def test_your_own_matrices_on_a_polygon_mesh_give_polygon_dec_back():
    mesh = tvf.Mesh(*MESHES["cube-sphere"])
    ops = tvf.operators(mesh)
    own = tvf.Complex.from_matrices(mesh, ops["d0"], ops["d1"], ops["M0"], ops["M1"], ops["M2"], sampling="polygon-sharp", id="mine")
    ours = tvf.basis(own, 10).eigenvalues
    built = tvf.basis(mesh, 10).eigenvalues
    assert np.abs(ours - built).max() <= 1e-9 * np.abs(built).max()


def test_your_own_matrices_on_a_quad_torus_need_their_node_kinds():
    # V = F on a quad torus: the sizes cannot tell vertices from faces.
    mesh = tvf.Mesh(*MESHES["quad-torus"])
    assert len(mesh.positions) == len(mesh.faces)
    ops = tvf.operators(mesh)
    parts = (mesh, ops["d0"], ops["d1"], ops["M0"], ops["M1"], ops["M2"])
    with pytest.raises(tvf.TvfError, match="72 nodes, which is ambiguous: the mesh has 72 vertices and 72 faces"):
        tvf.Complex.from_matrices(*parts, sampling="polygon-sharp")
    with pytest.raises(tvf.TvfError, match="'corners' is not a node kind"):
        tvf.Complex.from_matrices(*parts, sampling="polygon-sharp", nodes=("corners", None, None))
    own = tvf.Complex.from_matrices(*parts, sampling="polygon-sharp", id="mine", nodes=("vertices", None, "faces"))
    assert own.node_kinds == ("vertices", "edges", "faces")
    assert own.harmonic_dimension == 2
    ours = tvf.basis(own, 10).eigenvalues
    built = tvf.basis(mesh, 10).eigenvalues
    assert np.abs(ours - built).max() <= 1e-9 * np.abs(built).max()


def _lagrange_operators(V, faces):
    # Installed by scripts/test (pip package adobe-lagrange); missing, the test fails.
    import lagrange
    import lagrange.polyddg as polyddg

    mesh = lagrange.SurfaceMesh()
    mesh.add_vertices(np.ascontiguousarray(V, dtype=np.float64))
    sizes = np.array([len(f) for f in faces], dtype=np.uint32)
    mesh.add_hybrid(sizes, np.concatenate(faces).astype(np.uint32))
    # The operators refer to the mesh without owning it: both are returned, to live as long.
    return mesh, polyddg.DifferentialOperators(mesh)


def _edge_map(lagrange_d0, edges):
    """``S`` (E x E) with ``x_ours = S x_lagrange`` for edge values: Lagrange's edge ``e`` runs
    from the vertex with −1 in its ``d0`` row to the one with +1; ours from the smaller index."""
    number = {(int(a), int(b)): e for e, (a, b) in enumerate(edges)}
    d0 = sp.csr_matrix(lagrange_d0)
    rows, cols, signs = [], [], []
    for e in range(d0.shape[0]):
        start, end = d0.indptr[e], d0.indptr[e + 1]
        entries = dict(zip(d0.indices[start:end], d0.data[start:end]))
        assert sorted(entries.values()) == [-1.0, 1.0], entries
        tail = next(v for v, x in entries.items() if x < 0)
        head = next(v for v, x in entries.items() if x > 0)
        rows.append(number[(min(tail, head), max(tail, head))])
        cols.append(e)
        signs.append(1.0 if tail < head else -1.0)
    n = len(edges)
    assert sorted(rows) == list(range(n))
    return sp.csr_matrix((signs, (rows, cols)), shape=(n, n))


def _relative(a, b):
    a, b = sp.csr_matrix(a), sp.csr_matrix(b)
    return abs(a - b).max() / abs(b).max()


@pytest.mark.parametrize("name", sorted(MESHES))
def test_the_five_matrices_equal_lagranges_polygonal_operators(name):
    """d0, d1, M0 = star0, M1 = star1(beta) for beta in (1, 0.3), M2 = star2 of
    ``lagrange.polyddg.DifferentialOperators`` (de Goes, Butts, Desbrun 2020, Adobe's
    implementation) equal tvf's polygon-dec to 1e-12 relative, once Lagrange's edges are put in
    tvf's order and orientation; faces and vertices are numbered alike."""
    V, faces = MESHES[name]
    mesh = tvf.Mesh(V, faces)
    _lagrange_mesh, reference = _lagrange_operators(V, faces)
    S = _edge_map(reference.d0(), mesh.edges)
    for beta in (1.0, 0.3):
        ours = tvf.operators(mesh, "polygon-dec", beta=beta)
        theirs = {
            "d0": S @ reference.d0(),
            "d1": reference.d1() @ S.T,
            "M0": reference.star0(),
            "M1": S @ reference.star1(beta) @ S.T,
            "M2": reference.star2(),
        }
        for key, matrix in theirs.items():
            assert ours[key].shape == matrix.shape, (key, ours[key].shape, matrix.shape)
            error = _relative(ours[key], matrix)
            assert error <= 1e-12, f"{name}, beta {beta}: {key} differs by {error:.3e} (relative)"
