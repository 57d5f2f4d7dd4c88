"""The ranking rule: its vectorized form (sweeps) and its plain form (one solve) agree, ties included."""

import numpy as np

from flyopt.design import rank


def test_vectorized_and_plain_rule_pick_the_same_winner():
    rng = np.random.default_rng(7)
    n_groups, per = 300, 6
    group = np.repeat(np.arange(n_groups), per)
    n = group.size
    base = rng.uniform(1, 2, n)
    tie = rng.random(n) < 0.5  # exact and round-off ties are common
    objective = np.where(tie, np.repeat(base[::per], per) * (1 + rng.uniform(-1e-12, 1e-12, n)), base)
    cost = np.where(rng.random(n) < 0.3, np.nan, rng.choice([3.0, 3.0 * (1 + 1e-13), 5.0], n))
    mass = np.where(rng.random(n) < 0.5, objective, rng.uniform(1, 2, n))
    speed = rng.choice([30.0, 36.0, 50.0], n)
    material = rng.choice(["cast_steel", "cast_iron", "ductile_iron"], n).astype(object)
    shaft = rng.choice(["crank", "motor"], n).astype(object)
    best = rank.winners(group, objective, cost, mass, speed, material, shaft)  # numpy path (many groups)
    for g in range(n_groups):
        rows = np.flatnonzero(group == g)
        one = rank.winners(
            np.zeros(per, dtype=np.int64),
            objective[rows],
            cost[rows],
            mass[rows],
            speed[rows],
            material[rows],
            shaft[rows],
        )[0]  # plain path (one group)
        assert rows[one] == best[g], g


def test_exact_tie_goes_to_the_cheaper_then_the_name():
    # a disc at its envelope: the same mass whatever the density
    assert (
        rank.winners(
            [0, 0],
            [10.0, 10.0],
            [np.nan, 40.0],
            [10.0, 10.0],
            [30.0, 30.0],
            ["cast_iron", "cast_steel"],
            ["crank", "crank"],
        )[0]
        == 1
    )
    assert (
        rank.winners(
            [0, 0],
            [10.0, 10.0 * (1 + 1e-12)],
            [np.nan, np.nan],
            [10.0, 10.0],
            [30.0, 30.0],
            ["cast_steel", "cast_iron"],
            ["crank", "crank"],
        )[0]
        == 1
    )


def test_ranking_is_the_rule_applied_place_by_place():
    # reference: the winner of what is left, by rank.winners, one place at a time
    from types import SimpleNamespace

    rng = np.random.default_rng(11)
    for _ in range(400):
        n = int(rng.integers(1, 9))
        apart = rng.random() < 0.5  # objectives clearly apart (one sort) or with ties (place by place)
        objective = rng.uniform(1, 2, n) if apart else rng.choice([1.0, 1.0 * (1 + 1e-12), 1.5, 2.0], n)
        candidates = [
            SimpleNamespace(
                objective=float(objective[k]),
                cost=None if rng.random() < 0.3 else float(rng.choice([3.0, 5.0])),
                mass=float(rng.choice([1.0, 2.0])),
                stresses=SimpleNamespace(rim_speed=float(rng.choice([30.0, 36.0]))),
                material=str(rng.choice(["cast_iron", "cast_steel"])),
                shaft=f"s{k}",
            )
            for k in range(n)
        ]
        left, expected = list(candidates), []
        while left:
            k = rank.winners(
                np.zeros(len(left), dtype=np.int64),
                [c.objective for c in left],
                [np.nan if c.cost is None else c.cost for c in left],
                [c.mass for c in left],
                [c.stresses.rim_speed for c in left],
                [c.material for c in left],
                [c.shaft for c in left],
            )[0]
            expected.append(left.pop(k))
        assert [c.shaft for c in rank.ranking(candidates)] == [c.shaft for c in expected]
