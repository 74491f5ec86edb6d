"""validation/sheet_spectrum.py's table A joins each tabulated modulus to the late growth rate of the 60 s runs at
that modulus: every long run's rate must land in its row, although a run's E/E_cr,max is recomputed from its
modulus and is not the tabulated float."""

from lightsail_mbs.analysis import sheet_spectrum as ss
from lightsail_mbs.model import theory
from tests.helpers import validation_script


def test_every_long_run_lands_in_its_row_of_table_a():
    v = validation_script("sheet_spectrum")
    rows = [
        {"grid": 12, "ratio": ratio, "rate": 0.5, "family": "A1", **{f"rate_{f}": 0.5 for f in ss.FAMILIES}}
        for ratio in v.RATIOS
    ]
    long_rows = []
    for k, (grid, ratio) in enumerate(v.LONG_RUNS):
        p = v.case(grid, ratio)
        long_rows.append(
            {"grid": grid, "ratio": p.youngs_modulus / theory.critical_modulus_max(p), "late_rate": 0.1 * (k + 1)}
        )
    assert any(r["ratio"] != ratio for r, (_, ratio) in zip(long_rows, v.LONG_RUNS, strict=True))  # the float case
    lines = v.table_a(rows, long_rows)[2:]
    for ratio in {ratio for _, ratio in v.LONG_RUNS}:
        (line,) = [line for line in lines if line.startswith(f"| {ratio:.3g} |")]
        expected = " / ".join(
            f"{0.1 * (k + 1):.3f}" for g in (18, 24) for k, run in enumerate(v.LONG_RUNS) if run == (g, ratio)
        )
        assert line.endswith(f"| {expected} |"), line
