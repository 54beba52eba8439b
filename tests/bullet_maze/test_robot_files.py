"""Robot files and bare URDFs: validation (every error names the file and the field), drive
detection, and adversarial inputs kept as cases with their outcomes."""

from __future__ import annotations

import logging
import math
from collections.abc import Callable
from pathlib import Path

import pybullet_data
import pytest

from bullet_maze import BulletMazeEnv, load_robot_spec
from bullet_maze.robots import MAX_LINKS, resolve_robot
from bullet_maze.robots.drives import DEFAULT_BRAKING
from bullet_maze.robots.urdf import mesh_file, read_urdf

DATA = Path(pybullet_data.getDataPath())

INERTIA = '<inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/>'


def _wheel(name: str, y: float, mass: float = 0.5) -> str:
    return f"""
  <link name="{name}">
    <inertial><mass value="{mass}"/>{INERTIA}</inertial>
    <collision><origin rpy="1.5708 0 0"/><geometry><cylinder radius="0.1" length="0.04"/>
    </geometry></collision>
  </link>
  <joint name="{name}_joint" type="continuous">
    <parent link="base"/><child link="{name}"/><origin xyz="0 {y} 0"/><axis xyz="0 1 0"/>
  </joint>"""


def cart_urdf(base_mass: float = 5.0, wheel_mass: float = 0.5, extra: str = "") -> str:
    """A box on two wheels (a differential robot) with a fixed mast."""
    return f"""<?xml version="1.0"?>
<robot name="cart">
  <link name="base">
    <inertial><mass value="{base_mass}"/>{INERTIA}</inertial>
    <collision><origin xyz="0 0 0.05"/><geometry><box size="0.5 0.4 0.1"/></geometry>
    </collision>
  </link>
  {_wheel("left", 0.25, wheel_mass)}
  {_wheel("right", -0.25, wheel_mass)}
  <link name="mast"><visual><geometry><box size="0.02 0.02 0.3"/></geometry></visual></link>
  <joint name="mast_joint" type="fixed"><parent link="base"/><child link="mast"/>
    <origin xyz="0 0 0.2"/></joint>
  {extra}
</robot>
"""


ROBOT_FILE = """
urdf = "cart.urdf"
drive = "differential"
[wheels]
left = ["left_joint"]
right = ["right_joint"]
[limits]
max_wheel_speed = 10.0
"""


@pytest.fixture
def write(tmp_path: Path) -> Callable[[str, str], Path]:
    def write(name: str, text: str) -> Path:
        path = tmp_path / name
        path.write_text(text)
        return path

    return write


def test_a_robot_file_is_read(write: Callable[[str, str], Path]) -> None:
    write("cart.urdf", cart_urdf())
    path = write("cart.toml", ROBOT_FILE)
    spec = load_robot_spec(path)
    assert spec.name == "cart"
    assert spec.drive == "differential"
    assert spec.left == ("left_joint",)
    assert spec.urdf == path.parent / "cart.urdf"
    env = BulletMazeEnv(maze="open", robot=str(path), mode="dynamic", actions="native")
    try:
        assert env.robot.drive.kind == "differential"
        assert env.robot.drive.wheel_radius == pytest.approx(0.1, rel=0.01)  # measured
        assert env.robot.drive.track == pytest.approx(0.5, rel=0.01)
        assert env.observation_space.shape == (3,)
        assert env.robot.drive.limits.braking == DEFAULT_BRAKING  # the file does not say
    finally:
        env.close()
    path = write("braked.toml", ROBOT_FILE + "braking = 9.5\n")
    assert load_robot_spec(path).braking == 9.5
    env = BulletMazeEnv(maze="open", robot=str(path), mode="dynamic")
    try:
        assert env.robot.drive.limits.braking == 9.5
    finally:
        env.close()


