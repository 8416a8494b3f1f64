"""tvf.BasisFile: a .tvfb written by `tvf basis`, read in blocks — its metadata without the
fields, coefficients and filters equal bit for bit to `tvf coefficients` / `tvf filter` on the
same file (the same Rust block reader), equal to round-off to the in-memory tvf.Basis of the
same mesh, results independent of the block size, and bad files refused naming the file; every
pass over the file reported to `progress=` up to its end, and stopped mid-pass by an exception
of `progress` or by Ctrl+C."""

import json
import os
import pickle
import signal
import subprocess
import threading

import numpy as np
import pytest

import tvf
from reference import icosphere, torus, write_obj

K = 60
SEED = 5
# A lowpass, a highpass and explicit harmonic and rest gains: every gain of the filter is used.
FILTER = dict(integrable="lowpass:t=0.01", cointegrable="highpass:t=0.002", harmonic_gain=0.5, rest_gain=0.3)
FILTER_FLAGS = ["--integrable", "lowpass:t=0.01", "--cointegrable", "highpass:t=0.002", "--harmonic", "0.5", "--rest", "0.3"]


def run_cli(tvf_bin, cache, *args, block_bytes=None):
    environment = {**os.environ, "XDG_CACHE_HOME": str(cache)}
    environment.pop("TVF_BASIS_BLOCK_BYTES", None)
    if block_bytes is not None:
        environment["TVF_BASIS_BLOCK_BYTES"] = str(block_bytes)
    result = subprocess.run([str(tvf_bin), *map(str, args)], capture_output=True, text=True, env=environment)
    assert result.returncode == 0, f"tvf {' '.join(map(str, args))} failed: {result.stderr}"
    return result


@pytest.fixture(scope="module", params=["conforming-barycentric", "whitney-galerkin"])
def saved(request, tvf_bin, tmp_path_factory):
    """A genus-1 torus (two harmonic fields), its basis written by `tvf basis`, a field file,
    and the in-memory basis of the same mesh and seed. `whitney-galerkin` has a sparse M1."""
    folder = tmp_path_factory.mktemp("basis-file")
    V, F = torus(n=16, m=8)
    mesh = tvf.Mesh(V, F)
    write_obj(folder / "torus.obj", mesh.positions, mesh.faces)
    path = folder / "torus.tvfb"
    cache = folder / "cache"
    run_cli(tvf_bin, cache, "basis", folder / "torus.obj", "-k", K, "--seed", SEED, "--discretization", request.param, "-o", path)
    field = np.random.default_rng(3).normal(size=(len(mesh.faces), 3))
    np.save(folder / "field.npy", field)
    complex_ = tvf.Complex(mesh, request.param)
    return dict(
        folder=folder, path=path, mesh=mesh, complex=complex_, field=field, cache=cache, tvf_bin=tvf_bin,
        basis=tvf.basis(complex_, K, seed=SEED),
    )


def test_metadata_without_the_fields(saved):
    mesh, basis = saved["mesh"], saved["basis"]
    f = tvf.BasisFile(saved["path"])
    assert len(f) == f.k == K
    assert np.array_equal(f.eigenvalues, basis.eigenvalues)
    assert list(f.families) == list(basis.families)
    assert f.counts == {name: int(np.sum(basis.families == name)) for name in ("harmonic", "integrable", "cointegrable")}
    assert f.counts["harmonic"] == 2
    assert np.array_equal(f.eigenvalues_of("integrable"), basis.eigenvalues[basis.families == "integrable"])
    assert f.discretization == basis.discretization == saved["complex"].id
    assert f.mesh_fingerprint == mesh.fingerprint and f.face_count == len(mesh.faces)
    n0, n1, n2 = saved["complex"].dimensions
    assert (f.potential_dimension, f.field_dimension, f.co_potential_dimension) == (n0, n1, n2)
    assert f.layout == "eigenfunctions" and f.version >= 3 and set(f.matrix_hash) >= {"d0", "M1"}
    assert f.file_bytes == os.path.getsize(saved["path"])
    with pytest.raises(tvf.TvfError, match="not a family"):
        f.eigenvalues_of("harmonics")


