"""Optical tables with a wavelength axis: :class:`SpectralTable`, the force law c_n(θ; λ), c_t(θ; λ) of one
grating tabulated at several vacuum wavelengths λ_1 < … < λ_K on one set of angle nodes, and the table at any
wavelength between them.

**Why a wavelength axis.** A sail receding at βc sees the laser's wavelength λ₀ stretched to
λ' = λ₀ √((1 + β)/(1 − β)) (:mod:`lightsail_mbs.model.relativity`): 1.22 λ₀ at β = 0.2. A grating's
response moves with λ/Λ (its Rayleigh anomalies sit at sin θ = ±(1 − mλ/Λ)) and with the dispersion of its
materials, so the journey (:mod:`lightsail_mbs.studies.journey`) reads the table at λ' of each moment.

**How it is made** (:func:`grating_spectrum`): the grating is built at each λ_k (a material name is
evaluated at λ_k from meent's dispersive tables; a number or eps=… keeps its value) and tabulated by RCWA as
:func:`~lightsail_mbs.model.optics_grating.grating_tables` does: one node set for all wavelengths, whose
breaks are the Rayleigh anomalies of every λ_k, refined where any wavelength's spline misses its RCWA
midpoint.

**Interpolation in λ** (:meth:`SpectralTable.at`): linear between the two grid wavelengths around λ,
c(θ; λ) = (1 − w) c(θ; λ_k) + w c(θ; λ_{k+1}), w = (λ − λ_k)/(λ_{k+1} − λ_k). With one node set and one set
of breaks, a not-a-knot spline's coefficients are linear in its node values, so the table at λ is the spline
through the interpolated node values and is itself an :class:`~lightsail_mbs.model.optics_table.OpticalTable`
(the solvers read it unchanged); at a grid wavelength it is that wavelength's table exactly. Linear rather
than cubic in λ: the coefficients have square-root kinks where an anomaly crosses an angle node between two
grid wavelengths, and a linear interpolant does not overshoot there; its error away from the anomalies is
(Δλ)²/8 · |∂²c/∂λ²| (tests/model/test_optics_spectrum.py measures it against RCWA at a wavelength between
two grid wavelengths). A wavelength outside [λ_1, λ_K] is refused (:meth:`SpectralTable.check`), never
extrapolated.

**The file** (:meth:`SpectralTable.save`): the ``.npz`` format of :mod:`lightsail_mbs.model.optics` at
``format_version`` 2, one file for all wavelengths: ``wavelengths`` (K), ``theta`` (N), ``s_n``, ``s_t``
(K, N), ``coef_n``, ``coef_t`` (K, 4, N − 1), ``c_n``, ``c_t`` (K, N), per-node ``extra_*`` arrays (K, N) and
``metadata``, whose ``wavelength`` is the laser's λ₀ (inside the range) and ``tables`` the metadata of each
wavelength's table. One file rather than a set with a manifest: the wavelengths share their nodes, so one
file holds them without repetition, and a case names one path as for any table. Version 1 files (one
wavelength) are written and read as before; :meth:`OpticalTable.load
<lightsail_mbs.model.optics_table.OpticalTable.load>` reads a version 2 file as its table at λ₀ (this module
registers the reader in ``optics_table.VERSION_READERS``; :mod:`lightsail_mbs.model.optics` imports it), so a case
with a wavelength table runs at rest as with the single table at the laser's wavelength, and
:func:`read_spectrum` reads the whole file.
"""

from __future__ import annotations

import json
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from lightsail_mbs.base.validation import ParameterError, check, finite
from lightsail_mbs.model.optics_table import (
    FORMAT,
    SPECTRAL_VERSION,
    VERSION_READERS,
    OpticalTable,
    OpticsFileError,
    atomic_savez,
    read_once,
)

PER_NODE = ("s_n", "s_t", "coef_n", "coef_t")


