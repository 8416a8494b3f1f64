"""Times tvf.eigsh against scipy.sparse.linalg.eigsh on the cotan pencil of hand.obj (k = 500).

    python python/benchmarks/eigsh_hand.py [--mesh ../shared/meshes/hand.obj] [-k 500]

Both solve S0 x = l M0 x (P1 cotan stiffness, barycentric masses; 6,338 unknowns on hand.obj)
for the lowest k pairs in one run: SciPy by shift-invert Lanczos (ARPACK, sigma below zero,
which="LM"), tvf by spectrum slicing. Prints both times, the largest eigenvalue difference and
the machine load (uptime) before and after: on a shared machine concurrent jobs distort both.
"""

import argparse
import pathlib
import subprocess
import time

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as sla

import tvf

DEFAULT_MESH = pathlib.Path(__file__).resolve().parents[3] / "shared" / "meshes" / "hand.obj"


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--mesh", default=str(DEFAULT_MESH))
    parser.add_argument("-k", type=int, default=500)
    parser.add_argument("--sigma", type=float, default=-1e-3, help="SciPy's shift (below the zero eigenvalue)")
    args = parser.parse_args()

    print("load before:", subprocess.run(["uptime"], capture_output=True, text=True).stdout.strip())
    mesh = tvf.Mesh.load(args.mesh)
    ops = tvf.operators(mesh, "conforming-barycentric")
    A, m = ops["S0"], ops["M0"].diagonal()
    print(f"{args.mesh}: {A.shape[0]} unknowns, k = {args.k}")

    start = time.perf_counter()
    ours, _ = tvf.eigsh(A, m, args.k)
    tvf_seconds = time.perf_counter() - start

    start = time.perf_counter()
    theirs = sla.eigsh(A.tocsc(), k=args.k, M=sp.diags(m).tocsc(), sigma=args.sigma, which="LM", return_eigenvectors=True)[0]
    scipy_seconds = time.perf_counter() - start
    theirs = np.sort(theirs)

    difference = np.max(np.abs(ours - theirs))
    print(f"tvf.eigsh                 {tvf_seconds:8.2f} s")
    print(f"scipy.sparse.linalg.eigsh {scipy_seconds:8.2f} s (shift-invert, sigma {args.sigma:g})")
    print(f"max |eigenvalue difference| {difference:.2e} (largest eigenvalue {theirs[-1]:.6g})")
    print("load after: ", subprocess.run(["uptime"], capture_output=True, text=True).stdout.strip())


if __name__ == "__main__":
    main()
