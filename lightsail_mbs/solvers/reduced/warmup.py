"""Compile the reduced solver's kernels ahead of use, and say so when a run has to compile them.

The kernels are numba functions with ``cache=True``: compiled once, their machine code is stored next to
their source files (``__pycache__/*.nbi, *.nbc``, keyed by a hash of the source, the numba version and
the CPU) and loaded in a fraction of a second by every later process. Compiling them all takes tens of
seconds, so the package compiles them when it is installed: the build hook of ``setup.py`` runs
``python -m lightsail_mbs.solvers.reduced.warmup`` on the files being installed (a regular install) or
on the source tree (an editable install). It needs only numpy and numba.

If a run still has to compile (the cache was not written at install, the numba version or the CPU
changed, or the sources were edited), :func:`compile_notice` prints one line on stderr while it waits.

    python -m lightsail_mbs.solvers.reduced.warmup       # compile (or load) everything now
"""

from __future__ import annotations

import sys
import time
from contextlib import contextmanager

# compile time of each integrator's kernels on the reference machine (CPU s, which is the wall time when idle;
# docs/reports/benchmark.md); the message quotes it
COMPILE_SECONDS = {"DOP853": 10, "Radau": 35}
PACKAGE = "lightsail_mbs"
_announced = False


class _CompileListener:
    """numba event listener (numba.core.event.Listener's interface): announce the first compilation
    of a function of this package."""

    def __init__(self, method: str):
        self.method = method
        self.compiled = False

    def notify(self, event):
        if event.is_start:
            self.on_start(event)

    def on_start(self, event):
        global _announced
        dispatcher = event.data.get("dispatcher")
        module = getattr(getattr(dispatcher, "py_func", None), "__module__", "") or ""
        if not module.startswith(PACKAGE):
            return
        self.compiled = True
        if not _announced:
            _announced = True
            estimate = COMPILE_SECONDS.get(self.method, max(COMPILE_SECONDS.values()))
            print(
                f"lightsail-mbs: compiling the reduced solver ({self.method}; once, ~{estimate} s)…",
                file=sys.stderr,
                flush=True,
            )

    def on_end(self, event):
        pass


def _listener(method: str):
    from numba.core import event

    class Listener(_CompileListener, event.Listener):
        pass

    return Listener(method)


@contextmanager
def compile_notice(method: str):
    """Within this block, the first numba compilation of the package's kernels prints one line on stderr
    (nothing happens when every kernel loads from the cache)."""
    from numba.core import event

    listener = _listener(method)
    start = time.perf_counter()
    event.register("numba:compile", listener)
    try:
        yield listener
    finally:
        event.unregister("numba:compile", listener)
        if listener.compiled:
            print(
                f"lightsail-mbs: compiled in {time.perf_counter() - start:.0f} s; later runs load it from the cache",
                file=sys.stderr,
                flush=True,
            )


def compile_all() -> float:
    """Compile (or load from the cache) every kernel of the reduced solver with the argument types of its
    runs: both integrators on a torsion chain, Radau on the extensible TnT chain, the right-hand side on
    one state and on a batch, and its dense Jacobian (scipy's implicit methods). Returns the wall time (s)."""
    import numpy as np

    from lightsail_mbs.base.settings import RunSettings
    from lightsail_mbs.model.cases import paper_case
    from lightsail_mbs.solvers import solve
    from lightsail_mbs.solvers.reduced.dynamics import ChainDynamics
    from lightsail_mbs.solvers.reduced.kinematics import ChainModel

    start = time.perf_counter()
    settings = RunSettings(t_final=0.002)
    for case, method in [("torsion-soft", "DOP853"), ("torsion-soft", "Radau"), ("tnt-soft", "Radau")]:
        solve(paper_case(case, n=5), "reduced", settings, method=method)
    dynamics = ChainDynamics(ChainModel.from_params(paper_case("torsion-soft", n=5)))
    y = np.zeros(2 * dynamics.model.dof)
    dynamics.rhs(0.0, y)
    dynamics.rhs(0.0, np.zeros((y.size, 2)))
    dynamics.jacobian(0.0, y, np.ones(y.size))
    return time.perf_counter() - start


def main() -> int:
    print(f"lightsail-mbs: compiling the reduced solver's kernels into numba's cache ({__file__})", flush=True)
    seconds = compile_all()
    print(f"lightsail-mbs: reduced solver ready ({seconds:.1f} s)", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