@pytest.mark.parametrize(
    ("text", "error", "message"),
    [
        ('colour = "red"\n' + ROBOT_FILE, ValueError, r"unknown key\(s\) \['colour'\] at top"),
        (ROBOT_FILE + "speed = 3\n", ValueError, r"unknown key\(s\) \['speed'\] at \[limits\]"),
        (ROBOT_FILE.replace('"differential"', '"tank"'), ValueError, r"'drive' must be one of"),
        (ROBOT_FILE.replace('drive = "differential"', ""), ValueError, r"'drive' is required"),
        (ROBOT_FILE.replace('"cart.urdf"', "3"), TypeError, r"'urdf' must be a string"),
        (ROBOT_FILE.replace('["left_joint"]', '"left_joint"'), TypeError, r"'wheels.left' must"),
        (ROBOT_FILE.replace('["left_joint"]', "[1]"), TypeError, r"'wheels.left' must"),
        (ROBOT_FILE.replace('["left_joint"]', "[]"), ValueError, r"'wheels.left' must name"),
        (ROBOT_FILE.replace('left = ["left_joint"]', ""), ValueError, r"'wheels.left' is requ"),
        (
            ROBOT_FILE.replace('["left_joint"]', '["right_joint"]'),
            ValueError,
            r"\['right_joint'\] named in more than one list",
        ),
        (
            ROBOT_FILE.replace('["left_joint"]', '["left_joint", "left_joint"]'),
            ValueError,
            r"names a joint twice",
        ),
        (ROBOT_FILE.replace("10.0", "nan"), ValueError, r"'limits.max_wheel_speed' must be fin"),
        (ROBOT_FILE.replace("10.0", "inf"), ValueError, r"'limits.max_wheel_speed' must be fin"),
        (ROBOT_FILE.replace("10.0", "-10.0"), ValueError, r"max_wheel_speed' must be positive"),
        (ROBOT_FILE.replace("10.0", "true"), TypeError, r"max_wheel_speed' must be a number"),
        (ROBOT_FILE.replace("10.0", '"fast"'), TypeError, r"max_wheel_speed' must be a number"),
        (ROBOT_FILE + "max_steering = 0.5\n", ValueError, r"only an ackermann drive steers"),
        (ROBOT_FILE + "braking = 0\n", ValueError, r"'limits.braking' must be positive"),
        (ROBOT_FILE + "braking = 51\n", ValueError, r"'limits.braking' must be at most 50"),
        (ROBOT_FILE + "braking = nan\n", ValueError, r"'limits.braking' must be finite"),
        (ROBOT_FILE + 'braking = "hard"\n', TypeError, r"'limits.braking' must be a number"),
        (
            'urdf = "cart.urdf"\ndrive = "ackermann"\n[wheels]\ndriven = ["left_joint"]\n'
            'steering = ["right_joint"]\n[limits]\nbraking = 9.0\n',
            ValueError,
            r"limits.braking: only a differential drive has one",
        ),
        (
            ROBOT_FILE.replace('"differential"', '"holonomic"'),
            ValueError,
            r"\[wheels\]: a holonomic robot",
        ),
        (ROBOT_FILE + "[footprint]\nradius = -1\n", ValueError, r"'footprint.radius' must be p"),
        (ROBOT_FILE + "[footprint]\nradius = true\n", TypeError, r"'footprint.radius' must be"),
        (ROBOT_FILE + '[footprint]\nradius = "big"\n', TypeError, r"'footprint.radius' must"),
        (ROBOT_FILE + "[sensors]\nlidar_rays = 0\n", ValueError, r"'sensors.lidar_rays' must"),
        (ROBOT_FILE + "[sensors]\nlidar_rays = 1.5\n", TypeError, r"'sensors.lidar_rays' must"),
        (ROBOT_FILE + "[sensors]\nlidar_rays = true\n", TypeError, r"'sensors.lidar_rays' must"),
        (ROBOT_FILE + "[sensors]\nlidar_range = nan\n", ValueError, r"'sensors.lidar_range' mu"),
        ("wheels = 3\n" + ROBOT_FILE.split("[wheels]")[0], TypeError, r"'wheels' must be a tab"),
        (
            ROBOT_FILE + "[physics]\ntime_step = 0.1\n",
            ValueError,
            r"'physics.time_step' must be in",
        ),
        (ROBOT_FILE + "[physics]\ntime_step = 1e-5\n", ValueError, r"'physics.time_step' must b"),
        (ROBOT_FILE + "[physics]\ntime_step = -0.01\n", ValueError, r"time_step' must be posit"),
        (ROBOT_FILE + "[physics]\ntime_step = nan\n", ValueError, r"'physics.time_step' must be"),
        (ROBOT_FILE + '[physics]\ntime_step = "60 Hz"\n', TypeError, r"time_step' must be a num"),
        (ROBOT_FILE + "[physics]\nsolver_iterations = 0\n", ValueError, r"solver_iterations' mu"),
        (ROBOT_FILE + "[physics]\nsolver_iterations = 101\n", ValueError, r"in \[1, 100\]"),
        (ROBOT_FILE + "[physics]\nsolver_iterations = 5.0\n", TypeError, r"must be an integer"),
        (ROBOT_FILE + "[physics]\nsubsteps = 2\n", ValueError, r"\['substeps'\] at \[physics\]"),
        (ROBOT_FILE + "[physics]\ncompass = 3\n", TypeError, r"'physics.compass' must be a tab"),
        (
            ROBOT_FILE + "[physics.compass]\ntime_step = 1.0\n",
            ValueError,
            r"'physics.compass.time_step' must be in \[0.0005, 0.0333333\]",
        ),
        (
            ROBOT_FILE + "[physics.native]\nsolver_iterations = true\n",
            TypeError,
            r"'physics.native.solver_iterations' must be an integer",
        ),
        (
            ROBOT_FILE + "[physics.compass]\ncompass = {}\n",
            ValueError,
            r"unknown key\(s\) \['compass'\] at \[physics.compass\]",
        ),
        (
            ROBOT_FILE + "[physics.walk]\ntime_step = 0.01\n",
            ValueError,
            r"unknown key\(s\) \['walk'\] at \[physics\]",
        ),
        ('name = ""\n' + ROBOT_FILE, ValueError, r"'name' must not be empty"),
        ("name = 7\n" + ROBOT_FILE, TypeError, r"'name' must be a string"),
        ("urdf = [", ValueError, r"not valid TOML"),
        ("a = " + "[" * 2000 + "]" * 2000, ValueError, r"nested too deeply|not valid TOML"),
    ],
)
def test_robot_file_errors_name_the_file_and_the_field(
    write: Callable[[str, str], Path], text: str, error: type[Exception], message: str
) -> None:
    write("cart.urdf", cart_urdf())
    path = write("bad.toml", text)
    with pytest.raises(error, match=message) as caught:
        load_robot_spec(path)
    assert "bad.toml" in str(caught.value)


