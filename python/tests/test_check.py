"""tvf.check with a builder (V, F) -> matrices: a correct builder passes on generated meshes and
on a given mesh, and the accuracy checks; a DEC star inverted by mistake passes every structural
check and fails the accuracy checks; a builder broken only above 100 faces is caught and its failure shrunk to a
small failing mesh; a builder that raises fails the construction check, one that is wrong
only sometimes fails too; Ctrl+C and SystemExit propagate; cases and seed are integers."""

import os
import signal

import numpy as np
import pytest
import scipy.sparse as sp

import tvf
from reference import edges, p1_cr_complex, torus, whitney_complex


def builder(V, F):
    ref = p1_cr_complex(V, F)
    return dict(d0=ref["d0"], d1=ref["d1"], M0=ref["M0"], M1=ref["M1"], M2=sp.diags(ref["M2"]), sampling="face-frames")


def broken_above_100_faces(V, F):
    parts = builder(V, F)
    if len(F) > 100:
        M0 = np.array(parts["M0"].diagonal() if sp.issparse(parts["M0"]) else parts["M0"], dtype=float)
        M0[0] *= 2.0  # sum(M0) is no longer the area
        parts["M0"] = M0
    return parts


def test_a_correct_builder_passes_on_generated_meshes():
    report = tvf.check(builder, cases=12, seed=1)
    assert report.passed, str(report)
    accuracy = {o["name"]: o for o in report.accuracy}
    assert accuracy["convergence:jittered sphere:cointegrable"]["status"] == "passed", str(report)
    assert accuracy["consistency:co_laplacian_of_linear:flat box"]["status"] == "passed", str(report)
    assert report.cases_passed == 12
    assert report.counterexample is None
    names = {o["name"] for o in report.outcomes}
    assert {"d1_d0_zero", "spectrum union", "potential_masses_sum_to_area"} <= names
    measured = [o["measured"] for o in report.outcomes if o["name"] == "d1_d0_zero"]
    assert measured and 0.0 <= measured[0] < 1e-10
    comparisons = {o["name"]: o["comparison"] for o in report.outcomes}
    assert comparisons["d1_d0_zero"] == "at_most"
    assert comparisons["kernel dimension"] == "equals"


def test_a_correct_builder_passes_on_a_given_mesh():
    V, F = torus(n=10, m=5)
    report = tvf.check(builder, mesh=(V, F))
    assert report.passed, str(report)
    assert report.counterexample is None


def test_a_builder_broken_above_100_faces_is_caught_and_shrunk():
    report = tvf.check(broken_above_100_faces, cases=32, seed=7)
    assert not report.passed
    assert report.counterexample is not None
    V, F = report.counterexample
    assert V.shape[1] == 3 and F.shape[1] == 3
    # Shrunk to the smallest failing mesh of its shape family: just above the threshold.
    assert 100 < len(F) <= 200, len(F)
    failed = {o["name"] for o in report.failures}
    assert "potential_masses_sum_to_area" in failed, failed
    # The counterexample reproduces the failure on its own.
    again = tvf.check(broken_above_100_faces, mesh=(V, F))
    assert not again.passed


def barycentric_dec(V, F, inverted):
    """DEC with barycentric duals: ``M1`` per edge the barycentric dual length (edge midpoint
    to the barycentres of its faces) over the primal length, or (``inverted``, the bug) primal
    over dual; ``M0`` barycentric vertex areas, ``M2 = 1/area``; Whitney sampling."""
    ref = whitney_complex(V, F)
    E = ref["edges"]
    _, opposite = edges(F)
    area = 1.0 / ref["M2"]
    dual = np.zeros(len(E))
    centres = V[F].mean(axis=1)
    for c in range(3):
        e = opposite[:, c]
        midpoints = 0.5 * (V[E[e, 0]] + V[E[e, 1]])
        np.add.at(dual, e, np.linalg.norm(centres - midpoints, axis=1))
    primal = np.linalg.norm(V[E[:, 1]] - V[E[:, 0]], axis=1)
    M0 = np.bincount(F.ravel(), weights=np.repeat(area / 3, 3), minlength=len(V))
    M1 = primal / dual if inverted else dual / primal
    return dict(d0=ref["d0"], d1=ref["d1"], M0=M0, M1=M1, M2=ref["M2"], sampling="whitney")


