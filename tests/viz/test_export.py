"""The ParaView export of a sheet run (viz.export) and the rotating frame (viz.spin_frame): read back by
meshio (steps, cells, fields equal to the Result's), the geometry of moving tiles, a spinning disc that
stands still in the rotating frame, and the one-line refusals."""

import xml.etree.ElementTree as ET

import meshio
import numpy as np
import pytest

from lightsail_mbs import ParameterError, Result, RunSettings, SailParameters
from lightsail_mbs.cli import main
from lightsail_mbs.model import planforms, sheet, terms
from lightsail_mbs.viz.export import export, tile_geometry
from lightsail_mbs.viz.spin_frame import in_frame, spin
from tests.helpers import growing_sine

SPIN = 40.0  # rad/s


def spinning_dish(planform="disc", steps=7, t_final=0.1) -> Result:
    """A rigid dish w = a r² turning about the z axis through the sail's middle at SPIN: each tile's centre and
    rotation those of the dish at rest turned by Ωt, velocities Ω ẑ × (x − c), angular velocities Ω ẑ; in a
    Gaussian beam off the middle, so that the load differs from tile to tile."""
    p = SailParameters(model="sheet", planform=planform, n=8, ny=8, beam_waist=0.6, beam_centre=0.4)
    flat = sheet.flat_centres(p)
    middle = np.array([0.5 * p.length, 0.5 * p.width, 0.0])
    arm = flat - middle
    bowl = 0.05
    rest = arm + np.outer(bowl * (arm[:, 0] ** 2 + arm[:, 1] ** 2), [0, 0, 1])
    tilts = sheet.tilt_rotation(np.column_stack([-2 * bowl * arm[:, 0], -2 * bowl * arm[:, 1], np.ones(len(arm))]))
    times = np.linspace(0.0, t_final, steps)
    turns = np.array([[[np.cos(a), -np.sin(a), 0], [np.sin(a), np.cos(a), 0], [0, 0, 1]] for a in SPIN * times])
    centres = middle + np.einsum("tij,kj->tki", turns, rest)
    angles = sheet.angles_xyz(turns[:, None] @ tilts[None])
    velocities = SPIN * np.cross([0.0, 0.0, 1.0], centres - middle)
    rates = np.broadcast_to([0.0, 0.0, SPIN], centres.shape).copy()
    return Result.from_tiles(p, "synthetic", times, centres, angles, velocities, rates, settings=RunSettings(t_final))


def by_tile(blocks_data, tiles, count):
    """A cell field read back per block, put in tile order (every cell of a tile carries the tile's value)."""
    values = np.concatenate(blocks_data)
    out = np.full((count,) + values.shape[1:], np.nan)
    out[np.concatenate(tiles)] = values
    return out


@pytest.mark.parametrize("planform", ["disc", "hexagon", "rectangle"])
def test_xdmf_read_back_by_meshio_equals_the_result(tmp_path, planform):
    run = spinning_dish(planform)
    path = export(run, tmp_path / "run.xdmf")[0]
    count = planforms.mesh_of(run.params).count
    loads = terms.tile_forces(run.params, run.tile_centres, sheet.normal_xyz(run.tile_angles))
    assert np.ptp(loads[..., 2]) > 0.1 * np.max(np.abs(loads[..., 2]))  # the beam's profile shows in the load
    with meshio.xdmf.TimeSeriesReader(path) as reader:
        points, cells = reader.read_points_cells()
        assert reader.num_steps == len(run.time)
        fans = sum(len(o) - 1 for o in planforms.mesh_of(run.params).outlines if len(o) > 4)
        assert sum(len(block.data) for block in cells) == count + fans
        for step in range(len(run.time)):
            t, _, data = reader.read_data(step)
            assert t == run.time[step]
            tiles = data["tile"]
            for name, expected in (
                ("deflection", run.deflection()[step]),
                ("z", run.tile_centres[step, :, 2]),
                ("velocity", run.tile_velocities[step]),
                ("angular_velocity", run.tile_angular_velocities[step]),
                ("load", loads[step]),
            ):
                got = by_tile(data[name], tiles, count)
                np.testing.assert_allclose(got, expected, rtol=1e-15, atol=1e-15 * np.max(np.abs(expected)))