def test_a_robot_files_physics_enter_its_dynamic_envs(write: Callable[[str, str], Path]) -> None:
    write("cart.urdf", cart_urdf())
    text = ROBOT_FILE + "[physics]\nsolver_iterations = 20\n[physics.native]\ntime_step = 0.01\n"
    path = write("cart.toml", text)
    spec = load_robot_spec(path)
    assert spec.physics_defaults("native") == {"solver_iterations": 20, "time_step": 0.01}
    assert spec.physics_defaults("compass") == {"solver_iterations": 20}
    env = BulletMazeEnv(maze="open", robot=str(path), mode="dynamic", actions="native")
    try:
        assert (env.physics.time_step, env.physics.solver_iterations) == (0.01, 20)
        env.reset(seed=0)
        env.step(0)  # a native command of 0.1 s: 10 physics steps of 0.01 s
    finally:
        env.close()


def test_robot_file_bytes_and_size_are_checked(tmp_path: Path) -> None:
    binary = tmp_path / "binary.toml"
    binary.write_bytes(b'urdf = "\xff\xfe"\n')
    with pytest.raises(ValueError, match=r"binary\.toml: not UTF-8"):
        load_robot_spec(binary)
    huge = tmp_path / "huge.toml"
    huge.write_text("# " + "x" * 70_000 + "\n")
    with pytest.raises(ValueError, match=r"huge\.toml: .* at most 64 KiB"):
        load_robot_spec(huge)
    with pytest.raises(FileNotFoundError, match=r"ghost\.toml"):
        load_robot_spec(tmp_path / "ghost.toml")


