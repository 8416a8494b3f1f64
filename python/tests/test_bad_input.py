"""Bad input from Python raises with the message the command line gives for the same input."""

import json
import re

import numpy as np
import pytest

import tvf
from reference import icosphere, torus

TETRA_V = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], float)
TETRA_F = np.array([[0, 2, 1], [0, 1, 3], [1, 2, 3], [2, 0, 3]])


def write_off(path, V, F):
    with open(path, "w") as f:
        f.write(f"OFF\n{len(V)} {len(F)} 0\n")
        for p in V:
            f.write("%r %r %r\n" % tuple(float(x) for x in p))
        for t in F:
            f.write("3 %d %d %d\n" % tuple(int(x) for x in t))


def cli_message(run_tvf, path, *args):
    """The command line's error message with the leading 'error: FILE[:LINE]: ' removed."""
    result = run_tvf(*args, check=False)
    assert result.returncode == 1, result.stderr
    line = result.stderr.strip().splitlines()[-1]
    assert line.startswith("error: "), line
    return re.sub(r"^error: " + re.escape(str(path)) + r"(:\d+)?: ", "", line)


def python_message(callable_):
    with pytest.raises(tvf.TvfError) as info:
        callable_()
    return str(info.value)


@pytest.mark.parametrize(
    "case",
    ["nan_coordinate", "infinite_coordinate", "index_out_of_range", "negative_index", "repeated_vertex", "non_manifold_edge", "non_manifold_vertex", "inconsistent_orientation", "zero_area", "no_faces"],
)
def test_mesh_errors_match_the_command_line(tmp_path, run_tvf, case):
    V, F = TETRA_V.copy(), TETRA_F.copy()
    if case == "nan_coordinate":
        V[2, 0] = np.nan
    elif case == "infinite_coordinate":
        V[3, 2] = np.inf
    elif case == "index_out_of_range":
        F[1, 2] = 8
    elif case == "negative_index":
        F[1, 2] = -1
    elif case == "repeated_vertex":
        F[2] = [1, 2, 2]
    elif case == "non_manifold_edge":
        V = np.vstack([V, [[1, 1, -1], [1, -1, 1]]])
        F = np.vstack([F, [[0, 1, 4], [1, 0, 5]]])
    elif case == "non_manifold_vertex":
        # Two tetrahedra sharing only vertex 0.
        V = np.vstack([V, -V[1:]])
        F = np.vstack([F, [[0, 4, 5], [0, 6, 4], [4, 6, 5], [5, 6, 0]]])
    elif case == "inconsistent_orientation":
        F[0] = F[0][::-1]
    elif case == "zero_area":
        V = np.vstack([V, [[0.5, 0.5, 0.0]]])
        F = np.array([[0, 2, 1], [0, 1, 3], [1, 2, 3], [2, 0, 3], [0, 1, 4]])[:4]
        V[2] = [2.0, 0.0, 0.0]
    elif case == "no_faces":
        F = np.zeros((0, 3), np.int64)
    path = tmp_path / f"{case}.off"
    write_off(path, V, F)
    expected = cli_message(run_tvf, path, "info", path)
    got = python_message(lambda: tvf.Mesh(V, F, label="user mesh"))
    assert got.startswith("user mesh: "), got
    got = got[len("user mesh: "):]
    if case in ("index_out_of_range", "negative_index"):
        # The reader names the file, the array check the face: the rest is the same sentence.
        got = re.sub(r"^face \d+: ", "", got).replace("the mesh has", "the file has")
    assert got == expected
    # Loading the file from Python gives the command line's message itself, file and line.
    loaded = python_message(lambda: tvf.Mesh.load(path))
    assert loaded.startswith(str(path)) and loaded.endswith(expected)


def test_wrong_dtypes_and_shapes_are_refused():
    with pytest.raises(TypeError, match="F: expected an integer array"):
        tvf.Mesh(TETRA_V, TETRA_F.astype(float))
    with pytest.raises(TypeError, match="V: expected a float array"):
        tvf.Mesh(TETRA_V.astype(str), TETRA_F)
    with pytest.raises(TypeError, match="V: expected a float array"):
        tvf.Mesh([[object()] * 3] * 4, TETRA_F)
    with pytest.raises(tvf.TvfError, match=r"V: expected shape \(n, 3\), got \(4, 2\)"):
        tvf.Mesh(TETRA_V[:, :2], TETRA_F)
    # An m x 4 array is four quads: here each repeats its first corner.
    with pytest.raises(tvf.TvfError, match=r"face 0 uses vertex \d+ more than once"):
        tvf.Mesh(TETRA_V, np.hstack([TETRA_F, TETRA_F[:, :1]]))
    with pytest.raises(tvf.TvfError, match=r"F: expected shape \(m, 3\), \(m, k\) or a list of polygons"):
        tvf.Mesh(TETRA_V, TETRA_F.ravel())
    with pytest.raises(TypeError, match="expected a tvf.Mesh"):
        tvf.operators((TETRA_V, TETRA_F))
    mesh = tvf.Mesh(*icosphere(1))
    with pytest.raises(tvf.TvfError, match="unknown discretization|not in the catalog|unknown"):
        tvf.operators(mesh, "cotan-of-my-own")
    with pytest.raises(tvf.TvfError, match="expected face vectors"):
        tvf.decompose(mesh, np.zeros((80, 4)))
    with pytest.raises(tvf.TvfError, match="non-finite"):
        field = np.ones((80, 3))
        field[7, 1] = np.nan
        tvf.decompose(mesh, field)


