"""The Fourier basis of tangent fields and what is built on it: :func:`basis`,
:func:`decompose`, :func:`coefficients`, :func:`filter`, :func:`compress`, :func:`decompress`."""

from dataclasses import dataclass
from typing import Optional

import numpy as np

from . import _native
from ._arrays import integer
from ._fields import field_coefficients, field_in_form, field_rows, rows_in_form
from ._native import TvfError
from .basis_file import BasisFile
from .complex import Complex, as_complex


@dataclass
class Basis:
    """A Fourier basis: the ``k`` eigenfields of lowest eigenvalue of the Hodge-Laplacian
    ``L = M1^-1 S``, harmonic fields included, sorted by eigenvalue. Plain numpy arrays
    (picklable).

    - ``eigenvalues``: ``(k,)``, ascending, units 1/length^2 (frequency ``sqrt(eigenvalue)``).
    - ``families``: ``(k,)`` str array: ``harmonic`` (eigenvalue 0; ``2g`` on a closed mesh,
      ``2g + b - 1`` with ``b`` boundary loops), ``integrable`` (gradients ``d0 phi / sqrt(l)``,
      curl-free) or ``cointegrable`` (co-gradients ``-M1^-1 d1^T psi / sqrt(m)``,
      divergence-free).
    - ``coefficients``: ``(n1, k)``, the discretization's own coefficients, ``M1``-orthonormal:
      ``coefficients.T @ (M1 @ coefficients) = I`` with ``M1 = tvf.operators(complex)["M1"]``
      (diagonal or sparse).
    - ``fields``: ``(F, 3, k)``, each field sampled at the face centroids as a 3D tangent
      vector (``None`` for a complex without sampling).
    - ``discretization``: the complex id the basis belongs to.
    """

    eigenvalues: np.ndarray
    families: np.ndarray
    coefficients: np.ndarray
    fields: Optional[np.ndarray]
    discretization: str

    @property
    def harmonic_fields(self):
        """The harmonic basis fields as ``(F, 3, h)`` (or ``(n1, h)`` coefficients without
        sampling)."""
        chosen = self.families == "harmonic"
        source = self.fields if self.fields is not None else self.coefficients
        return source[..., chosen]

    def __len__(self):
        return len(self.eigenvalues)

    @classmethod
    def _of_native(cls, raw):
        """The basis of the dict the native code returns (``tvf._native.basis``)."""
        return cls(
            eigenvalues=np.asarray(raw["eigenvalues"]),
            families=np.array(raw["families"], dtype=str),
            coefficients=np.asarray(raw["coefficients"]),
            fields=None if raw["face_vectors"] is None else np.asarray(raw["face_vectors"]),
            discretization=raw["discretization"],
        )

    def _parts(self):
        return (
            np.ascontiguousarray(self.eigenvalues, dtype=np.float64),
            [str(f) for f in self.families],
            np.ascontiguousarray(self.coefficients, dtype=np.float64),
        )


def _complex_of(mesh, discretization, boundary, basis=None):
    """The complex a call works on; with a basis, the one the basis was computed for."""
    if isinstance(mesh, Complex):
        complex_ = mesh
    elif basis is not None:
        entry, _, condition = basis.discretization.rpartition("+")
        if condition not in ("tangential", "normal"):
            entry, condition = basis.discretization, None
        complex_ = Complex(mesh, entry, condition or boundary)
    else:
        complex_ = Complex(mesh, discretization, boundary)
    if basis is not None and basis.discretization != complex_.id:
        raise TvfError(
            f"the basis belongs to '{basis.discretization}', the discretization is '{complex_.id}'"
        )
    return complex_


def _field_in(complex_, field, name="field"):
    """``(coefficients, as_vectors)``: an ``(F, 3)`` field is converted through the sampling,
    an ``(n1,)`` one taken as coefficients."""
    return field_coefficients(
        field, name, complex_.dimensions[1], complex_.has_sampling, complex_.id,
        lambda array: _native.from_face_vectors(complex_._native, array),
    )


