"""Catalog entries on the intrinsic Delaunay triangulation from Python (``intrinsic_delaunay=``):
ids, the intrinsic connectivity and lengths from ``tvf.operators``, DEC on a non-Delaunay torus
with its two harmonic fields, fields over the input faces, and the cotan matrix and masses
against libigl's flip-only intrinsic Delaunay triangulation (``igl.intrinsic_delaunay_cotmatrix``,
an independent implementation), for DEC and for the finite element and Whitney entries built from
the intrinsic lengths."""

import igl
import numpy as np
import pytest
import scipy.sparse as sp

import tvf
from reference import torus


def jittered_torus(seed=3, amplitude=0.25):
    """The staggered torus of the reference module with its vertices moved at random by up to
    ``amplitude`` of the mean edge length: not Delaunay (checked below)."""
    V, F = torus(n=18, m=9)
    rng = np.random.default_rng(seed)
    edge = np.linalg.norm(V[F[:, 1]] - V[F[:, 0]], axis=1).mean()
    return V + amplitude * edge * rng.uniform(-1, 1, V.shape), F


def test_the_flag_gives_the_id_and_dec_builds_on_a_non_delaunay_torus():
    mesh = tvf.Mesh(*jittered_torus())
    with pytest.raises(tvf.TvfError, match="intrinsic_delaunay=True"):
        tvf.Complex(mesh, "dec-circumcentric")
    flipped = tvf.Complex(mesh, "dec-circumcentric", intrinsic_delaunay=True)
    assert flipped.id == "dec-circumcentric+intrinsic-delaunay"
    assert tvf.Complex(mesh, "dec-circumcentric+intrinsic-delaunay").id == flipped.id
    assert tvf.Complex(mesh, "dec-barycentric", intrinsic_delaunay="refine").id == "dec-barycentric+intrinsic-delaunay-refine"
    with pytest.raises(tvf.TvfError, match="flip' or 'refine"):
        tvf.Complex(mesh, "dec-circumcentric", intrinsic_delaunay="yes")
    listed = {d["id"]: d["builds_on_intrinsic"] for d in tvf.discretizations()}
    # Every triangle entry has a constructor from edge lengths; polygonal DEC has none.
    assert all(built for id, built in listed.items() if id != "polygon-dec")
    assert not listed["polygon-dec"]
    with pytest.raises(tvf.TvfError, match="vector areas"):
        tvf.Complex(mesh, "polygon-dec", intrinsic_delaunay=True)
    # Genus 1: two harmonic fields; fields are per input face.
    basis = tvf.basis(mesh, 8, "dec-circumcentric", intrinsic_delaunay=True)
    assert basis.discretization == flipped.id
    assert np.all(np.abs(basis.eigenvalues[:2]) < 1e-8) and basis.eigenvalues[2] > 1e-3
    assert basis.fields.shape == (len(mesh.faces), 3, 8)
    parts = tvf.decompose(mesh, np.tile([1.0, 0.5, 0.0], (len(mesh.faces), 1)), "dec-circumcentric", intrinsic_delaunay=True)
    assert parts["integrable"].shape == (len(mesh.faces), 3)


def test_operators_return_the_intrinsic_connectivity_and_lengths():
    V, F = jittered_torus()
    mesh = tvf.Mesh(V, F)
    ops = tvf.operators(mesh, "dec-circumcentric", intrinsic_delaunay=True)
    faces, edges, lengths = ops["intrinsic_faces"], ops["intrinsic_edges"], ops["intrinsic_edge_lengths"]
    positions = ops["intrinsic_vertex_positions"]
    assert faces.shape == (len(F), 3) and edges.shape == (len(lengths), 2)
    assert positions.shape == (len(V), 3) and np.array_equal(positions, mesh.positions)
    assert ops["d0"].shape == (len(edges), len(V)) and ops["d1"].shape == (len(faces), len(edges))
    assert ops["frames"].shape == (len(F), 2, 3)
    # d0 is the incidence of the edges as returned.
    d0 = ops["d0"].toarray()
    for e, (a, b) in enumerate(edges):
        if a != b:
            assert d0[e, a] == -1.0 and d0[e, b] == 1.0
    # Flips keep the total area: sum of 1 / M2.
    area = 1.0 / ops["M2"].diagonal()
    input_area = 0.5 * np.linalg.norm(np.cross(V[F[:, 1]] - V[F[:, 0]], V[F[:, 2]] - V[F[:, 0]]), axis=1).sum()
    assert abs(area.sum() - input_area) <= 1e-12 * input_area
    # Every star1 positive: every intrinsic edge is Delaunay, and some input edge was not.
    assert ops["M1"].diagonal().min() > 0
    input_cotan = sp.csr_matrix(igl.cotmatrix(V, F))
    input_cotan.setdiag(0)
    assert (input_cotan.data < -1e-12).any()


