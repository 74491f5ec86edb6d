"""Stability maps (studies.maps): every bisected boundary of the fake solver brackets E_cr,max (Eq. 8)."""

import pytest

from lightsail_mbs import ParameterError, RunSettings, SailParameters
from lightsail_mbs.model import theory
from lightsail_mbs.studies.maps import boundary_map
from tests.sweep_fake import fake_case


def test_boundary_map_brackets_the_known_threshold(tmp_path):
    """The fake solver fails iff E < E_cr,max: every bisected boundary must bracket it within 1.5×."""
    base, settings = SailParameters(model="torsion", n=8), RunSettings(t_final=0.1)
    rows = boundary_map(
        base,
        [(1e-7, 1.5), (1e-6, 1.5), (1e-6, 3.0)],
        store_dir=tmp_path,
        settings=settings,
        solver="fake",
        workers=1,
        progress=False,
        case_function=fake_case,
    )
    for row in rows:
        exact = theory.critical_modulus_max(base.replace(thickness=row.thickness, defect_mode=row.mode))
        assert row.status == "converged" and row.analytic == pytest.approx(exact) and row.t_final == 0.1
        assert row.unstable_value < exact <= row.stable_value <= 1.5 * row.unstable_value
        assert 1 / 1.5 < row.ratio < 1.5
        assert all(s == (v >= exact) for v, s in row.points)


def test_map_rejects_a_model_without_a_swept_stiffness(tmp_path):
    with pytest.raises(ParameterError, match="model"):
        boundary_map(SailParameters(model="rigid"), [(1e-6, 1.5)], store_dir=tmp_path, settings=RunSettings())
