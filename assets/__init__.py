"""Data files shipped with bullet_maze: maze layouts (TOML, collections in subfolders such as
``mazes/pointmaze/``), layout suites (TOML) and robot models (URDF)."""

from __future__ import annotations

from pathlib import Path

ASSET_DIR = Path(__file__).resolve().parent
MAZE_DIR = ASSET_DIR / "mazes"
ROBOT_DIR = ASSET_DIR / "robots"
SUITE_DIR = ASSET_DIR / "suites"

__all__ = ["ASSET_DIR", "MAZE_DIR", "ROBOT_DIR", "SUITE_DIR"]