@dataclass(frozen=True, eq=False)
class SpectralTable:
    """Tables of one grating at the wavelengths λ_1 < … < λ_K (m), on one set of angle nodes and breaks.

    wavelength: the laser's wavelength λ₀ (m, inside the range): the table a case uses at rest.
    source: where the table was read from (named in the errors)."""

    wavelengths: np.ndarray
    tables: tuple
    wavelength: float
    metadata: dict = field(default_factory=dict)
    source: str = "(not saved)"

    def __post_init__(self):
        lam = np.ascontiguousarray(self.wavelengths, float)
        check("wavelengths", lam.tolist(), lam.ndim == 1 and lam.size >= 2, "at least 2 wavelengths")
        check("wavelengths", lam.tolist(), bool(np.all(lam > 0) and np.all(np.diff(lam) > 0)), "increasing, > 0 (m)")
        check("tables", len(self.tables), len(self.tables) == lam.size, f"one table per wavelength ({lam.size})")
        first = self.tables[0]
        for t in self.tables:
            same = t.theta.shape == first.theta.shape and np.array_equal(t.theta, first.theta)
            check("tables", "nodes", same and t.bounded and t.polarization == first.polarization, "one node set")
        object.__setattr__(self, "wavelengths", lam)
        object.__setattr__(self, "tables", tuple(self.tables))
        v = finite("wavelength", self.wavelength)
        object.__setattr__(self, "wavelength", v)
        self.check(v, "wavelength")

    @property
    def range(self) -> tuple[float, float]:
        return float(self.wavelengths[0]), float(self.wavelengths[-1])

    def check(self, wavelength: float, name: str = "wavelength") -> float:
        """`wavelength` (m) if inside the table's range, else one ParameterError naming the file, the
        wavelength and the range."""
        lo, hi = self.range
        v = finite(name, wavelength)
        if not lo * (1 - 1e-12) <= v <= hi * (1 + 1e-12):
            raise ParameterError(
                f"{name}={v:.6g} m is invalid: allowed {lo:.6g} … {hi:.6g} m, the wavelengths of the optical "
                f"table {self.source} (tabulate a wider range: lightsail-mbs optics grating --wavelengths …)"
            )
        return min(max(v, lo), hi)

    def weights(self, wavelength: float) -> tuple[int, float]:
        """(k, w): λ = (1 − w) λ_k + w λ_{k+1} (checked against the range); a wavelength within 1e-12 of a
        grid wavelength is that wavelength (w = 0 or 1: a range spec's round-off gives its table exactly)."""
        v = self.check(wavelength)
        nearest = int(np.argmin(np.abs(self.wavelengths - v)))
        if abs(self.wavelengths[nearest] - v) <= 1e-12 * v:
            v = float(self.wavelengths[nearest])
        k = int(np.clip(np.searchsorted(self.wavelengths, v, side="right") - 1, 0, self.wavelengths.size - 2))
        lo, hi = self.wavelengths[k], self.wavelengths[k + 1]
        return k, float((v - lo) / (hi - lo))

    def at(self, wavelength: float) -> OpticalTable:
        """The table at `wavelength` (m): linear in λ between the grid wavelengths around it (module
        docstring); a grid wavelength's own table there."""
        k, w = self.weights(wavelength)
        a, b = self.tables[k], self.tables[k + 1]
        if w == 0.0:
            return a
        if w == 1.0:
            return b

        def mix(x, y):
            return (1.0 - w) * np.asarray(x) + w * np.asarray(y)

        arrays = {name: mix(getattr(a, name), getattr(b, name)) for name in PER_NODE}
        extra = {key: mix(a.extra[key], b.extra[key]) for key in a.extra if key in b.extra}
        meta = {
            **a.metadata,
            "wavelength": float(wavelength),
            "interpolated": {"between_m": [float(self.wavelengths[k]), float(self.wavelengths[k + 1])], "weight": w},
        }
        return OpticalTable(
            a.theta,
            arrays["s_n"],
            arrays["s_t"],
            arrays["coef_n"],
            arrays["coef_t"],
            a.normal_constant,
            a.tangential_constant,
            True,
            a.polarization,
            meta,
            extra,
        )

    def rest(self) -> OpticalTable:
        """The table at the laser's wavelength λ₀."""
        return self.at(self.wavelength)

    def normal_absorptance(self, wavelength: float) -> float:
        """A(0; λ) = 1 − R − T at normal incidence (the mean of the polarisations the table holds), linear in λ."""
        table = self.at(wavelength)
        node = int(np.argmin(np.abs(table.theta)))
        values = [v[node] for key, v in table.extra.items() if key.startswith("A_")]
        check("table", self.source, bool(values) and table.theta[node] == 0.0, "a grating table with its RCWA totals")
        return float(np.mean(values))

    @property
    def lossless(self) -> bool:
        return all(bool(t.metadata.get("lossless", False)) for t in self.tables)

    # ---- files ----------------------------------------------------------------------------------
    def to_arrays(self) -> dict:
        per = [t.to_arrays() for t in self.tables]
        meta = {
            **{k: v for k, v in self.metadata.items() if k != "tables"},
            "format": FORMAT,
            "format_version": SPECTRAL_VERSION,
            "kind": "grating spectrum",
            "wavelength": self.wavelength,
            "wavelengths": self.wavelengths.tolist(),
            "tables": [json.loads(str(d["metadata"])) for d in per],
        }
        stacked = {k: np.stack([d[k] for d in per]) for k in per[0] if k not in ("metadata", "theta")}
        return dict(wavelengths=self.wavelengths, theta=per[0]["theta"], metadata=np.array(json.dumps(meta)), **stacked)

    @classmethod
    def from_arrays(cls, arrays, source: str) -> SpectralTable:
        """The spectral table of arrays named as by :meth:`to_arrays`; OpticsFileError names what is wrong."""
        try:
            meta = json.loads(str(arrays["metadata"]))
            lam = np.array(arrays["wavelengths"], float)
            per = []
            for k, table_meta in enumerate(meta["tables"]):
                per_node = (key for key in arrays if key not in ("metadata", "wavelengths", "theta"))
                one = {key: np.array(arrays[key][k]) for key in per_node}
                one.update(theta=np.array(arrays["theta"]), metadata=np.array(json.dumps(table_meta)))
                per.append(OpticalTable.from_arrays(one, f"{source} (λ = {lam[k]:.6g} m)"))
            return cls(lam, tuple(per), meta["wavelength"], meta, source)
        except OpticsFileError:
            raise
        except (OSError, ValueError, KeyError, IndexError, ParameterError) as exc:
            raise OpticsFileError(f"{source}: not a readable optical table with a wavelength axis ({exc})") from None

    def save(self, path) -> Path:
        path = Path(path)
        check("out", str(path), path.suffix == ".npz", "a path ending in .npz")
        atomic_savez(path, self.to_arrays())
        return path

    def summary(self) -> dict:
        """The rest table's summary (OpticalTable.summary) with the wavelength axis."""
        lo, hi = self.range
        return self.rest().summary() | {
            "format_version": SPECTRAL_VERSION,
            "wavelength": self.wavelength,
            "wavelengths": self.wavelengths.tolist(),
            "wavelength_range": [lo, hi],
            "rcwa_cpu_seconds": float(sum(t.metadata.get("rcwa_cpu_seconds", 0.0) for t in self.tables)),
        }


