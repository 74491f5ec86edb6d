"""
A stability boundary
====================

How stiff must the paper's torsion sail be to hold its ν = 3/2 defect for 6 s? The modulus E is bracketed
and bisected in log space (``lightsail_mbs.studies.bisection``), each evaluation a 6 s run on the reduced
solver of a coarse chain (n = 12), every run kept in a resumable store. The boundary is compared with the
paper's closed-form scale E_cr,max (Eq. 8). The moment balance behind Eq. 8 gives the scaling but not the
constant: the measured boundary lies near 7.7 E_cr,max at n = 30 (:doc:`../beyond-the-paper`, the
stability analysis), and the coarse chain here lands close to it.

From the command line, the same boundary by scaled runs of 6 s::

    lightsail-mbs stability torsion-soft --run-time 6
"""

import tempfile

import matplotlib.pyplot as plt

from lightsail_mbs import RunSettings, paper_case
from lightsail_mbs.base.formatting import with_uncertainty
from lightsail_mbs.model import theory
from lightsail_mbs.studies.bisection import bisect_boundary

base = paper_case("torsion-soft", n=12)
e_cr_max = theory.critical_modulus_max(base)

boundary = bisect_boundary(
    lambda e: base.replace(youngs_modulus=e),
    1e11,
    1e13,
    store_dir=tempfile.mkdtemp(),
    solver="reduced",
    settings=RunSettings(t_final=6.0),
    factor=1.5,
    workers=1,
    progress=False,
)
lo, hi = boundary.bracket

# %%
# The boundary is the geometric mean of the final bracket; its ± is half the bracket's width.
print(
    f"{boundary.status} after {len(boundary.evaluations)} runs: failed at E = {boundary.unstable_value:.3g} Pa, "
    f"held at E = {boundary.stable_value:.3g} Pa"
)
print(f"6 s boundary E* = {with_uncertainty(boundary.value, (hi - lo) / 2)} Pa")
print(f"closed form E_cr,max = {e_cr_max:.3g} Pa (Eq. 8): E*/E_cr,max = {boundary.value / e_cr_max:.2f}")

fig, ax = plt.subplots(figsize=(7, 2.8))
for step, (value, stable, _) in enumerate(boundary.evaluations):
    ax.semilogx(value, step, "o", color="tab:blue" if stable else "tab:red")
ax.axvspan(lo, hi, color="grey", alpha=0.3, label="final bracket")
ax.axvline(e_cr_max, color="black", ls="--", label="E_cr,max (Eq. 8)")
ax.plot([], [], "o", color="tab:blue", label="held 6 s")
ax.plot([], [], "o", color="tab:red", label="failed")
ax.set_xlabel("Young's modulus E (Pa)")
ax.set_ylabel("evaluation")
ax.legend(loc="upper left", fontsize=8)
fig.tight_layout()
