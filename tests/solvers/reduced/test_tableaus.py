"""The compiled integrators' coefficient tables (solvers.reduced.tableaus): consistent as Runge–Kutta tables,
and bit-equal to scipy's (whose DOP853 and Radau the compiled steppers reproduce step for step)."""

import numpy as np
import pytest

from lightsail_mbs.solvers.reduced import tableaus as t


def test_dop853_table_is_consistent():
    s = t.DOP853_STAGES
    assert t.DOP853_A.shape == (16, 16) and t.DOP853_B.shape == (s,) and t.DOP853_D.shape == (4, 16)
    np.testing.assert_allclose(t.DOP853_A.sum(axis=1), t.DOP853_C, rtol=0, atol=1e-14)  # row sums = nodes
    assert t.DOP853_B.sum() == pytest.approx(1.0, abs=1e-15)
    assert t.DOP853_B @ t.DOP853_C[:s] == pytest.approx(0.5, abs=1e-15)  # order conditions
    assert t.DOP853_B @ t.DOP853_C[:s] ** 7 == pytest.approx(1 / 8, abs=1e-14)
    assert not np.triu(t.DOP853_A).any()  # explicit


def test_radau_table_is_consistent():
    s6 = np.sqrt(6.0)
    np.testing.assert_allclose(t.RADAU_C, [(4 - s6) / 10, (4 + s6) / 10, 1.0], rtol=1e-15)
    np.testing.assert_allclose(t.RADAU_T @ t.RADAU_TI, np.eye(3), rtol=0, atol=1e-14)


def test_tables_equal_scipys():
    dop = pytest.importorskip("scipy.integrate._ivp.dop853_coefficients")
    radau = pytest.importorskip("scipy.integrate._ivp.radau")
    assert t.DOP853_STAGES == dop.N_STAGES
    for mine, theirs in (
        (t.DOP853_A, dop.A),
        (t.DOP853_B, dop.B),
        (t.DOP853_C, dop.C),
        (t.DOP853_D, dop.D),
        (t.DOP853_E3, dop.E3),
        (t.DOP853_E5, dop.E5),
        (t.RADAU_C, radau.C),
        (t.RADAU_E, radau.E),
        (t.RADAU_T, radau.T),
        (t.RADAU_TI, radau.TI),
        (t.RADAU_P, radau.P),
    ):
        np.testing.assert_array_equal(mine, theirs)
    assert (t.RADAU_MU_REAL, t.RADAU_MU_COMPLEX, t.RADAU_NEWTON_MAXITER) == (
        radau.MU_REAL,
        radau.MU_COMPLEX,
        radau.NEWTON_MAXITER,
    )
