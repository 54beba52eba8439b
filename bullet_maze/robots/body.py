"""A robot's pybullet body: loaded from its URDF, scaled to its footprint, and measured.

A robot's size in the maze is the radius of its footprint: the largest horizontal distance from
its base to its collision geometry, measured with pybullet rays when it is loaded. Kinematic
collision checks and the planner use a disc of that radius.

Links on fixed joints are merged into their parents when the body is loaded
(``URDF_MERGE_FIXED_LINKS``): the husky keeps its base and four wheels instead of ten links,
and each physics step is about a quarter cheaper with the same contacts.
"""

from __future__ import annotations

import ctypes
import math
import os
import sys
import tempfile
from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import pybullet as pb

from bullet_maze.params import METRES_PER_UNIT
from bullet_maze.robots.urdf import UrdfModel

_RAY_ANGLES = 120
_RAY_HEIGHTS = 8


@contextmanager
def native_output_captured() -> Iterator[list[str]]:
    """Capture what C code writes to the process's stdout and stderr (pybullet's URDF importer
    warns there about every link without inertial data and reports every merged link, once per
    load, and explains its failures there). The list receives the text when the block ends."""
    captured: list[str] = []
    try:
        libc = ctypes.CDLL(None)  # the C library already loaded (not available on Windows)
        sys.stdout.flush()
        sys.stderr.flush()
        saved = [os.dup(1), os.dup(2)]
    except (AttributeError, OSError, TypeError, ValueError):  # no C library or no real fds
        yield captured
        return
    with tempfile.TemporaryFile() as sink:
        try:
            os.dup2(sink.fileno(), 1)
            os.dup2(sink.fileno(), 2)
            yield captured
        finally:
            libc.fflush(None)
            os.dup2(saved[0], 1)
            os.dup2(saved[1], 2)
            for fd in saved:
                os.close(fd)
            sink.seek(0)
            captured.append(sink.read().decode(errors="replace"))


def load_urdf(client: int, model: UrdfModel, scale: float = 1.0) -> int:
    """Load a checked URDF at the origin; a clear error naming the path instead of a pybullet
    one."""
    flags = pb.URDF_MERGE_FIXED_LINKS if model.has_fixed_joints else 0
    # package:// and other mesh references are looked up beside the original file.
    pb.setAdditionalSearchPath(str(model.path.parent), physicsClientId=client)
    with tempfile.TemporaryDirectory() as folder, native_output_captured() as output:
        path = model.path
        if model.text is not None:
            path = Path(folder) / model.path.name
            path.write_text(model.text)
        try:
            body = pb.loadURDF(
                str(path), [0.0, 0.0, 0.0], globalScaling=scale, flags=flags, physicsClientId=client
            )
        except pb.error as err:
            failure: pb.error | None = err
        else:
            failure = None
    if failure is not None:
        detail = " ".join("".join(output).split())[-300:]
        raise ValueError(
            f"robot URDF {model.path} could not be loaded by pybullet: {failure}"
            + (f" ({detail})" if detail else "")
        ) from failure
    return body


def footprint(client: int, body: int) -> tuple[float, float]:
    """(radius, lowest z) of a body at rest at the origin, in metres.

    The radius is the largest horizontal distance from the base to the body's collision geometry,
    found by casting rays inwards at every angle and height; call it before anything else stands
    near the body.
    """
    lows, highs = [], []
    for link in range(-1, pb.getNumJoints(body, physicsClientId=client)):
        low, high = pb.getAABB(body, link, physicsClientId=client)
        lows.append(low)
        highs.append(high)
    low, high = np.min(lows, axis=0), np.max(highs, axis=0)
    base = np.array(pb.getBasePositionAndOrientation(body, physicsClientId=client)[0])
    reach = 2.0 * float(np.max(np.abs(np.r_[low[:2], high[:2]] - np.r_[base[:2], base[:2]])))
    angles = np.linspace(0.0, 2.0 * math.pi, _RAY_ANGLES, endpoint=False)
    heights = np.linspace(low[2], high[2], _RAY_HEIGHTS + 2)[1:-1]
    a, z = np.meshgrid(angles, heights)
    starts = np.stack([base[0] + reach * np.cos(a), base[1] + reach * np.sin(a), z], -1)
    ends = np.stack([np.full_like(a, base[0]), np.full_like(a, base[1]), z], -1)
    hits = pb.rayTestBatch(
        starts.reshape(-1, 3).tolist(), ends.reshape(-1, 3).tolist(), physicsClientId=client
    )
    radii = [math.hypot(hit[3][0] - base[0], hit[3][1] - base[1]) for hit in hits if hit[0] == body]
    if not radii:
        raise ValueError("robot has no collision geometry to measure its footprint")
    return max(radii), float(low[2])


