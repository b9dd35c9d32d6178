"""Start-button reaction and CPU while waiting: j5aio (async and sync) beside j5 0.12.

What it measures: press -> code resumes, on a simulated SR v4 power board (firmware 3,
j5aio's simulator), over random presses, and the process's CPU while it waits.

Each *side* runs in a child process of its own, so that CPU figures are the side's alone:

* ``async``: ``await robot.power_board.start_button.wait_until_pressed()`` on a
  :class:`~j5aio.kit.KitRobot` of the simulated kit (the hardware backend over the
  simulated USB device, whose press rings the USB link's doorbell: the poll reads the
  button at once, through the protocol, and otherwise every 50 intervals);
* ``sync``: the same through the sync facade, ``robot.power_board.start_button
  .wait_until_pressed()``;
* ``wait_start``: :func:`j5aio.competition.start.wait_for_start` (what
  ``robot.wait_start()`` runs: the button, the start file, the trigger, the run LED
  flashing), async;
* ``polling``: as ``async`` with the simulator's doorbell taken away, so that the
  backend polls the simulator over the link as it polls a real board (every
  ``BUTTON_POLL_INTERVAL``, on the USB link's worker thread), with the poll's own
  figures: those a real fw 3 power
  board gets, bar the USB transfer's own time (here the simulator's, standing in for
  pyusb's). ``--intervals 10,15,20`` runs one such side
  per interval (``polling@10ms``...), to choose the interval; without it, the backend's
  own ``BUTTON_POLL_INTERVAL``. Each also reports the CPU time of one idle poll (the
  idle CPU over the reads made), and, as the machine's floor, the CPU time of a thread
  that does nothing but sleep for the same interval, over the same time, in the same
  process: no poll can cost less than that wake-up, and the difference is what the
  link, the backend and the transfer add to it;
* ``j5``: j5 0.12 (from the package registry, in its own venv made by
  ``bench/_peers.py``) driving the *same* simulator: j5's own SR v4 power board hardware
  backend is given the simulator as its pyusb device (the simulator's modules are loaded
  from this tree without j5aio's package, which j5's venv does not have). j5 reads the
  button every 50 ms.

A trial: the waiting code announces that it waits; a presser thread in the same process
sleeps a random 30-130 ms, notes the time and presses the simulated button (the
simulator's own ``press_start``); the reaction is the time from that press until the
awaiting code runs again. The button is released before the next trial. After the
presses, the side waits ``--idle`` seconds with nobody pressing and reports its process's
CPU time (``time.process_time``: user + system, every thread) over that wall time.

Sides are run in turn, round after round (interleaved), and every figure printed is the
median over rounds (p50 and p95 are taken within each round). Run::

    python bench/bench_button.py [--presses 50] [--rounds 3] [--idle 3] [--no-peer]
                                 [--intervals MS,MS,...] [--sides async,polling,...]

Goals: p50 <= 10 ms and p95 <= 20 ms, at the same time as CPU <= 1 % while
waiting, for async and sync (and, for the hardware path, ``polling``); an idle poll
<= 60 us of CPU.
"""

from __future__ import annotations

import argparse
import contextlib
import json
import os
import random
import socket
import statistics
import subprocess
import sys
import threading
import time
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
GOAL_P50_MS = 10.0
GOAL_P95_MS = 20.0
GOAL_CPU_PERCENT = 1.0
GOAL_POLL_US = 60.0
SIDES = ("async", "sync", "wait_start", "polling", "j5")
#: How often j5 0.12's power board backend reads the button, in seconds.
J5_POLL_INTERVAL = 0.05


# -- the presser (every side) -----------------------------------------------------------


