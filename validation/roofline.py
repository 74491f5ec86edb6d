"""Roofline of the benchmark rows: the work each run needs against what one core of this machine can do.

    python validation/roofline.py --markdown validation/roofline.md   # chain rows, sheets of 10 and 20 a side
    python validation/roofline.py --grids 10 20 40 --repeats 5 --sheet-repeats 2

The machine: its peak arithmetic rate, a 1024 × 1024 DGEMM on one thread (numpy's BLAS; SGEMM for the work
done in single precision), and its memory bandwidth, a 2 × 64 MB → 64 MB vector add (`numpy.add`, 24 bytes a
double), the least CPU time of five each. Every solver runs on one core, so one core's roofs are the limits
(OPENBLAS_NUM_THREADS=1 here).

A run: its base run (`solve(..., uncertainty=False)`), CPU time of this process (time.process_time, the
least of the repeats after one untimed run), and the work it did, counted from the run's own statistics
and the operation counts below. The limit is the larger of flops/peak and bytes/bandwidth; 'from the
limit' is CPU over that time: how far the run is from what the machine allows for the work it does
(the algorithm's work is not questioned here: fewer steps is a different figure).

Operation counts (flops; estimates where marked ≈, from the kernels' arithmetic, good to about ±50 %):

- in-house chain: ≈ 150 flops per slice per right-hand side (sines and cosines, the load, the springs,
  the 2×2 block-tridiagonal sweeps of dynamics.py and joints.py); Radau's O(n) Newton solve ≈ 150 flops
  per slice real, four times that complex, two per Newton iteration (≈ nfev/3 iterations), and its
  factorisation ≈ 100 flops per slice (× 4 complex) per LU;
- Exudyn chain (N coordinates of the kinematic tree): every residual or stage (one call of the force
  function each, counted) builds the tree's mass matrix (composite-rigid-body algorithm: N²/2 spatial
  transforms of ≈ 66 flops), its velocity terms (≈ 250 N) and the load (≈ 60 per slice); generalized-α
  adds a back-substitution (2N²) per evaluation and per Jacobian a dense LU ((2/3)N³) and N evaluations
  (numerical differentiation); DOPRI5 a dense LU and a back-substitution per stage;
- in-house sheet: ≈ 700 flops per tile per right-hand side (rotation matrices, two edge connectors per
  tile, the load); the triangular solves counted on the 6 × 6 block factors they read (block_lu.BlockFactors:
  2 flops an entry real, 8 complex; an entry's bytes streamed from memory when the pair of factors outgrows the
  last-level cache: 4 and 8 for the single-precision LU, sheet_radau.SINGLE_PRECISION_LU, 8 and 16 in double,
  the blocks' indices a 36th of that; where SuperLU solves, on nnz(L+U) with an index a nonzero: 8 and 12, 12
  and 20) and the factorisations from the
  factors' structure (Σ_k 2·|L_k|·|U_k|, × 4 complex), plus the two sparse products of each solve (double);
  the factorisations and triangular solves are held to the SGEMM peak when the LU is single;
- Exudyn sheet: every residual (Newton iterations + steps) ≈ 700 flops per tile as the in-house one, and a
  sparse back-substitution of its 6N coordinates, counted as the in-house factor of the same 6-per-tile
  graph (a proxy: Exudyn's own ordering is not visible); per Jacobian one such factorisation.
"""

from __future__ import annotations

import argparse
import os

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")  # one core: the roofs of a single-threaded run

import sys  # noqa: E402
import time  # noqa: E402
from pathlib import Path  # noqa: E402

import numpy as np  # noqa: E402

from lightsail_mbs import RunSettings, SailParameters, paper_case, paper_settings, solve  # noqa: E402
from lightsail_mbs.solvers.reduced import sheet_radau  # noqa: E402

sys.path.insert(0, str(Path(__file__).parent))
from sheet_profile import Counts  # noqa: E402  (the solve counter around the sheet's LU)

