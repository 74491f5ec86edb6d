"""
A sheet, and its frames
=======================

The sail as a sheet of n × ny rigid tiles moving in 3-D (``model="sheet"``, the :doc:`../sheet` page), with
the doubly sinusoidal defect w = a₀ sin(2πνx/L) sin(2πν_y y/W) and the soft modulus of the paper's Fig. 7.
A coarse 8 × 8 sheet on the reduced solver fails within a few seconds; its frames — the deflection map
and a 3-D view, red-framed from the failure on — are written as PNG files and shown here.

From the command line::

    lightsail-mbs simulate --model sheet --n 8 --ny 8 --mode-y 0.5 --modulus 4.5e9 --solver reduced --out sheet.npz
    lightsail-mbs render sheet.npz --frames 4 --out frames/
"""

import tempfile
from pathlib import Path

import matplotlib.pyplot as plt
from PIL import Image

from lightsail_mbs import RunSettings, SailParameters, solve
from lightsail_mbs.viz.sheet import render_sheet_frames

case = SailParameters(model="sheet", n=8, ny=8, defect_mode_y=0.5, youngs_modulus=4.5e9)
result = solve(case, "reduced", settings=RunSettings(t_final=4.0))

# %%
# The answer, with its uncertainty and the conditioning verdict.
print(result.answer_text())
print(f"tiles: {case.n} × {case.ny}, stored states: {result.time.size}, well conditioned: {result.well_conditioned}")

# %%
# Four frames, evenly spaced in time; the last is the first state at or after the failure, drawn as failed.
paths = render_sheet_frames(result, Path(tempfile.mkdtemp()), frames=4, size=(900, 400))
fig, axes = plt.subplots(2, 2, figsize=(10, 4.6))
for ax, path in zip(axes.flat, paths):
    ax.imshow(Image.open(path))
    ax.set_axis_off()
fig.tight_layout()
