"""One frame of a Result as 2-D drawing primitives, whatever renderer draws it.

The sail's deflection is ~1e-5 of its length, so a frame shows it exaggerated: every slice end
point p = c ± (l/2)(cos θ, sin θ) is written in the frame of the slice centres' total-least-squares
line (the line of analysis.line_offsets, which removes rigid drift and rotation), as (u, v), and
drawn at (u, E·v) with one exaggeration factor E for the whole sequence. Lengths are in units of
the sail length L. Hinge j (between slices j and j+1) carries the curvature κ_j = (θ_{j+1} − θ_j)/l
and the bending moment M_j = k_T (θ_{j+1} − θ_j) (paper Eq. 12); the free ends carry neither.
Arrows: the radiation load on each slice (Eq. 11 and its generalisation in loads.py), split into
its components along the slice's normal and tangent and drawn along the drawn slice's normal and
tangent, ending on the slice (the beam comes from below); the TnT boundary tension
T(∓cos θ, ∓sin θ) at the free ends (Eq. 32) along the drawn end slices.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from matplotlib.colors import LinearSegmentedColormap

from lightsail_mbs.analysis import fails_at_trough
from lightsail_mbs.base.validation import ParameterError
from lightsail_mbs.model.loads import radiation_forces
from lightsail_mbs.result import Result

COLOR_BY = ("curvature", "moment", None)
SAIL_RGBA = (0.15, 0.15, 0.15, 1.0)
GHOST_RGBA = (0.78, 0.78, 0.78, 1.0)
LOAD_RGBA = (0.95, 0.55, 0.05, 1.0)
TENSION_RGBA = (0.0, 0.5, 0.2, 1.0)
FAIL_RGBA = (0.85, 0.0, 0.0, 1.0)
TEXT_RGBA = (0.0, 0.0, 0.0, 1.0)
TIME_RGBA = (0.2, 0.35, 0.7, 1.0)
CHAR_WIDTH = 0.6  # advance of a monospace character in font sizes (DejaVu Sans Mono; Exudyn's font scaled to it)
# diverging: blue (negative) - dark grey (zero, distinct from the light grey initial shape) - red (positive)
COLORMAP = LinearSegmentedColormap.from_list("sail", ["#1f5bd6", "#7f9fe0", "#303030", "#e07a7a", "#d11f1f"])
COLOR_SCALES = ("frame", "run")


def text_width(text: str, size: float) -> float:
    """Width in pixels of a one-line monospace text of font size `size` (pixels), with 8 % to spare
    for a renderer whose font rounds to a larger size."""
    return 1.08 * CHAR_WIDTH * size * len(text)


@dataclass
class Text:
    """A left-aligned text whose top-left corner is at (x, y) (world units), size in pixels."""

    x: float
    y: float
    text: str
    size: float
    rgba: tuple = TEXT_RGBA


@dataclass
class Scene:
    """What one frame draws: box (x_min, x_max, y_min, y_max) in world units, filling width × height pixels;
    strokes (m, 2, 2) with RGBA colours (m, 4) and widths in pixels (m,), drawn in order; filled
    triangles (k, 3, 2) with colours (k, 4), drawn over the strokes; left-aligned texts."""

    width: int
    height: int
    box: tuple
    strokes: np.ndarray
    stroke_rgba: np.ndarray
    stroke_width: np.ndarray
    triangles: np.ndarray
    triangle_rgba: np.ndarray
    texts: list = field(default_factory=list)

    @property
    def pixel(self) -> float:
        """The size of one pixel in world units."""
        return (self.box[1] - self.box[0]) / self.width


def _line_frame(x: np.ndarray, y: np.ndarray):
    """Centroid and unit direction of the centres' total-least-squares line (as analysis.line_offsets)."""
    xc, yc = x.mean(), y.mean()
    dx, dy = x - xc, y - yc
    phi = 0.5 * math.atan2(2.0 * float(dx @ dy), float(dx @ dx - dy @ dy))
    return xc, yc, math.cos(phi), math.sin(phi)


