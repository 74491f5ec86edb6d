"""Draw a render_scene.Scene with Exudyn's software raytracer, headless.

The scene is the graphics data of one ObjectGround in a minimal system: every stroke becomes a
quad and every triangle a triangle of one TriangleList (per-vertex colours, lighting off, layers
at increasing z towards the orthographic camera), texts become Text items. Each frame replaces
the ground's graphics data and calls SC.renderer.RedrawAndGetImage(useRaytracer=True), which
needs neither a display nor OpenGL. renderer.Start() is never called (without a display it ends
the process).
"""

from __future__ import annotations

import os

import numpy as np

from lightsail_mbs.viz.scene import Scene


class ExudynCanvas:
    """A width × height pixel raytraced view; draw(scene) returns the RGB image (height, width, 3) uint8."""

    name = "exudyn"

    def __init__(self, width: int, height: int, threads: int | None = None):
        import exudyn
        from exudyn.utilities import ObjectGround, VObjectGround

        self.size = (width, height)
        self.sc = exudyn.SystemContainer()
        self.mbs = self.sc.AddSystem()
        self.ground = self.mbs.AddObject(ObjectGround(visualization=VObjectGround(graphicsData=[])))
        self.mbs.Assemble()
        vs = self.sc.visualizationSettings
        vs.view0.window.renderWindowSize = [width, height]
        vs.view0.scene.drawWorldBasis = False
        vs.view0.scene.drawCoordinateSystem = 0
        vs.view0.window.showComputationInfo = False
        vs.general.showSolverTime = False
        vs.general.showSolutionInformation = False
        vs.general.backgroundColor = [1.0, 1.0, 1.0, 1.0]
        # flat colours: one white light along the view axis, no ambient or specular part, every normal +z
        gl = vs.openGL
        gl.lightModelAmbient = [0.0, 0.0, 0.0, 1.0]
        gl.materialSpecular = [0.0, 0.0, 0.0, 1.0]
        gl.light0.position = [0.0, 0.0, 1.0, 0.0]
        gl.light0.diffuse = 1.0
        gl.light0.specular = 0.0
        gl.light1.enable = False
        vs.raytracer.numberOfThreads = threads or os.cpu_count() or 1
        self.box = None

    def _set_view(self, box) -> None:
        """Orthographic view of box: the visible height is 2·zoom, centred on the box centre."""
        self.sc.renderer.ZoomAll()  # initialises the render state of the inactive renderer
        self.sc.renderer.SetModelView(
            zoom=0.5 * (box[3] - box[2]), centerPoint=[0.5 * (box[0] + box[1]), 0.5 * (box[2] + box[3]), 0.0]
        )
        self.box = tuple(box)

    def draw(self, scene: Scene) -> np.ndarray:
        if (scene.width, scene.height) != self.size:
            raise ValueError(f"scene of {scene.width}x{scene.height} px on a {self.size[0]}x{self.size[1]} canvas")
        graphics = [_triangle_list(scene)] + [
            {
                "type": "Text",
                "color": list(t.rgba),
                "text": t.text,
                "fontSize": FONT_SCALE * t.size,
                "offset": [0.0, 0.0],
                "position": [t.x, t.y - TEXT_TOP * FONT_SCALE * t.size * scene.pixel, LAYER],
            }
            for t in scene.texts
        ]
        self.mbs.SetObjectParameter(self.ground, "VgraphicsData", graphics)
        if self.box != tuple(scene.box):
            self._set_view(scene.box)
        image = self.sc.renderer.RedrawAndGetImage(useRaytracer=True)
        return np.ascontiguousarray(image[..., :3], dtype=np.uint8)

    def close(self) -> None:
        self.mbs.Reset()


LAYER = 1e-3  # z step between consecutive primitives (world units; the view is orthographic)
# Exudyn's monospace font advances 0.725 font sizes per character and its letters reach 1.27 font sizes
# above a Text's position; scaled to the advance of render_scene.CHAR_WIDTH, top at the given y
FONT_SCALE = 0.6 / 0.725
TEXT_TOP = 1.27


def _triangle_list(scene: Scene) -> dict:
    """Strokes as quads (width in pixels), then the triangles, each primitive LAYER closer to the camera."""
    seg = scene.strokes
    d = seg[:, 1] - seg[:, 0]
    length = np.linalg.norm(d, axis=1, keepdims=True)
    d = np.divide(d, length, out=np.zeros_like(d), where=length > 0)
    offset = 0.5 * scene.stroke_width[:, None] * scene.pixel * np.stack([-d[:, 1], d[:, 0]], -1)
    quads = np.stack([seg[:, 0] - offset, seg[:, 1] - offset, seg[:, 1] + offset, seg[:, 0] + offset], 1)
    m, k = len(quads), len(scene.triangles)
    pts2 = np.concatenate([quads.reshape(-1, 2), scene.triangles.reshape(-1, 2)])
    z = np.concatenate([np.repeat(np.arange(m), 4), np.repeat(m + np.arange(k), 3)]) * LAYER / max(m + k, 1)
    points = np.column_stack([pts2, z])
    colors = np.concatenate([np.repeat(scene.stroke_rgba, 4, axis=0), np.repeat(scene.triangle_rgba, 3, axis=0)])
    qi = 4 * np.arange(m)[:, None]
    quad_tris = np.concatenate([qi + [0, 1, 2], qi + [0, 2, 3]])
    tri = 4 * m + 3 * np.arange(k)[:, None] + [0, 1, 2]
    triangles = np.concatenate([quad_tris.reshape(-1, 3), tri.reshape(-1, 3)]).astype(int)
    normals = np.tile([0.0, 0.0, 1.0], len(points))
    return {
        "type": "TriangleList",
        "points": points.ravel(),
        "colors": colors.ravel(),
        "triangles": triangles.ravel(),
        "normals": normals,
    }
