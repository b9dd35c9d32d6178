"""Stress trials of the hardware backends against their simulators: a white-box test rig.

It is not part of j5aio's API: a rig reads the backends' private state (their caches) and
knows only the boards it was written for. The test suite and ``bench/bench_reliability.py``
import it from here.

Each *rig* connects one real hardware backend to a simulator of its board and knows how
to compare what the backend remembers (its caches) with what the simulated board really
does. The trials built on rigs are run at full size by ``bench/bench_reliability.py``
and at a bounded size by the test suite:

* :func:`cancellation_trials`: random operations, each cancelled at a random moment
  through anyio (``move_on_after``) or asyncio itself (``Task.cancel``,
  ``asyncio.timeout``); counts wrong answers and caches that disagree with the board.
* :func:`bad_value_trials`: random bad values given to the components; counts the
  bytes that reached the wire.
* :func:`fuzzed_reply_trials`: requests answered with random bytes; counts
  exceptions that are not :class:`~j5aio.errors.CommunicationError` (or a subclass).
"""

from __future__ import annotations

import asyncio
import functools
import math
import random
import time
from collections.abc import AsyncIterator, Awaitable, Callable, Sequence
from contextlib import asynccontextmanager
from dataclasses import dataclass, field
from typing import Any, Literal

import anyio
import anyio.lowlevel

from j5aio.backends.hardware.arduino import ArduinoHardwareBackend
from j5aio.backends.hardware.sb import arduino_2019_codec as sb_codec
from j5aio.backends.hardware.sb.arduino import SBArduinoHardwareBackend
from j5aio.backends.hardware.sr.v4 import motor_fw3_codec as motor_codec
from j5aio.backends.hardware.sr.v4.motor_board import SRV4MotorBoardHardwareBackend
from j5aio.backends.hardware.sr.v4.power_board import SRV4PowerBoardHardwareBackend
from j5aio.backends.hardware.sr.v4.ruggeduino import SRV4RuggeduinoHardwareBackend
from j5aio.backends.hardware.sr.v4.servo_board import SRV4ServoBoardHardwareBackend
from j5aio.backends.hardware.transports.memory import SimulatorStream
from j5aio.backends.hardware.transports.stream import ByteStream
from j5aio.boards.board import Board
from j5aio.components.gpio_pin import GPIOPinMode
from j5aio.components.motor import MotorSpecialState, MotorState
from j5aio.errors import (
    BoardDisconnectionError,
    CommunicationError,
    NotSupportedByHardwareError,
)
from j5aio.simulator.arduino_pins import PinMode
from j5aio.simulator.sb_arduino_2019 import SBArduinoSimulator
from j5aio.simulator.sr_motor_fw3 import MotorMode, SRMotorBoardFw3Simulator
from j5aio.simulator.sr_power_fw3 import SRPowerBoardFw3Simulator
from j5aio.simulator.sr_ruggeduino_fw1 import SRRuggeduinoSimulator
from j5aio.simulator.sr_servo_fw2 import SRServoBoardFw2Simulator

__all__ = [
    "BACKEND_NAMES",
    "BadValueReport",
    "CancellationStyle",
    "FuzzReport",
    "ReplugReport",
    "Rig",
    "TrialReport",
    "bad_value_trials",
    "cancellation_trials",
    "fuzzed_reply_trials",
    "open_rig",
    "replug_trials",
    "rig_for",
]

#: The backends every trial runs against.
BACKEND_NAMES: tuple[str, ...] = ("sb-arduino", "ruggeduino", "motor", "power", "servo")

#: How a trial cancels: through anyio, or through asyncio itself.
CancellationStyle = Literal["anyio", "asyncio"]

_PINS = range(2, 8)
_MODES = (GPIOPinMode.DIGITAL_INPUT, GPIOPinMode.DIGITAL_INPUT_PULLUP, GPIOPinMode.DIGITAL_OUTPUT)
_SIM_MODES = {
    GPIOPinMode.DIGITAL_INPUT: PinMode.INPUT,
    GPIOPinMode.DIGITAL_INPUT_PULLUP: PinMode.INPUT_PULLUP,
    GPIOPinMode.DIGITAL_OUTPUT: PinMode.OUTPUT,
}

Operation = Callable[[], Awaitable[object]]


