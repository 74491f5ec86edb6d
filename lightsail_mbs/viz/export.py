"""A sheet run as a time series of moving tile polygons that ParaView opens, written by meshio.

Geometry. Tile k of the mesh (model.sheet_mesh) has its outline o_v at rest, in the plane z = 0 around its
flat centre c_k⁰. At sample t it is drawn where the run puts it: vertex v at x_v(t) = c_k(t) + R_k(t) (o_v − c_k⁰),
R_k the tile's rotation (its Tait–Bryan angles, model.sheet_grid.rotation_xyz). Each tile has vertices of its
own (the tiles are rigid and their corners part as the sail deforms). A tile of three or four corners is one
cell (triangle or quad); a tile of more (the disc's central polygon) is a fan of triangles from its centre,
since XDMF as meshio writes it has no general polygon. The cell field "tile" gives each cell's tile index.

Cell fields, per tile (SI units):

* ``deflection`` (m): the tile centre's offset from the best-fit plane of the centres (Result.deflection,
  what the failure rule measures); the same in either frame;
* ``z`` (m): the tile centre's coordinate along the beam;
* ``velocity`` (m/s) and ``angular_velocity`` (rad/s): the tile's, in the frame chosen;
* ``load`` (N): the net applied force on the tile, model.terms.tile_forces — radiation minus the frame
  force of the accelerating frame, plus a dead pressure's — not the connectors' forces or the edge tension;
  computed in the inertial frame, then turned into the frame chosen.

A Result carries no temperature; there is no temperature field.

Frames (viz.spin_frame): inertial (the Result's own) or rotating with the sail's mean spin.

Formats: ``xdmf`` — one ``.xdmf`` file, data inline as XML (no HDF5 needed), a temporal collection whose
grids each hold their own geometry (meshio's time-series writer with the geometry written per step; its
reader reads the fields back); ``vtu`` — one ``.vtu`` file per sample in a folder beside a ``.pvd`` index
that gives each its time (ParaView opens the ``.pvd``).
"""

from __future__ import annotations

import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np

from lightsail_mbs.base.files import write_atomically
from lightsail_mbs.base.validation import ParameterError
from lightsail_mbs.model import planforms, sheet, terms
from lightsail_mbs.result import Result
from lightsail_mbs.viz.spin_frame import check_frame, frame_rotation, in_frame, require_sheet_run, turn

FORMATS = ("xdmf", "vtu")
FIELDS = ("deflection", "z", "velocity", "angular_velocity", "load")


def check_format(fmt: str) -> None:
    if fmt not in FORMATS:
        raise ParameterError(f"--format={fmt!r} is invalid: allowed {', '.join(FORMATS)}")


def tile_cells(mesh) -> tuple[np.ndarray, np.ndarray, list]:
    """The cells of a mesh's tiles (module docstring): (owner (P,), offsets (P, 3), blocks), with each
    point's tile and its offset from the tile's flat centre in the tile's axes, and blocks a list of
    (meshio cell type, connectivity (C, V), tiles (C,))."""
    owner, offsets = [], []
    cells = {"triangle": ([], []), "quad": ([], [])}
    for k, outline in enumerate(mesh.outlines):
        start = len(owner)
        corners = len(outline)
        owner.extend([k] * corners)
        offsets.extend(np.asarray(outline, float) - mesh.centres[k])
        ring = start + np.arange(corners)
        if corners <= 4:
            kind = "triangle" if corners == 3 else "quad"
            cells[kind][0].append(ring)
            cells[kind][1].append(k)
            continue
        owner.append(k)
        offsets.append(np.zeros(2))  # the fan's centre: the tile's centre
        centre = start + corners
        for v in range(corners):
            cells["triangle"][0].append([centre, ring[v], ring[(v + 1) % corners]])
            cells["triangle"][1].append(k)
    offsets = np.column_stack([np.asarray(offsets, float), np.zeros(len(owner))])
    return (
        np.asarray(owner),
        offsets,
        [
            (kind, np.asarray(conn, dtype=np.int64).reshape(len(tiles), -1), np.asarray(tiles, dtype=np.int64))
            for kind, (conn, tiles) in cells.items()
            if tiles
        ],
    )