def test_huge_coordinates_match_the_command_line(tmp_path, run_tvf):
    V = TETRA_V * 1e200
    path = tmp_path / "huge.off"
    write_off(path, V, TETRA_F)
    expected = cli_message(run_tvf, path, "info", path)
    got = python_message(lambda: tvf.Mesh(V, TETRA_F, label=str(path)))
    assert got == f"{path}: {expected}"


def test_conflicting_constraints_match_the_command_line(tmp_path, run_tvf):
    V, F = torus(n=12, m=6)
    path = tmp_path / "torus.off"
    write_off(path, V, F)
    constraints = {
        "omega": 0.1,
        "constraints": [
            {"id": "east", "kind": "vector", "face": 5, "value": [1.0, 0.0, 0.0]},
            {"id": "again", "kind": "vector", "face": 5, "value": [0.0, 1.0, 0.0]},
        ],
    }
    file = tmp_path / "c.json"
    file.write_text(json.dumps(constraints))
    expected = run_tvf("spline", path, "--constraints", file, "-k", 30, "-o", tmp_path / "s.npy", "--no-cache", check=False)
    assert expected.returncode == 1
    expected = expected.stderr.strip().splitlines()[-1][len("error: "):]
    mesh = tvf.Mesh.load(path)
    got = python_message(lambda: tvf.spline(mesh, constraints, k=30, origin=str(file)))
    assert got == expected
    assert "again" in got

    unknown = {"constraints": [{"id": "x", "kind": "swirl", "face": 1, "value": 1.0}]}
    file.write_text(json.dumps(unknown))
    expected = run_tvf("design", path, "--constraints", file, "--full", "-o", tmp_path / "d.npy", check=False)
    got = python_message(lambda: tvf.design(mesh, unknown, origin=str(file)))
    assert got == expected.stderr.strip().splitlines()[-1][len("error: "):]


def run_isolated(code):
    """Runs ``code`` in a fresh interpreter (a crash or an abort there cannot take the test run
    with it); returns its stdout, failing on a crash, an exit code other than 0 or a hang."""
    import pathlib
    import subprocess
    import sys

    here = pathlib.Path(__file__).parent
    result = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, cwd=here, timeout=120)
    assert result.returncode == 0, f"exit {result.returncode}: {result.stderr[-2000:]}"
    return result.stdout


def test_from_matrices_checks_shapes_and_formats_before_converting():
    """A 2-entry sparse M1 of shape (2e8, 2e8) once aborted the interpreter on an allocation
    (its symmetry was checked before its shape); a CSR whose indptr points past its data once
    corrupted the heap inside scipy's conversion. Both are TvfErrors naming the matrix, raised
    before anything of their declared size is allocated."""
    out = run_isolated(
        """
import numpy as np, scipy.sparse as sp, tvf
from reference import icosphere, p1_cr_complex
V, F = icosphere(1)
mesh = tvf.Mesh(V, F)
ref = p1_cr_complex(V, F)
# COO: the test itself allocates nothing of the declared size.
huge = sp.coo_matrix((np.ones(2), ([0, 1], [0, 1])), shape=(200_000_000, 200_000_000))
for changes in (dict(M1=huge), dict(d0=sp.coo_matrix((200_000_000, len(V))))):
    parts = dict(d0=ref["d0"], d1=ref["d1"], M0=ref["M0"], M1=ref["M1"], M2=ref["M2"])
    parts.update(changes)
    try:
        tvf.Complex.from_matrices(mesh, **parts)
    except tvf.TvfError as e:
        print("refused:", e)
broken = sp.diags(ref["M1"]).tocsr()
broken.indptr[-1] = broken.nnz + 1000
try:
    tvf.Complex.from_matrices(mesh, ref["d0"], ref["d1"], ref["M0"], broken, ref["M2"])
except tvf.TvfError as e:
    print("refused:", e)
A = (ref["d0"].T @ ref["d0"]).tocsc()
A.indices[0] = 10**6
try:
    tvf.eigsh(A, np.ones(A.shape[0]), 3)
except tvf.TvfError as e:
    print("refused:", e)
"""
    )
    lines = out.splitlines()
    assert len(lines) == 4, out
    assert "M1 has shape (200000000, 200000000)" in lines[0] or "200000000 nodes" in lines[0], out
    assert "the field space has 200000000 nodes" in lines[1], out
    assert "M1: not a valid CSR matrix" in lines[2], out
    assert "A: not a valid CSC matrix: indices must be < 42" in lines[3], out
