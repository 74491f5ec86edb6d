"""Draw a render_scene.Scene with matplotlib's Agg backend (no display): one figure reused for every frame."""

from __future__ import annotations

import numpy as np
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.collections import LineCollection, PolyCollection
from matplotlib.figure import Figure

from lightsail_mbs.viz.scene import Scene

DPI = 100.0
POINTS_PER_PIXEL = 72.0 / DPI


class MatplotlibCanvas:
    """A width × height pixel Agg canvas; draw(scene) returns the RGB image (height, width, 3) uint8."""

    name = "matplotlib"

    def __init__(self, width: int, height: int):
        self.size = (width, height)
        self.figure = Figure(figsize=(width / DPI, height / DPI), dpi=DPI, facecolor="white")
        self.canvas = FigureCanvasAgg(self.figure)
        self.axes = self.figure.add_axes((0.0, 0.0, 1.0, 1.0))
        self.axes.set_axis_off()
        self.lines = LineCollection([], capstyle="butt", joinstyle="round")
        self.polys = PolyCollection([], edgecolors="none")
        self.axes.add_collection(self.lines)
        self.axes.add_collection(self.polys)
        self.texts = []

    def draw(self, scene: Scene) -> np.ndarray:
        if (scene.width, scene.height) != self.size:
            raise ValueError(f"scene of {scene.width}x{scene.height} px on a {self.size[0]}x{self.size[1]} canvas")
        ax = self.axes
        ax.set_xlim(scene.box[0], scene.box[1])
        ax.set_ylim(scene.box[2], scene.box[3])
        self.lines.set_segments(scene.strokes)
        self.lines.set_color(scene.stroke_rgba)
        self.lines.set_linewidth(scene.stroke_width * POINTS_PER_PIXEL)
        self.polys.set_verts(scene.triangles)
        self.polys.set_facecolor(scene.triangle_rgba)
        while len(self.texts) < len(scene.texts):
            self.texts.append(ax.text(0, 0, "", ha="left", va="top", family="DejaVu Sans Mono"))
        for artist, item in zip(self.texts, scene.texts):
            artist.set_visible(True)
            artist.set_position((item.x, item.y))
            artist.set_text(item.text)
            artist.set_color(item.rgba)
            artist.set_fontsize(item.size * POINTS_PER_PIXEL)
        for artist in self.texts[len(scene.texts) :]:
            artist.set_visible(False)
        self.canvas.draw()
        return np.asarray(self.canvas.buffer_rgba())[..., :3].copy()

    def close(self) -> None:
        self.figure.clear()
