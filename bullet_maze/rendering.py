"""Top-down images of the maze with pybullet's TinyRenderer (software, works with no display)."""

from __future__ import annotations

import math

import numpy as np
import pybullet as pb

from bullet_maze.params import BOUNDARY_THICKNESS, MAX_RENDER_SIDE, METRES_PER_UNIT, WALL_HEIGHT


class TopDownCamera:
    """A camera looking straight down on the arena from far above, +y up in the image.

    The image shows the arena and its walls; pixel (row, column) of maze point (x, y) is given by
    ``pixel``.
    """

    def __init__(self, arena: tuple[float, float], width: int = 256, height: int = 256) -> None:
        for name, side in (("render_width", width), ("render_height", height)):
            if isinstance(side, bool) or not isinstance(side, int):
                raise TypeError(f"{name} = {side!r}: must be an integer number of pixels")
            if side <= 0:
                raise ValueError(f"render size must be positive integers, got {name} = {side!r}")
            if side > MAX_RENDER_SIDE:
                raise ValueError(
                    f"{name} = {side} is larger than {MAX_RENDER_SIDE} pixels "
                    "(bullet_maze.params.MAX_RENDER_SIDE)"
                )
        self.width, self.height = width, height
        s = METRES_PER_UNIT
        margin = BOUNDARY_THICKNESS / 2
        self._lo = (-margin, -margin)
        self._hi = (arena[0] + margin, arena[1] + margin)
        cx, cy = arena[0] / 2 * s, arena[1] / 2 * s
        half = max(self._hi[0] - self._lo[0], self._hi[1] - self._lo[1]) / 2 * s
        # TinyRenderer needs a perspective projection: a narrow field of view from far above is
        # orthographic to within 1 % at the height of the walls.
        distance = 100.0 * WALL_HEIGHT * s
        self.view = pb.computeViewMatrix([cx, cy, distance], [cx, cy, 0.0], [0.0, 1.0, 0.0])
        fov = math.degrees(2.0 * math.atan(half / distance))
        self.projection = pb.computeProjectionMatrixFOV(
            fov, width / height, distance - 2.0 * WALL_HEIGHT * s, distance + 1.0
        )

    def pixel(self, x: float, y: float) -> tuple[int, int]:
        """(row, column) of the maze point (x, y) in the image."""
        u = (x - self._lo[0]) / (self._hi[0] - self._lo[0])
        v = (y - self._lo[1]) / (self._hi[1] - self._lo[1])
        column = min(self.width - 1, max(0, int(u * self.width)))
        row = min(self.height - 1, max(0, int((1.0 - v) * self.height)))
        return row, column

    def render(self, client: int) -> np.ndarray:
        """An RGB image, ``uint8`` of shape (height, width, 3)."""
        _, _, rgba, _, _ = pb.getCameraImage(
            self.width,
            self.height,
            self.view,
            self.projection,
            renderer=pb.ER_TINY_RENDERER,
            physicsClientId=client,
        )
        image = np.asarray(rgba, dtype=np.uint8).reshape(self.height, self.width, 4)
        return np.ascontiguousarray(image[..., :3])
