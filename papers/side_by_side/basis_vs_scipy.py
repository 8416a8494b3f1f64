#!/usr/bin/env python3
"""Side-by-side timing of `tvf basis -k K` against SciPy's `eigsh` shift-invert (ARPACK + SuperLU)
on the same mesh and the same matrices.

The reference solves the two scalar eigenproblems a Fourier basis of K fields needs, K/2
eigenpairs each: the potential pencil (S0, M0) (the cotan Laplacian for conforming elements) and
the co-potential pencil (S2, M2^-1) (the Crouzeix-Raviart Laplacian on edges), both exported by
`tvf operators`. Runs alternate (reference, tvf, reference, tvf, ...) so that a change of machine
load hits both alike; the script prints every run, the medians, their ratio and the load
(`uptime`) before and after. Absolute seconds do not travel between machines: compare ratios.

Usage:
    python3 papers/side_by_side/basis_vs_scipy.py MESH.obj [--runs 3] [--k 1000]
        [--tvf target/release/tvf] [--venv papers/side_by_side/.venv]

SciPy is imported from the running interpreter if it has it; otherwise a virtual environment
is created at --venv (once), SciPy is installed into it with pip, and the script re-runs itself
there.
"""

import argparse
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
REPOSITORY = HERE.parent.parent


def arguments():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("mesh", type=Path)
    parser.add_argument("--runs", type=int, default=3)
    parser.add_argument("--k", type=int, default=1000, help="fields of the tvf basis (K/2 eigenpairs per pencil for SciPy)")
    parser.add_argument("--tvf", type=Path, default=REPOSITORY / "target" / "release" / "tvf")
    parser.add_argument("--venv", type=Path, default=HERE / ".venv")
    return parser.parse_args()


def ensure_scipy(venv):
    """Re-executes this script in `venv` (created with SciPy if missing) unless SciPy imports."""
    try:
        import scipy  # noqa: F401

        return
    except ImportError:
        pass
    python = venv / "bin" / "python"
    if os.environ.get("TVF_SIDE_BY_SIDE_IN_VENV"):
        sys.exit(f"SciPy is still missing inside {venv}; remove that folder and try again")
    if not python.exists():
        print(f"creating {venv} with SciPy (once)", file=sys.stderr)
        subprocess.run([sys.executable, "-m", "venv", str(venv)], check=True)
        subprocess.run([str(python), "-m", "pip", "install", "--quiet", "scipy"], check=True)
    environment = dict(os.environ, TVF_SIDE_BY_SIDE_IN_VENV="1")
    os.execve(str(python), [str(python), *sys.argv], environment)


def uptime():
    return subprocess.run(["uptime"], capture_output=True, text=True).stdout.strip()


def export_operators(tvf, mesh, folder):
    subprocess.run([str(tvf), "operators", "-q", str(mesh), "-o", str(folder)], check=True)


def pencils(folder):
    """(name, A, mass diagonal) of the potential and the co-potential problem."""
    import scipy.io

    def read(name):
        return scipy.io.mmread(str(folder / f"{name}.mtx")).tocsc()

    potential = (read("S0"), read("M0").diagonal())
    co_potential = (read("S2"), 1.0 / read("M2").diagonal())
    return [("cotan (S0, M0)", *potential), ("Crouzeix-Raviart (S2, M2^-1)", *co_potential)]


def reference_seconds(problems, pairs):
    """Wall-clock seconds of eigsh shift-invert for `pairs` eigenpairs of every problem."""
    import scipy.sparse
    import scipy.sparse.linalg

    start = time.perf_counter()
    for _, a, mass in problems:
        # Just below the zero eigenvalue (A is singular), relative to the mean eigenvalue.
        sigma = -1e-6 * a.diagonal().sum() / mass.sum()
        values, _ = scipy.sparse.linalg.eigsh(
            a, k=pairs, M=scipy.sparse.diags(mass).tocsc(), sigma=sigma, which="LM"
        )
        if len(values) != pairs:
            raise RuntimeError(f"eigsh returned {len(values)} eigenpairs, not {pairs}")
    return time.perf_counter() - start


def tvf_seconds(tvf, mesh, k, output):
    start = time.perf_counter()
    subprocess.run([str(tvf), "basis", "-q", "-k", str(k), str(mesh), "-o", str(output)], check=True)
    return time.perf_counter() - start


def main():
    args = arguments()
    ensure_scipy(args.venv)
    if not args.tvf.exists():
        sys.exit(f"{args.tvf}: no tvf binary (build it with `cargo build --release -p tvf-cli`)")
    if not args.mesh.is_file():
        sys.exit(f"{args.mesh}: no such mesh file")
    print(f"mesh {args.mesh.name}, tvf basis -k {args.k} vs SciPy eigsh {args.k // 2} + {args.k // 2}")
    print(f"load before: {uptime()}")
    with tempfile.TemporaryDirectory(prefix="tvf-side-by-side-") as scratch:
        scratch = Path(scratch)
        export_operators(args.tvf, args.mesh, scratch / "operators")
        problems = pencils(scratch / "operators")
        for name, a, _ in problems:
            print(f"  {name}: n = {a.shape[0]}, nnz = {a.nnz}")
        reference, ours = [], []
        for run in range(args.runs):
            reference.append(reference_seconds(problems, args.k // 2))
            print(f"run {run + 1}: SciPy {reference[-1]:8.2f} s", flush=True)
            ours.append(tvf_seconds(args.tvf, args.mesh, args.k, scratch / "basis.tvfb"))
            print(f"run {run + 1}: tvf   {ours[-1]:8.2f} s", flush=True)
    median_reference = statistics.median(reference)
    median_ours = statistics.median(ours)
    print(f"median SciPy {median_reference:.2f} s, median tvf {median_ours:.2f} s, "
          f"ratio SciPy/tvf {median_reference / median_ours:.2f}")
    print(f"load after: {uptime()}")


if __name__ == "__main__":
    main()