def tile_geometry(result: Result, frame: str = "inertial") -> tuple[np.ndarray, list, dict]:
    """(points (T, P, 3), blocks, fields): the moving tile cells of a sheet run in `frame` and their cell
    fields by name, each (T, N) or (T, N, 3) per tile (module docstring); blocks as tile_cells."""
    require_sheet_run(result, "export")
    check_frame(frame)
    owner, offsets, blocks = tile_cells(planforms.mesh_of(result.params))
    shown = in_frame(result, frame)
    rotations = sheet.rotation_xyz(shown.tile_angles)
    points = shown.tile_centres[:, owner] + np.einsum("tpij,pj->tpi", rotations[:, owner], offsets)
    Q, _ = frame_rotation(result, frame)
    axes = sheet.rotation_xyz(result.tile_angles)[..., 0]  # R x̂ of each tile, read by a grating
    normals = sheet.normal_xyz(result.tile_angles)
    load = terms.tile_forces(result.params, result.tile_centres, normals, time=result.time, axes=axes)
    fields = {
        "deflection": result.deflection(),
        "z": shown.tile_centres[..., 2],
        "velocity": shown.tile_velocities,
        "angular_velocity": shown.tile_angular_velocities,
        "load": turn(Q, load),
    }
    return points, blocks, fields


def _cell_data(fields: dict, blocks: list, step: int) -> dict:
    data = {
        name: [np.ascontiguousarray(values[step][tiles]) for _, _, tiles in blocks] for name, values in fields.items()
    }
    data["tile"] = [tiles for _, _, tiles in blocks]
    return data


def export(result: Result, path, fmt: str = "xdmf", frame: str = "inertial") -> list[Path]:
    """Write a sheet run as a time series (module docstring) to `path` (the .xdmf file, or the .pvd index of
    the .vtu files written into the folder `path` without its suffix); returns the files written."""
    import meshio

    check_format(fmt)
    points, blocks, fields = tile_geometry(result, frame)
    cells = [(kind, conn) for kind, conn, _ in blocks]
    path = Path(path)
    if fmt == "xdmf":
        return [_write_xdmf(meshio, path, result.time, points, cells, blocks, fields)]
    folder = path.with_suffix("")
    folder.mkdir(parents=True, exist_ok=True)
    written, entries = [], []
    for step, t in enumerate(result.time):
        name = folder / f"{folder.name}_{step:05d}.vtu"
        meshio.write(name, meshio.Mesh(points[step], cells, cell_data=_cell_data(fields, blocks, step)))
        written.append(name)
        entries.append((float(t), f"{folder.name}/{name.name}"))
    root = ET.Element("VTKFile", type="Collection", version="0.1", byte_order="LittleEndian")
    collection = ET.SubElement(root, "Collection")
    for t, file in entries:
        ET.SubElement(collection, "DataSet", timestep=repr(t), group="", part="0", file=file)
    text = (ET.tostring(root, encoding="unicode") + "\n").encode()
    write_atomically(path, lambda handle: handle.write(text))
    return [path, *written]


def _write_xdmf(meshio, path: Path, time, points, cells, blocks, fields) -> Path:
    """meshio's XDMF time series with each step's own geometry: the writer's grid of the mesh holds the
    topology (and the first geometry); every step's grid includes the topology and writes its points."""

    class MovingWriter(meshio.xdmf.TimeSeriesWriter):
        def write_step(self, t, step_points, cell_data):
            grid = ET.SubElement(self.collection, "Grid")
            pointer = f'xpointer(//Grid[@Name="{self.mesh_name}"]/*[self::Topology])'
            ET.SubElement(grid, "{http://www.w3.org/2003/XInclude}include", xpointer=pointer)
            self.points(grid, step_points)
            ET.SubElement(grid, "Time", Value=repr(float(t)))
            self.cell_data(cell_data, grid)

    with MovingWriter(path, data_format="XML") as writer:
        writer.write_points_cells(points[0], cells)
        for step, t in enumerate(time):
            writer.write_step(t, points[step], _cell_data(fields, blocks, step))
    return path
