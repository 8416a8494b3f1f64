#!/usr/bin/env python3
"""Independent check of `tvf operators` against docs/conventions.md.

Re-derives G, G*, M, M*, M_X, J, S_c, S*_c, S and B from an OBJ file with numpy/scipy (no
code shared with tvf), runs `tvf operators` on the same file for both decompositions and both
mass lumpings, and compares every matrix entry for entry.

    pip install numpy scipy
    python3 conformance/tools/verify_operators.py path/to/mesh.obj [path/to/tvf]

Exit status 0 if every matrix agrees to 1e-12 relative to its largest entry.
"""
import json
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np
import scipy.io
import scipy.sparse as sp


def read_obj(path):
    vertices, faces = [], []
    for line in Path(path).read_text().splitlines():
        parts = line.split()
        if not parts:
            continue
        if parts[0] == "v":
            vertices.append([float(x) for x in parts[1:4]])
        elif parts[0] == "f":
            faces.append([int(p.split("/")[0]) - 1 for p in parts[1:4]])
    return np.array(vertices), np.array(faces, dtype=np.int64)


def operators(P, T, lumping):
    V, F = len(P), len(T)
    # Edges (a, b), a < b, lexicographic; edge opposite corner c joins corners c+1, c+2.
    pairs = np.sort(np.stack([T[:, [1, 2]], T[:, [2, 0]], T[:, [0, 1]]], axis=1), axis=2)
    edges, inverse = np.unique(pairs.reshape(-1, 2), axis=0, return_inverse=True)
    face_edges = inverse.reshape(F, 3)
    E = len(edges)
    p0, p1, p2 = P[T[:, 0]], P[T[:, 1]], P[T[:, 2]]
    nscaled = np.cross(p1 - p0, p2 - p0)
    area = 0.5 * np.linalg.norm(nscaled, axis=1)
    n = nscaled / (2 * area[:, None])
    e1 = (p1 - p0) / np.linalg.norm(p1 - p0, axis=1)[:, None]
    e2 = np.cross(n, e1)
    corners = [p0, p1, p2]
    rows, cols, gvals, gsvals, gscols = [], [], [], [], []
    for c in range(3):
        a, b = corners[(c + 1) % 3], corners[(c + 2) % 3]
        grad3 = np.cross(n, b - a) / (2 * area[:, None])  # n × (p_{c+2} − p_{c+1}) / 2A
        for k, frame in enumerate((e1, e2)):
            comp = np.einsum("ij,ij->i", grad3, frame)
            rows.append(2 * np.arange(F) + k)
            cols.append(T[:, c])
            gvals.append(comp)
            gscols.append(face_edges[:, c])
            gsvals.append(-2 * comp)
    rows = np.concatenate(rows)
    G = sp.csr_matrix((np.concatenate(gvals), (rows, np.concatenate(cols))), shape=(2 * F, V))
    Gs = sp.csr_matrix((np.concatenate(gsvals), (rows, np.concatenate(gscols))), shape=(2 * F, E))
    # Masses.
    if lumping == "barycentric":
        vshare = np.repeat(area[:, None] / 3, 3, axis=1)
        eshare = np.repeat(area[:, None] / 3, 3, axis=1)
    else:
        vshare, eshare = voronoi_shares(P, T, area)
    M = np.bincount(T.ravel(), weights=vshare.ravel(), minlength=V)
    Ms = np.bincount(face_edges.ravel(), weights=eshare.ravel(), minlength=E)
    MX = np.repeat(area, 2)
    J = sp.block_diag([np.array([[0.0, -1.0], [1.0, 0.0]])] * F, format="csr")
    return dict(G=G, Gstar=Gs, M=M, Mstar=Ms, MX=MX, J=J, V=V, E=E, F=F)