def test_an_inverted_star_passes_the_structure_and_fails_the_accuracy_checks():
    """The researcher's bug: ``M1 = primal/dual``. Symmetric, positive, the right kernel on
    every generated mesh; the accuracy checks name the patch test, the energy of a linear
    function and the convergence order (with its table of errors)."""
    inverted = lambda V, F: barycentric_dec(V, F, inverted=True)
    report = tvf.check(inverted, cases=4, seed=1)
    assert report.counterexample is None, str(report)
    assert not report.passed
    failed = {o["name"]: o for o in report.failures}
    for name in (
        "consistency:laplacian_of_linear:flat box",
        "consistency:energy_of_linear:curved sphere",
        "convergence:sphere:integrable",
        "convergence:jittered sphere:integrable",
    ):
        assert name in failed, sorted(failed)
    order = failed["convergence:sphere:integrable"]
    assert order["comparison"] == "at_least" and order["measured"] < 1.0, order
    assert "faces, h" in order["detail"]
    not_applicable = {o["name"] for o in report.accuracy if o["status"] == "not applicable"}
    assert "convergence:hemisphere:integrable" in not_applicable
    assert "convergence:sphere:integrable" in str(report)
    # The same matrices as one complex: the energy of a linear function on its own mesh fails.
    V, F = torus(n=12, m=6)
    complex = tvf.Complex.from_matrices(tvf.Mesh(V, F), **barycentric_dec(V, F, inverted=True))
    single = tvf.check(complex)
    assert "consistency:energy_of_linear:checked mesh" in {o["name"] for o in single.failures}


def p1_cr_with_boundary(V, F):
    """The conforming complex under the tangential condition on a mesh with boundary: the
    Crouzeix-Raviart co-potentials of boundary edges fixed to zero (their rows of ``d1``
    emptied), given as ``fixed_nodes`` as a ``--complex`` folder gives them."""
    parts = builder(V, F)
    E, opposite = edges(F)
    boundary = np.flatnonzero(np.bincount(opposite.ravel(), minlength=len(E)) == 1)
    if len(boundary) == 0:
        return parts
    keep = np.ones(len(E))
    keep[boundary] = 0.0
    parts["d1"] = (sp.diags(keep) @ parts["d1"]).tocsr()
    parts["fixed_nodes"] = dict(co_potentials=boundary.tolist())
    parts["boundary_condition"] = "tangential"
    return parts


def test_a_builder_with_boundary_conditions_passes_on_open_meshes():
    """Python with boundary: the builder gives fixed nodes and the condition; the generated
    meshes include meshes with boundary, and the accuracy checks the hemispheres."""
    report = tvf.check(p1_cr_with_boundary, cases=10, seed=4, open_meshes=True)
    assert report.passed, str(report)
    accuracy = {o["name"]: o for o in report.accuracy}
    hemisphere = accuracy["convergence:jittered hemisphere:cointegrable"]
    assert hemisphere["status"] == "passed" and hemisphere["measured"] >= 1.5, hemisphere
    # Without fixed nodes, matrices on an open mesh are refused: they cannot state its boundary condition.
    n = 6
    x, y = np.meshgrid(np.linspace(0, 1, n + 1), np.linspace(0, 1, n + 1))
    V = np.stack([x.ravel(), y.ravel(), 0.1 * (x * y).ravel()], axis=1)
    index = lambda i, j: i * (n + 1) + j
    F = np.array(
        [[index(i, j), index(i, j + 1), index(i + 1, j + 1)] for i in range(n) for j in range(n)]
        + [[index(i, j), index(i + 1, j + 1), index(i + 1, j)] for i in range(n) for j in range(n)],
        dtype=np.int64,
    )
    parts = builder(V, F)
    with pytest.raises(tvf.TvfError, match="without fixed nodes needs a closed mesh"):
        tvf.Complex.from_matrices(tvf.Mesh(V, F), **parts)
    complex = tvf.Complex.from_matrices(tvf.Mesh(V, F), **p1_cr_with_boundary(V, F))
    assert complex.id.endswith("+tangential"), complex.id
    assert tvf.check(complex).passed


