"""Cutting a sweep's points into chunks, sized by what they cost.

Chunks are sized by what they cost (:func:`chunk_bounds`): each takes at
most :data:`CHUNK_SECONDS` by the sweep's estimate and at most
1/(:data:`GUIDED` × workers) of what is left, down to
:data:`MIN_CHUNK_SECONDS`, so a 60-point sweep of a scene whose every point
needs a periodic solution is spread over the workers, the last chunks are
small enough that the workers finish together (also when the points near
the end cost more than the estimate says), and a 10⁶-point closed-form sweep
is not cut into a million pieces. Points that share a physics stay in one
chunk where they can (their analysis is then made once).
"""

from __future__ import annotations

import math
from collections.abc import Iterable

import numpy as np
from numpy.typing import ArrayLike

__all__ = [
    "CHUNK_SECONDS",
    "COLD_START_POINTS",
    "GUIDED",
    "IN_FLIGHT_PER_WORKER",
    "MAX_CHUNK_POINTS",
    "MIN_CHUNK_SECONDS",
    "SECONDS_CLOSED_FORM",
    "SECONDS_DESCRIBED",
    "SECONDS_IPOPT",
    "SECONDS_WHOLE_WHEEL",
    "SERIAL_SECONDS",
    "START_SHARE",
    "chunk_bounds",
]

#: Longest estimated time of one chunk [s] in one process: long enough that the cost of a
#: chunk (sending it, saving its part, ~5-10 ms) is small, short enough that a crash or
#: Ctrl-C loses little.
CHUNK_SECONDS = 1.0
#: Guided cutting: a chunk takes at most 1 / (GUIDED * workers) of the estimated time left,
#: so chunks shrink towards the end and the workers finish together.
GUIDED = 2
#: Shortest estimated time of a chunk [s] (one point at least): its cost in a worker process
#: (~2 ms to send it and its results) stays a few percent.
MIN_CHUNK_SECONDS = 0.05
#: Most points in one chunk: bounds the memory of a chunk's arrays (~10 MB for 10,000
#: points of 9 combinations).
MAX_CHUNK_POINTS = 10_000
#: Under workers="auto" a sweep estimated to take less than this in one process
#: runs serially: starting worker processes (0.05 s forked, ~2 s from a fresh
#: forkserver) and shipping the chunks would cost more than it saves.
SERIAL_SECONDS = 1.0
#: Estimated cost of one combination [s]: closed form (measured ~1 µs) and IPOPT
#: (measured ~2 ms per NLP, benchmarks/results/design.md).
SECONDS_CLOSED_FORM = 2e-6
SECONDS_IPOPT = 2.5e-3
#: Estimated cost of one combination of a whole wheel (rim_web, rim_arms) [s]: its NLP, the stress settling
#: and the rounding (benchmarks/results/sweep_estimate.md: 1.6 ms a combination on punch-press-wheel, whose
#: bounds prune most; 7.7 ms a combination and arm count on press-arms-wheel).
SECONDS_WHOLE_WHEEL = 5e-3
#: Estimated cost of one combination of a scene whose shaft is described [s]: ``flyopt solve``'s design with
#: the shaft's post-check and the key's forced response (benchmarks/results/sweep_estimate.md: 15-19 ms).
SECONDS_DESCRIBED = 12e-3
#: Chunks sent to each worker process at a time (one running, one waiting).
IN_FLIGHT_PER_WORKER = 2
#: What a chunk's first whole-wheel point costs beyond the others, in points: it starts each NLP without a
#: neighbour's wheel (20-30 ms against 9 ms warm on punch-press-wheel, benchmarks/results/wheel.md).
COLD_START_POINTS = 2.0
#: Most of a chunk its start may take (:func:`chunk_bounds`' ``start_costs``): a chunk is at least its start
#: over this, so a 40-point sweep of whole wheels on 2 workers runs as 2 chunks, not 9 with 9 cold starts.
START_SHARE = 0.15


