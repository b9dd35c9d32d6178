"""Late replies are never taken as the answer to a later request."""

from __future__ import annotations

from typing import ClassVar

import pytest

from j5aio.backends.hardware.sb.arduino import SBArduinoHardwareBackend
from j5aio.backends.hardware.sr.v4.motor_board import SRV4MotorBoardHardwareBackend
from j5aio.backends.hardware.sr.v4.ruggeduino import SRV4RuggeduinoHardwareBackend
from j5aio.backends.hardware.transports.memory import SimulatorStream
from j5aio.components.gpio_pin import GPIOPinMode
from j5aio.components.motor import MotorSpecialState
from j5aio.errors import CommunicationTimeoutError
from j5aio.simulator import SBArduinoSimulator
from j5aio.simulator.sr_motor_fw3 import SRMotorBoardFw3Simulator as MotorBoardSimulator
from j5aio.simulator.sr_ruggeduino_fw1 import SRRuggeduinoSimulator as RuggeduinoSimulator
from j5aio.testing.transports import FaultyStream, RecordingStream

TIMEOUT = 0.05


class QuickSBArduino(SBArduinoHardwareBackend):
    DEFAULT_TIMEOUT: ClassVar[float] = TIMEOUT


class QuickRuggeduino(SRV4RuggeduinoHardwareBackend):
    DEFAULT_TIMEOUT: ClassVar[float] = TIMEOUT


@pytest.mark.parametrize("late_by", [0.020, 0.025, 0.035])
async def test_sb_arduino_skips_a_reply_that_arrives_after_its_request_timed_out(
    late_by: float,
) -> None:
    sim = SBArduinoSimulator("A1")
    faulty = FaultyStream(SimulatorStream(sim, time_scale=0))
    recording = RecordingStream(faulty)
    board = await QuickSBArduino.from_stream(recording, port="sim", serial_number="A1")
    await board.setup()
    sim.set_input_level(2, True)
    sim.set_input_level(3, False)
    faulty.delay_next_reply(TIMEOUT + late_by)
    recording.clear()
    with pytest.raises(CommunicationTimeoutError):
        await board.pins[2].digital_read()
    # The HIGH of pin 2 arrives 20-35 ms after the timeout, during the next request,
    # which carries a request id because a reply was outstanding.
    assert await board.pins[3].digital_read() is False
    # Its own reply came after the late one: the line is clean, requests go plain again.
    assert await board.pins[2].digital_read() is True
    assert recording.sent.split(b"\n") == [b"R 2", b"@1 R 3", b"R 2", b""]
    await board.close()


async def test_ruggeduino_resynchronises_with_the_version_probe_after_a_timeout() -> None:
    sim = RuggeduinoSimulator("R1")
    faulty = FaultyStream(SimulatorStream(sim, time_scale=0))
    recording = RecordingStream(faulty)
    board = await QuickRuggeduino.from_stream(recording, port="sim", serial_number="R1")
    await board.setup()
    await board.pins[3].set_mode(GPIOPinMode.DIGITAL_INPUT)
    sim.set_input_level(2, True)
    sim.set_input_level(3, False)
    faulty.delay_next_reply(TIMEOUT + 0.03)
    with pytest.raises(CommunicationTimeoutError):
        await board.pins[2].digital_read()
    recording.clear()
    assert await board.pins[3].digital_read() is False
    # Sent between two probes: the late reply might yet come after later ones.
    assert recording.sent == b"vrdv"
    assert await board.pins[2].digital_read() is True
    await board.close()


async def test_motor_board_resynchronises_after_a_send_that_did_not_finish() -> None:
    sim = MotorBoardSimulator("M1")
    faulty = FaultyStream(SimulatorStream(sim, time_scale=0))
    recording = RecordingStream(faulty)
    board = await SRV4MotorBoardHardwareBackend.from_stream(
        recording, port="sim", serial_number="M1"
    )
    backend = board.backend
    assert isinstance(backend, SRV4MotorBoardHardwareBackend)
    backend.link.mark_dirty()  # as after a send that timed out half way
    recording.clear()
    await backend.set_motor_state(0, MotorSpecialState.COAST)
    assert recording.sent == b"\x00\x01\x02\x01"
    assert not backend.link.is_dirty
    await board.close()