def test_a_builder_that_raises_fails_construction():
    def raising(V, F):
        raise RuntimeError("not on this mesh")

    report = tvf.check(raising, cases=4, seed=0)
    assert not report.passed
    failed = {o["name"]: o["detail"] for o in report.failures}
    assert "construction" in failed and "not on this mesh" in failed["construction"], failed


def wrong_every_second_call():
    """A builder whose M0 is wrong on every second call (a bug that depends on state)."""
    calls = [0]

    def flaky(V, F):
        calls[0] += 1
        parts = builder(V, F)
        if calls[0] % 2 == 0:
            M0 = np.array(parts["M0"].diagonal() if sp.issparse(parts["M0"]) else parts["M0"], dtype=float)
            M0[0] *= 2.0
            parts["M0"] = M0
        return parts

    return flaky


def test_a_failure_that_does_not_reproduce_is_not_a_pass():
    """It once passed with a counterexample whose second look passed."""
    # Two shrinking steps: the verdict is under test, not how far a non-deterministic failure
    # shrinks (each step is a run of the core checks on a mesh of hundreds of faces).
    report = tvf.check(wrong_every_second_call(), cases=16, seed=2, accuracy=False, shrink_steps=2)
    assert not report.passed, str(report)
    assert report.counterexample is not None
    failed = {o["name"] for o in report.failures}
    assert "potential_masses_sum_to_area" in failed, str(report)
    assert report.reproduced in (True, False)
    if report.reproduced is False:
        assert "non-deterministic" in str(report)


def test_a_failure_only_on_the_first_call_is_reported_as_non_deterministic():
    """A builder wrong on its first call only: every later look at the failing mesh passes, so
    shrinking cannot reproduce it. The verdict stays a failure, with that first mesh as the
    counterexample, the numbers of the failing run, and the word that it did not reproduce."""
    calls = [0]

    def first_call_wrong(V, F):
        calls[0] += 1
        parts = builder(V, F)
        if calls[0] == 1:
            M0 = np.array(parts["M0"].diagonal() if sp.issparse(parts["M0"]) else parts["M0"], dtype=float)
            M0[0] *= 2.0
            parts["M0"] = M0
        return parts

    report = tvf.check(first_call_wrong, cases=4, seed=3, accuracy=False)
    assert calls[0] > 1, calls[0]
    assert not report.passed, str(report)
    assert report.reproduced is False, str(report)
    assert report.counterexample is not None
    assert "potential_masses_sum_to_area" in {o["name"] for o in report.failures}, str(report)
    assert "non-deterministic" in str(report), str(report)


def test_interrupts_and_exits_in_a_builder_propagate():
    """Ctrl+C in a builder once became a failed construction check, and the run a pass."""
    for exception in (KeyboardInterrupt, SystemExit):
        def raising(V, F, exception=exception):
            raise exception("stop")

        with pytest.raises(exception):
            tvf.check(raising, cases=8, seed=0)
        with pytest.raises(exception):
            tvf.check(raising, mesh=torus(n=10, m=5))
    # An ordinary exception is a failed construction check, not raised.
    def broken(V, F):
        raise ValueError("my bug")

    report = tvf.check(broken, cases=4, seed=0)
    assert not report.passed
    assert any(o["name"] == "construction" and "my bug" in o["detail"] for o in report.failures)


def test_ctrl_c_during_a_property_run_raises(sigint_raises_keyboard_interrupt):
    """SIGINT while the checks run (without the GIL) stops the run with KeyboardInterrupt; it once
    returned passed=True with the cases done so far."""
    calls = [0]

    def counting(V, F):
        calls[0] += 1
        if calls[0] == 3:
            os.kill(os.getpid(), signal.SIGINT)
        return builder(V, F)

    with pytest.raises(KeyboardInterrupt):
        tvf.check(counting, cases=64, seed=0)
    # The run stopped at the next call into Python: no further mesh was built.
    assert calls[0] <= 4, calls[0]