def _field_out(complex_, coefficients, as_vectors):
    return field_in_form(coefficients, as_vectors, lambda c: _native.to_face_vectors(complex_._native, c))


def basis(mesh, k, discretization=None, boundary="tangential", seed=0, progress=None, beta=None, *, intrinsic_delaunay=False):
    """The ``k`` eigenfields of lowest eigenvalue of the Hodge-Laplacian (``tvf basis -k K``).

    ``mesh``: a :class:`Mesh` (with ``discretization``, ``boundary``, ``beta``,
    ``intrinsic_delaunay`` as for :class:`Complex`) or a :class:`Complex`. ``k >= n1`` gives the complete basis (dense solvers: small meshes only). ``seed`` fixes the
    random start vectors (equal seeds, equal results). ``progress``: optional callable
    ``progress(stage, done, wanted)`` called from the computation (which runs without the GIL).

    Harmonic fields come from projecting random fields, the others from the two scalar
    eigenproblems ``(d0^T M1 d0, M0)`` and ``(d1 M1^-1 d1^T, M2^-1)`` solved by tvf's
    spectrum-slicing eigensolver; the selection is provably the lowest ``k`` (inertia counts).
    Sparse masses work as diagonal ones: a sparse ``M0`` or ``M2^-1`` is the pencil's mass
    matrix, and with a sparse ``M1`` the co-exact stiffness ``d1 M1^-1 d1^T`` (dense) is never
    formed (its shifts factor ``d1^T M2 d1 - s M1`` on the edges where ``M2^-1`` is diagonal, the
    sparse saddle matrix ``[[-M1, d1^T], [d1, -s M2^-1]]`` otherwise). Signs of eigenfields are
    arbitrary; eigenfields of a repeated eigenvalue span its
    eigenspace in an arbitrary orthonormal basis. Returns a :class:`Basis`."""
    complex_ = as_complex(mesh, discretization, boundary, beta, intrinsic_delaunay)
    k = integer(k, "k")
    if k < 0:
        raise TvfError(f"-k {k}: ask for at least one eigenfield")
    raw = _native.basis(complex_._native, k, integer(seed, "seed"), progress)
    return Basis._of_native(raw)


def decompose(mesh, field, discretization=None, boundary="tangential", beta=None, *, intrinsic_delaunay=False):
    """The Hodge decomposition ``v = d0 f - M1^-1 d1^T g + h`` (``tvf decompose``).

    ``field``: ``(F, 3)`` face vectors (projected onto the face planes) or ``(n1,)``
    coefficients. Returns a dict with ``integrable`` (curl-free), ``cointegrable``
    (divergence-free; also under its earlier key ``co_integrable``), ``harmonic`` — in the form the field was given — and the ``potential``
    ``f`` (``n0``) and ``co_potential`` ``g`` (``n2``), each with zero mean per component. The
    three parts are ``M1``-orthogonal and sum to the (projected) field. ``beta``: polygon-dec's
    stabilisation, and ``intrinsic_delaunay``, as for :class:`Complex`."""
    complex_ = as_complex(mesh, discretization, boundary, beta, intrinsic_delaunay)
    values, as_vectors = _field_in(complex_, field)
    parts = _native.decompose(complex_._native, values)
    out = {name: _field_out(complex_, parts[name], as_vectors) for name in ("integrable", "cointegrable", "harmonic")}
    out["co_integrable"] = out["cointegrable"]
    out["potential"] = np.asarray(parts["potential"])
    out["co_potential"] = np.asarray(parts["co_potential"])
    return out


def coefficients(mesh, field, basis, boundary="tangential"):
    """Fourier coefficients ``c = U^T M1 v`` of a field in ``basis`` (``tvf coefficients``).

    ``field``: ``(F, 3)`` or ``(n1,)``. Returns ``(c, relative_rest)``: ``c`` is ``(k,)`` in the
    order of ``basis.eigenvalues``; ``relative_rest = |v - U c| / |v|`` (``M1`` norms) is the
    part the basis does not represent. ``basis``: a :class:`Basis`, or a :class:`BasisFile`
    (read in blocks: :meth:`BasisFile.coefficients`)."""
    if isinstance(basis, BasisFile):
        return basis.coefficients(mesh, field)
    complex_ = _complex_of(mesh, None, boundary, basis)
    values, _ = _field_in(complex_, field)
    c, rest = _native.coefficients(complex_._native, basis._parts(), values)
    return np.asarray(c), rest


