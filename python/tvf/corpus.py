"""Every mesh of a folder × every discretization on a Dask cluster: one task per (mesh,
discretization), run on the workers with this package. What ``tvf compare --corpus FOLDER
--scheduler ADDRESS`` runs (the command line starts ``python -m tvf.corpus`` and reads the rows
it prints), and usable from Python::

    from dask.distributed import Client
    import tvf.corpus
    with Client("tcp://HOST:8786") as client:
        rows = tvf.corpus.corpus_runs(client, "meshes/", 50, ["conforming-barycentric", "whitney-galerkin"])

A row (a dict) has the keys of ``tvf compare --corpus --json``'s ``runs``: ``mesh`` (the file,
as the folder was given joined with its name), ``faces`` (0 if it did not load),
``discretization``, ``succeeded``, ``reason`` (why not, else ``None``), ``seconds`` (to load,
build the complex and compute the basis) and ``eigenvalues`` (the ``k`` lowest, ascending; empty
on a failure). A mesh that does not load, an entry that refuses it and a task lost with its
worker are rows with their reason; the other tasks go on. The workers need this package and the
mesh folder at the same path (a shared file system).
"""

import argparse
import json
import math
import pathlib
import sys
import time

MESH_SUFFIXES = {".obj", ".off", ".ply"}


def mesh_files(folder):
    """The mesh files (``.obj``, ``.off``, ``.ply``) of ``folder``, not recursive, sorted."""
    return sorted(p for p in pathlib.Path(folder).iterdir() if p.suffix.lower() in MESH_SUFFIXES and p.is_file())


def corpus_run(path, name, discretization, k, boundary):
    """One row: the ``k`` lowest eigenvalues of ``discretization`` on the mesh file ``path``
    (named ``name`` in the row), or why not. Runs on a worker; never raises for bad input."""
    import tvf

    row = {"mesh": name, "faces": 0, "discretization": discretization, "succeeded": False, "reason": None, "seconds": 0.0, "eigenvalues": []}
    start = time.perf_counter()
    try:
        mesh = tvf.Mesh.load(path)
    except Exception as error:
        row["reason"] = f"cannot load: {_message(error)}"
    else:
        row["faces"] = int(mesh.faces.shape[0])
        try:
            basis = tvf.basis(mesh, k, discretization=discretization, boundary=boundary)
            values = [float(x) for x in basis.eigenvalues]
            if not all(math.isfinite(x) for x in values):
                raise tvf.TvfError(f"{name}: '{discretization}' gave non-finite eigenvalues")
            row.update(succeeded=True, eigenvalues=values)
        except Exception as error:  # one run's failure is a row, not the end of the run
            row["reason"] = _message(error)
    row["seconds"] = time.perf_counter() - start
    return row


def _message(error):
    """tvf's own message for its errors; the type's name before any other's."""
    import tvf

    return str(error) if isinstance(error, tvf.TvfError) else f"{type(error).__name__}: {error}"


def corpus_runs(client, folder, k, discretizations, boundary="tangential", progress=None):
    """Submits one task per (mesh, discretization) of ``folder`` to the Dask ``client`` and
    returns the rows sorted by mesh, then in the order of ``discretizations``. ``progress``, if
    given, is called with (done, total) as tasks finish. Raises ``ValueError`` for a folder
    without mesh files."""
    from dask.distributed import as_completed

    files = mesh_files(folder)
    if not files:
        raise ValueError(f"{folder}: no mesh file (.obj, .off, .ply) in the folder")
    jobs = {}
    for path in files:
        name = str(pathlib.Path(folder) / path.name)
        for discretization in discretizations:
            future = client.submit(corpus_run, str(path.resolve()), name, discretization, k, boundary, pure=False)
            jobs[future] = (name, discretization)
    rows = []
    for done, future in enumerate(as_completed(list(jobs)), start=1):
        try:
            rows.append(future.result())
        except Exception as error:
            name, discretization = jobs[future]
            reason = f"task lost: {type(error).__name__}: {error}"
            rows.append({"mesh": name, "faces": 0, "discretization": discretization, "succeeded": False, "reason": reason, "seconds": 0.0, "eigenvalues": []})
        if progress is not None:
            progress(done, len(jobs))
    order = {d: i for i, d in enumerate(discretizations)}
    rows.sort(key=lambda r: (r["mesh"], order[r["discretization"]]))
    return rows


def main(argv=None):
    """``python -m tvf.corpus FOLDER -k K --discretization ID ... --scheduler ADDRESS``: the rows
    as one JSON list on stdout, progress on stderr."""
    parser = argparse.ArgumentParser(prog="python -m tvf.corpus", description=__doc__.split("\n\n")[0])
    parser.add_argument("folder")
    parser.add_argument("-k", type=int, required=True)
    parser.add_argument("--discretization", action="append", required=True)
    parser.add_argument("--boundary", default="tangential")
    parser.add_argument("--scheduler", required=True, help="address of a running Dask scheduler")
    args = parser.parse_args(argv)

    from dask.distributed import Client

    def progress(done, total):
        if done == total or (4 * done) // total > (4 * (done - 1)) // total:
            print(f"compare corpus on {args.scheduler}: runs {done}/{total}", file=sys.stderr, flush=True)

    try:
        with Client(args.scheduler, timeout="30s") as client:
            rows = corpus_runs(client, args.folder, args.k, args.discretization, args.boundary, progress)
    except (OSError, ValueError) as error:
        print(f"{type(error).__name__}: {error}", file=sys.stderr)
        return 1
    json.dump(rows, sys.stdout)
    sys.stdout.write("\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
