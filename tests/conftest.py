"""Fixtures shared across the test folders."""

import pytest
from threadpoolctl import threadpool_limits

from tests.helpers import growing_sine


@pytest.fixture(scope="session", autouse=True)
def one_blas_thread():
    """BLAS on one thread: the tests' matrices are small, and BLAS worker threads spinning beside the test
    process and the sweep workers only slow a 2-core machine down."""
    with threadpool_limits(1):
        yield


@pytest.fixture
def markers(tmp_path):
    """A folder for the fake solver's execution markers (tests.sweep_fake.executions counts them)."""
    path = tmp_path / "markers"
    path.mkdir()
    return path


@pytest.fixture(scope="module")
def run():
    """The synthetic growing-sine run of tests.helpers.growing_sine (torsion, n = 20, e^t over 1 s)."""
    return growing_sine()