@pytest.mark.parametrize(
    ("change", "message"),
    [
        (('["left_joint"]', '["nope"]'), r"'wheels.left': joint 'nope' cannot be driven \(the "),
        (('["left_joint"]', '["mast_joint"]'), r"joint 'mast_joint' .*it is a fixed joint"),
    ],
)
def test_missing_or_fixed_joints_name_the_field(
    write: Callable[[str, str], Path], change: tuple[str, str], message: str
) -> None:
    write("cart.urdf", cart_urdf())
    path = write("cart.toml", ROBOT_FILE.replace(*change))
    with pytest.raises(ValueError, match=message) as caught:
        BulletMazeEnv(maze="open", robot=str(path))
    assert "cart.toml" in str(caught.value)
    assert "['left_joint', 'right_joint']" in str(caught.value)  # the movable joints


def test_a_steering_hinge_must_be_vertical(write: Callable[[str, str], Path]) -> None:
    write("cart.urdf", cart_urdf())
    text = """
urdf = "cart.urdf"
drive = "ackermann"
[wheels]
driven = ["left_joint"]
steering = ["right_joint"]
[limits]
max_steering = 0.5
"""
    with pytest.raises(ValueError, match=r"'wheels.steering': joint 'right_joint' is not a steer"):
        BulletMazeEnv(maze="open", robot=str(write("car.toml", text)), actions="native")


def test_a_base_of_mass_zero_cannot_drive_in_dynamic_mode(
    write: Callable[[str, str], Path],
) -> None:
    # Today's bug: a static base was teleported by velocity commands, through a cylinder.
    urdf = write("static.urdf", cart_urdf(base_mass=0.0))
    with pytest.raises(ValueError, match=r"static\.urdf: its base link has mass 0.*kinematic"):
        BulletMazeEnv(robot=str(urdf), mode="dynamic")
    BulletMazeEnv(robot=str(urdf), mode="kinematic").close()  # kinematic mode never asks physics
    write("cart.urdf", cart_urdf(wheel_mass=0.0))
    toml = write("cart.toml", ROBOT_FILE)
    with pytest.raises(ValueError, match=r"cart\.toml: wheel joint 'left_joint' moves a link of"):
        BulletMazeEnv(robot=str(toml), mode="dynamic", actions="native")


def _chain(links: int) -> str:
    body = [f'<link name="l0"><inertial><mass value="1"/>{INERTIA}</inertial></link>']
    for i in range(1, links):
        body.append(f'<link name="l{i}"><inertial><mass value="1"/>{INERTIA}</inertial></link>')
        body.append(
            f'<joint name="j{i}" type="revolute"><parent link="l{i - 1}"/><child link="l{i}"/>'
            f'<limit lower="-1" upper="1" effort="1" velocity="1"/></joint>'
        )
    return '<?xml version="1.0"?>\n<robot name="chain">\n' + "\n".join(body) + "\n</robot>\n"


