"""Beam riding of a rigid curved sail with a payload: the planar model, its stiffness, the criterion.

**Model.** The sail of a case (its slices as shapes.initial_state places them: flat, or billowed on an
arc of radius R_c, SailParameters.billow_radius; a defect if a₀ > 0) locked into one rigid body, with
a payload point mass m_p (own inertia J_p) on a rigid stem a distance d from the sail's apex (L/2, 0)
towards the laser, at (L/2, −d). The beam travels along +y with intensity I(x) (uniform, or Gaussian
I₀ exp(−2(x − x_c)²/w²)); each slice carries the load of an optical table (model/optics.py; default:
the case's mirror or facet) at its centre; the payload carries no light. State: the lateral position X
of the centre of mass G (payload included) and the body's rotation φ (counter-clockwise) from its
initial pose. In the frame accelerating with the sail, the frame force −M g ŷ acts at G and has no
moment, and no load depends on the position along the beam, so the lateral and rotational motion is

    M Ẍ = Σ_i f_x,i,        I_G φ̈ = Σ_i (r_i − G) × f_i,

I_G = Σ (m |r_i − G|² + J) + m_p |r_P − G|² + J_p (:class:`RigidSail`, :meth:`RigidSail.rhs`).

**Criterion** (mirror, circular arc of radius R, arc length L, width W; :func:`criterion`).

1. Every slice of the arc is a chord of its circle; its mirror force acts at the chord's midpoint along
   the chord's normal, i.e. along a radius. So the whole radiation force passes through the centre of
   curvature C, for any illumination and any pose, and its moment about G is (C − G) × F.
2. Put C at lateral position x_C and turn the body by φ about C. An element at polar angle ψ from the
   apex direction (ψ ∈ [−ψ_e, ψ_e], ψ_e = L/(2|R|); the arc's point C + R e(ψ), e(ψ) = (sin ψ, cos ψ))
   lies at x_C + R sin ψ and carries (2W/c) I cos²ψ e(ψ) |R| dψ; turning by φ shifts the lit window
   to [−ψ_e − φ, ψ_e − φ]. To first order in x_C and φ, with I even about the beam axis:

       F_x = −k x_C − F_e φ,      F_y = F₀,
       k   = −(2W|R|/c) ∫ I′(R sin ψ) cos²ψ sin ψ dψ   (Gaussian: (8W R|R|/(c w²)) ∫ I cos²ψ sin²ψ dψ),
       F_e = (4W|R|/c) I_e cos²ψ_e sin ψ_e               (I_e = I(R sin ψ_e), the edge intensity),
       F₀  = (2W|R|/c) ∫ I(R sin ψ) cos³ψ dψ,

   integrals over [−ψ_e, ψ_e]. sign k = sign R: a sail concave towards the laser (R > 0) in a beam that
   falls off is pushed back towards the axis; a convex one is pushed out. For a shallow arc
   (ψ_e → 0): k → (2W/(cR))(∫I ds − L I_e), F_e → (2W/c) L I_e, F₀ → (2W/c) ∫I ds.
3. With D = y_G − y_C (G downstream of C: D > 0) and x_C = X + D φ, the moment about G is
   D (F_x cos φ + F_y sin φ) ≈ D (F_x + F₀ φ):

       M Ẍ = −k X − (kD + F_e) φ,
       I φ̈ = −kD X − (kD² + D (F_e − F₀)) φ.

   The stiffness [[k, kD + F_e], [kD, kD² + D(F_e − F₀)]] is not symmetric: the radiation load is
   circulatory, with no potential. Modes e^(iωt): λ = ω² solves λ² − Sλ + P = 0 with

       S = k/M + (kD² + D(F_e − F₀))/I,     P = −k D F₀ / (M I).

   **The sail rides the beam (bounded undamped oscillation about the axis) iff both λ are real and
   positive: (i) P > 0 ⟺ k D < 0, (ii) S > 0, (iii) S² ≥ 4P.**

   * R > 0 (concave towards the laser): (i) needs D < 0 — the centre of mass must lie beyond the
     centre of curvature, on the laser side: d > d* = R + (M_s/m_p) R sin ψ_e/ψ_e
     (= R(1 + M_s/m_p) + (M_s/m_p) y_s, y_s = R sin ψ_e/ψ_e − R ≈ −L²/(24R) the arc's centroid);
     (ii) then holds since F₀ > F_e for a beam that falls off; (iii) can still fail — the circulatory
     coupling merges the two frequencies into a growing pair ("flutter") in a band of stems above d*,
     which exists for wide beams (w ≳ L) and not for narrow ones.
   * R < 0 (convex towards the laser): (i) needs D > 0, and then every term of S is negative: never.
   * Flat (R → ∞): kD → (2W/c)(∫I ds − L I_e) > 0, so P < 0 for any payload: a flat sail never rides.

   There is no damping in the model: a stable sail oscillates for ever; an unstable one leaves at the
   rate max Re √(−λ).

:func:`linearised` differentiates the discrete rigid body (any table, any shape) numerically, the
check of the closed form; :func:`ride` integrates the nonlinear rigid body (scipy's DOP853) and
classifies the run: "rides", "drifts out" (|X − x_c| ≥ one beam waist) or "tumbles" (a slice turns
outside its optical table, or beyond ±90°).

**Literature.** Manchester & Loeb (ApJL 837, L20, 2017; abstract checked) find conical sails on
Gaussian beams unstable without active control and propose a spherical shell that rides the beam
passively, confirmed by 3-D ray tracing. Popova, Efendiev & Gabitov (Math. Methods Appl. Sci., 2017)
analyse a rigid sail with a payload on a Gaussian beam; their text was not available here and their
conditions are not compared term by term. The planar result above agrees with the picture of both
(flat sails never ride; a concave shell with a suitably placed centre of mass does, with undamped
oscillations); that their three-dimensional conditions reduce to (i)–(iii) in the plane is not checked.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from scipy.integrate import quad, solve_ivp
from scipy.optimize import brentq

from lightsail_mbs.base.constants import SPEED_OF_LIGHT
from lightsail_mbs.base.validation import check, finite
from lightsail_mbs.model import optics, shapes
from lightsail_mbs.model.parameters import SailParameters

VERDICTS = ("rides", "drifts out", "tumbles")


@dataclass(frozen=True, eq=False)
class RigidSail:
    """The sail of a case locked rigid, with a payload on a stem from its apex towards the laser.

    Parameters
    ----------
    params : SailParameters
        The sail, its shape (billow_radius, defect) and the beam.
    payload_mass : float
        m_p (kg), a point mass at (L/2, −d) in the initial pose.
    payload_distance : float
        d (m) from the apex (L/2, 0) towards the laser (negative: downstream).
    payload_inertia : float
        J_p (kg m²) of the payload about its own centre.
    table : OpticalTable, optional
        The slices' force law; default optics.for_case(params) (the mirror or the facet).
    mirrored : array of bool, optional
        Per slice: the table turned over (t → −t).
    """

    params: SailParameters
    payload_mass: float = 0.0
    payload_distance: float = 0.0
    payload_inertia: float = 0.0
    table: optics.OpticalTable | None = None
    mirrored: np.ndarray | None = None
    geometry: dict = field(init=False, repr=False)

    def __post_init__(self):
        for name in ("payload_mass", "payload_inertia"):
            v = finite(name, getattr(self, name))
            check(name, v, v >= 0, "≥ 0")
        finite("payload_distance", self.payload_distance)
        p = self.params
        if self.table is None:
            object.__setattr__(self, "table", optics.for_case(p))
        mirrored = np.zeros(p.n, bool) if self.mirrored is None else np.asarray(self.mirrored, bool)
        check("mirrored", mirrored.shape, mirrored.shape == (p.n,), f"one flag per slice ({p.n})")
        object.__setattr__(self, "mirrored", mirrored)
        st = shapes.initial_state(p)
        m, mp = p.slice_mass, self.payload_mass
        mass = m * p.n + mp
        payload = np.array([0.5 * p.length, -self.payload_distance])
        gx = (m * st.x.sum() + mp * payload[0]) / mass
        gy = (m * st.y.sum() + mp * payload[1]) / mass
        dx, dy = st.x - gx, st.y - gy
        inertia = m * float(np.sum(dx * dx + dy * dy)) + p.n * p.slice_inertia
        inertia += mp * float(np.sum((payload - (gx, gy)) ** 2)) + self.payload_inertia
        object.__setattr__(
            self,
            "geometry",
            dict(dx=dx, dy=dy, theta=st.theta, mass=mass, inertia=inertia, centre=(gx, gy), payload=payload),
        )

    @property
    def mass(self) -> float:
        """M = n m + m_p (kg)."""
        return self.geometry["mass"]

    @property
    def inertia(self) -> float:
        """I_G (kg m²) about the centre of mass."""
        return self.geometry["inertia"]

    @property
    def centre_of_mass(self) -> tuple[float, float]:
        """G in the initial pose (m)."""
        return self.geometry["centre"]

    def loads(self, X: float, phi: float) -> tuple[float, float, float]:
        """(F_x, F_y, moment about G) with G at lateral position X and the body turned by φ (N, N m)."""
        g = self.geometry
        c, s = math.cos(phi), math.sin(phi)
        rx = c * g["dx"] - s * g["dy"]
        ry = s * g["dx"] + c * g["dy"]
        fx, fy = self.table.forces(self.params, X + rx, g["theta"] + phi, self.mirrored)
        return float(fx.sum()), float(fy.sum()), float(np.sum(rx * fy - ry * fx))

    def rhs(self, t, y):
        """d/dt (X, φ, Ẋ, φ̇)."""
        fx, _, torque = self.loads(y[0], y[1])
        return np.array([y[2], y[3], fx / self.mass, torque / self.inertia])


@dataclass
class Linearisation:
    """The lateral–tilt stiffness per unit mass and inertia, K = −∂(Ẍ, φ̈)/∂(X, φ), about the axis."""

    K: np.ndarray
    S: float
    P: float
    eigenvalues: np.ndarray  # λ = ω²
    growth_rate: float  # max Re √(−λ) (1/s): 0 when it rides
    stable: bool
    residual: np.ndarray  # (Ẍ, φ̈) at the axis: zero for a sail symmetric about it


def linearised(sail: RigidSail, step: float = 1e-6) -> Linearisation:
    """K of the discrete rigid body about X = x_c, φ = 0 by central differences (steps step·L and step)."""
    x0 = sail.params.beam_centre

    def acc(dx, dphi):
        return sail.rhs(0.0, np.array([x0 + dx, dphi, 0.0, 0.0]))[2:]

    h = step * sail.params.length
    A = np.column_stack([(acc(h, 0) - acc(-h, 0)) / (2 * h), (acc(0, step) - acc(0, -step)) / (2 * step)])
    K = -A
    lam = np.linalg.eigvals(K)
    S, P = float(np.trace(K)), float(np.linalg.det(K))
    growth = float(np.max(np.sqrt(-lam.astype(complex)).real))
    return Linearisation(K, S, P, lam, growth, bool(P > 0 and S > 0 and S * S >= 4 * P), acc(0.0, 0.0))


@dataclass
class Criterion:
    """The closed form of the module docstring for a mirror arc, a payload on a stem and the case's beam."""

    k: float  # lateral stiffness of the radiation force (N/m)
    edge_force: float  # F_e (N)
    axial_force: float  # F₀ (N)
    D: float  # y_G − y_C (m)
    mass: float
    inertia: float
    S: float
    P: float
    discriminant: float  # S² − 4P
    stable: bool
    static_boundary: float  # d* (m): the stem that puts G on C
    growth_rate: float  # max Re √(−λ) (1/s)


