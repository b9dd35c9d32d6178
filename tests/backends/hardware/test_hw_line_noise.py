"""A burst of line noise costs at most the request it hit, never the link."""

from __future__ import annotations

import pytest

from j5aio.backends.hardware.sb.arduino import SBArduinoHardwareBackend
from j5aio.backends.hardware.transports.memory import SimulatorStream
from j5aio.backends.hardware.transports.readers import DEFAULT_MAX_LINE
from j5aio.errors import CommunicationError
from j5aio.simulator import SBArduinoSimulator
from j5aio.testing.transports import FaultyStream

NOISE = bytes(range(0x20, 0x7F)) * (DEFAULT_MAX_LINE // 95 + 2)  # over 4 KiB, no line end


@pytest.mark.parametrize("noise_at", ["start", "end"])
async def test_sb_arduino_2019_recovers_from_a_long_burst_without_a_line_ending(
    noise_at: str,
) -> None:
    sim = SBArduinoSimulator("A1")
    faulty = FaultyStream(SimulatorStream(sim, time_scale=0))
    board = await SBArduinoHardwareBackend.from_stream(faulty, port="sim", serial_number="A1")
    await board.setup()
    sim.set_input_level(2, True)

    def noisy(reply: bytes) -> bytes:
        return NOISE + reply if noise_at == "start" else reply + NOISE

    faulty.corrupt_next_reply(noisy, terminator=b"+ OK\r\n")
    with pytest.raises(CommunicationError):
        for _ in range(2):  # noise after a reply shows only on the next request
            await board.pins[2].digital_read()
    for _ in range(20):
        assert await board.pins[2].digital_read() is True
    await board.close()
