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
