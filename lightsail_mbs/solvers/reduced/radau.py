"""Compiled implicit Radau IIA (order 5) integrator for the stiff (extensible TnT) chain.

The method, simplified-Newton iteration, error estimate, step-size control (Gustafsson's
predictive controller) and cubic dense output of scipy.integrate.Radau (Hairer & Wanner,
*Solving ODEs II*, Sec. IV.8; the transformation matrices T, T⁻¹, the eigenvalues of A⁻¹ and
the interpolation matrix P are in tableaus.py), with the whole step loop in numba-compiled
code: the stage equations split into one real and one complex linear system of size 2·dof,
  (μ_real/h) I − J   and   (μ_complex/h) I − J,
LU-factorised with partial pivoting by compiled loops (no BLAS: no thread start-up on these
small systems, and the cost does not depend on OPENBLAS_NUM_THREADS). J = ∂ẏ/∂y is the compiled
forward-difference Jacobian of reduced_dynamics (dense: q̈ depends on every coordinate through the
joint-force solve, so the Jacobian of the minimal-coordinate form is dense; its cost is
O(n²) and the factorisation O(n³), refreshed only when Newton converges slowly).
"""

from __future__ import annotations

import numpy as np
from numba import njit

from lightsail_mbs.solvers.reduced import tableaus
from lightsail_mbs.solvers.reduced.dop853 import FINISHED, NOT_FINITE, OK, STEP_TOO_SMALL, initial_step
from lightsail_mbs.solvers.reduced.dynamics import jacobian_into, rhs_into

C = np.ascontiguousarray(tableaus.RADAU_C)
E = np.ascontiguousarray(tableaus.RADAU_E)
T = np.ascontiguousarray(tableaus.RADAU_T)
TI = np.ascontiguousarray(tableaus.RADAU_TI)
P = np.ascontiguousarray(tableaus.RADAU_P)
MU_REAL = float(tableaus.RADAU_MU_REAL)
MU_COMPLEX = complex(tableaus.RADAU_MU_COMPLEX)
NEWTON_MAXITER = tableaus.RADAU_NEWTON_MAXITER
MIN_FACTOR, MAX_FACTOR = 0.2, 10.0

# the integrator's scalar state (a float vector kept between calls)
(T_NOW, H_ABS, H_ABS_OLD, ERROR_OLD, CURRENT_JAC, LU_VALID, HAS_SOL, T_OLD, H_OLD, STEPS, NFEV, NJEV, NLU) = range(13)


@njit(cache=True)
def lu_factor(a, piv):
    """In-place LU factorisation with partial pivoting (real or complex a); piv: row swaps."""
    size = a.shape[0]
    for j in range(size):
        p = j
        big = abs(a[j, j])
        for i in range(j + 1, size):
            if abs(a[i, j]) > big:
                big = abs(a[i, j])
                p = i
        piv[j] = p
        if p != j:
            for col in range(size):
                a[j, col], a[p, col] = a[p, col], a[j, col]
        pivot = a[j, j]
        if pivot == 0:
            continue
        for i in range(j + 1, size):
            a[i, j] /= pivot
            factor = a[i, j]
            if factor != 0:
                for col in range(j + 1, size):
                    a[i, col] -= factor * a[j, col]


@njit(cache=True)
def lu_solve(a, piv, b):
    """Solve (LU) x = b in place in b, with the factors and pivots of lu_factor."""
    size = a.shape[0]
    for j in range(size):
        p = piv[j]
        if p != j:
            b[j], b[p] = b[p], b[j]
    for i in range(size):
        acc = b[i]
        for j in range(i):
            acc -= a[i, j] * b[j]
        b[i] = acc
    for i in range(size - 1, -1, -1):
        acc = b[i]
        for j in range(i + 1, size):
            acc -= a[i, j] * b[j]
        b[i] = acc / a[i, i]


@njit(cache=True)
def _rms(v):
    return np.sqrt(np.mean(v * v))


