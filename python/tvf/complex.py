"""Discretizations: the catalog, :class:`Complex` (catalog entries and your own matrices) and
:func:`operators`."""

import numpy as np
import scipy.sparse.linalg as spla

from . import _native
from ._arrays import csr_parts, declared_shape, mass, to_csr
from ._native import TvfError
from .linear_operator import ComposedOperator
from .mesh import Mesh

# The default on triangle meshes. Functions default to ``discretization=None``: this on a
# triangle mesh, ``polygon-dec`` on a mesh with polygons (as on the command line).
DEFAULT_DISCRETIZATION = "conforming-barycentric"


def discretizations():
    """The catalog: a list of dicts with ``id``, ``description``, ``preconditions``,
    ``needs_delaunay`` and ``boundary_conditions`` (the ones offered on meshes with boundary,
    the default first). The same list as ``tvf discretizations``."""
    return _native.discretizations()


class Complex:
    """A discretization built on a mesh: five matrices ``d0`` (``n1 x n0``), ``d1``
    (``n2 x n1``) and the symmetric positive definite masses ``M0``, ``M1``, ``M2`` (each a
    diagonal or a sparse matrix; ``M2`` possibly given by its sparse inverse), with
    ``d1 @ d0 = 0``.

    ``Complex(mesh, discretization=None, boundary="tangential", beta=None)`` builds a catalog
    entry (:func:`discretizations`); without ``discretization``, ``conforming-barycentric`` on
    a triangle mesh and ``polygon-dec`` on a polygon mesh (the triangle entries refuse polygon
    meshes: triangulate those first, e.g. ``tvf triangulate MESH -o OUT``). ``boundary``
    (``tangential`` or ``normal``) only matters on meshes with boundary. ``beta`` is
    ``polygon-dec``'s stabilisation weight (> 0, default 1: ``M1 = sum_f |A_f| U_f^T U_f +
    beta P_f^T P_f``; the id becomes ``polygon-dec-beta-...`` for another value); it is an error
    with any other entry. ``intrinsic_delaunay`` (``True`` or ``"flip"``, or ``"refine"``)
    builds the entry on the intrinsic Delaunay triangulation of the mesh (the id gets
    ``+intrinsic-delaunay`` or ``+intrinsic-delaunay-refine``; DEC then builds on every mesh;
    fields are still ``(F, 3)`` arrays over the input faces: see docs/discretizations.md); an id
    with that suffix does the same. :meth:`Complex.from_matrices` wraps matrices you assembled.
    Every function of the package takes a ``Complex`` wherever it takes a mesh and a
    ``discretization``.

    Attributes: ``mesh``, ``id``, ``dimensions`` (``(n0, n1, n2)``), ``node_kinds`` (each of
    ``vertices``, ``edges``, ``faces``, ``face-frames``), ``harmonic_dimension``,
    ``has_sampling`` (fields convert to and from face vectors), ``masses`` (how each mass is
    stored).
    """

    def __init__(self, mesh, discretization=None, boundary="tangential", beta=None, *, intrinsic_delaunay=False):
        _check_mesh(mesh)
        self.mesh = mesh
        entry = None if discretization is None else str(discretization)
        beta = None if beta is None else float(beta)
        mode = intrinsic_mode(intrinsic_delaunay)
        self._native = _native.Complex.build(mesh._native, entry, str(boundary), beta, mode)

    @classmethod
    def from_matrices(cls, mesh, d0, d1, M0, M1, M2=None, sampling="face-frames", id="custom", *, M2_inverse=None,
                      nodes=None, fixed_nodes=None, boundary_condition=None):
        """Your own discretization: the five matrices, run through the same Rust code as the
        built-in ones (basis, decomposition, coefficients, filter, compression, spline, design —
        the full one with diagonal masses, the reduced one always —, :func:`tvf.check`).

        - ``mesh``: a :class:`Mesh`. On a mesh with boundary, give what the boundary condition
          does, as a ``--complex`` folder's ``info.json`` does: ``fixed_nodes`` and
          ``boundary_condition`` (below).
        - ``d0`` (``n1 x n0``, the gradient: potentials to fields, pointwise) and ``d1``
          (``n2 x n1``, the integrated curl: fields to co-potentials): any ``scipy.sparse``
          matrix or dense array.
        - ``M0`` (``n0 x n0``, the potential mass, area), ``M1`` (``n1 x n1``, the field mass:
          ``x @ (M1 @ y)`` is the integral of ``<x, y>``), ``M2`` (``n2 x n2``, 1/area: turns
          the integrated curl into a pointwise one; ``M2^-1`` is the co-potential mass). Each
          is symmetric positive definite, given as

          * a vector of ``n`` entries: the diagonal (lumped masses, DEC's Hodge stars), or a
            diagonal matrix (sparse or dense): the same;
          * a sparse matrix with off-diagonal entries (any ``scipy.sparse`` format, or a dense
            2-D array): a Galerkin mass such as the consistent P1 mass
            ``|T| (1 + delta_ij) / 12`` per triangle or the Whitney 1-form mass. It must be
            symmetric to round-off (``max|M - M^T| <= 1e-12 max|M|``; it is used as
            ``(M + M^T) / 2``).

          Diagonal masses keep every derived operator a sparse matrix; a sparse mass makes
          those that contain its inverse compositions (see :func:`operators`). ``M2`` itself
          must be diagonal (the co-potential mass, its inverse, must be sparse): a sparse
          co-potential mass is given as ``M2_inverse``.
        - ``M2_inverse`` (keyword only, instead of ``M2``): the inverse ``M2^-1``, the
          co-potential mass, when that is the sparse one (a consistent co-potential mass: the
          consistent P1 mass of ``nonconforming-consistent``, whose ``M2`` is dense). A vector
          or a sparse matrix as above. Give exactly one of ``M2`` and ``M2_inverse``.
        - ``sampling``: ``"face-frames"`` (fields are ``2F`` coefficients, face ``t`` at
          ``2t, 2t+1`` in its frame ``e1 = normalize(p1 - p0)``, ``e2 = n x e1``; gives the
          rotation ``J`` too), ``"whitney"`` (fields are ``E`` edge integrals, Whitney
          interpolation; triangle meshes), ``"polygon-sharp"`` (``E`` edge integrals, one vector
          per face by polygonal DEC's sharp; polygon and triangle meshes) or ``"none"``.
        - ``id``: the name written into results and messages.
        - ``fixed_nodes`` (keyword only): ``dict(potentials=[...], fields=[...],
          co_potentials=[...])``, the node indices the boundary condition fixes to zero (each
          key optional, default none); their column of ``d0`` (potentials), row of ``d0`` and
          column of ``d1`` (fields), row of ``d1`` (co-potentials) must be empty. Without them
          on a mesh with boundary, the matrices usually leave too many harmonic fields, which
          is refused.
        - ``boundary_condition`` (keyword only): ``"tangential"`` or ``"normal"``, recorded in
          the complex's id and topology (default ``"tangential"``).

        - ``nodes`` (keyword only): the node kinds of the three spaces, a tuple such as
          ``("vertices", "edges", "faces")`` (each ``"vertices"``, ``"edges"``, ``"faces"``,
          ``"face-frames"`` or ``None``), checked against the sizes.

        A space whose kind ``nodes`` does not give gets the one kind of its size (V vertices, E
        edges, F faces, 2F face frames; the field space the kind its sampling needs, where that
        fits). A size two kinds share (``V = F`` on a quad torus) is refused asking for
        ``nodes``, since guessing would place the co-potentials at the wrong points. Checked, each failure a :class:`tvf.TvfError` whose message names the
        matrix (``d0``, ``d1``, ``M0``, ``M1``, ``M2``, ``M2_inverse (M2⁻¹)``): shapes (square
        masses of the right size), finite entries, symmetry, positive definiteness (a diagonal
        positive on every node a face uses; a sparse mass by the sparse Cholesky factorization
        that tvf then uses to solve with it), and ``max|d1 d0| <= 1e-10 max|d1| max|d0|``. Run
        :func:`tvf.check` for the rest of the conformance suite."""
        _check_mesh(mesh)
        if M2 is not None and M2_inverse is not None:
            raise TvfError("give the co-potential mass either as M2 or as its inverse M2_inverse, not both")
        if M2 is None and M2_inverse is None:
            raise TvfError("give the co-potential mass as M2 or as its inverse M2_inverse")
        co_potential_mass = ("M2", M2) if M2 is not None else ("M2_inverse", M2_inverse)
        _check_declared_shapes(mesh, d0, d1, M0, M1, co_potential_mass)
        complex_ = cls.__new__(cls)
        complex_.mesh = mesh
        complex_._native = _native.Complex.from_matrices(
            mesh._native,
            csr_parts(d0, "d0"),
            csr_parts(d1, "d1"),
            mass(M0, "M0"),
            mass(M1, "M1"),
            None if M2 is None else mass(M2, "M2"),
            None if M2_inverse is None else mass(M2_inverse, "M2_inverse"),
            str(sampling),
            str(id),
            None if nodes is None else tuple(None if kind is None else str(kind) for kind in nodes),
            _fixed_nodes(fixed_nodes),
            None if boundary_condition is None else str(boundary_condition),
        )
        return complex_

    @property
    def id(self):
        return self._native.id

    @property
    def dimensions(self):
        return self._native.dimensions

    @property
    def node_kinds(self):
        return self._native.node_kinds

    @property
    def harmonic_dimension(self):
        return self._native.harmonic_dimension

    @property
    def has_sampling(self):
        return self._native.has_sampling

    @property
    def masses(self):
        """How each mass is stored: ``{"M0": {"storage": ..., "form": ..., "key": ...}, "M1":
        ..., "M2": ...}``. ``storage`` is ``diagonal`` or ``sparse``; ``form`` is ``direct``
        (the sparse matrix is the mass) or ``inverse`` (it is the mass's inverse, and the mass
        is dense); ``key`` is the key of :func:`operators` holding the sparse matrix (``M2`` or
        ``M2_inverse``)."""
        return {name: dict(entry) for name, entry in self._native.masses.items()}

    def __repr__(self):
        return repr(self._native)


