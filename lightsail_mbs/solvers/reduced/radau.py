"""Compiled Radau IIA (order 5) for the reduced chain with an O(n) Newton matrix.

The method, simplified-Newton iteration, error estimate, step-size control (Gustafsson's predictive
controller) and cubic dense output are scipy.integrate.Radau's (Hairer & Wanner, *Solving ODEs II*,
Sec. IV.8; T, T⁻¹, the eigenvalues of A⁻¹ and the interpolation matrix P are in tableaus.py), with the
whole step loop in numba-compiled code. The linear algebra is the chain's own: instead of a dense
Jacobian and two dense LUs of size 2·dof (O(n²) + O(n³)), the two stage systems

    (μ_real/h) I − J̃   and   (μ_complex/h) I − J̃

use the structured approximate Jacobian J̃ = [[0, I], [−M⁻¹K̃, −M⁻¹C]] of newton.py (springs, dampers
and the geometric stiffness of the joint forces exact, M frozen at the state of the last "Jacobian"
refresh). "Evaluating the Jacobian" is storing cos θ, sin θ, the arms and the geometric stiffness of
the current state (O(n), one right-hand side); "factorising" is the block LDLᵀ of the 3×3
block-tridiagonal compliant-joint matrix, once in real and once in complex arithmetic (O(n)).
Everything per step is therefore O(n).

Simplified Newton with an approximate Jacobian converges linearly with the rate of the neglected
part (‖(σ − J̃)⁻¹(J − J̃)‖: load and velocity terms, of the order of the slow dynamics times h); the
step-size controller and Radau's error estimate are unchanged (the estimate uses (σ_real − J̃)⁻¹ as
a filter, which any J̃ carrying the stiff eigenvalues satisfies). Because refreshing J̃ is cheap, the
integrator refreshes it whenever Newton converges slowly, as scipy's does, and also whenever the
step size changes (REFRESH_ON_REFACTOR), so the factorisation always belongs to the current
configuration.
"""

from __future__ import annotations

import math

import numpy as np

from lightsail_mbs.base.kernels import njit
from lightsail_mbs.solvers.reduced import tableaus
from lightsail_mbs.solvers.reduced.chain_constants import C_S, C_T, EXTENSIBLE, K_S, K_T, N
from lightsail_mbs.solvers.reduced.dop853 import (
    FINISHED,
    NOT_FINITE,
    OK,
    STEP_TOO_SMALL,
    CompiledIntegrator,
    finite,
    initial_step,
    scaled_rms,
)
from lightsail_mbs.solvers.reduced.dynamics import rhs_into, workspace
from lightsail_mbs.solvers.reduced.newton import compliances, factor, geometry_into, newton_solve

C = np.ascontiguousarray(tableaus.RADAU_C)
E = np.ascontiguousarray(tableaus.RADAU_E)
T = np.ascontiguousarray(tableaus.RADAU_T)
TI = np.ascontiguousarray(tableaus.RADAU_TI)
P = np.ascontiguousarray(tableaus.RADAU_P)
MU_REAL = float(tableaus.RADAU_MU_REAL)
MU_COMPLEX = complex(tableaus.RADAU_MU_COMPLEX)
NEWTON_MAXITER = tableaus.RADAU_NEWTON_MAXITER
MIN_FACTOR, MAX_FACTOR = 0.2, 10.0
REFRESH_ON_REFACTOR = True

(
    T_NOW,
    H_ABS,
    H_ABS_OLD,
    ERROR_OLD,
    CURRENT_JAC,
    LU_VALID,
    HAS_SOL,
    T_OLD,
    H_OLD,
    STEPS,
    NFEV,
    NJEV,
    NLU,
    H_FACTORED,
) = range(14)
STATE_SIZE = 14


@njit(cache=True)
def _factor_one(k, sigma, geo, inv_in, piv, low, cpl):
    inv_kt, inv_ks, has_moment = compliances(sigma, k, geo[3], inv_in)
    factor(k, geo[0], geo[1], geo[2], inv_in, inv_kt, inv_ks, has_moment, piv, low, cpl)


