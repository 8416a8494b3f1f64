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
