"""Render each robot of the zoo in the default maze (the images of the README's robot table).

    python examples/robot_gallery.py [--out docs/images/robots] [--size 320]

Each robot stands in the paper maze just below the cylinder at (55, 105), facing it (up), and is
drawn by pybullet's TinyRenderer (no display needed) from a camera behind and above it.
"""

from __future__ import annotations

import argparse
import math
from pathlib import Path

import imageio.v3 as iio
import numpy as np
import pybullet as pb

from bullet_maze import METRES_PER_UNIT, BulletMazeEnv, available_robots

ACTIONS = {"racecar": "native"}
"""Robots that cannot take the default compass actions."""


def render(robot: str, size: int) -> np.ndarray:
    """An RGB image of ``robot`` at (55, 70) in the paper maze, facing +y."""
    env = BulletMazeEnv(maze="paper", robot=robot, actions=ACTIONS.get(robot, "compass"))
    try:
        x, y = 55.0, 70.0
        env.reset(seed=0, options={"start": (x, y, math.pi / 2)})
        env.world.move_markers((-100.0, -100.0), env.goal)  # the start square out of the way
        env.world.park_probe()
        s = METRES_PER_UNIT
        view = pb.computeViewMatrixFromYawPitchRoll(
            cameraTargetPosition=[x * s, (y + 6.0) * s, 0.25],
            distance=2.6,
            yaw=20.0,
            pitch=-35.0,
            roll=0.0,
            upAxisIndex=2,
        )
        projection = pb.computeProjectionMatrixFOV(50.0, 1.0, 0.05, 100.0)
        _, _, rgba, _, _ = pb.getCameraImage(
            size,
            size,
            view,
            projection,
            renderer=pb.ER_TINY_RENDERER,
            physicsClientId=env.client_id,
        )
    finally:
        env.close()
    return np.asarray(rgba, dtype=np.uint8).reshape(size, size, 4)[..., :3]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", type=Path, default=Path("docs/images/robots"))
    parser.add_argument("--size", type=int, default=320)
    args = parser.parse_args()
    args.out.mkdir(parents=True, exist_ok=True)
    for robot in available_robots():
        path = args.out / f"{robot}.png"
        iio.imwrite(path, render(robot, args.size))
        print(path)


if __name__ == "__main__":
    main()
