"""A field given in either form — ``(F, 3)`` face vectors or ``(n1,)`` coefficients — as the
discretization's coefficients, and back into the form it was given: shared by the functions on
a :class:`tvf.Complex` and those on a :class:`tvf.BasisFile`."""

import numpy as np

from ._arrays import float_array
from ._native import TvfError


def field_coefficients(field, name, n1, has_sampling, discretization, from_face_vectors):
    """``(coefficients, as_vectors)``: an ``(F, 3)`` field converted by ``from_face_vectors``
    (the sampling of ``discretization``, which must have one), an ``(n1,)`` one taken as
    coefficients."""
    array = float_array(field, name)
    if array.ndim == 2 and array.shape[1] == 3:
        if not has_sampling:
            raise TvfError(f"{name}: the discretization '{discretization}' has no sampling; give {n1} coefficients")
        coefficients, _normal = from_face_vectors(array)
        return np.asarray(coefficients), True
    if array.ndim == 1:
        return array, False
    raise TvfError(f"{name}: expected face vectors (F, 3) or {n1} coefficients, got shape {array.shape}")


def field_in_form(coefficients, as_vectors, to_face_vectors):
    """``coefficients`` as face vectors (``to_face_vectors``) if the field was given so."""
    coefficients = np.asarray(coefficients)
    if as_vectors:
        return np.asarray(to_face_vectors(coefficients))
    return coefficients


def field_rows(fields, n1, face_count, has_sampling, coefficients_of):
    """One field (``(F, 3)`` or ``(n1,)``) or a sequence of them as rows of coefficients
    ``(m, n1)``: ``coefficients_of(field)`` converts one (see :func:`field_coefficients`)."""
    array = np.asarray(fields)
    single = array.ndim == 1 or (array.ndim == 2 and array.shape[1] == 3 and has_sampling and array.shape[0] == face_count)
    items = [array] if single else list(array)
    if not items:
        return np.zeros((0, n1))
    return np.ascontiguousarray(np.stack([coefficients_of(f) for f in items]))


def rows_in_form(rows, as_vectors, has_sampling, face_count, to_face_vectors):
    """Rows of coefficients ``(m, n1)`` as face vectors ``(m, F, 3)`` (``as_vectors`` and a
    sampling), else as they are."""
    rows = np.asarray(rows)
    if not (as_vectors and has_sampling):
        return rows
    if not len(rows):
        return np.zeros((0, face_count, 3))
    return np.stack([np.asarray(to_face_vectors(r)) for r in rows])
