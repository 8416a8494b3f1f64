"""Discretizations: the catalog, :class:`Complex` (catalog entries and your own matrices) and
:func:`operators`."""

from . import _native
from ._arrays import csr_parts, diagonal, to_csr
from .mesh import Mesh

DEFAULT_DISCRETIZATION = "conforming-barycentric"


def discretizations():
    """The catalog: a list of dicts with ``id``, ``description``, ``preconditions``,
    ``needs_delaunay`` and ``boundary_conditions`` (the ones offered on meshes with boundary,
    the default first). The same list as ``tvf discretizations``."""
    return _native.discretizations()


class Complex:
    """A discretization built on a mesh: five matrices ``d0`` (``n1 x n0``), ``d1``
    (``n2 x n1``), diagonal ``M0``, ``M1``, ``M2``, with ``d1 @ d0 = 0``.

    ``Complex(mesh, discretization="conforming-barycentric", boundary="tangential")`` builds a
    catalog entry (:func:`discretizations`); ``boundary`` (``tangential`` or ``normal``) only
    matters on meshes with boundary. :meth:`Complex.from_matrices` wraps matrices you assembled.
    Every function of the package takes a ``Complex`` wherever it takes a mesh and a
    ``discretization``.

    Attributes: ``mesh``, ``id``, ``dimensions`` (``(n0, n1, n2)``), ``node_kinds`` (each of
    ``vertices``, ``edges``, ``faces``, ``face-frames``), ``harmonic_dimension``,
    ``has_sampling`` (fields convert to and from face vectors).
    """

    def __init__(self, mesh, discretization=DEFAULT_DISCRETIZATION, boundary="tangential"):
        _check_mesh(mesh)
        self.mesh = mesh
        self._native = _native.Complex.build(mesh._native, str(discretization), str(boundary))

    @classmethod
    def from_matrices(cls, mesh, d0, d1, M0, M1, M2, sampling="face-frames", id="custom"):
        """Your own discretization: the five matrices, run through the same Rust code as the
        built-in ones (basis, decomposition, filter, spline, design, :func:`tvf.check`).

        - ``mesh``: a closed :class:`Mesh` (with boundary, the boundary condition would have to
          be given too: use a catalog entry there).
        - ``d0`` (``n1 x n0``, the gradient: potentials to fields, pointwise) and ``d1``
          (``n2 x n1``, the integrated curl: fields to co-potentials): any ``scipy.sparse``
          matrix or dense array.
        - ``M0`` (``n0``, potential masses, area), ``M1`` (``n1``, field masses:
          ``x @ (M1 * y)`` is the integral of ``<x, y>``), ``M2`` (``n2``, 1/area: turns the
          integrated curl into a pointwise one): vectors or diagonal matrices.
        - ``sampling``: ``"face-frames"`` (fields are ``2F`` coefficients, face ``t`` at
          ``2t, 2t+1`` in its frame ``e1 = normalize(p1 - p0)``, ``e2 = n x e1``; gives the
          rotation ``J`` too), ``"whitney"`` (fields are ``E`` edge integrals, Whitney
          interpolation) or ``"none"``.
        - ``id``: the name written into results and messages.

        The space of each node set is inferred from its size (V vertices, E edges, F faces,
        2F face frames). Checked, each with a message naming the matrix: shapes, finite
        entries, masses positive on every node a face uses (``M2`` of a closed mesh: every
        node), and ``max|d1 d0| <= 1e-10 max|d1| max|d0|``. Run :func:`tvf.check` for the rest
        of the conformance suite."""
        _check_mesh(mesh)
        complex_ = cls.__new__(cls)
        complex_.mesh = mesh
        complex_._native = _native.Complex.from_matrices(
            mesh._native,
            csr_parts(d0, "d0"),
            csr_parts(d1, "d1"),
            diagonal(M0, "M0"),
            diagonal(M1, "M1"),
            diagonal(M2, "M2"),
            str(sampling),
            str(id),
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

    def __repr__(self):
        return repr(self._native)


def _check_mesh(mesh):
    if not isinstance(mesh, Mesh):
        raise TypeError(f"expected a tvf.Mesh, got {type(mesh).__name__} (build one with tvf.Mesh(V, F))")


def as_complex(mesh, discretization=DEFAULT_DISCRETIZATION, boundary="tangential"):
    """``mesh`` itself if it is a :class:`Complex`, else the catalog entry on it."""
    if isinstance(mesh, Complex):
        return mesh
    return Complex(mesh, discretization, boundary)


def operators(mesh, discretization=DEFAULT_DISCRETIZATION, boundary="tangential"):
    """Every matrix of a discretization as ``scipy.sparse.csr_matrix``, and the face frames.

    ``mesh`` is a :class:`Mesh` (then ``discretization`` and ``boundary`` choose the catalog
    entry) or a :class:`Complex`. Returns a dict (``n0``, ``n1``, ``n2``: potentials, field
    coefficients, co-potentials; conforming: ``V``, ``2F``, ``E``; nonconforming: ``E``,
    ``2F``, ``V``; DEC: ``V``, ``E``, ``F``):

    ===============  ==========  =====================================================
    key              shape       matrix
    ===============  ==========  =====================================================
    ``d0``           n1 x n0     gradient, potentials -> fields (pointwise)
    ``d1``           n2 x n1     integrated curl, fields -> co-potentials; d1 d0 = 0
    ``M0``           n0 x n0     diagonal potential mass (area)
    ``M1``           n1 x n1     diagonal field mass: x^T M1 y = integral of <x, y>
    ``M2``           n2 x n2     diagonal, integrated -> pointwise co-potentials (1/area)
    ``S0``           n0 x n0     potential stiffness d0^T M1 d0 (P1: the cotan matrix)
    ``S2``           n2 x n2     co-potential stiffness d1 M1^-1 d1^T
    ``S``            n1 x n1     Dirichlet energy M1 d0 M0^-1 d0^T M1 + d1^T M2 d1
    ``L``            n1 x n1     Hodge-Laplacian M1^-1 S
    ``B``            n1 x n1     biharmonic energy S M1^-1 S
    ``div``          n0 x n1     divergence -M0^-1 d0^T M1 (pointwise, at potential nodes)
    ``curl``         n2 x n1     curl M2 d1 (pointwise, at co-potential nodes)
    ``div_other``    n2 x n1     the other family's divergence (finite elements only)
    ``curl_other``   n0 x n1     the other family's curl (finite elements only)
    ``J``            n1 x n1     rotation by +pi/2, (a, b) -> (-b, a) per face (face fields)
    ``frames``       F x 2 x 3   numpy array: ``frames[t] = [e1, e2]`` of face t
    ===============  ==========  =====================================================

    Vertex rows and columns are in mesh numbering (see ``Mesh.vertex_map``); edges as
    ``Mesh.edges``. The entries equal those ``tvf operators`` writes."""
    complex_ = as_complex(mesh, discretization, boundary)
    raw = _native.operators(complex_._native)
    return {name: (value if name == "frames" else to_csr(value)) for name, value in raw.items()}
