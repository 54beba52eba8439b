"""The compiled kernel of the fast learning loop (numba, nopython, cached on disk).

:func:`run_episode` runs one episode of :meth:`agent.learner.SMDPAgent._run_episode` (the
reference) on arrays that mirror the agent and the kinematic maze env, and returns to Python
whenever something needs Python: a step the kernel cannot prove free (the real ``env.step``
through its wrappers does it: pybullet sweeps, new cells, noise blocks, ambiguous comparisons),
a split test (the reference's ``partition.record`` and ``_grow``), a new block of uniforms, or
full scratch arrays. Each return names an event; the driver (:mod:`agent.fast_loop`) handles it
and calls again, and the kernel resumes where it stopped (``st[I_PHASE]``). Nothing here draws
a random number or talks to pybullet: every draw comes from the agent's :class:`UniformStream`
block (``ubuf``) and the env's noise block (``noise``), in the reference's order.

Every float operation is the reference's, in the reference's order: Python float sums are
sequential (CPython 3.11 ``sum``), ``math.log``/``math.exp`` call the same libm, and numba does
not contract ``a * b + c`` into an FMA. ``math.hypot`` is the exception (CPython's differs from
libm's in the last bit), so the kernel decides ``hypot(a, b) <= r`` only when it is certain by
a wide margin and lets the real env take the step otherwise (:func:`hypot_le`).
"""

from __future__ import annotations

import math

from numba import njit

# Events (return values of run_episode).
EV_DONE = 0
EV_PY_STEP = 1
EV_RECORD = 2
EV_UNIFORM = 3
EV_GROW = 4
EV_POOL = 5
EV_SWEEP = 6

# Phases (st[I_PHASE]).
PH_START = 0
PH_SELECT = 1
PH_STEP = 2
PH_STEP_RESULT = 3
PH_END = 4
PH_END_LOOP = 5
PH_END_RESUME = 6
PH_DONE = 7
PH_SWEEP_RESULT = 8

# Integer state st[...]: run configuration first, then the episode's state.
C_KIND = 0  # 0 tree, 1 grid
C_ACTIONS = 1
C_EPOCH_CAP = 2
C_HOLD_EXPLORATION = 3
C_END_ON_COLLISION = 4
C_RECORDS = 5
C_BUFFER_CAP = 6
C_STRATEGY = 7  # S_EPSILON, S_ADAPTIVE, S_VDBE
C_VARIANT = 8  # adaptive: 1 = "cn_exponent"; vdbe: 1 = "exponential"
C_TABU = 9
C_TABU_INITIAL = 10
C_TABU_SHRINK = 11
C_TABU_MIN = 12
C_TABU_RESPECTS = 13
C_TABU_DEVIATION = 14
C_TABU_ALL_RANDOM = 15
C_MAX_STEPS = 16  # TimeLimit's max_episode_steps, -1 without one
I_BASE_SELECTED = 17  # the tabu's base strategy chose (and set its explored flag)
I_PHASE = 20
I_ACTION = 21
I_HOLD = 22
I_LEAF = 23
I_CURRENT = 24
I_NXT = 25
I_STEPS = 26
I_COLLISIONS = 27
I_EPOCHS = 28
I_N = 29
I_FIRST = 30
I_TERMINATED = 31
I_TRUNCATED = 32
I_COLLIDED = 33
I_SUCCESS = 34
I_DONE = 35
I_SPLIT = 36
I_HS = 37
I_HE = 38
I_ANY_SPLIT = 39
I_LAST_LEAF = 40
I_REC_LEAF = 41
I_REC_START = 42
I_REC_END = 43
I_EXPLORED = 44
I_BASE_EXPLORED = 45
I_TABU_HEAD = 46
I_TABU_LEN = 47
I_TABU_CAPACITY = 48
I_TABU_SUCCESSES = 49
I_TABU_DIRTY = 50
I_NDIRTY = 51
I_NFREE = 52
I_UPOS = 53
I_ULEN = 54
I_NOISE = 55
I_NOISE_LEN = 56
I_ELAPSED = 57
I_CHECKER_OK = 58
I_MOVED = 59
I_EXPLORED_DIRTY = 60
I_KERNEL_STEPS = 61
I_PY_STEPS = 62
I_BODY_MOVED = 63
N_INT = 64

