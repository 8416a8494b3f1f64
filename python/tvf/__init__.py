"""tvf — spectral processing of tangential vector fields on triangle and polygon meshes, from Python.

numpy arrays and ``scipy.sparse`` matrices in and out (dense derived operators as
``scipy.sparse.linalg.LinearOperator``); the computations are tvf's Rust code
(the same as the ``tvf`` command line), run without holding the GIL. Start with::

    import tvf
    mesh = tvf.Mesh(V, F)                       # or tvf.Mesh.load("bunny.obj")
    ops = tvf.operators(mesh, "conforming-barycentric")   # dict of scipy.sparse matrices
    basis = tvf.basis(mesh, k=100)              # eigenvalues, families, fields (F x 3 x k)

Every function's docstring is its reference (``help(tvf.basis)``); the conventions (shapes,
signs, units, orderings, the vertex map) are in ``docs/python.md`` of the repository.
Errors are :class:`tvf.TvfError` (a ``ValueError``) with the message the command line prints
for the same problem; wrong dtypes are a ``TypeError``.
"""

from ._native import TvfError
from .mesh import Mesh, read_mesh
from .complex import Complex, discretizations, operators, DEFAULT_DISCRETIZATION
from .linear_operator import ComposedOperator
from .basis_file import BasisFile
from .spectral import Basis, basis, decompose, coefficients, filter, compress, decompress
from .design import spline, design
from .solvers import eigsh
from .conformance import CheckReport, check, compare, convergence

__all__ = [
    "TvfError",
    "Mesh",
    "read_mesh",
    "Complex",
    "discretizations",
    "operators",
    "ComposedOperator",
    "DEFAULT_DISCRETIZATION",
    "Basis",
    "BasisFile",
    "basis",
    "decompose",
    "coefficients",
    "filter",
    "compress",
    "decompress",
    "spline",
    "design",
    "eigsh",
    "CheckReport",
    "check",
    "compare",
    "convergence",
]