@dataclass
class Rig:
    """One backend connected to a simulator of its board."""

    name: str
    board: Board
    simulator: Any
    #: Returns a random operation and the answer it must give (None: not checked).
    pick: Callable[[random.Random], tuple[Operation, object]]
    #: Describes every cache entry that disagrees with the simulated board.
    mismatches: Callable[[], list[str]]
    #: An idempotent call that reaches the board (to see whether it answers).
    probe: Operation

    async def settle(self) -> None:
        """Wait until no work for the board is left in flight."""
        link = getattr(self.board.backend, "link", None)
        call = getattr(link, "call", None)
        if call is not None:  # a USB link: a no-op job runs after every earlier one
            await call(lambda: None, description="waiting for earlier transfers")
        confirm = getattr(link, "confirm", None)
        if confirm is not None:  # a serial link: an acknowledgement may still be owed
            await confirm()
        await anyio.lowlevel.checkpoint()


@dataclass
class TrialReport:
    """What one run of trials observed."""

    backend: str
    style: str
    trials: int = 0
    cancelled: int = 0
    wrong_answers: int = 0
    mismatches: int = 0
    errors: int = 0
    details: list[str] = field(default_factory=list)

    def note(self, text: str) -> None:
        """Keep the first few details of what went wrong."""
        if len(self.details) < 10:
            self.details.append(text)


# -- rigs ---------------------------------------------------------------------------------

#: The most time a simulated board takes to answer, in seconds, so that cancellations
#: land before, during and after exchanges.
LATENCY = 0.001


class _SlowStream(ByteStream):
    """A stream that takes up to :data:`LATENCY` to send each request."""

    def __init__(self, inner: ByteStream, rng: random.Random) -> None:
        self._inner = inner
        self._rng = rng
        #: How many bytes have been sent.
        self.sent = 0

    @property
    def name(self) -> str:
        return self._inner.name

    @property
    def is_closed(self) -> bool:
        return self._inner.is_closed

    async def send(self, data: bytes) -> None:
        # The wait comes first: like every stream, this one sends all or nothing.
        await anyio.sleep(self._rng.uniform(0, LATENCY))
        await self._inner.send(data)
        self.sent += len(data)

    async def receive(self, max_bytes: int = 4096) -> bytes:
        return await self._inner.receive(max_bytes)

    def close_now(self) -> None:
        self._inner.close_now()


class _SlowDevice:
    """A USB simulator whose transfers take up to :data:`LATENCY` each."""

    #: Its transfers block, as a real board's do (the simulator's own claim is not
    #: passed on): the link runs them on its thread, where cancellations can land.
    answers_at_once = False

    def __init__(self, simulator: Any, rng: random.Random) -> None:
        self._simulator = simulator
        self._rng = rng
        #: How many transfers have been made.
        self.transfers = 0

    def __getattr__(self, name: str) -> Any:
        return getattr(self._simulator, name)

    def ctrl_transfer(self, *args: Any, **kwargs: Any) -> Any:
        self.transfers += 1
        time.sleep(self._rng.uniform(0, LATENCY))
        return self._simulator.ctrl_transfer(*args, **kwargs)


def _arduino_pick(
    backend: ArduinoHardwareBackend, sim: Any
) -> Callable[[random.Random], tuple[Operation, object]]:
    def pick(rng: random.Random) -> tuple[Operation, object]:
        pin = rng.choice(_PINS)
        mode = backend._pins.digital(pin).mode
        roll = rng.random()
        if roll < 0.4:
            wanted = rng.choice(_MODES)
            return (lambda: backend.set_gpio_pin_mode(pin, wanted)), None
        if roll < 0.7 and mode is GPIOPinMode.DIGITAL_OUTPUT:
            level = rng.random() < 0.5
            return (lambda: backend.write_gpio_pin_digital_state(pin, level)), None
        if mode is not GPIOPinMode.DIGITAL_OUTPUT:
            level = rng.random() < 0.5
            sim.set_input_level(pin, level)
            return (lambda: backend.read_gpio_pin_digital_state(pin)), level
        return (lambda: backend.set_gpio_pin_mode(pin, rng.choice(_MODES))), None

    return pick