# Float state fs[...].
F_X = 0
F_Y = 1
F_EX = 2
F_EY = 3
F_TOTAL = 4
F_EPS_SUM = 5
F_SX = 6
F_SY = 7
F_SR = 8
F_GX = 9
F_GY = 10
F_GR = 11
F_R_GOAL = 12
F_R_STEP = 13
F_OX = 14
F_OY = 15
F_OR = 16
F_ALPHA = 17
F_GAMMA = 18
F_EPSILON = 19
F_CN = 20
F_CH = 21
F_SIGMA = 22
F_DELTA = 23
F_CELL = 24
F_CELL_REACH = 25
F_TOLERANCE = 26
F_R_COLLISION = 27
F_SW_X0 = 28
F_SW_Y0 = 29
F_SW_X1 = 30
F_SW_Y1 = 31
N_FLOAT = 36

# Columns of the per-id integer table li[id, ...] and float table lf[id, ...].
L_DIM = 0
L_LEFT = 1
L_EPS_HAS = 2
L_COUNTS_HAS = 3
L_TABU_MASK = 4
L_SLOT = 5
L_DIRTY = 6
L_NEW = 7  # the kernel made this id's first strategy entry or buffer
N_LI = 8
LF_THRESHOLD = 0
LF_EPS = 1
N_LF = 2

S_EPSILON = 0
S_ADAPTIVE = 1
S_VDBE = 2

CELL_UNSEEN = -2
CELL_USELESS = -1

MARGIN = 1e-12
"""Relative margin of :func:`hypot_le`: libm's and CPython's hypot differ by an ulp or two
(2e-16 relative), so a comparison farther than this from the threshold has one answer."""


@njit(cache=True)
def hypot_le(a: float, b: float, r: float) -> int:
    """``math.hypot(a, b) <= r`` as CPython computes it: 1 or 0 when certain, -1 when not
    (non-finite input, under- or overflow, or within MARGIN of the threshold)."""
    if r == -math.inf:
        return 0  # a hypot is never -inf (nan <= -inf is false too)
    if not (math.isfinite(a) and math.isfinite(b)) or math.isnan(r):
        return -1
    h2 = a * a + b * b
    if not math.isfinite(h2) or (h2 < 1e-280 and (a != 0.0 or b != 0.0)):
        return -1
    if r == math.inf:
        return 1
    h = math.sqrt(h2)
    m = MARGIN * max(h, abs(r))
    if h < r - m:
        return 1
    if h > r + m:
        return 0
    return -1


@njit(cache=True, inline="always")
def leaf_of(x0, x1, st, li, lf, grid_f, grid_i):
    """``partition.leaf_of([x0, x1])``: PartitionTree's walk or UniformGrid's cell."""
    if st[C_KIND] == 0:
        node = 0
        d = li[0, L_DIM]
        while d >= 0:
            v = x0 if d == 0 else x1
            node = li[node, L_LEFT] if v < lf[node, LF_THRESHOLD] else li[node, L_LEFT] + 1
            d = li[node, L_DIM]
        return node
    leaf = 0
    for i in range(2):
        v = x0 if i == 0 else x1
        c = int((v - grid_f[i, 0]) * grid_f[i, 1])
        n = grid_i[i, 0]
        if c < 0:
            c = 0
        elif c >= n:
            c = n - 1
        leaf += c * grid_i[i, 1]
    return leaf


@njit(cache=True, inline="always")
def epsilon(leaf, st, fs, li, lf):
    """``strategy.epsilon(leaf)`` (Tabu passes its base's)."""
    if st[C_STRATEGY] == S_EPSILON:
        return fs[F_EPSILON]
    if li[leaf, L_EPS_HAS]:
        return lf[leaf, LF_EPS]
    return 1.0


