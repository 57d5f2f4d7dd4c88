"""The reduction of a scene to one machine (flyopt.machine.reduce): its memo and its copy at another δ."""

from flyopt.io.scene import load
from flyopt.machine.reduce import reduce


def test_memo_builds_once_and_a_machine_at_another_delta_shares_it():
    machine = reduce(load("problems/punch-press.toml"))
    calls = []

    def build():
        calls.append(1)
        return object()

    first = machine.memo("key", build)
    assert machine.memo("key", build) is first and len(calls) == 1
    other = machine.with_delta(machine.delta / 2)
    assert other.delta == machine.delta / 2 and other.memo("key", build) is first and len(calls) == 1
    assert machine.memo("another key", build) is not first and len(calls) == 2