def _arduino_mismatches(backend: ArduinoHardwareBackend, sim: Any) -> list[str]:
    found = []
    for pin in _PINS:
        state = backend._pins.digital(pin)
        if sim.pin_mode(pin) is not _SIM_MODES[state.mode]:
            found.append(f"pin {pin}: remembered {state.mode.name}, board {sim.pin_mode(pin)}")
        elif state.mode is GPIOPinMode.DIGITAL_OUTPUT and sim.output_level(pin) != state.level:
            found.append(f"pin {pin}: remembered level {state.level}, board drives the other")
    return found


async def _serial_board(
    backend_class: type[Any], sim: Any, stream_wrapper: Callable[[ByteStream], ByteStream] | None
) -> Board:
    stream: ByteStream = _SlowStream(SimulatorStream(sim, time_scale=0), random.Random(1))
    if stream_wrapper is not None:
        stream = stream_wrapper(stream)
    board: Board = await backend_class.from_stream(
        stream, port=f"sim-{sim.serial_number}", serial_number=sim.serial_number, time_scale=0.01
    )
    await board.setup()
    return board


def _sb_arduino_rig(board: Board, sim: Any) -> Rig:
    backend = board.backend
    assert isinstance(backend, SBArduinoHardwareBackend)
    pins = _arduino_pick(backend, sim)

    def pick(rng: random.Random) -> tuple[Operation, object]:
        if rng.random() < 0.25:
            servo = rng.randrange(4)
            position = None if rng.random() < 0.2 else rng.uniform(-1, 1)
            return (lambda: backend.set_servo_position(servo, position)), None
        return pins(rng)

    def mismatches() -> list[str]:
        found = _arduino_mismatches(backend, sim)
        for servo in range(4):
            remembered = sb_codec.servo_level(backend._servos[servo])
            if sim.servo_widths[servo] != remembered:
                actual = sim.servo_widths[servo]
                found.append(f"servo {servo}: remembered {remembered}, board {actual}")
        return found

    return Rig(
        "sb-arduino", board, sim, pick, mismatches, lambda: backend.read_gpio_pin_analogue_value(14)
    )


def _ruggeduino_rig(board: Board, sim: Any) -> Rig:
    backend = board.backend
    assert isinstance(backend, SRV4RuggeduinoHardwareBackend)
    return Rig(
        "ruggeduino",
        board,
        sim,
        _arduino_pick(backend, sim),
        lambda: _arduino_mismatches(backend, sim),
        lambda: backend.read_gpio_pin_analogue_value(14),
    )


def _motor_state_now(_: object, backend: SRV4MotorBoardHardwareBackend) -> MotorState:
    return backend._states[0]


def _motor_output(state: MotorState) -> tuple[MotorMode, int]:
    if state is MotorSpecialState.BRAKE:
        return MotorMode.BRAKE, 0
    if state is MotorSpecialState.COAST:
        return MotorMode.COAST, 0
    speed = motor_codec.encode_speed(state) - 128
    return (MotorMode.FORWARD if speed >= 0 else MotorMode.REVERSE), abs(speed)


def _motor_rig(board: Board, sim: Any) -> Rig:
    backend = board.backend
    assert isinstance(backend, SRV4MotorBoardHardwareBackend)

    def pick(rng: random.Random) -> tuple[Operation, object]:
        motor = rng.randrange(2)
        choices: list[MotorState] = [
            MotorSpecialState.BRAKE,
            MotorSpecialState.COAST,
            round(rng.uniform(-1, 1), 3),
        ]
        state = rng.choice(choices)
        return (lambda: backend.set_motor_state(motor, state)), None

    def mismatches() -> list[str]:
        found = []
        for motor in range(2):
            remembered = backend._states[motor]
            output = sim.motors[motor]
            if _motor_output(remembered) != (output.mode, output.steps):
                found.append(f"motor {motor}: remembered {remembered}, board {output}")
        return found

    probe = backend.get_motor_state  # cached: reaching the board needs a set
    return Rig(
        "motor",
        board,
        sim,
        pick,
        mismatches,
        lambda: backend.set_motor_state(0, _motor_state_now(probe, backend)),
    )