class Presser:
    """Presses the simulated start button at a random time after the waiter says it waits."""

    def __init__(self, press: Callable[[], None], release: Callable[[], None], seed: int) -> None:
        self._press = press
        self._release = release
        self._random = random.Random(seed)
        self.waiting = threading.Event()
        self.resumed = threading.Event()
        self.released = threading.Event()
        self.pressed_at = 0.0
        self._stop = False
        self._thread = threading.Thread(target=self._run, daemon=True)
        self._thread.start()

    def _run(self) -> None:
        while True:
            self.waiting.wait()
            self.waiting.clear()
            if self._stop:
                return
            time.sleep(self._random.uniform(0.03, 0.13))
            self.pressed_at = time.perf_counter()
            self._press()
            self.resumed.wait()
            self.resumed.clear()
            self._release()
            self.released.set()

    def resumed_now(self) -> float:
        """Note that the waiting code runs again: return the reaction; release the button.

        Returns once the button has been released, ready for the next trial.
        """
        reaction = time.perf_counter() - self.pressed_at
        self.resumed.set()
        self.released.wait()
        self.released.clear()
        return reaction

    def stop(self) -> None:
        """End the thread."""
        self._stop = True
        self.waiting.set()
        self._thread.join(5)


def _percentile(values: list[float], fraction: float) -> float:
    ordered = sorted(values)
    return ordered[min(len(ordered) - 1, round(fraction * (len(ordered) - 1)))]


def _cpu() -> float:
    return time.process_time()  # user + system of every thread, finer than os.times


def _report(
    reactions: list[float], cpu_seconds: float, wall: float, **extra: float
) -> None:
    ms = [r * 1000 for r in reactions]
    print(json.dumps({
        "p50": _percentile(ms, 0.5),
        "p95": _percentile(ms, 0.95),
        "cpu": 100 * cpu_seconds / wall,
        **extra,
    }))


def wake_floor_us(interval: float, seconds: float) -> float:
    """CPU time (us) of one wake-up of a thread that only sleeps ``interval`` at a time.

    The floor of any poll on this machine: a poll's thread wakes as often, and then does
    its read as well.
    """
    def sleeper() -> None:
        end = time.monotonic() + seconds
        while time.monotonic() < end:
            time.sleep(interval)

    start_cpu, start = _cpu(), time.perf_counter()
    thread = threading.Thread(target=sleeper)
    thread.start()
    thread.join()
    wakes = (time.perf_counter() - start) / interval
    return 1e6 * (_cpu() - start_cpu) / wakes


# -- j5aio sides ------------------------------------------------------------------------


def _kit() -> Any:
    from j5aio.simulator.kit import KitConfig, use_kit

    kit = use_kit(KitConfig(power_boards=1, motor_boards=0, servo_boards=0, sb_arduinos=0))
    # No camera: its simulated world moves on 100 times a second, which is not the button's
    # cost (about 2 % CPU on its own on the machine it was measured on).
    kit.camera = None
    return kit


def child_async(
    presses: int, idle: float, seed: int, mode: str, interval: float | None = None
) -> None:
    """Measure j5aio's async wait (``mode``: ``async``, ``wait_start`` or ``polling``).

    :param interval: for ``polling``, the poll interval in seconds (else the backend's).
    """
    import anyio

    from j5aio.backends.hardware.sr.v4.power_board import SRV4PowerBoardHardwareBackend

    if mode == "polling" and interval is not None:
        SRV4PowerBoardHardwareBackend.BUTTON_POLL_INTERVAL = interval
    if mode == "polling":
        # A real board rings no doorbell: its poll reads every interval.
        from j5aio.simulator.sr_usb import SRUsbBoardSimulator

        SRUsbBoardSimulator.add_doorbell = None  # type: ignore[assignment,method-assign]
        # Nor does it answer at once: its link polls on its worker thread.
        SRUsbBoardSimulator.answers_at_once = False
    poll_interval = SRV4PowerBoardHardwareBackend.BUTTON_POLL_INTERVAL

    from j5aio.competition.start import wait_for_start
    from j5aio.kit import KitRobot
    from j5aio.simulator.environment import SIMULATED_ENVIRONMENT

    sim = _kit().power_boards[0]
    presser = Presser(sim.press_start, sim.release_start, seed)

    async def main() -> None:
        async with KitRobot(environment=SIMULATED_ENVIRONMENT) as robot:
            button = robot.power_board.start_button

            async def wait(timeout: float | None = None) -> None:
                if mode == "wait_start":
                    await wait_for_start([robot.power_board], timeout)
                else:
                    await button.wait_until_pressed(timeout)

            reactions = []
            for _ in range(presses):
                presser.waiting.set()
                await wait()
                reactions.append(presser.resumed_now())
            presser.stop()
            start_cpu, start = _cpu(), time.perf_counter()
            with contextlib.suppress(TimeoutError):
                await wait(idle)
            cpu_seconds, wall = _cpu() - start_cpu, time.perf_counter() - start
            if mode != "polling":
                _report(reactions, cpu_seconds, wall)
                return
            # Both measured with the robot still up (its threads as they were).
            floor = wake_floor_us(poll_interval, idle)
            with _timed_transfers() as transfer_us, contextlib.suppress(TimeoutError):
                await wait(idle)
            _report(reactions, cpu_seconds, wall, interval=poll_interval * 1000,
                    poll_us=1e6 * cpu_seconds / (wall / poll_interval), floor_us=floor,
                    transfer_us=transfer_us[0])

    anyio.run(main)


