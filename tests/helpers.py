"""Helpers shared by several test modules: synthetic Results with known shapes, CSV and image reading, the
validation scripts as modules."""

import csv
import importlib.util
import math
import pathlib

import numpy as np

from lightsail_mbs import Result, RunSettings, SailParameters
from lightsail_mbs.model.shapes import hinge_points


def growing_sine(model="torsion", n=20, steps=41, rate=1.0, t_final=1.0, **changes) -> Result:
    """A synthetic run: slices on w(x, t) = a₀ e^{rate·t} sin(2πνx/L) with exact chords, so the amplitude
    ratio at time t is e^{rate·t} and the curvature at the hinges is known in closed form."""
    p = SailParameters(model=model, n=n, **changes)
    times = np.linspace(0.0, t_final, steps)
    x, y, theta = (np.empty((steps, n)) for _ in range(3))
    k = 2 * np.pi * p.defect_mode / p.length
    for j, t in enumerate(times):
        growth = math.exp(rate * t)
        pts = hinge_points(p, lambda s, g=growth: p.defect_amplitude * g * np.sin(k * s))
        d = np.diff(pts, axis=0)
        theta[j] = np.arctan2(d[:, 1], d[:, 0])
        x[j] = pts[:-1, 0] + 0.5 * p.slice_length * np.cos(theta[j])
        y[j] = pts[:-1, 1] + 0.5 * p.slice_length * np.sin(theta[j])
    zero = np.zeros_like(x)
    z = np.zeros((steps, n - 1)) if p.extensible else None
    return Result.from_trajectory(
        p, "synthetic", times, x, y, theta, zero, zero, zero, z=z, z_rate=z, settings=RunSettings(t_final=t_final)
    )


def synthetic_sheet(steps=5, t_final=1.0) -> Result:
    """A sheet run on w = a₀ e^t sin(3πx) sin(πy) (tile centres; angles and rates zero), as Result.from_tiles
    builds it: the amplitude ratio at time t is e^t."""
    from lightsail_mbs.model import sheet

    p = SailParameters(model="sheet", n=8, ny=6, defect_mode_y=0.5)
    flat = sheet.flat_centres(p)
    times = np.linspace(0, t_final, steps)
    w = p.defect_amplitude * np.sin(3 * np.pi * flat[:, 0]) * np.sin(np.pi * flat[:, 1])
    centres = np.stack([flat + np.outer([0, 0, 1], np.exp(t) * w).T for t in times])
    zero = np.zeros_like(centres)
    return Result.from_tiles(p, "synthetic", times, centres, zero, zero, zero, settings=RunSettings(t_final=t_final))


def plate(boundary: str, tiles: int = 9, **changes) -> SailParameters:
    """A square sheet of tiles × tiles as an unlit Kirchhoff plate (L = W = 1 m, h = 1 cm, E = 1.2e9 Pa, so
    D = 100 N m) under a uniform pressure of 0.01 Pa, with the given edge support."""
    return SailParameters(
        model="sheet",
        n=tiles,
        ny=tiles,
        thickness=0.01,
        youngs_modulus=1.2e9,
        intensity=0.0,
        defect_amplitude=0.0,
        pressure=0.01,
        boundary=boundary,
        **changes,
    )


def read_csv(path) -> list[dict]:
    with open(path, newline="") as handle:
        return list(csv.DictReader(handle))


def read_image(path) -> np.ndarray:
    """An image file as an (height, width, 3) RGB array."""
    from PIL import Image

    return np.asarray(Image.open(path).convert("RGB"))


def table_file(path, scale: float = 1.9):
    """A small optical table file at `path`: c_n = scale·cos²θ, c_t = 0.01·cos²θ·sin 2θ on |θ| ≤ 1.2 rad."""
    import numpy as np

    from lightsail_mbs.model import optics

    theta = optics.node_grid(1.2, 0.05)
    c2 = np.cos(theta) ** 2
    table = optics.OpticalTable.from_samples(theta, scale * c2, 0.01 * c2 * np.sin(2 * theta), (), "TE")
    return table.save(path)


def validation_script(name: str):
    """validation/NAME.py loaded as a module (its functions and constants, without running its main)."""
    path = pathlib.Path(__file__).parents[1] / "validation" / f"{name}.py"
    spec = importlib.util.spec_from_file_location(f"validation_{name}", path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module
