"""The Dask example on a LocalCluster of two worker processes: a generated corpus of several
genera (and one broken file) for every catalog entry, one table, failures per mesh."""

import csv
import importlib.util
import pathlib

import numpy as np
import pytest

import tvf
from reference import icosphere, plate_with_holes, torus, write_obj

EXAMPLE = pathlib.Path(__file__).resolve().parents[1] / "examples" / "corpus_dask.py"


def load_example():
    spec = importlib.util.spec_from_file_location("corpus_dask", EXAMPLE)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


@pytest.fixture(scope="module")
def corpus(tmp_path_factory):
    folder = tmp_path_factory.mktemp("corpus")
    write_obj(folder / "sphere.obj", *icosphere(2))
    write_obj(folder / "torus.obj", *torus(n=16, m=8))
    write_obj(folder / "genus2.obj", *plate_with_holes(2))
    write_obj(folder / "genus3.obj", *plate_with_holes(3))
    (folder / "broken.obj").write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n")
    (folder / "notes.txt").write_text("not a mesh")
    return folder


def test_corpus_spectra_on_two_worker_processes(corpus, tmp_path):
    from dask.distributed import Client, LocalCluster

    example = load_example()
    k = 12
    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster, Client(cluster) as client:
        rows = example.corpus_spectra(client, corpus, k)
    output = tmp_path / "spectra.csv"
    example.write_table(rows, output)

    with open(output) as f:
        table = list(csv.DictReader(f))
    ids = [e["id"] for e in tvf.discretizations()]
    meshes = ["broken.obj", "genus2.obj", "genus3.obj", "sphere.obj", "torus.obj"]
    assert [(r["mesh"], r["discretization"]) for r in table] == [(m, d) for m in meshes for d in ids]
    by_key = {(r["mesh"], r["discretization"]): r for r in table}

    # The broken file fails on every entry, with tvf's message naming it; the run went on.
    for d in ids:
        row = by_key[("broken.obj", d)]
        assert row["status"] == "failed"
        assert "broken.obj:4: vertex index 7 is out of range" in row["message"]
    # The voxel plates have right angles (cot a + cot b = 0): DEC refuses them, naming why.
    for mesh in ("genus2.obj", "genus3.obj"):
        for d in ("dec-barycentric", "dec-circumcentric"):
            assert by_key[(mesh, d)]["status"] == "failed" and "not Delaunay" in by_key[(mesh, d)]["message"]
    # Everything else succeeded with the right topology, in agreement with a local run.
    expected_genus = {"sphere.obj": 0, "torus.obj": 1, "genus2.obj": 2, "genus3.obj": 3}
    ok = [r for r in table if r["status"] == "ok"]
    # Four good meshes with every entry, but the two DEC entries on the two plates.
    assert len(ok) == 4 * len(ids) - 4
    for row in ok:
        genus = expected_genus[row["mesh"]]
        assert int(row["genus"]) == genus and int(row["harmonic"]) == 2 * genus
        values = np.array([float(x) for x in row["eigenvalues"].split()])
        assert len(values) == k and np.all(np.diff(values) >= 0)
    local = tvf.basis(tvf.Mesh.load(corpus / "torus.obj"), k, discretization="nonconforming-voronoi").eigenvalues
    remote = np.array([float(x) for x in by_key[("torus.obj", "nonconforming-voronoi")]["eigenvalues"].split()])
    assert np.allclose(local, remote, rtol=1e-12, atol=1e-12)
    # The work was spread over two worker processes.
    assert len({r["worker"] for r in table}) >= 2


def test_the_command_line_runs_a_corpus_on_a_dask_cluster_as_on_local_threads(corpus, tvf_bin, tmp_path):
    """``tvf compare --corpus FOLDER --scheduler ADDRESS`` runs the package's driver
    (``python -m tvf.corpus``, here this interpreter through TVF_PYTHON) against a LocalCluster
    of two worker processes: the same runs, outcomes, reasons and eigenvalues as on local
    threads, and each failure's cause said once."""
    import json
    import os
    import subprocess
    import sys

    from dask.distributed import LocalCluster

    flags = ["compare", "--corpus", str(corpus), "-k", "8", "--json", "--quiet"]
    for d in ("conforming-barycentric", "dec-circumcentric"):
        flags += ["--discretization", d]
    environment = {**os.environ, "TVF_PYTHON": sys.executable, "XDG_CACHE_HOME": str(tmp_path / "cache")}
    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster:
        address = cluster.scheduler_address
        remote = subprocess.run([str(tvf_bin), *flags, "--scheduler", address], capture_output=True, text=True, env=environment)
    assert remote.returncode == 0, remote.stderr
    local = subprocess.run([str(tvf_bin), *flags, "--threads", "2"], capture_output=True, text=True, env=environment)
    assert local.returncode == 0, local.stderr
    remote, local = json.loads(remote.stdout), json.loads(local.stdout)
    assert remote["scheduler"] == address and local["scheduler"] is None
    key = lambda r: (r["mesh"], r["discretization"], r["succeeded"], r["faces"])
    assert [key(r) for r in remote["runs"]] == [key(r) for r in local["runs"]]
    for a, b in zip(remote["runs"], local["runs"]):
        assert np.allclose(a["eigenvalues"], b["eigenvalues"], rtol=1e-9, atol=1e-12), (a, b)
    for a, b in zip(remote["entries"], local["entries"]):
        assert (a["discretization"], a["meshes"], a["succeeded"]) == (b["discretization"], b["meshes"], b["succeeded"])
    # Five mesh files: the broken one fails everywhere, DEC refuses the two voxel plates.
    assert [e["succeeded"] for e in remote["entries"]] == [4, 2]
    reasons = dict(((pathlib.Path(m).name, d), r) for d, e in zip(["conforming-barycentric", "dec-circumcentric"], remote["entries"]) for m, r in e["failures"])
    assert "vertex index 7 is out of range" in reasons[("broken.obj", "dec-circumcentric")]
    plate = reasons[("genus2.obj", "dec-circumcentric")]
    assert "not Delaunay" in plate
    local_plate = dict((pathlib.Path(m).name, r) for m, r in local["entries"][1]["failures"])["genus2.obj"]
    for reason in (plate, local_plate):
        assert reason.count("not Delaunay") == 1, reason
