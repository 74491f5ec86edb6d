"""Radau IIA (order 5, adaptive) for the sheet's mechanical first-order system, with a velocity-reduced
sparse linear solve.

The method is scipy.integrate.Radau's (Hairer & Wanner, *Solving ODEs II*, Sec. IV.8: simplified
Newton on the collocation system, transformed into one real and one complex linear system, embedded
error estimate, Gustafsson's step predictor; coefficients in tableaus.py), with five changes that make
it fast on the sheet's sparse Jacobian (measured at 20 × 20 tiles, soft sail to failure: 117 s with
scipy's Radau as is, 3.5 s CPU with the first four; docs: sheet):

1. **Velocity-reduced solve.** For y = (X, V) with Ẋ = B(X) V (centre rates, quaternion rates
   ½ Q(q) ω_b) and V̇ = a(X, V), J = [[∂(BV)/∂X, B], [A_X, A_V]]. The first block is O(|ω|) and is
   dropped from the Newton matrix (simplified Newton tolerates an approximate matrix). Then::

       μ x_X − B x_V = f_X,   μ x_V − A_X x_X − A_V x_V = f_V

   gives x_X = (f_X + B x_V)/μ and::

       (μ I − A_V − A_X B/μ) x_V = f_V + A_X f_X/μ,

   a system in the 6 velocity unknowns per tile instead of all 13 states (LU fill 1.9 M → 0.5 M).
2. **Quantised steps** h = h_max/2^k, with the LU pair of each k cached while the Jacobian is frozen
   (scipy refactorises whenever h changes, at almost every step of a transient). Steps land exactly on
   the grid j·h_max, so output samples on that grid are step end points (order 5); a final time off
   that grid is reached by one partial step.
3. **Jacobian refresh only when simplified Newton contracts slower than JACOBIAN_RATE** (scipy: 1e-3
   after more than two iterations), with up to NEWTON_MAXITER iterations: tile rotations of 1e-4 rad
   give contraction rates of 1e-2–0.3, and scipy's rule refreshed 68–174 times per run.
4. SuperLU with a minimum-degree ordering of the bodies (each body's 6 unknowns kept together) on the
   structurally symmetric pattern and no pivoting (μI dominates the diagonal), in single precision, its
   factors copied into 6 × 6 blocks for the triangular solves (ReducedLU, block_lu).
5. The first Newton increment of a step may already be converged, judged by the contraction rate θ last
   measured (RADAU5's FACCON = θ/(1 − θ), raised to the power 0.8 at every step so that an old rate counts
   for less; scipy's Radau always iterates at least twice): at 20 × 20 tiles 25 % fewer iterations.
"""

from __future__ import annotations

import heapq
from contextlib import contextmanager

import numpy as np
import scipy.sparse as sp
from numpy.linalg import norm
from scipy.sparse.linalg import splu

from lightsail_mbs.solvers.reduced import block_lu, tableaus

C = tableaus.RADAU_C
E = tableaus.RADAU_E
T = tableaus.RADAU_T
TI = tableaus.RADAU_TI
TI_REAL = TI[0]
TI_COMPLEX = TI[1] + 1j * TI[2]
P = tableaus.RADAU_P
MU_REAL = tableaus.RADAU_MU_REAL
MU_COMPLEX = tableaus.RADAU_MU_COMPLEX
MIN_FACTOR, MAX_FACTOR = 0.2, 10.0
EPS = np.finfo(float).eps
JACOBIAN_RATE = 0.3  # refresh the frozen Jacobian when simplified Newton contracts slower than this
NEWTON_MAXITER = 20  # iterations per step (a fresh Jacobian and its LUs cost ~100 iterations at 20 × 20)
# Newton has converged once an increment is this fraction of the tolerance, whatever the rate: at the
# round-off floor of a pre-stressed sheet (initial_equilibrium, large internal forces in balance) the
# increments stagnate at ~1e-9 of the tolerance with rates of 0.9–1; the rate test alone reads that as
# divergence and rejects the step (measured on 6 × 6 tiles over 0.1 s: 43,000 steps, 87 % rejected,
# with the rate test alone; 25 steps with this floor)
NEGLIGIBLE = 1e-3
FACCON_RATE = 0.99  # a rate measured below this sets the next steps' first-iteration test (RADAU5's limit)
CARRY_RATE = True  # the first Newton increment may converge, judged by the last measured rate (RADAU5)
SINGLE_PRECISION_LU = True  # the reduced LU in float32 / complex64 (ReducedLU)
BODY_VELOCITIES = 6  # unknowns per body in the reduced system: v and ω_b
MAX_LEVEL = 40  # the finest step is h_max / 2^MAX_LEVEL; time is kept as an integer count of those


