"""Reading a URDF before pybullet does: bounded, parsed, and prepared for loading.

pybullet's importer fails late and badly on hostile files (a 500-link URDF gives a raw
``pybullet.error``, a 2,000-link one can crash the process when the client closes), and it gives
every link without inertial data 1 kg and 1 kg m^2, which makes a robot with frame-only links
(sensor mounts, footprints) turn several times slower than its real inertia allows. So the file
is read here first, within bounds, and rewritten only where that helps:

* links without ``<inertial>`` get a near-zero mass (``FRAME_MASS``) when some other link has
  inertial data (a URDF without any keeps pybullet's defaults: it would otherwise weigh nothing);
* mesh references become the absolute paths pybullet would find from the original file
  (``mesh_file``), so that the rewritten text loads from anywhere.
"""

from __future__ import annotations

import contextlib
import math
import xml.etree.ElementTree as ET
from dataclasses import dataclass
from pathlib import Path

MAX_URDF_BYTES = 8 * 1024 * 1024
"""Largest URDF file read (8 MiB; pybullet_data's largest robot is under 200 KiB)."""

MAX_LINKS = 256
"""Most links a robot may have (humanoids have 30-70); checked before pybullet sees the file."""

FRAME_MASS = 0.01
"""kg given to a link without inertial data (a frame, a sensor mount) when others have some."""

JOINT_TYPES = ("fixed", "continuous", "revolute", "prismatic", "floating", "planar", "spherical")
"""URDF joint types, and pybullet's ``spherical`` extension (pybullet_data's humanoid uses it)."""


@dataclass(frozen=True)
class UrdfJoint:
    """One ``<joint>`` as written in the file."""

    name: str
    type: str
    parent: str
    child: str


@dataclass(frozen=True)
class UrdfModel:
    """What the env needs from a URDF file before loading it."""

    path: Path
    name: str
    links: tuple[str, ...]
    joints: tuple[UrdfJoint, ...]
    text: str | None
    """The rewritten URDF to load instead of the file, or None to load the file itself."""
    round_links: dict[str, float]
    """Radius (metres, the file's scale) of each link whose first collision shape is a cylinder
    or a sphere: a wheel's radius, exactly (pybullet loads cylinders as meshes)."""
    meshes: tuple[tuple[str, Path], ...] = ()
    """Each mesh file the URDF names and pybullet will find (:func:`mesh_path`): the name as
    written, and the file. A mesh found nowhere is left out (pybullet reports it on load)."""

    @property
    def has_fixed_joints(self) -> bool:
        """Whether pybullet may merge some links into their parents."""
        return any(joint.type == "fixed" for joint in self.joints)

    def joint(self, name: str) -> UrdfJoint | None:
        """The joint called ``name``, if there is one."""
        return next((joint for joint in self.joints if joint.name == name), None)


def read_urdf(path: Path) -> UrdfModel:
    """Parse and check a URDF file; a ``FileNotFoundError`` or ``ValueError`` naming the path."""
    if not path.is_file():
        raise FileNotFoundError(f"robot URDF not found: {path}")
    size = path.stat().st_size
    if size > MAX_URDF_BYTES:
        raise ValueError(
            f"robot URDF {path} is {size:,} bytes; at most {MAX_URDF_BYTES:,} are read"
        )
    # pybullet's own parser ignores blank lines before the XML declaration and NUL bytes after
    # the document; some of its shipped URDFs have them (pybullet_data's biped2d_pybullet.urdf,
    # humanoid.urdf), so they are read here too.
    data = path.read_bytes().lstrip(b" \t\r\n").rstrip(b"\x00 \t\r\n")
    try:
        root = ET.fromstring(data)
    except ET.ParseError as err:
        raise ValueError(f"robot URDF {path} is not well-formed XML: {err}") from None
    if root.tag != "robot":
        raise ValueError(f"robot URDF {path}: the root element is <{root.tag}>, not <robot>")
    links = root.findall("link")
    if not links:
        raise ValueError(f"robot URDF {path} has no <link>")
    if len(links) > MAX_LINKS:
        raise ValueError(
            f"robot URDF {path} has {len(links)} links; at most {MAX_LINKS} are supported"
        )
    names = [link.get("name", "") for link in links]
    if "" in names or len(set(names)) != len(names):
        raise ValueError(f"robot URDF {path}: every <link> needs a unique name")
    joints = []
    for element in root.findall("joint"):
        parent, child = element.find("parent"), element.find("child")
        joint = UrdfJoint(
            name=element.get("name", ""),
            type=element.get("type", ""),
            parent="" if parent is None else parent.get("link", ""),
            child="" if child is None else child.get("link", ""),
        )
        if not joint.name or joint.type not in JOINT_TYPES:
            raise ValueError(
                f"robot URDF {path}: joint {joint.name!r} has type {joint.type!r}; "
                f"URDF joint types are {list(JOINT_TYPES)}"
            )
        if joint.parent not in names or joint.child not in names:
            raise ValueError(
                f"robot URDF {path}: joint {joint.name!r} connects {joint.parent!r} to "
                f"{joint.child!r}, which are not both links of the file"
            )
        joints.append(joint)
    _check_numbers(root, path)
    round_links = {}
    for link in links:
        shape = link.find("collision/geometry/*")
        if shape is not None and shape.tag in ("cylinder", "sphere"):
            with contextlib.suppress(ValueError):
                round_links[link.get("name", "")] = float(shape.get("radius", "nan"))
    meshes = tuple(  # (before _rewritten, which makes some of the names absolute)
        (name, found)
        for name in dict.fromkeys(m.get("filename", "") for m in root.iter("mesh"))
        if (found := mesh_path(name, path)) is not None
    )
    return UrdfModel(
        path=path,
        name=root.get("name", path.stem),
        links=tuple(names),
        joints=tuple(joints),
        text=_rewritten(root, path),
        round_links={k: v for k, v in round_links.items() if math.isfinite(v) and v > 0},
        meshes=meshes,
    )