def cli_coefficients(saved, block_bytes):
    out = run_cli(
        saved["tvf_bin"], saved["cache"], "coefficients", saved["folder"] / "torus.obj", saved["folder"] / "field.npy",
        "--basis", saved["path"], "--json", block_bytes=block_bytes,
    )
    report = json.loads(out.stdout)
    return np.array([entry["coefficient"] for entry in report["coefficients"]]), report["relative_rest_norm"]


def test_coefficients_equal_the_command_line_bit_for_bit_and_the_basis_in_memory(saved):
    # A block of one stored column: every pass reads many blocks.
    f = tvf.BasisFile(saved["path"], block_bytes=8)
    c, rest = f.coefficients(saved["mesh"], saved["field"])
    expected, expected_rest = cli_coefficients(saved, block_bytes=8)
    assert np.array_equal(c, expected) and rest == expected_rest
    in_memory, in_memory_rest = tvf.coefficients(saved["complex"], saved["field"], saved["basis"])
    scale = np.max(np.abs(in_memory))
    assert np.max(np.abs(c - in_memory)) <= 1e-12 * scale
    assert abs(rest - in_memory_rest) <= 1e-12
    # The module function takes the file wherever it takes a basis.
    again, _ = tvf.coefficients(saved["mesh"], saved["field"], f)
    assert np.array_equal(again, c)


def test_filter_equals_the_command_line_bit_for_bit_and_the_basis_in_memory(saved):
    folder = saved["folder"]
    f = tvf.BasisFile(saved["path"], block_bytes=1000)
    filtered, coefficients = f.filter(saved["mesh"], saved["field"], **FILTER)
    run_cli(
        saved["tvf_bin"], saved["cache"], "filter", folder / "torus.obj", folder / "field.npy", "--basis", saved["path"],
        *FILTER_FLAGS, "-o", folder / "filtered.npy", block_bytes=1000,
    )
    assert np.array_equal(filtered, np.load(folder / "filtered.npy"))
    in_memory, in_memory_coefficients = tvf.filter(saved["complex"], saved["field"], saved["basis"], **FILTER)
    assert np.max(np.abs(filtered - in_memory)) <= 1e-12 * np.max(np.abs(in_memory))
    assert np.max(np.abs(coefficients - in_memory_coefficients)) <= 1e-12 * np.max(np.abs(in_memory_coefficients))
    # rest_gain=None: the command line's default --rest (the filters' gain at the top frequency).
    default_rest, _ = f.filter(saved["mesh"], saved["field"], integrable="lowpass:t=0.01", cointegrable="lowpass:t=0.01", rest_gain=None)
    run_cli(
        saved["tvf_bin"], saved["cache"], "filter", folder / "torus.obj", folder / "field.npy", "--basis", saved["path"],
        "--integrable", "lowpass:t=0.01", "--cointegrable", "lowpass:t=0.01", "-o", folder / "default.npy", block_bytes=1000,
    )
    assert np.array_equal(default_rest, np.load(folder / "default.npy"))
    with pytest.raises(tvf.TvfError, match="--integrable lowpass:q=1"):
        f.filter(saved["mesh"], saved["field"], integrable="lowpass:q=1")


def test_results_do_not_depend_on_the_block_size(saved, monkeypatch):
    """Bit for bit with a diagonal M1; with whitney-galerkin's sparse M1 the co-integrable fields
    are formed by one mass solve per block of co-potentials, and a solve of another number of
    columns rounds differently: equal to round-off."""
    mesh, field = saved["mesh"], saved["field"]
    exact = saved["complex"].masses["M1"]["storage"] == "diagonal"
    whole = tvf.BasisFile(saved["path"])  # one block holds every stored column
    assert whole.block_bytes == 64 << 20
    monkeypatch.setenv("TVF_BASIS_BLOCK_BYTES", "8")
    column = tvf.BasisFile(saved["path"])  # one stored column per block
    assert column.block_bytes == 8
    for method, args in [("coefficients", ()), ("filter", ()), ("synthesize", ())]:
        if method == "synthesize":
            c = np.random.default_rng(1).normal(size=(3, K))
            a, b = whole.synthesize(mesh, c), column.synthesize(mesh, c)
        else:
            a, b = getattr(whole, method)(mesh, field), getattr(column, method)(mesh, field)
        for x, y in zip(a, b):
            if exact:
                assert np.array_equal(x, y), method
            else:
                assert np.max(np.abs(np.subtract(x, y))) <= 1e-13 * np.max(np.abs(x)), method
    monkeypatch.setenv("TVF_BASIS_BLOCK_BYTES", "lots")
    with pytest.raises(tvf.TvfError, match="TVF_BASIS_BLOCK_BYTES"):
        tvf.BasisFile(saved["path"])