def test_each_step_has_its_own_geometry_the_tiles_moved_rigidly(tmp_path):
    """The XDMF grids' own points: step k's are step 0's turned by Ωt_k about the middle (a rigid spin), and
    each equals the points tile_geometry computes."""
    run = spinning_dish()
    path = export(run, tmp_path / "run.xdmf")[0]
    points, _, _ = tile_geometry(run)
    grids = ET.parse(path).getroot().find("Domain").find("Grid").findall("Grid")
    assert len(grids) == len(run.time)
    middle = np.array([0.5, 0.5, 0.0])
    first = None
    for step, grid in enumerate(grids):
        xyz = np.array(grid.find("Geometry").find("DataItem").text.split(), float).reshape(-1, 3)
        np.testing.assert_array_equal(xyz, points[step])
        first = xyz if first is None else first
        a = SPIN * run.time[step]
        turn = np.array([[np.cos(a), -np.sin(a), 0], [np.sin(a), np.cos(a), 0], [0, 0, 1]])
        np.testing.assert_allclose(xyz - middle, (first - middle) @ turn.T, atol=1e-14)


def test_a_spinning_dish_stands_still_in_the_rotating_frame(tmp_path):
    run = spinning_dish(steps=9, t_final=0.3)
    motion = spin(run)
    np.testing.assert_allclose(motion["rate"], SPIN, rtol=1e-13)
    np.testing.assert_allclose(motion["angle"], SPIN * run.time, rtol=1e-13, atol=1e-15)
    still = in_frame(run, "rotating")
    np.testing.assert_allclose(
        still.tile_centres, np.broadcast_to(run.tile_centres[0], run.tile_centres.shape), atol=1e-14
    )
    np.testing.assert_allclose(
        still.tile_angles, np.broadcast_to(run.tile_angles[0], run.tile_angles.shape), atol=1e-13
    )
    assert np.max(np.abs(still.tile_velocities)) < 1e-12 and np.max(np.abs(still.tile_angular_velocities)) < 1e-12
    assert np.max(np.abs(run.tile_velocities)) > 1.0  # the inertial frame sees the spin
    points, _, fields = tile_geometry(run, "rotating")
    np.testing.assert_allclose(points, np.broadcast_to(points[0], points.shape), atol=1e-14)
    np.testing.assert_allclose(fields["deflection"], run.deflection())  # the same in either frame
    inertial = terms.tile_forces(run.params, run.tile_centres, sheet.normal_xyz(run.tile_angles))
    np.testing.assert_allclose(np.linalg.norm(fields["load"], axis=-1), np.linalg.norm(inertial, axis=-1))


def test_vtu_series_and_its_pvd_index(tmp_path):
    run = spinning_dish(steps=4)
    files = export(run, tmp_path / "run.pvd", "vtu", "rotating")
    assert files[0] == tmp_path / "run.pvd" and len(files) == 1 + len(run.time)
    entries = ET.parse(files[0]).getroot().find("Collection").findall("DataSet")
    assert [float(e.get("timestep")) for e in entries] == list(run.time)
    points, _, fields = tile_geometry(run, "rotating")
    for step, entry in enumerate(entries):
        mesh = meshio.read(tmp_path / entry.get("file"))
        np.testing.assert_array_equal(mesh.points, points[step])
        count = planforms.mesh_of(run.params).count
        np.testing.assert_array_equal(by_tile(mesh.cell_data["z"], mesh.cell_data["tile"], count), fields["z"][step])


def test_the_command_and_its_refusals(tmp_path, capsys):
    spinning_dish(steps=3).save(tmp_path / "sheet.npz")
    growing_sine().save(tmp_path / "chain.npz")
    assert main(["export", str(tmp_path / "sheet.npz"), "--frame", "rotating"]) == 0
    assert "3 time steps, rotating frame" in capsys.readouterr().out
    with meshio.xdmf.TimeSeriesReader(tmp_path / "sheet.xdmf") as reader:
        assert reader.num_steps == 3
    assert main(["export", str(tmp_path / "chain.npz"), "--out", str(tmp_path / "c")]) == 2
    err = capsys.readouterr().err.strip()
    assert "export needs a sheet run" in err and "\n" not in err
    assert main(["export", str(tmp_path / "sheet.npz"), "--format", "obj"]) == 2
    err = capsys.readouterr().err.strip()
    assert "allowed xdmf, vtu" in err and "\n" not in err
    with pytest.raises(ParameterError, match="allowed inertial, rotating"):
        in_frame(spinning_dish(steps=2), "body")