@njit(cache=True, inline="always")
def row_max(q, leaf, actions, mask):
    """``max(row)`` of Python: the first largest value; masked actions count as -inf."""
    best = -math.inf if mask & 1 else q[leaf, 0]
    for a in range(1, actions):
        v = -math.inf if (mask >> a) & 1 else q[leaf, a]
        if v > best:
            best = v
    return best


@njit(cache=True, inline="always")
def greedy(q, leaf, actions, mask, ubuf, p, ulen):
    """``greedy_action(row, rng)`` on the row with masked actions at -inf.

    Returns (action, draw position); action -1 when a draw is needed and the block is spent.
    """
    best = row_max(q, leaf, actions, mask)
    count = 0
    first = -1
    for a in range(actions):
        v = -math.inf if (mask >> a) & 1 else q[leaf, a]
        if v == best:
            if first < 0:
                first = a
            count += 1
    if count == 1:
        return first, p
    if p >= ulen:
        return -1, p
    u = ubuf[p]
    pick = int(u * count)
    for a in range(actions):
        v = -math.inf if (mask >> a) & 1 else q[leaf, a]
        if v == best:
            if pick == 0:
                return a, p + 1
            pick -= 1
    return -1, p  # unreachable


@njit(cache=True, inline="always")
def base_select(leaf, mask, st, fs, q, li, lf, ubuf, p, ulen):
    """``Exploration.select``: (action, explored, position); action -1 when out of draws."""
    actions = st[C_ACTIONS]
    if p >= ulen:
        return -1, 0, p
    u = ubuf[p]
    p += 1
    if u < epsilon(leaf, st, fs, li, lf):
        if p >= ulen:
            return -1, 0, p
        return int(ubuf[p] * actions), 1, p + 1
    action, p = greedy(q, leaf, actions, mask, ubuf, p, ulen)
    return action, 0, p


@njit(cache=True, inline="always")
def popcount(mask, actions):
    n = 0
    for a in range(actions):
        n += (mask >> a) & 1
    return n


@njit(cache=True, inline="always")
def select(leaf, st, fs, q, li, lf, ubuf):
    """``strategy.select(leaf, q[leaf], rng)`` with the draws of ``ubuf`` from ``st[I_UPOS]``.

    Commits the position and the explored flags and returns the action, or returns -1 without
    changing anything when the block runs out (the driver appends the next block and the
    choice is made again from the start, with the same draws).
    """
    actions = st[C_ACTIONS]
    p = st[I_UPOS]
    ulen = st[I_ULEN]
    if not st[C_TABU]:
        action, explored, p = base_select(leaf, 0, st, fs, q, li, lf, ubuf, p, ulen)
        if action < 0:
            return -1
        st[I_EXPLORED] = explored
        st[I_BASE_EXPLORED] = explored
        st[I_UPOS] = p
        st[I_EXPLORED_DIRTY] = 1
        return action
    mask = li[leaf, L_TABU_MASK]
    listed = popcount(mask, actions)
    base_explored = st[I_BASE_EXPLORED]
    if listed > 0 and listed == actions and st[C_TABU_ALL_RANDOM]:
        if p >= ulen:
            return -1
        action = int(ubuf[p] * actions)
        st[I_UPOS] = p + 1
        st[I_EXPLORED] = 1
        st[I_EXPLORED_DIRTY] = 1
        return action
    if listed == 0 or listed == actions:
        action, explored, p = base_select(leaf, 0, st, fs, q, li, lf, ubuf, p, ulen)
        if action < 0:
            return -1
        st[I_EXPLORED] = explored
        st[I_BASE_EXPLORED] = explored
        st[I_BASE_SELECTED] = 1
        st[I_UPOS] = p
        st[I_EXPLORED_DIRTY] = 1
        return action
    if st[C_TABU_RESPECTS]:
        if p >= ulen:
            return -1
        u = ubuf[p]
        p += 1
        if u < epsilon(leaf, st, fs, li, lf):
            if p >= ulen:
                return -1
            pick = int(ubuf[p] * (actions - listed))
            p += 1
            action = -1
            for a in range(actions):
                if not (mask >> a) & 1:
                    if pick == 0:
                        action = a
                        break
                    pick -= 1
            st[I_UPOS] = p
            st[I_EXPLORED] = 1
            st[I_EXPLORED_DIRTY] = 1
            return action
        action, p = greedy(q, leaf, actions, mask, ubuf, p, ulen)
        if action < 0:
            return -1
        explored = 0
    else:
        action, explored, p = base_select(leaf, mask, st, fs, q, li, lf, ubuf, p, ulen)
        if action < 0:
            return -1
        base_explored = explored
        st[I_BASE_SELECTED] = 1
    if not explored and st[C_TABU_DEVIATION] and q[leaf, action] < row_max(q, leaf, actions, 0):
        explored = 1
    st[I_EXPLORED] = explored
    st[I_BASE_EXPLORED] = base_explored
    st[I_UPOS] = p
    st[I_EXPLORED_DIRTY] = 1
    return action