def hinge_values(result: Result, index: int, color_by: str | None) -> np.ndarray:
    """κ_j = Δθ_j / l (1/m) or M_j = k_T Δθ_j (N·m) at the n − 1 hinges of stored state `index`."""
    dtheta = np.diff(result.theta[index])
    dtheta = (dtheta + np.pi) % (2.0 * np.pi) - np.pi
    if color_by == "curvature":
        return dtheta / result.params.slice_length
    if color_by == "moment":
        return result.params.torsional_stiffness * dtheta
    return np.zeros_like(dtheta)


def check_color_by(params, color_by) -> None:
    if color_by not in COLOR_BY:
        raise ParameterError(f"color_by={color_by!r} is invalid: allowed 'curvature', 'moment' or None")
    if color_by == "moment" and params.torsional_stiffness == 0.0:
        raise ParameterError(
            f"color_by='moment' is invalid for model={params.model!r} with bending="
            f"{params.bending}: allowed only with torsional springs (k_T > 0); use 'curvature'"
        )


@dataclass(frozen=True)
class Layout:
    """Pixel layout of a frame of width × height: font sizes, the text band on top, the legend band below."""

    width: int
    height: int

    @property
    def scale(self) -> float:
        return max(0.5, min(self.width / 800.0, self.height / 400.0))

    @property
    def big_font(self) -> float:
        return max(13, round(17 * self.scale))

    @property
    def small_font(self) -> float:
        return max(10, round(12 * self.scale))

    @property
    def top_band(self) -> float:
        return 1.25 * self.big_font + 2.5 * self.small_font + 8 * self.scale

    @property
    def bottom_band(self) -> float:
        return 2.0 * self.small_font + 22 * self.scale

    @property
    def box(self) -> tuple:
        """World box: x from −0.05 to 1.05 (sail length 1); y = 0 in the middle of the sail band."""
        pix = 1.1 / self.width
        mid = 0.5 * (self.bottom_band - self.top_band) * pix  # y = 0 sits this far above the centre
        half = 0.5 * self.height * pix
        return (-0.05, 1.05, -half - mid, half - mid)

    @property
    def sail_half_height(self) -> float:
        """Half the height (world units) of the band between the text and the legend."""
        return 0.5 * (self.height - self.top_band - self.bottom_band) * 1.1 / self.width

    @property
    def arrow_length(self) -> float:
        return min(0.07, 0.3 * self.sail_half_height)


def _offsets(result: Result, index: int):
    """End points of every slice, (n, 2) each for u and v, in its line frame (metres)."""
    p = result.params
    x, y, th = result.x[index], result.y[index], result.theta[index]
    xc, yc, cphi, sphi = _line_frame(x, y)
    half = 0.5 * p.slice_length
    ends = np.stack(
        [
            np.stack([x - half * np.cos(th), y - half * np.sin(th)], -1),
            np.stack([x + half * np.cos(th), y + half * np.sin(th)], -1),
        ],
        1,
    )  # (n, 2, 2)
    du, dv = ends[..., 0] - xc, ends[..., 1] - yc
    u = cphi * du + sphi * dv + 0.5 * p.length
    v = -sphi * du + cphi * dv
    return u, v


@dataclass
class Style:
    """What is shared by every frame of a sequence (or of both runs side by side): the exaggeration E,
    whether it is automatic (adaptive: lowered frame by frame after failure when the sail would leave its band),
    the colour range ±vmax of the hinge values (color_scale 'run': the largest of all frames; 'frame':
    each frame its own, vmax unused), the time axis (t_start, t_end) and the layout."""

    layout: Layout
    exaggeration: float
    adaptive: bool
    color_by: str | None
    color_scale: str
    vmax: float
    arrows: bool
    time_span: tuple


def _round_down(value: float) -> float:
    """value rounded down to two significant digits."""
    digits = 10.0 ** (math.floor(math.log10(value)) - 1)
    return math.floor(value / digits) * digits


def _peak_deflection(result: Result, index: int) -> float:
    """Largest |offset| of a slice end point from the best-fit line, in units of L."""
    return float(np.abs(_offsets(result, index)[1]).max()) / result.params.length


def _deflection_limit(layout: Layout) -> float:
    """The largest drawn deflection (units of L) that keeps the sail and its load arrows inside the band."""
    return layout.sail_half_height - 1.2 * layout.arrow_length


