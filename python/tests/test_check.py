"""tvf.check with a builder (V, F) -> matrices: a correct builder passes on generated meshes and
on a given mesh; a builder broken only above 100 faces is caught and its failure shrunk to a
small failing mesh; a builder that raises fails the construction check, one that is wrong
only sometimes fails too; Ctrl+C and SystemExit propagate; cases and seed are integers."""

import os
import signal

import numpy as np
import pytest
import scipy.sparse as sp

import tvf
from reference import p1_cr_complex, torus


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
    report = tvf.check(wrong_every_second_call(), cases=16, seed=2)
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

    report = tvf.check(first_call_wrong, cases=4, seed=3)
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

for name, build in HOSTILE.items():
    try:
        report = tvf.check(build, cases=4, seed=5)
        failed = sorted({o["name"] for o in report.failures})
        print(f"{name}|passed={report.passed}|{','.join(failed)}")
    except BaseException as error:
        print(f"{name}|raised={type(error).__name__}|")
'''


def test_hostile_builders_never_pass_and_never_crash():
    """The sweep of hostile builders (wrong types, missing matrices, declared shapes of 2e8,
    broken CSR arrays, NaN, negative and denormal masses, wrong matrices, matrices of another
    mesh, non-determinism, exceptions): each run, in a separate interpreter (an abort there
    cannot hide), ends in a failed report naming a check — or, for KeyboardInterrupt and
    SystemExit, in that exception — never in passed=True, a crash or a hang."""
    import pathlib
    import subprocess
    import sys

    here = pathlib.Path(__file__).parent
    result = subprocess.run([sys.executable, "-c", HOSTILE_BUILDERS], capture_output=True, text=True, cwd=here, timeout=900)
    assert result.returncode == 0, result.stderr[-3000:]
    assert "panicked" not in result.stderr and "Traceback" not in result.stderr, result.stderr[-3000:]
    lines = [line.split("|") for line in result.stdout.splitlines()]
    assert len(lines) == 16, result.stdout
    for name, verdict, failed in lines:
        if name.startswith("raises KeyboardInterrupt"):
            assert verdict == "raised=KeyboardInterrupt", (name, verdict)
        elif name.startswith("raises SystemExit"):
            assert verdict == "raised=SystemExit", (name, verdict)
        else:
            assert verdict == "passed=False" and failed, (name, verdict, failed)
    print(f"builder sweep: {len(lines)} hostile builders, none passed, none crashed")
