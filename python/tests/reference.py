"""Independent numpy implementations for the tests: generated meshes, the P1 / Crouzeix-Raviart
complex assembled from the formulas of the maths conventions (face frames e1 = normalize(p1 - p0),
e2 = n x e1; G = P1 gradients, G* = -2 G per opposite corner; barycentric lumping), and the
Galerkin masses (the consistent P1 mass, the Whitney 1-form mass) with the complex of Whitney
forms, written without any tvf code."""

import numpy as np
import scipy.sparse as sp


def torus(major=1.0, minor=0.4, n=16, m=8, stagger=True):
    """A closed genus-1 triangle mesh: an n x m grid on the torus (rows staggered by half a
    step so that the triangles are acute enough for DEC)."""
    V = []
    for i in range(n):
        for j in range(m):
            u = 2 * np.pi * (i + (0.5 * (j % 2) if stagger else 0.0)) / n
            v = 2 * np.pi * j / m
            V.append([(major + minor * np.cos(v)) * np.cos(u), (major + minor * np.cos(v)) * np.sin(u), minor * np.sin(v)])
    F = []
    idx = lambda i, j: (i % n) * m + (j % m)
    for i in range(n):
        for j in range(m):
            a, b, c, d = idx(i, j), idx(i + 1, j), idx(i + 1, j + 1), idx(i, j + 1)
            if j % 2 == 0:
                F += [[a, b, d], [b, c, d]]
            else:
                F += [[a, b, c], [a, c, d]]
    return np.array(V, float), np.array(F, np.int64)


def icosphere(subdivisions=1):
    """A closed genus-0 mesh: an icosahedron subdivided and projected to the unit sphere."""
    t = (1 + 5 ** 0.5) / 2
    V = [[-1, t, 0], [1, t, 0], [-1, -t, 0], [1, -t, 0], [0, -1, t], [0, 1, t], [0, -1, -t], [0, 1, -t], [t, 0, -1], [t, 0, 1], [-t, 0, -1], [-t, 0, 1]]
    F = [[0, 11, 5], [0, 5, 1], [0, 1, 7], [0, 7, 10], [0, 10, 11], [1, 5, 9], [5, 11, 4], [11, 10, 2], [10, 7, 6], [7, 1, 8],
         [3, 9, 4], [3, 4, 2], [3, 2, 6], [3, 6, 8], [3, 8, 9], [4, 9, 5], [2, 4, 11], [6, 2, 10], [8, 6, 7], [9, 8, 1]]
    V = [np.array(v, float) / np.linalg.norm(v) for v in V]
    for _ in range(subdivisions):
        midpoint = {}

        def mid(a, b):
            key = (min(a, b), max(a, b))
            if key not in midpoint:
                p = V[a] + V[b]
                V.append(p / np.linalg.norm(p))
                midpoint[key] = len(V) - 1
            return midpoint[key]

        F = [f for a, b, c in F for f in ([a, mid(a, b), mid(c, a)], [b, mid(b, c), mid(a, b)], [c, mid(c, a), mid(b, c)], [mid(a, b), mid(b, c), mid(c, a)])]
    return np.array(V), np.array(F, np.int64)


def plate_with_holes(genus):
    """A closed surface of genus ``genus``: the boundary of a one-voxel-thick plate of
    3 x (2 genus + 1) unit cubes with ``genus`` square holes, each square split into two
    triangles (so it is not Delaunay: DEC refuses it)."""
    filled = {(x, y, 0) for x in range(2 * genus + 1) for y in range(3)} - {(2 * h + 1, 1, 0) for h in range(genus)}
    vertices, faces = {}, []

    def vertex(p):
        return vertices.setdefault(p, len(vertices))

    for (x, y, z) in filled:
        for axis in range(3):
            for side in (0, 1):
                neighbour = [x, y, z]
                neighbour[axis] += 1 if side else -1
                if tuple(neighbour) in filled:
                    continue
                # The square face of the cube on this side, counter-clockwise seen from outside.
                u, w = [a for a in range(3) if a != axis]
                corners = []
                for du, dw in ((0, 0), (1, 0), (1, 1), (0, 1)):
                    p = [x, y, z]
                    p[axis] += side
                    p[u] += du
                    p[w] += dw
                    corners.append(vertex(tuple(p)))
                outward = 1 if side else -1
                # (u, w, axis) right-handed iff axis == (u + 2) % 3 ... orientation by sign.
                right_handed = (axis - u) % 3 == 2
                if (outward > 0) != right_handed:
                    corners.reverse()
                a, b, c, d = corners
                faces += [[a, b, c], [a, c, d]]
    V = np.zeros((len(vertices), 3))
    for p, i in vertices.items():
        V[i] = p
    return V, np.array(faces, np.int64)