def test_the_cotan_matrix_and_masses_agree_with_libigl():
    V, F = jittered_torus()
    mesh = tvf.Mesh(V, F)
    ops = tvf.operators(mesh, "dec-circumcentric", intrinsic_delaunay=True)
    L, l_igl, F_igl = igl.intrinsic_delaunay_cotmatrix(V, F)
    # libigl's L is negative semi-definite; tvf's S0 = d0^T star1 d0 positive.
    scale = abs(L).max()
    assert abs(ops["S0"] + L).max() <= 1e-12 * scale
    # The same triangulation up to cocircular ties: the same total area and vertex masses
    # (barycentric thirds of libigl's faces).
    s = l_igl.sum(axis=1) / 2
    areas = np.sqrt(np.maximum(s * (s - l_igl[:, 0]) * (s - l_igl[:, 1]) * (s - l_igl[:, 2]), 0))
    bary = np.zeros(len(V))
    np.add.at(bary, F_igl.ravel(), np.repeat(areas / 3, 3))
    ours = tvf.operators(mesh, "dec-barycentric", intrinsic_delaunay=True)["M0"].diagonal()
    assert np.abs(ours - bary).max() <= 1e-12 * bary.max()


def test_finite_elements_and_whitney_forms_from_lengths_agree_with_libigl():
    """P1 stiffness G^T M_X G of the conforming entries and d0^T M1 d0 of Whitney forms are the
    cotan matrix of the intrinsic Delaunay triangulation; the consistent P1 mass is assembled
    here from libigl's intrinsic lengths."""
    V, F = jittered_torus()
    mesh = tvf.Mesh(V, F)
    L, l_igl, F_igl = igl.intrinsic_delaunay_cotmatrix(V, F)
    scale = abs(L).max()
    for id in ["conforming-barycentric", "conforming-voronoi", "conforming-consistent", "whitney-galerkin"]:
        ops = tvf.operators(mesh, id, intrinsic_delaunay=True)
        assert abs(ops["S0"] + L).max() <= 1e-12 * scale, id
    s = l_igl.sum(axis=1) / 2
    areas = np.sqrt(np.maximum(s * (s - l_igl[:, 0]) * (s - l_igl[:, 1]) * (s - l_igl[:, 2]), 0))
    rows = np.repeat(F_igl, 3, axis=1).ravel()
    cols = np.tile(F_igl, (1, 3)).ravel()
    values = (np.repeat(areas, 9) / 12) * np.tile((1 + np.eye(3)).ravel(), len(F_igl))
    consistent = sp.csr_matrix((values, (rows, cols)), shape=(len(V), len(V)))
    for id in ["conforming-consistent", "whitney-galerkin"]:
        M0 = sp.csr_matrix(tvf.operators(mesh, id, intrinsic_delaunay=True)["M0"])
        assert abs(M0 - consistent).max() <= 1e-12 * consistent.max(), id
    # Genus 1: two harmonic fields, one vector per input face, for a face-field entry too.
    basis = tvf.basis(mesh, 6, "nonconforming-barycentric", intrinsic_delaunay=True)
    assert basis.discretization == "nonconforming-barycentric+intrinsic-delaunay"
    assert np.all(np.abs(basis.eigenvalues[:2]) < 1e-8) and basis.eigenvalues[2] > 1e-3
    assert basis.fields.shape == (len(F), 3, 6)