@njit(cache=True, inline="always")
def adaptive_epsilon(counts, leaf, actions, delta_q, c_n, c_h, cn_exponent):
    """``agent.exploration.adaptive.adaptive_epsilon`` (eq. 5), operation for operation."""
    total = 0
    for a in range(actions):
        total += counts[leaf, a]
    if total == 0:
        return 1.0
    h = 0.0
    for a in range(actions):
        n = counts[leaf, a]
        if n:
            p = n / total
            h -= p * math.log(p)
    unused = 1.0 - (h / math.log(actions) if actions > 1 else 0.0)
    magnitude = abs(delta_q)
    if magnitude / (total * c_n) < c_h:
        scale = total * c_n if cn_exponent else float(total)
        return unused * (1.0 - math.exp(-magnitude / scale))
    return unused


@njit(cache=True, inline="always")
def mark_dirty(leaf, st, li, dirty):
    if not li[leaf, L_DIRTY]:
        li[leaf, L_DIRTY] = 1
        dirty[st[I_NDIRTY]] = leaf
        st[I_NDIRTY] += 1


@njit(cache=True, inline="always")
def tabu_trim(st, li, fifo):
    ring = fifo.shape[0]
    while st[I_TABU_LEN] > st[I_TABU_CAPACITY]:
        head = st[I_TABU_HEAD]
        leaf = fifo[head, 0]
        li[leaf, L_TABU_MASK] &= ~(1 << fifo[head, 1])
        st[I_TABU_HEAD] = (head + 1) % ring
        st[I_TABU_LEN] -= 1