@njit(cache=True)
def _factorise(jac, h, lu_real, piv_real, lu_complex, piv_complex):
    size = jac.shape[0]
    for i in range(size):
        for j in range(size):
            lu_real[i, j] = -jac[i, j]
            lu_complex[i, j] = -jac[i, j]
        lu_real[i, i] += MU_REAL / h
        lu_complex[i, i] += MU_COMPLEX / h
    lu_factor(lu_real, piv_real)
    lu_factor(lu_complex, piv_complex)


@njit(cache=True)
def _collocation(k, t, y, h, Z, scale, tol, lu_real, piv_real, lu_complex, piv_complex, state):
    """Simplified Newton on the transformed stage equations (Z: stage increments, updated in place).
    Returns (converged, iterations, rate)."""
    size = y.size
    W = np.zeros((3, size))
    for r in range(3):
        for s in range(3):
            W[r] += TI[r, s] * Z[s]
    F = np.empty((3, size))
    stage = np.empty(size)
    real = np.empty(size)
    cplx = np.empty(size, dtype=np.complex128)
    dW = np.empty((3, size))
    m_real, m_complex = MU_REAL / h, MU_COMPLEX / h
    norm_old = -1.0
    rate = -1.0
    iterations = 0
    for it in range(NEWTON_MAXITER):
        iterations = it + 1
        for s in range(3):
            stage[:] = y + Z[s]
            rhs_into(stage, k, F[s])
        state[NFEV] += 3
        if not np.all(np.isfinite(F)):
            return False, iterations, rate
        for i in range(size):
            real[i] = TI[0, 0] * F[0, i] + TI[0, 1] * F[1, i] + TI[0, 2] * F[2, i] - m_real * W[0, i]
            cplx[i] = (
                (TI[1, 0] + 1j * TI[2, 0]) * F[0, i]
                + (TI[1, 1] + 1j * TI[2, 1]) * F[1, i]
                + (TI[1, 2] + 1j * TI[2, 2]) * F[2, i]
                - m_complex * (W[1, i] + 1j * W[2, i])
            )
        lu_solve(lu_real, piv_real, real)
        lu_solve(lu_complex, piv_complex, cplx)
        dW[0] = real
        dW[1] = cplx.real
        dW[2] = cplx.imag
        dw_norm = np.sqrt(np.sum((dW / scale) ** 2) / (3 * size))
        if norm_old >= 0:
            rate = dw_norm / norm_old
        if rate >= 0 and (rate >= 1 or rate ** (NEWTON_MAXITER - it) / (1 - rate) * dw_norm > tol):
            return False, iterations, rate
        W += dW
        for r in range(3):
            Z[r] = T[r, 0] * W[0] + T[r, 1] * W[1] + T[r, 2] * W[2]
        if dw_norm == 0 or (rate >= 0 and rate / (1 - rate) * dw_norm < tol):
            return True, iterations, rate
        norm_old = dw_norm
    return False, iterations, rate


@njit(cache=True)
def _predict_factor(h_abs, h_abs_old, error, error_old):
    """Gustafsson's step-size predictor (Hairer & Wanner II, Sec. IV.8, Eq. 8.25); old < 0: none."""
    if error_old < 0 or h_abs_old < 0 or error == 0:
        multiplier = 1.0
    else:
        multiplier = h_abs / h_abs_old * (error_old / error) ** 0.25
    if error == 0:
        return np.inf
    return min(1.0, multiplier) * error**-0.25


@njit(cache=True)
def _dense(Z, y_old, x, out):
    """Cubic collocation polynomial y_old + Σ_r (Zᵀ P)_r x^(r+1) at x = (t − t_old)/h_old."""
    out[:] = y_old
    for r in range(3):
        coef = x ** (r + 1)
        for s in range(3):
            out += (coef * P[s, r]) * Z[s]


