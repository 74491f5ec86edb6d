"""Compiled explicit Dormand–Prince 8(5,3) integrator (DOP853) for the reduced chain.

The same method, step-size control, initial step and 7th-order dense output as
scipy.integrate.DOP853 (Hairer, Nørsett & Wanner, *Solving ODEs I*, Sec. II.10; the Butcher
tableau, error and interpolation coefficients are in tableaus.py), but the whole step loop
runs in numba-compiled code calling the compiled right-hand side (dynamics.rhs_into) with one
workspace: no Python work and no allocation per step (every stage combination is an element loop).
Error norm: RMS of the 5th-order estimate scaled by atol + rtol·max(abs(y), abs(y_new)), combined with
the 3rd-order one as err5²/√(err5² + 0.01 err3²); step factor 0.9·err^(−1/8) bounded to [0.2, 10] (no
growth right after a rejection).

Output is produced in chunks of sample times (`Dop853.advance`), so the caller can stop at
failure, show progress and keep memory bounded, at one Python call per chunk.
"""

from __future__ import annotations

import math

import numpy as np

from lightsail_mbs.base.kernels import njit
from lightsail_mbs.solvers.reduced import tableaus
from lightsail_mbs.solvers.reduced.chain_constants import N
from lightsail_mbs.solvers.reduced.dynamics import rhs_into, workspace

STAGES = tableaus.DOP853_STAGES  # 12 stages per step
A = np.ascontiguousarray(tableaus.DOP853_A)  # (16, 16): 12 step stages + 3 dense-output stages
B = np.ascontiguousarray(tableaus.DOP853_B)
C = np.ascontiguousarray(tableaus.DOP853_C)
E3 = np.ascontiguousarray(tableaus.DOP853_E3)
E5 = np.ascontiguousarray(tableaus.DOP853_E5)
D = np.ascontiguousarray(tableaus.DOP853_D)  # (4, 16) interpolation coefficients
ERROR_EXPONENT = -1.0 / 8.0  # −1/(error estimator order + 1)
SAFETY, MIN_FACTOR, MAX_FACTOR = 0.9, 0.2, 10.0

OK, FINISHED, STEP_TOO_SMALL, NOT_FINITE = 0, 1, 2, 3
STATUS = {STEP_TOO_SMALL: "required step size is less than spacing between numbers", NOT_FINITE: "non-finite state"}


@njit(cache=True)
def scaled_rms(v, scale):
    """√(mean((v_i/scale_i)²)): the error norm of both integrators."""
    acc = 0.0
    for i in range(v.size):
        r = v[i] / scale[i]
        acc += r * r
    return math.sqrt(acc / v.size)


@njit(cache=True)
def finite(v):
    """True when every entry of the vector v is finite."""
    for i in range(v.size):
        if not math.isfinite(v[i]):
            return False
    return True


@njit(cache=True)
def initial_step(t0, y0, f0, k, t_span, rtol, atol, max_step, order):
    """Hairer's starting step (Solving ODEs I, Sec. II.4) from the time t0 for an error estimator of this
    order, as scipy's select_initial_step."""
    size = y0.size
    scale = np.empty(size)
    for i in range(size):
        scale[i] = atol[i] + abs(y0[i]) * rtol
    d0, d1 = scaled_rms(y0, scale), scaled_rms(f0, scale)
    h0 = 1e-6 if d0 < 1e-5 or d1 < 1e-5 else 0.01 * d0 / d1
    h0 = min(h0, t_span)
    probe = np.empty(size)
    for i in range(size):
        probe[i] = y0[i] + h0 * f0[i]
    f1 = np.empty(size)
    rhs_into(t0 + h0, probe, k, workspace(int(k[N])), f1)
    for i in range(size):
        probe[i] = f1[i] - f0[i]
    d2 = scaled_rms(probe, scale) / h0
    if d1 <= 1e-15 and d2 <= 1e-15:
        h1 = max(1e-6, h0 * 1e-3)
    else:
        h1 = (0.01 / max(d1, d2)) ** (1.0 / (order + 1))
    return min(100 * h0, h1, t_span, max_step)


