"""
A sheet, and its frames
=======================

The sail as a sheet of n × ny rigid tiles moving in 3-D (``model="sheet"``, the :doc:`../sheet` page), here
with the paper's ν = 3/2 sine defect uniform across the width and the soft modulus of its Fig. 7. A sheet
whose defect does not vary across the width is the paper's chain in 3-D, so the same case as a chain of
n = 32 slices is run beside it: the two failure times agree within their error bars. The sheet's frames
— the deflection map and a 3-D view, red-framed from the failure on — are written as PNG files and shown.

From the command line::

    lightsail-mbs simulate --model sheet --n 32 --ny 2 --modulus 4.5e9 --solver reduced --out sheet.npz
    lightsail-mbs render sheet.npz --frames 4 --out frames/
"""

import tempfile
from pathlib import Path

import matplotlib.pyplot as plt
from PIL import Image

from lightsail_mbs import RunSettings, SailParameters, solve
from lightsail_mbs.viz.sheet import render_sheet_frames

settings = RunSettings(t_final=4.0)
case = SailParameters(model="sheet", n=32, ny=2, youngs_modulus=4.5e9)
result = solve(case, "reduced", settings=settings)
chain = solve(case.replace(model="torsion", ny=1), "reduced", settings=settings)

# %%
# The answers, with their uncertainty, the conditioning verdict and any warning about resolution.
print(f"sheet {case.n} × {case.ny}: {result.answer_text()}; warnings: {result.warnings or 'none'}")
print(f"chain n = {case.n}:  {chain.answer_text()}; warnings: {chain.warnings or 'none'}")
print(f"sheet − chain: {result.failure_time - chain.failure_time:.2g} s")

# %%
# Four frames, evenly spaced in time; the last is the first state at or after the failure, drawn as failed.
paths = render_sheet_frames(result, Path(tempfile.mkdtemp()), frames=4, size=(900, 400))
fig, axes = plt.subplots(2, 2, figsize=(10, 4.6))
for ax, path in zip(axes.flat, paths):
    ax.imshow(Image.open(path))
    ax.set_axis_off()
fig.tight_layout()
