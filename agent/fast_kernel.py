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

import ctypes
import math

import numpy as np
from llvmlite import ir
from numba import carray, njit, types
from numba.extending import intrinsic

# Events (return values of run_episode).
EV_DONE = 0
EV_PY_STEP = 1
EV_RECORD = 2
EV_UNIFORM = 3
EV_GROW = 4
EV_POOL = 5
EV_SWEEP = 6
EV_SUMS = 7
EV_PY_TAIL = 8
EV_CALLBACK_ERROR = 9

SWEEP_CALLBACK = ctypes.CFUNCTYPE(
    ctypes.c_int64,
    ctypes.c_double,
    ctypes.c_double,
    ctypes.c_double,
    ctypes.c_double,
    ctypes.c_int64,
)
"""The driver's sweep, called from the kernel without returning (about 0.3 us a call against
several for a return): ``sweep(x0, y0, x1, y1, known)`` answers ``World.sweep_collides(x0, y0,
x1, y1)`` and writes the safe ball; returns collided + 2 * success (the goal test), -1 when it
raised (the driver re-raises the exception after the kernel returns EV_CALLBACK_ERROR).
``known`` = 1: the kernel's :func:`certified_free` found the move not proved free on a cell it
knows (the world's own ``certified_free`` answers False too, with no side effect), so the
driver may go straight to the queries; 2: the safe ball does not hold the move and the cell is
unseen here (the driver goes straight to the cell's bounds); 0: undecided here (a margin, a
cell outside the table, or a free move whose goal test was uncertain)."""

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
PH_RECORD = 9

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
C_KREC = 64  # the split test runs here (else in Python, EV_RECORD)
C_MAX_LEAVES = 65
C_MIDPOINT = 66  # split_point "midpoint"
C_ROOT_NORM = 67  # range_normalization "root"
C_INHERIT_SAMPLES = 68
C_INHERIT_Q = 69
C_RESET_COUNTS = 70
C_STRATEGY_INHERIT = 71  # AdaptiveEpsilon / VDBE inherit_on_split
C_TABU_INHERIT = 72  # Tabu on_split "inherit"
I_NLEAVES = 73
I_NIDS = 74
I_NLOG = 75
I_REC_STAGE = 76
I_ADD_K = 77
I_SUM_SLOT = 78
I_SPLIT_DIM = 79
I_SWEEP = 80  # the address of the driver's SWEEP_CALLBACK (see call_sweep)
N_INT = 96

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
F_RW0 = 32  # the root's width per dimension
F_RW1 = 33
F_MIN_FRACTION = 34
F_MAX_ABS_MEAN = 35
F_MIN_VARIANCE = 36
F_MIN_T = 37
F_Q_INIT = 38
F_SPLIT_VALUE = 39
N_FLOAT = 48

# Columns of the per-id integer table li[id, ...] and float table lf[id, ...].
L_DIM = 0
L_LEFT = 1
L_EPS_HAS = 2
L_COUNTS_HAS = 3
L_TABU_MASK = 4
L_SLOT = 5
L_DIRTY = 6
L_PARENT = 7
L_DEPTH = 8
N_LI = 10
LF_THRESHOLD = 0
LF_EPS = 1
LF_LO0 = 2
LF_LO1 = 3
LF_HI0 = 4
LF_HI1 = 5
N_LF = 6

# Columns of bctr[slot, ...]: the buffer's counters and the stretch of storage written since the
# driver last copied it into the ErrorBuffer.
B_COUNT = 0
B_HEAD = 1
B_LOW = 2
B_HIGH = 3
N_BCTR = 4

# Kinds of log[k, 0]: what the driver must replay, in order, into the Python dicts.
LOG_BUFFER = 0  # partition._buffers[id] created
LOG_COUNTS = 1  # AdaptiveEpsilon._counts[id] created
LOG_EPS = 2  # _epsilon[id] created
LOG_SPLIT = 3  # id split: popped from every dict
LOG_ROOM = 8
"""Log entries one end_epoch and its record can add at most."""

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
def add_log(kind, leaf, st, log):
    k = st[I_NLOG]
    log[k, 0] = kind
    log[k, 1] = leaf
    st[I_NLOG] = k + 1


@njit(cache=True, inline="always")
def alloc_slot(leaf, st, li, bufi, buff, bctr, bsum, free, log):
    """``partition._buffers[leaf] = ErrorBuffer(dims, capacity)``: a zeroed slot."""
    st[I_NFREE] -= 1
    slot = free[st[I_NFREE]]
    li[leaf, L_SLOT] = slot
    bufi[slot, :] = 0.0
    buff[slot, :] = 0.0
    bctr[slot, B_COUNT] = 0
    bctr[slot, B_HEAD] = 0
    bctr[slot, B_LOW] = buff.shape[1]
    bctr[slot, B_HIGH] = 0
    bsum[slot, 0] = 0.0
    bsum[slot, 1] = 0.0
    add_log(LOG_BUFFER, leaf, st, log)
    return slot