def chunk_bounds(
    costs: ArrayLike,
    *,
    workers: int = 1,
    starts: ArrayLike | None = None,
    breaks: Iterable[int] | None = None,
    chunk_size: int | None = None,
    start_costs: ArrayLike | None = None,
) -> np.ndarray:
    """Where to cut a sweep's points (in the order they run) into chunks.

    Parameters
    ----------
    costs : array_like of float
        Estimated time of each point in one process [s], in run order (a
        point that needs a new analysis carries its cost).
    workers : int
        Workers the chunks are for.
    starts : array_like of bool, optional
        Where a cut may fall without splitting points that share work (the
        first point of each physics); default: anywhere.
    breaks : array_like of int, optional
        Positions where a chunk must end (e.g. the ends of blocks whose rows
        are put back in point order together).
    chunk_size : int, optional
        Points per chunk, as given by the user: cuts every ``chunk_size``
        points (and at ``breaks``), whatever the costs.
    start_costs : array_like of float, optional
        What a chunk starting at each point costs beyond ``costs`` [s] (its
        whole wheels solved cold); default none.

    Returns
    -------
    ndarray of int
        ``[0, b1, ..., n]``: chunk ``k`` holds the points ``bounds[k]:bounds[k+1]``.

    Notes
    -----
    Guided self-scheduling: a chunk aims at ``R / (GUIDED * workers)`` of the
    estimated time ``R`` still to cut, within [:data:`MIN_CHUNK_SECONDS`,
    :data:`CHUNK_SECONDS`], and holds at most :data:`MAX_CHUNK_POINTS`
    points. Where a chunk's start cost sets a higher floor than
    :data:`MIN_CHUNK_SECONDS` (the dearest start still to come over
    :data:`START_SHARE`), the chunks stop shrinking near it: what is left once
    the aim falls below twice that floor is cut into equal chunks (by cost:
    fixed ends, which a break or a group may move), each at most the aim of the
    chunk before it (or :data:`CHUNK_SECONDS`) and at least the floor where that
    still gives each worker one, and as many as make all the chunks a multiple
    of the workers (fewer where the chunk before allows larger ones, else
    more): the last round gives each worker one, without small chunks' cold
    starts. A cut that would split a group of ``starts`` moves to the group's
    end when the chunk then stays within twice its aim, else to the group's
    start; a chunk of one group is split only where the group's points after
    its first (its designs, without its analysis) exceed twice the aim.
    """
    costs = np.asarray(costs, dtype=float)
    n = len(costs)
    ends = sorted({int(b) for b in (breaks if breaks is not None else ()) if 0 < b < n} | {n})
    if n == 0:
        return np.array([0], dtype=np.int64)
    if chunk_size is not None:
        bounds, start = [0], 0
        for end in ends:
            bounds.extend(range(start + chunk_size, end, chunk_size))
            bounds.append(end)
            start = end
        return np.array(bounds, dtype=np.int64)
    cum = np.concatenate([[0.0], np.cumsum(costs)])
    # a chunk may start on any of the structures still to come (each of its NLPs starts cold once in it): the
    # dearest start at or after each point
    first = np.zeros(n) if start_costs is None else np.asarray(start_costs, dtype=float)
    dearest = np.maximum.accumulate(first[::-1])[::-1]
    n_workers = max(workers, 1)
    share = GUIDED * n_workers
    group = None if starts is None else np.flatnonzero(np.asarray(starts, dtype=bool))
    bounds, start, block = [0], 0, 0
    last_aim = CHUNK_SECONDS
    edges = None  # where the equal last chunks end, in cumulative cost, once the start costs hold the cut up
    while start < n:
        while ends[block] <= start:
            block += 1
        limit = min(ends[block], start + MAX_CHUNK_POINTS)
        left = cum[-1] - cum[start]
        floor = min(CHUNK_SECONDS, dearest[start] / START_SHARE)
        if edges is None and floor > MIN_CHUNK_SECONDS and left / share < 2 * floor:
            # as many equal chunks as leave each at least the floor, none above the chunk before, a multiple of
            # the workers counting the chunks cut so far (the last round of chunks gives each worker one)
            count = n_workers * max(
                1, int(left / (n_workers * floor) * (1 + 1e-9)), math.ceil(left / (n_workers * last_aim) * (1 - 1e-9))
            )
            over = (len(bounds) - 1 + count) % n_workers  # fewer and larger where the chunk before allows
            count += -over if over and left / (count - over) <= last_aim * (1 + 1e-9) else -over % n_workers
            edges = cum[start] + left * np.arange(1, count + 1) / count
            edges[-1] = cum[-1]
            step = left / count
        if edges is not None:
            aim = edges[int(np.searchsorted(edges, cum[start] + 1e-9 * step, side="right"))] - cum[start]
        else:
            aim = min(CHUNK_SECONDS, max(MIN_CHUNK_SECONDS, floor, left / share))
            last_aim = aim
        # the first end whose chunk reaches the aim (a relative 1e-9 spares round-off a point)
        end = int(np.searchsorted(cum, cum[start] + aim * (1 - 1e-9), side="left"))
        end = min(max(end, start + 1), limit)
        if group is not None and end < limit:
            k = int(np.searchsorted(group, end, side="right"))  # groups starting after `end`
            begin = int(group[k - 1]) if k else 0  # the group `end` falls in
            if begin != end:
                after = int(group[k]) if k < len(group) else n
                if after <= limit and cum[after] - cum[start] <= 2 * aim:
                    end = after
                elif begin > start:
                    end = begin
                elif after <= limit and cum[after] - cum[start + 1] <= 2 * aim:
                    end = after  # one group: split only where its designs outweigh its analysis
        bounds.append(end)
        start = end
    return np.array(bounds, dtype=np.int64)