@njit(cache=True)
def advance(
    k,
    state,
    y,
    f,
    jac,
    lu_real,
    piv_real,
    lu_complex,
    piv_complex,
    Z,
    y_old,
    jac_scales,
    t_bound,
    rtol,
    atol,
    max_step,
    samples,
    out,
):
    """Step (scipy Radau's algorithm) until every time in `samples` is passed; interpolated states
    go to the rows of out. All arrays and the scalar state persist between calls.
    Returns (status, number of samples written)."""
    size = y.size
    written = 0
    newton_tol = max(10 * np.finfo(np.float64).eps / rtol, min(0.03, rtol**0.5))
    if not (np.all(np.isfinite(y)) and np.all(np.isfinite(f))):
        return NOT_FINITE, written
    while written < samples.size and samples[written] <= state[T_NOW]:
        _dense(Z, y_old, (samples[written] - state[T_OLD]) / state[H_OLD], out[written])
        written += 1
    Z0 = np.empty((3, size))
    y_new = np.empty(size)
    f_new = np.empty(size)
    probe = np.empty(size)
    while written < samples.size:
        t = state[T_NOW]
        if t >= t_bound:
            return FINISHED, written
        min_step = 10.0 * (np.nextafter(t, np.inf) - t)
        h_abs, h_abs_old, error_old = state[H_ABS], state[H_ABS_OLD], state[ERROR_OLD]
        if h_abs > max_step:
            h_abs, h_abs_old, error_old = max_step, -1.0, -1.0
        elif h_abs < min_step:
            h_abs, h_abs_old, error_old = min_step, -1.0, -1.0
        rejected = False
        safety, error, iterations, rate = 0.9, 0.0, 0, -1.0
        Znew = Z0.copy()
        while True:
            if h_abs < min_step:
                return STEP_TOO_SMALL, written
            t_new = min(t + h_abs, t_bound)
            h = t_new - t
            h_abs = h
            if state[HAS_SOL] != 0:
                for s in range(3):
                    _dense(Z, y_old, (t + h * C[s] - state[T_OLD]) / state[H_OLD], Z0[s])
                    Z0[s] -= y
            else:
                Z0[:] = 0.0
            scale = atol + np.abs(y) * rtol
            converged = False
            while not converged:
                if state[LU_VALID] == 0:
                    _factorise(jac, h, lu_real, piv_real, lu_complex, piv_complex)
                    state[NLU] += 2
                    state[LU_VALID] = 1
                Znew = Z0.copy()
                converged, iterations, rate = _collocation(
                    k, t, y, h, Znew, scale, newton_tol, lu_real, piv_real, lu_complex, piv_complex, state
                )
                if not converged:
                    if state[CURRENT_JAC] != 0:
                        break
                    jacobian_into(y, k, jac_scales, jac)
                    state[NFEV] += size + 1
                    state[NJEV] += 1
                    state[CURRENT_JAC] = 1
                    state[LU_VALID] = 0
            if not converged:
                h_abs *= 0.5
                state[LU_VALID] = 0
                continue
            y_new[:] = y + Znew[2]
            ZE = (E[0] * Znew[0] + E[1] * Znew[1] + E[2] * Znew[2]) / h
            err = f + ZE
            lu_solve(lu_real, piv_real, err)
            scale = atol + np.maximum(np.abs(y), np.abs(y_new)) * rtol
            error = _rms(err / scale)
            safety = 0.9 * (2 * NEWTON_MAXITER + 1) / (2 * NEWTON_MAXITER + iterations)
            if rejected and error > 1:
                rhs_into(y + err, k, probe)
                state[NFEV] += 1
                err = probe + ZE
                lu_solve(lu_real, piv_real, err)
                error = _rms(err / scale)
            if error > 1:
                factor = _predict_factor(h_abs, h_abs_old, error, error_old)
                h_abs *= max(MIN_FACTOR, safety * factor)
                state[LU_VALID] = 0
                rejected = True
            else:
                break
        recompute_jac = iterations > 2 and rate > 1e-3
        factor = min(MAX_FACTOR, safety * _predict_factor(h_abs, h_abs_old, error, error_old))
        if not recompute_jac and factor < 1.2:
            factor = 1.0
        else:
            state[LU_VALID] = 0
        rhs_into(y_new, k, f_new)
        state[NFEV] += 1
        if recompute_jac:
            jacobian_into(y_new, k, jac_scales, jac)
            state[NFEV] += size + 1
            state[NJEV] += 1
            state[CURRENT_JAC] = 1
        else:
            state[CURRENT_JAC] = 0
        state[H_ABS_OLD] = state[H_ABS]
        state[ERROR_OLD] = error
        state[H_ABS] = h_abs * factor
        state[STEPS] += 1
        y_old[:] = y
        Z[:] = Znew
        state[T_OLD], state[H_OLD], state[HAS_SOL] = t, h, 1.0
        state[T_NOW] = t_new
        y[:] = y_new
        f[:] = f_new
        if not np.all(np.isfinite(y_new)):
            return NOT_FINITE, written
        while written < samples.size and samples[written] <= t_new:
            _dense(Z, y_old, (samples[written] - t) / h, out[written])
            written += 1
    return OK, written