def _check_declared_shapes(mesh, d0, d1, M0, M1, co_potential_mass):
    """Refuses shapes that cannot belong to ``mesh`` (every size one of its ``V``, ``E``, ``F``,
    ``2F``; ``d0``, ``d1`` and the masses fitting together) from the shapes the arguments
    declare, before anything of their size is converted or allocated (the native checks say the
    same, later)."""
    V, E, F = mesh._native.sizes
    label = mesh.label

    def matrix_shape(value, name):
        shape = declared_shape(value)
        if len(shape) != 2:
            raise TvfError(f"{label}: {name} has shape {shape}: a matrix has two dimensions")
        return shape

    n1, n0 = matrix_shape(d0, "d0")
    n2, d1_columns = matrix_shape(d1, "d1")
    for n, space in [(n0, "potential space"), (n1, "field space"), (n2, "co-potential space")]:
        if n not in (V, E, F, 2 * F):
            raise TvfError(
                f"{label}: the {space} has {n} nodes: not the mesh's {V} vertices, {E} edges, "
                f"{F} faces or {2 * F} face-frame coefficients"
            )
    if d1_columns != n1:
        raise TvfError(f"{label}: d1 is {n2} x {d1_columns}: its columns must be the {n1} rows of d0")
    for (name, value), n, what in [
        (("M0", M0), n0, "column of d0"),
        (("M1", M1), n1, "row of d0"),
        (co_potential_mass, n2, "row of d1"),
    ]:
        if isinstance(value, spla.LinearOperator):
            continue  # refused as a mass by its type (mass())
        shape = declared_shape(value)
        if len(shape) == 1 and shape[0] != n:
            raise TvfError(f"{label}: {name} (one entry per {what}): expected {n} entries, found {shape[0]}")
        if len(shape) == 2 and shape[0] != shape[1]:
            raise TvfError(f"{label}: {name} is {shape[0]} × {shape[1]}, not square")
        if len(shape) not in (1, 2) or (len(shape) == 2 and shape != (n, n)):
            raise TvfError(f"{label}: {name} has shape {shape}, but the complex needs {n} x {n} (one row per {what})")


