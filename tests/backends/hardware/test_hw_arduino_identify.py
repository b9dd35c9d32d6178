"""Telling the four Arduino firmwares apart on one open port, in the order the report gives.

They share USB IDs, so only what they answer tells them apart: the SB 2019 firmware
prints a banner when the port opens; the SR firmwares answer ``v`` at once; the sb2024
firmware answers ``*IDN?`` (after a NACK for the ``v`` left in its line buffer).
"""

from __future__ import annotations

import pytest

from j5aio.backends.hardware.arduino_gpio import ArduinoGPIOBackend
from j5aio.backends.hardware.sb import SBArduino2024HardwareBackend
from j5aio.backends.hardware.sr.v4 import SRArduinoHardwareBackend
from j5aio.backends.hardware.transports.memory import SimulatorStream
from j5aio.backends.hardware.transports.serial_link import SerialLink
from j5aio.boards.arduino import AnaloguePin
from j5aio.boards.arduino.all_digital import AllDigitalUno
from j5aio.errors import CommunicationError, CommunicationTimeoutError, UnsupportedFirmwareError
from j5aio.simulator import (
    SBArduino2024Simulator,
    SBArduinoSimulator,
    SerialBoardSimulator,
    SRRuggeduinoSimulator,
)
from j5aio.simulator.arduino_base import ArduinoBoardSimulator
from j5aio.simulator.serve import serve_on_pty

SCALE = 0.1  # replies from a simulator are instant; keep the waits short


async def probe(link: SerialLink) -> str:
    """Return which firmware answers on ``link``."""
    try:
        first = await link.read_line(timeout=0.05)
    except CommunicationTimeoutError:
        first = b""
    if first == b"# Booted":
        return "sb2019"
    try:
        await SRArduinoHardwareBackend.identify_firmware(link, time_scale=SCALE, attempts=1)
    except UnsupportedFirmwareError as error:
        return f"sr-fw{error.found}"
    except CommunicationError:
        version = await SBArduino2024HardwareBackend.identify_firmware(
            link, time_scale=SCALE, attempts=2,
        )
        return f"sb{version}"
    return "sr-fw2"


@pytest.mark.parametrize(
    ("simulator", "expected"),
    [
        (SBArduinoSimulator("A"), "sb2019"),
        (SRRuggeduinoSimulator("B"), "sr-fw1"),
        (SRRuggeduinoSimulator("C", firmware_version=2), "sr-fw2"),
        (SBArduino2024Simulator("D"), "sb2.0"),
    ],
)
async def test_one_open_port_tells_the_four_firmwares_apart(
    simulator: SerialBoardSimulator, expected: str,
) -> None:
    link = SerialLink(SimulatorStream(simulator, time_scale=0), name="sim")
    assert await probe(link) == expected
    await link.aclose()


async def test_an_sb2019_board_whose_banner_was_missed_fails_both_cleanly() -> None:
    link = SerialLink(SimulatorStream(SBArduinoSimulator("A"), time_scale=0), name="sim")
    await link.drain()  # the banner went by unread
    for backend in (SRArduinoHardwareBackend, SBArduino2024HardwareBackend):
        with pytest.raises(CommunicationError):
            await backend.identify_firmware(link, time_scale=SCALE, attempts=2)
    await link.aclose()


@pytest.mark.parametrize(
    ("backend_class", "simulator", "version"),
    [
        (SRArduinoHardwareBackend, SRRuggeduinoSimulator("P1", firmware_version=2), "2"),
        (SBArduino2024HardwareBackend, SBArduino2024Simulator("P2"), "2.0"),
    ],
)
async def test_attach_over_a_real_pseudo_terminal(
    backend_class: type[ArduinoGPIOBackend], simulator: ArduinoBoardSimulator, version: str,
) -> None:
    with serve_on_pty(simulator, time_scale=0.02) as server:
        board = await backend_class.attach(server.path, time_scale=0.1)
        assert isinstance(board, AllDigitalUno)
        assert board.firmware_version == version
        await board.setup()
        simulator.set_analogue(AnaloguePin.A3, volts=2.5)
        assert await board.pins[AnaloguePin.A3].analogue_read() == 2.5
        simulator.set_ultrasound_distance(6, 7, 0.3)
        assert await board.ultrasound_sensors[6, 7].distance() == 0.3
        assert await backend_class.attach(server.path) is board
        await board.close()