def _check_numbers(root: ET.Element, path: Path) -> None:
    """Every mass, inertia, origin and size in the file is a finite number (pybullet would read
    ``nan`` or garbage silently)."""
    numeric = {
        "mass": ("value",),
        "inertia": ("ixx", "ixy", "ixz", "iyy", "iyz", "izz"),
        "origin": ("xyz", "rpy"),
        "box": ("size",),
        "cylinder": ("radius", "length"),
        "sphere": ("radius",),
        "mesh": ("scale",),
        "axis": ("xyz",),
        "limit": ("lower", "upper", "effort", "velocity"),
    }
    for tag, attributes in numeric.items():
        for element in root.iter(tag):
            for attribute in attributes:
                text = element.get(attribute)
                if text is None:
                    continue
                # Text that is no number (xacro left-overs such as husky.urdf's
                # "$(optenv ...)") is pybullet's to judge; a number must be finite.
                for token in text.split():
                    try:
                        value = float(token)
                    except ValueError:
                        continue
                    if not math.isfinite(value):
                        raise ValueError(
                            f"robot URDF {path}: <{tag} {attribute}={text!r}> is not finite"
                        )
    for mass in root.iter("mass"):
        negative = False
        with contextlib.suppress(ValueError):
            negative = float(mass.get("value", "0")) < 0.0
        if negative:
            raise ValueError(f"robot URDF {path}: a <mass> is negative ({mass.get('value')})")


def _rewritten(root: ET.Element, path: Path) -> str | None:
    """The URDF text to load in place of the file, or None if the file loads as it is."""
    changed = False
    links = root.findall("link")
    if any(link.find("inertial") is not None for link in links):
        for link in links:
            if link.find("inertial") is None:
                inertial = ET.SubElement(link, "inertial")
                ET.SubElement(inertial, "mass", value=repr(FRAME_MASS))
                moment = repr(FRAME_MASS * 1e-3)
                ET.SubElement(
                    inertial,
                    "inertia",
                    ixx=moment,
                    ixy="0",
                    ixz="0",
                    iyy=moment,
                    iyz="0",
                    izz=moment,
                )
                changed = True
    for mesh in root.iter("mesh"):
        found = mesh_file(mesh.get("filename", ""), path)
        if found is not None:
            mesh.set("filename", found)
            changed = True
    return ET.tostring(root, encoding="unicode") if changed else None


def mesh_file(filename: str, urdf: Path) -> str | None:
    """The absolute path of the mesh ``filename`` named in the URDF at ``urdf``, found by
    pybullet's own rule, when a copy of the URDF elsewhere would not find it; None otherwise.

    pybullet drops a leading ``package://`` or ``model://``, tries the name as it stands (from
    the working directory), then beside the URDF and in each folder above it (bullet3's
    ``UrdfFindMeshFile``). A copy loaded from a temporary folder would search above that folder
    instead, so such a mesh (pybullet_data's ``xarm`` meshes under ``package://``, the
    ``racecar_differential`` meshes two folders up) is named by its absolute path. A mesh found
    nowhere is left for pybullet to report."""
    for prefix in ("package://", "model://"):
        if filename.startswith(prefix):
            filename = filename[len(prefix) :]
            break
    else:
        if "://" in filename:
            return None
    if not filename or Path(filename).is_absolute() or _is_file(Path(filename)):
        return None
    folder = urdf.resolve().parent
    for place in (folder, *folder.parents):
        if _is_file(place / filename):
            return str(place / filename)
    return None


def mesh_path(filename: str, urdf: Path) -> Path | None:
    """The file pybullet loads for the mesh ``filename`` named in the URDF at ``urdf`` (by the
    rule of :func:`mesh_file`: as it stands, else beside the URDF or in a folder above), or None
    when there is none."""
    found = mesh_file(filename, urdf)
    if found is not None:
        return Path(found)
    for prefix in ("package://", "model://"):
        filename = filename.removeprefix(prefix)
    return Path(filename).resolve() if filename and _is_file(Path(filename)) else None


def _is_file(path: Path) -> bool:
    """``path.is_file()``, False where the name itself is unusable (too long, say)."""
    try:
        return path.is_file()
    except (OSError, ValueError):
        return False
