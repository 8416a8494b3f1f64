"""The conformance suite's core checks on any complex, or property-based on a builder of
complexes over generated meshes with a shrunk counterexample (:func:`check`); the convergence
study against exact spectra (:func:`convergence`); discretizations side by side on one mesh
(:func:`compare`)."""

from dataclasses import dataclass, field
from typing import List, Optional, Tuple

from . import _native
from ._arrays import integer
from .complex import Complex
from .mesh import Mesh


@dataclass
class CheckReport:
    """What :func:`check` measured: ``outcomes`` is a list of dicts with ``name``, ``status``
    (``passed``, ``failed``, ``skipped`` or ``not applicable``), ``measured``, ``limit`` (the
    largest passing value; for counts the expected count; for lower bounds the least passing
    value), ``comparison`` (``at_most``, ``equals`` for counts, ``at_least`` for lower bounds
    such as an observed order of convergence) and ``detail`` (one line). ``accuracy`` holds the
    accuracy checks of a builder in the same form."""

    complex_id: str
    outcomes: List[dict]
    #: With a builder: the meshes that passed (before the first failure).
    cases_passed: int = 1
    #: With a builder: the shrunk minimal failing mesh ``(V, F)``, or ``None``.
    counterexample: Optional[Tuple] = None
    #: With a builder: every check measured on the counterexample, in the run that failed.
    counterexample_outcomes: List[dict] = field(default_factory=list)
    #: With a builder and a counterexample: whether it failed again when checked once more
    #: (``False``: a non-deterministic failure, e.g. a builder whose result changes from call to
    #: call; still a failure). ``None`` without a counterexample.
    reproduced: Optional[bool] = None
    #: The run's verdict where the native run gives one (a property run); else the outcomes'.
    verdict: Optional[bool] = None
    #: With a builder: the accuracy checks (consistency of linear functions on a flat box and a
    #: curved sphere; convergence of the lowest eigenvalues on regular and jittered spheres,
    #: observed order >= 1.5), run once; empty with ``accuracy=False``.
    accuracy: List[dict] = field(default_factory=list)

    @property
    def passed(self):
        """Whether every check of every case passed: false whenever a case failed, even when
        its counterexample passes on a second look (:attr:`reproduced`)."""
        if self.verdict is not None:
            return self.verdict and not self.failures
        return not self.failures

    @property
    def failures(self):
        """The failed outcomes (on the counterexample, if there is one)."""
        outcomes = self.outcomes + self.counterexample_outcomes + self.accuracy
        return [o for o in outcomes if o["status"] == "failed"]

    def __str__(self):
        lines = [f"conformance of '{self.complex_id}': {'passed' if self.passed else 'FAILED'}"]
        for o in self.outcomes:
            lines.append(f"  {o['status']:<7} {o['name']}: {o['detail']}")
        if self.counterexample is not None:
            V, F = self.counterexample
            lines.append(f"counterexample: {len(V)} vertices, {len(F)} faces")
            if self.reproduced is False:
                lines.append(
                    "  non-deterministic: checked once more, this mesh passed; the failures below "
                    "are from the run that failed"
                )
            for o in self.counterexample_outcomes:
                lines.append(f"  {o['status']:<7} {o['name']}: {o['detail']}")
        if self.accuracy:
            lines.append("accuracy checks:")
            for o in self.accuracy:
                lines.append(f"  {o['status']:<7} {o['name']} = {o['measured']:.3g}: {o['detail']}")
        return "\n".join(lines)