@njit(cache=True, inline="always")
def free_slot(leaf, st, li, free):
    slot = li[leaf, L_SLOT]
    if slot >= 0:
        free[st[I_NFREE]] = slot
        st[I_NFREE] += 1
        li[leaf, L_SLOT] = -1


@njit(cache=True, inline="always")
def touched(slot, low, high, bctr):
    if low < bctr[slot, B_LOW]:
        bctr[slot, B_LOW] = low
    if high > bctr[slot, B_HIGH]:
        bctr[slot, B_HIGH] = high


@njit(cache=True)
def buffer_add(slot, xs, x_rows, x_start, es, e_start, k, n, bufi, buff, bctr, bsum):
    """``ErrorBuffer.add`` of the pairs (xs[x_rows[x_start + i]], es[e_start + i]), i < n, from
    the k-th on (``x_rows`` None: rows x_start + i). Returns n when done, or -(i + 1) when the
    ring wrapped after pair i: the driver must set the exact sums (``ErrorBuffer._exact_sums``,
    NumPy's) in ``bsum[slot]`` before the call from pair i + 1 on."""
    capacity = buff.shape[1]
    count = bctr[slot, B_COUNT]
    head = bctr[slot, B_HEAD]
    if k == 0 and head + n < capacity and count + n <= capacity:
        s = 0.0
        s2 = 0.0
        for i in range(n):
            row = x_start + i if x_rows is None else x_rows[x_start + i]
            e = es[e_start + i]
            bufi[slot, 2 * (head + i)] = xs[row, 0]
            bufi[slot, 2 * (head + i) + 1] = xs[row, 1]
            buff[slot, head + i] = e
            s += e
        for i in range(n):
            e = es[e_start + i]
            s2 += e * e
        touched(slot, head, head + n, bctr)
        bctr[slot, B_HEAD] = head + n
        bctr[slot, B_COUNT] = count + n
        bsum[slot, 0] = bsum[slot, 0] + s
        bsum[slot, 1] = bsum[slot, 1] + s2
        return n
    total = bsum[slot, 0]
    total_sq = bsum[slot, 1]
    i = k
    while i < n:
        row = x_start + i if x_rows is None else x_rows[x_start + i]
        e = es[e_start + i]
        bufi[slot, 2 * head] = xs[row, 0]
        bufi[slot, 2 * head + 1] = xs[row, 1]
        touched(slot, head, head + 1, bctr)
        if count == capacity:
            old = buff[slot, head]
            total -= old
            total_sq -= old * old
        else:
            count += 1
        buff[slot, head] = e
        total += e
        total_sq += e * e
        head += 1
        i += 1
        if head == capacity:
            bctr[slot, B_HEAD] = 0
            bctr[slot, B_COUNT] = count
            return -i
    bctr[slot, B_HEAD] = head
    bctr[slot, B_COUNT] = count
    bsum[slot, 0] = total
    bsum[slot, 1] = total_sq
    return n


@njit(cache=True, inline="always")
def pairwise_block(a, first, n, step):
    """NumPy's ``pairwise_sum`` for n <= 128 (one block: eight accumulators)."""
    if n < 8:
        res = 0.0
        for i in range(n):
            res += a[first + i * step]
        return res
    r0 = a[first]
    r1 = a[first + step]
    r2 = a[first + 2 * step]
    r3 = a[first + 3 * step]
    r4 = a[first + 4 * step]
    r5 = a[first + 5 * step]
    r6 = a[first + 6 * step]
    r7 = a[first + 7 * step]
    i = 8
    m = n - n % 8
    while i < m:
        b = first + i * step
        r0 += a[b]
        r1 += a[b + step]
        r2 += a[b + 2 * step]
        r3 += a[b + 3 * step]
        r4 += a[b + 4 * step]
        r5 += a[b + 5 * step]
        r6 += a[b + 6 * step]
        r7 += a[b + 7 * step]
        i += 8
    res = ((r0 + r1) + (r2 + r3)) + ((r4 + r5) + (r6 + r7))
    while i < n:
        res += a[first + i * step]
        i += 1
    return res