@pytest.mark.parametrize("block_bytes", [8, 64 << 20])
def test_compression_equals_the_command_line_bit_for_bit(saved, block_bytes):
    """`BasisFile.compress` writes the bytes `tvf compress --basis` writes at the same block size
    (8 bytes: one stored column per block, so whitney-galerkin's sparse M1 takes the command
    line's whole-basis fallback; 64 MiB: every family in one block, read in blocks), and both
    decoders read each other's files: `tvf decompress` decodes Python's bytes bit for bit as
    `BasisFile.decompress` does, and the in-memory `tvf.Basis`, whose id is the file's, decodes
    them to round-off."""
    folder = saved["folder"]
    f = tvf.BasisFile(saved["path"], block_bytes=block_bytes)
    data = f.compress(saved["mesh"], saved["field"], pairs=20)
    assert data == tvf.compress(saved["mesh"], saved["field"], f, pairs=20)
    out = folder / f"field-{block_bytes}.tvfc"
    run_cli(
        saved["tvf_bin"], saved["cache"], "compress", folder / "torus.obj", folder / "field.npy", "--basis", saved["path"],
        "--pairs", 20, "-o", out, block_bytes=block_bytes,
    )
    assert data == out.read_bytes()
    decoded = f.decompress(saved["mesh"], data)
    assert decoded.shape == (1, len(saved["mesh"].faces), 3)
    assert np.array_equal(decoded, tvf.decompress(saved["mesh"], data, f))
    run_cli(
        saved["tvf_bin"], saved["cache"], "decompress", folder / "torus.obj", out, "--basis", saved["path"],
        "-o", folder / f"decoded-{block_bytes}.npy", block_bytes=block_bytes,
    )
    assert np.array_equal(decoded[0], np.load(folder / f"decoded-{block_bytes}.npy"))
    in_memory = tvf.decompress(saved["complex"], data, saved["basis"])
    assert np.max(np.abs(decoded - in_memory)) <= 1e-12 * np.max(np.abs(in_memory))
    # A sequence of frames, quantised; the coefficients form.
    frames = np.stack([saved["field"], 2.0 * saved["field"]])
    quantised = f.compress(saved["mesh"], frames, pairs=20, bits=12)
    rows = f.decompress(saved["mesh"], quantised, as_vectors=False)
    assert rows.shape == (2, f.field_dimension)
    assert np.max(np.abs(rows[1] - 2.0 * rows[0])) <= 1e-2 * np.max(np.abs(rows[1]))
    with pytest.raises(tvf.TvfError, match="bits"):
        f.compress(saved["mesh"], saved["field"], pairs=20, bits=40)


def test_compressed_bytes_of_another_basis_are_refused(saved, tmp_path):
    other = tvf.Mesh(*torus(n=12, m=8))
    data = tvf.compress(other, np.ones((len(other.faces), 3)), tvf.basis(other, 10), pairs=3)
    with pytest.raises(tvf.TvfError, match="mesh"):
        tvf.BasisFile(saved["path"]).decompress(saved["mesh"], data)


