"""A reply that comes after its request timed out never answers a later request.

Today's boards (the fw 4 text firmwares, SR Arduino firmware 2, SB Arduino sb2024) name
nothing of the request in a reply, so after a timeout the link resynchronises with a
probe whose answer is known before it sends the next request. Each test delays one
reply past its request's timeout and asks another question whose true answer differs
from the late one: the second answer must be its own.
"""

from __future__ import annotations

from collections.abc import Awaitable, Callable
from typing import Any, ClassVar

import anyio
import pytest

from j5aio.backends.hardware.sb.arduino_2024 import SBArduino2024HardwareBackend
from j5aio.backends.hardware.serial_backend import SerialHardwareBackend
from j5aio.backends.hardware.sr.v4.arduino import SRArduinoHardwareBackend
from j5aio.backends.hardware.sr.v4.motor_board_fw4 import SRV4MotorBoardFw4HardwareBackend
from j5aio.backends.hardware.sr.v4.power_board_fw4 import SRV4PowerBoardFw4HardwareBackend
from j5aio.backends.hardware.sr.v4.servo_board_fw4 import SRV4ServoBoardFw4HardwareBackend
from j5aio.backends.hardware.sr.v4.text_protocol import echo_probe
from j5aio.backends.hardware.transports.memory import SimulatorStream
from j5aio.components.gpio_pin import GPIOPinMode
from j5aio.errors import CommunicationError, CommunicationTimeoutError
from j5aio.simulator import (
    SBArduino2024Simulator,
    SRMotorBoardFw4Simulator,
    SRPowerBoardFw4Simulator,
    SRServoBoardFw4Simulator,
)
from j5aio.simulator.sr_ruggeduino_fw1 import SRRuggeduinoSimulator
from j5aio.testing.transports import FaultyStream, RecordingStream

TIMEOUT = 0.05

Ask = Callable[[Any], Awaitable[object]]


class QuickPower(SRV4PowerBoardFw4HardwareBackend):
    DEFAULT_TIMEOUT: ClassVar[float] = TIMEOUT


class QuickMotor(SRV4MotorBoardFw4HardwareBackend):
    DEFAULT_TIMEOUT: ClassVar[float] = TIMEOUT


class QuickServo(SRV4ServoBoardFw4HardwareBackend):
    DEFAULT_TIMEOUT: ClassVar[float] = TIMEOUT


class QuickSRArduino(SRArduinoHardwareBackend):
    DEFAULT_TIMEOUT: ClassVar[float] = TIMEOUT


class QuickSB2024(SBArduino2024HardwareBackend):
    DEFAULT_TIMEOUT: ClassVar[float] = TIMEOUT


def _power() -> tuple[Any, type[SerialHardwareBackend], Ask, Ask, object]:
    sim = SRPowerBoardFw4Simulator("srP1")
    sim.battery_voltage = 11.5
    sim.set_output_current(4, 2.25)  # L2, the brain output, is always on
    return (
        sim,
        QuickPower,
        lambda b: b.get_battery_sensor_voltage(0),
        lambda b: b.get_power_output_current(4),
        2.25,
    )


def _motor() -> tuple[Any, type[SerialHardwareBackend], Ask, Ask, object]:
    sim = SRMotorBoardFw4Simulator("srM1")
    sim.input_voltage = 11.5
    sim.set_motor_current(1, 3.5)
    return (
        sim,
        QuickMotor,
        lambda b: b.get_voltage_sensor_voltage(0),
        lambda b: b.get_motor_current(1),
        3.5,
    )


def _servo() -> tuple[Any, type[SerialHardwareBackend], Ask, Ask, object]:
    sim = SRServoBoardFw4Simulator("srS1")
    sim.set_supply(voltage=6.0, current=0.75)
    return (
        sim,
        QuickServo,
        lambda b: b.get_supply_voltage(0),
        lambda b: b.get_supply_current(0),
        0.75,
    )


def _sr_arduino() -> tuple[Any, type[SerialHardwareBackend], Ask, Ask, object]:
    sim = SRRuggeduinoSimulator("A1", firmware_version=2)
    sim.set_analogue(14, raw=512)
    sim.set_ultrasound_distance(2, 3, 0.25)
    return (
        sim,
        QuickSRArduino,
        lambda b: b.read_gpio_pin_analogue_value(14),
        lambda b: b.get_ultrasound_distance(2, 3),
        pytest.approx(0.25, abs=0.001),
    )


def _sb2024() -> tuple[Any, type[SerialHardwareBackend], Ask, Ask, object]:
    sim = SBArduino2024Simulator("A2")
    sim.set_analogue(14, raw=512)
    sim.set_ultrasound_distance(2, 3, 0.25)
    return (
        sim,
        QuickSB2024,
        lambda b: b.read_gpio_pin_analogue_value(14),
        lambda b: b.get_ultrasound_distance(2, 3),
        pytest.approx(0.25, abs=0.001),
    )


BOARDS = {
    "power-fw4": _power,
    "motor-fw4": _motor,
    "servo-fw4": _servo,
    "sr-arduino-fw2": _sr_arduino,
    "sb2024": _sb2024,
}


