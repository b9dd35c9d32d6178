"""A cancelled pin-mode change leaves the remembered pin table true to the board.

Making a pin an output takes two requests on today's Arduinos (its level, then its
mode); they go as one exchange, so a cancellation cannot fall between them.
"""

from __future__ import annotations

from typing import Any

import anyio
import pytest

from j5aio.backends.hardware.arduino_gpio import ArduinoGPIOBackend
from j5aio.backends.hardware.sb.arduino_2024 import SBArduino2024HardwareBackend
from j5aio.backends.hardware.sr.v4.arduino import SRArduinoHardwareBackend
from j5aio.backends.hardware.transports.memory import SimulatorStream
from j5aio.components.gpio_pin import GPIOPinMode
from j5aio.errors import UnexpectedReplyError
from j5aio.simulator import PinMode, SBArduino2024Simulator
from j5aio.simulator.sr_ruggeduino_fw1 import SRRuggeduinoSimulator
from j5aio.testing.transports import RecordingStream, ScriptedStream

SIM_MODES = {
    GPIOPinMode.DIGITAL_INPUT: PinMode.INPUT,
    GPIOPinMode.DIGITAL_INPUT_PULLUP: PinMode.INPUT_PULLUP,
    GPIOPinMode.DIGITAL_OUTPUT: PinMode.OUTPUT,
}


class CancellingStream(RecordingStream):
    """Cancels ``scope`` as soon as a request starting with ``trigger`` has been sent."""

    trigger: bytes | None = None
    scope: anyio.CancelScope | None = None

    async def send(self, data: bytes) -> None:
        await super().send(data)
        if self.trigger is not None and data.startswith(self.trigger) and self.scope:
            self.scope.cancel()


def _sims() -> dict[str, tuple[Any, type[ArduinoGPIOBackend[Any]], bytes]]:
    return {
        "sr-arduino-fw2": (
            SRRuggeduinoSimulator("A1", firmware_version=2), SRArduinoHardwareBackend, b"le",
        ),
        "sb2024": (
            SBArduino2024Simulator("A2"), SBArduino2024HardwareBackend, b"PIN:4:DIGITAL:SET:0",
        ),
    }


@pytest.mark.parametrize("name", ["sr-arduino-fw2", "sb2024"])
async def test_a_cancelled_switch_to_output_is_all_or_nothing(name: str) -> None:
    sim, backend_class, level_request = _sims()[name]
    stream = CancellingStream(SimulatorStream(sim, time_scale=0))
    board = await backend_class.from_stream(stream, port="sim", serial_number="A")
    await board.setup()
    pin = board.pins[4]
    await pin.set_mode(GPIOPinMode.DIGITAL_OUTPUT)
    await pin.digital_write(False)
    await pin.set_mode(GPIOPinMode.DIGITAL_INPUT_PULLUP)  # the latch is high: the pull-up
    assert sim.pin_mode(4) is PinMode.INPUT_PULLUP

    # Cancelled as soon as the low level has gone, before the mode could follow.
    with anyio.CancelScope() as scope:
        stream.trigger, stream.scope = level_request, scope
        await pin.set_mode(GPIOPinMode.DIGITAL_OUTPUT)
    stream.trigger = None
    backend = board.backend
    assert isinstance(backend, ArduinoGPIOBackend)
    remembered = backend.pins.mode(4)
    assert SIM_MODES[remembered] is sim.pin_mode(4)
    assert remembered is GPIOPinMode.DIGITAL_OUTPUT  # the exchange ran to its end
    assert sim.output_level(4) is False
    await board.close()


async def test_a_bad_reply_to_the_pair_names_the_board_and_leaves_the_mode() -> None:
    stream = ScriptedStream([(b"v", b"SRduino:2\n"), (b"lcoc", b"\nx\n")])
    board = await SRArduinoHardwareBackend.from_stream(stream, port="s", serial_number="A")
    backend = board.backend
    assert isinstance(backend, SRArduinoHardwareBackend)
    with pytest.raises(UnexpectedReplyError, match=r"SR Arduino.* on s: bad reply b'x'"):
        await backend.set_gpio_pin_mode(2, GPIOPinMode.DIGITAL_OUTPUT)
    assert backend.pins.mode(2) is GPIOPinMode.DIGITAL_INPUT
    stream.assert_all_used()
    await board.close()