def _power_rig(board: Board, sim: Any) -> Rig:
    backend = board.backend
    assert isinstance(backend, SRV4PowerBoardHardwareBackend)

    def pick(rng: random.Random) -> tuple[Operation, object]:
        on = rng.random() < 0.5
        if rng.random() < 0.7:
            output = rng.randrange(6)
            return (lambda: backend.set_power_output_enabled(output, on)), None
        led = rng.randrange(2)
        return (lambda: backend.set_led_state(led, on)), None

    def mismatches() -> list[str]:
        found = [
            f"output {n}: remembered {backend._outputs[n]}, board {sim.outputs[n]}"
            for n in range(6)
            if backend._outputs[n] != sim.outputs[n]
        ]
        if backend._leds[0] != sim.run_led:
            found.append(f"run LED: remembered {backend._leds[0]}, board {sim.run_led}")
        return found

    return Rig("power", board, sim, pick, mismatches, lambda: backend.get_battery_sensor_voltage(0))


def _servo_rig(board: Board, sim: Any) -> Rig:
    backend = board.backend
    assert isinstance(backend, SRV4ServoBoardHardwareBackend)

    def pick(rng: random.Random) -> tuple[Operation, object]:
        servo = rng.randrange(12)
        position = round(rng.uniform(-1, 1), 2)
        return (lambda: backend.set_servo_position(servo, position)), None

    def mismatches() -> list[str]:
        found = []
        for servo in range(12):
            remembered = backend._positions[servo]
            expected = round((remembered or 0.0) * 100)
            if sim.positions[servo] != expected:
                found.append(f"servo {servo}: remembered {expected}, board {sim.positions[servo]}")
        return found

    return Rig(
        "servo",
        board,
        sim,
        pick,
        mismatches,
        lambda: backend.set_servo_position(0, backend._positions[0]),
    )


_RIGS: dict[str, Callable[[Board, Any], Rig]] = {
    "sb-arduino": _sb_arduino_rig,
    "ruggeduino": _ruggeduino_rig,
    "motor": _motor_rig,
    "power": _power_rig,
    "servo": _servo_rig,
}


async def _connect(name: str, wrap: Callable[[ByteStream], ByteStream] | None) -> Rig:
    if name == "sb-arduino":
        sim: Any = SBArduinoSimulator("RIG-SB")
        board = await _serial_board(SBArduinoHardwareBackend, sim, wrap)
    elif name == "ruggeduino":
        sim = SRRuggeduinoSimulator("RIG-RUGGEDUINO")
        board = await _serial_board(SRV4RuggeduinoHardwareBackend, sim, wrap)
    elif name == "motor":
        sim = SRMotorBoardFw3Simulator("RIG-MOTOR")
        board = await _serial_board(SRV4MotorBoardHardwareBackend, sim, wrap)
    elif name == "power":
        sim = SRPowerBoardFw3Simulator("RIG-POWER")
        board = await SRV4PowerBoardHardwareBackend.from_usb_device(
            _SlowDevice(sim, random.Random(2))
        )
        await board.setup()
    else:
        sim = SRServoBoardFw2Simulator("RIG-SERVO")
        board = await SRV4ServoBoardHardwareBackend.from_usb_device(
            _SlowDevice(sim, random.Random(3))
        )
        await board.setup()
    return _RIGS[name](board, sim)


def rig_for(name: str, board: Board, sim: Any) -> Rig:
    """Make the rig of backend ``name`` around a board already connected to ``sim``."""
    return _RIGS[name](board, sim)


@asynccontextmanager
async def open_rig(
    name: str, *, wrap: Callable[[ByteStream], ByteStream] | None = None
) -> AsyncIterator[Rig]:
    """Connect backend ``name`` (one of :data:`BACKEND_NAMES`) to a fresh simulator.

    :param wrap: wraps a serial board's stream (to inject faults, say).
    :raises ValueError: an unknown name.
    """
    if name not in _RIGS:
        raise ValueError(f"no rig called {name!r}; choose from {', '.join(BACKEND_NAMES)}")
    rig = await _connect(name, wrap)
    try:
        yield rig
    finally:
        await rig.board.close()


# -- random cancellation --------------------------------------------------------------------