def filter(mesh, field, basis, integrable="identity", cointegrable="identity", harmonic_gain=1.0, rest_gain=1.0, boundary="tangential"):
    """A spectral filter (``tvf filter``): each coefficient scaled by a gain of its frequency.

    ``integrable``, ``cointegrable``: the responses of the two families, as the command line's
    specs: ``identity``, ``lowpass:t=T`` (``exp(-T l)``), ``highpass:t=T``
    (``2 - exp(-T l)``), ``bandpass:lo=A,hi=B`` (frequencies ``sqrt(l)`` in ``[A, B]``),
    ``cutoff:f=F``, ``curve:f1=g1,f2=g2,...``. ``harmonic_gain`` scales the harmonic part,
    ``rest_gain`` the part outside the basis. Returns ``(filtered_field,
    filtered_coefficients)``, the field in the form it was given. ``basis``: a :class:`Basis`,
    or a :class:`BasisFile` (read in blocks: :meth:`BasisFile.filter`)."""
    if isinstance(basis, BasisFile):
        return basis.filter(mesh, field, integrable, cointegrable, harmonic_gain, rest_gain)
    complex_ = _complex_of(mesh, None, boundary, basis)
    values, as_vectors = _field_in(complex_, field)
    out, c = _native.filter(
        complex_._native, basis._parts(), values, str(integrable), str(cointegrable), float(harmonic_gain), float(rest_gain)
    )
    return _field_out(complex_, out, as_vectors), np.asarray(c)


def compress(mesh, fields, basis, pairs, bits=None, boundary="tangential"):
    """Compresses fields by truncating their Fourier series (``tvf compress``): the lowest
    ``pairs`` integrable and co-integrable coefficients plus the harmonic ones, stored as
    64-bit floats (``bits=None``) or quantised to ``bits`` bits (2-32) and range-coded.

    ``fields``: one field ``(F, 3)`` / ``(n1,)`` or a sequence of them. Returns the bytes of a
    ``.tvfc`` file (stamped with the mesh fingerprint and the basis id), readable by
    :func:`decompress` and ``tvf decompress`` (with the same basis). ``basis``: a
    :class:`Basis`, or a :class:`BasisFile` (read in blocks: :meth:`BasisFile.compress`)."""
    if isinstance(basis, BasisFile):
        return basis.compress(mesh, fields, pairs, bits)
    complex_ = _complex_of(mesh, None, boundary, basis)
    rows = field_rows(fields, complex_.dimensions[1], len(complex_.mesh.faces), complex_.has_sampling, lambda f: _field_in(complex_, f)[0])
    return bytes(_native.compress(complex_._native, basis._parts(), rows, int(pairs), None if bits is None else int(bits)))


def decompress(mesh, data, basis, as_vectors=True, boundary="tangential"):
    """The fields of compressed bytes (from :func:`compress` or a ``.tvfc`` file), checked
    against the mesh and the basis. Returns ``(frames, F, 3)`` face vectors (``as_vectors``,
    with sampling) or ``(frames, n1)`` coefficients. ``basis``: a :class:`Basis`, or a
    :class:`BasisFile` (read in blocks: :meth:`BasisFile.decompress`)."""
    if isinstance(basis, BasisFile):
        return basis.decompress(mesh, data, as_vectors)
    complex_ = _complex_of(mesh, None, boundary, basis)
    rows = _native.decompress(complex_._native, basis._parts(), bytes(data))
    return rows_in_form(rows, as_vectors, complex_.has_sampling, len(complex_.mesh.faces), lambda r: _field_out(complex_, r, True))
