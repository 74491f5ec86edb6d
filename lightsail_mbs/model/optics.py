"""Optics as data: the per-slice radiation force law read from a table over the angle of incidence.

**The law.** A slice of area A = l W at angle θ from +x (tangent t = (cos θ, sin θ), normal
n = (−sin θ, cos θ)) in a beam travelling along +ŷ with local intensity I(x) carries

    f = (I A / c) [c_n(θ) n + c_t(θ) t],

applied at the slice centre. θ is also the signed angle of incidence: the beam direction is
ŷ = cos θ n + sin θ t, so the incident light's tangential direction cosine along +t is sin θ. An
:class:`OpticalTable` holds c_n and c_t as

    c_n(θ) = cos²θ [A_n + s_n(θ)],     c_t(θ) = A_t cos θ sin θ + cos²θ s_t(θ),

two constants A_n, A_t (a specular, absorbing facet) and two tabulated parts s_n, s_t. Dividing by
cos²θ, the projected area times the normal momentum factor of a mirror, keeps the tabulated parts
O(1) up to grazing incidence. Built in:

* the mirror, :func:`mirror`: A_n = 2, A_t = 0, s ≡ 0, so c_n = 2 cos²θ, c_t = 0 and
  f = (2 I A / c) cos²θ n, exactly the paper's Eq. (11);
* the facet of specular reflectivity R and absorptivity α, :func:`facet`: A_n = 2R + α, A_t = α,
  s ≡ 0, exactly model/loads.py's law f = (I A / c) cos θ [2R cos θ n + α ŷ] (expand ŷ);
* a 1-D grating, :func:`grating_table`: A_n = A_t = 0 and s_n = c_n/cos²θ, s_t = c_t/cos²θ from RCWA
  (model/rcwa.py, momentum balance of the diffraction orders) at the tabulated angles.

Both built-ins hold at every angle; a grating table holds on [θ_first, θ_last] and is NaN outside,
so that an integrator stops ("non-finite state") rather than extrapolate.

**Interpolation.** s_n and s_t are cubic splines (not-a-knot) in θ on each piece between *breaks*:
the Rayleigh anomalies, where an order grazes the sail (sin θ + mλ/Λ = ±1) and the coefficients have
a square-root kink. Each break is a node; nodes are uniform on each piece with spacing ≤ the step,
graded towards each break (step·2^(−k)), and refined where RCWA at an interval's midpoint is off the
spline by more than a tolerance (:func:`grating_table`); a range symmetric about 0 keeps an exactly
symmetric node set. Stored: the nodes θ_k, the node values and the per-interval cubic coefficients
(4, N − 1), highest power first (scipy's PPoly layout).

**A slice carrying the table turned over** (t → −t, e.g. the mirrored half of a sail with two
halves) sees c_n(−θ) and −c_t(−θ): the ``mirrored`` argument.

**How a solver evaluates it.**

* numpy (the Exudyn force function, analysis): ``table.forces(p, x, theta, mirrored)`` returns
  (f_x, f_y) per slice, the same signature as :func:`lightsail_mbs.model.loads.radiation_forces`;
  ``table.coefficients(theta)`` returns (c_n, c_t).
* compiled (the reduced solver's numba kernel): ``packed = table.packed()`` is one contiguous
  float64 vector that the solver keeps beside its constants; inside the kernel
  ``fx, fy = packed_force(packed, I * A / c, theta, mirrored)`` (or ``packed_coefficients``) for each
  slice, both ``@njit`` functions of this module. Layout of ``packed``: [PACKED_VERSION, N, bounded,
  A_n, A_t, θ_0 … θ_{N−1}, coef_n (4 rows of N − 1), coef_t (4 rows of N − 1)].

**Table files** (:meth:`OpticalTable.save`): ``.npz`` with arrays ``theta``, ``s_n``, ``s_t``,
``coef_n``, ``coef_t`` (the spline), ``c_n``, ``c_t`` (the coefficients at the nodes, for reading
by eye or another program), optional per-node ``extra_*`` arrays (the RCWA totals R, T, A), and
``metadata``: one JSON string with ``format`` = "lightsail-mbs optical table", ``format_version``,
``kind``, ``polarization``, the constants A_n, A_t, ``bounded`` and, for a grating, its geometry,
cache keys, RCWA backend and version, harmonics, angle range, step, grading and refinement, Rayleigh
anomalies and the CPU time of its RCWA.

**Cache.** RCWA samples are cached on disk (:func:`cache_directory`: ``$LIGHTSAIL_MBS_CACHE/optics``
or ``~/.cache/lightsail-mbs/optics``): one file per grating geometry, polarisation, backend and its
version, harmonics and source of model/rcwa.py (a SHA-256 of all of them) holds every angle computed
for them, so a change of any of them computes afresh, nothing stale is served, and a table on other
nodes reuses the angles it shares.
"""

