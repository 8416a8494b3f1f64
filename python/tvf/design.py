"""Fields from constraints: :func:`spline` (hard) and :func:`design` (soft)."""

import json

import numpy as np

from . import _native
from ._native import TvfError
from .basis_file import BasisFile, _field_out as _file_field_out
from .complex import as_complex
from .spectral import _complex_of, _field_out, basis as compute_basis


def _json(constraints):
    if isinstance(constraints, (str, bytes)):
        return constraints if isinstance(constraints, str) else constraints.decode("utf-8")
    try:
        return json.dumps(constraints, allow_nan=True)
    except TypeError as e:
        raise TvfError(f"constraints: not JSON data: {e}") from None


def _result(complex_, raw):
    coefficients = np.asarray(raw["field"])
    field = _field_out(complex_, coefficients, complex_.has_sampling)
    return {"field": field, "coefficients": coefficients, "residuals": dict(raw["residuals"])}


def spline(mesh, constraints, k=None, basis=None, discretization=None, boundary="tangential", seed=0, progress=None, origin="constraints", *, intrinsic_delaunay=False):
    """A tangential vector field spline (``tvf spline``): minimises ``E_B + omega E_D`` in the
    basis of the ``k`` lowest eigenfields subject to the constraints, met exactly in that basis.

    ``constraints``: the dict of a constraint file (``{"omega": 0.1, "constraints": [{"id":
    "a", "kind": "vector", "face": 12, "value": [1, 0, 0]}, ...]}``; kinds ``vector``,
    ``divergence``, ``curl``; locations ``face`` (+ ``barycentric``), ``vertex``, ``edge``;
    see the README's "Constraint files"), or its JSON text. ``origin`` names it in messages.
    Give ``k`` (the basis is computed), a :class:`tvf.Basis`, or a :class:`tvf.BasisFile` (read
    in blocks as ``tvf spline --basis FILE`` reads it: only the rows of the basis the constraints
    touch are held; ``progress`` then hears of its passes, ``rows`` and ``synthesising``, as
    :class:`tvf.BasisFile`'s products do, Ctrl+C noticed at every block). Conflicting or dependent
    constraints raise :class:`tvf.TvfError` naming them, as the command line does.

    Returns a dict: ``field`` (``(F, 3)`` face vectors, or coefficients without sampling),
    ``coefficients`` (``n1``), ``residuals`` (``{id: (absolute, relative)}``)."""
    if basis is None and k is None:
        raise TvfError("spline: give k (the basis size) or a basis")
    return _reduced(mesh, constraints, k, basis, discretization, boundary, seed, progress, origin, soft=False, intrinsic_delaunay=intrinsic_delaunay)


def design(mesh, constraints, discretization=None, boundary="tangential", origin="constraints", k=None, basis=None, seed=0, progress=None, *, intrinsic_delaunay=False):
    """Soft-constrained design (``tvf design``): minimises
    ``E_D + omega E_B + sum_i weight_i |C_i x - c_i|^2`` (plus a tiny screening
    ``eps x^T M1 x`` that pins harmonic fields the constraints leave free).

    - **full** (``k`` and ``basis`` not given; ``tvf design --full``): over the full field
      space, by a sparse ``LDL^T`` of an augmented system with iterative refinement. Every
      complex: where a mass is not diagonal (``whitney-galerkin``, ``conforming-consistent``,
      ``nonconforming-consistent``, a :meth:`Complex.from_matrices` complex with sparse masses)
      the system gets auxiliary unknowns (the divergence and curl at the nodes) so that it stays
      sparse.
    - **reduced** (``k``, a :class:`tvf.Basis` or a :class:`tvf.BasisFile` given; ``tvf design
      --reduced``): in the basis of the ``k`` lowest eigenfields (computed with ``seed`` and
      ``progress`` as :func:`tvf.basis`, or the basis given; a basis file is read in blocks,
      ``progress`` hearing of its passes as for :func:`spline`), a dense system of the basis
      size. Every complex.

    ``constraints`` as for :func:`spline` (``weight`` > 0 per constraint, default 1). Returns
    the same dict as :func:`spline`."""
    if basis is None and k is None:
        complex_ = as_complex(mesh, discretization, boundary, intrinsic_delaunay=intrinsic_delaunay)
        raw = _native.design(complex_._native, _json(constraints), str(origin))
        return _result(complex_, raw)
    return _reduced(mesh, constraints, k, basis, discretization, boundary, seed, progress, origin, soft=True, intrinsic_delaunay=intrinsic_delaunay)


def _reduced(mesh, constraints, k, basis, discretization, boundary, seed, progress, origin, soft, intrinsic_delaunay=False):
    """The spline (``soft`` false) or reduced soft design in ``basis``, or in the basis of the
    ``k`` lowest eigenfields computed here."""
    if isinstance(basis, BasisFile):
        blocks = basis._blocks(mesh, progress)
        raw = blocks.reduced(_json(constraints), str(origin), soft, progress)
        coefficients = np.asarray(raw["field"])
        field = _file_field_out(blocks, coefficients, blocks.has_sampling)
        return {"field": field, "coefficients": coefficients, "residuals": dict(raw["residuals"])}
    if basis is None:
        complex_ = as_complex(mesh, discretization, boundary, intrinsic_delaunay=intrinsic_delaunay)
        basis = compute_basis(complex_, k, seed=seed, progress=progress)
    else:
        complex_ = _complex_of(mesh, discretization, boundary, basis)
    raw = _native.reduced(complex_._native, basis._parts(), _json(constraints), str(origin), soft)
    return _result(complex_, raw)