@njit(cache=True, inline="always")
def end_epoch(
    leaf,
    action,
    start,
    end,
    bootstrap,
    st,
    fs,
    q,
    visits,
    counts,
    li,
    lf,
    fifo,
    xs,
    rs,
    errs,
    bufi,
    buff,
    bctr,
    bsum,
    free,
    dirty,
):
    """``SMDPAgent._end_epoch`` for the inputs ``xs[start:end]``: eqs. (9)-(10), the strategy's
    hooks and, when the leaf's buffer takes the pairs without a split test, the record.

    Returns 0 (recorded, no split possible), 1 (the driver must record: the buffer fills, so
    the split test runs in Python; the errors are in ``errs[:end - start]``) or 2 (no free
    buffer slot: nothing was changed, the driver must grow the pool).
    """
    n = end - start
    records = st[C_RECORDS]
    slot = li[leaf, L_SLOT]
    count = 0
    head = 0
    in_kernel = False
    if records:
        if slot >= 0:
            count = bctr[slot, 0]
            head = bctr[slot, 1]
        in_kernel = head + n < st[C_BUFFER_CAP] and count + n < st[C_BUFFER_CAP]
        if in_kernel and slot < 0 and st[I_NFREE] == 0:
            return 2
    gamma = fs[F_GAMMA]
    alpha = fs[F_ALPHA]
    old = q[leaf, action]
    g = bootstrap
    for k in range(n - 1, -1, -1):  # eq. (9), epoch_returns
        g = rs[start + k] + gamma * g
        errs[k] = g
    total = 0.0
    for k in range(n):
        total += errs[k]
    new = (1.0 - alpha) * old + alpha * (total / n)  # eq. (10), leaf_update
    for k in range(n):
        errs[k] = errs[k] - old
    q[leaf, action] = new
    visits[leaf, action] += 1
    mark_dirty(leaf, st, li, dirty)
    strategy = st[C_STRATEGY]
    actions = st[C_ACTIONS]
    if strategy == S_ADAPTIVE:
        if not li[leaf, L_COUNTS_HAS]:
            for a in range(actions):
                counts[leaf, a] = 0
            li[leaf, L_COUNTS_HAS] = 1
            li[leaf, L_NEW] = 1
        counts[leaf, action] += 1
        lf[leaf, LF_EPS] = adaptive_epsilon(
            counts, leaf, actions, new - old, fs[F_CN], fs[F_CH], st[C_VARIANT]
        )
        if not li[leaf, L_EPS_HAS]:
            li[leaf, L_EPS_HAS] = 1
            li[leaf, L_NEW] = 1
    elif strategy == S_VDBE:
        previous = lf[leaf, LF_EPS] if li[leaf, L_EPS_HAS] else 1.0
        decay = math.exp(-abs(new - old) / fs[F_SIGMA])
        f = 1.0 - decay if st[C_VARIANT] else (1.0 - decay) / (1.0 + decay)
        delta = fs[F_DELTA]
        lf[leaf, LF_EPS] = delta * f + (1.0 - delta) * previous
        if not li[leaf, L_EPS_HAS]:
            li[leaf, L_EPS_HAS] = 1
            li[leaf, L_NEW] = 1
    if st[C_TABU]:  # Tabu.on_epoch_end
        mask = li[leaf, L_TABU_MASK]
        if not (mask >> action) & 1:
            li[leaf, L_TABU_MASK] = mask | (1 << action)
            ring = fifo.shape[0]
            tail = (st[I_TABU_HEAD] + st[I_TABU_LEN]) % ring
            fifo[tail, 0] = leaf
            fifo[tail, 1] = action
            st[I_TABU_LEN] += 1
            tabu_trim(st, li, fifo)
            st[I_TABU_DIRTY] = 1
    if not records:
        return 0
    if not in_kernel:
        return 1
    if slot < 0:
        st[I_NFREE] -= 1
        slot = free[st[I_NFREE]]
        li[leaf, L_SLOT] = slot
        li[leaf, L_NEW] = 1
        bctr[slot, 0] = 0
        bctr[slot, 1] = 0
        bctr[slot, 2] = 0
        bsum[slot, 0] = 0.0
        bsum[slot, 1] = 0.0
    # ErrorBuffer.add, the branch without wrap: slice copies and sequential sums.
    s = 0.0
    s2 = 0.0
    for k in range(n):
        e = errs[k]
        bufi[slot, 2 * (head + k)] = xs[start + k, 0]
        bufi[slot, 2 * (head + k) + 1] = xs[start + k, 1]
        buff[slot, head + k] = e
        s += e
        s2 += e * e
    bctr[slot, 0] = count + n
    bctr[slot, 1] = head + n
    bsum[slot, 0] = bsum[slot, 0] + s
    bsum[slot, 1] = bsum[slot, 1] + s2
    return 0