from __future__ import annotations

import hashlib
import json
import math
import os
import tempfile
import time
from dataclasses import dataclass, field
from importlib import metadata as importlib_metadata
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from lightsail_mbs.base.constants import SPEED_OF_LIGHT
from lightsail_mbs.base.kernels import njit
from lightsail_mbs.base.validation import ParameterError, check, finite
from lightsail_mbs.model import rcwa
from lightsail_mbs.model.loads import intensity

if TYPE_CHECKING:  # annotations only: the case (model/parameters.py) imports this module, not the reverse
    from lightsail_mbs.model.parameters import SailParameters

FORMAT = "lightsail-mbs optical table"
FORMAT_VERSION = 1
PACKED_VERSION = 1.0
PACKED_HEADER = 5
TABLE_POLARIZATIONS = ("TE", "TM", "mean")
DEFAULT_THETA_MAX = math.radians(85.0)
DEFAULT_STEP = math.radians(0.25)
DEFAULT_HARMONICS = 60
DEFAULT_TOLERANCE = 1e-4  # refinement: a midpoint off the spline by more than this becomes a node
DEFAULT_GRADE = 12  # nodes at step·2^(−k), k = 1…12, beside each Rayleigh anomaly
DEFAULT_PASSES = 4
MAX_THETA = math.radians(89.9)


class OpticsFileError(ValueError):
    """A file that should hold an optical table is missing, unreadable, of another format or version."""