def test_synthesis_fields_and_the_materialised_basis(saved):
    mesh, basis = saved["mesh"], saved["basis"]
    f = tvf.BasisFile(saved["path"], block_bytes=4096)
    loaded = f.to_basis(mesh)
    assert np.array_equal(loaded.eigenvalues, basis.eigenvalues) and loaded.discretization == basis.discretization
    assert np.max(np.abs(loaded.coefficients - basis.coefficients)) <= 1e-10 * np.max(np.abs(basis.coefficients))
    c = np.random.default_rng(2).normal(size=(4, K))
    many = f.synthesize(mesh, c, as_vectors=False)
    assert many.shape == (4, saved["complex"].dimensions[1])
    for row, coefficients in zip(many, c):
        # One pass for several sets gives each set's own sum, bit for bit.
        assert np.array_equal(row, f.synthesize(mesh, coefficients, as_vectors=False))
    assert np.max(np.abs(many - c @ loaded.coefficients.T)) <= 1e-12 * np.max(np.abs(many))
    vectors = f.synthesize(mesh, c[0])
    assert vectors.shape == (len(mesh.faces), 3)
    assert np.max(np.abs(vectors - loaded.fields @ c[0])) <= 1e-12 * np.max(np.abs(vectors))
    chosen = f.fields(mesh, [0, 5, K - 1])
    assert chosen.shape == (len(mesh.faces), 3, 3)
    assert np.max(np.abs(chosen - loaded.fields[:, :, [0, 5, K - 1]])) <= 1e-13 * np.max(np.abs(chosen))
    # Coefficients of a basis field: 1 at its own index.
    projected, rest = f.coefficients(mesh, basis.coefficients[:, 7])
    assert abs(projected[7] - 1) < 1e-9 and rest < 1e-9
    assert len(f.basis_id(mesh)) == 16
    # Pickled as its path: used again after unpickling, with the same results.
    again = pickle.loads(pickle.dumps(f))
    assert again.path == f.path and np.array_equal(again.synthesize(mesh, c[0]), vectors)
    with pytest.raises(tvf.TvfError, match="expected 60 per field"):
        f.synthesize(mesh, np.ones(K + 1))
    with pytest.raises(tvf.TvfError, match="the basis has 60 fields"):
        f.fields(mesh, [K])


def test_a_mismatched_mesh_or_discretization_is_refused_naming_the_file(saved):
    f = tvf.BasisFile(saved["path"])
    V, F = torus(n=18, m=8)
    with pytest.raises(tvf.TvfError, match=r"torus\.tvfb: basis belongs to another mesh"):
        f.coefficients(tvf.Mesh(V, F), np.ones((len(F), 3)))
    other = "conforming-voronoi" if saved["complex"].id != "conforming-voronoi" else "whitney-galerkin"
    with pytest.raises(tvf.TvfError, match=r"torus\.tvfb: the basis belongs to"):
        f.coefficients(tvf.Complex(saved["mesh"], other), saved["field"])
    with pytest.raises(TypeError, match="tvf.Mesh or tvf.Complex"):
        f.coefficients("torus.obj", saved["field"])


def test_truncated_flipped_and_foreign_files_are_refused_naming_the_file(saved, tmp_path):
    data = saved["path"].read_bytes()
    truncated = tmp_path / "truncated.tvfb"
    truncated.write_bytes(data[:-100])
    with pytest.raises(tvf.TvfError, match=r"truncated\.tvfb: truncated basis file"):
        tvf.BasisFile(truncated)
    # A flipped bit in the stored columns: the metadata still read, the first use refuses it.
    flipped = tmp_path / "flipped.tvfb"
    damaged = bytearray(data)
    damaged[len(data) - 4096] ^= 0x10
    flipped.write_bytes(bytes(damaged))
    f = tvf.BasisFile(flipped)
    with pytest.raises(tvf.TvfError, match=r"flipped\.tvfb: damaged basis file \(payload checksum mismatch\)"):
        f.filter(saved["mesh"], saved["field"])
    header = tmp_path / "header.tvfb"
    damaged = bytearray(data)
    damaged[40] ^= 0x01
    header.write_bytes(bytes(damaged))
    with pytest.raises(tvf.TvfError, match=r"header\.tvfb: "):
        tvf.BasisFile(header)
    foreign = tmp_path / "foreign.tvfb"
    foreign.write_bytes(b"not a basis at all" * 10)
    with pytest.raises(tvf.TvfError, match=r"foreign\.tvfb: not a tvf basis file"):
        tvf.BasisFile(foreign)
    with pytest.raises(tvf.TvfError, match=r"missing\.tvfb"):
        tvf.BasisFile(tmp_path / "missing.tvfb")


