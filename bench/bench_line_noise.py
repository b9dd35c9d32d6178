"""Line noise: does every serial board answer again after a long burst of garbage?

Each trial damages one reply with a burst of random bytes (4 to 8 KiB, with or without
line endings, before or after the reply: the request it hit may fail), then asks the
board the same question twice. A *failed recovery* is a trial in which neither of those
two answers is the true one; a *wrong answer* is any answer, in any trial, that is not
the board's true one. Boards and questions are those of ``bench_late_replies.py``.

Goal: 0 failed recoveries and 0 wrong answers per 1,000 bursts, on every board.

Run: ``PYTHONPATH=$PWD python bench/bench_line_noise.py [--trials 1000] [--boards a,b]``
"""

from __future__ import annotations

import argparse
import random

import anyio
from bench_late_replies import CASES, _matches, _quick  # type: ignore[import-not-found]

from j5aio.backends.hardware.transports.memory import SimulatorStream
from j5aio.errors import CommunicationError
from j5aio.testing.transports import FaultyStream


def _burst(rng: random.Random) -> bytes:
    size = rng.randrange(4096, 8192)
    if rng.random() < 0.5:  # no line ending at all: one over-long "line"
        return bytes(rng.choice(range(0x20, 0x7F)) for _ in range(size))
    return bytes(rng.randrange(256) for _ in range(size))


async def run_case(name: str, trials: int, seed: int) -> tuple[int, int, int]:
    """Return (failed recoveries, wrong answers, errors) for ``trials`` bursts."""
    case = CASES[name]
    rng = random.Random(seed)
    faulty = FaultyStream(SimulatorStream(case.simulator(), time_scale=0))
    board = await _quick(case.backend).from_stream(faulty, port=name, serial_number=name)
    await board.setup()
    if case.prepare is not None:
        await case.prepare(board)
    failed = wrong = errors = 0
    try:
        for _ in range(trials):
            burst = _burst(rng)
            before = rng.random() < 0.5

            def noisy(reply: bytes, burst: bytes = burst, before: bool = before) -> bytes:
                return burst + reply if before else reply + burst

            faulty.corrupt_next_reply(noisy, terminator=case.terminator)
            recovered = False
            for _ in range(3):  # the request hit, then two more
                try:
                    value = await case.question_b(board.backend)
                except CommunicationError:
                    errors += 1
                    recovered = False
                    continue
                if _matches(value, case.answer_b):
                    recovered = True
                else:
                    wrong += 1
                    recovered = False
            failed += not recovered
    finally:
        await board.close()
    return failed, wrong, errors


async def main(trials: int, boards: list[str]) -> int:
    print(f"Line noise: {trials} bursts of 4-8 KiB per board")
    print(f"  {'board':<17}{'failed recoveries':>19}{'wrong':>7}{'errors':>8}")
    results: dict[str, tuple[int, int, int]] = {}

    async def one(name: str, seed: int) -> None:
        results[name] = await run_case(name, trials, seed)

    async with anyio.create_task_group() as group:  # every board at once
        for seed, name in enumerate(boards):
            group.start_soon(one, name, seed)
    total = 0
    for name in boards:
        failed, wrong, errors = results[name]
        total += failed + wrong
        print(f"  {name:<17}{failed:>19}{wrong:>7}{errors:>8}")
    print(f"Goal: 0 failed recoveries and 0 wrong answers. Total: {total}")
    return 0 if total == 0 else 1


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--trials", type=int, default=1000)
    parser.add_argument("--boards", default=",".join(CASES))
    arguments = parser.parse_args()
    raise SystemExit(anyio.run(main, arguments.trials, arguments.boards.split(",")))