async def _cancel_natively(operation: Operation, delay: float, rng: random.Random) -> bool:
    """Run ``operation``, cancelling it with Task.cancel or asyncio.timeout after ``delay``."""
    if rng.random() < 0.5:
        task = asyncio.ensure_future(operation())
        await asyncio.sleep(delay)
        cancelled = task.cancel()
        try:
            await task
        except asyncio.CancelledError:
            return cancelled
        return False
    try:
        async with asyncio.timeout(delay):
            await operation()
    except TimeoutError:
        return True
    return False


async def _run_one(
    rig: Rig, style: CancellationStyle, rng: random.Random, report: TrialReport, max_delay: float
) -> None:
    operation, expected = rig.pick(rng)
    delay = rng.uniform(0, max_delay)
    result: list[object] = []

    async def run() -> None:
        result.append(await operation())

    report.trials += 1
    try:
        if style == "anyio":
            with anyio.move_on_after(delay) as scope:
                await run()
            cancelled = scope.cancelled_caught
        else:
            cancelled = await _cancel_natively(run, delay, rng)
    except (CommunicationError, ValueError) as exc:
        report.errors += 1
        report.note(f"{type(exc).__name__}: {exc}")
        cancelled = False
    report.cancelled += cancelled
    await rig.settle()
    if result and expected is not None and result[0] != expected:
        report.wrong_answers += 1
        report.note(f"answer {result[0]!r}, expected {expected!r}")
    wrong = rig.mismatches()
    if wrong:
        report.mismatches += len(wrong)
        for line in wrong:
            report.note(line)


async def cancellation_trials(
    name: str,
    style: CancellationStyle,
    trials: int,
    *,
    seed: int = 0,
    max_delay: float = 0.003,
) -> TrialReport:
    """Run ``trials`` random operations on backend ``name``, each cancelled at random.

    :param style: ``"anyio"`` (``move_on_after``) or ``"asyncio"`` (``Task.cancel`` or
        ``asyncio.timeout``, which break through anyio shields).
    :param max_delay: the latest moment of a cancellation, in seconds.
    """
    rng = random.Random(seed)
    report = TrialReport(name, style)
    async with open_rig(name) as rig:
        for _ in range(trials):
            await _run_one(rig, style, rng, report, max_delay)
    return report


def summarise(reports: Sequence[TrialReport]) -> dict[str, int]:
    """Add up the counts of several reports."""
    return {
        "trials": sum(r.trials for r in reports),
        "cancelled": sum(r.cancelled for r in reports),
        "wrong_answers": sum(r.wrong_answers for r in reports),
        "mismatches": sum(r.mismatches for r in reports),
        "errors": sum(r.errors for r in reports),
    }




# -- unplug and replug ----------------------------------------------------------------------


@dataclass
class ReplugReport:
    """What unplugging and replugging one simulated board, again and again, observed."""

    backend: str
    trials: int = 0
    #: Calls made while unplugged that failed with BoardDisconnectionError (all should).
    disconnection_errors: int = 0
    #: Calls made while unplugged that seemed to work, or failed some other way.
    wrong_outcomes: int = 0
    #: Seconds from plugging the board back in to its first answer.
    back_after: list[float] = field(default_factory=list)
    #: Cache entries that disagreed with the board once it was back.
    stale: int = 0
    #: Times discovery gave a new object instead of the one in use.
    duplicates: int = 0
    #: Times make_safe failed on the board once it was back.
    make_safe_failures: int = 0
    details: list[str] = field(default_factory=list)


_KIT_FIELDS = {
    "sb-arduino": "sb_arduinos",
    "ruggeduino": "ruggeduinos",
    "motor": "motor_boards",
    "power": "power_boards",
    "servo": "servo_boards",
}


def _board_class(name: str) -> type[Board]:
    classes: dict[str, type[Board]] = {
        "sb-arduino": SBArduinoHardwareBackend.board,
        "ruggeduino": SRV4RuggeduinoHardwareBackend.board,
        "motor": SRV4MotorBoardHardwareBackend.board,
        "power": SRV4PowerBoardHardwareBackend.board,
        "servo": SRV4ServoBoardHardwareBackend.board,
    }
    return classes[name]