def predict_factor(h, h_old, error, error_old) -> float:
    """Gustafsson's step-size predictor (Hairer & Wanner II, Sec. IV.8, Eq. 8.25)."""
    if error_old is None or h_old is None or error == 0:
        multiplier = 1.0
    else:
        multiplier = h / h_old * (error_old / error) ** 0.25
    with np.errstate(divide="ignore"):
        return min(1.0, multiplier) * error**-0.25


def solve_collocation(fun, t, y, h, Z0, scale, tol, lu_real, lu_complex, faccon=None):
    """Simplified Newton on the transformed collocation system (scipy's solve_collocation_system) with
    NEWTON_MAXITER iterations, stopping early only when it diverges (rate ≥ 0.9) or cannot reach tol;
    from the second iteration on, an increment below NEGLIGIBLE · tol is converged whatever the rate.
    The first increment is converged when faccon · ‖ΔW‖ < tol, faccon = θ/(1 − θ) from an earlier step's
    rate θ (RADAU5's FACCON, Hairer & Wanner II, Sec. IV.8: the error left after an increment is bounded
    by θ/(1 − θ) of it); None: the first increment never is. Returns (converged, iterations, Z, rate)."""
    n = y.shape[0]
    m_real = MU_REAL / h
    m_complex = MU_COMPLEX / h
    W = TI.dot(Z0)
    Z = Z0
    F = np.empty((3, n))
    ch = h * C
    dW = np.empty_like(W)
    norm_old, rate, converged = None, None, False
    for k in range(NEWTON_MAXITER):
        for i in range(3):
            F[i] = fun(t + ch[i], y + Z[i])
        if not np.all(np.isfinite(F)):
            break
        dW_real = lu_real.solve(F.T.dot(TI_REAL) - m_real * W[0])
        dW_complex = lu_complex.solve(F.T.dot(TI_COMPLEX) - m_complex * (W[1] + 1j * W[2]))
        dW[0] = dW_real
        dW[1] = dW_complex.real
        dW[2] = dW_complex.imag
        dW_norm = norm(dW / scale) / np.sqrt(dW.size)
        if norm_old is not None:
            rate = dW_norm / norm_old
        at_floor = rate is not None and dW_norm <= NEGLIGIBLE * tol
        if (
            not at_floor
            and rate is not None
            and (rate >= 0.9 or rate ** (NEWTON_MAXITER - k) / (1 - rate) * dW_norm > tol)
        ):
            break
        W += dW
        Z = T.dot(W)
        contraction = faccon if rate is None else rate / (1 - rate)
        if dW_norm == 0 or at_floor or (contraction is not None and contraction * dW_norm < tol):
            converged = True
            break
        norm_old = dW_norm
    return converged, k + 1, Z, rate


@contextmanager
def small_pages():
    """numpy's large arrays allocated in this block without its transparent-huge-page advice. On a machine whose
    memory is fragmented the kernel compacts memory to give an advised region its 2 MB pages at the first touch:
    measured on this (shared) machine, the first touch of 2 GB took 3.7–5.5 s with the advice and 0.8 s without
    (0.14 s when huge pages were free). The sheet's factors (~0.1 GB each at 100 × 100 tiles, a new pair per step
    level and Jacobian) and its samples (GBs) are written once each, where that compaction dominated."""
    core = getattr(np, "_core", None) or getattr(np, "core", None)  # numpy ≥ 2: _core; 1.x: core
    advise = getattr(getattr(core, "multiarray", None), "_set_madvise_hugepage", None)
    previous = advise(False) if advise is not None else None
    try:
        yield
    finally:
        if advise is not None:
            advise(previous)