@njit(cache=True)
def pairwise_sum(a, first, n, step):
    """NumPy's ``pairwise_sum`` (``add.reduce`` of a 1-d float64 array) of a[first + i * step]:
    blocks of at most 128, halves rounded down to a multiple of 8, summed as NumPy's recursion
    sums them (here with an explicit stack: numba cannot cache recursive functions)."""
    if n <= 128:
        return pairwise_block(a, first, n, step)
    starts = np.empty(64, dtype=np.int64)
    sizes = np.empty(64, dtype=np.int64)
    stages = np.empty(64, dtype=np.int64)
    values = np.empty(64, dtype=np.float64)
    top = 1
    nv = 0
    starts[0] = first
    sizes[0] = n
    stages[0] = 0
    while top > 0:
        j = top - 1
        m = sizes[j]
        if m <= 128:
            values[nv] = pairwise_block(a, starts[j], m, step)
            nv += 1
            top -= 1
            continue
        half = m // 2
        half -= half % 8
        if stages[j] == 0:
            stages[j] = 1
            starts[top] = starts[j]
            sizes[top] = half
            stages[top] = 0
            top += 1
        elif stages[j] == 1:
            stages[j] = 2
            starts[top] = starts[j] + half * step
            sizes[top] = m - half
            stages[top] = 0
            top += 1
        else:
            values[nv - 2] = values[nv - 2] + values[nv - 1]
            nv -= 1
            top -= 1
    return values[0]


@njit(cache=True)
def column_stats(group, c):
    """``group.mean(axis=0)[c]`` and ``group.var(axis=0, ddof=1)[c]`` of an (n, 2) C array:
    NumPy reduces axis 0 of such an array row by row (sequential sums)."""
    n = group.shape[0]
    s = 0.0
    for i in range(n):
        s += group[i, c]
    mean = s / n
    ss = 0.0
    for i in range(n):
        x = group[i, c] - mean
        ss += x * x
    return mean, ss / (n - 1)


@njit(cache=True)
def vector_stats(group, c):
    """``float(v.mean())`` and ``float(v.var(ddof=1))`` of the column view v = group[:, c]
    (pairwise sums: the strided view, then its contiguous squared deviations)."""
    n = group.shape[0]
    flat = group.reshape(-1)
    mean = (0.0 + pairwise_sum(flat, c, n, 2)) / n
    squares = np.empty(n, dtype=np.float64)
    for i in range(n):
        x = flat[c + 2 * i] - mean
        squares[i] = x * x
    return mean, (0.0 + pairwise_sum(squares, 0, n, 1)) / (n - 1)


@njit(cache=True)
def density_crossing(mean1, var1, n1, mean2, var2, n2):
    """``split_statistics.density_crossing`` (eq. 13); (found, root)."""
    if mean1 == mean2 or var1 <= 0.0 or var2 <= 0.0 or n1 <= 0 or n2 <= 0:
        return False, 0.0
    log_term = 2.0 * var1 * var2 * math.log(n1 * math.sqrt(var2) / (n2 * math.sqrt(var1)))
    a = var1 - var2
    b = 2.0 * (mean1 * var2 - mean2 * var1)
    c = mean2 * mean2 * var1 - mean1 * mean1 * var2 + log_term
    biggest = var2 if var2 > var1 else var1
    nroots = 0
    root0 = 0.0
    root1 = 0.0
    if abs(a) <= 1e-12 * biggest:
        if b != 0.0:
            root0 = -c / b
            nroots = 1
    else:
        disc = b * b - 4.0 * a * c
        if disc < 0.0:
            return False, 0.0
        sq = math.sqrt(disc)
        root0 = (-b - sq) / (2.0 * a)
        root1 = (-b + sq) / (2.0 * a)
        nroots = 2
    low = mean2 if mean2 < mean1 else mean1
    high = mean2 if mean2 > mean1 else mean1
    middle = 0.5 * (mean1 + mean2)
    found = False
    best = 0.0
    for j in range(nroots):
        r = root0 if j == 0 else root1
        if low < r < high:
            if not found:
                best = r
                found = True
            elif abs(r - middle) < abs(best - middle):
                best = r
    return found, best