def test_cases_and_seed_must_be_integers():
    for bad in (2.7, 3.0, "4"):
        with pytest.raises(TypeError, match="cases must be an integer"):
            tvf.check(builder, cases=bad)
    with pytest.raises(TypeError, match="seed must be an integer"):
        tvf.check(builder, cases=2, seed=0.5)
    with pytest.raises(TypeError, match="shrink_steps must be an integer"):
        tvf.check(builder, cases=2, shrink_steps=1.5)
    with pytest.raises(ValueError, match="shrink_steps must be in"):
        tvf.check(builder, cases=2, shrink_steps=-1)


def test_without_shrinking_the_counterexample_is_the_first_failing_mesh():
    """``shrink_steps=0``: the counterexample is the first mesh the builder failed on (the
    first one above 100 faces it was called with), and no smaller mesh is tried after it."""
    sizes = []

    def recording(V, F):
        sizes.append(len(F))
        return broken_above_100_faces(V, F)

    report = tvf.check(recording, cases=32, seed=7, accuracy=False, shrink_steps=0)
    assert not report.passed
    first_failure = next(i for i, n in enumerate(sizes) if n > 100)
    V, F = report.counterexample
    assert len(F) == sizes[first_failure], (len(F), sizes)
    assert all(n == sizes[first_failure] for n in sizes[first_failure:]), sizes


HOSTILE_BUILDERS = r'''
import numpy as np, scipy.sparse as sp, tvf
from test_check import builder

def scaled(name, factor):
    def build(V, F):
        parts = builder(V, F)
        parts[name] = parts[name] * factor
        return parts
    return build

def replaced(name, value):
    def build(V, F):
        parts = builder(V, F)
        parts[name] = value(V, F, parts)
        return parts
    return build

def broken_indptr(V, F, parts):
    m = sp.diags(np.asarray(parts["M1"] if not sp.issparse(parts["M1"]) else parts["M1"].diagonal())).tocsr()
    m.indptr[-1] += 1000
    return m

def with_nan(V, F, parts):
    d0 = parts["d0"].tocsr().copy()
    d0.data[0] = np.nan
    return d0

calls = [0]
def flaky(V, F):
    calls[0] += 1
    parts = builder(V, F)
    if calls[0] % 2 == 0:
        parts["M0"] = np.asarray(parts["M0"], dtype=float) * 1.5
    return parts

def raising(exception):
    def build(V, F):
        raise exception("hostile")
    return build

HOSTILE = {
    "returns None": lambda V, F: None,
    "returns a string": lambda V, F: "d0",
    "misses d1": lambda V, F: {k: v for k, v in builder(V, F).items() if k != "d1"},
    "M1 of shape (2e8, 2e8)": replaced("M1", lambda V, F, p: sp.coo_matrix((np.ones(2), ([0, 1], [0, 1])), shape=(200_000_000, 200_000_000))),
    "d0 of shape (2e8, V)": replaced("d0", lambda V, F, p: sp.coo_matrix((200_000_000, len(V)))),
    "M1 whose indptr points past its data": replaced("M1", broken_indptr),
    "d0 with a NaN": replaced("d0", with_nan),
    "negative M1": scaled("M1", -1.0),
    "denormal M1 (1e-310)": scaled("M1", 1e-310),
    "M0 off by a factor": scaled("M0", 1.5),
    "matrices of another mesh": lambda V, F: builder(*__import__("reference").torus(n=6, m=4)),
    "wrong on every second call": flaky,
    "raises ValueError": raising(ValueError),
    "raises MemoryError": raising(MemoryError),
    "raises KeyboardInterrupt": raising(KeyboardInterrupt),
    "raises SystemExit": raising(SystemExit),
}

import sys
group, groups = int(sys.argv[1]), int(sys.argv[2])
print(f"total|{len(HOSTILE)}|")
for name, build in list(HOSTILE.items())[group::groups]:
    try:
        # Two shrinking steps: the verdict is under test, not the counterexample's size.
        report = tvf.check(build, cases=4, seed=5, shrink_steps=2)
        failed = sorted({o["name"] for o in report.failures})
        print(f"{name}|passed={report.passed}|{','.join(failed)}")
    except BaseException as error:
        print(f"{name}|raised={type(error).__name__}|")
'''


HOSTILE_GROUPS = 4