def auto_exaggeration(results, indices, layout: Layout) -> float:
    """The sequence's E: the initial amplitude a₀ drawn at 5 % of L (at most 35 % of the sail band's half
    height), lowered if a chosen frame up to the run's failure would leave the band; rounded down to two
    significant digits; at least 1. Frames after failure may lower it further (frame_exaggeration)."""
    target = min(0.05, 0.35 * layout.sail_half_height)
    e = math.inf
    for r, idx in zip(results, indices):
        a0 = float(r.amplitude[0]) / r.params.length
        fail = r.failure_time
        until = [i for i in idx if fail is None or r.time[i] <= fail] or list(idx[:1])
        peak = max(_peak_deflection(r, i) for i in until)
        if a0 > 0:
            e = min(e, target / a0)
        if peak > 0:
            e = min(e, _deflection_limit(layout) / peak)
    if not math.isfinite(e) or e <= 1.0:
        return 1.0
    return _round_down(e)


def frame_exaggeration(style: Style, states) -> float:
    """E for one frame showing the (result, index) pairs `states`: the style's, or with automatic
    exaggeration lowered (two significant digits, below 1 if need be) so that every sail stays in its band."""
    if not style.adaptive:
        return style.exaggeration
    peak = max(_peak_deflection(r, i) for r, i in states)
    limit = _deflection_limit(style.layout)
    if peak * style.exaggeration <= limit or peak == 0.0:
        return style.exaggeration
    return _round_down(limit / peak)


def make_style(
    results, indices, layout: Layout, exaggeration=None, color_by="curvature", arrows=True, color_scale="frame"
) -> Style:
    for r in results:
        check_color_by(r.params, color_by)
    if color_scale not in COLOR_SCALES:
        raise ParameterError(
            f"color_scale={color_scale!r} is invalid: allowed 'frame' (each frame its own range) "
            "or 'run' (one range for the whole sequence)"
        )
    adaptive = exaggeration is None
    if adaptive:
        exaggeration = auto_exaggeration(results, indices, layout)
    elif not (isinstance(exaggeration, (int, float)) and math.isfinite(exaggeration) and exaggeration > 0):
        raise ParameterError(f"exaggeration={exaggeration!r} is invalid: allowed a finite number > 0 (None: automatic)")
    vmax = max(
        (float(np.abs(hinge_values(r, i, color_by)).max(initial=0.0)) for r, idx in zip(results, indices) for i in idx),
        default=0.0,
    )
    time_span = (
        min(float(r.time[0]) for r in results),
        max(max(float(r.settings.t_final), float(r.time[-1])) for r in results),
    )
    return Style(layout, float(exaggeration), adaptive, color_by, color_scale, vmax, bool(arrows), time_span)


def _arrow(start, vector, width_px, pix, rgba, strokes, triangles):
    """A shaft stroke (width in pixels) and a filled head triangle (4 shaft widths long) from start along vector."""
    length = float(np.hypot(*vector))
    if length == 0.0:
        return
    d = np.asarray(vector) / length
    nrm = np.array([-d[1], d[0]])
    head = min(4.0 * width_px * pix, 0.5 * length)
    tip = np.asarray(start) + vector
    base = tip - head * d
    strokes.append((np.array([start, base]), rgba, width_px))
    triangles.append((np.array([tip, base + 0.45 * head * nrm, base - 0.45 * head * nrm]), rgba))


def _fmt_exaggeration(e: float) -> str:
    return f"{e:.2g}" if e < 10 or e >= 1e5 else f"{e:.0f}"