@njit(cache=True, inline="always")
def certified_free(x0, y0, x1, y1, fs, cells, bounds_c, bounds_r, pieces):
    """``World.certified_free``: 1 proved free, 0 not proved, -1 undecided here (an unseen
    cell, a cell outside the table, a comparison within the margin)."""
    a = hypot_le(x1 - fs[F_SX], y1 - fs[F_SY], fs[F_SR])
    if a < 0:
        return -1
    if a == 1:
        b = hypot_le(x0 - fs[F_SX], y0 - fs[F_SY], fs[F_SR])
        if b < 0:
            return -1
        if b == 1:
            return 1
    cx = int(x0 // fs[F_CELL])
    cy = int(y0 // fs[F_CELL])
    if cx < 0 or cy < 0 or cx >= cells.shape[0] or cy >= cells.shape[1]:
        return -1
    index = cells[cx, cy]
    if index == CELL_UNSEEN:
        return -1
    if index == CELL_USELESS:
        return 0
    # _CellBounds.clear
    ax = x0 - bounds_c[index, 0]
    ay = y0 - bounds_c[index, 1]
    bx = x1 - bounds_c[index, 0]
    by = y1 - bounds_c[index, 1]
    reach = fs[F_CELL_REACH]
    inside = hypot_le(ax, ay, reach)
    if inside < 0:
        return -1
    if inside == 0:
        return 0
    inside = hypot_le(bx, by, reach)
    if inside < 0:
        return -1
    if inside == 0:
        return 0
    tolerance = fs[F_TOLERANCE]
    for k in range(bounds_r[index, 0], bounds_r[index, 0] + bounds_r[index, 1]):
        distance, nx, ny = pieces[k, 0], pieces[k, 1], pieces[k, 2]
        if distance + nx * ax + ny * ay < tolerance or distance + nx * bx + ny * by < tolerance:
            return 0
    return 1


@njit(cache=True, inline="always")
def env_step(action, st, fs, moves, noise, cells, bounds_c, bounds_r, pieces):
    """``env.step(action)`` (kinematic, through TimeLimit): 1 when taken here (the move proved
    free and the goal test certain), 2 when only Python can decide the collision or the goal
    (the move is in ``fs[F_SW_X0:F_SW_Y1 + 1]``: the driver calls ``World.sweep_collides`` on
    it, as ``step`` does, and :func:`finish_step` completes the step), 0 when ``env.step``
    itself must take it (a new noise block, the checker's first steps). Only 1 changes state.
    """
    if not st[I_CHECKER_OK]:
        return 0
    i = st[I_NOISE]
    if i >= st[I_NOISE_LEN]:
        return 0
    dx = moves[action, 0] + noise[i]
    dy = moves[action, 1] + noise[i + 1]
    x0 = fs[F_EX]
    y0 = fs[F_EY]
    x1 = x0 + dx
    y1 = y0 + dy
    success = -1
    if certified_free(x0, y0, x1, y1, fs, cells, bounds_c, bounds_r, pieces) == 1:
        success = hypot_le(x1 - fs[F_GX], y1 - fs[F_GY], fs[F_GR])
    if success < 0:
        fs[F_SW_X0] = x0
        fs[F_SW_Y0] = y0
        fs[F_SW_X1] = x1
        fs[F_SW_Y1] = y1
        return 2
    st[I_COLLIDED] = 0
    st[I_SUCCESS] = success
    fs[F_OX] = x1
    fs[F_OY] = y1
    finish_step(st, fs)
    return 1


@njit(cache=True, inline="always")
def finish_step(st, fs):
    """The rest of ``step`` once the collision (``st[I_COLLIDED]``), the goal test
    (``st[I_SUCCESS]``) and the final position (``fs[F_OX]``, ``fs[F_OY]``) are known."""
    st[I_NOISE] += 2
    if not st[I_COLLIDED]:
        fs[F_EX] = fs[F_OX]
        fs[F_EY] = fs[F_OY]
        st[I_BODY_MOVED] = 1
    st[I_MOVED] = 1
    st[I_ELAPSED] += 1
    if st[I_COLLIDED]:
        fs[F_OR] = fs[F_R_COLLISION]
    elif st[I_SUCCESS]:
        fs[F_OR] = fs[F_R_GOAL]
    else:
        fs[F_OR] = fs[F_R_STEP]
    st[I_TERMINATED] = st[I_SUCCESS]
    st[I_TRUNCATED] = 1 if (st[C_MAX_STEPS] >= 0 and st[I_ELAPSED] >= st[C_MAX_STEPS]) else 0


@njit(cache=True)
def run_episode(
    st,
    fs,
    li,
    lf,
    q,
    visits,
    counts,
    fifo,
    ubuf,
    grid_f,
    grid_i,
    xs,
    rs,
    held,
    errs,
    bufi,
    buff,
    bctr,
    bsum,
    free,
    dirty,
    moves,
    noise,
    cells,
    bounds_c,
    bounds_r,
    pieces,
):
    """Run (or resume) the episode until it ends or needs Python; returns the event."""
    while True:
        phase = st[I_PHASE]
        if phase == PH_START:
            leaf = leaf_of(fs[F_X], fs[F_Y], st, li, lf, grid_f, grid_i)
            st[I_LEAF] = leaf
            st[I_CURRENT] = leaf
            st[I_STEPS] = 0
            st[I_COLLISIONS] = 0
            st[I_EPOCHS] = 1
            st[I_N] = 0
            st[I_FIRST] = 1
            fs[F_TOTAL] = 0.0
            st[I_PHASE] = PH_SELECT
        elif phase == PH_SELECT:
            leaf = st[I_LEAF]
            action = select(leaf, st, fs, q, li, lf, ubuf)
            if action < 0:
                return EV_UNIFORM
            st[I_ACTION] = action
            st[I_HOLD] = 1 if (st[C_HOLD_EXPLORATION] and st[I_EXPLORED]) else 0
            if st[I_FIRST]:
                fs[F_EPS_SUM] = epsilon(leaf, st, fs, li, lf)
                st[I_FIRST] = 0
            else:
                fs[F_EPS_SUM] += epsilon(leaf, st, fs, li, lf)
                st[I_EPOCHS] += 1
            st[I_N] = 0
            st[I_PHASE] = PH_STEP
        elif phase == PH_STEP or phase == PH_STEP_RESULT or phase == PH_SWEEP_RESULT:  # noqa: SIM109
            if phase == PH_STEP:
                if st[I_N] >= xs.shape[0]:
                    return EV_GROW
                code = env_step(
                    st[I_ACTION], st, fs, moves, noise, cells, bounds_c, bounds_r, pieces
                )
                if code == 1:
                    st[I_KERNEL_STEPS] += 1
                elif code == 2:
                    st[I_PHASE] = PH_SWEEP_RESULT
                    return EV_SWEEP
                else:
                    st[I_PHASE] = PH_STEP_RESULT
                    return EV_PY_STEP
            elif phase == PH_SWEEP_RESULT:
                finish_step(st, fs)
            n = st[I_N]
            xs[n, 0] = fs[F_X]
            xs[n, 1] = fs[F_Y]
            r = fs[F_OR]
            rs[n] = r
            if st[I_HOLD]:
                held[n] = st[I_CURRENT]
            n += 1
            st[I_N] = n
            st[I_STEPS] += 1
            fs[F_TOTAL] += r
            fs[F_X] = fs[F_OX]
            fs[F_Y] = fs[F_OY]
            collided = st[I_COLLIDED]
            if collided:
                st[I_COLLISIONS] += 1
            nxt = leaf_of(fs[F_X], fs[F_Y], st, li, lf, grid_f, grid_i)
            st[I_NXT] = nxt
            st[I_CURRENT] = nxt
            done = 1 if (st[I_TERMINATED] or st[I_TRUNCATED]) else 0
            st[I_DONE] = done
            if (
                done
                or (nxt != st[I_LEAF] and not st[I_HOLD])
                or n >= st[C_EPOCH_CAP]
                or (collided and st[C_END_ON_COLLISION])
            ):
                st[I_PHASE] = PH_END
            else:
                st[I_PHASE] = PH_STEP
        elif phase == PH_END or phase == PH_END_LOOP or phase == PH_END_RESUME:  # noqa: SIM109
            n = st[I_N]
            action = st[I_ACTION]
            split = 0
            finished = False
            if not st[I_HOLD]:
                if phase == PH_END:
                    nxt = st[I_NXT]
                    bootstrap = 0.0 if st[I_TERMINATED] else row_max(q, nxt, st[C_ACTIONS], 0)
                    code = end_epoch(
                        st[I_LEAF],
                        action,
                        0,
                        n,
                        bootstrap,
                        st,
                        fs,
                        q,
                        visits,
                        counts,
                        li,
                        lf,
                        fifo,
                        xs,
                        rs,
                        errs,
                        bufi,
                        buff,
                        bctr,
                        bsum,
                        free,
                        dirty,
                    )
                    if code == 2:
                        return EV_POOL
                    if code == 1:
                        st[I_REC_LEAF] = st[I_LEAF]
                        st[I_REC_START] = 0
                        st[I_REC_END] = n
                        st[I_PHASE] = PH_END_RESUME
                        return EV_RECORD
                else:  # PH_END_RESUME
                    split = st[I_SPLIT]
                finished = True
            else:  # _end_held_run: one epoch per stretch of inputs in one leaf
                if phase == PH_END:
                    st[I_LAST_LEAF] = leaf_of(fs[F_X], fs[F_Y], st, li, lf, grid_f, grid_i)
                    st[I_ANY_SPLIT] = 0
                    st[I_HS] = 0
                elif phase == PH_END_RESUME:
                    if st[I_SPLIT]:
                        st[I_ANY_SPLIT] = 1
                        for k in range(st[I_HE], n):
                            held[k] = leaf_of(xs[k, 0], xs[k, 1], st, li, lf, grid_f, grid_i)
                        st[I_LAST_LEAF] = leaf_of(fs[F_X], fs[F_Y], st, li, lf, grid_f, grid_i)
                    st[I_HS] = st[I_HE]
                st[I_PHASE] = PH_END_LOOP
                while st[I_HS] < n:
                    start = st[I_HS]
                    leaf = held[start]
                    end = start + 1
                    while end < n and held[end] == leaf:
                        end += 1
                    if end < n:
                        bootstrap = row_max(q, held[end], st[C_ACTIONS], 0)
                    elif st[I_TERMINATED]:
                        bootstrap = 0.0
                    else:
                        bootstrap = row_max(q, st[I_LAST_LEAF], st[C_ACTIONS], 0)
                    code = end_epoch(
                        leaf,
                        action,
                        start,
                        end,
                        bootstrap,
                        st,
                        fs,
                        q,
                        visits,
                        counts,
                        li,
                        lf,
                        fifo,
                        xs,
                        rs,
                        errs,
                        bufi,
                        buff,
                        bctr,
                        bsum,
                        free,
                        dirty,
                    )
                    if code == 2:
                        return EV_POOL
                    if code == 1:
                        st[I_REC_LEAF] = leaf
                        st[I_REC_START] = start
                        st[I_REC_END] = end
                        st[I_HE] = end
                        st[I_PHASE] = PH_END_RESUME
                        return EV_RECORD
                    st[I_HS] = end
                split = st[I_ANY_SPLIT]
                finished = True
            if finished:
                if st[I_DONE]:
                    if st[C_TABU] and st[I_SUCCESS]:  # Tabu.on_episode_end
                        st[I_TABU_SUCCESSES] += 1
                        capacity = st[C_TABU_INITIAL] - st[I_TABU_SUCCESSES] // st[C_TABU_SHRINK]
                        st[I_TABU_CAPACITY] = max(st[C_TABU_MIN], capacity)
                        tabu_trim(st, li, fifo)
                        st[I_TABU_DIRTY] = 1
                    st[I_PHASE] = PH_DONE
                    return EV_DONE
                leaf = leaf_of(fs[F_X], fs[F_Y], st, li, lf, grid_f, grid_i) if split else st[I_NXT]
                st[I_LEAF] = leaf
                st[I_CURRENT] = leaf
                st[I_PHASE] = PH_SELECT
        else:
            return EV_DONE