def _fixed_nodes(fixed_nodes):
    """``fixed_nodes`` (a dict with ``potentials``, ``fields``, ``co_potentials``) as the native
    triple of index lists, or ``None``."""
    if fixed_nodes is None:
        return None
    if not isinstance(fixed_nodes, dict):
        raise TypeError(f"fixed_nodes: expected a dict, got {type(fixed_nodes).__name__}")
    keys = ("potentials", "fields", "co_potentials")
    unknown = set(fixed_nodes) - set(keys)
    if unknown:
        raise TvfError(f"fixed_nodes: unknown key(s) {sorted(unknown)}: potentials, fields, co_potentials")
    lists = []
    for key in keys:
        values = np.asarray(fixed_nodes.get(key, []))
        if values.size and (values.ndim != 1 or not np.issubdtype(values.dtype, np.integer) or values.min() < 0):
            raise TvfError(f"fixed_nodes['{key}']: expected non-negative integer indices")
        lists.append([int(v) for v in values.ravel()])
    return tuple(lists)


def _check_mesh(mesh):
    if not isinstance(mesh, Mesh):
        raise TypeError(f"expected a tvf.Mesh, got {type(mesh).__name__} (build one with tvf.Mesh(V, F))")


def intrinsic_mode(intrinsic_delaunay):
    """The mode of an ``intrinsic_delaunay`` argument: ``None`` for ``False``/``None``,
    ``"flip"`` for ``True``, else ``"flip"`` or ``"refine"`` as given."""
    if intrinsic_delaunay is None or intrinsic_delaunay is False:
        return None
    if intrinsic_delaunay is True:
        return "flip"
    if intrinsic_delaunay in ("flip", "refine"):
        return intrinsic_delaunay
    raise TvfError(f"intrinsic_delaunay={intrinsic_delaunay!r}: give True, False, 'flip' or 'refine'")