def build_scene(
    result: Result, index: int, style: Style, label: str | None = None, exaggeration: float | None = None
) -> Scene:
    """The primitives of stored state `index` of `result` under `style`, with the deflection exaggerated by
    `exaggeration` (None: frame_exaggeration of this state alone)."""
    p = result.params
    lay = style.layout
    L = p.length
    pix = 1.1 / lay.width
    E = frame_exaggeration(style, [(result, index)]) if exaggeration is None else exaggeration
    strokes, triangles, texts = [], [], []  # strokes: (points (2, 2), rgba, width in pixels)

    # initial shape (ghost) and the best-fit line
    u0, v0 = _offsets(result, 0)
    ghost = np.stack([u0, E * v0], -1) / L  # (n, 2 ends, 2)
    strokes.extend((seg, GHOST_RGBA, 2.0 * lay.scale) for seg in ghost)
    strokes.append((np.array([[0.0, 0.0], [1.0, 0.0]]), GHOST_RGBA, 1.0))

    u, v = _offsets(result, index)
    ends = np.stack([u, E * v], -1) / L  # (n, 2, 2) drawn end points
    centres = ends.mean(axis=1)
    along = ends[:, 1] - ends[:, 0]
    along /= np.linalg.norm(along, axis=1, keepdims=True)
    normal = np.stack([-along[:, 1], along[:, 0]], -1)

    if style.arrows:
        fx, fy = radiation_forces(p, result.x[index], result.theta[index])
        th = result.theta[index]
        f_t = fx * np.cos(th) + fy * np.sin(th)
        f_n = -fx * np.sin(th) + fy * np.cos(th)
        fmax = float(np.max(np.hypot(f_t, f_n)))
        step = max(1, math.ceil(p.n / 30))
        for i in range(step // 2, p.n, step):
            if fmax > 0:
                vec = lay.arrow_length * (f_n[i] * normal[i] + f_t[i] * along[i]) / fmax
                _arrow(centres[i] - vec, vec, 1.5 * lay.scale, pix, LOAD_RGBA, strokes, triangles)
        if p.model == "tnt" and p.tension > 0:
            _arrow(ends[0, 0], -lay.arrow_length * along[0], 2.0 * lay.scale, pix, TENSION_RGBA, strokes, triangles)
            _arrow(ends[-1, 1], lay.arrow_length * along[-1], 2.0 * lay.scale, pix, TENSION_RGBA, strokes, triangles)

    # the sail: each slice in two halves, coloured by the hinge value at that end (0 at the free ends)
    values = np.concatenate([[0.0], hinge_values(result, index, style.color_by), [0.0]])
    vmax = style.vmax if style.color_scale == "run" else float(np.abs(values).max())
    for i in range(p.n):
        for half, (a, b) in enumerate(((ends[i, 0], centres[i]), (centres[i], ends[i, 1]))):
            rgba = SAIL_RGBA if style.color_by is None else _color(values[i + half], vmax)
            strokes.append((np.array([a, b]), rgba, 4.0 * lay.scale))

    # texts: title line (time, amplitude ratio; failure on the right), case line, arrow legend
    t = float(result.time[index])
    a0 = float(result.amplitude[0])
    x0, x1 = lay.box[0] + 8 * lay.scale * pix, lay.box[1] - 8 * lay.scale * pix
    y1 = lay.box[3] - 6 * lay.scale * pix
    y2 = y1 - 1.3 * lay.big_font * pix
    y3 = y2 - 1.25 * lay.small_font * pix
    decimals = max(0, 3 - math.floor(math.log10(style.time_span[1] - style.time_span[0] or 1.0)))
    growth = f"a/a0 = {result.amplitude[index] / a0:.3f}" if a0 > 0 else f"a = {result.amplitude[index]:.3g} m"
    texts.append(Text(x0, y1, f"t = {t:.{decimals}f} s   {growth}", lay.big_font))
    fail = result.failure_time
    if fail is not None and t >= fail:
        where = "trough" if fails_at_trough(result.x[index], result.y[index]) else "crest"
        note = f"FAILED at t = {fail:.{decimals}f} s ({where})"
        texts.append(Text(x1 - text_width(note, lay.big_font) * pix, y1, note, lay.big_font, FAIL_RGBA))
        _mark_failure(ends, E * v / L, lay, strokes, triangles)
    what = f"{label}: " if label else ""
    lowered = f" (lowered from x{_fmt_exaggeration(style.exaggeration)})" if E < style.exaggeration else ""
    texts.append(
        Text(
            x0,
            y2,
            f"{what}{p.model}, n = {p.n}, {result.solver}   deflection x{_fmt_exaggeration(E)}"
            f"{lowered} vs best-fit line, grey: t = 0",
            lay.small_font,
        )
    )
    if style.arrows:
        texts.append(Text(x0, y3, "arrows: radiation load", lay.small_font, LOAD_RGBA))
        if p.model == "tnt" and p.tension > 0:
            texts.append(
                Text(
                    x0 + text_width("arrows: radiation load, ", lay.small_font) * pix,
                    y3,
                    f"boundary tension T = {p.tension:.3g} N",
                    lay.small_font,
                    TENSION_RGBA,
                )
            )
    if result.error and index == result.time.size - 1:
        note = f"solver stopped: {result.error}"[:60]
        texts.append(Text(x1 - text_width(note, lay.small_font) * pix, y3, note, lay.small_font, FAIL_RGBA))

    _legend(result, index, style, vmax, strokes, triangles, texts)
    return _assemble(lay, strokes, triangles, texts)


def _mark_failure(ends, deflection, lay: Layout, strokes, triangles) -> None:
    """A red border round the frame and a red wedge pointing at the largest deflection (where it fails:
    from below at a trough, from above at a crest)."""
    pix = 1.1 / lay.width
    k = int(np.argmax(np.abs(deflection).max(axis=1)))
    tip = ends[k].mean(axis=0)
    side = 1.0 if tip[1] >= 0 else -1.0
    h = 12 * lay.scale * pix
    apex = tip + side * np.array([0.0, 0.5 * h])
    triangles.append((np.array([apex, apex + [-0.5 * h, side * h], apex + [0.5 * h, side * h]]), FAIL_RGBA))
    w = 2.0 * lay.scale * pix
    b = lay.box
    corners = [[b[0] + w, b[2] + w], [b[1] - w, b[2] + w], [b[1] - w, b[3] - w], [b[0] + w, b[3] - w]]
    for a, c in zip(corners, corners[1:] + corners[:1]):
        strokes.append((np.array([a, c]), FAIL_RGBA, 4.0 * lay.scale))


def _color(value: float, vmax: float) -> tuple:
    return tuple(COLORMAP(0.5 if vmax == 0 else 0.5 + 0.5 * value / vmax))


def _legend(result: Result, index: int, style: Style, vmax: float, strokes, triangles, texts) -> None:
    """Time bar (elapsed time, red failure tick) bottom left; colour bar of the hinge values bottom right."""
    lay = style.layout
    pix = 1.1 / lay.width
    y_bar = lay.box[2] + (8 + 0.5 * lay.small_font) * lay.scale * pix
    y_text = y_bar + (6 * lay.scale + 1.2 * lay.small_font) * pix
    t0, t1 = style.time_span
    span = t1 - t0 or 1.0
    x0, x1 = 0.0, 0.45
    frac = (float(result.time[index]) - t0) / span
    strokes.append((np.array([[x0, y_bar], [x1, y_bar]]), GHOST_RGBA, 6 * lay.scale))
    strokes.append((np.array([[x0, y_bar], [x0 + frac * (x1 - x0), y_bar]]), TIME_RGBA, 6 * lay.scale))
    fail = result.failure_time
    if fail is not None:
        xf = x0 + (fail - t0) / span * (x1 - x0)
        strokes.append(
            (np.array([[xf, y_bar - 8 * lay.scale * pix], [xf, y_bar + 8 * lay.scale * pix]]), FAIL_RGBA, 3 * lay.scale)
        )
    texts.append(
        Text(x0, y_text, f"time {t0:g} - {t1:g} s" + ("" if fail is None else " (red: failure)"), lay.small_font)
    )
    if style.color_by is None:
        return
    c0, c1, cells = 0.65, 1.0, 48
    edges = np.linspace(c0, c1, cells + 1)
    for k in range(cells):
        strokes.append(
            (
                np.array([[edges[k], y_bar], [edges[k + 1], y_bar]]),
                _color((k + 0.5) / cells * 2 - 1, 1.0),
                10 * lay.scale,
            )
        )
    unit = "1/m" if style.color_by == "curvature" else "N m"
    texts.append(Text(c0, y_text, f"{style.color_by} +-{vmax:.2g} {unit}", lay.small_font))


def _assemble(lay: Layout, strokes, triangles, texts) -> Scene:
    seg = np.array([s[0] for s in strokes], float).reshape(-1, 2, 2)
    rgba = np.array([s[1] for s in strokes], float).reshape(-1, 4)
    width = np.array([s[2] for s in strokes], float)
    tri = np.array([t[0] for t in triangles], float).reshape(-1, 3, 2)
    trgba = np.array([t[1] for t in triangles], float).reshape(-1, 4)
    return Scene(lay.width, lay.height, lay.box, seg, rgba, width, tri, trgba, texts)