def criterion(p: SailParameters, payload_mass: float, payload_distance: float) -> Criterion:
    """The beam-riding criterion on the exact continuous arc of radius p.billow_radius (finite), a mirror."""
    R = float(p.billow_radius)
    check("billow_radius", R, math.isfinite(R), "finite (the criterion is for a curved sail; flat never rides)")
    L, W = p.length, p.width
    a = abs(R)
    psi_e = L / (2 * a)
    if p.uniform_beam:

        def inten(x):
            return p.intensity

        k = 0.0
    else:
        w = p.beam_waist

        def inten(x):
            return p.intensity * math.exp(-2.0 * (x / w) ** 2)

        integral = quad(lambda u: inten(a * math.sin(u)) * (math.cos(u) * math.sin(u)) ** 2, -psi_e, psi_e)[0]
        k = 8.0 * W * R * a / (SPEED_OF_LIGHT * w * w) * integral
    edge = inten(a * math.sin(psi_e))
    Fe = 4.0 * W * a / SPEED_OF_LIGHT * edge * math.cos(psi_e) ** 2 * math.sin(psi_e)
    F0 = 2.0 * W * a / SPEED_OF_LIGHT * quad(lambda u: inten(a * math.sin(u)) * math.cos(u) ** 3, -psi_e, psi_e)[0]
    Ms = p.density * p.thickness * W * L
    mp = float(payload_mass)
    M = Ms + mp
    sinc = math.sin(psi_e) / psi_e
    y_c = -R
    y_s = y_c + R * sinc  # the arc's centroid
    y_g = (Ms * y_s - mp * payload_distance) / M
    D = y_g - y_c
    inertia = Ms * R * R - Ms * (R * sinc) ** 2 + Ms * (y_s - y_g) ** 2 + mp * (payload_distance + y_g) ** 2
    S = k / M + (k * D * D + D * (Fe - F0)) / inertia
    P = -k * D * F0 / (M * inertia)
    lam = np.roots([1.0, -S, P]).astype(complex)
    growth = float(np.max(np.sqrt(-lam).real))
    d_star = R + Ms / mp * R * sinc if mp > 0 else math.inf
    disc = S * S - 4 * P
    return Criterion(k, Fe, F0, D, M, inertia, S, P, disc, bool(P > 0 and S > 0 and disc >= 0), d_star, growth)