@pytest.mark.parametrize("group", range(HOSTILE_GROUPS))
def test_hostile_builders_never_pass_and_never_crash(group):
    """The sweep of hostile builders (wrong types, missing matrices, declared shapes of 2e8,
    broken CSR arrays, NaN, negative and denormal masses, wrong matrices, matrices of another
    mesh, non-determinism, exceptions): each run, in a separate interpreter (an abort there
    cannot hide), ends in a failed report naming a check — or, for KeyboardInterrupt and
    SystemExit, in that exception — never in passed=True, a crash or a hang. The 16 builders
    are run in four groups (every fourth, from ``group``), one interpreter each, so that
    pytest's workers share them."""
    import pathlib
    import subprocess
    import sys

    here = pathlib.Path(__file__).parent
    command = [sys.executable, "-c", HOSTILE_BUILDERS, str(group), str(HOSTILE_GROUPS)]
    result = subprocess.run(command, capture_output=True, text=True, cwd=here, timeout=900)
    assert result.returncode == 0, result.stderr[-3000:]
    assert "panicked" not in result.stderr and "Traceback" not in result.stderr, result.stderr[-3000:]
    total, *lines = [line.split("|") for line in result.stdout.splitlines()]
    assert total == ["total", "16", ""], result.stdout
    assert len(lines) == len(range(group, 16, HOSTILE_GROUPS)), result.stdout
    for name, verdict, failed in lines:
        if name.startswith("raises KeyboardInterrupt"):
            assert verdict == "raised=KeyboardInterrupt", (name, verdict)
        elif name.startswith("raises SystemExit"):
            assert verdict == "raised=SystemExit", (name, verdict)
        else:
            assert verdict == "passed=False" and failed, (name, verdict, failed)
    print(f"builder sweep, group {group}: {len(lines)} hostile builders, none passed, none crashed")


def test_compare_takes_complexes_ids_and_builders_alike():
    """tvf.compare: a catalog id, a builder and a complex side by side; the builder of the
    conforming complex agrees with its catalog entry exactly (eigenvalues, and every eigenspace
    cluster at angle 0); the report has the keys of ``tvf compare --json``."""
    V, F = torus(n=12, m=6)
    mesh = tvf.Mesh(V, F)
    dec = tvf.Complex(mesh, "nonconforming-barycentric")
    result = tvf.compare(["conforming-barycentric", builder, dec], k=10, mesh=mesh)
    assert result["reference"] == "conforming-barycentric"
    entries = result["entries"]
    assert [e["discretization"] for e in entries][1:] == ["builder", "nonconforming-barycentric"]
    same = entries[1]
    assert max(same["relative_difference"]) < 1e-9, same
    assert len(same["principal_angles"]) == 10
    # Clusters known complete (a computed eigenvalue above them): the same spaces. The last
    # cluster of a family may be cut by k differently, so it is not asserted.
    complete = [c for c in same["clusters"] if c["gap_above"] is not None]
    assert complete and max(max(c["angles"]) for c in complete) < 1e-6, same["clusters"]
    other = entries[2]
    assert 0 < max(other["relative_difference"]) < 0.2
    assert all(0 <= a <= np.pi / 2 + 1e-12 for a in other["principal_angles"])
    assert [e["harmonic"] for e in entries] == [2, 2, 2]
    assert entries[0]["n1"] == 2 * F.shape[0] and other["n1"] == 2 * F.shape[0]
    assert all(e["basis_seconds"] >= 0 for e in entries)
    assert entries[0]["assembly_seconds"] >= 0 and other["assembly_seconds"] is None
    # Another reference, by id.
    again = tvf.compare(["conforming-barycentric", dec], k=10, mesh=mesh, reference="nonconforming-barycentric")
    assert again["reference"] == "nonconforming-barycentric"
    assert again["entries"][1]["basis_ratio"] == 1.0
    with pytest.raises(ValueError, match="not one of the entries"):
        tvf.compare(["conforming-barycentric", dec], k=4, mesh=mesh, reference="whitney-galerkin")
    with pytest.raises(TypeError, match="needs mesh"):
        tvf.compare(["conforming-barycentric", builder], k=4)