@pytest.mark.parametrize(
    ("text", "message"),
    [
        (_chain(500), rf"500 links; at most {MAX_LINKS}"),
        (_chain(2000), rf"2000 links; at most {MAX_LINKS}"),
        ("not xml <<<", r"not well-formed XML"),
        ("<sdf><model/></sdf>", r"the root element is <sdf>"),
        ('<robot name="r"/>', r"has no <link>"),
        ('<robot name="r"><link name="a"/><link name="a"/></robot>', r"unique name"),
        (
            '<robot name="r"><link name="a"/><joint name="j" type="hinge"><parent link="a"/>'
            '<child link="a"/></joint></robot>',
            r"joint 'j' has type 'hinge'",
        ),
        (
            '<robot name="r"><link name="a"/><joint name="j" type="fixed"><parent link="a"/>'
            '<child link="b"/></joint></robot>',
            r"which are not both links",
        ),
        (cart_urdf().replace('<mass value="5.0"/>', '<mass value="nan"/>'), r"not finite"),
        (cart_urdf().replace('<mass value="5.0"/>', '<mass value="-5"/>'), r"mass> is negative"),
        (cart_urdf().replace('xyz="0 0.25 0"', 'xyz="0 inf 0"'), r"<origin xyz='0 inf 0'>"),
    ],
    ids=[
        "500-links",
        "2000-links",
        "garbage",
        "sdf",
        "no-link",
        "twin-links",
        "bad-type",
        "dangling",
        "nan-mass",
        "negative-mass",
        "inf-origin",
    ],
)
def test_hostile_urdfs_are_refused_before_pybullet_loads_them(
    write: Callable[[str, str], Path], text: str, message: str
) -> None:
    path = write("hostile.urdf", text)
    with pytest.raises(ValueError, match=message) as caught:
        BulletMazeEnv(robot=str(path))
    assert "hostile.urdf" in str(caught.value)


def test_what_pybullet_accepts_is_read(write: Callable[[str, str], Path]) -> None:
    # pybullet ignores NUL bytes after the document (pybullet_data's humanoid.urdf ends with
    # one) and loads its own ``spherical`` joint type; both reach the env as they reach pybullet.
    humanoid = read_urdf(DATA / "humanoid" / "humanoid.urdf")
    assert humanoid.joint("chest") is not None
    assert humanoid.joint("chest").type == "spherical"  # type: ignore[union-attr]
    path = write("padded.urdf", cart_urdf() + "\x00\x00\n")
    env = BulletMazeEnv(maze="open", robot=str(path), mode="dynamic")
    try:
        assert env.robot.drive.kind == "differential"
        env.reset(seed=0)
        env.step(0)
    finally:
        env.close()


@pytest.mark.parametrize(
    "urdf",
    [
        "xarm/xarm6_robot.urdf",  # package:// meshes, and links without inertia (rewritten)
        "racecar/racecar_differential.urdf",  # meshes named from two folders up
        "biped/biped2d_pybullet.urdf",  # blank lines before the XML declaration
    ],
)
def test_pybullet_data_urdfs_that_pybullet_loads_load_here(urdf: str) -> None:
    env = BulletMazeEnv(maze="open", robot=str(DATA / urdf))
    try:
        env.reset(seed=0)
        env.step(0)
    finally:
        env.close()


def test_a_rewritten_urdf_finds_its_meshes_where_pybullet_would(tmp_path: Path) -> None:
    mesh = tmp_path / "shared" / "block.obj"
    mesh.parent.mkdir()
    mesh.write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")
    urdf = tmp_path / "robots" / "arm" / "arm.urdf"
    urdf.parent.mkdir(parents=True)
    assert mesh_file("shared/block.obj", urdf) == str(mesh)  # two folders up
    assert mesh_file("package://shared/block.obj", urdf) == str(mesh)
    assert mesh_file("model://shared/block.obj", urdf) == str(mesh)
    assert mesh_file(str(mesh), urdf) is None  # already absolute
    assert mesh_file("shared/missing.obj", urdf) is None  # left for pybullet to report
    assert mesh_file("http://example.org/block.obj", urdf) is None
    assert mesh_file("a" * 5000 + ".obj", urdf) is None  # a name too long for the system
    assert mesh_file("package://" + "b/" * 3000 + "c.obj", urdf) is None


