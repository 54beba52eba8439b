"""SMDP epoch returns and the leaf update (section IV.A-B, eqs. 6-10).

An epoch is one action held while the input stays in one leaf. These functions are called once
per epoch with the epoch's rewards; they are plain Python because epochs are short and NumPy's
per-call cost would dominate.
"""

from __future__ import annotations

from collections.abc import Sequence


def epoch_returns(rewards: list[float], bootstrap: float, gamma: float) -> list[float]:
    """Eq. (9): the discounted return of each input of an epoch.

    ``Q(s_{t+k}, a) = r_{t+k} + gamma r_{t+k+1} + ... + gamma^{tau-k-1} r_{t+tau-1}
    + gamma^{tau-k} V-bar(s')`` for ``k = 0 .. tau-1``, where ``bootstrap`` is V-bar(s'),
    max_a Q-bar(s', a) of the leaf the epoch ended in, or 0 at a terminal state.
    """
    out = [0.0] * len(rewards)
    g = bootstrap
    for k in range(len(rewards) - 1, -1, -1):
        g = rewards[k] + gamma * g
        out[k] = g
    return out


def epoch_discounts(tau: int, gamma: float) -> list[float]:
    """The factor eq. (9) applies to V-bar(s') for each input: ``gamma^(tau - k)``, k = 0 .. tau-1.

    With these, ``epoch_returns(rs, b, gamma)[k] == epoch_returns(rs, 0, gamma)[k] + D_k b``: the
    split the model of ``TreeConfig.planning="sweep"`` stores (:mod:`agent.leaf_model`).
    """
    out = [0.0] * tau
    d = 1.0
    for k in range(tau - 1, -1, -1):
        d *= gamma
        out[k] = d
    return out


def leaf_update(q: float, returns: list[float], alpha: float) -> tuple[float, list[float]]:
    """Eq. (10): move Q-bar(s_t, a) towards the mean of the epoch's per-input returns.

    ``Q-bar <- (1 - alpha) Q-bar + alpha (1/tau) sum_k Q(s_{t+k}, a)``. Returns the new Q-bar and
    the estimation errors ``delta_k = Q(s_{t+k}, a) - Q-bar_t(s_t, a)`` measured against the value
    before the update (the state-error pairs of section IV.B). The change the update made,
    ``new - q``, is alpha times the mean error: the Delta-Q of eq. (5).
    """
    errors = [g - q for g in returns]
    new_q = (1.0 - alpha) * q + alpha * (sum(returns) / len(returns))
    return new_q, errors


def greedy_among(row: Sequence[float], allowed: Sequence[int] | None = None) -> int:
    """Eq. (11)'s greedy action of a Q-bar row: the largest value, the lowest index among ties;
    only the ``allowed`` actions compete when given (``TreeConfig.greedy_min_epochs``)."""
    actions = range(len(row)) if allowed is None else allowed
    return max(actions, key=row.__getitem__)
