"""Per-episode statistics returned by ``learn``."""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class EpisodeStats:
    """What happened in one training episode."""

    episode: int
    """Index of the episode over the agent's life (continues across ``learn`` calls)."""
    steps: int
    """Environment steps taken."""
    episode_return: float
    """Undiscounted sum of rewards."""
    success: bool
    """``info["is_success"]`` at the last step if the env reports it, else ``terminated``."""
    truncated: bool
    """The episode was cut by a time limit."""
    leaves: int
    """Leaves of the partition at the end of the episode."""
    collisions: int
    """Steps whose ``info[collision_key]`` was true."""
    epochs: int = 0
    """SMDP epochs (decision points) in the episode (section IV.A)."""
    mean_epsilon: float = 0.0
    """Mean exploration rate at the episode's decision points."""