def test_a_mesh_name_too_long_for_the_system_is_pybullets_to_refuse(
    write: Callable[[str, str], Path],
) -> None:
    mesh = f'<visual><geometry><mesh filename="{"a" * 5000}.obj"/></geometry></visual>'
    extra = (  # a frame link without inertia makes the file be rewritten, meshes and all
        f'<link name="frame">{mesh}</link>'
        '<joint name="frame_joint" type="fixed"><parent link="base"/><child link="frame"/>'
        "</joint>"
    )
    path = write("long.urdf", cart_urdf(extra=extra))
    with pytest.raises(ValueError, match=r"long\.urdf could not be loaded by pybullet"):
        BulletMazeEnv(maze="open", robot=str(path))


def test_an_oversized_urdf_is_not_read(tmp_path: Path) -> None:
    path = tmp_path / "big.urdf"
    with path.open("w") as file:
        file.write('<robot name="big"><link name="a"/>')
        file.write("<!--" + "x" * (9 * 1024 * 1024) + "-->")
        file.write("</robot>")
    with pytest.raises(ValueError, match=r"big\.urdf is .* bytes; at most"):
        BulletMazeEnv(robot=str(path))


def test_unknown_robots_list_the_choices() -> None:
    with pytest.raises(ValueError, match=r"unknown robot 'tank'.*'disc'.*'husky'.*'racecar'"):
        resolve_robot("tank")
    with pytest.raises(TypeError, match=r"robot must be"):
        resolve_robot(3)  # type: ignore[arg-type]
    with pytest.raises(FileNotFoundError, match=r"nowhere\.toml"):
        resolve_robot("/nowhere.toml")


@pytest.mark.parametrize(
    ("urdf", "drive", "wheels"),
    [
        ("husky/husky.urdf", "differential", 4),
        ("r2d2.urdf", "differential", 4),
        ("racecar/racecar.urdf", "ackermann", 2),
    ],
)
def test_bare_urdfs_get_their_wheels_detected(urdf: str, drive: str, wheels: int) -> None:
    env = BulletMazeEnv(maze="open", robot=str(DATA / urdf), actions="native")
    try:
        assert env.robot.drive.kind == drive
        assert env.robot.has_heading
        assert env.observation_space.shape == (3,)
        assert len(env.robot.wheel_velocities()) == wheels
    finally:
        env.close()


def test_an_undetectable_urdf_is_holonomic_with_a_warning(
    caplog: pytest.LogCaptureFixture,
) -> None:
    path = DATA / "mini_cheetah" / "mini_cheetah.urdf"
    with caplog.at_level(logging.WARNING, logger="bullet_maze.robots.robot"):
        env = BulletMazeEnv(maze="open", robot=str(path))
    try:
        assert env.robot.drive.kind == "holonomic"
        assert env.observation_space.shape == (2,)
    finally:
        env.close()
    assert "mini_cheetah.urdf: no drive detected" in caplog.text
    assert "torso_to_abduct_fl_j" in caplog.text  # the ignored joints are named


def test_a_urdf_without_joints_is_holonomic_silently(caplog: pytest.LogCaptureFixture) -> None:
    with caplog.at_level(logging.WARNING):
        env = BulletMazeEnv(maze="open", robot=str(DATA / "cube.urdf"))
    env.close()
    assert env.robot.drive.kind == "holonomic"
    assert "no drive detected" not in caplog.text


def test_frame_links_without_inertia_weigh_almost_nothing() -> None:
    # husky.urdf leaves its footprint and sensor mounts without inertial data; pybullet would
    # give each 1 kg and 1 kg m^2, which made the robot turn several times slower.
    env = BulletMazeEnv(robot="husky", mode="dynamic")
    try:
        assert env.robot.body.mass == pytest.approx(33.455 + 6 * 0.01, abs=1e-6)
    finally:
        env.close()
    assert math.isfinite(env.robot.radius)
