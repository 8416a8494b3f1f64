"""Polygon meshes generated in numpy for the tests: a quad torus, a cube-sphere, the dual of an
icosphere (pentagons and hexagons), and a jittered copy with non-planar polygons. Each is
``(V, faces)`` with faces a list of vertex-index lists, counter-clockwise seen from outside."""

import numpy as np

from reference import icosphere


def _oriented(V, faces, outward):
    """``faces`` with each polygon reversed where its vector area points against
    ``outward(centroid)``."""
    oriented = []
    for face in faces:
        p = V[face]
        area = 0.5 * np.cross(p, np.roll(p, -1, axis=0)).sum(axis=0)
        c = p.mean(axis=0)
        oriented.append(list(face) if area @ outward(c) > 0 else list(face[::-1]))
    return oriented


def quad_torus(major=1.0, minor=0.4, around=12, tube=6):
    theta = 2 * np.pi * np.arange(around) / around
    phi = 2 * np.pi * np.arange(tube) / tube
    T, P = np.meshgrid(theta, phi, indexing="ij")
    V = np.stack([(major + minor * np.cos(P)) * np.cos(T), (major + minor * np.cos(P)) * np.sin(T), minor * np.sin(P)], axis=-1).reshape(-1, 3)
    index = lambda i, j: (i % around) * tube + (j % tube)
    faces = [[index(i, j), index(i + 1, j), index(i + 1, j + 1), index(i, j + 1)] for i in range(around) for j in range(tube)]
    tube_centre = lambda c: c - major * np.array([c[0], c[1], 0.0]) / np.hypot(c[0], c[1])
    return V, _oriented(V, faces, tube_centre)


def cube_sphere(n=3):
    keys, faces = {}, []
    positions = []

    def vertex(key):
        if key not in keys:
            p = np.array(key, dtype=float) * 2 / n - 1
            positions.append(p / np.linalg.norm(p))
            keys[key] = len(positions) - 1
        return keys[key]

    for axis in range(3):
        for side in (0, n):
            u, v = (axis + 1) % 3, (axis + 2) % 3
            for i in range(n):
                for j in range(n):
                    quad = []
                    for di, dj in ((0, 0), (1, 0), (1, 1), (0, 1)):
                        key = [0, 0, 0]
                        key[axis], key[u], key[v] = side, i + di, j + dj
                        quad.append(vertex(tuple(key)))
                    faces.append(quad)
    V = np.array(positions)
    return V, _oriented(V, faces, lambda c: c)


def icosphere_dual(subdivisions=1):
    """The dual of an icosphere: a vertex per triangle (its centroid pushed to the sphere), a
    polygon per icosphere vertex (its five or six triangles in turn)."""
    Vt, Ft = icosphere(subdivisions)
    centroids = Vt[Ft].mean(axis=1)
    V = centroids / np.linalg.norm(centroids, axis=1)[:, None]
    faces = []
    for v in range(len(Vt)):
        around = np.nonzero((Ft == v).any(axis=1))[0]
        n = Vt[v] / np.linalg.norm(Vt[v])
        e1 = np.cross(n, [0.3, 0.5, 0.8])
        e1 /= np.linalg.norm(e1)
        e2 = np.cross(n, e1)
        d = V[around] - Vt[v]
        order = np.argsort(np.arctan2(d @ e2, d @ e1))
        faces.append([int(t) for t in around[order]])
    return V, _oriented(V, faces, lambda c: c)


def jittered(V, faces, amount=0.08, seed=3):
    """``V`` with every vertex moved radially by up to ``amount`` of its distance: non-planar
    polygons (the faces are kept)."""
    rng = np.random.default_rng(seed)
    return V * (1 + amount * rng.uniform(-1, 1, size=(len(V), 1))), faces