def test_a_file_changed_after_it_was_checked_is_refused(saved, tmp_path):
    copy = tmp_path / "copy.tvfb"
    copy.write_bytes(saved["path"].read_bytes())
    f = tvf.BasisFile(copy)
    f.coefficients(saved["mesh"], saved["field"])
    with open(copy, "ab") as out:
        out.write(b"\0" * 8)
    with pytest.raises(tvf.TvfError, match=r"copy\.tvfb.*changed since it was checked"):
        f.coefficients(saved["mesh"], saved["field"])


CONSTRAINTS = {
    "omega": 0.1,
    "constraints": [
        {"id": "a", "kind": "vector", "face": 12, "value": [1.0, 0.0, 0.0]},
        {"id": "b", "kind": "vector", "face": 200, "barycentric": [0.2, 0.3, 0.5], "value": [0.0, 1.0, 0.5]},
        {"id": "c", "kind": "divergence", "vertex": 5, "value": 2.0, "weight": 10.0},
    ],
}


@pytest.mark.parametrize("command", ["spline", "design"])
def test_spline_and_reduced_design_in_a_basis_file(saved, command):
    """`tvf.spline(…, basis=BasisFile)` and `tvf.design(…, basis=BasisFile)` (only the rows of
    `U` the constraints touch read) equal `tvf spline --basis` / `tvf design --reduced --basis`
    on the same file bit for bit (the same reduced basis from the same rows) and the in-memory
    basis's to round-off."""
    folder, mesh = saved["folder"], saved["mesh"]
    (folder / "constraints.json").write_text(json.dumps(CONSTRAINTS))
    f = tvf.BasisFile(saved["path"], block_bytes=4096)
    solve = tvf.spline if command == "spline" else tvf.design
    found = solve(mesh, CONSTRAINTS, basis=f)
    expected = solve(saved["complex"], CONSTRAINTS, basis=saved["basis"])
    scale = np.max(np.abs(expected["field"]))
    assert found["field"].shape == (len(mesh.faces), 3)
    assert np.max(np.abs(found["field"] - expected["field"])) <= 1e-11 * scale
    assert set(found["residuals"]) == {"a", "b", "c"}
    flags = ["--reduced"] if command == "design" else []
    out = folder / f"{command}.npy"
    run_cli(
        saved["tvf_bin"], saved["cache"], command, folder / "torus.obj", "--constraints", folder / "constraints.json",
        *flags, "--basis", saved["path"], "-o", out, block_bytes=4096,
    )
    assert np.array_equal(found["field"], np.load(out))


def test_a_mesh_with_boundary_brings_its_boundary_condition_back(tvf_bin, tmp_path):
    """On a mesh with boundary the file's id carries the condition (`…+normal`): the complex is
    rebuilt with it, and coefficients equal `tvf coefficients --basis` bit for bit."""
    V, F = icosphere(3)
    # The faces above z = 0.6 removed: a sphere with a hole (one boundary loop).
    kept = F[np.max(V[F][:, :, 2], axis=1) < 0.6]
    mesh = tvf.Mesh(V, kept)
    write_obj(tmp_path / "plate.obj", mesh.positions, mesh.faces)
    path = tmp_path / "plate.tvfb"
    cache = tmp_path / "cache"
    run_cli(tvf_bin, cache, "basis", tmp_path / "plate.obj", "-k", 30, "--boundary", "normal", "-o", path)
    f = tvf.BasisFile(path, block_bytes=64)
    assert f.discretization == "conforming-barycentric+normal"
    field = np.random.default_rng(4).normal(size=(len(mesh.faces), 3))
    np.save(tmp_path / "field.npy", field)
    c, rest = f.coefficients(mesh, field)
    out = run_cli(tvf_bin, cache, "coefficients", tmp_path / "plate.obj", tmp_path / "field.npy", "--basis", path, "--json", block_bytes=64)
    report = json.loads(out.stdout)
    assert np.array_equal(c, [entry["coefficient"] for entry in report["coefficients"]])
    assert rest == report["relative_rest_norm"]
    in_memory, _ = tvf.coefficients(tvf.Complex(mesh, boundary="normal"), field, tvf.basis(mesh, 30, boundary="normal"))
    assert np.max(np.abs(c - in_memory)) <= 1e-12 * np.max(np.abs(in_memory))
    with pytest.raises(tvf.TvfError, match=r"plate\.tvfb: the basis belongs to 'conforming-barycentric\+normal'"):
        f.coefficients(tvf.Complex(mesh), field)


