"""Late replies: wrong answers per 1,000 replies that came after their request timed out.

Every serial board generation is driven by its real hardware backend over an in-memory
stream to its simulator, through a fault-injecting stream
(:class:`j5aio.testing.transports.FaultyStream`). In each trial one request (question A)
gets its reply late, by 21 to 100 ms more than the timeout, and the request times out;
then question B, whose true answer differs, is asked every few milliseconds until well
after the late reply has come (it lands in the middle of one of them, or between two).
A *wrong answer* is any answer that is not the board's true one (the late A taken for a
B, say: 11.5 A of "output current" that was the battery's 11.5 V). An error
(:class:`~j5aio.errors.CommunicationError`) is not a wrong answer, and is counted apart.

Two models of lateness:

* ``in-order``: the late reply holds back everything after it, as on a serial line
  (``FaultyStream.delay_next_reply``);
* ``out-of-order``: later replies overtake the late one (``hold_next_reply``).

Goal: 0 wrong answers on every board, in both models.

Run: ``PYTHONPATH=$PWD python bench/bench_late_replies.py [--trials 1000] [--boards a,b]``
"""

from __future__ import annotations

import argparse
import random
import time
from collections.abc import Awaitable, Callable
from dataclasses import dataclass
from typing import Any, ClassVar

import anyio

from j5aio.backends.hardware.sb.arduino import SBArduinoHardwareBackend
from j5aio.backends.hardware.sb.arduino_2024 import SBArduino2024HardwareBackend
from j5aio.backends.hardware.serial_backend import SerialHardwareBackend
from j5aio.backends.hardware.sr.v4.arduino import SRArduinoHardwareBackend
from j5aio.backends.hardware.sr.v4.motor_board_fw4 import SRV4MotorBoardFw4HardwareBackend
from j5aio.backends.hardware.sr.v4.power_board_fw4 import SRV4PowerBoardFw4HardwareBackend
from j5aio.backends.hardware.sr.v4.ruggeduino import SRV4RuggeduinoHardwareBackend
from j5aio.backends.hardware.sr.v4.servo_board_fw4 import SRV4ServoBoardFw4HardwareBackend
from j5aio.backends.hardware.transports.memory import SimulatorStream
from j5aio.components.gpio_pin import GPIOPinMode
from j5aio.errors import CommunicationError
from j5aio.simulator import (
    SBArduino2024Simulator,
    SBArduinoSimulator,
    SRMotorBoardFw4Simulator,
    SRPowerBoardFw4Simulator,
    SRServoBoardFw4Simulator,
)
from j5aio.simulator.sr_ruggeduino_fw1 import SRRuggeduinoSimulator
from j5aio.testing.transports import FaultyStream

#: The reply timeout every backend is given here, in seconds.
TIMEOUT = 0.03
#: How much later than the timeout a late reply comes, in seconds.
LATE_BY = (0.021, 0.1)
#: The gap between two questions after the timed-out one, in seconds.
GAP = 0.004

Ask = Callable[[Any], Awaitable[object]]


@dataclass
class Case:
    """A board, two questions with different true answers, and how to set it up."""

    backend: type[SerialHardwareBackend]
    simulator: Callable[[], Any]
    question_a: Ask
    question_b: Ask
    answer_a: object
    answer_b: object
    prepare: Callable[[Any], Awaitable[None]] | None = None
    #: The bytes that end a reply (a reply of several lines is held back whole).
    terminator: bytes = b"\n"


def _quick(backend: type[SerialHardwareBackend]) -> type[SerialHardwareBackend]:
    class Quick(backend):  # type: ignore[valid-type,misc]
        DEFAULT_TIMEOUT: ClassVar[float] = TIMEOUT

    Quick.__name__ = backend.__name__
    return Quick


def _power() -> Any:
    sim = SRPowerBoardFw4Simulator("srP1")
    sim.battery_voltage = 11.5
    sim.set_output_current(4, 2.25)
    return sim


def _motor() -> Any:
    sim = SRMotorBoardFw4Simulator("srM1")
    sim.input_voltage = 11.5
    sim.set_motor_current(1, 3.5)
    return sim


def _servo() -> Any:
    sim = SRServoBoardFw4Simulator("srS1")
    sim.set_supply(voltage=6.0, current=0.75)
    return sim


def _arduino(sim: Any) -> Any:
    sim.set_analogue(14, raw=512)
    sim.set_ultrasound_distance(2, 3, 0.25)
    return sim


def _digital(sim: Any) -> Any:
    sim.set_input_level(4, True)
    sim.set_input_level(5, False)
    return sim


async def _analogue_pin(board: Any) -> None:
    await board.pins[14].set_mode(GPIOPinMode.ANALOGUE_INPUT)


async def _run_motor(board: Any) -> None:
    await board.backend.set_motor_state(1, 0.5)  # a coasting motor draws nothing