def is_spectral(path) -> bool:
    """Whether the table file at `path` has a wavelength axis (format version 2)."""
    return isinstance(read_spectrum(path, single=True), SpectralTable)


_CACHE: dict = {}


def read_spectrum(path, single: bool = False):
    """The SpectralTable of a version 2 file, read once per path, size and modification time; a version 1
    file: None with `single`, else an OpticsFileError saying it has no wavelength axis."""
    table = read_once(_CACHE, path, _read_spectrum)
    if table is None and not single:
        raise OpticsFileError(f"{Path(path)}: an optical table at one wavelength (no wavelength axis)")
    return table


def _read_spectrum(path: Path):
    """The SpectralTable of the file at `path`, or None for a valid table at one wavelength."""
    try:
        with np.load(path, allow_pickle=False) as d:
            arrays = {k: d[k] for k in d.files}
    except (OSError, ValueError) as exc:
        raise OpticsFileError(f"{path}: not a readable optical table ({exc})") from None
    if "wavelengths" in arrays:
        return SpectralTable.from_arrays(arrays, str(path))
    OpticalTable.from_arrays(arrays, str(path))  # a bad single table is refused here too
    return None


def grating_spectrum(gratings, wavelength: float, **settings) -> SpectralTable:
    """The SpectralTable of the gratings (one geometry built at each grid wavelength, increasing) by RCWA on
    one node set (:func:`~lightsail_mbs.model.optics_grating.grating_tables`, settings as for
    :func:`~lightsail_mbs.model.optics_grating.grating_table`); `wavelength`: the laser's λ₀."""
    from lightsail_mbs.model.optics_grating import grating_tables

    gratings = list(gratings)
    lam = np.array([g.wavelength for g in gratings])
    tables = grating_tables(gratings, **settings)
    meta = {"kind": "grating spectrum", "name": gratings[0].name}
    return SpectralTable(lam, tuple(tables), wavelength, meta)


def _rest_table(arrays, source: str) -> OpticalTable:
    return SpectralTable.from_arrays(arrays, source).rest()


VERSION_READERS[SPECTRAL_VERSION] = _rest_table
