"""The reduced sheet's Jacobian with its dense rows apart (solvers.reduced.sheet_jacobian, option
jacobian="split"): the same matrix as the coloured difference quotients, from far fewer colours on a polar disc."""

import numpy as np
import pytest

from lightsail_mbs import RunSettings, SailParameters, solve
from lightsail_mbs.base.validation import ParameterError
from lightsail_mbs.model import materials
from lightsail_mbs.solvers.reduced.sheet import STATE, SheetModel

SPIN = 2 * np.pi * 120.0  # rad/s


def film(planform="disc", n=17, ny=24, **changes) -> SailParameters:
    """A 1 m sheet of a 200 nm Si₃N₄ film spinning at 120 Hz in a 1 GW/m² beam (a disc: 1 + 8 rings of 24 tiles)."""
    fields = dict(model="sheet", planform=planform, n=n, ny=ny, length=1.0, width=1.0, material="silicon-nitride")
    fields.update(thickness=2e-7, spin_rate=SPIN, intensity=1e9, beam_waist=0.4, defect_amplitude=1e-5, **changes)
    return SailParameters(**materials.fill(fields))


def perturbed(model: SheetModel) -> np.ndarray:
    """The model's start with every entry moved by 1e-4 of its size (at least 1e-7): no entry of J vanishes by
    symmetry."""
    y = model.y0()
    return y + 1e-4 * np.random.default_rng(1).standard_normal(y.size) * np.maximum(1e-3, np.abs(y))


@pytest.mark.parametrize("frame", ["turning", "inertial"])
def test_split_jacobian_is_the_coloured_one_on_a_disc(frame):
    """193-tile disc: the centre tile (24 neighbours) is the only dense tile, the colours drop from 25 to at most 8;
    every other tile's rows are the coloured quotients bit for bit, the centre's within the quotients' round-off,
    10⁴ ε |f_r| / δ_c for row r and increment δ_c (a wrong block would be off by ~1e8 of that)."""
    p = film()
    coloured, split = SheetModel(p, frame=frame), SheetModel(p, frame=frame, jacobian="split")
    assert split.dense.tiles.tolist() == [0]
    assert len(coloured.groups) == 25 and len(split.groups) <= 8
    y, t = perturbed(coloured), 1.3e-3
    A, B = coloured.jacobian(t, y), split.jacobian(t, y)
    assert np.array_equal(A.indices, B.indices) and np.array_equal(A.indptr, B.indptr)
    difference = (B - A).tocoo()
    rows, cols, values = difference.row, difference.col, np.abs(difference.data)
    assert set((rows // STATE).tolist()) == {0}  # only the centre's rows differ
    f = coloured.rhs(t, y)
    bound = 1e4 * np.finfo(float).eps * np.abs(f[rows]) / coloured.increments(y, cols)
    assert np.all(values <= bound)
    assert np.abs(A.data).max() > 1e8 * bound.max()  # the bound is far below the entries' size


def test_split_jacobian_changes_nothing_on_a_rectangle():
    """A rectangular grid has no dense tile: the same colouring and the same matrix."""
    p = film(planform="rectangle", n=8, ny=6)
    coloured, split = SheetModel(p, frame="turning"), SheetModel(p, frame="turning", jacobian="split")
    assert split.dense is None and len(split.groups) == len(coloured.groups) == 5
    y = perturbed(coloured)
    assert (coloured.jacobian(0.0, y) != split.jacobian(0.0, y)).nnz == 0


def test_split_run_is_the_coloured_run():
    """The same 49-tile disc over 1 ms with either Jacobian: the same run to the tolerance (the Newton matrices
    differ in round-off only): the tiles' out-of-plane displacements within 1e-6 of their largest (2e-11 measured)."""
    p = film(n=9, ny=12)
    settings = RunSettings(t_final=1e-3, output_interval=5e-4, stop_at_failure=False, failure_ratio=1e300)
    a = solve(p, "reduced", settings, uncertainty=False, rtol=1e-5)
    b = solve(p, "reduced", settings, uncertainty=False, rtol=1e-5, jacobian="split")
    assert b.info["colours"] < a.info["colours"] == 13
    za, zb = a.tile_centres[..., 2], b.tile_centres[..., 2]
    assert np.abs(za - zb).max() <= 1e-6 * np.abs(za).max()


def test_bad_jacobian_option_is_one_line():
    with pytest.raises(ParameterError, match="jacobian='dense' is invalid"):
        solve(film(n=9, ny=12), "reduced", RunSettings(t_final=1e-3), uncertainty=False, jacobian="dense")


def test_the_benchmark_disc_takes_7_colours_instead_of_57():
    """The 1009-tile disc of validation/spin_benchmark.py (1 + 18 rings of 56 tiles)."""
    p = film(n=37, ny=56)
    assert len(SheetModel(p, jacobian="split").groups) == 7
    assert len(SheetModel(p).groups) == 57
