"""Checks and conversions of the arrays handed to tvf: dtypes, shapes, contiguity, and
``scipy.sparse`` matrices to and from the CSR parts the native module speaks. A sparse
matrix's arrays are checked (:func:`checked_sparse`) before scipy converts it: its conversions
trust them, and a CSR whose ``indptr`` points past its data corrupts the process's memory."""

import numbers

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from ._native import TvfError


def float_array(value, name, ndim=None, columns=None):
    """``value`` as a C-contiguous float64 array; a non-numeric dtype is a TypeError, a wrong
    number of dimensions or columns a TvfError naming ``name``."""
    array = np.asarray(value)
    if array.dtype == object or not (
        np.issubdtype(array.dtype, np.floating) or np.issubdtype(array.dtype, np.integer)
    ):
        raise TypeError(f"{name}: expected a float array, got dtype {array.dtype}")
    if np.issubdtype(array.dtype, np.complexfloating):
        raise TypeError(f"{name}: expected a real float array, got dtype {array.dtype}")
    _check_shape(array, name, ndim, columns)
    return np.ascontiguousarray(array, dtype=np.float64)


def index_array(value, name, ndim=None, columns=None):
    """``value`` as a C-contiguous int64 array; floats (even integral ones) are a TypeError."""
    array = np.asarray(value)
    if array.dtype == bool or not np.issubdtype(array.dtype, np.integer):
        raise TypeError(f"{name}: expected an integer array of vertex indices, got dtype {array.dtype}")
    _check_shape(array, name, ndim, columns)
    if np.issubdtype(array.dtype, np.unsignedinteger) and array.size and array.max() > np.iinfo(np.int64).max:
        raise TvfError(f"{name}: index {array.max()} is out of range")
    return np.ascontiguousarray(array, dtype=np.int64)


def integer(value, name):
    """``value`` as an ``int`` if it is an integer (Python's, numpy's); anything else — ``2.7``,
    ``3.0``, a string — is a TypeError naming ``name`` (``int()`` would silently truncate)."""
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, numbers.Integral):
        raise TypeError(f"{name} must be an integer, got {value!r}")
    return int(value)


def declared_shape(matrix):
    """The shape a matrix argument declares, read without converting it: a ``scipy.sparse``
    matrix's or ``LinearOperator``'s ``shape``, else numpy's shape of the array."""
    if sp.issparse(matrix) or isinstance(matrix, spla.LinearOperator):
        return tuple(int(n) for n in matrix.shape)
    return tuple(int(n) for n in np.shape(matrix))


def checked_sparse(matrix, name):
    """``matrix`` if its arrays are consistent (a CSR/CSC/BSR's ``indptr``, ``indices`` and
    ``data``, a COO's ``row``, ``col`` and ``data``); a TvfError naming ``name`` and the problem
    otherwise. Other formats (DIA, LIL, DOK) are scipy's own structures."""
    if not sp.issparse(matrix):
        return matrix
    try:
        if matrix.format in ("csr", "csc", "bsr"):
            matrix.check_format(full_check=True)
        elif matrix.format == "coo":
            _check_coo(matrix)
    except (ValueError, TypeError, IndexError) as error:
        raise TvfError(f"{name}: not a valid {matrix.format.upper()} matrix: {error}") from None
    return matrix


def _check_coo(matrix):
    rows, cols = matrix.shape
    row, col, data = (np.asarray(a) for a in (matrix.row, matrix.col, matrix.data))
    if not (row.ndim == col.ndim == data.ndim == 1) or not (len(row) == len(col) == len(data)):
        raise ValueError(f"row, col and data have {len(row)}, {len(col)} and {len(data)} entries")
    if len(row) and (row.min() < 0 or row.max() >= rows or col.min() < 0 or col.max() >= cols):
        raise ValueError(f"an entry lies outside the shape {matrix.shape}")


def _check_shape(array, name, ndim, columns):
    if ndim is not None and array.ndim != ndim:
        want = "(n, %d)" % columns if columns is not None else f"{ndim} dimensions"
        raise TvfError(f"{name}: expected shape {want}, got {array.shape}")
    if columns is not None and array.shape[-1] != columns:
        raise TvfError(f"{name}: expected shape (n, {columns}), got {array.shape}")


def csr_parts(matrix, name):
    """A scipy.sparse matrix (or dense 2-D array) as ``(indptr, indices, data, shape)``,
    float64, canonical CSR."""
    if not sp.issparse(matrix):
        matrix = float_array(matrix, name, ndim=2)
    elif not (np.issubdtype(matrix.dtype, np.floating) or np.issubdtype(matrix.dtype, np.integer)):
        raise TypeError(f"{name}: expected a real sparse matrix, got dtype {matrix.dtype}")
    matrix = sp.csr_matrix(checked_sparse(matrix, name), dtype=np.float64, copy=True)
    matrix.sum_duplicates()
    matrix.sort_indices()
    return (
        np.ascontiguousarray(matrix.indptr, dtype=np.int64),
        np.ascontiguousarray(matrix.indices, dtype=np.int64),
        np.ascontiguousarray(matrix.data, dtype=np.float64),
        (int(matrix.shape[0]), int(matrix.shape[1])),
    )


def mass(matrix, name):
    """A mass as the native module takes it: the ``n`` entries of a diagonal (from a vector, or
    a square matrix without off-diagonal entries), or the CSR parts of a sparse matrix (any
    ``scipy.sparse`` format, or a dense 2-D array). Symmetry and positive definiteness are
    checked by the native module."""
    if isinstance(matrix, spla.LinearOperator):
        hint = f": give its inverse ({name}_inverse of tvf.operators) as {name}_inverse" if name == "M2" else ""
        raise TypeError(f"{name}: expected a vector or a sparse matrix, got a LinearOperator (a dense mass){hint}")
    if not sp.issparse(matrix):
        array = float_array(matrix, name)
        if array.ndim == 1:
            return array
        if array.ndim != 2:
            raise TvfError(f"{name}: expected a vector or a matrix, got shape {array.shape}")
        matrix = sp.csr_matrix(array)
    checked_sparse(matrix, name)
    square = matrix.shape[0] == matrix.shape[1]
    coo = sp.coo_matrix(matrix)
    if square and not np.any(coo.data[coo.row != coo.col]):
        return float_array(matrix.diagonal(), name)
    return csr_parts(matrix, name)


def to_csr(parts):
    """``scipy.sparse.csr_matrix`` from the native module's CSR parts."""
    indptr, indices, data, shape = parts
    return sp.csr_matrix((data, indices, indptr), shape=shape)