@njit(cache=True)
def choose_split(leaf, slot, st, fs, lf, bufi, buff, bctr):
    """``PartitionTree._try_split`` up to ``split``: the buffer's pairs in ``arrays()`` order,
    ``choose_split`` (eqs. 12-13); returns (dimension, value), dimension -1 for None."""
    if st[I_NLEAVES] >= st[C_MAX_LEAVES]:
        return -1, 0.0
    lo0 = lf[leaf, LF_LO0]
    lo1 = lf[leaf, LF_LO1]
    hi0 = lf[leaf, LF_HI0]
    hi1 = lf[leaf, LF_HI1]
    rw0 = fs[F_RW0]
    rw1 = fs[F_RW1]
    mw0 = rw0 * fs[F_MIN_FRACTION]
    mw1 = rw1 * fs[F_MIN_FRACTION]
    el0 = (hi0 - lo0) >= 2.0 * mw0
    el1 = (hi1 - lo1) >= 2.0 * mw1
    if not (el0 or el1):
        return -1, 0.0
    capacity = buff.shape[1]
    count = bctr[slot, B_COUNT]
    head = bctr[slot, B_HEAD]
    n1 = 0
    n2 = 0
    for i in range(count):
        j = i if count < capacity else (i + head) % capacity
        e = buff[slot, j]
        if e > 0.0:
            n1 += 1
        elif e < 0.0:
            n2 += 1
    if n1 < 2 or n2 < 2:
        return -1, 0.0
    pos = np.empty((n1, 2), dtype=np.float64)
    neg = np.empty((n2, 2), dtype=np.float64)
    a = 0
    b = 0
    for i in range(count):
        j = i if count < capacity else (i + head) % capacity
        e = buff[slot, j]
        if e > 0.0:
            pos[a, 0] = bufi[slot, 2 * j]
            pos[a, 1] = bufi[slot, 2 * j + 1]
            a += 1
        elif e < 0.0:
            neg[b, 0] = bufi[slot, 2 * j]
            neg[b, 1] = bufi[slot, 2 * j + 1]
            b += 1
    r0 = hi0 - lo0
    r1 = hi1 - lo1
    if st[C_ROOT_NORM]:
        r0 = r0 / rw0 if rw0 > 0.0 else 0.0
        r1 = r1 / rw1 if rw1 > 0.0 else 0.0
    raw0 = 0.0
    raw1 = 0.0
    for c in range(2):  # t_statistics without the range weight
        m1, v1 = column_stats(pos, c)
        m2, v2 = column_stats(neg, c)
        gap = abs(m1 - m2)
        spread = math.sqrt(v1 / n1 + v2 / n2)
        t = gap / spread if spread > 0.0 else (math.inf if gap > 0 else 0.0)
        if c == 0:
            raw0 = t
        else:
            raw1 = t
    min_t = fs[F_MIN_T]
    if min_t > 0.0 and not ((el0 and raw0 >= min_t) or (el1 and raw1 >= min_t)):
        return -1, 0.0
    t0 = r0 * raw0 if el0 else -math.inf
    t1 = r1 * raw1 if el1 else -math.inf
    if math.isnan(t0):
        dim = 0
    elif math.isnan(t1):
        dim = 1
    else:
        dim = 1 if t1 > t0 else 0
    low = lo0 if dim == 0 else lo1
    high = hi0 if dim == 0 else hi1
    margin = mw0 if dim == 0 else mw1
    m1, v1 = vector_stats(pos, dim)
    m2, v2 = vector_stats(neg, dim)
    found = False
    point = 0.0
    if not st[C_MIDPOINT]:
        found, point = density_crossing(m1, v1, n1, m2, v2, n2)
    if not found:
        point = 0.5 * (m1 + m2)
    floor = low + margin
    if floor > point:
        point = floor
    ceiling = high - margin
    if ceiling < point:
        point = ceiling
    return dim, point


