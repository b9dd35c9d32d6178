"""What the sync wrappers' misspelling hint costs on every attribute set.

:class:`j5aio.sync.wrapping.SyncWrapper` routes each attribute set through a Python
``__setattr__`` (so that a misspelt name can be answered with "did you mean"). Measures,
side by side in one run, the median time of a property set on a wrapper and on a plain
``__slots__`` class with the same property, with a no-op setter, so the figure is the
hint's own cost. A facade call that reaches a board costs tens of microseconds (see
``bench_sync_facade.py``); the goal here is under 1 µs added per set. Run::

    python bench/bench_setattr_hint.py [--sets 200000] [--rounds 7]
"""

from __future__ import annotations

import argparse
import statistics
import timeit

from j5aio.sync.wrapping import SyncWrapper

GOAL_NS = 1000.0


class _Wrapper(SyncWrapper):
    __slots__ = ()

    @property
    def power(self) -> float:
        return 0.0

    @power.setter
    def power(self, value: float) -> None:
        pass


class _Plain:
    __slots__ = ("__weakref__", "_core")

    @property
    def power(self) -> float:
        return 0.0

    @power.setter
    def power(self, value: float) -> None:
        pass


def main() -> None:
    """Time both ways, interleaved, and print the medians and their difference."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--sets", type=int, default=200_000)
    parser.add_argument("--rounds", type=int, default=7)
    options = parser.parse_args()
    wrapper, plain = _Wrapper._from_core(object()), _Plain()
    ours: list[float] = []
    floor: list[float] = []
    for _ in range(options.rounds):
        ours.append(timeit.timeit("w.power = 0.5", globals={"w": wrapper}, number=options.sets))
        floor.append(timeit.timeit("p.power = 0.5", globals={"p": plain}, number=options.sets))
    ours_ns = statistics.median(ours) / options.sets * 1e9
    floor_ns = statistics.median(floor) / options.sets * 1e9
    print(f"{options.rounds} rounds x {options.sets} sets; medians in nanoseconds")
    print(f"{'SyncWrapper (with the hint)':<32} {ours_ns:8.0f}")
    print(f"{'plain __slots__ class':<32} {floor_ns:8.0f}")
    added = ours_ns - floor_ns
    verdict = "within" if added <= GOAL_NS else "OVER"
    print(f"added by the hint: {added:.0f} ns ({verdict} the {GOAL_NS:.0f} ns goal); "
          f"ratio {ours_ns / floor_ns:.1f}")


if __name__ == "__main__":
    main()
