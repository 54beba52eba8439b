"""Layout files from the command line: ``python -m bullet_maze SUBCOMMAND ...``.

    python -m bullet_maze generate "rooms:seed=3,door=30" --out my.toml
    python -m bullet_maze import-map map.json --cell-size 50 --out my.toml
    python -m bullet_maze import-map map.json --start-cell 1,1 --goal-cell 5,7 --out my.toml
    python -m bullet_maze import-map --standard umaze --out umaze.toml
    python -m bullet_maze show my.toml

``generate`` writes a generator spec's layout as an ordinary layout file (loading the file gives
the same layout); ``import-map`` converts a Gymnasium-Robotics / D4RL ``maze_map`` (a JSON list of
rows: 1 wall, 0 free, "g" goal, "r" reset, "c" either); ``show`` prints a layout's size and its
physical limit. Bad input ends with exit code 2 and a message naming it.
"""

from __future__ import annotations

import argparse
import json
import sys
from collections.abc import Sequence
from pathlib import Path

from bullet_maze.layout import layout_to_toml, load_layout
from bullet_maze.layout_types import MazeLayout
from bullet_maze.maze_maps import DEFAULT_CELL_SIZE, STANDARD_MAPS, layout_from_maze_map
from bullet_maze.params import MAX_LAYOUT_FILE_BYTES
from bullet_maze.planning import shortest_path


def main(argv: Sequence[str] | None = None) -> int:
    """Parse ``argv`` and run the subcommand; returns the exit code."""
    parser = _parser()
    args = parser.parse_args(argv)
    try:
        if args.command == "generate":
            layout = load_layout(args.spec)
            header = f"Made by: python -m bullet_maze generate {args.spec!r}\n{layout.description}"
            _write(layout, args.out, header, args.force)
        elif args.command == "import-map":
            layout = _import(args)
            _write(layout, args.out, f"Made by: python -m bullet_maze {_quoted(args)}", args.force)
        else:
            _show(load_layout(args.maze))
    except (ValueError, TypeError, FileNotFoundError, FileExistsError) as error:
        parser.exit(2, f"python -m bullet_maze {args.command}: error: {error}\n")
    return 0


def _parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="python -m bullet_maze",
        description=__doc__,
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    sub = parser.add_subparsers(dest="command", metavar="SUBCOMMAND", required=True)
    generate = sub.add_parser("generate", help="write a generated layout as a layout file")
    generate.add_argument(
        "spec", metavar="SPEC", help='a generator spec, e.g. "maze:seed=2,rows=8"'
    )
    _output(generate)
    imported = sub.add_parser("import-map", help="write a maze_map (JSON) as a layout file")
    source = imported.add_mutually_exclusive_group(required=True)
    source.add_argument("map", nargs="?", type=Path, metavar="MAP", help="JSON file of the map")
    source.add_argument("--standard", choices=sorted(STANDARD_MAPS), help="a PointMaze map")
    imported.add_argument(
        "--cell-size",
        type=float,
        default=DEFAULT_CELL_SIZE,
        metavar="UNITS",
        help=f"side of a map cell in maze units (default {DEFAULT_CELL_SIZE:g})",
    )
    imported.add_argument("--name", help="the layout's name (default: the map's)")
    for end in ("start", "goal"):
        imported.add_argument(
            f"--{end}-cell",
            type=_cell,
            metavar="ROW,COLUMN",
            help=f"the {end} cell (row 0 at the top), where the map marks none",
        )
    _output(imported)
    show = sub.add_parser("show", help="print a layout's size and physical limit")
    show.add_argument("maze", metavar="MAZE", help="a layout name, file or generator spec")
    return parser


def _cell(text: str) -> tuple[int, int]:
    """A ``--start-cell`` or ``--goal-cell`` value: two integers, ``ROW,COLUMN``."""
    parts = text.split(",")
    try:
        row, column = (int(part) for part in parts)
    except ValueError:
        raise argparse.ArgumentTypeError(
            f"expected ROW,COLUMN (two integers, e.g. 3,4), got {text!r}"
        ) from None
    return row, column


def _output(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--out", type=Path, required=True, metavar="FILE", help="file to write")
    parser.add_argument("--force", action="store_true", help="overwrite an existing file")


def _import(args: argparse.Namespace) -> MazeLayout:
    cells = {"start_cell": args.start_cell, "goal_cell": args.goal_cell}
    if args.standard:
        name = args.name or f"pointmaze/{args.standard}"
        return layout_from_maze_map(
            STANDARD_MAPS[args.standard],
            args.cell_size,
            name=name,
            description=f"PointMaze's {args.standard} map (Gymnasium-Robotics), D4RL's goal cell",
            source=f"--standard {args.standard}",
            **cells,
        )
    path: Path = args.map
    if not path.is_file():
        raise FileNotFoundError(f"map file not found: {path}")
    if path.stat().st_size > MAX_LAYOUT_FILE_BYTES:
        raise ValueError(f"{path}: larger than {MAX_LAYOUT_FILE_BYTES:,} bytes")
    try:
        maze_map = json.loads(path.read_bytes().decode("utf-8"))
    except (UnicodeDecodeError, json.JSONDecodeError, RecursionError) as err:
        raise ValueError(f"{path}: not a JSON maze map: {err}") from None
    return layout_from_maze_map(
        maze_map, args.cell_size, name=args.name or path.stem, source=str(path), **cells
    )


def _write(layout: MazeLayout, out: Path, header: str, force: bool) -> None:
    if out.exists() and not (force and out.is_file()):
        raise FileExistsError(f"{out} exists (pass --force to overwrite a file)")
    if out.suffix != ".toml":
        raise ValueError(f"--out {out}: a layout file's name ends in .toml")
    out.parent.mkdir(parents=True, exist_ok=True)
    out.write_text(layout_to_toml(layout, header))
    print(f"wrote {out}: {_summary(layout)}")


def _show(layout: MazeLayout) -> None:
    limit = shortest_path(layout)
    print(f"{layout.name}: {_summary(layout)}")
    if layout.description:
        print(f"  {layout.description}")
    print(
        f"  shortest path {limit.length:.1f}, L1 geodesic {limit.l1_length:.1f}, least steps "
        f"{limit.steps} (noise-free from the start: {limit.lattice_steps})"
    )


def _summary(layout: MazeLayout) -> str:
    return (
        f"arena {layout.arena[0]:g} x {layout.arena[1]:g}, {len(layout.walls)} walls, "
        f"{len(layout.obstacles)} obstacles, start {layout.start}, goal {layout.goal} "
        f"(radius {layout.goal_radius:g}), robot radius {layout.robot_radius:g}"
    )


def _quoted(args: argparse.Namespace) -> str:
    source = f"--standard {args.standard}" if args.standard else str(args.map)
    cells = "".join(
        f" --{end}-cell {cell[0]},{cell[1]}"
        for end, cell in (("start", args.start_cell), ("goal", args.goal_cell))
        if cell is not None
    )
    return f"import-map {source} --cell-size {args.cell_size:g}{cells}"


if __name__ == "__main__":
    sys.exit(main())
