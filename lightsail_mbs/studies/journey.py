"""The whole acceleration of a sail: its trajectory to a target speed under constant beam power, and at snapshots
along it the sail-frame beam, the temperature field, the thermal strain, the tension left and the margin to the
paper's criteria, with a verdict (docs/journey.md).

**What is quasi-static.** The trajectory is the closed form of a flat craft of constant rest mass m under
constant intercepted power P (:class:`lightsail_mbs.model.relativity.Trajectory`, coefficient c_n(0) = 2R + α
of the case). In the sail's rest frame the intensity I' = I (1 − β)/(1 + β), the acceleration g₀ ∝ I' and the
wavelength λ' change on the proper-time scale c/(2g₀) (:func:`lightsail_mbs.model.thermal.change_time_scale`):
minutes to hours for the cases in docs/journey.md. The film's thermal time ρ c_p h/(4εσT³) is milliseconds to
seconds, so the temperature is the steady field of each moment (:func:`lightsail_mbs.model.thermal.steady_profile`;
every snapshot reports both times and the lag they imply, :func:`lightsail_mbs.model.thermal.lag`; the journey
refuses a case where T would lag its steady field by more than 1 %). The paper's
shape criteria are quasi-static too (Eqs 8 and 10 at the intensity of the moment), and so is the optional
shape run of each snapshot: the case at that moment's intensity and tension, solved in the sail's frame.

**The snapshots** are spaced so that g₀ and I' change by the fraction `step` between neighbours (equal steps in
ln I'), T ∝ I'^(1/4) by about step/4 and λ' by step/2 (the default 5 %: at most 1.3 % in T).

**A table with a wavelength axis** (:class:`lightsail_mbs.model.optics.SpectralTable`) is read at each
snapshot's sail-frame wavelength λ' = λ₀ √((1 + β)/(1 − β)) (λ₀ the settings' laser wavelength): its c_n(0; λ')
drives the trajectory (:class:`lightsail_mbs.model.relativity.VaryingTrajectory`, quadratures instead of the
closed forms), its normal-incidence absorptance 1 − R − T heats the film (unless the settings give one or the
table is lossless) and its table at λ' is the shape runs' force law (:meth:`Journey.optics_at`). The snapshots
stay equal steps in ln I'; c_n(0) adds its own change to g₀'s between them, shown in the rows.

**The time domain** is :mod:`lightsail_mbs.studies.journey_run`: the whole journey of a chain as one run, with the
world line (model/world_line.py), the Doppler dimming, the heated film's tension (model/heating.py) and a wavelength
table's force law at λ' inside it. Here the snapshots' shape runs keep the intensity of their moment. The first-order
velocity-dependent terms of the load are a physics term (model.terms.velocity, case field velocity_terms) that the
snapshots' shape runs do not switch on.
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass

import numpy as np

from lightsail_mbs.base.validation import ParameterError, check, finite
from lightsail_mbs.model import expansion, materials, relativity, thermal
from lightsail_mbs.model.parameters import SailParameters

LASER_WAVELENGTH = 1.064e-6  # m: the Starshot beam (Nd:YAG / Yb fibre lasers; Parkin 2018's 1.06 µm)
QUASI_STEADY_LIMIT = 1e-2  # the largest lag of T behind its steady field (a fraction of T) the journey accepts


@dataclass(frozen=True)
class JourneySettings:
    """How the journey runs: the beam power P the sail intercepts (W, lab frame), the target speed β, the
    laser's wavelength, the thermal inputs that override the case's material (absorptance, emissivities),
    the surroundings' and the reference (tensioning) temperatures, the snapshots' fractional step in g₀, and
    whether each snapshot is run for its shape with the reduced solver (shape_time: its duration in units of
    the finite-amplitude time t_c). carried_mass: mass the craft carries beyond the case's sail and payload
    (kg; a payload the case's shape model does not hold, e.g. on an extensible TnT chain)."""

    power: float
    target_speed: float = 0.2
    wavelength: float = LASER_WAVELENGTH
    material: str | None = None
    absorptance: float | None = None
    emissivity_front: float | None = None
    emissivity_back: float | None = None
    environment: float = thermal.DEEP_SPACE
    reference_temperature: float = 293.15
    step: float = 0.05
    shape_runs: bool = False
    shape_time: float = 20.0
    carried_mass: float = 0.0

    def __post_init__(self):
        for name in ("power", "wavelength", "step", "shape_time"):
            check(name, getattr(self, name), finite(name, getattr(self, name)) > 0, "> 0")
        v = finite("target_speed", self.target_speed)
        check("target_speed", v, 0 < v < 1, "0 < β < 1 (a fraction of c)")
        check("step", self.step, self.step <= 0.5, "0 < step ≤ 0.5 (the fractional change of g₀ between snapshots)")
        for name in ("environment", "reference_temperature", "carried_mass"):
            check(name, getattr(self, name), finite(name, getattr(self, name)) >= 0, "≥ 0 (K, kg)")
        if self.absorptance is not None:
            v = finite("absorptance", self.absorptance)
            check("absorptance", v, 0 <= v <= 1, "0 ≤ A ≤ 1")
        for name in ("emissivity_front", "emissivity_back"):
            if getattr(self, name) is not None:
                v = finite(name, getattr(self, name))
                check(name, v, 0 <= v <= 1, "0 ≤ ε ≤ 1")
        if self.material is not None:
            materials.get(self.material)


@dataclass(frozen=True)
class Film:
    """The thermal and elastic inputs of the journey: the material's values under the settings' overrides."""

    material: str
    absorptance: float
    emissivity: float  # ε_f + ε_b
    heat_capacity: float  # c_p, J/(kg·K)
    conductivity: float  # k, W/(m·K)
    expansion: float  # α_T, 1/K
    poisson: float
    limit_temperature: float  # K

    @classmethod
    def of(cls, p: SailParameters, s: JourneySettings) -> Film:
        name = s.material or p.material
        if name is None:
            raise ParameterError(
                f"material=None is invalid: allowed one of {', '.join(materials.MATERIALS)} (the journey needs "
                "the film's thermal properties: --material NAME)"
            )
        m = materials.get(name)
        front = m.emissivity_front.value if s.emissivity_front is None else s.emissivity_front
        back = m.emissivity_back.value if s.emissivity_back is None else s.emissivity_back
        check("emissivity_front", front, front + back > 0, "ε_f + ε_b > 0 (the film must radiate)")
        return cls(
            name,
            m.absorptance.value if s.absorptance is None else s.absorptance,
            front + back,
            m.heat_capacity.value,
            m.conductivity.value,
            m.thermal_expansion.value,
            m.poisson_ratio.value,
            m.limit_temperature.value,
        )


def craft_mass(p: SailParameters, carried: float = 0.0) -> float:
    """m = ρ h L W + m_p + carried (kg): the sail, its payload and what else the craft carries."""
    return p.density * p.thickness * p.length * p.width + p.payload_mass + carried


def lab_peak_intensity(p: SailParameters, power: float) -> float:
    """I₀ (W/m², lab frame) of the case's beam profile that puts the power P on the sail: P/(L W) × I₀/Ī."""
    return power / (p.length * p.width) * p.intensity / p.mean_intensity


def snapshot_speeds(target: float, step: float) -> np.ndarray:
    """β of the snapshots from rest to the target: equal steps in ln I' = ln((1 − β)/(1 + β)), each at most a
    change of the fraction `step` in g₀ (and I')."""
    drop = -math.log((1.0 - target) / (1.0 + target))
    count = max(2, math.ceil(drop / -math.log(1.0 - step)))
    factors = np.exp(-np.linspace(0.0, drop, count + 1))  # (1 − β)/(1 + β)
    betas = (1.0 - factors) / (1.0 + factors)
    betas[-1] = target
    return betas


def spectrum_of(p: SailParameters):
    """The case's optical table with a wavelength axis (:class:`lightsail_mbs.model.optics.SpectralTable`), or
    None (no table file, or a table at one wavelength)."""
    if not p.optics_file:
        return None
    from lightsail_mbs.model import optics

    try:
        return optics.read_spectrum(p.optics, single=True)
    except optics.OpticsFileError as exc:
        raise ParameterError(f"optics={p.optics!r} is invalid: {exc}") from None


class Journey:
    """The journey of a case under the settings: snapshots (:meth:`snapshot`), the rows of all of them
    (:meth:`run`), and the verdict (:meth:`verdict`)."""

    def __init__(self, p: SailParameters, s: JourneySettings):
        check(
            "initial_beta",
            p.initial_beta,
            p.initial_beta == 0,
            "0 for a journey (it follows the sail from rest; each snapshot's shape run is lit at its moment's "
            "Doppler-shifted intensity)",
        )
        self.case, self.settings, self.film = p, s, Film.of(p, s)
        self.mass = craft_mass(p, s.carried_mass)
        self.spectrum = spectrum_of(p)
        if self.spectrum is None:
            self.trajectory = relativity.Trajectory(s.power, self.mass, p.normal_momentum)
        else:
            self.trajectory = self._spectral_trajectory()
        self.peak = lab_peak_intensity(p, s.power)
        self.edges = np.linspace(0.0, p.length, p.n + 1)
        centres = 0.5 * (self.edges[1:] + self.edges[:-1])
        profile = np.ones(p.n) if p.uniform_beam else thermal.gaussian_flux(centres, 1.0, p.beam_waist, p.beam_centre)
        self.profile = profile  # I(x)/I₀ along the slices (a sheet: through the beam's axis)

    def _spectral_trajectory(self) -> relativity.VaryingTrajectory:
        """The trajectory with c_n(0) of the table at λ'(β), after checking that the table covers the
        sail-frame wavelengths from rest to the target speed."""
        spectrum, s = self.spectrum, self.settings
        lo, hi = spectrum.range
        top = s.wavelength * float(relativity.wavelength_factor(s.target_speed))
        if not (lo * (1 - 1e-12) <= s.wavelength and top <= hi * (1 + 1e-12)):
            raise ParameterError(
                f"wavelength={s.wavelength:.6g} is invalid: allowed a laser wavelength whose sail-frame "
                f"wavelengths up to β = {s.target_speed:g}, {s.wavelength:.6g} … {top:.6g} m, lie inside the "
                f"wavelengths of the optical table {self.case.optics}, {lo:.6g} … {hi:.6g} m"
            )
        normal = np.array([t.normal_at_zero for t in spectrum.tables])  # c_n(0) is linear in λ between them

        def coefficient(beta):
            return float(
                np.interp(s.wavelength * float(relativity.wavelength_factor(beta)), spectrum.wavelengths, normal)
            )

        ratio = (spectrum.wavelengths / s.wavelength) ** 2  # (1 + β)/(1 − β) at each grid wavelength
        kinks = [(r - 1) / (r + 1) for r in ratio if r > 1 and (r - 1) / (r + 1) < s.target_speed]
        return relativity.VaryingTrajectory(s.power, self.mass, coefficient, kinks)

    def optics_at(self, beta: float) -> tuple[SailParameters, float, dict]:
        """The case, the absorptance and the extra row entries at β: with a wavelength table, the case with its
        table at λ'(β) (a file in the cache, :func:`lightsail_mbs.model.optics.stored_copy`), the table's
        normal-incidence absorptance 1 − R − T there unless the settings give one or the table is lossless;
        otherwise the case and the film's absorptance, no extra entries."""
        if self.spectrum is None:
            return self.case, self.film.absorptance, {}
        from lightsail_mbs.model import optics

        lam = self.settings.wavelength * float(relativity.wavelength_factor(beta))
        table = self.spectrum.at(lam)
        case = self.case.replace(optics=str(optics.stored_copy(table)))
        own = self.settings.absorptance is None and not self.spectrum.lossless
        absorptance = self.spectrum.normal_absorptance(lam) if own else self.film.absorptance
        return case, absorptance, {"normal_momentum": table.normal_at_zero, "absorptance": absorptance}

    def temperatures(self, sail_peak: float, absorptance: float | None = None) -> np.ndarray:
        """The slices' steady temperatures (K) at the sail-frame peak intensity I'₀ (absorptance: the film's
        unless given): radiative equilibrium for a uniform beam, the conducting strip's field for a Gaussian
        one."""
        f, p = self.film, self.case
        flux = (f.absorptance if absorptance is None else absorptance) * sail_peak * self.profile
        if p.uniform_beam:
            return np.asarray(thermal.equilibrium_temperature(flux, f.emissivity, self.settings.environment))
        conductance = f.conductivity * p.thickness
        return thermal.steady_profile(self.edges, flux, conductance, f.emissivity, self.settings.environment)

    def snapshot(self, beta: float) -> dict:
        """Every number of the moment the sail reaches β (SI units; a row of journey.csv)."""
        s, f, tr = self.settings, self.film, self.trajectory
        p, absorptance, extra = self.optics_at(beta)
        factor = float(relativity.intensity_factor(beta))
        sail_peak = self.peak * factor
        T = self.temperatures(sail_peak, absorptance)
        mean = float(np.mean(T))
        rise = mean - s.reference_temperature
        tension = expansion.remaining_tension(p, f.expansion, f.poisson, rise)
        limit = expansion.critical(p, sail_peak)
        g0 = float(tr.proper_acceleration(beta))
        thermal_time = float(thermal.time_scale(p.density * f.heat_capacity * p.thickness, f.emissivity, T.max()))
        return {
            "t": float(tr.time(beta)),
            "tau": float(tr.proper_time(beta)),
            "beta": float(beta),
            "distance": float(tr.distance(beta)),
            "intensity_sail": sail_peak,
            "acceleration": g0,
            "wavelength": s.wavelength * float(relativity.wavelength_factor(beta)),
            "temperature_max": float(T.max()),
            "temperature_mean": mean,
            "thermal_strain": float(expansion.thermal_strain(f.expansion, mean, s.reference_temperature)),
            "tension": math.nan if tension is None else tension,
            "critical": _nan(limit),
            "margin": _nan(expansion.margin(p, sail_peak, tension)),
            # the pre-tension that would leave exactly the critical tension: the relief plus the criterion
            "tension_needed": math.nan if tension is None else p.tension + p.edge_tension - tension + limit,
            "thermal_time": thermal_time,
            "change_time": float(thermal.change_time_scale(g0)),
            "thermal_lag": thermal.lag(thermal_time, float(thermal.change_time_scale(g0)), T.max(), s.environment),
            **extra,
        }

    def run(self, progress: bool = False, store=None, limit: int | None = None) -> list[dict]:
        """The snapshots from rest to the target speed (and, with shape_runs, each one's shape run). store: a
        :class:`~lightsail_mbs.studies.journey_store.RowStore` that the finished rows are read from and written
        to as they are made; limit: compute at most this many snapshots now (the rows so far are returned, the
        journey unfinished)."""
        from tqdm import tqdm

        betas = snapshot_speeds(self.settings.target_speed, self.settings.step)
        rows = store.done() if store is not None else []
        todo = betas[len(rows) :] if limit is None else betas[len(rows) : len(rows) + limit]
        for beta in tqdm(
            todo, desc="journey", unit="snapshot", disable=not progress, initial=len(rows), total=len(betas)
        ):
            row = self.snapshot(float(beta))
            if self.settings.shape_runs:
                row.update(shape_run(self.optics_at(float(beta))[0], row, self.settings.shape_time))
            rows.append(row)
            if store is not None:
                store.add(row)
        if len(rows) < len(betas):
            return rows
        worst = max(r["thermal_lag"] for r in rows)
        if worst > QUASI_STEADY_LIMIT:
            raise ParameterError(
                f"thickness={self.case.thickness!r} is invalid: allowed a film whose thermal time keeps its "
                f"temperature within {QUASI_STEADY_LIMIT:g} of the steady field (here it lags by {worst:.3g} of "
                "it): the quasi-steady journey would not describe it"
            )
        return rows

    def verdict(self, rows: list[dict]) -> dict:
        """The journey's outcome: 'temperature' (T_max exceeds T_lim), 'shape' (the margin falls below 1) or
        'intact' (neither up to the target speed), at the first snapshot where it happens. (Under constant
        power I' only falls along the way, and with it T, the tension's relief and the criterion: the first
        violation is at the start or nowhere. A power that changes in time would need the moment located
        between snapshots.)"""
        limit = self.film.limit_temperature
        for row in rows:
            if row["temperature_max"] > limit:
                what = f"exceeds the limit temperature {limit:.4g} K ({row['temperature_max']:.4g} K)"
            elif row["margin"] < 1:  # NaN (no criterion) compares False
                what = f"fails by shape (margin {row['margin']:.3g} < 1)"
            else:
                continue
            kind = "temperature" if what.startswith("exceeds") else "shape"
            moment = f"τ = {row['tau']:.4g} s (t = {row['t']:.4g} s, β = {row['beta']:.4g})"
            return {
                "verdict": kind,
                "beta": row["beta"],
                "t": row["t"],
                "tau": row["tau"],
                "text": f"{what} at {moment}",
            }
        return {"verdict": "intact", "text": f"reaches β = {self.settings.target_speed:g} intact"}


def _nan(value):
    return math.nan if value is None else float(value)


def shape_run(p: SailParameters, row: dict, duration: float, solver: str = "reduced") -> dict:
    """The snapshot's case solved for its shape in the sail's frame (no uncertainty twins): the intensity of the
    moment and, for a framed model, the tension left (a slack film: 0), a free chain expanded by the moment's
    thermal strain (:func:`lightsail_mbs.model.expansion.heated_case`), for `duration` finite-amplitude times
    t_c. Returns whether it failed and when (s of proper time from the snapshot)."""
    from lightsail_mbs.analysis.runs import solve
    from lightsail_mbs.base.settings import RunSettings
    from lightsail_mbs.model.theory import time_scale

    changes = {"intensity": row["intensity_sail"]}
    if p.model == "tnt":
        changes["tension"] = max(row["tension"], 0.0)
    elif p.model == "sheet":
        changes["edge_tension"] = max(row["tension"], 0.0)
    case = p.replace(**changes)
    if p.model in ("rigid", "torsion") and p.boundary == "free":
        case = expansion.heated_case(case, row["thermal_strain"])
    result = solve(case, solver, RunSettings(t_final=duration * time_scale(case)), uncertainty=False)
    summary = result.summary()
    return {"shape_failed": bool(summary["failed"]), "shape_failure_time": _nan(summary.get("failure_time"))}


def notes(p: SailParameters, film: Film) -> list[str]:
    """Where the case's own values differ from its film's (materials.CASE_FIELDS): set on purpose, or a case
    built without materials.fill (a bare SailParameters(material=…) keeps the defaults)."""
    m = materials.get(film.material)
    return [
        f"the case's {field} {getattr(p, field):g} differs from {m.name}'s {m.value(prop):g}"
        for field, prop in materials.CASE_FIELDS.items()
        if getattr(p, field) != m.value(prop)
    ]


def run_journey(p: SailParameters, s: JourneySettings, progress: bool = False, folder=None) -> dict:
    """The journey's report: the case, the settings, the film, the snapshots (each with the verdict so far,
    :func:`with_verdict`), the verdict and the ratio of the thermal to the beam's time scale (what makes the
    temperature quasi-steady). folder: keep the finished rows there and resume from them
    (:mod:`lightsail_mbs.studies.journey_store`)."""
    journey = Journey(p, s)
    store = None
    if folder is not None:
        from lightsail_mbs.studies.journey_store import RowStore, key_of

        store = RowStore(folder, key_of(p.to_dict(), asdict(s)), snapshot_speeds(s.target_speed, s.step))
    rows = journey.run(progress, store)
    verdict = journey.verdict(rows)
    return {
        "case": p.to_dict(),
        "settings": asdict(s),
        "film": asdict(journey.film),
        "mass": journey.mass,
        "lab_peak_intensity": journey.peak,
        "snapshots": with_verdict(rows, verdict),
        "verdict": verdict,
        "quasi_steady_ratio": max(r["thermal_time"] / r["change_time"] for r in rows),
        "thermal_lag": max(r["thermal_lag"] for r in rows),
        "notes": notes(p, journey.film),
        "optics": optics_report(journey),
        "resume": None if store is None else store.report(),
    }


def with_verdict(rows: list[dict], verdict: dict) -> list[dict]:
    """The rows with the column ``verdict``: the journey's outcome so far, 'intact' before the verdict's moment and
    its kind ('temperature', 'shape', 'stopped') from the first row at or after it (the last row's is the
    journey's; a verdict without a moment, a run stopped by its error, marks the last row)."""
    moment = verdict.get("tau", math.inf if verdict["verdict"] == "intact" else rows[-1]["tau"])
    return [{**row, "verdict": verdict["verdict"] if row["tau"] >= moment else "intact"} for row in rows]


def optics_report(journey: Journey) -> dict:
    """How the journey read the case's optics: a table with a wavelength axis at each snapshot's sail-frame
    wavelength (its range, where the absorptance came from), or the case's one law throughout."""
    spectrum, s = journey.spectrum, journey.settings
    if spectrum is None:
        return {"wavelength_axis": False, "text": "the case's optics at every wavelength (no wavelength axis)"}
    source = "the film's" if s.absorptance is not None or spectrum.lossless else "the table's 1 − R − T at θ = 0"
    lo, hi = spectrum.range
    return {
        "wavelength_axis": True,
        "table": journey.case.optics,
        "wavelength_range": [lo, hi],
        "absorptance": source,
        "text": f"the optical table {journey.case.optics} read at each snapshot's sail-frame wavelength λ' "
        f"(its range {lo:.6g} … {hi:.6g} m, linear in λ): the force law and c_n(0) in the trajectory; absorptance "
        f"{source}",
    }
