"""The optical table of a 1-D grating by RCWA (:func:`grating_table`): nodes graded towards the Rayleigh
anomalies, RCWA samples cached on disk, the spline refined where RCWA at a midpoint is off it (the law, the
spline and the cache: :mod:`lightsail_mbs.model.optics`).
"""

from __future__ import annotations

import hashlib
import json
import math
import time
from importlib import metadata as importlib_metadata
from pathlib import Path

import numpy as np

from lightsail_mbs.base.validation import check, finite
from lightsail_mbs.model import grating, rcwa
from lightsail_mbs.model.optics_table import TABLE_POLARIZATIONS, OpticalTable, atomic_savez, cache_directory

DEFAULT_THETA_MAX = math.radians(85.0)
DEFAULT_STEP = math.radians(0.25)
DEFAULT_HARMONICS = 60
DEFAULT_TOLERANCE = 1e-4  # refinement: a midpoint off the spline by more than this becomes a node
DEFAULT_GRADE = 12  # nodes at step·2^(−k), k = 1…12, beside each Rayleigh anomaly
DEFAULT_PASSES = 4
MAX_THETA = math.radians(89.9)


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


def rcwa_code_hash() -> str:
    """SHA-256 (16 hex digits) of model/grating.py and model/rcwa.py: the code that turns a geometry into
    coefficients."""
    digest = hashlib.sha256()
    for module in (grating, rcwa):
        digest.update(Path(module.__file__).read_bytes())
    return digest.hexdigest()[:16]