@dataclass(frozen=True, eq=False)
class OpticalTable:
    """The per-slice force law c_n(θ), c_t(θ) (module docstring).

    Parameters
    ----------
    theta : ndarray
        Spline nodes (rad), strictly increasing, at least 2.
    s_n, s_t : ndarray
        Values of the tabulated parts at the nodes (c/cos²θ for a grating, zeros for a built-in).
    coef_n, coef_t : ndarray
        (4, N − 1) cubic coefficients per interval, highest power first, in θ − θ_k.
    normal_constant, tangential_constant : float
        A_n and A_t.
    bounded : bool
        True: NaN outside [θ_0, θ_{N−1}]; False: the law holds at every angle (built-ins).
    polarization : str
        "TE", "TM", "mean" (unpolarised), or "any" (a built-in, the same for both).
    metadata : dict
        What the table is and how it was made (JSON-able).
    extra : dict
        Optional per-node arrays (the RCWA totals).
    """

    theta: np.ndarray
    s_n: np.ndarray
    s_t: np.ndarray
    coef_n: np.ndarray
    coef_t: np.ndarray
    normal_constant: float = 0.0
    tangential_constant: float = 0.0
    bounded: bool = True
    polarization: str = "any"
    metadata: dict = field(default_factory=dict)
    extra: dict = field(default_factory=dict)

    def __post_init__(self):
        theta = np.ascontiguousarray(self.theta, float)
        n = theta.size
        check("theta", n, theta.ndim == 1 and n >= 2, "at least 2 nodes")
        check("theta", "nodes", bool(np.all(np.isfinite(theta)) and np.all(np.diff(theta) > 0)), "strictly increasing")
        for name in ("s_n", "s_t"):
            v = np.ascontiguousarray(getattr(self, name), float)
            check(name, v.shape, v.shape == (n,), f"shape ({n},) like theta")
            object.__setattr__(self, name, v)
        for name in ("coef_n", "coef_t"):
            v = np.ascontiguousarray(getattr(self, name), float)
            check(name, v.shape, v.shape == (4, n - 1), f"shape (4, {n - 1})")
            object.__setattr__(self, name, v)
        object.__setattr__(self, "theta", theta)
        object.__setattr__(self, "normal_constant", finite("normal_constant", self.normal_constant))
        object.__setattr__(self, "tangential_constant", finite("tangential_constant", self.tangential_constant))
        allowed = (*TABLE_POLARIZATIONS, "any")
        check("polarization", self.polarization, self.polarization in allowed, ", ".join(allowed))

    # ---- construction ---------------------------------------------------------------------------
    @classmethod
    def from_samples(
        cls, theta, c_n, c_t, breaks=(), polarization: str = "any", metadata=None, extra=None
    ) -> OpticalTable:
        """A bounded table through samples c_n(θ_k), c_t(θ_k) (|θ_k| < π/2): cubic splines of c/cos²θ,
        independent on each piece between consecutive `breaks` (which must be nodes)."""
        from scipy.interpolate import CubicSpline  # here: the solvers import this module and not scipy's splines

        theta = np.asarray(theta, float)
        check("theta", "samples", theta.ndim == 1 and np.all(np.abs(theta) < math.pi / 2), "|θ| < π/2 rad")
        c2 = np.cos(theta) ** 2
        s_n, s_t = np.asarray(c_n, float) / c2, np.asarray(c_t, float) / c2
        coef_n, coef_t = np.zeros((4, max(theta.size - 1, 0))), np.zeros((4, max(theta.size - 1, 0)))
        cuts = [0]
        for b in breaks:
            if theta[0] < b < theta[-1]:
                k = int(np.argmin(np.abs(theta - b)))
                check("breaks", b, abs(theta[k] - b) <= 1e-12, "angles that are nodes of the table")
                cuts.append(k)
        cuts = sorted(set(cuts + [theta.size - 1]))
        for i0, i1 in zip(cuts[:-1], cuts[1:]):
            for values, coef in ((s_n, coef_n), (s_t, coef_t)):
                if i1 - i0 == 1:  # one interval: a straight line
                    coef[:, i0] = (0.0, 0.0, (values[i1] - values[i0]) / (theta[i1] - theta[i0]), values[i0])
                else:
                    piece = slice(i0, i1 + 1)
                    coef[:, i0:i1] = CubicSpline(theta[piece], values[piece], bc_type="not-a-knot").c
        return cls(theta, s_n, s_t, coef_n, coef_t, 0.0, 0.0, True, polarization, dict(metadata or {}), extra or {})

    # ---- evaluation -----------------------------------------------------------------------------
    def tabulated(self, theta, mirrored=False) -> tuple[np.ndarray, np.ndarray]:
        """(s_n, s_t) at θ (numpy, vectorised), for the slice turned over where `mirrored`; NaN outside a
        bounded table."""
        th = np.asarray(theta, float)
        sign = np.where(mirrored, -1.0, 1.0)
        u = sign * th
        k = np.clip(np.searchsorted(self.theta, u, side="right") - 1, 0, self.theta.size - 2)
        dx = u - self.theta[k]
        a, b = self.coef_n, self.coef_t
        sn = ((a[0, k] * dx + a[1, k]) * dx + a[2, k]) * dx + a[3, k]
        st = ((b[0, k] * dx + b[1, k]) * dx + b[2, k]) * dx + b[3, k]
        if self.bounded:
            outside = ~((u >= self.theta[0]) & (u <= self.theta[-1]))
            sn = np.where(outside, np.nan, sn)
            st = np.where(outside, np.nan, st)
        return sn, sign * st

    def coefficients(self, theta, mirrored=False) -> tuple[np.ndarray, np.ndarray]:
        """(c_n, c_t) at θ (rad), numpy, vectorised; `mirrored` (bool or per-angle bools): the slice carries
        the table turned over (t → −t)."""
        th = np.asarray(theta, float)
        sn, st = self.tabulated(th, mirrored)
        c, s = np.cos(th), np.sin(th)
        cc = c * c
        return cc * (self.normal_constant + sn), self.tangential_constant * c * s + cc * st

    def forces(self, p: SailParameters, x, theta, mirrored=False) -> tuple[np.ndarray, np.ndarray]:
        """(f_x, f_y) on each slice centre at abscissa x and angle θ (N), inertial directions: the beam of
        case `p` (uniform or Gaussian, loads.intensity) on slices of area l W; as loads.radiation_forces."""
        th = np.asarray(theta, float)
        cn, ct = self.coefficients(th, mirrored)
        scale = intensity(p, x) * p.slice_length * p.width / SPEED_OF_LIGHT
        c, s = np.cos(th), np.sin(th)
        return scale * (ct * c - cn * s), scale * (cn * c + ct * s)

    def nominal_acceleration(self, p: SailParameters) -> float:
        """g₀ = c_n(0) Ī / (c ρ h): the flat sail's acceleration under this law (for the mirror exactly
        SailParameters.nominal_acceleration)."""
        return self.normal_at_zero * p.mean_intensity / (SPEED_OF_LIGHT * p.density * p.thickness)

    @property
    def normal_at_zero(self) -> float:
        """c_n(0): the flat sail's normal force coefficient at normal incidence (2 for the mirror)."""
        return float(self.coefficients(0.0)[0])

    # ---- views ----------------------------------------------------------------------------------
    @property
    def c_n(self) -> np.ndarray:
        """c_n at the nodes."""
        return self.coefficients(self.theta)[0]

    @property
    def c_t(self) -> np.ndarray:
        """c_t at the nodes."""
        return self.coefficients(self.theta)[1]

    @property
    def kind(self) -> str:
        return str(self.metadata.get("kind", "table"))

    @property
    def theta_range(self) -> tuple[float, float]:
        """The angles (rad) where the law holds: the nodes' span, or (−inf, inf) for a built-in."""
        return (float(self.theta[0]), float(self.theta[-1])) if self.bounded else (-math.inf, math.inf)

    def packed(self) -> np.ndarray:
        """The table as one float64 vector for compiled kernels (layout in the module docstring)."""
        n = self.theta.size
        head = [PACKED_VERSION, float(n), float(self.bounded), self.normal_constant, self.tangential_constant]
        return np.ascontiguousarray(np.concatenate([head, self.theta, self.coef_n.ravel(), self.coef_t.ravel()]))

    # ---- files ----------------------------------------------------------------------------------
    @property
    def digest(self) -> str:
        """SHA-256 (hex, 16 digits) of what the solvers use: the packed law (packed()) and the polarisation.
        Two tables with the same digest give the same runs."""
        h = hashlib.sha256(self.packed().tobytes())
        h.update(self.polarization.encode())
        return h.hexdigest()[:16]

    def to_arrays(self) -> dict:
        """The table as the named arrays of its .npz file (module docstring)."""
        meta = {
            **self.metadata,
            "format": FORMAT,
            "format_version": FORMAT_VERSION,
            "polarization": self.polarization,
            "normal_constant": self.normal_constant,
            "tangential_constant": self.tangential_constant,
            "bounded": self.bounded,
        }
        return dict(
            theta=self.theta,
            s_n=self.s_n,
            s_t=self.s_t,
            coef_n=self.coef_n,
            coef_t=self.coef_t,
            c_n=self.c_n,
            c_t=self.c_t,
            metadata=np.array(json.dumps(meta, sort_keys=True)),
            **{f"extra_{k}": np.asarray(v) for k, v in self.extra.items()},
        )

    @classmethod
    def from_arrays(cls, arrays, source: str) -> OpticalTable:
        """The table of arrays named as by :meth:`to_arrays` (a mapping, e.g. an open .npz); OpticsFileError
        names `source` and what is wrong."""
        try:
            meta = json.loads(str(arrays["metadata"]))
            if meta.get("format") != FORMAT:
                raise OpticsFileError(f"{source}: not an optical table (format {meta.get('format')!r})")
            if meta.get("format_version") != FORMAT_VERSION:
                raise OpticsFileError(
                    f"{source}: optical table format version {meta.get('format_version')!r}; this version reads "
                    f"{FORMAT_VERSION} (write the table again)"
                )
            extra = {k[6:]: np.array(arrays[k]) for k in arrays if k.startswith("extra_")}
            values = [np.array(arrays[k]) for k in ("theta", "s_n", "s_t", "coef_n", "coef_t")]
        except OpticsFileError:
            raise
        except (OSError, ValueError, KeyError) as exc:
            raise OpticsFileError(f"{source}: not a readable optical table ({exc})") from None
        try:
            return cls(
                *values,
                normal_constant=meta["normal_constant"],
                tangential_constant=meta["tangential_constant"],
                bounded=bool(meta["bounded"]),
                polarization=meta["polarization"],
                metadata=meta,
                extra=extra,
            )
        except (KeyError, ParameterError) as exc:
            raise OpticsFileError(f"{source}: inconsistent optical table ({exc})") from None

    def save(self, path) -> Path:
        """Write the table as .npz (module docstring) and return the path."""
        path = Path(path)
        check("out", str(path), path.suffix == ".npz", "a path ending in .npz")
        path.parent.mkdir(parents=True, exist_ok=True)
        _atomic_savez(path, self.to_arrays())
        return path

    @classmethod
    def load(cls, path) -> OpticalTable:
        """Read a table written by :meth:`save`; OpticsFileError names what is wrong with the file."""
        path = Path(path)
        if not path.is_file():
            raise OpticsFileError(f"{path}: no such optical table file")
        try:
            with np.load(path, allow_pickle=False) as d:
                return cls.from_arrays({k: d[k] for k in d.files}, str(path))
        except OpticsFileError:
            raise
        except (OSError, ValueError, KeyError) as exc:
            raise OpticsFileError(f"{path}: not a readable optical table ({exc})") from None

    def summary(self) -> dict:
        """What `lightsail-mbs optics info` prints: kind, polarisation, range, nodes, c_n(0), c_t(0), metadata."""
        cn0, ct0 = (float(v) for v in self.coefficients(0.0))
        lo, hi = self.theta_range
        return {
            "kind": self.kind,
            "polarization": self.polarization,
            "theta_range_deg": [math.degrees(lo), math.degrees(hi)],
            "nodes": int(self.theta.size),
            "c_n(0)": cn0,
            "c_t(0)": ct0,
            "normal_constant": self.normal_constant,
            "tangential_constant": self.tangential_constant,
            **{k: v for k, v in self.metadata.items() if k not in ("normal_constant", "tangential_constant")},
        }