@njit(cache=True)
def _interpolate(interp, y_old, x, out):
    """The 7th-order dense output at x = (t − t_old)/h (Horner-like form)."""
    size = out.size
    for i in range(size):
        acc = 0.0
        for r in range(6, -1, -1):
            acc += interp[r, i]
            acc *= x if (6 - r) % 2 == 0 else 1.0 - x
        out[i] = acc + y_old[i]


@njit(cache=True)
def _stages(first, stop, t, y, h, K, stage, k, work):
    """Stages first … stop − 1 of the tableau: K[s] = f(t + C[s] h, y + h Σ_{j<s} A[s, j] K[j])."""
    for s in range(first, stop):
        for i in range(y.size):
            acc = 0.0
            for j in range(s):
                acc += A[s, j] * K[j, i]
            stage[i] = y[i] + h * acc
        rhs_into(t + C[s] * h, stage, k, work, K[s])


@njit(cache=True)
def advance(k, state, y, f, interp, y_old, t_bound, rtol, atol, max_step, samples, out):
    """Step from state = [t, |h|, steps, nfev, t_old, h_old] until every time in `samples` is passed,
    writing the interpolated states into the rows of out. Returns (status, samples written).
    The first call (nfev = 0) evaluates f(y₀) and, when |h| = 0, chooses the initial step."""
    size = y.size
    work = workspace(int(k[N]))
    if state[3] == 0:
        rhs_into(state[0], y, k, work, f)
        state[3] = 1
        if state[1] <= 0:
            state[1] = initial_step(state[0], y, f, k, t_bound, rtol, atol, max_step, 7)
            state[3] += 1
    K = np.empty((16, size))
    y_new = np.empty(size)
    f_new = np.empty(size)
    stage = np.empty(size)
    written = 0
    t, h_abs = state[0], state[1]
    if not (finite(y) and finite(f)):
        return NOT_FINITE, written
    while written < samples.size and samples[written] <= t:
        _interpolate(interp, y_old, (samples[written] - state[4]) / state[5], out[written])
        written += 1
    while written < samples.size:
        if t >= t_bound:
            return FINISHED, written
        min_step = 10.0 * (np.nextafter(t, np.inf) - t)
        h_abs = min(h_abs, max_step)
        if h_abs < min_step:
            h_abs = min_step
        rejected = False
        while True:
            if h_abs < min_step:
                state[0], state[1] = t, h_abs
                return STEP_TOO_SMALL, written
            t_new = min(t + h_abs, t_bound)
            h = t_new - t
            h_abs = h
            for i in range(size):
                K[0, i] = f[i]
            _stages(1, STAGES, t, y, h, K, stage, k, work)
            for i in range(size):
                acc = 0.0
                for j in range(STAGES):
                    acc += B[j] * K[j, i]
                y_new[i] = y[i] + h * acc
            rhs_into(t_new, y_new, k, work, f_new)
            for i in range(size):
                K[STAGES, i] = f_new[i]
            state[3] += STAGES
            e5 = 0.0
            e3 = 0.0
            for i in range(size):
                sc = atol[i] + max(abs(y[i]), abs(y_new[i])) * rtol
                a5 = 0.0
                a3 = 0.0
                for j in range(STAGES + 1):
                    a5 += E5[j] * K[j, i]
                    a3 += E3[j] * K[j, i]
                a5 /= sc
                a3 /= sc
                e5 += a5 * a5
                e3 += a3 * a3
            if e5 == 0.0 and e3 == 0.0:
                error = 0.0
            else:
                error = abs(h) * e5 / math.sqrt((e5 + 0.01 * e3) * size)
            if error < 1.0:
                factor = MAX_FACTOR if error == 0.0 else min(MAX_FACTOR, SAFETY * error**ERROR_EXPONENT)
                if rejected:
                    factor = min(1.0, factor)
                h_abs *= factor
                break
            if np.isfinite(error):
                h_abs *= max(MIN_FACTOR, SAFETY * error**ERROR_EXPONENT)
            else:
                h_abs *= MIN_FACTOR
            rejected = True
        state[2] += 1
        if not finite(y_new):
            state[0], state[1] = t, h_abs
            return NOT_FINITE, written
        if samples[written] <= t_new:
            _stages(STAGES + 1, 16, t, y, h, K, stage, k, work)
            state[3] += 3
            for i in range(size):
                d0 = y_new[i] - y[i]
                interp[0, i] = d0
                interp[1, i] = h * f[i] - d0
                interp[2, i] = 2 * d0 - h * (f_new[i] + f[i])
                for r in range(4):
                    acc = 0.0
                    for j in range(16):
                        acc += D[r, j] * K[j, i]
                    interp[3 + r, i] = h * acc
                y_old[i] = y[i]
            state[4], state[5] = t, h
            while written < samples.size and samples[written] <= t_new:
                _interpolate(interp, y_old, (samples[written] - t) / h, out[written])
                written += 1
        t = t_new
        for i in range(size):
            y[i] = y_new[i]
            f[i] = f_new[i]
    state[0], state[1] = t, h_abs
    return OK, written


