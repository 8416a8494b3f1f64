"""Meshes: :class:`Mesh` and :func:`read_mesh`."""

import numpy as np

from . import _native
from ._arrays import float_array, index_array
from ._native import TvfError


class Mesh:
    """A valid oriented manifold triangle or polygon mesh.

    ``Mesh(V, F, label="mesh")``: ``V`` is ``n x 3`` (float); ``F`` is ``m x 3`` (integer,
    0-based vertex indices, counter-clockwise seen from outside), an ``m x k`` integer array
    (all faces ``k``-gons), or a list of polygons, each a sequence of at least three vertex
    indices (faces of any sizes). A mesh whose faces all have three corners is a triangle mesh;
    any larger face makes it a **polygon mesh**, kept as polygons (possibly non-planar or
    non-convex), on which ``polygon-dec`` is the default discretization (de Goes, Butts, Desbrun
    2020; the triangle entries refuse polygon meshes). The validation is the one
    every ``tvf`` command applies to a mesh file, in the same order and with the same messages
    (prefixed by ``label`` instead of the file and line): no faces, non-finite coordinates,
    indices out of range, repeated vertices in a face, non-manifold edges and vertices,
    non-orientable or inconsistently oriented faces, zero-area faces, polygons that fold over
    themselves, coordinates so large that the area overflows. Each raises :class:`tvf.TvfError`; a non-numeric ``V`` or a
    non-integer ``F`` raises ``TypeError``.

    **Unreferenced vertices** (no face uses them) are dropped and the others renumbered in
    order: ``mesh.positions`` is ``V' x 3`` with ``V' <= n`` and ``mesh.vertex_map[v]`` is the
    input index of mesh vertex ``v``. Every vertex-indexed result (rows of ``d0``, ``M0``,
    potentials) is in mesh numbering; ``x_input[mesh.vertex_map] = x`` puts it back in yours.

    Attributes: ``positions`` (V x 3), ``faces`` (F x 3 int64 for a triangle mesh, a list of
    int64 arrays for a polygon mesh), ``edges`` (E x 2, int64,
    ``(a, b)`` with ``a < b`` in lexicographic order — the numbering of every edge-indexed
    quantity), ``vertex_map`` (V, int64), ``input_vertex_count``, ``face_areas`` (F),
    ``face_normals`` (F x 3), ``genus``, ``component_count``, ``is_closed``,
    ``boundary_loop_count``, ``warnings`` (list of str), ``fingerprint`` (16 hex digits, as in
    constraint and compressed files), ``label``.
    """

    def __init__(self, V, F, label="mesh"):
        positions = float_array(V, "V", ndim=2, columns=3)
        corners, sizes = _face_lists(F)
        self._native = _native.Mesh(positions, corners, sizes, str(label))

    @classmethod
    def load(cls, path):
        """Reads and validates a mesh file (``.obj``, ``.off``, ``.ply`` ASCII or binary);
        errors name the file and the line as the command line does."""
        mesh = cls.__new__(cls)
        mesh._native = _native.read_mesh(str(path))
        return mesh

    def __getattr__(self, name):
        if name == "_native":
            raise AttributeError(name)
        return getattr(self._native, name)

    def __repr__(self):
        return repr(self._native)

    def __reduce__(self):
        # Pickles as the validated arrays (the vertex map of the original input is not kept).
        return (Mesh, (self.positions, self.faces, self.label))


def _face_lists(F):
    """``(corners, sizes)``: every face's vertex indices one face after the other, and the
    number of corners of each face (both int64), from an ``m x k`` integer array or a list of
    integer sequences."""
    if isinstance(F, np.ndarray) or (
        isinstance(F, (list, tuple)) and len(F) > 0 and len({len(np.atleast_1d(f)) for f in F}) == 1
    ):
        array = np.asarray(F)
        if array.dtype != object and array.ndim == 2:
            faces = index_array(array, "F", ndim=2)
            return np.ascontiguousarray(faces.reshape(-1)), np.full(faces.shape[0], faces.shape[1], dtype=np.int64)
        if isinstance(F, np.ndarray) and array.dtype != object:
            raise TvfError(f"F: expected shape (m, 3), (m, k) or a list of polygons, got {array.shape}")
    polygons = [index_array(face, f"F[{t}]", ndim=1) for t, face in enumerate(F)]
    sizes = np.array([len(p) for p in polygons], dtype=np.int64)
    corners = np.concatenate(polygons) if polygons else np.zeros(0, dtype=np.int64)
    return np.ascontiguousarray(corners, dtype=np.int64), sizes


def read_mesh(path):
    """``(V, F)`` of a mesh file (OBJ, OFF, PLY), validated like every ``tvf`` command does.

    ``V`` is ``n x 3`` float64, ``F`` is ``m x 3`` int64 (0-based) for a triangle mesh, a list
    of int64 arrays (one per polygon) for a polygon mesh. Unreferenced vertices are
    dropped (use :meth:`Mesh.load` to keep the map back to the file's numbering). Errors are
    :class:`tvf.TvfError` naming the file, the line and the problem."""
    mesh = Mesh.load(path)
    faces = mesh.faces
    return np.asarray(mesh.positions), faces if isinstance(faces, list) else np.asarray(faces)
