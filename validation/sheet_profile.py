"""Where the in-house sheet solver spends its CPU: `nice -n 10 python validation/sheet_profile.py [--grids 20 40]`.

The paper's soft sail (E = 4.5e9 Pa, 1-D sine ν = 1.5) on nx × nx tiles, run to failure by the in-house
solver with its defaults, once warm in this process and once more under cProfile with the process CPU clock
(time.process_time), its time grouped by what the work is: the sparse triangular solves of the Newton
iterations and the error estimate (block_lu), the factorisations (SuperLU, and the copy of its factors into
blocks), the two sparse products of each solve
(A_X, B), the right-hand sides (the compiled kernel; those of the coloured finite-difference Jacobian
counted apart from the count of Jacobians × colours × 13), the sampling and unpacking of the output, and
the rest. The counts are the run's: steps, Newton iterations (one complex solve each), solves,
factorisations, Jacobians, right-hand sides, and the size of the factors (nnz(L + U) of the real one).
Writes validation/sheet_profile.md.
"""

from __future__ import annotations

import argparse
import cProfile
import os

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import pstats  # noqa: E402
import sys  # noqa: E402
import time  # noqa: E402
from pathlib import Path  # noqa: E402

import numpy as np  # noqa: E402

from lightsail_mbs import RunSettings, SailParameters, solve  # noqa: E402
from lightsail_mbs.solvers.reduced import sheet_radau  # noqa: E402
from lightsail_mbs.solvers.reduced.sheet import STATE  # noqa: E402

HERE = Path(__file__).resolve().parent
GROUPS = {  # category -> (parts of built-in functions' names, names of Python functions) it holds
    "triangular solves": (("method 'solve' of 'SuperLU'",), ("_solve",)),
    "factorisations": (("gstrf",), ("from_superlu", "_gather_factor", "_invert_diagonal")),
    "sparse products": (("csr_matvec",), ()),
    "right-hand sides": ((), ("rhs_kernel",)),
    "output (dense output, sampling, unpacking)": ((), ("unpack_into", "sol", "plane_offsets", "unpack")),
}


class Counts:
    """Solves (real, complex), factorisations, the real factor's size and the first factor of each kind with its
    system (keyed by complex or not), counted around sheet_radau.ReducedLU (also validation/roofline.py's)."""

    def __init__(self):
        self.solves, self.factorisations, self.nnz = {False: 0, True: 0}, 0, 0
        self.block_nnz = 0  # entries of the 6 × 6 block factors the triangular solves read (0: SuperLU's own)
        self.factor = {}

    def install(self):
        original, counts, factor = sheet_radau.ReducedLU, self, sheet_radau.splu
        made = []

        def kept(*args, **kwargs):  # SuperLU's factorisation, kept here (ReducedLU keeps only its blocks)
            made[:] = [factor(*args, **kwargs)]
            return made[0]

        class Counted(original):
            def __init__(self, system, mu):
                super().__init__(system, mu)
                counts.factorisations += 1
                counts.factor.setdefault(bool(np.iscomplexobj(mu)), (made[0], system))
                if not np.iscomplexobj(mu):
                    counts.nnz = max(counts.nnz, self.nnz)
                    if self.blocks is not None:
                        counts.block_nnz = max(counts.block_nnz, self.blocks.nnz)

            def solve(self, f):
                counts.solves[bool(np.iscomplexobj(self.mu))] += 1
                return super().solve(f)

        sheet_radau.ReducedLU, sheet_radau.splu = Counted, kept

        def undo():
            sheet_radau.ReducedLU, sheet_radau.splu = original, factor

        return undo


def grouped(profile: cProfile.Profile) -> dict:
    """CPU seconds (own time) of each group and of everything else."""
    stats = pstats.Stats(profile).stats
    total = sum(value[2] for value in stats.values())
    out = {}
    for group, (parts, names) in GROUPS.items():
        out[group] = sum(
            value[2]
            for (_, _, name), value in stats.items()
            if name in names or (name.startswith("<") and any(part in name for part in parts))
        )
    out["rest"] = total - sum(out.values())
    return out