@contextlib.contextmanager
def _timed_transfers() -> Iterator[list[float]]:
    """Time the simulated device's transfers (its thread's CPU); yield [us per transfer].

    The share of an idle poll that is the stand-in for pyusb's transfer, measured in a
    wait of its own (the timing costs a little CPU itself).
    """
    from j5aio.simulator.environment import SimulatedUSBDevice

    real = SimulatedUSBDevice.ctrl_transfer
    spent = [0, 0]

    def timed(self: SimulatedUSBDevice, *args: Any, **kwargs: Any) -> Any:
        start = time.thread_time_ns()
        try:
            return real(self, *args, **kwargs)
        finally:
            spent[0] += time.thread_time_ns() - start
            spent[1] += 1

    result = [0.0]
    SimulatedUSBDevice.ctrl_transfer = timed  # type: ignore[method-assign]
    try:
        yield result
    finally:
        SimulatedUSBDevice.ctrl_transfer = real  # type: ignore[method-assign]
        result[0] = spent[0] / max(spent[1], 1) / 1000


def child_sync(presses: int, idle: float, seed: int) -> None:
    """Measure j5aio's sync facade wait."""
    from j5aio.sync import KitRobot, simulated_environment

    sim = _kit().power_boards[0]
    presser = Presser(sim.press_start, sim.release_start, seed)
    robot = KitRobot(environment=simulated_environment())
    button = robot.power_board.start_button
    reactions = []
    for _ in range(presses):
        presser.waiting.set()
        button.wait_until_pressed()
        reactions.append(presser.resumed_now())
    presser.stop()
    start_cpu, start = _cpu(), time.perf_counter()
    with contextlib.suppress(TimeoutError):
        button.wait_until_pressed(idle)
    _report(reactions, _cpu() - start_cpu, time.perf_counter() - start)


# -- j5's side (run by j5's own interpreter: no j5aio package, no anyio) -----------------


def child_j5(presses: int, idle: float, seed: int) -> None:
    """Measure j5 0.12 waiting for the simulator's button with its own backend."""
    import importlib
    import types

    # The simulator's modules only (relative imports, pyusb): not j5aio's package.
    package = types.ModuleType("j5aio_simulator")
    package.__path__ = [str(ROOT / "j5aio" / "simulator")]
    sys.modules["j5aio_simulator"] = package
    fw3 = importlib.import_module("j5aio_simulator.sr_power_fw3")

    # j5 is in its own venv only: imported by name, so that type checkers here skip it.
    j5_backends = importlib.import_module("j5.backends.hardware.sr.v4.power_board")
    j5_boards = importlib.import_module("j5.boards.sr.v4")

    sim = fw3.SRPowerBoardFw3Simulator("SIMPB0")
    backend = j5_backends.SRV4PowerBoardHardwareBackend(sim)
    board = j5_boards.PowerBoard("SIMPB0", backend)
    presser = Presser(sim.press_start, sim.release_start, seed)
    reactions = []
    for _ in range(presses):
        presser.waiting.set()
        board.start_button.wait_until_pressed()
        reactions.append(presser.resumed_now())
    presser.stop()
    # j5's wait has no timeout: wait in a thread that nobody presses for, for ``idle`` s.
    start_cpu, start = _cpu(), time.perf_counter()
    waiter = threading.Thread(target=board.start_button.wait_until_pressed, daemon=True)
    waiter.start()
    waiter.join(idle)
    _report(reactions, _cpu() - start_cpu, time.perf_counter() - start)
    sim.press_start()
    waiter.join(1)