CHAIN = {  # paper case -> label (validation/benchmark.py's rows)
    "torsion-stable": "torsion E=4.5e13, 6 s (stable)",
    "torsion-soft": "torsion E=4.5e9, to failure",
    "tnt-stable": "tnt T=3.34e-3 N, 6 s (stable)",
    "tnt-soft": "tnt T=3.34e-8 N, to failure",
    "rigid": "rigid n=40 ν=1.5, 10 ms",
}
SLICE_RHS, SLICE_SOLVE, SLICE_FACTOR = 150.0, 150.0, 100.0  # ≈ flops per slice (module docstring)
CRBA_TRANSFORM, TREE_VELOCITY, SLICE_LOAD = 66.0, 250.0, 60.0
TILE_RHS = 700.0


def last_level_cache() -> float:
    """Bytes of the last-level cache (Linux sysfs; 32 MB when it cannot be read)."""
    sizes = []
    for entry in Path("/sys/devices/system/cpu/cpu0/cache").glob("index*/size"):
        text = entry.read_text().strip()
        sizes.append(
            float(text[:-1]) * {"K": 2**10, "M": 2**20}.get(text[-1], 1.0) if text[-1].isalpha() else float(text)
        )
    return max(sizes) if sizes else 32.0 * 2**20


def machine(repeats: int = 5) -> dict:
    """Peak flop/s of one core (1024² DGEMM; `flops_single`: SGEMM), its bandwidth (bytes/s of a 64 MB vector
    add), best of repeats, and the last-level cache (bytes)."""
    n = 1024
    peaks = {}
    for name, dtype in (("flops", np.float64), ("flops_single", np.float32)):
        a, b = np.random.rand(n, n).astype(dtype), np.random.rand(n, n).astype(dtype)
        a @ b
        peaks[name] = max(2.0 * n**3 / _best(lambda a=a, b=b: a @ b, repeats), 1.0)
    size = 8 * 2**20
    x, y, z = np.random.rand(size), np.random.rand(size), np.random.rand(size)
    np.add(x, y, out=z)
    bandwidth = 24.0 * size / _best(lambda: np.add(x, y, out=z), repeats)
    return {**peaks, "bandwidth": bandwidth, "cache": last_level_cache()}


def _best(work, repeats: int) -> float:
    """The least CPU time (s) of work() over repeats: on a shared machine the wall clock also counts the
    time the probe waits for a core."""
    best = float("inf")
    for _ in range(repeats):
        start = time.process_time()
        work()
        best = min(best, time.process_time() - start)
    return best


def timed(params, solver: str, settings, repeats: int):
    """(least CPU s, Result) of the base run, after one untimed run."""
    result = solve(params, solver, settings, uncertainty=False)
    best = float("inf")
    for _ in range(repeats):
        start = time.process_time()
        result = solve(params, solver, settings, uncertainty=False)
        best = min(best, time.process_time() - start)
    return best, result


def reduced_chain_work(p, info: dict) -> tuple[float, float]:
    """(flops, bytes) of an in-house chain run from its statistics (bytes: everything fits in cache, 0)."""
    n, nfev = p.n, info.get("nfev", 0)
    flops = nfev * n * SLICE_RHS
    if info.get("method") == "Radau":
        flops += (nfev / 3.0) * n * SLICE_SOLVE * 5.0 + info.get("nlu", 0) * n * SLICE_FACTOR * 2.5
    return flops, 0.0


def exudyn_chain_work(p, info: dict, evaluations: int) -> tuple[float, float]:
    """(flops, bytes) of an Exudyn chain run: `evaluations` residuals or stages (force function calls)."""
    size = info["coordinates"]
    per = 0.5 * size * size * CRBA_TRANSFORM + TREE_VELOCITY * size + SLICE_LOAD * p.n
    if info.get("method") == "DOPRI5":
        per += (2.0 / 3.0) * size**3 + 2.0 * size * size
        return evaluations * per, 0.0
    jacobians = info.get("njev", 0)
    flops = evaluations * (per + 2.0 * size * size) + jacobians * ((2.0 / 3.0) * size**3 + size * per)
    return flops, 0.0


