"""Tests of flyopt.studies.chunks: a sweep's points cut into chunks by what they cost, physics kept together."""

import numpy as np

from flyopt.studies import chunks


def test_chunk_bounds_by_cost():
    # 60 points of 0.1 s, 2 workers: a chunk takes a quarter of what is left, at most 1 s
    # (10 points), so the chunks shrink towards the end, down to a point
    assert chunks.chunk_bounds(np.full(60, 0.1), workers=2).tolist() == [
        0,
        10,
        20,
        30,
        38,
        44,
        48,
        51,
        54,
        56,
        57,
        58,
        59,
        60,
    ]
    # 10^6 closed-form points: 1 s would be 55,556 points, held to MAX_CHUNK_POINTS
    bounds = chunks.chunk_bounds(np.full(1_000_000, 1.8e-5), workers=2)
    sizes = np.diff(bounds)
    assert sizes.max() == chunks.MAX_CHUNK_POINTS and (sizes[:90] == sizes.max()).all()
    assert 100 < len(sizes) < 110 and sizes[-1] < sizes[-5] < sizes.max()
    # a small sweep: chunks of at least MIN_CHUNK_SECONDS (0.05 s), not of 0.01 s
    assert chunks.chunk_bounds(np.full(24, 0.01), workers=2).tolist() == [0, 6, 11, 16, 21, 24]
    # the user's chunk size, cut again at the breaks
    assert chunks.chunk_bounds(np.ones(10), chunk_size=4, breaks=[6]).tolist() == [0, 4, 6, 10]


def test_chunk_bounds_keep_groups_together():
    # 6 physics of 10 points; the first point of each carries its analysis (0.5 s)
    costs = np.full(60, 1e-3)
    costs[::10] += 0.5
    starts = np.zeros(60, dtype=bool)
    starts[::10] = True
    bounds = chunks.chunk_bounds(costs, workers=2, starts=starts)
    assert bounds.tolist() == [0, 20, 30, 40, 50, 60]  # never a physics in two chunks
    assert chunks.chunk_bounds(costs, workers=2).tolist() == [0, 11, 24, 31, 41, 51, 60]
    # a group whose designs alone outweigh a chunk is split (aim 0.125 s: 12,500 points,
    # held to MAX_CHUNK_POINTS)
    big = chunks.chunk_bounds(np.full(25_000, 1e-5), starts=np.r_[True, np.zeros(24_999, bool)])
    assert big.tolist() == [0, 10_000, 17_500, 25_000]


def test_a_chunks_cold_start_holds_its_size_up_and_the_last_chunks_are_equal():
    # whole wheels: 45 ms a point, a chunk's first point 90 ms more (its NLPs started cold), so a chunk is at
    # least 0.6 s, some 13.3 points (its start at most START_SHARE of it)
    for n, expected in (
        (40, [20, 20]),  # 2 cold starts, not the 9 of the guided cut alone
        (60, [15, 15, 15, 15]),
        (80, [14, 13, 13, 14, 13, 13]),  # 80 / 13.3 = 6 to the last bit: as many as 81 points get
        (81, [14, 13, 14, 13, 14, 13]),
        (100, [17, 17, 16, 17, 17, 16]),
    ):
        costs = np.full(n, 0.045)
        bounds = chunks.chunk_bounds(costs, workers=2, start_costs=chunks.COLD_START_POINTS * costs)
        assert np.diff(bounds).tolist() == expected, n
    for n, workers in ((400, 2), (230, 4), (438, 8), (230, 3)):
        costs = np.full(n, 0.045)
        sizes = np.diff(chunks.chunk_bounds(costs, workers=workers, start_costs=2 * costs))
        guided = int(np.sum(sizes == 23))  # the guided cut's 1 s chunks first
        assert (sizes[:guided] == 23).all() and sizes.sum() == n
        # then equal chunks, none above the chunk before, none below the floor by more than a point's rounding,
        # so many that every worker's last round has one (the least-loaded worker takes the next chunk)
        last = sizes[guided:]
        assert last.max() - last.min() <= 1 and last.max() <= 23 and last.min() >= 13, (n, workers)
        assert len(sizes) % workers == 0, (n, workers)
    # fewer points than a chunk's floor on each worker: still one chunk each
    costs = np.full(10, 0.045)
    assert np.diff(chunks.chunk_bounds(costs, workers=2, start_costs=2 * costs)).tolist() == [5, 5]


def test_a_chunk_is_held_up_by_the_dearest_start_still_to_come():
    # points alternating between a bare wheel (no start cost) and a whole wheel: a chunk starting on either
    # holds both structures and starts each cold once, so the floor is the whole wheel's wherever it starts
    costs = np.full(40, 0.045)
    start_costs = 2 * costs
    start_costs[::2] = 0.0
    assert np.diff(chunks.chunk_bounds(costs, workers=2, start_costs=start_costs)).tolist() == [20, 20]
    # closed-form points first (no start cost), whole wheels after: the closed forms' chunk takes them all
    costs = np.r_[np.full(1000, 2e-6), np.full(40, 0.045)]
    start_costs = np.r_[np.zeros(1000), 2 * costs[1000:]]
    sizes = np.diff(chunks.chunk_bounds(costs, workers=2, start_costs=start_costs))
    assert len(sizes) == 2 and sizes[0] >= 1000
    # a break inside the equal chunks ends one early; the others keep their ends
    costs = np.full(60, 0.045)
    bounds = chunks.chunk_bounds(costs, workers=2, start_costs=2 * costs, breaks=[20])
    assert bounds.tolist() == [0, 15, 20, 30, 45, 60]


def test_no_start_cost_cuts_as_before():
    # closed forms and bare-wheel NLPs start no warmer within a chunk: their cut is the guided one
    for costs in (np.full(60, 0.1), np.full(24, 0.01), np.full(1000, 2e-6)):
        alone = chunks.chunk_bounds(costs, workers=2)
        assert (chunks.chunk_bounds(costs, workers=2, start_costs=np.zeros(len(costs))) == alone).all()
    # a start cost below MIN_CHUNK_SECONDS * START_SHARE sets no floor above MIN_CHUNK_SECONDS
    costs = np.full(60, 0.1)
    small = np.full(60, 0.5 * chunks.MIN_CHUNK_SECONDS * chunks.START_SHARE)
    assert (chunks.chunk_bounds(costs, workers=2, start_costs=small) == chunks.chunk_bounds(costs, workers=2)).all()