def as_complex(mesh, discretization=None, boundary="tangential", beta=None, intrinsic_delaunay=False):
    """``mesh`` itself if it is a :class:`Complex`, else the catalog entry on it (``beta``:
    polygon-dec's stabilisation; ``intrinsic_delaunay``: see :class:`Complex`)."""
    if isinstance(mesh, Complex):
        return mesh
    return Complex(mesh, discretization, boundary, beta, intrinsic_delaunay=intrinsic_delaunay)


def operators(mesh, discretization=None, boundary="tangential", beta=None, *, intrinsic_delaunay=False):
    """Every matrix of a discretization, and the face frames.

    ``mesh`` is a :class:`Mesh` (then ``discretization`` and ``boundary`` choose the catalog
    entry, ``beta`` polygon-dec's stabilisation) or a :class:`Complex`. Returns a dict (``n0``,
    ``n1``, ``n2``: potentials, field coefficients, co-potentials; conforming: ``V``, ``2F``,
    ``E``; nonconforming: ``E``, ``2F``, ``V``; DEC, ``whitney-galerkin`` and ``polygon-dec``:
    ``V``, ``E``, ``F``). A value is a
    ``scipy.sparse.csr_matrix`` where the matrix is sparse, and a
    :class:`tvf.ComposedOperator` (a ``scipy.sparse.linalg.LinearOperator`` applied by tvf,
    never formed) where it is dense:

    ================  ==========  ====================================================  ========
    key               shape       matrix                                                type
    ================  ==========  ====================================================  ========
    ``d0``            n1 x n0     gradient, potentials -> fields (pointwise)            csr
    ``d1``            n2 x n1     integrated curl, fields -> co-potentials; d1 d0 = 0   csr
    ``M0``            n0 x n0     potential mass (area): diagonal or sparse SPD         csr
    ``M1``            n1 x n1     field mass, x^T M1 y = integral of <x, y>: diagonal   csr
                                  or sparse SPD
    ``M2``            n2 x n2     integrated -> pointwise co-potentials (1/area);       csr / op
                                  M2^-1 is the co-potential mass. Dense (an operator)
                                  where ``M2_inverse`` is given
    ``M2_inverse``    n2 x n2     only where M2 is stored as its inverse: the sparse    csr
                                  co-potential mass (``nonconforming-consistent``)
    ``S0``            n0 x n0     potential stiffness d0^T M1 d0 (P1: the cotan matrix) csr
    ``S2``            n2 x n2     co-potential stiffness d1 M1^-1 d1^T                  csr / op
    ``S``             n1 x n1     Dirichlet energy M1 d0 M0^-1 d0^T M1 + d1^T M2 d1     csr / op
    ``L``             n1 x n1     Hodge-Laplacian M1^-1 S                               csr / op
    ``B``             n1 x n1     biharmonic energy S M1^-1 S                           csr / op
    ``div``           n0 x n1     divergence -M0^-1 d0^T M1 (pointwise, potentials)     csr / op
    ``curl``          n2 x n1     curl M2 d1 (pointwise, at co-potential nodes)         csr / op
    ``div_other``     n2 x n1     the other family's divergence (finite elements only)  csr / op
    ``curl_other``    n0 x n1     the other family's curl (finite elements only)       csr / op
    ``J``             n1 x n1     rotation by +pi/2, (a, b) -> (-b, a) per face         csr
    ``frames``        F x 2 x 3   ``frames[t] = [e1, e2]`` of face t                    ndarray
    ================  ==========  ====================================================  ========

    On the intrinsic Delaunay triangulation (``intrinsic_delaunay``, see :class:`Complex`) the
    nodes are the intrinsic vertices, edges and faces, and four more keys describe them:
    ``intrinsic_faces`` (``(F_i, 3)`` int, counter-clockwise vertex triples; a vertex may
    repeat), ``intrinsic_edges`` (``(E_i, 2)`` int, the direction of ``d0``'s ``-1, +1``),
    ``intrinsic_edge_lengths`` (``(E_i,)``) and ``intrinsic_vertex_positions`` (``(V_i, 3)``,
    where each vertex sits on the input surface; the input's vertices come first). ``frames``
    stays per input face.

    A derived operator is a ``csr_matrix`` exactly where every mass it contains is diagonal
    (every lumped entry: all of them) or appears uninverted; it is a ComposedOperator where it
    contains ``M0^-1`` or ``M1^-1`` of a sparse mass or ``M2`` given by its inverse
    (``conforming-consistent``: ``S``, ``L``, ``B``, ``div``, ``curl_other``;
    ``whitney-galerkin``: all of ``S2``, ``S``, ``L``, ``B``, ``div``;
    ``nonconforming-consistent``: ``M2``, ``S``, ``L``, ``B``, ``curl``, ``div_other``).
    :attr:`Complex.masses` says how each mass is stored. Masses are the stored matrices
    (a fixed node of a mesh with boundary keeps its row); a mass given as an operator applies
    ``M2`` on the free nodes and is zero on the others.

    Vertex rows and columns are in mesh numbering (see ``Mesh.vertex_map``); edges as
    ``Mesh.edges``. The sparse entries equal those ``tvf operators`` writes (which writes
    ``M2_inverse`` in place of a dense ``M2`` and leaves dense derived matrices out)."""
    complex_ = as_complex(mesh, discretization, boundary, beta, intrinsic_delaunay)
    raw = _native.operators(complex_._native)
    return {name: _operator(name, value) for name, value in raw.items()}


def _operator(name, value):
    if name == "frames" or name.startswith("intrinsic_"):
        return value
    if isinstance(value, _native.Operator):
        return ComposedOperator(value)
    return to_csr(value)