class Radau:
    """The compiled Radau IIA integrator for one chain (constants k) from y0 at t = 0 to t_bound.
    jac_scales: typical abs(y_j) for the difference steps of the Jacobian."""

    def __init__(self, k, y0, t_bound, rtol, atol, jac_scales, max_step=np.inf, first_step=None):
        self.k = k
        self.y = np.array(y0, float)
        size = self.y.size
        self.f = np.empty(size)
        rhs_into(self.y, k, self.f)
        self.t_bound = float(t_bound)
        self.rtol = float(rtol)
        self.atol = np.broadcast_to(np.asarray(atol, float), self.y.shape).copy()
        self.max_step = float(max_step)
        self.jac_scales = np.ascontiguousarray(jac_scales, float)
        h0 = (
            first_step
            if first_step is not None
            else initial_step(self.y, self.f, k, self.t_bound, self.rtol, self.atol, self.max_step, 3)
        )
        self.jac = np.empty((size, size))
        jacobian_into(self.y, k, self.jac_scales, self.jac)
        self.lu_real = np.empty((size, size))
        self.lu_complex = np.empty((size, size), dtype=np.complex128)
        self.piv_real = np.zeros(size, dtype=np.int64)
        self.piv_complex = np.zeros(size, dtype=np.int64)
        self.Z = np.zeros((3, size))
        self.y_old = self.y.copy()
        self.state = np.zeros(13)
        self.state[[H_ABS, H_ABS_OLD, ERROR_OLD, CURRENT_JAC, H_OLD]] = [h0, -1.0, -1.0, 1.0, 1.0]
        self.state[NFEV], self.state[NJEV] = 2 + size + 1, 1
        self.status = OK

    @property
    def t(self) -> float:
        return float(self.state[T_NOW])

    @property
    def steps(self) -> int:
        return int(self.state[STEPS])

    @property
    def nfev(self) -> int:
        return int(self.state[NFEV])

    @property
    def njev(self) -> int:
        return int(self.state[NJEV])

    @property
    def nlu(self) -> int:
        return int(self.state[NLU])

    def advance(self, samples: np.ndarray) -> np.ndarray:
        """Integrate past the sample times (increasing); returns the states there as columns
        (fewer if the run ended early: self.status is then FINISHED or an error code)."""
        out = np.empty((samples.size, self.y.size))
        self.status, written = advance(
            self.k,
            self.state,
            self.y,
            self.f,
            self.jac,
            self.lu_real,
            self.piv_real,
            self.lu_complex,
            self.piv_complex,
            self.Z,
            self.y_old,
            self.jac_scales,
            self.t_bound,
            self.rtol,
            self.atol,
            self.max_step,
            np.ascontiguousarray(samples, float),
            out,
        )
        return out[:written].T