@njit(cache=True)
def split_leaf(
    leaf,
    dim,
    value,
    st,
    fs,
    li,
    lf,
    q,
    visits,
    counts,
    fifo,
    bufi,
    buff,
    bctr,
    bsum,
    free,
    dirty,
    log,
):
    """``PartitionTree.split`` with the children's samples, ``SMDPAgent._grow`` and the
    strategy's ``on_split``. Returns the slot of a child buffer whose ring wrapped (the driver
    must set its exact sums), else -1."""
    first = st[I_NIDS]
    capacity = buff.shape[1]
    slot = li[leaf, L_SLOT]
    count = bctr[slot, B_COUNT]
    head = bctr[slot, B_HEAD]
    # the pairs in arrays() order, before the parent's slot is freed
    xs = np.empty((count, 2), dtype=np.float64)
    es = np.empty(count, dtype=np.float64)
    for i in range(count):
        j = i if count < capacity else (i + head) % capacity
        xs[i, 0] = bufi[slot, 2 * j]
        xs[i, 1] = bufi[slot, 2 * j + 1]
        es[i] = buff[slot, j]
    li[leaf, L_DIM] = dim
    lf[leaf, LF_THRESHOLD] = value
    li[leaf, L_LEFT] = first
    for c in range(2):
        child = first + c
        li[child, L_DIM] = -1
        li[child, L_LEFT] = -1
        li[child, L_PARENT] = leaf
        li[child, L_DEPTH] = li[leaf, L_DEPTH] + 1
        li[child, L_SLOT] = -1
        li[child, L_TABU_MASK] = 0
        li[child, L_EPS_HAS] = 0
        li[child, L_COUNTS_HAS] = 0
        li[child, L_DIRTY] = 0
        lf[child, LF_THRESHOLD] = 0.0
        lf[child, LF_EPS] = 0.0
        lf[child, LF_LO0] = lf[leaf, LF_LO0]
        lf[child, LF_LO1] = lf[leaf, LF_LO1]
        lf[child, LF_HI0] = lf[leaf, LF_HI0]
        lf[child, LF_HI1] = lf[leaf, LF_HI1]
    lf[first, LF_HI0 + dim] = value
    lf[first + 1, LF_LO0 + dim] = value
    free_slot(leaf, st, li, free)
    add_log(LOG_SPLIT, leaf, st, log)
    st[I_NIDS] = first + 2
    st[I_NLEAVES] += 1
    pending = -1
    if st[C_INHERIT_SAMPLES]:
        left = np.empty(count, dtype=np.int64)
        right = np.empty(count, dtype=np.int64)
        nl = 0
        nr = 0
        for i in range(count):
            if xs[i, dim] < value:
                left[nl] = i
                nl += 1
            else:
                right[nr] = i
                nr += 1
        for c in range(2):
            rows = left if c == 0 else right
            m = nl if c == 0 else nr
            if m == 0:
                continue
            child = first + c
            cslot = alloc_slot(child, st, li, bufi, buff, bctr, bsum, free, log)
            ces = np.empty(m, dtype=np.float64)
            for i in range(m):
                ces[i] = es[rows[i]]
            r = buffer_add(cslot, xs, rows, 0, ces, 0, 0, m, bufi, buff, bctr, bsum)
            if r < 0:  # all pairs went this way and filled the ring: sums from NumPy
                pending = cslot
    # SMDPAgent._grow
    actions = st[C_ACTIONS]
    for c in range(2):
        child = first + c
        for a in range(actions):
            q[child, a] = q[leaf, a] if st[C_INHERIT_Q] else fs[F_Q_INIT]
            visits[child, a] = 0 if st[C_RESET_COUNTS] else visits[leaf, a]
        mark_dirty(child, st, li, dirty)
    mark_dirty(leaf, st, li, dirty)
    # the base strategy's on_split
    strategy = st[C_STRATEGY]
    if strategy == S_ADAPTIVE:
        had = li[leaf, L_COUNTS_HAS] and li[leaf, L_EPS_HAS]
        li[leaf, L_COUNTS_HAS] = 0
        li[leaf, L_EPS_HAS] = 0
        if st[C_STRATEGY_INHERIT] and had:
            for c in range(2):
                child = first + c
                for a in range(actions):
                    counts[child, a] = counts[leaf, a]
                lf[child, LF_EPS] = lf[leaf, LF_EPS]
                li[child, L_COUNTS_HAS] = 1
                li[child, L_EPS_HAS] = 1
                add_log(LOG_COUNTS, child, st, log)
                add_log(LOG_EPS, child, st, log)
    elif strategy == S_VDBE:
        had = li[leaf, L_EPS_HAS]
        li[leaf, L_EPS_HAS] = 0
        if st[C_STRATEGY_INHERIT] and had:
            for c in range(2):
                child = first + c
                lf[child, LF_EPS] = lf[leaf, LF_EPS]
                li[child, L_EPS_HAS] = 1
                add_log(LOG_EPS, child, st, log)
    if st[C_TABU] and li[leaf, L_TABU_MASK]:  # Tabu.on_split, _set_entries, _trim
        ring = fifo.shape[0]
        length = st[I_TABU_LEN]
        kept = np.empty((2 * length, 2), dtype=np.int64)
        m = 0
        for j in range(length):
            e = (st[I_TABU_HEAD] + j) % ring
            owner = fifo[e, 0]
            action = fifo[e, 1]
            if owner != leaf:
                kept[m, 0] = owner
                kept[m, 1] = action
                m += 1
            elif st[C_TABU_INHERIT]:
                for c in range(2):
                    kept[m, 0] = first + c
                    kept[m, 1] = action
                    m += 1
        li[leaf, L_TABU_MASK] = 0
        if st[C_TABU_INHERIT]:
            li[first, L_TABU_MASK] = 0
            li[first + 1, L_TABU_MASK] = 0
            for j in range(m):
                li[kept[j, 0], L_TABU_MASK] |= 1 << kept[j, 1]
        for j in range(m):
            fifo[j, 0] = kept[j, 0]
            fifo[j, 1] = kept[j, 1]
        st[I_TABU_HEAD] = 0
        st[I_TABU_LEN] = m
        tabu_trim(st, li, fifo)
        st[I_TABU_DIRTY] = 1
    return pending