def counting_force():
    """Wrap the Exudyn chain's force function to count its calls; returns (counter list, undo)."""
    from lightsail_mbs.solvers.exudyn import chain

    original, calls = chain.generalized_force, [0]

    def generalized_force(p, layout, *beam_factor_of):
        force = original(p, layout, *beam_factor_of)

        def counted(q, q_t=None, t=0.0):
            calls[0] += 1
            return force(q, q_t, t)

        return counted

    chain.generalized_force = generalized_force

    def undo():
        chain.generalized_force = original

    return calls, undo


def chain_rows(roof: dict, repeats: int) -> list[dict]:
    rows = []
    for case, label in CHAIN.items():
        params, settings = paper_case(case), paper_settings(case)
        cpu, result = timed(params, "reduced", settings, repeats)
        flops, data = reduced_chain_work(params, result.info)
        rows.append(row(label, "in-house", cpu, result.info, flops, data, roof))
        cpu, result = timed(params, "exudyn", settings, repeats)
        calls, undo = counting_force()
        try:
            solve(params, "exudyn", settings, uncertainty=False)
        finally:
            undo()
        flops, data = exudyn_chain_work(params, result.info, calls[0])
        rows.append(row(label, "Exudyn", cpu, result.info, flops, data, roof))
    return rows


def factor_work(lu) -> tuple[int, float]:
    """(nnz of L + U, flops of the factorisation from its structure: Σ_k 2 |L_k| |U_k|, real)."""
    lower = np.diff(lu.L.tocsc().indptr) - 1
    upper = np.diff(lu.U.tocsr().indptr) - 1
    return int(lu.L.nnz + lu.U.nnz), float(2.0 * np.sum(lower * upper) + lu.L.nnz)


def sheet_rows(grids, roof: dict, repeats: int) -> list[dict]:
    rows = []
    for grid in grids:
        params = SailParameters(model="sheet", n=grid, ny=grid, youngs_modulus=4.5e9)
        settings = RunSettings(t_final=3.0)
        label = f"sheet {grid}×{grid}, soft, to failure"
        tiles = grid * grid
        cpu, result = timed(params, "reduced", settings, repeats)
        counter = Counts()
        undo = counter.install()
        try:
            solve(params, "reduced", settings, uncertainty=False)
        finally:
            undo()
        (nnz, lu_flops), system = factor_work(counter.factor[False][0]), counter.factor[False][1]
        products = 2.0 * (system.AX.nnz + system.B.nnz)
        info = result.info
        single = sheet_radau.SINGLE_PRECISION_LU
        if counter.block_nnz:  # the triangular solves read the block factors
            read, (real_bytes, complex_bytes) = counter.block_nnz, ((4.0, 8.0) if single else (8.0, 16.0))
        else:
            read, (real_bytes, complex_bytes) = nnz, ((8.0, 12.0) if single else (12.0, 20.0))
        lu = info["nlu"] / 2 * lu_flops * (1 + 4) + (counter.solves[False] * 2.0 + counter.solves[True] * 8.0) * read
        flops = info["nfev"] * tiles * TILE_RHS + (counter.solves[False] + 2 * counter.solves[True]) * products
        streamed = (real_bytes + complex_bytes) * read > roof["cache"]  # the pair of factors fits in the cache, or not
        data = (counter.solves[False] * real_bytes + counter.solves[True] * complex_bytes) * read * streamed
        flops += 0.0 if single else lu
        rows.append(row(label, "in-house", cpu, info, flops, data, roof, single_flops=lu if single else 0.0))
        cpu, result = timed(params, "exudyn", settings, repeats)
        info = result.info
        residuals = info["newton_iterations"] + info["steps"]
        flops = residuals * (tiles * TILE_RHS + 2.0 * nnz) + info["njev"] * lu_flops
        streamed = 20.0 * nnz > roof["cache"]  # Exudyn's factors in double
        rows.append(row(label, "Exudyn", cpu, info, flops, residuals * 12.0 * nnz * streamed, roof))
    return rows