def empty_small_pages(shape, dtype=float) -> np.ndarray:
    """np.empty(shape, dtype) allocated in small_pages."""
    with small_pages():
        return np.empty(shape, dtype)


class ReducedSystem:
    """The frozen Jacobian's blocks A_X, A_V, B and K = A_X B, the index sets of X and V, and the body pattern of
    the reduced matrix with its elimination order and symbolic factorisation (block_lu.BlockPattern;
    `pattern`: an earlier system's, reused when the pattern is the same).

    products(complex) gives A_X and B for the right-hand sides of that kind: for the complex system their
    complex copies, made once per Jacobian (a real sparse matrix times a complex vector converts the
    matrix at every product: 8 ms a product at 100 × 100 tiles; the converted product is the same
    arithmetic, so the same numbers)."""

    def __init__(self, J: sp.spmatrix, B: sp.spmatrix, X: np.ndarray, V: np.ndarray, pattern=None):
        rows = J.tocsr()[V]
        self.AX = rows[:, X].tocsr()
        self.AV = rows[:, V].tocsc()
        self.B = B.tocsr()
        self.K = (self.AX @ self.B).tocsc()
        self.X, self.V = X, V
        self.n = J.shape[0]
        self.identity = sp.identity(len(V), format="csc")
        graph = block_lu.body_graph(abs(self.AV) + abs(self.K), BODY_VELOCITIES)
        self.pattern = pattern if pattern is not None and pattern.matches(graph) else block_lu.BlockPattern(graph)
        self.order = (BODY_VELOCITIES * self.pattern.order[:, None] + np.arange(BODY_VELOCITIES)).ravel()
        self._complex = None

    def products(self, complex_: bool):
        """(A_X, B) for real or complex right-hand sides."""
        if not complex_:
            return self.AX, self.B
        if self._complex is None:
            self._complex = (self.AX.astype(np.complex128), self.B.astype(np.complex128))
        return self._complex


class ReducedLU:
    """The LU of μ I − A_V − K/μ and the back-substitution of the full system (μ I − J) x = f.

    SuperLU factors the matrix with the rows and columns in the bodies' elimination order (ReducedSystem.order)
    and no pivoting (μ I dominates the diagonal); its factors are then copied into 6 × 6 blocks
    (block_lu.BlockFactors), whose triangular solves are dense block products (SuperLU's own solve where they
    do not fit the block pattern).

    With single=True (default: SINGLE_PRECISION_LU) the LU is factored and applied in single precision
    (float32, complex64), everything around it in double: the reduced right-hand side is formed in double
    and rounded to single only to enter the triangular solves, x_X is formed in double from the rounded-up
    x_V. The Newton matrix is already approximate (the dropped block, a frozen Jacobian), so the iteration
    converges to the same collocation solution: its residual F is evaluated in double and its convergence
    test is unchanged; the single LU only adds ~κ·6e-8 to each increment's relative error (measured 1e-4 on
    random right-hand sides at 40 × 40 tiles), far below the contraction rates of 1e-2–0.3 it already
    has. Where a single-precision pivot rounds to exactly 0 (a stiff stem's entries of 1e14 beside a diagonal of
    1e2, in the spun equilibrium's relaxation of a cap on a stem), that factorisation is made in double."""

    def __init__(self, system: ReducedSystem, mu, single: bool | None = None):
        self.system, self.mu = system, mu
        single = SINGLE_PRECISION_LU if single is None else single
        self.complex = bool(np.iscomplexobj(mu))
        S = (mu * system.identity - system.AV - system.K / mu).tocsc()[system.order][:, system.order]
        precisions = [np.dtype(np.complex64 if self.complex else np.float32), S.dtype] if single else [S.dtype]
        with small_pages():
            for self.dtype in precisions:  # single precision's pivot may round to exactly 0: then double
                try:
                    lu = splu(
                        S.astype(self.dtype, copy=False),
                        permc_spec="NATURAL",
                        diag_pivot_thresh=0.0,
                        options=dict(SymmetricMode=True),
                    )
                    break
                except RuntimeError:  # "Factor is exactly singular"
                    if self.dtype == precisions[-1]:
                        raise
            self.nnz = lu.L.nnz + lu.U.nnz
            self.blocks = block_lu.BlockFactors.from_superlu(lu, system.pattern)
        self.lu = lu if self.blocks is None else None  # SuperLU's own factors only where the blocks do not fit

    def solve(self, f):
        s, mu = self.system, self.mu
        fx, fv = f[s.X], f[s.V]
        AX, B = s.products(self.complex or np.iscomplexobj(f))
        rhs = fv + (AX @ fx) / mu
        if self.blocks is not None and not (np.iscomplexobj(rhs) and not self.complex):
            xv = self.blocks.solve(rhs)
        else:
            order = s.order
            xv = np.empty_like(rhs)
            xv[order] = self.lu.solve(rhs[order].astype(self.dtype, copy=False))
        xx = (fx + B @ xv) / mu
        out = np.empty(s.n, dtype=np.result_type(xv, xx))
        out[s.X] = xx
        out[s.V] = xv
        return out