@njit(cache=True)
def _factorise(k, h, geo, real_fac, cplx_fac):
    """Block LDLᵀ of the real (σ = μ_real/h) and complex (σ = μ_complex/h) compliant-joint systems.
    real_fac / cplx_fac: (pivots⁻¹, lower, couplings, 1/J') of each."""
    _factor_one(k, MU_REAL / h, geo, real_fac[3], real_fac[0], real_fac[1], real_fac[2])
    _factor_one(k, MU_COMPLEX / h, geo, cplx_fac[3], cplx_fac[0], cplx_fac[1], cplx_fac[2])


@njit(cache=True)
def _solve(k, sigma, geo, fac, lam, scratch, x):
    """x ← (σ I − J̃)⁻¹ x with the factors fac of this σ."""
    has_moment = k[K_T] != 0.0 or k[C_T] != 0.0
    inv_ks = sigma * sigma / (k[C_S] * sigma + k[K_S]) if k[EXTENSIBLE] != 0.0 else 0.0 * sigma
    newton_solve(
        x, sigma, k, geo[0], geo[1], geo[2], geo[3], fac[3], inv_ks, has_moment, fac[0], fac[1], fac[2], lam, scratch
    )


@njit(cache=True)
def advance(k, state, y, f, geo, real_fac, cplx_fac, geometric, Z, y_old, t_bound, rtol, atol, max_step, samples, out):
    """Step (scipy Radau's algorithm, structured linear algebra) until every time in `samples` is
    passed; interpolated states go to the rows of out. Returns (status, samples written).
    The first call (nfev = 0) evaluates f(y₀), J̃'s first state and, when |h| = 0, the initial step."""
    size = y.size
    dof = size // 2
    n = int(k[N])
    work = workspace(n)
    if state[NFEV] == 0:
        rhs_into(state[T_NOW], y, k, work, f)
        state[NFEV] = 1
        if state[H_ABS] <= 0:
            state[H_ABS] = initial_step(state[T_NOW], y, f, k, t_bound, rtol, atol, max_step, 3)
            state[NFEV] += 1
        geometry_into(state[T_NOW], y, k, work, geo[0], geo[1], geo[2], geo[3], geometric)
        state[NJEV] = 1
    lam_r = np.empty((n - 1, 3))
    lam_c = np.empty((n - 1, 3), dtype=np.complex128)
    scr_r = np.empty((3, dof))
    scr_c = np.empty((3, dof), dtype=np.complex128)
    written = 0
    newton_tol = max(10 * 2.220446049250313e-16 / rtol, min(0.03, rtol**0.5))
    if not (finite(y) and finite(f)):
        return NOT_FINITE, written
    while written < samples.size and samples[written] <= state[T_NOW]:
        _dense(Z, y_old, (samples[written] - state[T_OLD]) / state[H_OLD], out[written])
        written += 1
    Z0 = np.empty((3, size))
    Znew = np.empty((3, size))
    y_new = np.empty(size)
    f_new = np.empty(size)
    probe = np.empty(size)
    err = np.empty(size)
    ZE = np.empty(size)
    scale = np.empty(size)
    W = np.zeros((3, size))
    F = np.empty((3, size))
    stage = np.empty(size)
    real = np.empty(size)
    cplx = np.empty(size, dtype=np.complex128)
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
        while True:
            if h_abs < min_step:
                return STEP_TOO_SMALL, written
            t_new = min(t + h_abs, t_bound)
            h = t_new - t
            h_abs = h
            if state[HAS_SOL] != 0:
                for s in range(3):
                    _dense(Z, y_old, (t + h * C[s] - state[T_OLD]) / state[H_OLD], Z0[s])
                    for i in range(size):
                        Z0[s, i] -= y[i]
            else:
                for s in range(3):
                    for i in range(size):
                        Z0[s, i] = 0.0
            for i in range(size):
                scale[i] = atol[i] + abs(y[i]) * rtol
            converged = False
            while not converged:
                if state[LU_VALID] == 0 or state[H_FACTORED] != h:
                    if REFRESH_ON_REFACTOR and state[CURRENT_JAC] == 0:
                        geometry_into(t, y, k, work, geo[0], geo[1], geo[2], geo[3], geometric)
                        state[NJEV] += 1
                        state[CURRENT_JAC] = 1
                    _factorise(k, h, geo, real_fac, cplx_fac)
                    state[NLU] += 2
                    state[LU_VALID] = 1
                    state[H_FACTORED] = h
                for s in range(3):
                    for i in range(size):
                        Znew[s, i] = Z0[s, i]
                converged, iterations, rate = _collocation(
                    k,
                    t,
                    y,
                    h,
                    Znew,
                    scale,
                    newton_tol,
                    geo,
                    real_fac,
                    cplx_fac,
                    lam_r,
                    lam_c,
                    scr_r,
                    scr_c,
                    state,
                    work,
                    W,
                    F,
                    stage,
                    real,
                    cplx,
                )
                if not converged:
                    if state[CURRENT_JAC] != 0:
                        break
                    geometry_into(t, y, k, work, geo[0], geo[1], geo[2], geo[3], geometric)
                    state[NJEV] += 1
                    state[CURRENT_JAC] = 1
                    state[LU_VALID] = 0
            if not converged:
                h_abs *= 0.5
                state[LU_VALID] = 0
                continue
            for i in range(size):
                y_new[i] = y[i] + Znew[2, i]
                ZE[i] = (E[0] * Znew[0, i] + E[1] * Znew[1, i] + E[2] * Znew[2, i]) / h
                err[i] = f[i] + ZE[i]
            _solve(k, MU_REAL / h, geo, real_fac, lam_r, scr_r, err)
            for i in range(size):
                scale[i] = atol[i] + max(abs(y[i]), abs(y_new[i])) * rtol
            error = scaled_rms(err, scale)
            safety = 0.9 * (2 * NEWTON_MAXITER + 1) / (2 * NEWTON_MAXITER + iterations)
            if rejected and error > 1:
                for i in range(size):
                    stage[i] = y[i] + err[i]
                rhs_into(t, stage, k, work, probe)
                state[NFEV] += 1
                for i in range(size):
                    err[i] = probe[i] + ZE[i]
                _solve(k, MU_REAL / h, geo, real_fac, lam_r, scr_r, err)
                error = scaled_rms(err, scale)
            if error > 1:
                factor_ = _predict_factor(h_abs, h_abs_old, error, error_old)
                h_abs *= max(MIN_FACTOR, safety * factor_)
                state[LU_VALID] = 0
                rejected = True
            else:
                break
        recompute_jac = iterations > 2 and rate > 1e-3
        factor_ = min(MAX_FACTOR, safety * _predict_factor(h_abs, h_abs_old, error, error_old))
        if not recompute_jac and factor_ < 1.2:
            factor_ = 1.0
        else:
            state[LU_VALID] = 0
        rhs_into(t_new, y_new, k, work, f_new)
        state[NFEV] += 1
        if recompute_jac:
            geometry_into(t_new, y_new, k, work, geo[0], geo[1], geo[2], geo[3], geometric)
            state[NJEV] += 1
            state[CURRENT_JAC] = 1
        else:
            state[CURRENT_JAC] = 0
        state[H_ABS_OLD] = state[H_ABS]
        state[ERROR_OLD] = error
        state[H_ABS] = h_abs * factor_
        state[STEPS] += 1
        for i in range(size):
            y_old[i] = y[i]
            y[i] = y_new[i]
            f[i] = f_new[i]
            for s in range(3):
                Z[s, i] = Znew[s, i]
        state[T_OLD], state[H_OLD], state[HAS_SOL] = t, h, 1.0
        state[T_NOW] = t_new
        if not finite(y_new):
            return NOT_FINITE, written
        while written < samples.size and samples[written] <= t_new:
            _dense(Z, y_old, (samples[written] - t) / h, out[written])
            written += 1
    return OK, written