@njit(cache=True)
def record(
    st, fs, li, lf, q, visits, counts, fifo, xs, errs, bufi, buff, bctr, bsum, free, dirty, log
):
    """``partition.record(leaf, xs[start:end], errs[:end - start])`` and, after a split,
    ``SMDPAgent._grow``; resumable (``st[I_REC_STAGE]``). Returns 0 when done (``st[I_SPLIT]``
    says whether it split), EV_SUMS when NumPy's exact sums of ``st[I_SUM_SLOT]`` are needed,
    EV_PY_TAIL when ``split`` would raise (the driver lets the reference raise it)."""
    leaf = st[I_REC_LEAF]
    start = st[I_REC_START]
    n = st[I_REC_END] - start
    stage = st[I_REC_STAGE]
    if stage == 0:
        slot = li[leaf, L_SLOT]
        if slot < 0:
            slot = alloc_slot(leaf, st, li, bufi, buff, bctr, bsum, free, log)
        r = buffer_add(slot, xs, None, start, errs, 0, st[I_ADD_K], n, bufi, buff, bctr, bsum)
        if r < 0:
            st[I_ADD_K] = -r
            st[I_SUM_SLOT] = slot
            return EV_SUMS
        stage = 1
    if stage == 1:
        st[I_REC_STAGE] = 3
        st[I_SPLIT] = 0
        slot = li[leaf, L_SLOT]
        count = bctr[slot, B_COUNT]
        if count < st[C_BUFFER_CAP]:
            return 0
        mean = bsum[slot, 0] / count
        v = bsum[slot, 1] / count - mean * mean
        variance = v if v > 0.0 else 0.0
        dim = -1
        value = 0.0
        if (
            count >= st[C_BUFFER_CAP]
            and abs(mean) < fs[F_MAX_ABS_MEAN]
            and variance > fs[F_MIN_VARIANCE]
        ):
            dim, value = choose_split(leaf, slot, st, fs, lf, bufi, buff, bctr)
        if dim < 0:  # buf.clear()
            bctr[slot, B_COUNT] = 0
            bctr[slot, B_HEAD] = 0
            bsum[slot, 0] = 0.0
            bsum[slot, 1] = 0.0
            return 0
        low = lf[leaf, LF_LO0 + dim]
        high = lf[leaf, LF_HI0 + dim]
        if not low < value < high:
            st[I_SPLIT_DIM] = dim
            fs[F_SPLIT_VALUE] = value
            return EV_PY_TAIL
        st[I_SPLIT] = 1
        pending = split_leaf(
            leaf,
            dim,
            value,
            st,
            fs,
            li,
            lf,
            q,
            visits,
            counts,
            fifo,
            bufi,
            buff,
            bctr,
            bsum,
            free,
            dirty,
            log,
        )
        if pending >= 0:
            st[I_REC_STAGE] = 2
            st[I_SUM_SLOT] = pending
            return EV_SUMS
    return 0


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
    log,
):
    """``SMDPAgent._end_epoch`` for the inputs ``xs[start:end]``: eqs. (9)-(10), the strategy's
    hooks and, when the leaf's buffer takes the pairs without a split test, the record.

    Returns 0 (recorded, no split possible), 1 (the split test must run: the errors are in
    ``errs[:end - start]``) or 2 (no room in the log, the slot pool or the id table: nothing
    was changed, the driver must grow them).
    """
    n = end - start
    records = st[C_RECORDS]
    if st[I_NLOG] + LOG_ROOM > log.shape[0] or (
        records and (st[I_NFREE] < 3 or st[I_NIDS] + 2 > li.shape[0])
    ):
        return 2
    slot = li[leaf, L_SLOT]
    count = 0
    head = 0
    in_kernel = False
    if records:
        if slot >= 0:
            count = bctr[slot, B_COUNT]
            head = bctr[slot, B_HEAD]
        in_kernel = head + n < st[C_BUFFER_CAP] and count + n < st[C_BUFFER_CAP]
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
            add_log(LOG_COUNTS, leaf, st, log)
        counts[leaf, action] += 1
        lf[leaf, LF_EPS] = adaptive_epsilon(
            counts, leaf, actions, new - old, fs[F_CN], fs[F_CH], st[C_VARIANT]
        )
        if not li[leaf, L_EPS_HAS]:
            li[leaf, L_EPS_HAS] = 1
            add_log(LOG_EPS, leaf, st, log)
    elif strategy == S_VDBE:
        previous = lf[leaf, LF_EPS] if li[leaf, L_EPS_HAS] else 1.0
        decay = math.exp(-abs(new - old) / fs[F_SIGMA])
        f = 1.0 - decay if st[C_VARIANT] else (1.0 - decay) / (1.0 + decay)
        delta = fs[F_DELTA]
        lf[leaf, LF_EPS] = delta * f + (1.0 - delta) * previous
        if not li[leaf, L_EPS_HAS]:
            li[leaf, L_EPS_HAS] = 1
            add_log(LOG_EPS, leaf, st, log)
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
        slot = alloc_slot(leaf, st, li, bufi, buff, bctr, bsum, free, log)
    buffer_add(slot, xs, None, start, errs, 0, 0, n, bufi, buff, bctr, bsum)
    return 0