@dataclass(frozen=True)
class JointInfo:
    """A movable joint of the loaded body, measured at rest at the origin facing +x."""

    index: int
    name: str
    type: int
    """pybullet's joint type (``JOINT_REVOLUTE``, ``JOINT_PRISMATIC``, ...)."""
    lower: float
    upper: float
    """Position limits (upper < lower for a continuous joint)."""
    axis: tuple[float, float, float]
    """Joint axis in the base frame."""
    position: tuple[float, float, float]
    """Link frame origin in the base frame, metres."""
    extent: tuple[float, float, float]
    """Size of the link's collision box (axis-aligned, metres)."""
    mass: float
    parent: int
    """Index of the parent link (-1: the base)."""

    @property
    def continuous(self) -> bool:
        """A revolute joint without limits (pybullet reports upper < lower)."""
        return self.type == pb.JOINT_REVOLUTE and self.upper < self.lower


class Body:
    """A URDF in one client, rescaled so that its footprint has ``radius`` maze units if given
    (else at its own size); see the module docstring."""

    def __init__(self, client: int, model: UrdfModel, radius: float | None) -> None:
        self.client = client
        self.model = model
        body = load_urdf(client, model)
        try:
            natural, low = footprint(client, body)
        except ValueError as err:
            pb.removeBody(body, physicsClientId=client)
            raise ValueError(f"robot URDF {model.path}: {err}") from err
        scale = 1.0 if radius is None else radius * METRES_PER_UNIT / natural
        if scale != 1.0:
            pb.removeBody(body, physicsClientId=client)
            body = load_urdf(client, model, scale)
        self.id = body
        self.scale = scale
        """globalScaling applied to the URDF."""
        self.radius = natural * scale / METRES_PER_UNIT
        """Footprint radius in maze units."""
        base_z = pb.getBasePositionAndOrientation(body, physicsClientId=client)[0][2]
        self.rest_z = base_z - low * scale
        """Base height (metres) at which the body's lowest point touches the floor."""
        self.mass = pb.getDynamicsInfo(body, -1, physicsClientId=client)[0]
        """Mass of the base link (kg) after merging fixed links; 0 makes it static."""
        self.joints = self._measure_joints()
        """Movable joints by name (fixed ones are merged away)."""
        self.indices = tuple(joint.index for joint in self.joints.values())

    def _measure_joints(self) -> dict[str, JointInfo]:
        client, body = self.client, self.id
        base, orientation = pb.getBasePositionAndOrientation(body, physicsClientId=client)
        inverse = np.array(pb.getMatrixFromQuaternion(orientation)).reshape(3, 3).T
        joints = {}
        for index in range(pb.getNumJoints(body, physicsClientId=client)):
            info = pb.getJointInfo(body, index, physicsClientId=client)
            if info[2] == pb.JOINT_FIXED:
                continue
            state = pb.getLinkState(
                body, index, computeForwardKinematics=True, physicsClientId=client
            )
            frame = np.array(pb.getMatrixFromQuaternion(state[5])).reshape(3, 3)
            axis = inverse @ frame @ np.array(info[13])
            position = inverse @ (np.array(state[4]) - np.array(base))
            low, high = pb.getAABB(body, index, physicsClientId=client)
            joints[info[1].decode()] = JointInfo(
                index=index,
                name=info[1].decode(),
                type=info[2],
                lower=info[8],
                upper=info[9],
                axis=(float(axis[0]), float(axis[1]), float(axis[2])),
                position=(float(position[0]), float(position[1]), float(position[2])),
                extent=(high[0] - low[0], high[1] - low[1], high[2] - low[2]),
                mass=pb.getDynamicsInfo(body, index, physicsClientId=client)[0],
                parent=info[16],
            )
        return joints

    def joint(self, name: str, field: str, source: str) -> JointInfo:
        """The movable joint ``name``, or a ValueError naming the robot file's field."""
        if name not in self.joints:
            fixed = self.model.joint(name)
            why = (
                "it is a fixed joint"
                if fixed is not None and fixed.type == "fixed"
                else "the URDF has no such joint"
            )
            raise ValueError(
                f"{source}: field '{field}': joint {name!r} cannot be driven ({why}); the "
                f"movable joints of {self.model.path.name} are {sorted(self.joints)}"
            )
        return self.joints[name]