class SheetRadau:
    """Adaptive Radau IIA with steps h_max/2^k (module docstring).

    fun(t, y) → ẏ; jac(t, y) → sparse J; kinematics(y) → sparse B; X, V: the index sets of y.
    step() advances one accepted step (returns None, or an error message with status "failed");
    sol(t) evaluates the last step's collocation polynomial (dense output, O(h⁴))."""

    def __init__(self, fun, t0, y0, t_bound, rtol, atol, jac, kinematics, X, V, h_max, first_level=12):
        self.fun, self.jac, self.kinematics = fun, jac, kinematics
        self.X, self.V = X, V
        self.t, self.y = float(t0), np.asarray(y0, float).copy()
        self.t_bound = float(t_bound)
        self.rtol, self.atol = rtol, np.asarray(atol, float)
        self.f = fun(self.t, self.y)
        self.h_max = float(h_max)
        self.level = int(first_level)
        self.h_old = self.error_norm_old = None
        self.newton_tol = max(10 * EPS / rtol, min(0.03, rtol**0.5))
        self.lus = {}
        self.faccon = 1.0  # θ/(1 − θ) of the last measured Newton rate θ, raised to 0.8 at every step (RADAU5)
        self.sol = None
        self.status = "running"
        self.njev = self.nlu = self.nsteps = self.nrejected = 0
        self.step_index = 0  # t = step_index · h_max / 2^MAX_LEVEL, exact
        self.system = None
        self._new_jacobian()

    def _new_jacobian(self):
        pattern = None if self.system is None else self.system.pattern  # the same for the whole run
        self.system = ReducedSystem(self.jac(self.t, self.y), self.kinematics(self.y), self.X, self.V, pattern)
        self.current_jac = True
        self.lus = {}
        self.njev += 1

    def _lu_pair(self, level, h=None):
        """The LU pair of step level `level` (or of the final partial step h, keyed by h)."""
        key = level if h is None else ("final", h)
        if key not in self.lus:
            h = self.h_max / 2**level if h is None else h
            self.lus[key] = (ReducedLU(self.system, MU_REAL / h), ReducedLU(self.system, MU_COMPLEX / h))
            self.nlu += 2
        return self.lus[key]

    def _dense(self, t_old, h, y_old, Z):
        Q = np.dot(Z.T, P)

        def sol(t):
            x = (np.asarray(t, float) - t_old) / h
            powers = np.cumprod(np.tile(x, (Q.shape[1], 1)), axis=0)
            return Q @ powers + y_old[:, None]

        return sol

    def step(self):
        t, y, f = self.t, self.y, self.f
        level = self.level
        rejected = False
        while True:
            if level > 30:
                self.status = "failed"
                return f"step size below {self.h_max / 2**30:.3g} s at t = {t:.9g} s"
            h = self.h_max / 2**level
            final = t + h > self.t_bound + 1e-12 * self.h_max  # t_bound off this level's grid: a partial step
            if final:
                h = self.t_bound - t
            Z0 = np.zeros((3, y.size)) if self.sol is None else self.sol(t + h * C).T - y
            scale = self.atol + np.abs(y) * self.rtol
            self.faccon = max(self.faccon, EPS) ** 0.8
            faccon = self.faccon if CARRY_RATE else None
            while True:
                lu_real, lu_complex = self._lu_pair(level, h if final else None)
                converged, n_iter, Z, rate = solve_collocation(
                    self.fun, t, y, h, Z0, scale, self.newton_tol, lu_real, lu_complex, faccon
                )
                if converged and rate is not None and rate < FACCON_RATE:
                    self.faccon = rate / (1 - rate)
                if converged or self.current_jac:
                    break
                self._new_jacobian()
            if not converged:
                level += 1
                self.nrejected += 1
                continue
            y_new = y + Z[-1]
            ZE = Z.T.dot(E) / h
            error = lu_real.solve(f + ZE)
            scale = self.atol + np.maximum(np.abs(y), np.abs(y_new)) * self.rtol
            error_norm = norm(error / scale) / np.sqrt(y.size)
            if rejected and error_norm > 1:
                error = lu_real.solve(self.fun(t, y + error) + ZE)
                error_norm = norm(error / scale) / np.sqrt(y.size)
            if not np.isfinite(error_norm):
                self.status = "failed"
                return f"non-finite state at t = {t:.9g} s"
            if error_norm > 1:
                factor = predict_factor(h, self.h_old, error_norm, self.error_norm_old)
                safety = 0.9 * (2 * 6 + 1) / (2 * 6 + min(n_iter, 6))
                level += max(1, int(np.ceil(-np.log2(max(MIN_FACTOR, safety * factor)))))
                rejected = True
                self.nrejected += 1
                continue
            break
        safety = 0.9 * (2 * 6 + 1) / (2 * 6 + min(n_iter, 6))
        factor = min(MAX_FACTOR, safety * predict_factor(h, self.h_old, error_norm, self.error_norm_old))
        self.h_old, self.error_norm_old = h, error_norm
        # the next level: the largest h_max/2^k not above h·factor that keeps t on that k's grid
        new_level = max(0, level - int(np.floor(np.log2(max(factor, 1e-12)))))
        self.step_index += 2 ** (MAX_LEVEL - level)
        while new_level < level and self.step_index % (2 ** (MAX_LEVEL - new_level)):
            new_level += 1
        self.level = new_level
        self.sol = self._dense(t, h, y, Z)
        self.t = self.t_bound if final else self.step_index * self.h_max / 2**MAX_LEVEL
        self.y = y_new
        self.f = self.fun(self.t, y_new)
        self.nsteps += 1
        if n_iter > 2 and rate is not None and rate > JACOBIAN_RATE:
            self._new_jacobian()
        else:
            self.current_jac = False
        if self.t >= self.t_bound - 1e-12 * self.h_max:
            self.status = "finished"
        return None


