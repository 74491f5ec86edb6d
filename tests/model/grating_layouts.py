"""Grating layouts (model/sheet_grating.py) written as files for the tests."""

import tempfile
from pathlib import Path

# a TE-like and a TM-like law (c_g, c_l, c_n: c₀, c₁, c₂, c₁₁, c₁₂, c₂₂), of FlexSailSim's size and shape
TE = ([0.15, 1.3, 0.2, -2.3, 0.4, -0.27], [0.01, 0.3, -0.5, 0.0, 0.1, 0.2], [0.32, 2.6, 0.1, -14.0, 0.3, 2.3])
TM = ([0.14, -0.6, 0.1, 1.6, -0.2, 0.15], [-0.02, 0.1, 0.2, 0.3, 0.0, -0.1], [-0.16, -0.2, 0.05, -1.4, 0.1, -0.5])
# FlexSailSim's pizza: TE about ±x, TM about ±y, in-plane pressures pointing outward
PIZZA = ((-30, 30, 0, TE), (30, 150, 90, TM), (150, 210, 180, TE), (210, 330, 270, TM))
ZERO = ([0.0] * 6,) * 3
# a law of degree 5 (21 coefficients a list, graded order 1, u₁, u₂, u₁², u₁u₂, u₂², u₁³, …) beside one of degree 3
HIGHER = [(-1) ** k * (9.0 + k) * 10 ** (k // 4) for k in range(15)]  # degrees 3, 4, 5: 9 … 2300
QUINTIC = tuple([f * v for v in [0.15, 1.3, 0.2, -2.3, 0.4, -0.27] + HIGHER] for f in (1.0, -0.1, 0.5))
CUBIC = (
    [0.14, -0.6, 0.1, 1.6, -0.2, 0.15, 8.0, -3.0, 2.0, 5.0],
    [0.01, 0.3, -0.1],
    [-0.16, -0.2, 0.05, -1.4, 0.1, -0.5],
)
WIDE = ((-30, 30, 0, QUINTIC), (30, 150, 90, CUBIC), (150, 210, 180, QUINTIC), (210, 330, 270, CUBIC))
_FOLDER = Path(tempfile.mkdtemp(prefix="grating_layouts_"))


def text(sectors) -> str:
    """The TOML of sectors (from, to, direction, (along, across, normal)) in degrees."""
    out = []
    for start, end, direction, (along, across, normal) in sectors:
        out += ["[[sector]]", f"from = {start}", f"to = {end}", f"direction = {direction}"]
        lists = zip(("along", "across", "normal"), (along, across, normal))
        out += [f"{key} = {[float(v) for v in values]}" for key, values in lists]
    return "\n".join(out) + "\n"


def write(name: str, sectors) -> str:
    """The path of a layout file of `sectors` (module folder, one per name)."""
    path = _FOLDER / f"{name}.toml"
    path.write_text(text(sectors))
    return str(path)
