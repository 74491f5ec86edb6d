"""Optical tables and their files: :class:`OpticalTable`, the per-slice force law c_n(θ), c_t(θ) as two
constants and cubic splines, evaluated with numpy; its ``.npz`` format, read once per file version; the
cache folder (the law, its spline and the format: :mod:`lightsail_mbs.model.optics`).
"""

from __future__ import annotations

import hashlib
import json
import math
import os
import tempfile
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from lightsail_mbs.base.constants import SPEED_OF_LIGHT
from lightsail_mbs.base.validation import ParameterError, check, finite
from lightsail_mbs.model.loads import intensity
from lightsail_mbs.model.optics_kernels import PACKED_VERSION

if TYPE_CHECKING:  # annotations only: the case (model/parameters.py) reads its table here, not the reverse
    from lightsail_mbs.model.parameters import SailParameters


FORMAT = "lightsail-mbs optical table"
FORMAT_VERSION = 1  # one wavelength; version 2 (a wavelength axis) is model/optics_spectrum.py's
SPECTRAL_VERSION = 2
# readers of the other format versions, by version, each returning an OpticalTable: model/optics_spectrum.py
# (imported with model/optics.py) adds version 2's, the table at the laser's wavelength
VERSION_READERS: dict = {}
TABLE_POLARIZATIONS = ("TE", "TM", "mean")


class OpticsFileError(ValueError):
    """A file that should hold an optical table is missing, unreadable, of another format or version."""


@dataclass(frozen=True, eq=False)
class OpticalTable:
    """The per-slice force law c_n(θ), c_t(θ) (:mod:`lightsail_mbs.model.optics`).

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
        """The table as one float64 vector for compiled kernels (layout: :mod:`lightsail_mbs.model.optics_kernels`)."""
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
        """The table as the named arrays of its .npz file (:mod:`lightsail_mbs.model.optics`)."""
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
        """The table of arrays named as by :meth:`to_arrays` (a mapping, e.g. an open .npz), or of a table
        with a wavelength axis (format version 2) its table at the laser's wavelength; OpticsFileError
        names `source` and what is wrong."""
        try:
            meta = json.loads(str(arrays["metadata"]))
            if meta.get("format") != FORMAT:
                raise OpticsFileError(f"{source}: not an optical table (format {meta.get('format')!r})")
            reader = VERSION_READERS.get(meta.get("format_version"))
            if reader is not None:
                return reader(arrays, source)
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
        """Write the table as .npz (:mod:`lightsail_mbs.model.optics`) and return the path."""
        path = Path(path)
        check("out", str(path), path.suffix == ".npz", "a path ending in .npz")
        path.parent.mkdir(parents=True, exist_ok=True)
        atomic_savez(path, self.to_arrays())
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


def read_once(cache: dict, path, read):
    """read(path), kept in `cache` by the file's resolved path, size and modification time (at most 65
    entries); a file that cannot be stat'ed is an OpticsFileError."""
    path = Path(path)
    try:
        st = path.stat()
    except OSError as exc:
        raise OpticsFileError(f"{path}: cannot be read ({exc.strerror or exc})") from None
    key = (str(path.resolve()), st.st_size, st.st_mtime_ns)
    if key not in cache:
        if len(cache) > 64:
            cache.clear()
        cache[key] = read(path)
    return cache[key]


def read_table(path) -> OpticalTable:
    """OpticalTable.load(path), read once per resolved path, size and modification time (a case reads its
    table at every validation)."""
    return read_once(_READ_CACHE, path, OpticalTable.load)


def stored_copy(table: OpticalTable) -> Path:
    """A file holding `table`, named by its digest in the cache (:func:`cache_directory`): written once,
    the same path for the same table."""
    path = cache_directory() / f"table-{table.digest}.npz"
    if not (path.is_file() and read_table(path).digest == table.digest):
        table.save(path)
    return path


def cache_directory() -> Path:
    """$LIGHTSAIL_MBS_CACHE/optics, else $XDG_CACHE_HOME/lightsail-mbs/optics, else ~/.cache/lightsail-mbs/optics."""
    root = os.environ.get("LIGHTSAIL_MBS_CACHE")
    if root:
        return Path(root) / "optics"
    base = os.environ.get("XDG_CACHE_HOME") or Path.home() / ".cache"
    return Path(base) / "lightsail-mbs" / "optics"


def atomic_savez(path: Path, arrays: dict) -> None:
    """Write `arrays` as a .npz file at `path` atomically: a reader finds the old file or the new one."""
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(prefix=path.stem, suffix=".npz", dir=path.parent)
    os.close(fd)
    try:
        np.savez_compressed(tmp, **arrays)
        os.replace(tmp, path)
    finally:
        if os.path.exists(tmp):
            os.unlink(tmp)
