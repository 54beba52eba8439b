"""Vector envs: SyncVectorEnv and AsyncVectorEnv, including spawned workers."""

from __future__ import annotations

import gymnasium as gym
import numpy as np
import pytest

import bullet_maze  # noqa: F401  (registers the ids)


def _run(envs: gym.vector.VectorEnv) -> np.ndarray:
    obs, _ = envs.reset(seed=[0, 1])
    assert obs.shape == (2, 2)
    trace = [obs]
    for step in range(20):
        obs, rewards, _, _, infos = envs.step(np.array([step % 4, 3]))
        trace.append(obs)
        assert rewards.shape == (2,)
        assert infos["collision"].shape == (2,)
    envs.close()
    return np.array(trace)


def test_sync_and_async_agree() -> None:
    sync = _run(gym.make_vec("BulletMaze-v0", num_envs=2, vectorization_mode="sync"))
    fork = _run(gym.make_vec("BulletMaze-v0", num_envs=2, vectorization_mode="async"))
    assert sync.tobytes() == fork.tobytes()
    assert not np.array_equal(sync[:, 0], sync[:, 1])  # two seeds, two trajectories
    manual = _run(gym.vector.SyncVectorEnv([lambda: gym.make("BulletMaze-v0")] * 2))
    assert manual.tobytes() == sync.tobytes()


@pytest.mark.filterwarnings("ignore::DeprecationWarning")
def test_async_spawned_workers_register_the_ids() -> None:
    # A spawned worker imports nothing of ours until it makes the env from its spec; the entry
    # point's import must register the ids there (Gymnasium #222).
    envs = gym.make_vec(
        "BulletMaze-v0", num_envs=2, vectorization_mode="async", vector_kwargs={"context": "spawn"}
    )
    trace = _run(envs)
    sync = _run(gym.make_vec("BulletMaze-v0", num_envs=2, vectorization_mode="sync"))
    assert trace.tobytes() == sync.tobytes()
