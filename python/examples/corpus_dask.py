"""Spectra of a folder of meshes for every catalog entry, computed on a Dask cluster.

    python corpus_dask.py MESHES/ -k 50 -o spectra.csv                 # a local cluster
    python corpus_dask.py MESHES/ -k 50 -o spectra.csv --scheduler tcp://HOST:8786

One task per (mesh, discretization): it loads the mesh on the worker, computes the k lowest
eigenvalues of the Hodge-Laplacian with tvf (the GIL is released, so threads of a worker run in
parallel too) and returns one row. A mesh that cannot be read, or a discretization that refuses
it (DEC needs a Delaunay mesh), gives a row with status ``failed`` and tvf's message; the other
tasks go on. The rows are written to one CSV table (atomically: a temporary file, then renamed).

On a real cluster the workers need the package (``pip install ./python``) and must see the mesh
folder at the same path (a shared file system); start ``dask scheduler`` and ``dask worker
tcp://HOST:8786`` on the machines and pass ``--scheduler tcp://HOST:8786``. Nothing else changes.
"""

import argparse
import csv
import os
import pathlib
import socket
import tempfile
import time

MESH_SUFFIXES = {".obj", ".off", ".ply"}

COLUMNS = ["mesh", "discretization", "status", "message", "vertices", "faces", "genus", "harmonic", "k", "seconds", "worker", "eigenvalues"]


def mesh_spectrum(path, discretization, k):
    """One row of the table: the ``k`` lowest eigenvalues of ``discretization`` on the mesh at
    ``path``, or the reason it failed. Runs on a worker; never raises for bad input."""
    import tvf

    row = {"mesh": pathlib.Path(path).name, "discretization": discretization, "k": k, "worker": f"{socket.gethostname()}:{os.getpid()}"}
    start = time.perf_counter()
    try:
        mesh = tvf.Mesh.load(path)
        row.update(vertices=mesh.positions.shape[0], faces=mesh.faces.shape[0], genus=mesh.genus)
        basis = tvf.basis(mesh, k, discretization=discretization)
        if not all(map(lambda x: x == x and abs(x) != float("inf"), basis.eigenvalues)):
            raise tvf.TvfError(f"{path}: non-finite eigenvalues")
        row.update(
            status="ok",
            message="",
            harmonic=int((basis.families == "harmonic").sum()),
            eigenvalues=" ".join(repr(float(x)) for x in basis.eigenvalues),
        )
    except Exception as error:  # one mesh's failure is a row, not the end of the run
        row.update(status="failed", message=f"{type(error).__name__}: {error}")
    row["seconds"] = round(time.perf_counter() - start, 4)
    return row


def mesh_files(folder):
    """The mesh files of ``folder`` (not recursive), sorted by name."""
    return sorted(p for p in pathlib.Path(folder).iterdir() if p.suffix.lower() in MESH_SUFFIXES and p.is_file())


def corpus_spectra(client, folder, k, discretizations=None):
    """Submits one task per (mesh, discretization) to the Dask ``client`` and collects the
    rows as they finish (sorted by mesh, then catalog order). A task lost with its worker is
    reported as a failed row too."""
    from dask.distributed import as_completed

    import tvf

    ids = discretizations or [entry["id"] for entry in tvf.discretizations()]
    jobs = {}
    for path in mesh_files(folder):
        for discretization in ids:
            future = client.submit(mesh_spectrum, str(path.resolve()), discretization, k, pure=False)
            jobs[future] = (path.name, discretization)
    rows = []
    for future in as_completed(list(jobs)):
        try:
            rows.append(future.result())
        except Exception as error:
            name, discretization = jobs[future]
            rows.append({"mesh": name, "discretization": discretization, "k": k, "status": "failed", "message": f"task lost: {type(error).__name__}: {error}"})
    order = {d: i for i, d in enumerate(ids)}
    rows.sort(key=lambda r: (r["mesh"], order[r["discretization"]]))
    return rows


def write_table(rows, output):
    """Writes the rows as CSV to ``output`` atomically."""
    output = pathlib.Path(output)
    handle, temporary = tempfile.mkstemp(prefix=".tvf-write-", suffix=".tmp", dir=output.parent)
    try:
        with os.fdopen(handle, "w", newline="") as f:
            writer = csv.DictWriter(f, fieldnames=COLUMNS)
            writer.writeheader()
            for row in rows:
                writer.writerow({c: row.get(c, "") for c in COLUMNS})
        os.replace(temporary, output)
    except BaseException:
        os.unlink(temporary)
        raise


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("folder", help="folder of .obj/.off/.ply meshes")
    parser.add_argument("-k", type=int, default=50, help="eigenvalues per mesh and discretization")
    parser.add_argument("-o", "--output", required=True, help="CSV table to write")
    parser.add_argument("--scheduler", help="address of a running Dask scheduler (default: a local cluster)")
    parser.add_argument("--workers", type=int, default=2, help="worker processes of the local cluster")
    parser.add_argument("--discretization", action="append", help="catalog id (repeatable; default: all)")
    args = parser.parse_args()

    from dask.distributed import Client, LocalCluster

    if args.scheduler:
        client = Client(args.scheduler)
    else:
        client = Client(LocalCluster(n_workers=args.workers, threads_per_worker=1, processes=True))
    with client:
        rows = corpus_spectra(client, args.folder, args.k, args.discretization)
    write_table(rows, args.output)
    failed = [r for r in rows if r["status"] != "ok"]
    print(f"{len(rows)} rows ({len(rows) - len(failed)} ok, {len(failed)} failed) -> {args.output}")
    for row in failed:
        print(f"  failed: {row['mesh']} / {row['discretization']}: {row['message']}")


if __name__ == "__main__":
    main()