def profile(grid: int) -> dict:
    params = SailParameters(model="sheet", n=grid, ny=grid, youngs_modulus=4.5e9)
    settings = RunSettings(t_final=3.0)
    solve(SailParameters(model="sheet", n=4, ny=4, youngs_modulus=4.5e9), "reduced", settings, uncertainty=False)
    start = time.process_time()
    solve(params, "reduced", settings, uncertainty=False)
    plain = time.process_time() - start
    counts = Counts()
    undo = counts.install()
    profiler = cProfile.Profile(time.process_time)
    try:
        start = time.process_time()
        profiler.enable()
        result = solve(params, "reduced", settings, uncertainty=False)
        profiler.disable()
        cpu = time.process_time() - start
    finally:
        undo()
    from lightsail_mbs.solvers.reduced.sheet import SheetModel

    colours = len(SheetModel(params).groups)
    info = result.info
    jacobian_rhs = info["njev"] * colours * STATE
    return dict(
        grid=grid,
        cpu=cpu,
        plain=plain,
        failure_time=result.failure_time,
        info=info,
        counts=counts,
        groups=grouped(profiler),
        jacobian_share=jacobian_rhs / max(info["nfev"], 1),
        jacobian_rhs=jacobian_rhs,
    )


def markdown(rows: list[dict], command: str) -> str:
    head = [
        "# Where the in-house sheet solver spends its CPU",
        "",
        f"Generated by `{command}`. The paper's soft sail on nx × nx tiles to failure (in-house solver, "
        "defaults): the CPU of a warm run, then of one under cProfile with the process CPU clock (the "
        "profiler's own overhead lands in 'rest'); own CPU time of the functions grouped by the work they do "
        "(shares of the profiled run; the Jacobian's share of the right-hand sides is its count over all "
        f"of them). Load average {os.getloadavg()[0]:.1f} on {os.cpu_count()} cores at the end.",
        "",
        "| grid | CPU (s) | profiled (s) | steps | Newton it. | solves real · complex | factorisations · Jacobians "
        "| RHS (of which Jacobian) | nnz(L+U) | " + " | ".join(f"{g} (s)" for g in (*GROUPS, "rest")) + " |",
        "|---|---:|---:|---:|---:|---|---|---|---:|" + "---:|" * (len(GROUPS) + 1),
    ]
    lines = []
    for r in rows:
        info, c = r["info"], r["counts"]
        groups = " | ".join(f"{r['groups'][g]:.2f} ({r['groups'][g] / r['cpu']:.0%})" for g in (*GROUPS, "rest"))
        lines.append(
            f"| {r['grid']}×{r['grid']} | {r['plain']:.2f} | {r['cpu']:.2f} | {info['steps']} | {c.solves[True]} "
            f"| {c.solves[False]} · {c.solves[True]} | {c.factorisations} · {info['njev']} "
            f"| {info['nfev']} ({r['jacobian_rhs']}) | {c.nnz:,} | {groups} |"
        )
    per_step = [
        f"* {r['grid']} × {r['grid']}: {1e3 * r['cpu'] / r['info']['steps']:.1f} ms CPU a step, "
        f"{r['counts'].solves[True] / r['info']['steps']:.2f} Newton iterations a step, "
        f"failure at {r['failure_time']:.9g} s"
        for r in rows
    ]
    return "\n".join([*head, *lines, "", *per_step]) + "\n"


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--grids", nargs="*", type=int, default=[20, 40])
    parser.add_argument("--out", default=str(HERE / "sheet_profile.md"))
    args = parser.parse_args(argv)
    rows = []
    for grid in args.grids:
        rows.append(profile(grid))
        print(f"{grid}x{grid}: {rows[-1]['cpu']:.2f} s CPU", {k: round(v, 2) for k, v in rows[-1]["groups"].items()})
    command = "nice -n 10 python validation/sheet_profile.py" + "".join(
        f" {a}" for a in (argv if argv is not None else sys.argv[1:])
    )
    text = markdown(rows, command)
    Path(args.out).write_text(text)
    print(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
