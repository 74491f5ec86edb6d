"""The report of paper.sheet_physics: its rows as Markdown tables and as a figure.

Functions of the rows that paper.sheet_physics.compute returns (no runs): summary_markdown (each boundary
with its bisection bracket, each sheet's against the strip's of the same grid) and plot.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from lightsail_mbs.viz.plots import new_figure, save_figure


def _bracket(lo, hi) -> str:
    """A bisected boundary as its geometric middle × or ÷ its half-width factor, and the bracket."""
    if lo is None or hi is None:
        return "not bracketed"
    mid, half = math.sqrt(lo * hi), math.sqrt(hi / lo)
    return f"{mid:.3g} (×÷{half:.3f}; {lo:.3g} – {hi:.3g})"


def _number(value, digits=3) -> str:
    return "–" if value is None else f"{value:.{digits}g}"


def _boundary_table(data, quantity, extra=None) -> list[str]:
    """Rows of bisected boundaries: bracket, against the strip of the same grid, runs (and extra columns)."""
    extra = extra or {}
    head = f"| case | grid | {quantity}: middle (×÷ half-width; bracket) | sheet / strip (range) | runs |"
    lines = [head + "".join(f" {name} |" for name in extra), "|---|---|---|---|---|" + "---|" * len(extra)]
    for r in data:
        grid = r["grid"].split("×")[0]
        strip = next((q for q in data if q["case"] == "strip" and q["grid"].split("×")[0] == grid), None)
        versus = "–"
        if r["case"] != "strip" and strip and None not in (r["ratio_low"], r["ratio_high"], strip["ratio_low"]):
            lo, hi = r["ratio_low"] / strip["ratio_high"], r["ratio_high"] / strip["ratio_low"]
            versus = f"{math.sqrt(lo * hi):.3g} ({lo:.3g} – {hi:.3g})"
        cells = "".join(f" {f(r)} |" for f in extra.values())
        lines.append(
            f"| {r['case']} | {r['grid']} | {_bracket(r['ratio_low'], r['ratio_high'])} | {versus} | "
            f"{r['runs']} |{cells}"
        )
    return lines + [""]


def summary_markdown(rows) -> str:
    """The studies as Markdown tables: each boundary with its bisection bracket, each sheet's boundary
    against the strip's of the same grid (ratio range from the two brackets), the failure times against E,
    the unlit runs, and the Gaussian failure times of sheet and strip with their ratio."""
    lines = ["# The sheet against the strip", ""]
    lines += ["## Critical modulus: E_stable / E_cr,max", ""]
    lines += _boundary_table(rows["modulus"], "E_stable / E_cr,max")
    lines += [
        "## Doubly sinusoidal sheet, E_m = E: failure time against E "
        f"({_number(rows['horizon'][0]['t_final'])} s runs)",
        "",
        "| grid | E / E_cr,max | t(1.5 a₀) (s) | t(2 a₀) (s) | growth rate between (1/s) | largest a / a₀ |",
        "|---|---|---|---|---|---|",
    ]
    for r in rows["horizon"]:
        lines.append(
            f"| {r['grid']}×{r['grid']} | {r['ratio']:g} | {_number(r['t_1_5'], 4)} | {_number(r['t_2'], 4)} | "
            f"{_number(r['growth_rate'])} | {_number(r['max_ratio'], 4)} |"
        )
    lines += [
        "",
        f"## Doubly sinusoidal sheets, E_m = E, E = {_number(rows['resolution'][0]['ratio'])} E_cr,max: "
        "failure time against the tiles per half wavelength",
        "",
        "| ν_x = ν_y | grid | tiles per half wave | t(1.5 a₀) (s) | t(2 a₀) (s) | growth rate between (1/s) |",
        "|---|---|---|---|---|---|",
    ]
    for r in rows["resolution"]:
        lines.append(
            f"| {r['mode']:g} | {r['grid']}×{r['grid']} | {r['tiles_per_half_wave']:.3g} | {_number(r['t_1_5'], 4)} | "
            f"{_number(r['t_2'], 4)} | {_number(r['growth_rate'])} |"
        )
    lines += ["", "## Stabilising edge tension, unlit-twin rule: T_stable / T_cr,max", ""]
    lines += _boundary_table(
        rows["twin"],
        "T_stable / T_cr,max",
        {
            "twin's peak / a₀ at the stable end": lambda r: _number(r["unlit_peak_stable"], 4),
            "lit peak / a₀ there": lambda r: _number(r["lit_peak_stable"], 4),
            "largest z_lit − z_twin / a₀ there": lambda r: _number(r["departure_stable"], 3),
            "twin's peak / a₀ at the failing end": lambda r: _number(r["unlit_peak_failed"], 4),
            "failure time there (s)": lambda r: _number(r["failure_time_failed"], 4),
        },
    )
    lines += [
        f"## Unlit sheets at {_number(rows['unlit'][0]['tension_ratio'])} T_cr,max, 6 s",
        "",
        "| case | grid | largest a / a₀ | reached 2 a₀ at (s) |",
        "|---|---|---|---|",
    ]
    for r in rows["unlit"]:
        lines.append(f"| {r['case']} | {r['grid']} | {_number(r['max_ratio'], 4)} | {_number(r['failure_time'], 4)} |")
    lines += [
        "",
        "## Doubly sinusoidal sheet above its tension boundary: lit run and unlit twin, 6 s",
        "",
        "| grid | T / T_cr,max | lit peak / a₀ | twin's peak / a₀ | lit / twin | twin rule: fails at (s) | "
        "paper's rule: fails at (s) |",
        "|---|---|---|---|---|---|---|",
    ]
    for r in rows["scan"]:
        lines.append(
            f"| {r['grid']}×{r['grid']} | {r['tension_ratio']:g} | {_number(r['lit_peak'], 4)} | "
            f"{_number(r['twin_peak'], 4)} | {_number(r['peak_ratio'], 4)} | "
            f"{_number(r['twin_rule_failure_time'], 4)} | "
            f"{_number(r['papers_rule_failure_time'], 4)} |"
        )
    lines += ["", "## Stabilising edge tension, paper's rule: T_stable / T_cr,max", ""]
    lines += _boundary_table(rows["tension"], "T_stable / T_cr,max")
    lines += [
        "## Centred Gaussian beam, 1-D sine, E = 4.5e9 Pa: failure time",
        "",
        "| grid | waist w (m) | strip (ms) | sheet (ms) | sheet / strip |",
        "|---|---|---|---|---|",
    ]
    g = rows["gaussian"]
    for grid in sorted({r["grid"] for r in g}):
        for w in sorted({r["waist_m"] for r in g}, reverse=True):
            pick = {r["case"]: r["failure_time_ms"] for r in g if r["grid"] == grid and r["waist_m"] == w}
            strip, sheet = pick.get("strip"), pick.get("sheet")
            ratio = f"{sheet / strip:.3f}" if strip and sheet else "–"
            lines.append(
                f"| {grid}×{grid} | {w:g} | {'–' if strip is None else f'{strip:.4f}'} | "
                f"{'–' if sheet is None else f'{sheet:.4f}'} | {ratio} |"
            )
    lines.append("")
    return "\n".join(lines)


def _boundary_panel(ax, data, xlabel) -> None:
    """Bisection brackets per case (rows) and grid (offset markers), log axis when any is bracketed."""
    labels = list(dict.fromkeys(r["case"] for r in data))
    grids = list(dict.fromkeys(r["grid"].split("×")[0] for r in data))
    for j, g in enumerate(grids):
        mine = [(i, r) for i, c in enumerate(labels) for r in data if r["case"] == c and r["grid"].split("×")[0] == g]
        if not mine:
            continue
        y = np.array([i for i, _ in mine]) + 0.6 * (j / max(1, len(grids) - 1) - 0.5)
        mid = np.array([r["ratio"] or np.nan for _, r in mine])
        lo = np.array([r["ratio_low"] or np.nan for _, r in mine])
        hi = np.array([r["ratio_high"] or np.nan for _, r in mine])
        ax.errorbar(mid, y, xerr=[mid - lo, hi - mid], fmt="o", capsize=3, label=f"{g} tiles along L")
    ax.set_yticks(np.arange(len(labels)), labels, fontsize=7)
    if any(r["ratio"] for r in data):
        ax.set_xscale("log")
    ax.set_xlabel(xlabel)
    ax.legend(fontsize=7)


def plot(path, rows, *, run_length: float) -> Path:
    """Top: critical moduli, failure time against E (doubly sinusoidal, E_m = E); bottom: edge tension
    (paper's rule and unlit-twin rule, brackets), Gaussian failure times. run_length (s): how long the
    boundary runs are (a line on the failure-time panel)."""
    fig, ax = new_figure(2, 2, size=(13.0, 8.4))
    _boundary_panel(ax[0, 0], rows["modulus"], "E_stable / E_cr,max (6 s)")
    for grid in sorted({r["grid"] for r in rows["horizon"]}):
        mine = [r for r in rows["horizon"] if r["grid"] == grid]
        ax[0, 1].plot([r["ratio"] for r in mine], [r["t_2"] or np.nan for r in mine], "o-", label=f"{grid}×{grid}")
    ax[0, 1].axhline(run_length, color="0.6", lw=0.8, ls="--")
    if any(r["t_2"] for r in rows["horizon"]):  # a log axis needs a point
        ax[0, 1].set_xscale("log")
    ax[0, 1].set_xlabel("E / E_cr,max (doubly sinusoidal, E_m = E)")
    ax[0, 1].set_ylabel("time to 2 a₀ (s)")
    ax[0, 1].legend(fontsize=7)
    tension = [dict(r, case=f"{r['case']} (paper's rule)") for r in rows["tension"]]
    tension += [dict(r, case=f"{r['case']} (twin rule)") for r in rows["twin"]]
    _boundary_panel(ax[1, 0], tension, "T_stable / T_cr,max (6 s)")
    g = rows["gaussian"]
    for grid in sorted({r["grid"] for r in g}):
        for label, style in (("strip", "s--"), ("sheet", "o-")):
            mine = [r for r in g if r["grid"] == grid and r["case"] == label]
            ax[1, 1].plot(
                [r["waist_m"] for r in mine],
                [r["failure_time_ms"] or np.nan for r in mine],
                style,
                label=f"{label}, {grid} tiles along L",
            )
    ax[1, 1].set_xlabel("beam waist w (m)")
    ax[1, 1].set_ylabel("failure time (ms)")
    ax[1, 1].legend(fontsize=7)
    fig.suptitle("The sheet against the strip (in-house solver; brackets: bisection)", fontsize=10)
    return save_figure(fig, path)