_READ_CACHE: dict = {}


def read_table(path) -> OpticalTable:
    """OpticalTable.load(path), read once per resolved path, size and modification time (a case reads its
    table at every validation)."""
    path = Path(path)
    try:
        st = path.stat()
    except OSError as exc:
        raise OpticsFileError(f"{path}: cannot be read ({exc.strerror or exc})") from None
    key = (str(path.resolve()), st.st_size, st.st_mtime_ns)
    if key not in _READ_CACHE:
        if len(_READ_CACHE) > 64:
            _READ_CACHE.clear()
        _READ_CACHE[key] = OpticalTable.load(path)
    return _READ_CACHE[key]


def stored_copy(table: OpticalTable) -> Path:
    """A file holding `table`, named by its digest in the cache (:func:`cache_directory`): written once,
    the same path for the same table."""
    path = cache_directory() / f"table-{table.digest}.npz"
    if not (path.is_file() and read_table(path).digest == table.digest):
        table.save(path)
    return path


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
def packed_slice_force(packed, push, c, s, theta, mirrored):
    """The radiation force (f_x, f_y) on one slice (N), inertial directions, as the reduced solver applies
    it: push = I(x) l W / c, c, s = cos θ, sin θ. With q_n = A_n + s_n (module docstring)

        normal = (q_n c)(push c),   tangential = push (A_t c s + c² s_t),
        f_x = tangential c − normal s,   f_y = normal c + tangential s,

    the product order of model/loads.py's law as the reduced solver's kernel computes it, so the built-in
    mirror (q_n = 2, A_t = s_t = 0) gives Eq. (11) to the last bit there."""
    sign = -1.0 if mirrored else 1.0
    sn, st = packed_tabulated(packed, sign * theta)
    normal = ((packed[3] + sn) * c) * (push * c)
    tangential = push * (packed[4] * c * s + c * c * (sign * st))
    return tangential * c - normal * s, normal * c + tangential * s