def distance2_colouring(neighbours: list, apart=()) -> np.ndarray:
    """Colours (N,) of a graph given by its closed neighbourhoods (sets, each holding its own vertex) such
    that no two vertices of one colour share a neighbour (a distance-2 colouring: one right-hand side per
    colour and state component gives every column of the Jacobian). Vertices `apart` (rows computed apart:
    sheet_jacobian.DenseRows) may be shared; two neighbours never share a colour.

    Greedy in DSATUR order (Brélaz 1979) on the distance-2 graph: next the uncoloured vertex with the most
    distinct colours within distance 2 (ties: the most vertices within distance 2, then the lowest index),
    given the smallest colour free there. A rectangular grid takes 5 colours, the least possible (a tile
    and its 4 neighbours must all differ); greedy in index order takes 6–7."""
    N = len(neighbours)
    apart = set(apart)
    reach = [neighbours[k].union(*(neighbours[j] for j in neighbours[k] - apart)) - {k} for k in range(N)]
    colour = np.full(N, -1)
    seen = [set() for _ in range(N)]
    heap = [(0, -len(reach[k]), k) for k in range(N)]
    heapq.heapify(heap)
    while heap:
        _, _, k = heapq.heappop(heap)
        if colour[k] >= 0:
            continue
        c = 0
        while c in seen[k]:
            c += 1
        colour[k] = c
        for j in reach[k]:
            if colour[j] < 0 and c not in seen[j]:
                seen[j].add(c)
                heapq.heappush(heap, (-len(seen[j]), -len(reach[j]), j))
    return colour