async def replug_trials(name: str, trials: int, *, seed: int = 0) -> ReplugReport:
    """Unplug and replug a board of the simulated kit ``trials`` times.

    Each time: change some state, unplug, make a call (it must fail with
    :class:`~j5aio.errors.BoardDisconnectionError`), plug back in, then time how long the
    same board object takes to answer again, compare its caches with the board, look
    it up again (it must be the same object) and make it safe.
    """
    from j5aio.simulator.environment import SIMULATED_ENVIRONMENT
    from j5aio.simulator.kit import KitConfig, use_kit

    counts = dict.fromkeys(_KIT_FIELDS.values(), 0)
    counts[_KIT_FIELDS[name]] = 1
    kit = use_kit(KitConfig(**counts))
    sim = getattr(kit, _KIT_FIELDS[name])[0]
    board = (await SIMULATED_ENVIRONMENT.get_board_group(_board_class(name))).singular()
    rig = rig_for(name, board, sim)
    rng = random.Random(seed)
    report = ReplugReport(name)
    try:
        for _ in range(trials):
            await _replug_once(rig, rng, report, name)
    finally:
        await board.close()
    return report


async def _replug_once(rig: Rig, rng: random.Random, report: ReplugReport, name: str) -> None:
    from j5aio.simulator.environment import SIMULATED_ENVIRONMENT

    report.trials += 1
    operation, _ = rig.pick(rng)
    await operation()
    rig.simulator.unplug()
    try:
        await rig.probe()
    except BoardDisconnectionError:
        report.disconnection_errors += 1
    except Exception as exc:
        report.wrong_outcomes += 1
        report.details.append(f"while unplugged: {exc!r}")
    else:
        report.wrong_outcomes += 1
        report.details.append("a call worked while the board was unplugged")
    rig.simulator.plug()
    start = time.perf_counter()
    deadline = start + 5
    while True:
        try:
            await rig.probe()
            break
        except BoardDisconnectionError:
            if time.perf_counter() > deadline:
                report.details.append("the board did not answer within 5 s of its return")
                return
            await anyio.sleep(0.002)
    report.back_after.append(time.perf_counter() - start)
    await rig.settle()
    stale = rig.mismatches()
    report.stale += len(stale)
    report.details.extend(stale[:3])
    again = await SIMULATED_ENVIRONMENT.get_board_group(_board_class(name))
    if list(again) != [rig.board] or again.singular() is not rig.board:
        report.duplicates += 1
    try:
        await rig.board.make_safe()
    except Exception as exc:
        report.make_safe_failures += 1
        report.details.append(f"make_safe: {exc!r}")


# -- bad values -----------------------------------------------------------------------------

#: Values no component may accept for a power, position, level, duration or pitch.
BAD_VALUES: tuple[object, ...] = (
    math.nan,
    math.inf,
    -math.inf,
    1.0000001,
    -1.5,
    2,
    10**400,
    1e308,
    "0.5",
    b"1",
    [1],
    object(),
    0.0004,
    -0.0,
)


@dataclass
class BadValueReport:
    """What giving components bad values observed."""

    backend: str
    trials: int = 0
    #: Calls refused with TypeError or ValueError (or NotSupportedByHardwareError).
    refused: int = 0
    #: Calls that went through (a value that was fine after all, such as 2 seconds).
    accepted: int = 0
    #: Refused calls that still sent something to the board: must be 0.
    reached_the_wire: int = 0
    #: Other exceptions: must be 0.
    foreign: int = 0
    details: list[str] = field(default_factory=list)


def _traffic(rig: Rig) -> int:
    backend: Any = rig.board.backend
    link = backend.link
    device = getattr(link, "device", None)
    if device is not None:
        return int(getattr(device, "transfers", 0))
    return int(getattr(link.stream, "sent", 0))


def _bad_calls(rig: Rig, rng: random.Random) -> list[tuple[str, Operation]]:
    board: Any = rig.board
    value = rng.choice(BAD_VALUES)
    calls: list[tuple[str, Operation]] = []
    if rig.name in ("sb-arduino", "ruggeduino"):
        pin = board.pins[rng.choice(_PINS)]
        calls += [
            (f"set_mode({value!r})", lambda: pin.set_mode(value)),
            (f"digital_write({value!r})", lambda: pin.digital_write(value)),
        ]
    if rig.name in ("sb-arduino", "servo"):
        servo = board.servos[rng.randrange(4)]
        calls.append((f"set_position({value!r})", lambda: servo.set_position(value)))
    if rig.name == "motor":
        motor = board.motors[rng.randrange(2)]
        calls.append((f"set_power({value!r})", lambda: motor.set_power(value)))
    if rig.name == "power":
        output = list(board.outputs)[rng.randrange(6)]
        calls += [
            (f"set_is_enabled({value!r})", lambda: output.set_is_enabled(value)),
            (f"buzz({value!r}, 440)", lambda: board.piezo.buzz(value, 440)),
            (f"buzz(0.1, {value!r})", lambda: board.piezo.buzz(0.1, value)),
            (f"run_led.set_state({value!r})", lambda: board._run_led.set_state(value)),
        ]
    return calls


