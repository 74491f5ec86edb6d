"""The failure time a film's seed predicts, from the linear growth spectrum of the chain.

A chain started from its defect shape plus a film (or white roughness) differs from the ideal-defect chain by a
small displacement Δq at rest. Linearised at rest in the initial state, q̈ = A δq (A = ∂q̈/∂q,
:func:`lightsail_mbs.analysis.linear_stability.jacobian`), that difference evolves as

    δq(t) = cosh(√A t) Δq = Σ_i c_i cosh(√μ_i t) v_i,       c = V⁻¹ Δq,

each growing mode (μ_i > 0) as c_i cosh(σ_i t), σ_i = √μ_i: a mode started from rest with displacement c grows as
c cosh(σ t), not c e^{σ t}. The fastest-growing deformation mode sets σ and the wavelength reported; every mode
carries its own projection of the seed. The sail has failed when the failure measure (model.failure: half the
peak-to-peak offset from the best-fit line) of the ideal shape plus δq reaches failure_ratio × its initial value.

**Two predictions.**

* ``spectrum`` (no run needed): the ideal shape is held at its initial state plus its own linear response to the
  initial acceleration it feels, (cosh(√A t) − 1) A⁻¹ q̈₀ (the defect projected on the growing modes). It is late:
  the growth rate of the defect shape rises as the sail moves (σ 6.99 → 7.84 /s by t = 1 s on the paper's soft
  sail at n = 30, 5.75 → 7.25 /s at n = 80, while the amplitude has grown by 2 %), so it overestimates failure
  times by 7–22 % there (validation/prediction.md).
* ``trajectory`` (given the ideal-defect run): the ideal shape is the run's, and δq grows in the stretched time
  τ(t) = ∫₀ᵗ σ(t′)/σ(0) dt′, σ(t′) the fastest growth rate of the run's states linearised at rest
  (TRAJECTORY_SAMPLES of them). One run without a film then predicts the failure time with any film.

**Regime of validity** (validation/prediction.md, 12 seeded films on torsion chains below E_cr,max): the seed must
stay small against the defect until failure, so that δq is linear about the ideal run. The 'trajectory' prediction
is within 5 % in 6 of the 12 cases (the soft sail at n = 30 and 80 and the stiffer sail, films of 1e-10 to 1e-8 m)
and late by 5–12 % in the others: at n = 50, where the fastest wave sits at the grid scale (two slices per
wavelength), and for films of 1e-7 m, which reshape the run itself; one stretch factor for every mode is the
approximation that limits it. The 'spectrum' prediction is late by 13–25 % in every case.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from lightsail_mbs.analysis.finite_amplitude import reduced_equations
from lightsail_mbs.analysis.linear_stability import jacobian
from lightsail_mbs.model import failure, film, shapes
from lightsail_mbs.model.parameters import SailParameters

TRAJECTORY_SAMPLES = 60  # states of the ideal run linearised for the stretched time
TIME_SAMPLES = 3001  # samples of the spectrum-only prediction's amplitude
HORIZON = 30.0  # the spectrum-only prediction looks this many e-foldings of the fastest mode ahead


@dataclass(frozen=True)
class Prediction:
    """A predicted failure time (s, None: no failure predicted within the horizon), the fastest growth rate σ (s⁻¹)
    at the initial state, its mode's wavelength (m), the seed the fastest mode carries (its share of the failure
    measure at t = 0, m) and which prediction it is ('spectrum' or 'trajectory')."""

    time: float | None
    growth_rate: float
    wavelength: float | None
    seed: float
    method: str

    def to_dict(self) -> dict:
        return dict(self.__dict__)


def ideal(p: SailParameters) -> SailParameters:
    """The same case without film or roughness."""
    return p.replace(film_rms=0.0, roughness=0.0)


def _packed(p: SailParameters):
    """(the reduced solver's equations of the chain, q of its initial state)."""
    equations = reduced_equations(p)
    return equations, equations.coordinates(shapes.initial_state(p))


def _modes(p: SailParameters, state) -> tuple[np.ndarray, np.ndarray]:
    """(√μ (complex), V): the eigenvalues' square roots and eigenvectors of A = ∂q̈/∂q at rest in `state`."""
    jac = jacobian(p, state=state, positions_only=True)
    mu, vectors = np.linalg.eig(jac[jac.shape[0] // 2 :])
    return np.sqrt(mu.astype(complex)), vectors


def fastest_rate(p: SailParameters, state) -> float:
    """The largest growth rate (s⁻¹) of the chain linearised at rest in `state`."""
    return float(_modes(p, state)[0].real.max())


def stretched_time(p: SailParameters, trajectory) -> np.ndarray:
    """τ at the run's samples: ∫ σ(t′)/σ(0) dt′ with σ from TRAJECTORY_SAMPLES of the run's states."""
    index = np.unique(np.linspace(0, trajectory.time.size - 1, TRAJECTORY_SAMPLES).astype(int))
    rates = np.array(
        [
            fastest_rate(p, shapes.ChainState(trajectory.x[k], trajectory.y[k], trajectory.theta[k], _z(trajectory, k)))
            for k in index
        ]
    )
    t = trajectory.time[index]
    tau = np.concatenate([[0.0], np.cumsum(0.5 * (rates[1:] + rates[:-1]) * np.diff(t))]) / rates[0]
    return np.interp(trajectory.time, t, tau)


def _z(trajectory, k: int) -> np.ndarray:
    z = trajectory.z[k]
    return z if z.size else np.zeros(trajectory.theta.shape[1] - 1)


def predict(
    params: SailParameters, seed: SailParameters | None = None, trajectory=None, failure_ratio: float = 2.0
) -> Prediction:
    """The failure time of the chain `params` predicted from the linear spectrum (module docstring).

    seed: the case whose start seeds the growth (default `params` itself; a case without film or roughness is
    seeded by the reference film); trajectory: the ideal-defect run (a Result of ``ideal(params)``) for the
    'trajectory' prediction, else the 'spectrum' prediction."""
    seeded = seed if seed is not None else params
    if not seeded.film_rms and not seeded.roughness:
        ref = film.REFERENCE_FILM
        seeded = seeded.replace(film_rms=ref.rms, film_correlation_length=ref.correlation_length, film_hurst=ref.hurst)
    base = ideal(params)
    equations, q_seed = _packed(seeded)
    _, q_ideal = _packed(base)
    roots, vectors = _modes(base, shapes.initial_state(base))
    c = np.linalg.solve(vectors, q_seed - q_ideal)
    offsets_ideal = failure.line_offsets(*equations.centres(q_ideal))

    def offsets(dq):  # the failure measure's offsets of the ideal start plus δq, less the ideal start's
        return failure.line_offsets(*equations.centres(q_ideal + dq.real)) - offsets_ideal

    limit = failure_ratio * failure.amplitude(*equations.centres(q_seed))
    growth = roots.real
    fastest = int(np.argmax(growth))
    mode = vectors[:, fastest].real
    mode_offsets = offsets(mode * 1e-9 / np.abs(mode).max()) / (1e-9 / np.abs(mode).max())
    seed_size = float(abs(c[fastest].real) * 0.5 * (mode_offsets.max() - mode_offsets.min()))
    wavelength = seeded.slice_length * _wavelength_in_slices(mode[2 : 2 + params.n]) if growth[fastest] > 0 else None
    if trajectory is not None:
        times, tau = trajectory.time, stretched_time(base, trajectory)
        shape = [failure.line_offsets(trajectory.x[k], trajectory.y[k]) for k in range(times.size)]
        method = "trajectory"
    else:
        acc = equations.accelerations(q_ideal[:, None], np.zeros((equations.dof, 1)))[:, 0]
        d = np.linalg.solve(vectors, acc)
        times = tau = np.linspace(0.0, HORIZON / max(growth[fastest], 1e-12), TIME_SAMPLES)
        shape = [offsets_ideal + offsets(vectors @ (d * _from_rest(roots, t))) for t in times]
        method = "spectrum"
    amplitude = np.array([_half_spread(s + offsets(vectors @ (c * np.cosh(roots * t)))) for s, t in zip(shape, tau)])
    amplitude[0] = limit / failure_ratio
    t_fail = failure.failure_time(times, amplitude, failure_ratio)
    return Prediction(t_fail, float(growth[fastest]), wavelength, seed_size, method)


def _from_rest(roots: np.ndarray, t: float) -> np.ndarray:
    """(cosh(√μ t) − 1)/μ: the response of each mode from rest to a unit constant acceleration (t²/2 at μ → 0)."""
    mu = roots**2
    small = np.abs(mu) * t * t <= 1e-8
    return np.where(small, 0.5 * t * t, (np.cosh(roots * t) - 1) / np.where(small, 1.0, mu))


def _half_spread(offsets: np.ndarray) -> float:
    return 0.5 * float(offsets.max() - offsets.min())


def _wavelength_in_slices(angles: np.ndarray) -> float:
    from lightsail_mbs.analysis.resolvedness import dominant_wavelength

    return dominant_wavelength(angles)