async def _connect(make: Callable[[], Any]) -> tuple[Any, Any, Ask, Ask, object, FaultyStream]:
    sim, backend_class, first, second, expected = make()
    faulty = FaultyStream(SimulatorStream(sim, time_scale=0))
    board = await backend_class.from_stream(faulty, port="sim", serial_number="S1")
    await board.setup()
    if "arduino" in backend_class.__module__:
        await board.pins[14].set_mode(GPIOPinMode.ANALOGUE_INPUT)
    if backend_class is QuickMotor:
        await board.backend.set_motor_state(1, 0.5)  # a coasting motor draws nothing
    return sim, board, first, second, expected, faulty


@pytest.mark.parametrize("late_by", [0.02, 0.04])
@pytest.mark.parametrize("name", list(BOARDS))
async def test_a_late_reply_is_not_the_next_answer(name: str, late_by: float) -> None:
    _, board, first, second, expected, faulty = await _connect(BOARDS[name])
    backend = board.backend
    faulty.delay_next_reply(TIMEOUT + late_by)
    with pytest.raises(CommunicationTimeoutError):
        await first(backend)
    # The late reply (a voltage, an ADC reading) arrives while this request waits.
    assert await second(backend) == expected
    assert not backend.link.is_dirty
    await board.close()


@pytest.mark.parametrize("name", list(BOARDS))
async def test_a_clean_link_sends_no_probe(name: str) -> None:
    sim, backend_class, _, second, _ = BOARDS[name]()
    recording = RecordingStream(SimulatorStream(sim, time_scale=0))
    board = await backend_class.from_stream(recording, port="sim", serial_number="S1")
    recording.clear()
    await second(board.backend)
    assert b"ECHO" not in recording.sent
    assert b"*IDN?" not in recording.sent
    assert not recording.sent.startswith(b"v")
    await board.close()


async def test_fw4_resynchronises_with_a_fresh_echo_each_time() -> None:
    sim, _, first, _, _ = _power()
    recording = RecordingStream(FaultyStream(SimulatorStream(sim, time_scale=0)))
    faulty = recording.inner
    assert isinstance(faulty, FaultyStream)
    board = await QuickPower.from_stream(recording, port="sim", serial_number="srP1")
    backend = board.backend
    assert isinstance(backend, QuickPower)
    probes = []
    for _ in range(2):
        faulty.delay_next_reply(TIMEOUT + 0.02)
        with pytest.raises(CommunicationTimeoutError):
            await first(backend)
        recording.clear()
        assert await backend.get_battery_sensor_voltage(0) == 11.5
        probe = recording.sent.split(b"\n")[0]
        assert probe.startswith(b"ECHO:SYNC")
        probes.append(probe)
    assert probes[0] != probes[1]
    await board.close()


def test_the_echo_probe_is_answered_by_its_nonce() -> None:
    request, answer = echo_probe()
    again, other = echo_probe()
    assert request == b"ECHO:" + answer + b"\n"
    assert answer.startswith(b"SYNC") and b":" not in answer
    assert other != answer and again != request


async def test_a_board_silent_after_a_late_reply_gives_errors_then_answers_again() -> None:
    _, board, first, second, _, faulty = await _connect(_sr_arduino)
    backend = board.backend
    faulty.delay_next_reply(TIMEOUT + 0.02)
    with pytest.raises(CommunicationTimeoutError):
        await first(backend)
    faulty.silence()
    with pytest.raises(CommunicationError):
        await second(backend)
    assert backend.link.is_dirty
    faulty.resume()
    assert await backend.read_gpio_pin_analogue_value(14) == pytest.approx(2.5)
    await board.close()


@pytest.mark.parametrize("late_by", [0.01, 0.05])
@pytest.mark.parametrize("name", list(BOARDS))
async def test_a_late_reply_that_later_replies_overtake_is_never_an_answer(
    name: str, late_by: float
) -> None:
    """The late reply comes after replies to later requests (out of order)."""
    _, board, first, second, expected, faulty = await _connect(BOARDS[name])
    backend = board.backend
    faulty.hold_next_reply(TIMEOUT + late_by)
    with pytest.raises(CommunicationTimeoutError):
        await first(backend)
    answers = 0
    for _ in range(12):  # the held reply comes during one of these, or between them
        try:
            value = await second(backend)
        except CommunicationError:
            continue  # it came amid a reply: an error, never a wrong answer
        finally:
            await anyio.sleep(0.01)
        assert value == expected
        answers += 1
    assert answers >= 10
    await board.close()


async def test_a_late_line_is_waited_for_only_so_long() -> None:
    """A reply that never comes stops costing probes after the link's late limit."""
    sim, _, first, second, expected = _power()
    faulty = FaultyStream(SimulatorStream(sim, time_scale=0))
    recording = RecordingStream(faulty)
    board = await QuickPower.from_stream(recording, port="sim", serial_number="srP1")
    backend = board.backend
    assert isinstance(backend, QuickPower)
    backend.link._late_limit = 0.1  # (the default is seconds)
    faulty.drop_next_reply()
    with pytest.raises(CommunicationTimeoutError):
        await first(backend)
    recording.clear()
    assert await second(backend) == expected
    assert recording.sent.count(b"ECHO:") == 2  # bracketed: the dropped line may yet come
    await anyio.sleep(0.1)
    recording.clear()
    assert await second(backend) == expected
    assert b"ECHO:" not in recording.sent  # given up for lost: plain again
    await board.close()
