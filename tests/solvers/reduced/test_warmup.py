"""The compile notice: one line on stderr when a run has to compile the package's kernels, nothing when they
load from numba's cache."""

import numba
import numpy as np

from lightsail_mbs.solvers.reduced import warmup


def test_compile_notice_once_and_only_when_compiling(monkeypatch, capsys):
    monkeypatch.setattr(warmup, "_announced", False)
    monkeypatch.setattr(warmup, "PACKAGE", __name__.split(".")[0])  # this test's functions count as the package's
    first = numba.njit(lambda x: x + 1.0)
    second = numba.njit(lambda x: 2.0 * x)
    with warmup.compile_notice("DOP853"):
        first(1.0)
        second(1.0)
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 2 and "compiling the reduced solver (DOP853" in err[0] and "compiled in" in err[1]
    with warmup.compile_notice("DOP853"):  # already compiled: silent
        first(2.0)
        second(np.float64(3.0))
    assert capsys.readouterr().err == ""


def test_compile_notice_ignores_other_packages(monkeypatch, capsys):
    monkeypatch.setattr(warmup, "_announced", False)
    monkeypatch.setattr(warmup, "PACKAGE", "no_such_package")
    with warmup.compile_notice("Radau"):
        numba.njit(lambda x: x - 1.0)(1.0)
    assert capsys.readouterr().err == ""
