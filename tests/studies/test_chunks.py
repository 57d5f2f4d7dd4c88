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
    # least 0.6 s (its start at most START_SHARE of it)
    for n, expected in (
        (40, [20, 20]),  # 2 cold starts, not the 9 of the guided cut alone
        (60, [15, 15, 15, 15]),
        (100, [17, 17, 17, 17, 16, 16]),
    ):
        costs = np.full(n, 0.045)
        bounds = chunks.chunk_bounds(costs, workers=2, start_costs=chunks.COLD_START_POINTS * costs)
        assert np.diff(bounds).tolist() == expected, n
    costs = np.full(400, 0.045)
    sizes = np.diff(chunks.chunk_bounds(costs, workers=2, start_costs=2 * costs))
    # the guided cut's 1 s chunks, then equal chunks for each worker, none smaller than the floor's 14 points
    assert (sizes[:13] == 23).all() and len(sizes[13:]) % 2 == 0
    assert sizes[13:].max() - sizes[13:].min() <= 1 and sizes.min() >= 14
    assert (np.diff(sizes) <= 0).all()
    # four workers: the 100 points in 8 equal chunks, each worker two
    sizes = np.diff(chunks.chunk_bounds(np.full(100, 0.045), workers=4, start_costs=np.full(100, 0.09)))
    assert len(sizes) == 8 and sizes.max() - sizes.min() <= 1
    # fewer points than a chunk's floor on each worker: still one chunk each
    assert np.diff(chunks.chunk_bounds(np.full(10, 0.045), workers=2, start_costs=np.full(10, 0.09))).tolist() == [
        5,
        5,
    ]


def test_no_start_cost_cuts_as_before():
    # closed forms and bare-wheel NLPs start no warmer within a chunk: their cut is the guided one
    for costs in (np.full(60, 0.1), np.full(24, 0.01), np.full(1000, 2e-6)):
        alone = chunks.chunk_bounds(costs, workers=2)
        assert (chunks.chunk_bounds(costs, workers=2, start_costs=np.zeros(len(costs))) == alone).all()
    # a start cost below MIN_CHUNK_SECONDS * START_SHARE sets no floor above MIN_CHUNK_SECONDS
    costs = np.full(60, 0.1)
    small = np.full(60, 0.5 * chunks.MIN_CHUNK_SECONDS * chunks.START_SHARE)
    assert (chunks.chunk_bounds(costs, workers=2, start_costs=small) == chunks.chunk_bounds(costs, workers=2)).all()
