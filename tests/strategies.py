"""Hypothesis strategies shared by the property tests: cases, run settings, saved runs, and how many examples.

The default suite draws few examples with a fixed seed (deterministic and fast); the ``slow`` variant of
each property draws many at random (``pytest -m slow``).
"""

import math

import numpy as np
import pytest
from hypothesis import HealthCheck, settings
from hypothesis import strategies as st

from lightsail_mbs import RunSettings, SailParameters
from lightsail_mbs.model.fields import BOUNDARIES, MODELS, SHEET_BOUNDARIES
from lightsail_mbs.model.parameters import SPEED_OF_LIGHT

FAST_EXAMPLES, SLOW_EXAMPLES = 8, 150
EXAMPLES = [
    pytest.param(FAST_EXAMPLES, id="fast"),
    pytest.param(SLOW_EXAMPLES, id="slow", marks=pytest.mark.slow),
]


def check_property(test, examples: int) -> None:
    """Run a @given test with this many examples, derandomized (the same cases on every run and machine, so a
    failure reproduces and the run time is bounded); the slow variant draws many more cases than the fast."""
    settings(
        max_examples=examples,
        deadline=None,
        derandomize=True,
        suppress_health_check=[HealthCheck.too_slow, HealthCheck.filter_too_much],
        database=None,
    )(test)()


def log_uniform(low_exponent: float, high_exponent: float, zero: bool = False):
    """10^U(low, high), and 0 when zero is allowed (drawn often: the boundary of the range)."""
    values = st.floats(low_exponent, high_exponent).map(lambda e: 10.0**e)
    return st.one_of(st.just(0.0), values) if zero else values


@st.composite
def case_kwargs(draw) -> dict:
    """Keyword arguments of a SailParameters over wide ranges around the paper's (mostly accepted)."""
    model = draw(st.sampled_from(MODELS))
    length = draw(log_uniform(-1, 1))
    mode = draw(st.one_of(st.sampled_from([0.5, 1.0, 1.5, 2.0, 3.0]), st.floats(0.1, 6.0)))
    reflectivity = draw(st.floats(0.0, 1.0))
    kwargs = dict(
        model=model,
        n=draw(st.integers(2, 24)),
        length=length,
        width=draw(log_uniform(-1, 1)),
        thickness=draw(log_uniform(-8, -5)),
        density=draw(log_uniform(2, 4)),
        youngs_modulus=draw(log_uniform(6, 13, zero=model != "tnt")),
        tension=draw(log_uniform(-10, -2, zero=True)) if model == "tnt" else 0.0,
        intensity=draw(log_uniform(6, 11, zero=True)),
        defect_amplitude=draw(st.floats(0.0, 0.9)) * length / (2 * math.pi * mode) * draw(log_uniform(-6, 0)),
        defect_mode=mode,
        defect_seed=draw(st.one_of(st.none(), st.integers(0, 10**6))),
        defect_mode_count=draw(st.integers(1, 12)),
        defect_spectrum=draw(st.floats(-1.0, 3.0)),
        beam_waist=draw(st.one_of(st.just(math.inf), log_uniform(-1, 2).map(lambda w: w * length))),
        beam_centre=draw(st.one_of(st.none(), st.floats(0.0, 1.0).map(lambda f: f * length))),
        reflectivity=reflectivity,
        absorptivity=draw(st.floats(0.0, 1.0)) * (1.0 - reflectivity),
        bending=draw(st.sampled_from([None, True, False])),
        axial_springs=draw(st.booleans()),
        torsional_damping=draw(log_uniform(-12, -4, zero=True)),
        axial_damping=draw(log_uniform(-8, -2, zero=True)),
        stiffness_damping=draw(log_uniform(-8, -4, zero=True)),
        boundary=draw(st.sampled_from(BOUNDARIES)),
        tip_load=draw(log_uniform(-9, -4, zero=True)) * draw(st.sampled_from([1.0, -1.0])),
        tip_load_time_constant=draw(log_uniform(-4, -1, zero=True)),
    )
    if kwargs["reflectivity"] == 0 and kwargs["absorptivity"] == 0:
        kwargs["reflectivity"] = 1.0
    if model == "sheet":  # a few tiles across; the chain's fields (FieldInfo.models) at their defaults
        kwargs.update(
            ny=draw(st.integers(1, 4)),
            defect_mode_y=draw(st.one_of(st.none(), st.floats(0.25, 3.0))),
            membrane_modulus=draw(st.one_of(st.none(), log_uniform(6, 12))),
            edge_tension=draw(log_uniform(-9, -3, zero=True)),
            beam_centre_y=draw(st.one_of(st.none(), st.floats(0.0, 1.0).map(lambda f: f * kwargs["width"]))),
            boundary=draw(st.sampled_from(SHEET_BOUNDARIES)),
            tip_load=0.0,
            tip_load_time_constant=0.0,
            axial_springs=True,
            torsional_damping=0.0,
            axial_damping=0.0,
        )
    return kwargs


def accepted_cases():
    """SailParameters the package accepts, drawn from case_kwargs."""

    def build(kwargs):
        try:
            return SailParameters(**kwargs)
        except Exception:  # noqa: BLE001 - rejected combinations are filtered out here (tested elsewhere)
            return None

    return case_kwargs().map(build).filter(lambda p: p is not None)


BAD_VALUES = st.sampled_from(
    [math.nan, math.inf, -math.inf, -1.0, 0.0, -1e-300, 1e308, "1e-6", "abc", None, True, False, [1.0], {}, 10**400, -7]
)


@st.composite
def any_case_kwargs(draw) -> dict:
    """case_kwargs with one to three fields replaced by a value of the wrong sign, kind or type."""
    kwargs = draw(case_kwargs())
    for name in draw(st.lists(st.sampled_from(sorted(kwargs)), min_size=1, max_size=3, unique=True)):
        kwargs[name] = draw(BAD_VALUES)
    return kwargs


@st.composite
def short_run(draw, p: SailParameters) -> RunSettings:
    """A few output samples over a fraction of the case's load time scale √(L/g₀) (1 ms without load)."""
    g0 = p.nominal_acceleration
    scale = math.sqrt(p.length / g0) if g0 > 0 else 1e-3
    t_final = min(max(draw(st.floats(0.01, 0.3)) * scale, 1e-5), 1e-2)
    samples = draw(st.integers(1, 8))
    return RunSettings(
        t_final=t_final,
        output_interval=t_final / samples,
        stop_at_failure=draw(st.booleans()),
        failure_ratio=draw(st.floats(1.01, 5.0)),
    )


def flat_frame_force(p: SailParameters) -> float:
    """f₀ = 2 I₀ l W / c (N): the load on one flat slice, a force scale for finite-output checks."""
    return 2 * p.intensity * p.slice_length * p.width / SPEED_OF_LIGHT


def float_arrays(shape):
    """float64 arrays of a shape with any values, NaN, ±inf and −0.0 included."""
    from hypothesis.extra.numpy import arrays

    return arrays(np.float64, shape, elements=st.floats(allow_nan=True, allow_infinity=True, width=64))


JSON_SCALARS = st.one_of(
    st.none(), st.booleans(), st.integers(-(2**53), 2**53), st.floats(allow_nan=False, allow_infinity=False), st.text()
)
JSON_VALUES = st.recursive(
    JSON_SCALARS,
    lambda inner: st.one_of(st.lists(inner, max_size=3), st.dictionaries(st.text(max_size=8), inner, max_size=3)),
    max_leaves=8,
)
