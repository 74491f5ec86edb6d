"""The sail as a sheet: n × ny rigid tiles moving in 3-D, joined along their shared edges.

A case with ``SailParameters(model="sheet", n=nx, ny=ny, ...)``. Its geometry, initial shapes and
defects, edge connections and loads are shared by both sheet solvers (:mod:`lightsail_mbs.solvers.exudyn.sheet`,
:mod:`lightsail_mbs.solvers.reduced.sheet`).

Where it is written
-------------------
* :mod:`~lightsail_mbs.model.sheet_mesh`: the tiles and their connections as arrays, whatever the planform
  (:mod:`~lightsail_mbs.model.planforms` names the mesh generators);
* :mod:`~lightsail_mbs.model.sheet_grid`: the tiles' masses and inertias, the rotations of a tile and the
  connectors' strain measure;
* :mod:`~lightsail_mbs.model.sheet_shapes`: defects and the initial state;
* :mod:`~lightsail_mbs.model.sheet_connectors`: the edge connections, their stiffnesses, the reference
  state and pre-stress, the edge tension;
* this module: the tiles' load, the chain the sheet reduces to and what the grid resolves; every name of
  the three others is importable from here.

Chain limit: with a defect uniform across the width and free side edges, every column of tiles moves
as one, the y-edge springs (model/sheet_connectors.py) are not strained at all (δ = b(I − R_y)ŷ = 0
for rotations about y), the ny x-edge springs between two columns add up to the chain's
k_T = Σ D b/a = E (W h³/12)/l (paper Sec. III.B), and the stiff translational springs stand in for the
chain's hinges. So 1-D defects use the chain's own exact-chord construction
(:mod:`lightsail_mbs.model.shapes`).

Loads (the physics terms, :mod:`lightsail_mbs.model.terms`)
-------------------------------------------------------------
Each tile carries at its centre the net force of the one facet law of every solver: radiation
(I ab/c) cos θ [2R cos θ n + α ẑ] with n = R_tile ẑ, cos θ = n_z, minus the frame force
(2R + α) Ī ab/c ẑ (the frame accelerates with the flat sail at g₀ = (2R + α)Ī/(cρh)), their
cancellation done analytically from the normal's small components (n_x, n_y); I is uniform or the
round Gaussian at the tile centre. A dead pressure p (params.pressure, the plate validations) adds
p·ab ẑ.
"""

from __future__ import annotations

from lightsail_mbs.model import planforms, shapes
from lightsail_mbs.model.parameters import SailParameters
from lightsail_mbs.model.sheet_connectors import (
    SHEAR_CORRECTION,
    Connectors,
    connectors,
    edge_followers,
    edge_stiffness,
    equilibrium_offsets,
    static_loads,
)
from lightsail_mbs.model.sheet_grid import (
    Tiles,
    angles_xyz,
    flat_centres,
    normal_xyz,
    quaternion_rotation,
    relative_displacement,
    require_sheet,
    rotation_minus_identity,
    rotation_xyz,
    tile_count,
    tilt_quaternion,
    tilt_rotation,
)
from lightsail_mbs.model.sheet_shapes import (
    PERTURBATION_SEED,
    cap,
    defect_surface,
    initial_quaternions,
    initial_state,
    multimode_coefficients,
    perturbed,
)

# the sheet's names, wherever they are defined: this module is where the rest of the package reads them
__all__ = [
    "CONVERGED_TILES_PER_HALF_WAVE_2D",
    "MIN_TILES_PER_HALF_WAVE",
    "PERTURBATION_SEED",
    "SHEAR_CORRECTION",
    "Connectors",
    "Tiles",
    "angles_xyz",
    "as_strip",
    "cap",
    "connectors",
    "defect_surface",
    "defect_warnings",
    "edge_followers",
    "edge_stiffness",
    "equilibrium_offsets",
    "flat_centres",
    "initial_quaternions",
    "initial_state",
    "multimode_coefficients",
    "normal_xyz",
    "perturbed",
    "quaternion_rotation",
    "relative_displacement",
    "require_sheet",
    "rotation_minus_identity",
    "rotation_xyz",
    "static_loads",
    "tile_count",
    "tilt_quaternion",
    "tilt_rotation",
]