class Recorder:
    """A `progress(stage, done, wanted)` callable keeping its calls."""

    def __init__(self):
        self.calls = []

    def __call__(self, stage, done, wanted):
        self.calls.append((stage, done, wanted))

    def passes(self):
        """The calls split into passes (each starts at done 0), each checked: one stage and one
        `wanted` throughout, `done` growing at every call up to `wanted`. The stages and the
        number of blocks of each pass; the calls are then forgotten."""
        passes = []
        for stage, done, wanted in self.calls:
            if done == 0:
                passes.append([])
            assert passes, f"a pass starts at done 0: {self.calls}"
            passes[-1].append((stage, done, wanted))
        found = []
        for calls in passes:
            stage, _, wanted = calls[0]
            assert wanted > 0 and all(c[0] == stage and c[2] == wanted for c in calls), calls
            assert all(b[1] > a[1] for a, b in zip(calls, calls[1:])), calls
            assert calls[-1][1] == wanted, calls
            found.append((stage, len(calls) - 1))
        self.calls = []
        return found


def test_every_product_reports_each_pass_to_its_end(saved):
    """Each product reports the passes it makes over the file, from 0 to their totals (bytes),
    a call per block (blocks of 4 KiB: several per pass) — the check when the mesh first uses
    the file included — and gives what it gives without a `progress` callable, bit for bit."""
    mesh, field = saved["mesh"], saved["field"]
    plain = tvf.BasisFile(saved["path"], block_bytes=4096)
    f = tvf.BasisFile(saved["path"], block_bytes=4096)
    heard = Recorder()

    def stages(passes):
        for stage, blocks in passes:
            assert blocks >= (1 if stage == "checking" else 4), passes
        return [stage for stage, _ in passes]

    c, rest = f.coefficients(mesh, field, progress=heard)
    assert stages(heard.passes()) == ["checking", "projecting", "synthesising"]
    expected_c, expected_rest = plain.coefficients(mesh, field)
    assert np.array_equal(c, expected_c) and rest == expected_rest
    filtered, _ = f.filter(mesh, field, progress=heard, **FILTER)
    # The filter's two syntheses (the rest outside the basis, the output) share one pass.
    assert stages(heard.passes()) == ["projecting", "synthesising"]
    assert np.array_equal(filtered, plain.filter(mesh, field, **FILTER)[0])
    sets = np.random.default_rng(4).normal(size=(3, K))
    assert np.array_equal(f.synthesize(mesh, sets, progress=heard), plain.synthesize(mesh, sets))
    assert stages(heard.passes()) == ["synthesising"]
    assert np.array_equal(f.fields(mesh, [0, 5, K - 1], progress=heard), plain.fields(mesh, [0, 5, K - 1]))
    assert stages(heard.passes()) == ["synthesising"]
    assert f.basis_id(mesh, progress=heard) == plain.basis_id(mesh)
    assert stages(heard.passes()) == ["fields"]
    frames = np.stack([field, 2.0 * field])
    data = f.compress(mesh, frames, pairs=20, progress=heard)
    assert data == plain.compress(mesh, frames, pairs=20)
    # A sparse M1 whose co-potentials do not fit a block of 4 KiB is loaded whole: no pass.
    in_blocks = saved["complex"].id != "whitney-galerkin"
    expected = ["fields", "projecting", "projecting"]
    assert stages(heard.passes()) == (expected if in_blocks else [])
    assert np.array_equal(f.decompress(mesh, data, progress=heard), plain.decompress(mesh, data))
    assert stages(heard.passes()) == (["fields", "synthesising"] if in_blocks else [])
    found = tvf.spline(mesh, CONSTRAINTS, basis=f, progress=heard)
    assert stages(heard.passes()) == ["rows", "synthesising"]
    assert np.array_equal(found["field"], tvf.spline(mesh, CONSTRAINTS, basis=plain)["field"])
    found = tvf.design(mesh, CONSTRAINTS, basis=f, progress=heard)
    assert stages(heard.passes())[0] == "rows"
    assert np.array_equal(found["field"], tvf.design(mesh, CONSTRAINTS, basis=plain)["field"])


