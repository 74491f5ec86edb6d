"""The spin map's cap from the spun equilibrium: its spectrum in the turning frame.

The map's case (paper.spinning_maps: the 25-tile disc of the stiff film on a cap of R_c = 1 m, a stem payload of
the sail's mass at 1.15 d*) spinning at 40, 80 and 120 rad/s in its beam centred on the spin axis, linearised in
its turning frame (analysis.spin_spectrum):

* about its lit spun equilibrium (spin_spectrum.lit_state: the relaxation of solvers.reduced.sheet_relax with the
  light on): the fastest eigenvalue of the whole linearisation L, of L on the craft's six rigid motions
  (spin_spectrum.rigid_modes: the shape held) and of the deformations (rotating_spectrum), beside the rigid
  criterion's fastest root (analysis.ride3d_criterion, undamped, on the sphere R_c). The relaxed cap's sag and
  the radius of the sphere through its apex and rim, R_fit = (r² + s²)/(2s), and the criterion's d* on that
  sphere, tell how far spin has flattened it;
* the same cap without its payload, unlit, about its spun equilibrium (spin_equilibrium: the start of every
  spinning cell of the map): the fastest Re λ of its deformations.

The map's cells themselves are in scenarios/figures/spinning_maps.md (scenarios/spinning_beam.py --only maps).

Run from the repository root: ``nice -n 10 python validation/spin_equilibrium_cells.py [--out FILE]``
(default validation/spin_equilibrium_cells.md).
"""

from __future__ import annotations

import argparse
from pathlib import Path

import numpy as np

from lightsail_mbs.analysis import spin_spectrum
from lightsail_mbs.analysis.ride3d_criterion import cap_criterion
from lightsail_mbs.paper import spinning_maps as maps
from lightsail_mbs.studies.tables import markdown_table

SPECTRUM_SPINS, SPECTRUM_RATIO = (40.0, 80.0, 120.0), 1.15
REPORT = Path("validation/spin_equilibrium_cells.md")


def fastest(values) -> str:
    v = np.asarray(values)[np.argmax(np.real(values))]
    return f"{v.real:+.3f} ± {abs(v.imag):.2f}i"


def spectrum_rows() -> list[dict]:
    rows = []
    for spin in SPECTRUM_SPINS:
        p = maps.BASE.replace(billow_radius=1.0, spin_rate=spin)
        d = SPECTRUM_RATIO * maps.d_star(p)
        p = p.replace(payload_stem=d)
        state = spin_spectrum.lit_state(p)
        L = spin_spectrum.rotating_linearisation(p, state).toarray()
        whole = np.linalg.eigvals(L)
        whole = whole[np.abs(whole) > 1e-6]  # the rigid motions' zero eigenvalues (axial, spin)
        rigid = spin_spectrum.rigid_modes(p, state=state)
        shape = spin_spectrum.rotating_spectrum(p, state=state)
        sag, fit = lit_fit(p, state)
        unlit = spin_spectrum.rotating_spectrum(p.replace(payload_mass=0.0, payload_stem=0.0, spin_equilibrium=True))
        rows.append(
            {
                "Ω (rad/s)": f"{spin:g}",
                "whole L: fastest λ (1/s)": fastest(whole),
                "rigid motions: fastest λ": fastest(rigid),
                "deformations: fastest λ": fastest(shape.eigenvalues),
                "criterion on R_c = 1 m: fastest s": fastest(cap_criterion(p, maps.SAIL_MASS, d).roots),
                "sag (mm), start → spun": f"{spin_sag(p):.1f} → {sag * 1e3:.1f}",
                "R_fit (m)": f"{fit:.2f}",
                "d/d* on R_fit": f"{d / maps.d_star(p.replace(billow_radius=fit)):.2f}",
                "no payload, unlit: deformations' fastest Re λ": f"{np.max(np.real(unlit.eigenvalues)):+.2g}",
            }
        )
        print(rows[-1], flush=True)
    return rows


def lit_fit(p, state: np.ndarray) -> tuple[float, float]:
    """(sag s (m), R_fit (m)) of the tiles of case p at its lit state: the rim tile's height above the middle
    tile's, and the radius (r² + s²)/(2s) of the sphere through the middle and the rim (r the rim's radius)."""
    return cap_fit(spin_spectrum._start(p)[0][:-1] + state.reshape(-1, 13)[:-1, 0:3])


def cap_fit(tiles: np.ndarray) -> tuple[float, float]:
    """(sag s (m), R_fit (m)) of tile centres (N, 3): the rim tile's height above the middle tile's and the radius
    (r² + s²)/(2s) of the sphere through them (r the rim's radius)."""
    radius = np.hypot(*(tiles[:, :2] - tiles[:, :2].mean(axis=0)).T)
    sag = abs(float(tiles[np.argmax(radius), 2] - tiles[np.argmin(radius), 2]))
    return sag, (radius.max() ** 2 + sag**2) / (2 * sag)


def spin_sag(p) -> float:
    """The start's sag (mm) of the case's tiles: the rim tile's height above the middle tile's."""
    return cap_fit(spin_spectrum._start(p.replace(spin_rate=0.0))[1][:-1])[0] * 1e3


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--out", type=Path, default=REPORT, help=f"the report [default: {REPORT}]")
    args = parser.parse_args()
    command = "validation/spin_equilibrium_cells.py" + ("" if args.out == REPORT else f" --out {args.out}")
    text = [
        "# The spin map's cap from the spun equilibrium: its spectrum in the turning frame",
        "",
        f"Made by `nice -n 10 python {command}` (its docstring says what it runs).",
        "",
        f"d = {SPECTRUM_RATIO:g} d*, the beam centred on the spin axis. λ = Re λ ± |Im λ| i (1/s); the rigid",
        "criterion's s is in the inertial frame (its Re the same). The lit state turns at Ω + δ rather than Ω",
        "(validation/spin_spectrum_rigid.md), which leaves a spurious real spin pair in the rigid motions and L.",
        "",
        markdown_table(spectrum_rows()),
    ]
    args.out.write_text("\n".join(text) + "\n")
    print("\n".join(text))


if __name__ == "__main__":
    main()