# -- the parent -------------------------------------------------------------------------


def run_side(side: str, args: argparse.Namespace, seed: int) -> dict[str, float] | None:
    """Run one side in a child process; return its figures (``None`` if it failed).

    ``side`` is one of :data:`SIDES`, or ``polling@<ms>ms`` for a poll interval of its own.
    """
    interval: list[str] = []
    if side.startswith("polling@"):
        side, ms = side.split("@")
        interval = ["--interval", str(float(ms.removesuffix("ms")) / 1000)]
    if side == "j5":
        sys.path.insert(0, str(HERE))
        from _peers import J5_PEER, peer_python  # type: ignore[import-not-found]

        python = str(peer_python(*J5_PEER))
        env = dict(os.environ)
        env.pop("PYTHONPATH", None)
    else:
        python = sys.executable
        env = dict(os.environ, PYTHONPATH=os.pathsep.join(
            filter(None, [str(ROOT), os.environ.get("PYTHONPATH")])
        ))
    # A port of its own for the robot lock: other robot programs may run on this machine.
    with socket.socket() as probe:
        probe.bind(("127.0.0.1", 0))
        env["J5AIO_LOCK_PORT"] = str(probe.getsockname()[1])
    command = [python, str(Path(__file__).resolve()), "--child", side,
               "--presses", str(args.presses), "--idle", str(args.idle), "--seed", str(seed),
               *interval]
    result = subprocess.run(command, capture_output=True, text=True, env=env, timeout=600)
    lines = result.stdout.strip().splitlines()
    if result.returncode != 0 or not lines:
        print(f"  {side}: failed ({result.returncode}): {result.stderr.strip()[-600:]}")
        return None
    figures: dict[str, float] = json.loads(lines[-1])
    return figures