async def bad_value_trials(name: str, trials: int, *, seed: int = 0) -> BadValueReport:
    """Give the components of backend ``name`` ``trials`` random bad values.

    Counts the refused calls that nevertheless sent something to the board.
    """
    rng = random.Random(seed)
    report = BadValueReport(name)
    async with open_rig(name) as rig:
        while report.trials < trials:
            for what, call in _bad_calls(rig, rng):
                report.trials += 1
                before = _traffic(rig)
                try:
                    await call()
                except (TypeError, ValueError, NotSupportedByHardwareError):
                    report.refused += 1
                    await rig.settle()
                    if _traffic(rig) != before:
                        report.reached_the_wire += 1
                        report.details.append(f"{what} was refused but reached the wire")
                except Exception as exc:
                    report.foreign += 1
                    report.details.append(f"{what}: {exc!r}")
                else:
                    report.accepted += 1
    return report


# -- fuzzed replies -------------------------------------------------------------------------


@dataclass
class FuzzReport:
    """What requests answered with random bytes observed."""

    backend: str
    trials: int = 0
    #: CommunicationError (or a subclass): the right way to fail.
    communication_errors: int = 0
    #: Answers that were returned (the random bytes happened to be a valid reply).
    answers: int = 0
    #: Any other exception: must be 0.
    foreign: int = 0
    details: list[str] = field(default_factory=list)


class _FuzzedStream(ByteStream):
    """A stream whose board answers every request with random bytes."""

    def __init__(self, name: str, rng: random.Random, replies: Callable[[random.Random], bytes]):
        self._name = name
        self._rng = rng
        self._replies = replies
        self._pending = bytearray()
        self._arrived = anyio.Event()
        self._closed = False

    @property
    def name(self) -> str:
        return self._name

    @property
    def is_closed(self) -> bool:
        return self._closed

    async def send(self, data: bytes) -> None:
        await anyio.lowlevel.checkpoint()
        self._pending += self._replies(self._rng)
        self._arrived.set()

    async def receive(self, max_bytes: int = 4096) -> bytes:
        while not self._pending:
            if self._closed:
                raise anyio.ClosedResourceError
            self._arrived = anyio.Event()
            await self._arrived.wait()
        data = bytes(self._pending[:max_bytes])
        del self._pending[:max_bytes]
        return data

    def close_now(self) -> None:
        self._closed = True
        self._arrived.set()


def _fuzz_reply(rng: random.Random) -> bytes:
    """Random bytes, often shaped like a reply line, sometimes wildly not."""
    pieces = [
        b"> ",
        b"+ OK",
        b"- Error",
        b"# ",
        b"@1 ",
        b"a0 ",
        b"inf",
        b"nan",
        b"1e20",
        b"9" * rng.randrange(1, 500),
        b"-1",
        b"\r\n",
        b"\n",
        b"h",
        b"l",
        b"SRduino:1",
        b"MCV4B:3",
        bytes(rng.randrange(256) for _ in range(rng.randrange(8))),
    ]
    return b"".join(rng.choice(pieces) for _ in range(rng.randrange(1, 8))) + b"\n"


class _FuzzedDevice:
    """A USB device that answers every read with random bytes of a random length."""

    def __init__(self, simulator: Any, rng: random.Random) -> None:
        self._simulator = simulator
        self._rng = rng
        self.fuzzing = False

    def __getattr__(self, name: str) -> Any:
        return getattr(self._simulator, name)

    def ctrl_transfer(self, request_type: int, *args: Any, **kwargs: Any) -> Any:
        result = self._simulator.ctrl_transfer(request_type, *args, **kwargs)
        if self.fuzzing and request_type & 0x80:
            length = self._rng.choice([0, 1, 3, 4, 5, 8, 9, 64])
            return bytes(self._rng.randrange(256) for _ in range(length))
        return result