@njit(cache=True, inline="always")
def certified_free(x0, y0, x1, y1, fs, cells, bounds_c, bounds_r, pieces):
    """``World.certified_free``: 1 proved free, 0 not proved, 2 the safe ball does not hold the
    move and (x0, y0)'s cell is unseen here (the world's own ``certified_free`` goes on to the
    cell's bounds), -1 undecided here (a cell outside the table, a comparison within the
    margin)."""
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
        return 2
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
    free and the goal test certain), 2 or 3 when only Python can decide the collision or the
    goal (the move is in ``fs[F_SW_X0:F_SW_Y1 + 1]``: the driver's sweep answers
    ``World.sweep_collides`` on it, as ``step`` does, and :func:`finish_step` completes the
    step; 3: :func:`certified_free` found it not proved free on a known cell, 4: outside the
    safe ball on an unseen cell; the sweep's ``known`` is the code - 2), 0 when
    ``env.step`` itself must take it (a new noise block, the checker's first steps). Only 1
    changes state.
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
    free = certified_free(x0, y0, x1, y1, fs, cells, bounds_c, bounds_r, pieces)
    if free == 1:
        success = hypot_le(x1 - fs[F_GX], y1 - fs[F_GY], fs[F_GR])
    if success < 0:
        fs[F_SW_X0] = x0
        fs[F_SW_Y0] = y0
        fs[F_SW_X1] = x1
        fs[F_SW_Y1] = y1
        return 3 if free == 0 else (4 if free == 2 else 2)
    st[I_COLLIDED] = 0
    st[I_SUCCESS] = success
    fs[F_OX] = x1
    fs[F_OY] = y1
    finish_step(st, fs)
    return 1


@intrinsic
def call_sweep(typingctx, address, x0, y0, x1, y1, known):
    """Call the SWEEP_CALLBACK at ``address`` (an int64) with the move and ``known``: the
    driver stores its callback's address in ``st[I_SWEEP]`` instead of passing the ctypes
    object, whose unboxing cost several us at every call of :func:`run_pooled`."""
    signature = types.int64(
        types.int64, types.float64, types.float64, types.float64, types.float64, types.int64
    )

    def codegen(context, builder, sig, args):
        double, int64 = ir.DoubleType(), ir.IntType(64)
        function = ir.FunctionType(int64, [double, double, double, double, int64])
        pointer = builder.inttoptr(args[0], function.as_pointer())
        return builder.call(pointer, args[1:])

    return signature, codegen


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
    log,
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
                elif code >= 2:
                    result = call_sweep(
                        st[I_SWEEP], fs[F_SW_X0], fs[F_SW_Y0], fs[F_SW_X1], fs[F_SW_Y1], code - 2
                    )
                    if result < 0:
                        st[I_PHASE] = PH_STEP
                        return EV_CALLBACK_ERROR
                    collided = result & 1
                    st[I_COLLIDED] = collided
                    st[I_SUCCESS] = result >> 1
                    fs[F_OX] = fs[F_SW_X0] if collided else fs[F_SW_X1]
                    fs[F_OY] = fs[F_SW_Y0] if collided else fs[F_SW_Y1]
                    st[I_PY_STEPS] += 1
                    finish_step(st, fs)
                else:
                    st[I_PHASE] = PH_STEP_RESULT
                    return EV_PY_STEP
            elif phase == PH_SWEEP_RESULT:
                st[I_PY_STEPS] += 1
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
                        log,
                    )
                    if code == 2:
                        return EV_POOL
                    if code == 1:
                        st[I_REC_LEAF] = st[I_LEAF]
                        st[I_REC_START] = 0
                        st[I_REC_END] = n
                        if st[C_KREC]:
                            st[I_REC_STAGE] = 0
                            st[I_ADD_K] = 0
                            st[I_PHASE] = PH_RECORD
                            continue
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
                        log,
                    )
                    if code == 2:
                        return EV_POOL
                    if code == 1:
                        st[I_REC_LEAF] = leaf
                        st[I_REC_START] = start
                        st[I_REC_END] = end
                        st[I_HE] = end
                        if st[C_KREC]:
                            st[I_REC_STAGE] = 0
                            st[I_ADD_K] = 0
                            st[I_PHASE] = PH_RECORD
                            break
                        st[I_PHASE] = PH_END_RESUME
                        return EV_RECORD
                    st[I_HS] = end
                if st[I_PHASE] == PH_RECORD:
                    continue
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
        elif phase == PH_RECORD:
            code = record(
                st,
                fs,
                li,
                lf,
                q,
                visits,
                counts,
                fifo,
                xs,
                errs,
                bufi,
                buff,
                bctr,
                bsum,
                free,
                dirty,
                log,
            )
            if code != 0:
                return code
            st[I_PHASE] = PH_END_RESUME
        else:
            return EV_DONE