def main(argv: list[str] | None = None) -> None:
    """Run the bench (or, with ``--child``, one side of it)."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--presses", type=int, default=50)
    parser.add_argument("--rounds", type=int, default=3)
    parser.add_argument("--idle", type=float, default=3.0)
    parser.add_argument("--seed", type=int, default=12)
    parser.add_argument("--no-peer", action="store_true", help="skip j5 0.12")
    parser.add_argument(
        "--intervals", type=_interval_list, default=[],
        help="poll intervals (ms, comma-separated) for a hardware-path side each, "
        "instead of the backend's own",
    )
    parser.add_argument(
        "--sides", type=_side_list, default=list(SIDES),
        help=f"the sides to run, comma-separated (default: {','.join(SIDES)})",
    )
    parser.add_argument("--child", choices=SIDES, help=argparse.SUPPRESS)
    parser.add_argument("--interval", type=float, help=argparse.SUPPRESS)
    args = parser.parse_args(argv)
    if args.child == "j5":
        child_j5(args.presses, args.idle, args.seed)
        return
    if args.child == "sync":
        child_sync(args.presses, args.idle, args.seed)
        return
    if args.child:
        child_async(args.presses, args.idle, args.seed, args.child, args.interval)
        return

    sides = [side for side in args.sides if not (args.no_peer and side == "j5")]
    if args.intervals and "polling" in sides:
        at = sides.index("polling")
        sides[at:at + 1] = [f"polling@{ms:g}ms" for ms in args.intervals]
    results: dict[str, list[dict[str, float]]] = {side: [] for side in sides}
    print(f"start button: {args.presses} random presses per round, {args.idle} s idle, "
          f"{args.rounds} rounds, sides interleaved: {', '.join(sides)}")
    for index in range(args.rounds):
        for side in sides:
            figures = run_side(side, args, args.seed + index)
            if figures is not None:
                results[side].append(figures)
                print(f"  round {index + 1} {side:>15}: p50 {figures['p50']:5.1f} ms  "
                      f"p95 {figures['p95']:5.1f} ms  CPU {figures['cpu']:5.2f} %"
                      + _poll_figures(figures))
    print(f"\nmedians over rounds (goal: p50 <= {GOAL_P50_MS:g} ms, p95 <= {GOAL_P95_MS:g} ms "
          f"and CPU <= {GOAL_CPU_PERCENT:g} % while waiting, at the same time)")
    medians: dict[str, dict[str, float]] = {}
    for side, rounds in results.items():
        if not rounds:
            print(f"  {side:>15}: no figures")
            continue
        medians[side] = {key: statistics.median(r[key] for r in rounds) for key in rounds[0]}
        m = medians[side]
        met = (m["p50"] <= GOAL_P50_MS and m["p95"] <= GOAL_P95_MS
               and m["cpu"] <= GOAL_CPU_PERCENT)
        verdict = "" if side == "j5" else ("  MET" if met else "  NOT MET")
        print(f"  {side:>15}: p50 {m['p50']:5.1f} ms  p95 {m['p95']:5.1f} ms  "
              f"CPU {m['cpu']:5.2f} %{verdict}")
    _print_polls(medians)
    if "j5" in medians:
        j5 = medians["j5"]
        for side in medians:
            if side != "j5":
                m = medians[side]
                print(f"  {side} / j5: p50 {m['p50'] / j5['p50']:.2f}x  "
                      f"p95 {m['p95'] / j5['p95']:.2f}x  CPU {m['cpu'] / j5['cpu']:.2f}x")


def _interval_list(text: str) -> list[float]:
    try:
        intervals = [float(part) for part in text.split(",") if part.strip()]
    except ValueError:
        raise argparse.ArgumentTypeError(f"not a list of milliseconds: {text!r}") from None
    if not intervals or not all(0 < ms <= 1000 for ms in intervals):
        raise argparse.ArgumentTypeError(f"intervals must be 0-1000 ms, not {text!r}")
    return intervals


def _side_list(text: str) -> list[str]:
    sides = [part.strip() for part in text.split(",") if part.strip()]
    unknown = [side for side in sides if side not in SIDES]
    if unknown or not sides:
        raise argparse.ArgumentTypeError(
            f"sides are some of {', '.join(SIDES)}, not {text!r}"
        )
    return [side for side in SIDES if side in sides]  # in the usual order


def _poll_figures(figures: dict[str, float]) -> str:
    if "poll_us" not in figures:
        return ""
    return (f"  ({figures['interval']:g} ms: {figures['poll_us']:4.0f} us/poll, "
            f"floor {figures['floor_us']:4.0f} us, transfer {figures['transfer_us']:3.0f} us)")


def _print_polls(medians: dict[str, dict[str, float]]) -> None:
    """Print what one idle poll costs on the hardware path (medians over rounds)."""
    polling = {side: m for side, m in medians.items() if "poll_us" in m}
    if not polling:
        return
    print(f"\none idle poll on the hardware path, CPU time (goal <= {GOAL_POLL_US:g} us) = the "
          "floor (a thread that only sleeps as often,\nin the same process: what the machine "
          "charges for the wake-up alone) + the transfer (the simulator standing in\nfor "
          "pyusb, timed on its thread in a wait of its own) + the rest (link and backend)")
    for side, m in polling.items():
        rest = m["poll_us"] - m["floor_us"] - m["transfer_us"]
        verdict = "MET" if m["poll_us"] <= GOAL_POLL_US else "NOT MET"
        print(f"  {side:>15}: every {m['interval']:g} ms: {m['poll_us']:4.0f} us  {verdict}"
              f"  = floor {m['floor_us']:3.0f} + transfer {m['transfer_us']:3.0f}"
              f" + rest {rest:3.0f} us")
    if "j5" in medians:
        j5_us = medians["j5"]["cpu"] / 100 * J5_POLL_INTERVAL * 1e6
        print(f"  {'j5':>15}: every {J5_POLL_INTERVAL * 1000:g} ms: {j5_us:4.0f} us "
              "(its idle CPU over its reads)")


if __name__ == "__main__":
    main()
