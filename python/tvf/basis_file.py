"""A basis file used where it lies: :class:`BasisFile` reads a ``.tvfb`` written by ``tvf basis``
a block of stored columns at a time, as ``tvf filter --basis FILE`` does, so that a basis larger
than memory can project, filter and synthesise fields."""

import os

import numpy as np

from . import _native
from ._arrays import float_array, integer
from ._fields import field_coefficients, field_in_form, field_rows, rows_in_form
from ._native import TvfError
from .complex import Complex
from .mesh import Mesh

# The command line's variable for the block size (bytes), and its default (64 MiB).
BLOCK_BYTES_VARIABLE = "TVF_BASIS_BLOCK_BYTES"
DEFAULT_BLOCK_BYTES = 64 << 20


class BasisFile:
    """A Fourier basis in a ``.tvfb`` file (``tvf basis MESH -k K -o FILE``), read in blocks.

    ``BasisFile(path, block_bytes=None)`` reads the file's header, eigenvalues and families only
    (a few kilobytes, whatever the basis's size) and checks the file's size against its header.
    The first use on a mesh checks the whole file as the command line's ``--basis`` does — the
    mesh's fingerprint, the discretization's matrices (the file carries a hash of the five
    matrices and the fixed nodes), the payload's checksum and every stored value, read through
    once in blocks — and every use reads the stored eigenfunctions (potentials, co-potentials,
    harmonic fields) a block at a time: memory holds one block (at most ``block_bytes``; default
    ``$TVF_BASIS_BLOCK_BYTES``, else 64 MiB; at least one stored column) and a few fields,
    never the ``n1 x k`` basis. A corrupt, truncated or mismatched file raises
    :class:`tvf.TvfError` naming the file and the problem.

    Metadata (no field read): ``path``, ``k`` (``len(f)``), ``eigenvalues`` (``(k,)``,
    ascending), ``families`` (``(k,)`` str array), ``counts`` (fields per family),
    ``discretization`` (the complex id), ``mesh_fingerprint`` (16 hex digits, as
    ``Mesh.fingerprint``), ``face_count``, ``field_dimension`` (``n1``), ``potential_dimension``
    and ``co_potential_dimension`` (``n0``, ``n2``), ``matrix_hash`` (hex per matrix),
    ``version``, ``layout``, ``file_bytes``; :meth:`eigenvalues_of` per family.

    Products, each a pass over the file (``mesh``: the :class:`Mesh` the basis was computed on,
    or its :class:`Complex`; another mesh is refused): :meth:`coefficients`, :meth:`filter`,
    :meth:`synthesize`, :meth:`fields` (some basis fields), :meth:`compress`, :meth:`decompress`,
    :meth:`basis_id`.
    :meth:`to_basis` loads the whole basis into memory (a :class:`tvf.Basis`, ``n1 x k`` and
    ``F x 3 x k`` arrays). :func:`tvf.coefficients`, :func:`tvf.filter`, :func:`tvf.compress` and
    :func:`tvf.decompress` take a ``BasisFile``
    wherever they take a ``Basis``, and :func:`tvf.spline` and :func:`tvf.design` (reduced) take
    it as ``basis=`` (only the rows of the basis the constraints touch are read).

    A ``BasisFile`` pickles as its path and metadata (the file is checked again where it is
    next used). The products run without the GIL. Each takes ``progress=None``, an optional
    callable ``progress(stage, done, wanted)`` called on the calling thread at the start of every
    pass over the file (``done`` 0) and after each block of it (``done == wanted`` after the
    last): ``stage`` is the pass — ``checking`` (the check when a mesh first uses the file),
    ``projecting``, ``synthesising``, ``fields`` (every field formed once: the basis id) or
    ``rows`` (the rows of the basis a spline's constraints touch) — and ``done``, ``wanted`` are
    bytes of the file (the stored columns the pass covers; for ``checking``, the payload). Ctrl+C
    is noticed at every block: ``KeyboardInterrupt`` is raised promptly, mid-pass, and so is any
    exception the ``progress`` callable raises (the pass stops there; the ``BasisFile`` stays
    usable). A product made of several passes (:meth:`filter`: a projection and syntheses)
    reports each.
    """

    def __init__(self, path, block_bytes=None):
        self.path = os.fspath(path)
        summary = _native.basis_file_summary(self.path)
        self.version = summary["version"]
        self.layout = summary["layout"]
        self.discretization = summary["discretization"]
        self.mesh_fingerprint = summary["mesh_fingerprint"]
        self.face_count = summary["face_count"]
        self.field_dimension = summary["field_dimension"]
        self.potential_dimension = summary["potential_dimension"]
        self.co_potential_dimension = summary["co_potential_dimension"]
        self.eigenvalues = np.asarray(summary["eigenvalues"])
        self.families = np.array(summary["families"], dtype=str)
        self.counts = dict(summary["counts"])
        self.matrix_hash = summary["matrix_hash"]
        self.file_bytes = summary["file_bytes"]
        self.block_bytes = _block_bytes(block_bytes)
        self._opened = None

    @property
    def k(self):
        """Number of basis fields."""
        return len(self.eigenvalues)

    def __len__(self):
        return self.k

    def __getstate__(self):
        # Pickled as its path and metadata (e.g. to send it to Dask workers that see the same
        # file): the open file is not carried, it is checked again where it is next used.
        state = dict(self.__dict__)
        state["_opened"] = None
        return state

    def __repr__(self):
        return (
            f"BasisFile({self.path!r}: {self.k} fields of '{self.discretization}' on {self.face_count} faces, "
            f"{self.file_bytes} bytes, blocks of {self.block_bytes} bytes)"
        )

    def eigenvalues_of(self, family):
        """The eigenvalues of one family (``harmonic``, ``integrable`` or ``cointegrable``),
        ascending."""
        if family not in ("harmonic", "integrable", "cointegrable"):
            raise TvfError(f"'{family}' is not a family: harmonic, integrable or cointegrable")
        return self.eigenvalues[self.families == family]

    def coefficients(self, mesh, field, progress=None):
        """``(c, relative_rest)`` as :func:`tvf.coefficients`: ``c = U^T M1 v`` (``(k,)``) of
        ``field`` (``(F, 3)`` face vectors or ``(n1,)`` coefficients) and
        ``|v - U c| / |v|`` (``M1`` norms); the numbers of ``tvf coefficients MESH FIELD
        --basis FILE --json``. ``progress``: see the class."""
        blocks = self._blocks(mesh, progress)
        values, _ = _field_in(blocks, field)
        c, rest = blocks.coefficients(values, progress)
        return np.asarray(c), rest

    def filter(self, mesh, field, integrable="identity", cointegrable="identity", harmonic_gain=1.0, rest_gain=1.0, progress=None):
        """A spectral filter, as :func:`tvf.filter` (the same response specs: ``identity``,
        ``lowpass:t=T``, ``highpass:t=T``, ``bandpass:lo=A,hi=B``, ``cutoff:f=F``,
        ``curve:F,G;F,G;...``) and ``tvf filter --basis FILE``. ``rest_gain=None`` takes the
        command line's default for ``--rest`` (the filters' gain at the basis's highest
        frequency); ``1.0``, the default here as in :func:`tvf.filter`, keeps the part outside
        the basis. Returns ``(filtered_field, filtered_coefficients)``, the field in the form
        it was given. ``progress``: see the class."""
        blocks = self._blocks(mesh, progress)
        values, as_vectors = _field_in(blocks, field)
        out, c, _ = blocks.filter(
            values, str(integrable), str(cointegrable), float(harmonic_gain), None if rest_gain is None else float(rest_gain), progress
        )
        return _field_out(blocks, out, as_vectors), np.asarray(c)

    def synthesize(self, mesh, coefficients, as_vectors=True, progress=None):
        """The field ``U c`` of coefficients ``c`` (``(k,)``), or the fields of the rows of a
        ``(m, k)`` array, all in one pass over the file: ``(F, 3)`` face vectors (``(m, F,
        3)``) with ``as_vectors`` on a complex with sampling, else ``(n1,)`` (``(m, n1)``)
        coefficients. ``progress``: see the class."""
        blocks = self._blocks(mesh, progress)
        array = float_array(coefficients, "coefficients")
        if array.ndim not in (1, 2):
            raise TvfError(f"coefficients: expected ({self.k},) or (m, {self.k}), got shape {array.shape}")
        rows = np.asarray(blocks.synthesize(np.ascontiguousarray(np.atleast_2d(array)), progress))
        if as_vectors and blocks.has_sampling:
            fields = [np.asarray(blocks.face_vectors_of_field(r)) for r in rows]
            rows = np.stack(fields) if fields else np.zeros((0, self.face_count, 3))
        return rows[0] if array.ndim == 1 else rows

    def fields(self, mesh, indices, progress=None):
        """Basis fields ``indices`` (basis order) sampled at the face centroids: ``(F, 3,
        len(indices))``, formed from the file in one pass (``to_basis().fields[..., indices]``
        without loading the rest; reported as ``synthesising``). ``progress``: see the
        class."""
        blocks = self._blocks(mesh, progress)
        chosen = [integer(i, "index") for i in np.atleast_1d(indices)]
        if any(i < 0 for i in chosen):
            raise TvfError(f"basis field {min(chosen)}: indices are ≥ 0")
        return np.asarray(blocks.face_fields(chosen, progress))

    def compress(self, mesh, fields, pairs, bits=None, progress=None):
        """The bytes of a ``.tvfc`` file of ``fields`` (one ``(F, 3)`` / ``(n1,)`` field or a
        sequence), as :func:`tvf.compress` and ``tvf compress MESH FIELD --basis FILE`` write
        them: the lowest ``pairs`` pairs plus the harmonic fields, 64-bit (``bits=None``) or
        quantised to ``bits`` bits. Read in blocks, except for a basis with a non-diagonal
        ``M1`` whose co-potentials do not fit one block: loaded whole then, as the command line
        does, so that the basis id the file carries is the loaded basis's (and ``progress``
        then hears of nothing but the check). In blocks, ``progress`` (see the class) hears of
        the pass ``fields`` (the basis id), then of a projection per field, the fields taken in
        turn."""
        blocks = self._blocks(mesh, progress)
        rows = field_rows(fields, blocks.dimensions[1], self.face_count, blocks.has_sampling, lambda f: _field_in(blocks, f)[0])
        return bytes(blocks.compress(rows, integer(pairs, "pairs"), None if bits is None else integer(bits, "bits"), progress))

    def decompress(self, mesh, data, as_vectors=True, progress=None):
        """The fields of ``.tvfc`` bytes compressed in this basis (by :meth:`compress`,
        :func:`tvf.compress` with the loaded basis, or ``tvf compress``), checked against the
        mesh and the basis id: ``(frames, F, 3)`` face vectors (``as_vectors``, with sampling)
        or ``(frames, n1)`` coefficients. Read in blocks as :meth:`compress` (``progress``: the
        passes ``fields``, then ``synthesising`` per group of 16 frames)."""
        blocks = self._blocks(mesh, progress)
        rows = blocks.decompress(bytes(data), progress)
        return rows_in_form(rows, as_vectors, blocks.has_sampling, self.face_count, blocks.face_vectors_of_field)

    def basis_id(self, mesh, progress=None):
        """The basis id (16 hex digits) that :func:`tvf.compress` and ``tvf compress`` stamp
        compressed files with, every field formed once from the file (the pass ``fields``;
        ``progress``: see the class)."""
        return self._blocks(mesh, progress).basis_id(progress)

    def to_basis(self, mesh, progress=None):
        """The whole basis **in memory**, a :class:`tvf.Basis` (``coefficients`` ``n1 x k``,
        ``fields`` ``F x 3 x k``: ``8 (n1 + 3F) k`` bytes), read and checked as the command
        line loads a basis file (``progress`` hears of the ``checking`` pass only, when a
        mesh first uses the file; the whole load is not reported)."""
        from .spectral import Basis

        return Basis._of_native(self._blocks(mesh, progress).load())

    def _blocks(self, mesh, progress=None):
        """The file opened (checked whole, the pass ``checking`` reported to ``progress``) for
        ``mesh``; kept for the next call on the same mesh."""
        if isinstance(mesh, Complex):
            complex_, mesh = mesh, mesh.mesh
        elif isinstance(mesh, Mesh):
            complex_ = None
        else:
            raise TypeError(f"mesh: expected a tvf.Mesh or tvf.Complex, got {type(mesh).__name__}")
        if self.matrix_hash is None or self.layout != "eigenfunctions":
            raise TvfError(
                f"{self.path}: the basis file was written by an earlier tvf (format version {self.version}, "
                f"{self.layout} layout) and is not read in blocks: compute it again with `tvf basis`"
            )
        if self._opened is None or self._opened[0] != mesh.fingerprint:
            self._opened = None
            blocks = _native.BasisBlocks.open(self.path, mesh._native, self.block_bytes, progress=progress)
            self._opened = (mesh.fingerprint, blocks)
        blocks = self._opened[1]
        if complex_ is not None and complex_.id != blocks.discretization:
            raise TvfError(f"{self.path}: the basis belongs to '{blocks.discretization}', the discretization is '{complex_.id}'")
        return blocks


def _block_bytes(given):
    """The block size: ``given``, else ``$TVF_BASIS_BLOCK_BYTES``, else 64 MiB."""
    if given is not None:
        value = integer(given, "block_bytes")
        if value <= 0:
            raise TvfError(f"block_bytes = {value}: a positive number of bytes, e.g. 67108864")
        return value
    raw = os.environ.get(BLOCK_BYTES_VARIABLE)
    if raw is None:
        return DEFAULT_BLOCK_BYTES
    try:
        value = int(raw.strip())
    except ValueError:
        value = 0
    if value <= 0:
        raise TvfError(f"environment variable {BLOCK_BYTES_VARIABLE} = '{raw}': a positive number of bytes, e.g. 67108864")
    return value


def _field_in(blocks, field, name="field"):
    """``(coefficients, as_vectors)`` of a field of the basis's complex (see
    :func:`field_coefficients`)."""
    n1 = blocks.dimensions[1]
    return field_coefficients(field, name, n1, blocks.has_sampling, blocks.discretization, blocks.field_of_face_vectors)


def _field_out(blocks, coefficients, as_vectors):
    return field_in_form(coefficients, as_vectors, blocks.face_vectors_of_field)
