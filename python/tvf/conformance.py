"""The conformance suite's core checks on any complex: :func:`check`."""

from dataclasses import dataclass
from typing import List

from . import _native
from .complex import Complex


@dataclass
class CheckReport:
    """What :func:`check` measured: ``outcomes`` is a list of dicts with ``name``, ``status``
    (``passed``, ``failed`` or ``skipped``), ``measured``, ``limit`` (the largest passing
    value; for counts the expected count) and ``detail`` (one line)."""

    complex_id: str
    outcomes: List[dict]

    @property
    def passed(self):
        """Whether no check failed."""
        return not self.failures

    @property
    def failures(self):
        """The failed outcomes."""
        return [o for o in self.outcomes if o["status"] == "failed"]

    def __str__(self):
        lines = [f"conformance of '{self.complex_id}': {'passed' if self.passed else 'FAILED'}"]
        for o in self.outcomes:
            lines.append(f"  {o['status']:<7} {o['name']}: {o['detail']}")
        return "\n".join(lines)


def check(complex_):
    """Runs the core checks of tvf's conformance suite (the same code the Rust test suite
    asserts with) on a :class:`Complex` — a catalog entry or your own
    (:meth:`Complex.from_matrices`) — on its mesh:

    ``d1 d0 = 0``; integrable fields orthogonal to co-integrable ones; masses positive on used
    nodes, ``sum(M0) = area``; the harmonic dimension the complex reports; ``S``, ``B`` and both
    stiffness matrices symmetric; the Hodge decomposition (orthogonal parts summing back,
    curl-free / divergence-free parts, known parts recovered); and for small complexes
    (``n1 <= 1600``; Lemma 1: ``n1 <= 1000``, otherwise reported as skipped) positive
    semi-definiteness, ``dim ker L``, the spectrum of ``L`` as the union of the two scalar
    spectra, and Lemma 1's eigenfields. Returns a :class:`CheckReport`; nothing raises for a
    failed check."""
    if not isinstance(complex_, Complex):
        raise TypeError(f"expected a tvf.Complex, got {type(complex_).__name__}")
    return CheckReport(complex_.id, [dict(o) for o in _native.check(complex_._native)])
