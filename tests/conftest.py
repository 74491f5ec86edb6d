"""Fixtures shared across the test folders."""

import pytest

from tests.helpers import growing_sine


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