@njit(cache=True)
def normal_tangential_into(packed, mirrored, push, c, s, theta, normal, tangential):
    """The force components along each slice's normal and tangent (N), as the Exudyn force function
    applies them (f = (tangential + i normal) e^{iθ} in its complex notation): push_i = I(x_i) l W / c
    (half of f₀ for the uniform beam), mirrored_i ≠ 0 for a slice carrying the table turned over,

        normal = (q_n push)(c²),   tangential = push (A_t c s + c² s_t),

    the product order of Exudyn's Eq. (11) path, f₀ (c²) n, so the built-in mirror gives its bits."""
    for i in range(theta.size):
        sign = -1.0 if mirrored[i] != 0.0 else 1.0
        sn, st = packed_tabulated(packed, sign * theta[i])
        ci, si = c[i], s[i]
        normal[i] = ((packed[3] + sn) * push[i]) * (ci * ci)
        tangential[i] = push[i] * (packed[4] * ci * si + ci * ci * (sign * st))


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


def slice_flags(p: SailParameters) -> np.ndarray:
    """1.0 for each slice of case p that carries its table turned over (t → −t), else 0.0: none for the
    layout 'uniform'; for 'mirrored-halves' the slices whose centres lie right of the middle (i ≥ n/2;
    with n odd the middle slice keeps the table's orientation)."""
    flags = np.zeros(p.n)
    if p.optics_layout == "mirrored-halves":
        flags[(p.n + 1) // 2 :] = 1.0
    return flags


def solver_block(p: SailParameters) -> np.ndarray:
    """What a solver's compiled load reads for case p's table: the n slice flags, then the packed table."""
    return np.concatenate([slice_flags(p), p.optical_table().packed()])


# ---- built-in laws -------------------------------------------------------------------------------
def _constant(normal: float, tangential: float, meta: dict) -> OpticalTable:
    theta = np.array([-math.pi / 2, math.pi / 2])
    z = np.zeros(2)
    return OpticalTable(theta, z, z, np.zeros((4, 1)), np.zeros((4, 1)), normal, tangential, False, "any", meta)


def mirror() -> OpticalTable:
    """The perfect mirror, Eq. (11): c_n = 2 cos²θ, c_t = 0, at every angle."""
    return _constant(2.0, 0.0, {"kind": "mirror"})


def facet(reflectivity: float, absorptivity: float) -> OpticalTable:
    """The specular, absorbing facet of model/loads.py: c_n = (2R + α) cos²θ, c_t = α cos θ sin θ."""
    R, a = finite("reflectivity", reflectivity), finite("absorptivity", absorptivity)
    check("reflectivity", R, 0 <= R <= 1, "0 ≤ R ≤ 1")
    check("absorptivity", a, 0 <= a <= 1 - R, f"0 ≤ α ≤ 1 − R = {1 - R:g}")
    return _constant(2.0 * R + a, a, {"kind": "facet", "reflectivity": R, "absorptivity": a})


def for_case(p: SailParameters) -> OpticalTable:
    """The built-in table of a case's optics: the mirror for R = 1, α = 0, else the facet."""
    if p.reflectivity == 1.0 and p.absorptivity == 0.0:
        return mirror()
    return facet(p.reflectivity, p.absorptivity)


# ---- gratings --------------------------------------------------------------------------------------
def node_grid(theta_max: float, step: float, breaks=(), grade: int = 0) -> np.ndarray:
    """Nodes on [−θ_max, θ_max]: each break is a node, each piece between breaks uniform with spacing
    ≤ step, and, with grade = K > 0, nodes at b ± step·2^(−k), k = 1…K, beside every break b (where the
    coefficients have square-root kinks); the set is exactly symmetric about 0 (0 is a node)."""
    edges = sorted({0.0, theta_max, *(abs(b) for b in breaks if 0 < abs(b) < theta_max)})
    half = [0.0]
    for a, b in zip(edges[:-1], edges[1:]):
        k = max(1, math.ceil((b - a) / step - 1e-9))
        half += list(a + (b - a) * np.arange(1, k + 1) / k)
        half[-1] = b
    for b in {abs(b) for b in breaks if abs(b) < theta_max}:
        for k in range(1, grade + 1):
            half += [v for v in (b - step * 2.0**-k, b + step * 2.0**-k) if 0 < v < theta_max]
    half = np.unique(half)
    return np.concatenate([-half[:0:-1], half])


def cache_directory() -> Path:
    """$LIGHTSAIL_MBS_CACHE/optics, else $XDG_CACHE_HOME/lightsail-mbs/optics, else ~/.cache/lightsail-mbs/optics."""
    root = os.environ.get("LIGHTSAIL_MBS_CACHE")
    if root:
        return Path(root) / "optics"
    base = os.environ.get("XDG_CACHE_HOME") or Path.home() / ".cache"
    return Path(base) / "lightsail-mbs" / "optics"


def rcwa_code_hash() -> str:
    """SHA-256 (16 hex digits) of model/rcwa.py: the code that turns a geometry into coefficients."""
    return hashlib.sha256(Path(rcwa.__file__).read_bytes()).hexdigest()[:16]


def _backend_version(backend: str) -> str:
    try:
        return importlib_metadata.version(backend)
    except importlib_metadata.PackageNotFoundError:
        return "not installed"


SAMPLE_FIELDS = ("c_n", "c_t", "R", "T", "A", "cpu")


def rcwa_samples(
    g: rcwa.Grating,
    theta,
    polarization: str,
    harmonics: int = DEFAULT_HARMONICS,
    backend: str = "meent",
    cache_dir: Path | None = None,
    progress=None,
) -> dict:
    """c_n, c_t, the totals R = ΣR_m, T = ΣT_m, A = 1 − R − T and the CPU seconds of one polarisation at
    the angles θ, by RCWA. Every angle ever computed for a geometry, polarisation, harmonics, backend (and
    its version) and source of model/rcwa.py is kept in one cache file; only angles not in it are computed
    (cache_dir None: :func:`cache_directory`; False: no cache). Returns the arrays in the order of θ, and
    'computed': how many angles were new."""
    check("polarization", polarization, polarization in rcwa.POLARIZATIONS, "TE or TM")
    theta = np.asarray(theta, float)
    ident = {
        "geometry": g.to_dict() | {"name": ""},
        "polarization": polarization,
        "harmonics": harmonics,
        "backend": backend,
        "backend_version": _backend_version(backend),
        "code": rcwa_code_hash(),
    }
    key = hashlib.sha256(json.dumps(ident, sort_keys=True).encode()).hexdigest()[:24]
    store = {}
    path = None
    if cache_dir is not False:
        path = Path(cache_dir or cache_directory()) / f"rcwa-{g.key()}-{polarization}-{key}.npz"
        if path.is_file():
            try:
                with np.load(path, allow_pickle=False) as d:
                    store = {float(t): row for t, row in zip(d["theta"], d["values"])}
            except (OSError, ValueError, KeyError):
                store = {}  # unreadable: computed afresh and overwritten
    missing = [float(t) for t in dict.fromkeys(theta.tolist()) if float(t) not in store]
    for i, th in enumerate(missing):
        t0 = time.process_time()
        o = rcwa.orders(g, th, polarization, harmonics, backend)
        c_n, c_t = rcwa.force_coefficients(o)
        store[th] = np.array([c_n, c_t, o.reflected.sum(), o.transmitted.sum(), o.absorbed, time.process_time() - t0])
        if progress is not None:
            progress(i + 1, len(missing))
    if path is not None and missing:
        angles = np.array(sorted(store))
        _atomic_savez(path, dict(theta=angles, values=np.array([store[t] for t in angles]), ident=json.dumps(ident)))
    rows = np.array([store[float(t)] for t in theta]).reshape(theta.size, len(SAMPLE_FIELDS))
    return {"theta": theta, **dict(zip(SAMPLE_FIELDS, rows.T)), "computed": len(missing), "cache_key": key}


def grating_table(
    g: rcwa.Grating,
    polarization: str = "TE",
    harmonics: int = DEFAULT_HARMONICS,
    theta_max: float = DEFAULT_THETA_MAX,
    step: float = DEFAULT_STEP,
    backend: str = "meent",
    cache_dir: Path | None = None,
    progress=None,
    tolerance: float = DEFAULT_TOLERANCE,
    grade: int = DEFAULT_GRADE,
    passes: int = DEFAULT_PASSES,
) -> OpticalTable:
    """The force table of a grating by RCWA.

    Nodes: :func:`node_grid` (spacing ≤ step, breaks at the Rayleigh anomalies graded by `grade` levels).
    Then up to `passes` refinements: RCWA at the midpoint of every interval wider than step/16 (in later
    passes, of the new intervals), and each midpoint (with its mirror image, so the node set stays
    symmetric) whose c_n or c_t differs from the spline by more than `tolerance` becomes a node
    (tolerance 0: no refinement). polarization: "TE", "TM" or "mean" (unpolarised or circular: the mean
    of the two efficiencies, hence of c_n and c_t, which are linear in them). RCWA samples are cached
    (:func:`rcwa_samples`)."""
    check("polarization", polarization, polarization in TABLE_POLARIZATIONS, ", ".join(TABLE_POLARIZATIONS))
    check("harmonics", harmonics, isinstance(harmonics, int) and 1 <= harmonics <= 2000, "an integer 1 … 2000")
    check("backend", backend, backend in rcwa.BACKENDS, " or ".join(rcwa.BACKENDS))
    v = finite("theta_max", theta_max)
    check("theta_max", v, 0 < v <= MAX_THETA, f"0 < θ_max ≤ {math.degrees(MAX_THETA):g}° (in rad)")
    v = finite("step", step)
    check("step", v, 0 < v <= math.radians(10.0), "0 < step ≤ 10° (in rad)")
    v = finite("tolerance", tolerance)
    check("tolerance", v, v >= 0, "≥ 0 (0: no refinement)")
    check("grade", grade, isinstance(grade, int) and 0 <= grade <= 30, "an integer 0 … 30")
    check("passes", passes, isinstance(passes, int) and 0 <= passes <= 10, "an integer 0 … 10")
    breaks = g.rayleigh_anomalies(theta_max)
    pols = ("TE", "TM") if polarization == "mean" else (polarization,)
    done = [0]

    def sample(angles):
        out = {p: rcwa_samples(g, angles, p, harmonics, backend, cache_dir, tick) for p in pols}
        done[0] += len(angles)
        return out

    def tick(i, total):
        if progress is not None:
            progress(done[0] + i, None)

    theta = node_grid(theta_max, step, breaks, grade)
    nodes = sample(theta)
    values = {p: {k: nodes[p][k] for k in SAMPLE_FIELDS} for p in pols}
    candidates = theta
    added, estimate, used = 0, math.nan, 0
    for _ in range(passes if tolerance > 0 else 0):
        used += 1
        table = _from_samples(theta, values, pols, breaks, polarization)
        lo, hi = candidates[:-1], candidates[1:]
        wide = (hi - lo) > step / 16
        mids = 0.5 * (lo + hi)[wide]
        mids = mids[~np.isin(mids, theta)]
        if mids.size == 0:
            break
        got = sample(mids)
        c_n = np.mean([got[p]["c_n"] for p in pols], axis=0)
        c_t = np.mean([got[p]["c_t"] for p in pols], axis=0)
        cn_s, ct_s = table.coefficients(mids)
        err = np.maximum(np.abs(c_n - cn_s), np.abs(c_t - ct_s))
        estimate = float(err.max())
        order = np.argsort(mids)
        flagged = err[order] > tolerance
        flagged |= flagged[::-1]  # the mirror image of a flagged midpoint too (the midpoints are symmetric)
        new = mids[order][flagged]
        if new.size == 0:
            break
        added += new.size
        theta = np.concatenate([theta, new])
        keep = np.argsort(theta)
        for p in pols:
            values[p] = {k: np.concatenate([values[p][k], got[p][k][order][flagged]])[keep] for k in SAMPLE_FIELDS}
        theta = theta[keep]
        # next pass: the intervals on both sides of every new node
        near = np.unique(np.concatenate([np.searchsorted(theta, new) + d for d in (-1, 0, 1)]))
        candidates = theta[near[(near >= 0) & (near < theta.size)]]
    cpu = float(sum(rcwa_samples(g, theta, p, harmonics, backend, cache_dir)["cpu"].sum() for p in pols))
    meta = {
        "kind": "grating",
        "grating": g.to_dict(),
        "geometry_key": g.key(),
        "backend": backend,
        "backend_version": _backend_version(backend),
        "harmonics": harmonics,
        "theta_max": theta_max,
        "step": step,
        "grade": grade,
        "tolerance": tolerance,
        "refinement_passes": used,
        "refinement_nodes": added,
        "refinement_last_error": estimate,
        "rayleigh_anomalies": breaks.tolist(),
        "rcwa_cpu_seconds": cpu,
        "rcwa_code": rcwa_code_hash(),
        "cache_keys": [nodes[p]["cache_key"] for p in pols],
        "lossless": g.lossless,
    }
    return _from_samples(theta, values, pols, breaks, polarization, meta)


def _from_samples(theta, values, pols, breaks, polarization, meta=None) -> OpticalTable:
    c_n = np.mean([values[p]["c_n"] for p in pols], axis=0)
    c_t = np.mean([values[p]["c_t"] for p in pols], axis=0)
    extra = {f"{name}_{p}": values[p][name] for p in pols for name in ("R", "T", "A")}
    return OpticalTable.from_samples(theta, c_n, c_t, breaks, polarization, meta or {"kind": "grating"}, extra)


def _atomic_savez(path: Path, arrays: dict) -> None:
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(prefix=path.stem, suffix=".npz", dir=path.parent)
    os.close(fd)
    try:
        np.savez_compressed(tmp, **arrays)
        os.replace(tmp, path)
    finally:
        if os.path.exists(tmp):
            os.unlink(tmp)
