"""The optical force law compiled: an :class:`~lightsail_mbs.model.optics_table.OpticalTable` packed into one float64
vector (OpticalTable.packed()) and the numba kernels that evaluate it inside the solvers' right-hand sides.

Layout of ``packed``: [PACKED_VERSION, N, bounded, A_n, A_t, θ_0 … θ_{N−1}, coef_n (4 rows of N − 1),
coef_t (4 rows of N − 1)] (the law and its spline: :mod:`lightsail_mbs.model.optics`).
"""

from __future__ import annotations

import math

from lightsail_mbs.base.kernels import njit

PACKED_VERSION = 1.0


PACKED_HEADER = 5


# ---- compiled evaluation -------------------------------------------------------------------------
@njit(cache=True)
def packed_tabulated(packed, u):
    """(s_n, s_t) of OpticalTable.packed() at the table angle u (NaN outside a bounded table)."""
    n = int(packed[1])
    nodes = PACKED_HEADER
    cn0 = nodes + n
    ct0 = cn0 + 4 * (n - 1)
    m = n - 1
    if packed[2] != 0.0 and not (packed[nodes] <= u <= packed[nodes + n - 1]):
        return math.nan, math.nan
    lo, hi = 0, n - 1  # binary search for θ_lo ≤ u < θ_hi, clamped to the end intervals
    while hi - lo > 1:
        mid = (lo + hi) // 2
        if packed[nodes + mid] <= u:
            lo = mid
        else:
            hi = mid
    dx = u - packed[nodes + lo]
    sn = ((packed[cn0 + lo] * dx + packed[cn0 + m + lo]) * dx + packed[cn0 + 2 * m + lo]) * dx
    sn += packed[cn0 + 3 * m + lo]
    st = ((packed[ct0 + lo] * dx + packed[ct0 + m + lo]) * dx + packed[ct0 + 2 * m + lo]) * dx
    st += packed[ct0 + 3 * m + lo]
    return sn, st


@njit(cache=True)
def packed_coefficients(packed, theta, mirrored):
    """(c_n, c_t) at angle θ from OpticalTable.packed() (NaN outside a bounded table)."""
    sign = -1.0 if mirrored else 1.0
    sn, st = packed_tabulated(packed, sign * theta)
    c = math.cos(theta)
    s = math.sin(theta)
    cc = c * c
    return cc * (packed[3] + sn), packed[4] * c * s + cc * sign * st


@njit(cache=True)
def packed_force(packed, scale, theta, mirrored):
    """(f_x, f_y) = scale [c_n n + c_t t] at angle θ; scale = I A / c of the slice."""
    cn, ct = packed_coefficients(packed, theta, mirrored)
    c = math.cos(theta)
    s = math.sin(theta)
    return scale * (ct * c - cn * s), scale * (cn * c + ct * s)


@njit(cache=True)
def packed_net_force(packed, local, mean, area_c, c, s, theta, mirrored, normal_at_zero):
    """The net force (f_x, f_y) on one slice in the accelerating frame, radiation plus the frame force
    −c_n(0) Ī A/c ŷ, with their cancellation done analytically (N). local, mean: I(x) and Ī; area_c = l W/c;
    normal_at_zero: q_n(0) = c_n(0) of the table. With push = I A/c, q_n = A_n + s_n(±θ) and
    1 − cos³θ = 2 sin²(θ/2)(1 + cos θ + cos²θ):

        f_x = (((−push q_n) c) c) s + tangential c,
        f_y = −push q_n(0) (1 − cos³θ) + push c³ (q_n − q_n(0)) + tangential s + q_n(0) (A/c)(I − Ī),

    every term to a few ulps of itself (the plain sum push q_n c³ − q_n(0) Ī A/c keeps only ~8 digits of the
    remainder at the paper's slopes). For the mirror (q_n ≡ 2, no tangential part) the product order is that
    of the analytic net force of Eq. (11) (2R = 2, α = 0), so the built-in mirror reproduces it to the bit.
    For a solver whose load is the net force rather than radiation plus a separate frame force."""
    sign = -1.0 if mirrored else 1.0
    sn, st = packed_tabulated(packed, sign * theta)
    push = local * area_c
    qn = packed[3] + sn
    tangential = push * (packed[4] * c * s + c * c * (sign * st))
    half = math.sin(0.5 * theta)
    one_minus_cos = 2.0 * half * half
    fx = -push * qn * c * c * s + tangential * c
    fy = -push * (normal_at_zero * one_minus_cos * (1.0 + c + c * c))
    fy += push * (c * c * c) * (qn - normal_at_zero) + tangential * s
    fy += normal_at_zero * area_c * (local - mean)
    return fx, fy
