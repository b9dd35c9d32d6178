"""Reliability figures: every hardware backend against its simulator.

Random cancellations, through anyio (``move_on_after``) and through asyncio itself
    (``Task.cancel``, ``asyncio.timeout``): wrong answers and caches that disagree with
    the simulated board, per backend. Goal: 0 and 0.
Signals: busy sync and async programs on the simulated kit stopped by SIGINT or SIGTERM;
    time from the signal to every motor braked, from the simulators' own state-change
    times (``bench_signals.py``). Goal: 100 of 100 within 50 ms.
Unplug and replug: the same board object answers again (time from the board's return to
    its first answer; goal <= 1 s plus boot time), nothing stale, no duplicate object,
    make_safe works. In memory (every backend, the simulated kit) and over a real
    pseudo-terminal whose simulator hangs up when unplugged (SB Arduino, by --link).
Bad values given to components: refused calls that still reached the wire. Goal: 0.
Requests answered with random bytes: exceptions other than CommunicationError. Goal: 0.

Run: ``python bench/bench_reliability.py [--trials N] [--replugs N]``
"""

from __future__ import annotations

import argparse
import statistics
import sys
import tempfile
import time
from pathlib import Path

# The trials' rig is a white-box part of the test suite (tests/testing/reliability_rig.py):
# the repository's root must be importable.
sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

import anyio
import bench_signals  # type: ignore[import-not-found]  # beside this script

from j5aio.backends.hardware.reconnect import ReconnectPolicy
from j5aio.backends.hardware.sb.arduino import SBArduinoHardwareBackend
from j5aio.boards.sb.arduino import SBArduinoBoard
from j5aio.errors import BoardDisconnectionError
from j5aio.simulator import SBArduinoSimulator
from j5aio.simulator.serve import serve_on_pty
from tests.testing.reliability_rig import (
    BACKEND_NAMES,
    CancellationStyle,
    bad_value_trials,
    cancellation_trials,
    fuzzed_reply_trials,
    replug_trials,
)


def _ms(values: list[float]) -> str:
    if not values:
        return "-"
    return f"median {statistics.median(values) * 1000:7.1f} ms, max {max(values) * 1000:7.1f} ms"


async def cancellations(trials: int) -> None:
    print(f"random cancellations ({trials} trials per backend and style)")
    print(f"    {'backend':<11}{'style':<9}{'cancelled':>10}{'wrong':>7}{'stale':>7}{'errors':>8}")
    for name in BACKEND_NAMES:
        styles: tuple[CancellationStyle, ...] = ("anyio", "asyncio")
        for style in styles:
            report = await cancellation_trials(name, style, trials, seed=1)
            print(
                f"    {name:<11}{style:<9}{report.cancelled:>10}{report.wrong_answers:>7}"
                f"{report.mismatches:>7}{report.errors:>8}"
            )


def signals(trials: int) -> None:
    print(f"signal trials ({trials} per kind of program, SIGINT and SIGTERM alternating)")
    bench_signals.report(bench_signals.run_trials(trials))


async def unplug_and_replug(replugs: int) -> None:
    print(f"unplug and replug ({replugs} times per backend, simulated kit, in memory)")
    for name in BACKEND_NAMES:
        report = await replug_trials(name, replugs, seed=2)
        print(
            f"    {name:<11} back after {_ms(report.back_after)}; failed while out "
            f"{report.disconnection_errors}/{report.trials}, wrong {report.wrong_outcomes}, "
            f"stale {report.stale}, duplicates {report.duplicates}, "
            f"make_safe failures {report.make_safe_failures}"
        )
    back = await _pty_replugs(replugs)
    print(f"    sb-arduino over a pty (hang-up on unplug, by --link): back after {_ms(back)}")
    print("    (the board's own boot is instant here; add the real board's boot time)")


async def _pty_replugs(replugs: int) -> list[float]:
    sim = SBArduinoSimulator("PTY-REPLUG")
    back: list[float] = []
    with tempfile.TemporaryDirectory() as folder:
        link = Path(folder) / "arduino"
        with serve_on_pty(sim, time_scale=0, link=link):
            board = await SBArduinoHardwareBackend.attach(str(link), time_scale=0.1)
            assert isinstance(board, SBArduinoBoard)
            backend = board.backend
            assert isinstance(backend, SBArduinoHardwareBackend)
            backend.reconnect_policy = ReconnectPolicy()  # the default, stated
            await board.setup()
            for _ in range(replugs):
                sim.unplug()
                while True:
                    try:
                        await board.pins[14].analogue_read()
                    except BoardDisconnectionError:
                        break
                    await anyio.sleep(0.005)
                await anyio.sleep(0.05)
                sim.plug()
                start = time.perf_counter()
                while True:
                    try:
                        await board.pins[14].analogue_read()
                        break
                    except BoardDisconnectionError:
                        await anyio.sleep(0.002)
                back.append(time.perf_counter() - start)
            await board.close()
    return back


async def bad_values(trials: int) -> None:
    print(f"bad values ({trials} per backend)")
    for name in BACKEND_NAMES:
        report = await bad_value_trials(name, trials, seed=3)
        print(
            f"    {name:<11} refused {report.refused:>5}, accepted {report.accepted:>4}, "
            f"reached the wire {report.reached_the_wire}, foreign exceptions {report.foreign}"
        )


async def fuzzed_replies(trials: int) -> None:
    print(f"fuzzed replies ({trials} per backend)")
    for name in BACKEND_NAMES:
        report = await fuzzed_reply_trials(name, trials, seed=4)
        print(
            f"    {name:<11} CommunicationError {report.communication_errors:>5}, "
            f"answers {report.answers:>4}, foreign exceptions {report.foreign}"
        )


async def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument(
        "--trials", type=int, default=2000, help="cancellation, bad-value and fuzzed-reply trials"
    )
    parser.add_argument("--replugs", type=int, default=20, help="replugs per backend")
    parser.add_argument(
        "--signal-trials", type=int, default=100, help="signal trials per kind of program"
    )
    args = parser.parse_args()
    await cancellations(args.trials)
    signals(args.signal_trials)
    await unplug_and_replug(args.replugs)
    await bad_values(args.trials)
    await fuzzed_replies(args.trials)


if __name__ == "__main__":
    anyio.run(main)