def voronoi_shares(P, T, area):
    """Meyer et al. mixed areas for vertices; midpoint Voronoi cells clipped to the triangle for edges."""
    F = len(T)
    vshare = np.zeros((F, 3))
    eshare = np.zeros((F, 3))
    for t in range(F):
        q = P[T[t]]
        ang = []
        for c in range(3):
            u, v = q[(c + 1) % 3] - q[c], q[(c + 2) % 3] - q[c]
            ang.append(np.arctan2(np.linalg.norm(np.cross(u, v)), u @ v))
        A = area[t]
        obtuse = [c for c in range(3) if ang[c] > np.pi / 2]
        for c in range(3):
            if obtuse:
                vshare[t, c] = A / 2 if c == obtuse[0] else A / 4
            else:
                j, k = (c + 1) % 3, (c + 2) % 3
                # |p_c p_j|² cot(angle at k) + |p_c p_k|² cot(angle at j), over 8
                vshare[t, c] = (np.sum((q[c] - q[j]) ** 2) / np.tan(ang[k])
                                + np.sum((q[c] - q[k]) ** 2) / np.tan(ang[j])) / 8
        # 2D coordinates, midpoints, clipping by perpendicular bisectors.
        x = q[1] - q[0]
        x /= np.linalg.norm(x)
        nn = np.cross(q[1] - q[0], q[2] - q[0])
        nn /= np.linalg.norm(nn)
        y = np.cross(nn, x)
        tri = [np.array([(p - q[0]) @ x, (p - q[0]) @ y]) for p in q]
        mids = [(tri[(c + 1) % 3] + tri[(c + 2) % 3]) / 2 for c in range(3)]
        for c in range(3):
            poly = tri
            for o in ((c + 1) % 3, (c + 2) % 3):
                poly = clip(poly, mids[c], mids[o])
            eshare[t, c] = polygon_area(poly)
    return vshare, eshare


def clip(poly, keep, other):
    def inside(p):
        return np.sum((p - keep) ** 2) - np.sum((p - other) ** 2)
    out = []
    for i in range(len(poly)):
        a, b = poly[i], poly[(i + 1) % len(poly)]
        sa, sb = inside(a), inside(b)
        if sa <= 0:
            out.append(a)
        if sa * sb < 0:
            w = sa / (sa - sb)
            out.append(a + w * (b - a))
    return out


def polygon_area(poly):
    s = 0.0
    for i in range(len(poly)):
        a, b = poly[i], poly[(i + 1) % len(poly)]
        s += a[0] * b[1] - a[1] * b[0]
    return abs(s) / 2


def expected_matrices(ops, decomposition):
    G, Gs, J = ops["G"], ops["Gstar"], ops["J"]
    M, Ms, MX = ops["M"], ops["Mstar"], ops["MX"]
    D = sp.diags
    Sc = G.T @ D(MX) @ G
    Ss = Gs.T @ D(MX) @ Gs
    if decomposition == "conforming":
        inner = G @ D(1 / M) @ G.T - J @ Gs @ D(1 / Ms) @ Gs.T @ J
    else:
        inner = Gs @ D(1 / Ms) @ Gs.T - J @ G @ D(1 / M) @ G.T @ J
    S = D(MX) @ inner @ D(MX)
    B = S @ D(1 / MX) @ S
    return dict(G=G, Gstar=Gs, M=D(M), Mstar=D(Ms), MX=D(MX), J=J, Sc=Sc, Sstar=Ss, S=S, B=B)


def main():
    mesh = sys.argv[1]
    tvf = sys.argv[2] if len(sys.argv) > 2 else "target/release/tvf"
    P, T = read_obj(mesh)
    worst = 0.0
    for lumping in ("barycentric", "voronoi"):
        ops = operators(P, T, lumping)
        for decomposition in ("conforming", "nonconforming"):
            expected = expected_matrices(ops, decomposition)
            with tempfile.TemporaryDirectory() as out:
                subprocess.run([tvf, "operators", mesh, "--decomposition", decomposition,
                                "--mass", lumping, "--out", out], check=True, capture_output=True)
                info = json.loads(Path(out, "info.json").read_text())
                assert (info["vertices"], info["edges"], info["faces"]) == (ops["V"], ops["E"], ops["F"])
                for name, want in expected.items():
                    got = scipy.io.mmread(str(Path(out, name + ".mtx"))).tocsr()
                    want = sp.csr_matrix(want)
                    assert got.shape == want.shape, (name, got.shape, want.shape)
                    diff = abs(got - want).max()
                    scale = abs(want).max()
                    rel = diff / scale
                    worst = max(worst, rel)
                    status = "ok" if rel <= 1e-12 else "MISMATCH"
                    print(f"{lumping:12s} {decomposition:14s} {name:6s} {str(got.shape):16s} "
                          f"nnz {got.nnz:8d}  max|diff|/max|entry| = {rel:.2e}  {status}")
    print(f"worst relative difference: {worst:.2e}")
    sys.exit(0 if worst <= 1e-12 else 1)


if __name__ == "__main__":
    main()