def check(x, cases=64, seed=0, mesh=None, delaunay=False, accuracy=True, open_meshes=False, shrink_steps=512):
    """Runs the core checks of tvf's conformance suite (the same code the Rust test suite
    asserts with):

    ``d1 d0 = 0``; integrable fields orthogonal to co-integrable ones; masses positive on used
    nodes, ``sum(M0) = area``; the harmonic dimension the complex reports; ``S``, ``B`` and both
    stiffness matrices symmetric; the Hodge decomposition (orthogonal parts summing back,
    curl-free / divergence-free parts, known parts recovered); and for small complexes
    (``n1 <= 1600``; Lemma 1: ``n1 <= 1000``, otherwise reported as skipped) positive
    semi-definiteness, ``dim ker L``, the spectrum of ``L`` as the union of the two scalar
    spectra, and Lemma 1's eigenfields.

    ``x`` is either

    - a :class:`Complex` (a catalog entry or your own, :meth:`Complex.from_matrices`): checked on
      its mesh (``cases``, ``seed``, ``mesh`` are not used); or
    - a builder: a callable ``(V, F) -> dict(d0=, d1=, M0=, M1=, M2=, sampling=)`` (the
      arguments of :meth:`Complex.from_matrices`; ``M2_inverse=`` instead of ``M2=``, ``id=``
      optional; scipy.sparse or numpy). With ``mesh=(V, F)`` it is checked on that mesh;
      otherwise on ``cases`` closed meshes generated from ``seed`` (genus 0–5, several
      components, jittered, slivers, rigidly moved; only Delaunay ones with ``delaunay=True``);
      with ``open_meshes=True`` also meshes with boundary (disks, cylinders, hemispheres,
      surfaces with holes), for a builder that returns ``fixed_nodes=`` and
      ``boundary_condition=`` (see :meth:`Complex.from_matrices`) where the mesh has a boundary.
      When a case fails, the mesh description is shrunk (fewer faces, lower genus, no jitter;
      at most ``shrink_steps`` steps, each a run of the core checks on a smaller mesh: ``0``
      keeps the first failing mesh) and the report's ``counterexample`` is the minimal failing
      ``(V, F)`` with its checks in
      ``counterexample_outcomes`` (as measured in the run that failed); ``outcomes`` then hold
      each check's worst case over the passing meshes. A failure that does not come back when
      the counterexample is checked once more (a builder whose result changes from call to
      call) is still a failure: ``passed`` is false and ``reproduced`` is ``False``. A builder
      that raises an ``Exception`` fails the check named ``construction``;
      ``KeyboardInterrupt`` (Ctrl+C, also between and inside the checks) and ``SystemExit``
      stop the run and are raised.

    Accuracy: a :class:`Complex` also gets the consistency checks of linear functions on its
    own mesh (the gradient sampled exactly; the energy ``phi' S phi`` of a linear ``phi`` equal
    to the piecewise flat surface's). A builder also gets, once and unless ``accuracy=False``,
    the accuracy checks in :attr:`CheckReport.accuracy`: on a closed box of six flat jittered
    patches and on a jittered sphere, the gradient of a linear function, both patch tests (the
    stiffness of each nodal space annihilates linear functions inside flat faces) and the energy
    of a linear function; and the relative error of the lowest eigenvalues of both families on
    icospheres of levels 1-3, regular and jittered, with an observed order of at least 1.5, and
    with ``open_meshes=True`` on ring hemispheres too (without it: not applicable). Checks a complex cannot run (no
    sampling, values on faces) are ``not applicable`` with the reason.

    ``cases``, ``seed`` and ``shrink_steps`` are integers (``cases=2.7`` is a TypeError). Returns a
    :class:`CheckReport`; nothing raises for a failed check."""
    if isinstance(x, Complex):
        return CheckReport(x.id, [dict(o) for o in _native.check(x._native)])
    if not callable(x):
        raise TypeError(f"expected a tvf.Complex or a builder (V, F) -> dict, got {type(x).__name__}")
    cases, seed = integer(cases, "cases"), integer(seed, "seed")
    shrink_steps = integer(shrink_steps, "shrink_steps")
    if cases < 1:
        raise ValueError(f"cases must be at least 1, got {cases}")
    if seed < 0:
        raise ValueError(f"seed must be non-negative, got {seed}")
    if not 0 <= shrink_steps < 2**32:
        raise ValueError(f"shrink_steps must be in 0..2**32, got {shrink_steps}")
    native_mesh = None if mesh is None else Mesh(*mesh, label="mesh")._native

    result = _native.check_builder(
        _native_builder(x), cases, seed, native_mesh, bool(delaunay), bool(accuracy), bool(open_meshes),
        shrink_steps,
    )
    return CheckReport(
        getattr(x, "__name__", "builder"),
        [dict(o) for o in result["outcomes"]],
        cases_passed=result["cases_passed"],
        counterexample=result["counterexample"],
        counterexample_outcomes=[dict(o) for o in result["counterexample_outcomes"]],
        reproduced=result["reproduced"],
        verdict=bool(result["passed"]),
        accuracy=[dict(o) for o in result["accuracy"]],
    )


