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
* compiled (both solvers' numba kernels): ``packed = table.packed()`` is one contiguous float64
  vector that the solver keeps beside its constants (:func:`solver_block`: the slices' flags, then the
  packed table); inside the kernel ``fx, fy = packed_net_force(...)`` gives each slice's net force in the
  accelerating frame, ``packed_force`` and ``packed_coefficients`` the radiation alone
  (:mod:`lightsail_mbs.model.optics_kernels`, with the layout of ``packed``).

**Table files** (:meth:`OpticalTable.save`): ``.npz`` with arrays ``theta``, ``s_n``, ``s_t``,
``coef_n``, ``coef_t`` (the spline), ``c_n``, ``c_t`` (the coefficients at the nodes, for reading
by eye or another program), optional per-node ``extra_*`` arrays (the RCWA totals R, T, A), and
``metadata``: one JSON string with ``format`` = "lightsail-mbs optical table", ``format_version``,
``kind``, ``polarization``, the constants A_n, A_t, ``bounded`` and, for a grating, its geometry,
cache keys, RCWA backend and version, harmonics, angle range, step, grading and refinement, Rayleigh
anomalies and the CPU time of its RCWA. A table with a wavelength axis is ``format_version`` 2
(:mod:`~lightsail_mbs.model.optics_spectrum`); read as one table, it is its table at the laser's wavelength.

**Cache.** RCWA samples are cached on disk (:func:`cache_directory`: ``$LIGHTSAIL_MBS_CACHE/optics``
or ``~/.cache/lightsail-mbs/optics``): one file per grating geometry, polarisation, backend and its
version, harmonics and source of model/grating.py and model/rcwa.py (a SHA-256 of all of them) holds
every angle computed for them, so a change of any of them computes afresh, nothing stale is served, and a table on other
nodes reuses the angles it shares.

**Where it is written.** This module holds the built-in laws and what a solver reads for a case
(:func:`slice_flags`, :func:`solver_block`); the table, its numpy evaluation and its files are
:mod:`~lightsail_mbs.model.optics_table`, the compiled law :mod:`~lightsail_mbs.model.optics_kernels`,
grating tables by RCWA :mod:`~lightsail_mbs.model.optics_grating`, tables with a wavelength axis
:mod:`~lightsail_mbs.model.optics_spectrum` (file format version 2). Their names are importable from here.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from lightsail_mbs.base.constants import SPEED_OF_LIGHT
from lightsail_mbs.base.validation import check, finite
from lightsail_mbs.model.optics_grating import (
    DEFAULT_GRADE,
    DEFAULT_HARMONICS,
    DEFAULT_PASSES,
    DEFAULT_STEP,
    DEFAULT_THETA_MAX,
    DEFAULT_TOLERANCE,
    MAX_THETA,
    SAMPLE_FIELDS,
    backend_version,
    grating_table,
    node_grid,
    rcwa_code_hash,
    rcwa_samples,
)
from lightsail_mbs.model.optics_kernels import (
    PACKED_HEADER,
    PACKED_VERSION,
    packed_coefficients,
    packed_force,
    packed_net_force,
    packed_tabulated,
)
from lightsail_mbs.model.optics_spectrum import SpectralTable, grating_spectrum, read_spectrum
from lightsail_mbs.model.optics_table import (
    FORMAT,
    FORMAT_VERSION,
    TABLE_POLARIZATIONS,
    OpticalTable,
    OpticsFileError,
    cache_directory,
    read_table,
    stored_copy,
)

if TYPE_CHECKING:  # annotations only: the case (model/parameters.py) imports this module, not the reverse
    from lightsail_mbs.model.parameters import SailParameters

# the room's names, wherever they are defined: this module is where the rest of the package reads optics
__all__ = [
    "DEFAULT_GRADE",
    "DEFAULT_HARMONICS",
    "DEFAULT_PASSES",
    "DEFAULT_STEP",
    "DEFAULT_THETA_MAX",
    "DEFAULT_TOLERANCE",
    "FORMAT",
    "FORMAT_VERSION",
    "MAX_THETA",
    "PACKED_HEADER",
    "PACKED_VERSION",
    "SAMPLE_FIELDS",
    "SPEED_OF_LIGHT",
    "SpectralTable",
    "TABLE_POLARIZATIONS",
    "OpticalTable",
    "OpticsFileError",
    "backend_version",
    "cache_directory",
    "facet",
    "for_case",
    "grating_spectrum",
    "grating_table",
    "mirror",
    "node_grid",
    "packed_coefficients",
    "packed_force",
    "packed_net_force",
    "packed_tabulated",
    "rcwa_code_hash",
    "rcwa_samples",
    "read_spectrum",
    "read_table",
    "slice_flags",
    "solver_block",
    "stored_copy",
]


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