@njit(cache=True)
def _collocation(
    k, t, y, h, Z, scale, tol, geo, real_fac, cplx_fac, lam_r, lam_c, scr_r, scr_c, state, work, W, F, stage, real, cplx
):
    """Simplified Newton on the transformed stage equations at the times t + C h (Z: stage increments, updated
    in place). Returns (converged, iterations, rate)."""
    size = y.size
    for r in range(3):
        for i in range(size):
            W[r, i] = TI[r, 0] * Z[0, i] + TI[r, 1] * Z[1, i] + TI[r, 2] * Z[2, i]
    m_real, m_complex = MU_REAL / h, MU_COMPLEX / h
    norm_old = -1.0
    rate = -1.0
    iterations = 0
    for it in range(NEWTON_MAXITER):
        iterations = it + 1
        for s in range(3):
            for i in range(size):
                stage[i] = y[i] + Z[s, i]
            rhs_into(t + C[s] * h, stage, k, work, F[s])
        state[NFEV] += 3
        if not (finite(F[0]) and finite(F[1]) and finite(F[2])):
            return False, iterations, rate
        for i in range(size):
            real[i] = TI[0, 0] * F[0, i] + TI[0, 1] * F[1, i] + TI[0, 2] * F[2, i] - m_real * W[0, i]
            cplx[i] = (
                (TI[1, 0] + 1j * TI[2, 0]) * F[0, i]
                + (TI[1, 1] + 1j * TI[2, 1]) * F[1, i]
                + (TI[1, 2] + 1j * TI[2, 2]) * F[2, i]
                - m_complex * (W[1, i] + 1j * W[2, i])
            )
        _solve(k, m_real, geo, real_fac, lam_r, scr_r, real)
        _solve(k, m_complex, geo, cplx_fac, lam_c, scr_c, cplx)
        acc = 0.0
        for i in range(size):
            a0, a1, a2 = real[i] / scale[i], cplx[i].real / scale[i], cplx[i].imag / scale[i]
            acc += a0 * a0 + a1 * a1 + a2 * a2
        dw_norm = math.sqrt(acc / (3 * size))
        if norm_old >= 0:
            rate = dw_norm / norm_old
        if rate >= 0 and (rate >= 1 or rate ** (NEWTON_MAXITER - it) / (1 - rate) * dw_norm > tol):
            return False, iterations, rate
        for i in range(size):
            W[0, i] += real[i]
            W[1, i] += cplx[i].real
            W[2, i] += cplx[i].imag
        for r in range(3):
            for i in range(size):
                Z[r, i] = T[r, 0] * W[0, i] + T[r, 1] * W[1, i] + T[r, 2] * W[2, i]
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
    x2 = x * x
    x3 = x2 * x
    for i in range(out.size):
        acc = y_old[i]
        for s in range(3):
            acc += (x * P[s, 0] + x2 * P[s, 1] + x3 * P[s, 2]) * Z[s, i]
        out[i] = acc