def frames(V, F):
    """Face frames ``(F, 2, 3)``, unit normals ``(F, 3)`` and areas ``(F,)``."""
    p0, p1, p2 = V[F[:, 0]], V[F[:, 1]], V[F[:, 2]]
    cross = np.cross(p1 - p0, p2 - p0)
    area = 0.5 * np.linalg.norm(cross, axis=1)
    n = cross / (2 * area[:, None])
    e1 = (p1 - p0) / np.linalg.norm(p1 - p0, axis=1)[:, None]
    e2 = np.cross(n, e1)
    return np.stack([e1, e2], axis=1), n, area


def edges(F):
    """Edges ``(E, 2)`` with a < b in lexicographic order, and the edge of each face's corner
    ``(F, 3)`` (the edge opposite corner c)."""
    pairs = np.sort(np.stack([F[:, [1, 2]], F[:, [2, 0]], F[:, [0, 1]]], axis=1).reshape(-1, 2), axis=1)
    unique, inverse = np.unique(pairs, axis=0, return_inverse=True)
    return unique, inverse.reshape(-1, 3)


def p1_cr_complex(V, F):
    """The conforming complex (P1 potentials, face fields, CR co-potentials), barycentric
    masses: ``d0 = G``, ``d1 = G*^T J M_X``, ``M0 = M``, ``M1 = M_X``, ``M2 = M*^-1``; and
    ``J``, ``G``, ``G*``, ``M*`` for further checks. Vertices no face uses get zero rows,
    columns and masses."""
    nf, nv = len(F), len(V)
    fr, _, area = frames(V, F)
    E, opposite = edges(F)
    grads, _ = p1_gradients(V, F)
    G_rows, G_cols, G_vals, Gs_cols, Gs_vals = [], [], [], [], []
    for t in range(nf):
        for c in range(3):
            for k in range(2):
                g = grads[t, c] @ fr[t, k]
                G_rows.append(2 * t + k)
                G_cols.append(F[t, c])
                G_vals.append(g)
                Gs_cols.append(opposite[t, c])
                Gs_vals.append(-2 * g)
    G = sp.csr_matrix((G_vals, (G_rows, G_cols)), shape=(2 * nf, nv))
    Gs = sp.csr_matrix((Gs_vals, (G_rows, Gs_cols)), shape=(2 * nf, len(E)))
    MX = np.repeat(area, 2)
    M = np.bincount(F.ravel(), weights=np.repeat(area / 3, 3), minlength=nv)
    Ms = np.bincount(opposite.ravel(), weights=np.repeat(area / 3, 3), minlength=len(E))
    J = sp.block_diag([np.array([[0.0, -1.0], [1.0, 0.0]])] * nf, format="csr")
    d1 = (Gs.T @ J @ sp.diags(MX)).tocsr()
    return {"d0": G, "d1": d1, "M0": M, "M1": MX, "M2": 1.0 / Ms, "J": J, "G": G, "Gs": Gs, "Ms": Ms, "frames": fr, "edges": E}


def p1_gradients(V, F):
    """The gradient of each face's three P1 hat functions ``(F, 3, 3)`` (corner c: the hat
    function of vertex ``F[t, c]``) and the face areas ``(F,)``."""
    _, n, area = frames(V, F)
    grads = np.zeros((len(F), 3, 3))
    for c in range(3):
        pa, pb = V[F[:, (c + 1) % 3]], V[F[:, (c + 2) % 3]]
        grads[:, c] = np.cross(n, pb - pa) / (2 * area[:, None])
    return grads, area


def consistent_p1_mass(V, F):
    """The consistent P1 mass ``M[i, j] = sum_T |T| (1 + delta_ij) / 12`` (V x V, sparse)."""
    _, _, area = frames(V, F)
    rows, cols, vals = [], [], []
    for a in range(3):
        for b in range(3):
            rows.append(F[:, a])
            cols.append(F[:, b])
            vals.append(area * (2.0 if a == b else 1.0) / 12)
    return sp.csr_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))), shape=(len(V), len(V)))