def row(label, solver, cpu, info, flops, data, roof, single_flops: float = 0.0) -> dict:
    """A table row: `flops` in double and `single_flops` in single precision, `data` bytes streamed."""
    arithmetic = flops / roof["flops"] + single_flops / roof["flops_single"]
    limit = max(arithmetic, data / roof["bandwidth"])
    bound = "memory" if data / roof["bandwidth"] > arithmetic else "arithmetic"
    flops += single_flops
    steps = info.get("steps", "—")
    print(f"{label:36s} {solver:8s} cpu {cpu:8.4f} s  limit {limit:.2e} s  ({cpu / limit:,.0f}x)", flush=True)
    return dict(label=label, solver=solver, cpu=cpu, steps=steps, flops=flops, data=data, limit=limit, bound=bound)


def markdown(rows: list[dict], roof: dict, command: str, repeats: tuple[int, int]) -> str:
    lines = [
        "# Roofline: each benchmark row against what the machine can do",
        "",
        f"Generated by `{command}` (validation/roofline.py: the operation counts and what they include are in its "
        "docstring). One core of this machine: peak "
        f"{roof['flops'] / 1e9:.1f} GFlop/s (1024² DGEMM, one thread; {roof['flops_single'] / 1e9:.1f} SGEMM, the "
        "single-precision LU's), memory bandwidth "
        f"{roof['bandwidth'] / 1e9:.1f} GB/s (64 MB vector add), last-level cache {roof['cache'] / 2**20:.0f} MB; "
        f"load average {os.getloadavg()[0]:.1f} on "
        f"{os.cpu_count()} cores at the end. CPU: time.process_time of the base run, the least of {repeats[0]} "
        f"timed runs (chains) or {repeats[1]} (sheets) after an untimed one. "
        "The limit is the larger of flops/peak and bytes/bandwidth for the work the run does; 'from the limit' "
        "is CPU over it.",
        "",
        "| row | solver | CPU (s) | steps | work (Mflop) | factor bytes streamed (MB) | bound | limit (s) "
        "| from the limit |",
        "|---|---|---:|---:|---:|---:|---|---:|---:|",
    ]
    for r in rows:
        lines.append(
            f"| {r['label']} | {r['solver']} | {r['cpu']:.4f} | {r['steps']} | {r['flops'] / 1e6:,.1f} "
            f"| {r['data'] / 1e6:,.1f} | {r['bound']} | {r['limit']:.2e} | {r['cpu'] / r['limit']:,.0f}× |"
        )
    return "\n".join(lines) + "\n"


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--grids", nargs="*", type=int, default=[10, 20], help="sheet rows: tiles a side")
    parser.add_argument("--repeats", type=int, default=3, help="timed runs per chain row")
    parser.add_argument("--sheet-repeats", type=int, default=1, help="timed runs per sheet row")
    parser.add_argument("--markdown", type=Path, help="write the table to this file (validation/roofline.md)")
    args = parser.parse_args(argv)
    if args.repeats < 1 or args.sheet_repeats < 1:
        parser.error("--repeats and --sheet-repeats must be ≥ 1")
    roof = machine()
    print(f"peak {roof['flops'] / 1e9:.1f} GFlop/s, bandwidth {roof['bandwidth'] / 1e9:.1f} GB/s", flush=True)
    rows = chain_rows(roof, args.repeats) + sheet_rows(args.grids, roof, args.sheet_repeats)
    command = "python validation/roofline.py" + "".join(f" {a}" for a in (argv or sys.argv[1:]))
    text = markdown(rows, roof, command, (args.repeats, args.sheet_repeats))
    print(text)
    if args.markdown:
        args.markdown.write_text(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