class StopAt:
    """A `progress` callable raising `error` at its `at`-th call of stage `stage`."""

    def __init__(self, stage, at, error):
        self.stage, self.at, self.error, self.calls = stage, at, error, 0

    def __call__(self, stage, done, wanted):
        if stage == self.stage:
            self.calls += 1
            if self.calls == self.at:
                raise self.error


@pytest.mark.parametrize("error", [KeyboardInterrupt, ValueError("enough")])
def test_an_exception_of_progress_stops_the_pass_and_is_raised(saved, error):
    """A `progress` callable raising mid-pass (at the third block: `KeyboardInterrupt`, as
    Ctrl+C raises it at a block, or any other exception) stops the pass there — no further
    call — and the exception propagates as it was raised; the file stays usable."""
    mesh, field = saved["mesh"], saved["field"]
    f = tvf.BasisFile(saved["path"], block_bytes=4096)
    expected = f.coefficients(mesh, field)
    expected_type = error if isinstance(error, type) else type(error)
    for stage, call in [
        ("projecting", lambda p: f.coefficients(mesh, field, progress=p)),
        ("synthesising", lambda p: f.synthesize(mesh, np.ones(K), progress=p)),
        ("fields", lambda p: f.basis_id(mesh, progress=p)),
        ("rows", lambda p: tvf.spline(mesh, CONSTRAINTS, basis=f, progress=p)),
    ]:
        stop = StopAt(stage, 3, error)
        with pytest.raises(expected_type):
            call(stop)
        assert stop.calls == 3, stage
    checked = tvf.BasisFile(saved["path"], block_bytes=4096)
    stop = StopAt("checking", 1, error)
    with pytest.raises(expected_type):
        checked.coefficients(mesh, field, progress=stop)
    c, rest = f.coefficients(mesh, field)
    assert np.array_equal(c, expected[0]) and rest == expected[1]
    c, rest = checked.coefficients(mesh, field)
    assert np.array_equal(c, expected[0]) and rest == expected[1]


def test_ctrl_c_mid_pass_raises_keyboard_interrupt(saved):
    """A SIGINT arriving mid-pass (sent by the `progress` callable at the third block, which
    then returns normally) raises `KeyboardInterrupt` by the next block at the latest: the pass
    does not run to its end."""
    if threading.current_thread() is not threading.main_thread():
        pytest.skip("signals are handled on the main thread only")
    mesh, field = saved["mesh"], saved["field"]
    f = tvf.BasisFile(saved["path"], block_bytes=4096)
    f.coefficients(mesh, field)
    calls = []

    def interrupting(stage, done, wanted):
        calls.append((stage, done, wanted))
        if len(calls) == 3:
            os.kill(os.getpid(), signal.SIGINT)

    previous = signal.signal(signal.SIGINT, signal.default_int_handler)
    try:
        with pytest.raises(KeyboardInterrupt):
            f.synthesize(mesh, np.ones(K), progress=interrupting)
    finally:
        signal.signal(signal.SIGINT, previous)
    assert 3 <= len(calls) <= 4 and calls[-1][1] < calls[-1][2], calls