def convergence(discretizations, surfaces=("sphere", "hemisphere-tangential", "hemisphere-normal"),
                levels=(1, 2, 3, 4), eigenvalues=24):
    """The convergence study of ``tvf convergence``: each discretization on refinements of
    surfaces with exact spectra, the largest relative error of the lowest ``eigenvalues``
    eigenvalues of each family per level, the observed orders and the basis times.

    ``discretizations`` is a list whose items are catalog ids (``"conforming-barycentric"``),
    builders — callables ``(V, F) -> dict(d0=, d1=, M0=, M1=, M2=, sampling=)`` as for
    :func:`check`, named by their ``__name__`` — or ``(name, id_or_builder)`` pairs. Builders run
    on closed meshes only (:meth:`Complex.from_matrices`): use ``surfaces=("sphere",)``.
    ``surfaces`` are ``sphere`` (icospheres, ``20·4^level`` faces), ``hemisphere-tangential``
    and ``hemisphere-normal`` (ring meshes with ``2·2^level`` rings made Delaunay by edge flips).

    Returns a dict with ``rows`` (dicts: ``discretization``, ``surface``, ``boundary``,
    ``level``, ``faces``, ``h`` (mean edge length), ``integrable_error``,
    ``cointegrable_error``, ``seconds``) and ``orders`` (dicts: ``discretization``,
    ``surface``, ``boundary``, ``family`` (``integrable`` or ``cointegrable``), ``order``: the
    least-squares slope of log error against log h, the coarsest level dropped when there are
    three or more; ``None`` where it cannot be fitted)."""
    candidates = []
    for item in discretizations:
        name, source = item if isinstance(item, tuple) else (None, item)
        if isinstance(source, str):
            candidates.append((name or source, source))
        elif callable(source):
            candidates.append((name or getattr(source, "__name__", "builder"), _native_builder(source)))
        else:
            raise TypeError(f"expected a catalog id or a builder (V, F) -> dict, got {type(source).__name__}")
    names = [name for name, _ in candidates]
    if len(set(names)) != len(names):
        raise ValueError(f"discretization names must differ: {names}")
    levels = [integer(level, "a level") for level in levels]
    if not levels or min(levels) < 0 or sorted(levels) != levels:
        raise ValueError(f"levels must be ascending non-negative integers, got {levels}")
    eigenvalues = integer(eigenvalues, "eigenvalues")
    if eigenvalues < 1:
        raise ValueError(f"eigenvalues must be at least 1, got {eigenvalues}")
    return _native.convergence(candidates, [str(s) for s in surfaces], levels, eigenvalues)


def _native_builder(builder):
    """A builder returning a dict of matrices as one returning the native complex."""

    def build(V, F):
        parts = dict(builder(V, F))
        parts.setdefault("id", getattr(builder, "__name__", "builder"))
        return Complex.from_matrices(Mesh(V, F, label="generated mesh"), **parts)._native

    return build


def compare(entries, k, mesh=None, reference=None, cluster_tolerance=0.01):
    """Discretizations side by side on one mesh, as ``tvf compare`` does: each entry's basis of
    the ``k`` lowest fields (timed, with its peak memory), its eigenvalues per family against the
    reference's, and the principal angles between their eigenspaces (clusters of near-equal
    eigenvalues compared as subspaces; fields compared as one tangent vector per face at its
    centroid, area-weighted; every entry must sample).

    ``entries`` (at least two) are :class:`Complex` objects, catalog ids, or builders
    ``(V, F) -> dict`` as for :func:`check`; ids and builders need ``mesh`` (a :class:`Mesh`),
    complexes must all be on one mesh. ``reference`` is the entry the others are compared with
    (its position, or its id; default the first); ``cluster_tolerance`` the largest relative gap
    of consecutive eigenvalues of one family inside a cluster.

    Returns the dict ``tvf compare --json`` prints: ``reference`` (id), ``entries`` (per entry
    ``discretization``, ``n0``/``n1``/``n2``, ``mass_nonzeros``, ``assembly_seconds`` (building
    the complex here; ``None`` for a complex passed in built), ``basis_seconds``, their ratios to
    the reference's, ``peak_bytes`` (resident bytes the basis computation added at its peak;
    ``None`` where not measurable), ``harmonic``/``integrable``/``cointegrable`` counts,
    ``eigenvalues``, ``relative_difference`` ``|la - lb| / max(la, lb)`` index by index,
    ``families`` (per family its eigenvalues and relative differences), ``principal_angles``
    (radians, every cluster's in order), ``clusters`` (family, positions, eigenvalues, gap to the
    next, angles), ``in_reference_span`` and ``reference_in_span`` (share of each field's squared
    norm in the other's span))."""
    import json
    import time

    k = integer(k, "k")
    complexes, seconds = [], []
    for entry in entries:
        if isinstance(entry, Complex):
            complexes.append(entry)
            seconds.append(float("nan"))
            continue
        if mesh is None:
            raise TypeError("compare: a catalog id or a builder needs mesh=tvf.Mesh(V, F)")
        start = time.perf_counter()
        if isinstance(entry, str):
            complexes.append(Complex(mesh, entry))
        elif callable(entry):
            parts = dict(entry(mesh.positions, mesh.faces))
            parts.setdefault("id", getattr(entry, "__name__", "builder"))
            complexes.append(Complex.from_matrices(mesh, **parts))
        else:
            raise TypeError(f"compare: expected a tvf.Complex, a catalog id or a builder, got {type(entry).__name__}")
        seconds.append(time.perf_counter() - start)
    ids = [c.id for c in complexes]
    if reference is None:
        position = 0
    elif isinstance(reference, str):
        if reference not in ids:
            raise ValueError(f"compare: reference {reference!r} is not one of the entries {ids}")
        position = ids.index(reference)
    else:
        position = integer(reference, "reference")
        if not 0 <= position < len(complexes):
            raise ValueError(f"compare: reference {position} is not a position among {len(complexes)} entries")
    text = _native.compare([c._native for c in complexes], k, position, float(cluster_tolerance), seconds)
    return json.loads(text)