def backend_version(backend: str) -> str:
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
    its version) and source of model/grating.py and model/rcwa.py is kept in one cache file; only angles
    not in it are computed (cache_dir None: :func:`cache_directory`; False: no cache). Returns the arrays in
    the order of θ, and 'computed': how many angles were new."""
    check("polarization", polarization, polarization in rcwa.POLARIZATIONS, "TE or TM")
    theta = np.asarray(theta, float)
    ident = {
        "geometry": g.to_dict() | {"name": ""},
        "polarization": polarization,
        "harmonics": harmonics,
        "backend": backend,
        "backend_version": backend_version(backend),
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
        atomic_savez(path, dict(theta=angles, values=np.array([store[t] for t in angles]), ident=json.dumps(ident)))
    rows = np.array([store[float(t)] for t in theta]).reshape(theta.size, len(SAMPLE_FIELDS))
    return {"theta": theta, **dict(zip(SAMPLE_FIELDS, rows.T)), "computed": len(missing), "cache_key": key}


def grating_table(g: rcwa.Grating, polarization: str = "TE", **settings) -> OpticalTable:
    """The force table of a grating by RCWA.

    Nodes: :func:`node_grid` (spacing ≤ step, breaks at the Rayleigh anomalies graded by `grade` levels).
    Then up to `passes` refinements: RCWA at the midpoint of every interval wider than step/16 (in later
    passes, of the new intervals), and each midpoint (with its mirror image, so the node set stays
    symmetric) whose c_n or c_t differs from the spline by more than `tolerance` becomes a node
    (tolerance 0: no refinement). polarization: "TE", "TM" or "mean" (unpolarised or circular: the mean
    of the two efficiencies, hence of c_n and c_t, which are linear in them). RCWA samples are cached
    (:func:`rcwa_samples`). settings: harmonics, theta_max (rad), step (rad), backend, cache_dir, progress,
    tolerance, grade, passes, as :func:`grating_tables` takes them."""
    return grating_tables([g], polarization, **settings)[0]


def grating_tables(
    gratings,
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
) -> list[OpticalTable]:
    """The force tables of several gratings (the same geometry at several wavelengths) on one set of nodes,
    as :func:`grating_table` builds one: the breaks are the Rayleigh anomalies of every grating, and a
    midpoint becomes a node where any grating's spline is off by more than `tolerance`. Every table has the
    same nodes and breaks, so its spline coefficients are linear in its node values (one grating: exactly
    :func:`grating_table`'s table)."""
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
    gratings = list(gratings)
    check("gratings", len(gratings), len(gratings) >= 1, "at least one grating")
    if len(gratings) == 1:
        breaks = gratings[0].rayleigh_anomalies(theta_max)
    else:
        breaks = np.unique(np.concatenate([g.rayleigh_anomalies(theta_max) for g in gratings]))
    pols = ("TE", "TM") if polarization == "mean" else (polarization,)
    done = [0]

    def sample(angles):
        out = [{p: rcwa_samples(g, angles, p, harmonics, backend, cache_dir, tick) for p in pols} for g in gratings]
        done[0] += len(angles) * len(gratings)
        return out

    def tick(i, total):
        if progress is not None:
            progress(done[0] + i, None)

    theta = node_grid(theta_max, step, breaks, grade)
    nodes = sample(theta)
    values = [{p: {k: got[p][k] for k in SAMPLE_FIELDS} for p in pols} for got in nodes]
    candidates = theta
    added, estimate, used = 0, math.nan, 0
    for _ in range(passes if tolerance > 0 else 0):
        used += 1
        lo, hi = candidates[:-1], candidates[1:]
        wide = (hi - lo) > step / 16
        mids = 0.5 * (lo + hi)[wide]
        mids = mids[~np.isin(mids, theta)]
        if mids.size == 0:
            break
        got = sample(mids)
        err = np.zeros(mids.size)
        for value, new_samples in zip(values, got):
            table = _from_samples(theta, value, pols, breaks, polarization)
            c_n = np.mean([new_samples[p]["c_n"] for p in pols], axis=0)
            c_t = np.mean([new_samples[p]["c_t"] for p in pols], axis=0)
            cn_s, ct_s = table.coefficients(mids)
            err = np.maximum(err, np.maximum(np.abs(c_n - cn_s), np.abs(c_t - ct_s)))
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
        for value, new_samples in zip(values, got):
            for p in pols:
                value[p] = {
                    k: np.concatenate([value[p][k], new_samples[p][k][order][flagged]])[keep] for k in SAMPLE_FIELDS
                }
        theta = theta[keep]
        # next pass: the intervals on both sides of every new node
        near = np.unique(np.concatenate([np.searchsorted(theta, new) + d for d in (-1, 0, 1)]))
        candidates = theta[near[(near >= 0) & (near < theta.size)]]
    refinement = dict(refinement_passes=used, refinement_nodes=added, refinement_last_error=estimate)
    settings = dict(harmonics=harmonics, theta_max=theta_max, step=step, grade=grade, tolerance=tolerance)
    tables = []
    for g, value, got in zip(gratings, values, nodes):
        cpu = float(sum(rcwa_samples(g, theta, p, harmonics, backend, cache_dir)["cpu"].sum() for p in pols))
        meta = _metadata(g, backend, settings, refinement, breaks, cpu, [got[p]["cache_key"] for p in pols])
        tables.append(_from_samples(theta, value, pols, breaks, polarization, meta))
    return tables


def _metadata(g, backend, settings, refinement, breaks, cpu, cache_keys) -> dict:
    return {
        "kind": "grating",
        "grating": g.to_dict(),
        "geometry_key": g.key(),
        "backend": backend,
        "backend_version": backend_version(backend),
        "harmonics": settings["harmonics"],
        "theta_max": settings["theta_max"],
        "step": settings["step"],
        "grade": settings["grade"],
        "tolerance": settings["tolerance"],
        **refinement,
        "rayleigh_anomalies": breaks.tolist(),
        "rcwa_cpu_seconds": cpu,
        "rcwa_code": rcwa_code_hash(),
        "cache_keys": cache_keys,
        "lossless": g.lossless,
    }


def _from_samples(theta, values, pols, breaks, polarization, meta=None) -> OpticalTable:
    c_n = np.mean([values[p]["c_n"] for p in pols], axis=0)
    c_t = np.mean([values[p]["c_t"] for p in pols], axis=0)
    extra = {f"{name}_{p}": values[p][name] for p in pols for name in ("R", "T", "A")}
    return OpticalTable.from_samples(theta, c_n, c_t, breaks, polarization, meta or {"kind": "grating"}, extra)