class Radau(CompiledIntegrator):
    """Radau IIA with the O(n) Newton matrix for one chain (constants k) from y0 at t = 0 to t_bound."""

    kernel = staticmethod(advance)
    t_at, steps_at, nfev_at, njev_at, nlu_at = T_NOW, STEPS, NFEV, NJEV, NLU

    def __init__(self, k, y0, t_bound, rtol, atol, max_step=np.inf, first_step=None, geometric=True):
        super().__init__(k, y0, t_bound, rtol, atol, max_step, first_step)
        self.geometric = bool(geometric)
        n = int(k[N])
        self.geo = np.zeros((4, n))  # cos θ, sin θ, arms, geometric stiffness of J̃'s state
        self.real_fac = tuple(np.zeros((n - 1, 3, 3)) for _ in range(3)) + (np.zeros(n),)
        self.cplx_fac = tuple(np.zeros((n - 1, 3, 3), np.complex128) for _ in range(3)) + (np.zeros(n, np.complex128),)
        self.Z = np.zeros((3, self.y.size))
        self.state = np.zeros(STATE_SIZE)
        self.state[[H_ABS, H_ABS_OLD, ERROR_OLD, CURRENT_JAC, H_OLD, H_FACTORED]] = [
            self.first_step,
            -1.0,
            -1.0,
            1.0,
            1.0,
            -1.0,
        ]

    def work(self) -> tuple:
        return (self.geo, self.real_fac, self.cplx_fac, self.geometric, self.Z)