# ---- the chain this sheet reduces to, and what the grid resolves ----------------------------------
def as_strip(p: SailParameters) -> SailParameters:
    """The paper's torsion chain of the same sail (n slices, the sheet's E, beam, defect along x and film): the
    sheet's limit for a 1-D defect, free side edges and no edge tension (module docstring)."""
    require_sheet(p)
    return SailParameters(
        model="torsion",
        n=p.n,
        length=p.length,
        width=p.width,
        thickness=p.thickness,
        density=p.density,
        youngs_modulus=p.youngs_modulus,
        intensity=p.intensity,
        defect_amplitude=p.defect_amplitude,
        defect_mode=p.defect_mode,
        defect_seed=p.defect_seed,
        defect_mode_count=p.defect_mode_count,
        defect_spectrum=p.defect_spectrum,
        beam_waist=p.beam_waist,
        beam_centre=p.beam_centre,
        reflectivity=p.reflectivity,
        absorptivity=p.absorptivity,
        bending=p.bending,
        film_rms=p.film_rms,
        film_correlation_length=p.film_correlation_length,
        film_hurst=p.film_hurst,
        film_seed=p.film_seed,
    )


MIN_TILES_PER_HALF_WAVE = shapes.MIN_SLICES_PER_HALF_WAVE
# A doubly curved defect needs more: the E_m = E critical modulus of ν_x = ν_y = 1.5 (docs/sheet.md,
# paper.sheet_physics) is about 3× the converged value at 4 tiles per half wavelength, 1.14× at 6 and
# 1.04× at 8 (bisection brackets on 12, 18, 24 and 30/36 tiles along L).
CONVERGED_TILES_PER_HALF_WAVE_2D = 8


def defect_warnings(p: SailParameters, initial_amplitude: float) -> list[str]:
    """Why a grid of tiles may not carry the case's defect: the chain's checks along x
    (shapes.defect_warnings), too few tiles per half wavelength across the width, and, for a doubly
    curved defect, fewer than CONVERGED_TILES_PER_HALF_WAVE_2D tiles per half wavelength in either
    direction (resolved, but its stability results are not yet converged in the grid)."""
    notes = shapes.defect_warnings(p, initial_amplitude, element="tiles")
    if p.defect_mode_y is not None and p.defect_amplitude > 0:
        mesh = planforms.mesh_of(p)
        across = mesh.across[1]
        label = f"ny = {p.ny}" if mesh.grid is not None else f"{across:.3g} tiles across the width"
        shortest_y = shapes.shortest_mode(p, p.defect_mode_y)
        per_half_wave_y = across / (2.0 * shortest_y)
        if per_half_wave_y < MIN_TILES_PER_HALF_WAVE:
            notes.append(
                f"{label} gives {per_half_wave_y:.3g} tiles per half wavelength of the defect across the "
                f"width (ν_y = {shortest_y:g}); at least {MIN_TILES_PER_HALF_WAVE} are needed to resolve it"
            )
        shortest_x = shapes.shortest_mode(p, p.defect_mode)
        coarsest = min(mesh.across[0] / (2.0 * shortest_x), per_half_wave_y)
        sizes = f"{p.n} × {p.ny} tiles" if mesh.grid is not None else f"{mesh.count} tiles ({p.planform})"
        if MIN_TILES_PER_HALF_WAVE <= coarsest < CONVERGED_TILES_PER_HALF_WAVE_2D:
            notes.append(
                f"{sizes} give {coarsest:.3g} tiles per half wavelength of the doubly "
                "curved defect; its stability results converge from about "
                f"{CONVERGED_TILES_PER_HALF_WAVE_2D} (measured on the critical modulus of ν = 1.5 × 1.5: about 3× "
                "too high at 4, 1.14× at 6, 1.04× at 8)"
            )
    return notes