async def _fuzz_serial(name: str, trials: int, rng: random.Random, report: FuzzReport) -> None:
    sim: Any = SBArduinoSimulator("FUZZ") if name == "sb-arduino" else SRRuggeduinoSimulator("F")
    backend_class: Any = (
        SBArduinoHardwareBackend if name == "sb-arduino" else SRV4RuggeduinoHardwareBackend
    )

    class Quick(backend_class):  # type: ignore[misc]
        DEFAULT_TIMEOUT = 0.02
        ULTRASOUND_TIMEOUT = 0.02  # a fuzzed reply need not be waited for seconds

    board = await Quick.from_stream(
        SimulatorStream(sim, time_scale=0), port="fuzz", serial_number="F", time_scale=0.01
    )
    backend = board.backend
    fuzzed = _FuzzedStream("fuzzed", rng, _fuzz_reply)
    backend._link = type(backend.link)(fuzzed, name="fuzzed", default_timeout=0.02)
    reads = [
        lambda: backend.read_gpio_pin_digital_state(rng.choice(_PINS)),
        lambda: backend.read_gpio_pin_analogue_value(14 + rng.randrange(4)),
        lambda: backend.set_gpio_pin_mode(rng.choice(_PINS), rng.choice(_MODES[:2])),
    ]
    if name == "sb-arduino":
        reads += [
            lambda: backend.get_ultrasound_distance(2, 3),
            lambda: backend.get_ultrasound_pulse(4, 5),
        ]
    for _ in range(trials):
        await _fuzz_one(rng.choice(reads), report)
    await board.close()


async def _fuzz_usb(name: str, trials: int, rng: random.Random, report: FuzzReport) -> None:
    sim: Any = SRPowerBoardFw3Simulator("F") if name == "power" else SRServoBoardFw2Simulator("F")
    device = _FuzzedDevice(sim, rng)
    backend_class: Any = (
        SRV4PowerBoardHardwareBackend if name == "power" else SRV4ServoBoardHardwareBackend
    )
    board = await backend_class.from_usb_device(device)
    backend = board.backend
    device.fuzzing = True
    if name == "power":
        reads = [
            lambda: backend.get_battery_sensor_voltage(0),
            lambda: backend.get_power_output_current(rng.randrange(6)),
            lambda: backend.get_button_state(0),
        ]
    else:
        reads = [backend._handshake]
    for _ in range(trials):
        await _fuzz_one(rng.choice(reads), report)
    await board.close()


async def _fuzz_motor(trials: int, rng: random.Random, report: FuzzReport) -> None:
    for _ in range(trials):
        fuzzed = _FuzzedStream("fuzzed", rng, _fuzz_reply)
        await _fuzz_one(functools.partial(_motor_handshake, fuzzed), report)


async def _motor_handshake(stream: ByteStream) -> Board:
    return await SRV4MotorBoardHardwareBackend.from_stream(
        stream, port="fuzz", serial_number="F", time_scale=0.01
    )


async def _fuzz_one(call: Operation, report: FuzzReport) -> None:
    report.trials += 1
    try:
        result = await call()
    except CommunicationError:
        report.communication_errors += 1
        return
    except Exception as exc:
        report.foreign += 1
        if len(report.details) < 10:
            report.details.append(repr(exc))
        return
    report.answers += 1
    if isinstance(result, Board):
        await result.close()


async def fuzzed_reply_trials(name: str, trials: int, *, seed: int = 0) -> FuzzReport:
    """Answer ``trials`` requests of backend ``name`` with random bytes.

    Counts the exceptions that are not :class:`~j5aio.errors.CommunicationError`.
    """
    rng = random.Random(seed)
    report = FuzzReport(name)
    if name in ("sb-arduino", "ruggeduino"):
        await _fuzz_serial(name, trials, rng, report)
    elif name == "motor":
        await _fuzz_motor(trials, rng, report)
    elif name in ("power", "servo"):
        await _fuzz_usb(name, trials, rng, report)
    else:
        raise ValueError(f"no rig called {name!r}; choose from {', '.join(BACKEND_NAMES)}")
    return report