class CompiledIntegrator:
    """What the compiled step loops share: the state from y0 at t = 0 up to t_bound, the statistics read
    from the loop's state vector (at the indices t_at, steps_at, nfev_at, njev_at, nlu_at; None: not
    counted) and advance(), which calls the loop `kernel` with the arrays of work() between f and y_old."""

    kernel = None  # staticmethod(the compiled step loop)
    t_at = steps_at = nfev_at = njev_at = nlu_at = None  # indices in the state vector

    def __init__(self, k, y0, t_bound, rtol, atol, max_step, first_step):
        self.k = k
        self.y = np.array(y0, float)
        self.f = np.empty_like(self.y)  # f(y₀) and the initial step: at the first advance (compiled)
        self.t_bound = float(t_bound)
        self.rtol = float(rtol)
        self.atol = np.broadcast_to(np.asarray(atol, float), self.y.shape).copy()
        self.max_step = float(max_step)
        self.first_step = 0.0 if first_step is None else float(first_step)
        self.y_old = self.y.copy()
        self.status = OK

    def _count(self, index) -> int:
        return 0 if index is None else int(self.state[index])

    t = property(lambda self: float(self.state[self.t_at]))
    steps = property(lambda self: self._count(self.steps_at))
    nfev = property(lambda self: self._count(self.nfev_at))
    njev = property(lambda self: self._count(self.njev_at))
    nlu = property(lambda self: self._count(self.nlu_at))

    def work(self) -> tuple:
        """The loop's own arrays, passed between f and y_old."""
        return ()

    def advance(self, samples: np.ndarray) -> np.ndarray:
        """Integrate past the sample times (increasing); returns the states there as columns
        (fewer if the run ended early: self.status is then FINISHED or an error code)."""
        out = np.empty((samples.size, self.y.size))
        self.status, written = self.kernel(
            self.k,
            self.state,
            self.y,
            self.f,
            *self.work(),
            self.y_old,
            self.t_bound,
            self.rtol,
            self.atol,
            self.max_step,
            np.ascontiguousarray(samples, float),
            out,
        )
        return out[:written].T


class Dop853(CompiledIntegrator):
    """The compiled DOP853 for one chain (constants k) from y0 at t = 0 up to t_bound."""

    kernel = staticmethod(advance)
    t_at, steps_at, nfev_at = 0, 2, 3

    def __init__(self, k, y0, t_bound, rtol, atol, max_step=np.inf, first_step=None):
        super().__init__(k, y0, t_bound, rtol, atol, max_step, first_step)
        self.state = np.array([0.0, self.first_step, 0.0, 0.0, 0.0, 1.0])
        self.interp = np.zeros((7, self.y.size))

    def work(self) -> tuple:
        return (self.interp,)