CASES: dict[str, Case] = {
    "power-fw4": Case(
        SRV4PowerBoardFw4HardwareBackend, _power,
        lambda b: b.get_battery_sensor_voltage(0), lambda b: b.get_power_output_current(4),
        11.5, 2.25,
    ),
    "motor-fw4": Case(
        SRV4MotorBoardFw4HardwareBackend, _motor,
        lambda b: b.get_voltage_sensor_voltage(0), lambda b: b.get_motor_current(1),
        11.5, 3.5, _run_motor,
    ),
    "servo-fw4": Case(
        SRV4ServoBoardFw4HardwareBackend, _servo,
        lambda b: b.get_supply_voltage(0), lambda b: b.get_supply_current(0),
        6.0, 0.75,
    ),
    "sr-arduino-fw2": Case(
        SRArduinoHardwareBackend, lambda: _arduino(SRRuggeduinoSimulator("A1", firmware_version=2)),
        lambda b: b.read_gpio_pin_analogue_value(14), lambda b: b.get_ultrasound_distance(2, 3),
        2.5, 0.25, _analogue_pin,
    ),
    "sb2024": Case(
        SBArduino2024HardwareBackend, lambda: _arduino(SBArduino2024Simulator("A2")),
        lambda b: b.read_gpio_pin_analogue_value(14), lambda b: b.get_ultrasound_distance(2, 3),
        2.5, 0.25, _analogue_pin,
    ),
    "sb-arduino-2019": Case(
        SBArduinoHardwareBackend, lambda: _digital(SBArduinoSimulator("A3")),
        lambda b: b.read_gpio_pin_digital_state(4), lambda b: b.read_gpio_pin_digital_state(5),
        True, False, terminator=b"+ OK\r\n",
    ),
    "ruggeduino-fw1": Case(
        SRV4RuggeduinoHardwareBackend, lambda: _digital(SRRuggeduinoSimulator("A4")),
        lambda b: b.read_gpio_pin_digital_state(4), lambda b: b.read_gpio_pin_digital_state(5),
        True, False,
    ),
}

MODELS = ("in-order", "out-of-order")


@dataclass
class Tally:
    """What one board showed in one model."""

    late: int = 0
    answers: int = 0
    wrong: int = 0
    errors: int = 0
    examples: list[str] | None = None

    def note(self, text: str) -> None:
        if self.examples is None:
            self.examples = []
        if len(self.examples) < 3:
            self.examples.append(text)


def _matches(value: object, truth: object) -> bool:
    if isinstance(truth, float) and isinstance(value, float):
        return abs(value - truth) < 0.01
    return value == truth


async def _ask(tally: Tally, question: Ask, backend: Any, truth: object, what: str) -> None:
    try:
        value = await question(backend)
    except CommunicationError:
        tally.errors += 1
        return
    tally.answers += 1
    if not _matches(value, truth):
        tally.wrong += 1
        tally.note(f"{what} read {value!r}, truly {truth!r}")


async def run_case(name: str, model: str, trials: int, seed: int) -> Tally:
    """Run ``trials`` late replies against one board in one model."""
    case = CASES[name]
    rng = random.Random(seed)
    sim = case.simulator()
    faulty = FaultyStream(SimulatorStream(sim, time_scale=0))
    board = await _quick(case.backend).from_stream(faulty, port=name, serial_number=name)
    await board.setup()
    if case.prepare is not None:
        await case.prepare(board)
    backend = board.backend
    tally = Tally()
    hold = getattr(faulty, "hold_next_reply", None)  # absent before out-of-order faults
    try:
        for _ in range(trials):
            late = TIMEOUT + rng.uniform(*LATE_BY)
            if model == "in-order":
                faulty.delay_next_reply(late)  # (what follows is held back too)
            else:
                assert hold is not None
                hold(late, case.terminator)
            try:
                value = await case.question_a(backend)
            except CommunicationError:
                tally.late += 1
            else:  # answered in time after all (a busy machine): not a late reply
                if not _matches(value, case.answer_a):
                    tally.wrong += 1
                    tally.note(f"A read {value!r}, truly {case.answer_a!r}")
                continue
            until = time.monotonic() + late + 0.02
            while time.monotonic() < until:
                await _ask(tally, case.question_b, backend, case.answer_b, "B")
                await anyio.sleep(GAP)
            await _ask(tally, case.question_a, backend, case.answer_a, "A")
            await anyio.sleep(0.02)  # let anything else still late come and go
    finally:
        await board.close()
    return tally


async def main(trials: int, boards: list[str], models: list[str]) -> int:
    print(f"Late replies: {trials} per board and model; timeout {TIMEOUT * 1000:.0f} ms, "
          f"replies late by {LATE_BY[0] * 1000:.0f}-{LATE_BY[1] * 1000:.0f} ms more")
    print(f"  {'board':<17}{'model':<14}{'late':>6}{'answers':>9}{'wrong':>7}"
          f"{'per 1000':>10}{'errors':>8}")
    results: dict[tuple[str, str], Tally] = {}

    async def one(name: str, model: str, seed: int) -> None:
        results[name, model] = await run_case(name, model, trials, seed)

    async with anyio.create_task_group() as group:  # every board at once, as on a robot
        for seed, name in enumerate(boards):
            for model in models:
                group.start_soon(one, name, model, seed)
    total_wrong = 0
    for name in boards:
        for model in models:
            tally = results[name, model]
            per_thousand = 1000 * tally.wrong / tally.late if tally.late else 0.0
            total_wrong += tally.wrong
            print(f"  {name:<17}{model:<14}{tally.late:>6}{tally.answers:>9}{tally.wrong:>7}"
                  f"{per_thousand:>10.1f}{tally.errors:>8}")
            for example in tally.examples or []:
                print(f"      e.g. {example}")
    print(f"Goal: 0 wrong answers. Total wrong: {total_wrong}")
    return 0 if total_wrong == 0 else 1


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--trials", type=int, default=1000)
    parser.add_argument("--boards", default=",".join(CASES),
                        help=f"comma-separated, from: {', '.join(CASES)}")
    parser.add_argument("--models", default=",".join(MODELS))
    arguments = parser.parse_args()
    raise SystemExit(anyio.run(
        main, arguments.trials, arguments.boards.split(","), arguments.models.split(","),
    ))