def boundaries(p: SailParameters, payload_mass: float, d_min: float, d_max: float, samples: int = 400) -> list:
    """The stems d in [d_min, d_max] where the criterion changes: roots of P ("static", G on C) and of
    S² − 4P ("flutter"), sorted, as (d, kind, stable above)."""
    ds = np.geomspace(d_min, d_max, samples) if d_min > 0 else np.linspace(d_min, d_max, samples)
    out = []
    for kind, attr in (("static", "P"), ("flutter", "discriminant")):

        def f(d, attr=attr):
            return getattr(criterion(p, payload_mass, d), attr)

        values = np.array([f(d) for d in ds])
        for i in np.nonzero(np.sign(values[1:]) != np.sign(values[:-1]))[0]:
            d = brentq(f, ds[i], ds[i + 1], xtol=1e-12 * abs(ds[i + 1]), rtol=1e-13)
            out.append((d, kind, criterion(p, payload_mass, d * (1 + 1e-9)).stable))
    return sorted(out)


@dataclass
class Ride:
    """A nonlinear rigid-body run: lateral position X − x_c and tilt φ at the sample times, the verdict."""

    time: np.ndarray
    lateral: np.ndarray
    tilt: np.ndarray
    verdict: str
    decided_at: float | None
    info: dict = field(default_factory=dict)

    def envelope_growth(self) -> float:
        """max |X − x_c| over the last fifth of the run / over its first fifth."""
        n = max(self.time.size // 5, 1)
        return float(np.max(np.abs(self.lateral[-n:])) / np.max(np.abs(self.lateral[:n])))

    def growth_rate(self, start: float = 0.0, windows: int = 20) -> float:
        """Exponential growth rate of the lateral envelope (1/s): least-squares slope of log max |X − x_c| over
        `windows` equal windows of the run after `start` (a divergence and a growing oscillation alike, when a
        window holds at least one oscillation); nan with fewer than 3 windows of samples."""
        keep = self.time >= start
        t, a = self.time[keep], np.abs(self.lateral[keep])
        edges = np.linspace(t[0], t[-1], windows + 1) if t.size else []
        centres, peaks = [], []
        for lo, hi in zip(edges[:-1], edges[1:]):
            inside = (t >= lo) & (t <= hi)
            if inside.any():
                centres.append(t[inside][np.argmax(a[inside])])
                peaks.append(a[inside].max())
        if len(peaks) < 3 or min(peaks) <= 0:
            return math.nan
        return float(np.polyfit(centres, np.log(peaks), 1)[0])


def ride(
    sail: RigidSail,
    t_final: float,
    offset: float = 0.0,
    tilt: float = 0.0,
    output_interval: float = 0.01,
    rtol: float = 1e-10,
    drift_factor: float = 1.0,
) -> Ride:
    """Integrate the rigid body from rest at lateral offset X − x_c and tilt φ (DOP853, rtol, atol = rtol·(L,
    1, L/s, 1/s)) and classify: "drifts out" once |X − x_c| ≥ drift_factor·w (uniform beam: never), "tumbles"
    once a slice reaches the edge of its table's range or |φ| ≥ π/2, else "rides"; the run stops there."""
    p = sail.params
    check("t_final", t_final, t_final > 0, "> 0 s")
    check("output_interval", output_interval, 0 < output_interval <= t_final, f"0 < interval ≤ t_final = {t_final}")
    width = drift_factor * p.beam_waist
    x0 = p.beam_centre

    def drift(t, y):
        return width - abs(y[0] - x0)

    lo, hi = sail.table.theta_range
    sign = np.where(sail.mirrored, -1.0, 1.0)
    theta0 = sail.geometry["theta"]

    def turn(t, y):  # the body turned by a right angle, or a slice at the edge of its table
        u = sign * (theta0 + y[1])
        return min(math.pi / 2 - abs(y[1]), hi - float(u.max()), float(u.min()) - lo)

    drift.terminal = turn.terminal = True

    def rhs(t, y):
        out = sail.rhs(t, y)
        # beyond its table a slice's load is NaN; only a stage of the step that crosses the edge sees it,
        # and the event ends the run there: such a stage gets no light
        return out if np.all(np.isfinite(out)) else np.nan_to_num(out, nan=0.0)

    samples = np.arange(0.0, t_final + 0.5 * output_interval, output_interval)
    L = p.length
    sol = solve_ivp(
        rhs,
        (0.0, samples[-1]),
        np.array([x0 + offset, tilt, 0.0, 0.0]),
        method="DOP853",
        t_eval=samples,
        rtol=rtol,
        atol=rtol * np.array([L, 1.0, L, 1.0]),
        events=[drift, turn] if math.isfinite(width) else [turn],
    )
    lateral, phi = sol.y[0] - x0, sol.y[1]
    verdict, when = "rides", None
    if sol.status == 1:
        hit = [k for k, ev in enumerate(sol.t_events) if ev.size]
        when = float(min(sol.t_events[k][0] for k in hit))
        first = min(hit, key=lambda k: sol.t_events[k][0])
        verdict = "drifts out" if (math.isfinite(width) and first == 0) else "tumbles"
    info = dict(nfev=int(sol.nfev), rtol=rtol, message=sol.message)
    return Ride(sol.t, lateral, phi, verdict, when, info)


FLEXIBLE_VERDICTS = ("rides", "drifts out", "crumples")


@dataclass
class FlexibleRide:
    """A run of the flexible sail (a Result of either solver) read as beam riding: at the sample times the
    lateral position X − x_c of the craft's centre of mass (sail and payload), the tilt φ and the
    deformation δ of the sail (:func:`flexible_ride`), and the verdict."""

    time: np.ndarray
    lateral: np.ndarray  # X − x_c (m)
    tilt: np.ndarray  # φ (rad), counter-clockwise from the initial pose
    deformation: np.ndarray  # δ (m)
    verdict: str
    decided_at: float | None


def flexible_ride(result, crumple: float = 0.01, drift_factor: float = 1.0) -> FlexibleRide:
    """The beam-riding histories of a flexible run and its verdict.

    Each sample's slice centres r_i are fitted by the initial ones turned by φ and moved (least squares over
    the slice centres: the Procrustes rotation about their centroid); the tilt is φ plus the case's initial
    tilt (so: from the untilted pose), the deformation δ the largest distance of a slice centre from the fitted
    rigid shape, and the lateral position the craft's centre of mass (payload included) minus the beam axis.
    Verdict: "crumples" once δ ≥ crumple (m), else "drifts out" once |X − x_c| ≥ drift_factor·w (a Gaussian
    beam), else "rides"; decided_at is the first sample that decides it.
    """
    from lightsail_mbs.model import payload as payload_model

    p = result.params
    x, y, theta = result.x, result.y, result.theta
    m, mp = p.slice_mass, p.payload_mass
    where = payload_model.position(p, x, y, theta)
    total = m * p.n + mp
    gx = m * x.sum(axis=1) / total
    if where is not None:
        gx = gx + mp * where[0] / total
    # Procrustes rotation of the sail's slice centres about their centroid, against the initial shape
    cx, cy = x.mean(axis=1, keepdims=True), y.mean(axis=1, keepdims=True)
    u, v = x - cx, y - cy
    u0, v0 = u[0], v[0]
    turn = np.arctan2(np.sum(u0 * v - v0 * u, axis=1), np.sum(u0 * u + v0 * v, axis=1))
    c, s = np.cos(turn)[:, None], np.sin(turn)[:, None]
    fit_u, fit_v = c * u0 - s * v0, s * u0 + c * v0
    deformation = np.max(np.hypot(u - fit_u, v - fit_v), axis=1)
    lateral = gx - p.beam_centre
    tilt = turn + p.initial_tilt  # from the untilted pose
    verdict, when = "rides", None
    crumpled = np.flatnonzero(deformation >= crumple)
    width = drift_factor * p.beam_waist
    drifted = np.flatnonzero(np.abs(lateral) >= width) if math.isfinite(width) else np.zeros(0, int)
    firsts = [(int(crumpled[0]), "crumples")] if crumpled.size else []
    firsts += [(int(drifted[0]), "drifts out")] if drifted.size else []
    if firsts:
        k, verdict = min(firsts)
        when = float(result.time[k])
    return FlexibleRide(result.time, lateral, tilt, deformation, verdict, when)