# -- One call, few arguments ----------------------------------------------------------------

POOLED_INT = (
    "st",
    "li",
    "visits",
    "counts",
    "fifo",
    "grid_i",
    "held",
    "bctr",
    "free",
    "dirty",
    "log",
    "cells",
    "bounds_r",
)
POOLED_FLOAT = (
    "fs",
    "lf",
    "q",
    "ubuf",
    "grid_f",
    "xs",
    "rs",
    "errs",
    "bufi",
    "buff",
    "bsum",
    "moves",
    "noise",
    "bounds_c",
    "pieces",
)
"""The arrays :func:`run_pooled` takes as views of two pools (row i of ``lay`` for the i-th of
POOLED_INT + POOLED_FLOAT: offset, rows, columns), in this order: numba's dispatch costs per
array argument, and the kernel returns to Python for every pybullet sweep."""


@intrinsic
def address(typingctx, pool, offset):
    """A pointer to ``pool[offset]`` (a C-contiguous 1-d array, ``0 <= offset <= pool.size``)."""
    signature = types.CPointer(pool.dtype)(pool, offset)

    def codegen(context, builder, sig, args):
        array = context.make_array(sig.args[0])(context, builder, value=args[0])
        return builder.gep(array.data, [args[1]])

    return signature, codegen


@njit(cache=True, inline="always")
def view1(pool, lay, i):
    """Row i of ``lay`` as a 1-d view of ``pool`` that numba does not reference-count: an
    array made by ``carray`` has no meminfo, so every incref and decref the kernel's inlined
    helpers make of it is a null test instead of an atomic add (they were about a tenth of
    the fast loop's time). ``pool`` outlives the call (the driver holds it)."""
    return carray(address(pool, lay[i, 0]), lay[i, 1])


@njit(cache=True, inline="always")
def view2(pool, lay, i):
    """Row i of ``lay`` as a 2-d C-contiguous view of ``pool`` (see :func:`view1`)."""
    return carray(address(pool, lay[i, 0]), (lay[i, 1], lay[i, 2]))


@njit(cache=True)
def run_pooled(ipool, fpool, lay):
    """:func:`run_episode` on the pools' views."""
    f = len(POOLED_INT)
    return run_episode(
        view1(ipool, lay, 0),  # st
        view1(fpool, lay, f),  # fs
        view2(ipool, lay, 1),  # li
        view2(fpool, lay, f + 1),  # lf
        view2(fpool, lay, f + 2),  # q
        view2(ipool, lay, 2),  # visits
        view2(ipool, lay, 3),  # counts
        view2(ipool, lay, 4),  # fifo
        view1(fpool, lay, f + 3),  # ubuf
        view2(fpool, lay, f + 4),  # grid_f
        view2(ipool, lay, 5),  # grid_i
        view2(fpool, lay, f + 5),  # xs
        view1(fpool, lay, f + 6),  # rs
        view1(ipool, lay, 6),  # held
        view1(fpool, lay, f + 7),  # errs
        view2(fpool, lay, f + 8),  # bufi
        view2(fpool, lay, f + 9),  # buff
        view2(ipool, lay, 7),  # bctr
        view2(fpool, lay, f + 10),  # bsum
        view1(ipool, lay, 8),  # free
        view1(ipool, lay, 9),  # dirty
        view2(ipool, lay, 10),  # log
        view2(fpool, lay, f + 11),  # moves
        view1(fpool, lay, f + 12),  # noise
        view2(ipool, lay, 11),  # cells
        view2(fpool, lay, f + 13),  # bounds_c
        view2(ipool, lay, 12),  # bounds_r
        view2(fpool, lay, f + 14),  # pieces
    )
