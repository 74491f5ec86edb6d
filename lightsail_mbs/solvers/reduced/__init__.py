"""The in-house reduced-Lagrangian solver: O(n) chain dynamics in minimal coordinates, compiled integrators.

numba's first load of any compiled function initialises its CPU target, which imports numba.np.arraymath;
that module probes at import whether BLAS is available by importing scipy.linalg.cython_blas, which
loads all of scipy.linalg (≈ 0.2 s of CPU, a fifth of a warm `lightsail-mbs simulate`). The reduced
solver's kernels use no BLAS and scipy (a dependency) provides it, so the probe is answered here without
the import (`_answer_blas_probe`); numba's linear algebra still imports scipy's BLAS when it compiles
anything that needs it.
"""

from __future__ import annotations

import importlib.util
import sys


def _answer_blas_probe() -> None:
    """Import numba.np.arraymath with its BLAS probe (numba.np.linalg.ensure_blas) answered "available"
    when scipy is installed; numba.np.linalg keeps its own ensure_blas for the functions that use BLAS."""
    if "numba.np.arraymath" in sys.modules or importlib.util.find_spec("scipy") is None:
        return
    try:
        from numba.np import linalg
    except ImportError:
        return
    probe = getattr(linalg, "ensure_blas", None)
    if probe is None:
        return
    linalg.ensure_blas = lambda: None
    try:
        import numba.np.arraymath  # noqa: F401 - its import-time probe sees BLAS available
    finally:
        linalg.ensure_blas = probe


_answer_blas_probe()