def whitney_complex(V, F):
    """The complex of Whitney forms with Galerkin masses (FEEC's P1 -> Whitney 1-forms -> P0):
    ``d0`` the signed edge-vertex incidence (edge (a, b), a < b, from a to b), ``d1`` the
    signed face-edge incidence (+1 where the counter-clockwise boundary of the face runs from a
    to b), ``M0`` the consistent P1 mass, ``M1`` the Whitney mass
    ``M1[e, f] = sum_T integral <W_e, W_f>`` with ``W_ab = l_a grad l_b - l_b grad l_a``
    (exact quadrature: ``integral l_i l_j = |T| (1 + delta_ij) / 12``), ``M2 = 1/area``."""
    E, opposite = edges(F)
    ne = len(E)
    d0 = sp.csr_matrix((np.concatenate([-np.ones(ne), np.ones(ne)]), (np.tile(np.arange(ne), 2), np.concatenate([E[:, 0], E[:, 1]]))), shape=(ne, len(V)))
    grads, area = p1_gradients(V, F)
    # The local edge opposite corner c runs from corner c + 1 to corner c + 2 along the
    # counter-clockwise boundary; its global orientation is from the smaller vertex index.
    local = [((c + 1) % 3, (c + 2) % 3) for c in range(3)]
    d1_rows, d1_cols, d1_vals = [], [], []
    rows, cols, vals = [], [], []
    for t in range(len(F)):
        oriented = []
        for c, (i, j) in enumerate(local):
            if F[t, i] > F[t, j]:
                i, j = j, i
            oriented.append((opposite[t, c], i, j))
            d1_rows.append(t)
            d1_cols.append(opposite[t, c])
            d1_vals.append(1.0 if F[t, (c + 1) % 3] < F[t, (c + 2) % 3] else -1.0)
        g = grads[t]
        m = lambda a, b: area[t] * (2.0 if a == b else 1.0) / 12
        for e, i, j in oriented:
            for f, k, l in oriented:
                value = m(i, k) * g[j] @ g[l] - m(i, l) * g[j] @ g[k] - m(j, k) * g[i] @ g[l] + m(j, l) * g[i] @ g[k]
                rows.append(e)
                cols.append(f)
                vals.append(value)
    d1 = sp.csr_matrix((d1_vals, (d1_rows, d1_cols)), shape=(len(F), ne))
    M1 = sp.csr_matrix((vals, (rows, cols)), shape=(ne, ne))
    return {"d0": d0, "d1": d1, "M0": consistent_p1_mass(V, F), "M1": M1, "M2": 1.0 / area, "edges": E}


def cotan_matrix(V, F):
    """The cotan stiffness ``S_c`` (V x V), from the cotangents of the opposite angles."""
    nv = len(V)
    rows, cols, vals = [], [], []
    for c in range(3):
        i, j, k = F[:, c], F[:, (c + 1) % 3], F[:, (c + 2) % 3]
        u, w = V[j] - V[i], V[k] - V[i]
        cot = np.einsum("ij,ij->i", u, w) / np.linalg.norm(np.cross(u, w), axis=1)
        for a, b in ((j, k), (k, j)):
            rows.append(a)
            cols.append(b)
            vals.append(-0.5 * cot)
        for a in (j, k):
            rows.append(a)
            cols.append(a)
            vals.append(0.5 * cot)
    return sp.csr_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))), shape=(nv, nv))


def write_obj(path, V, F):
    """Writes an OBJ file (1-based faces)."""
    with open(path, "w") as f:
        for p in V:
            f.write("v %.17g %.17g %.17g\n" % tuple(p))
        for t in F:
            f.write("f %d %d %d\n" % tuple(np.asarray(t) + 1))


def max_difference(a, b):
    """``max |a - b|`` for sparse or dense arrays, and ``max |b|``."""
    d = a - b
    d = abs(d).max() if sp.issparse(d) else np.max(np.abs(d)) if np.size(d) else 0.0
    s = abs(b).max() if sp.issparse(b) else np.max(np.abs(b))
    return float(d), float(s)
