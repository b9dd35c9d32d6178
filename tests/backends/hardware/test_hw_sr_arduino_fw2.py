"""The SR Arduino firmware 2 hardware backend, against the SR firmware simulator and scripts."""

from __future__ import annotations

import contextlib

import anyio
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from j5aio.backends.hardware.serial_backend import SerialHardwareBackend
from j5aio.backends.hardware.sr.v4 import SRArduinoHardwareBackend, SRV4RuggeduinoHardwareBackend
from j5aio.backends.hardware.transports.memory import SimulatorStream
from j5aio.backends.hardware.transports.serial_link import SerialLink
from j5aio.boards.sr.v4 import Ruggeduino, SRArduinoBoard
from j5aio.components.gpio_pin import GPIOPinMode
from j5aio.errors import (
    CommunicationError,
    CommunicationTimeoutError,
    NotSupportedByHardwareError,
    UnexpectedReplyError,
    UnsupportedFirmwareError,
)
from j5aio.simulator import PinMode, SRRuggeduinoSimulator
from j5aio.testing.transports import RecordingStream, ScriptedStream

Backend = SRArduinoHardwareBackend
SETUP = [(b"i" + bytes([ord("a") + pin]), b"\n") for pin in range(2, 20)]


def fw2(serial: str = "SRA1") -> SRRuggeduinoSimulator:
    return SRRuggeduinoSimulator(serial, firmware_version=2)


async def connect(
    sim: SRRuggeduinoSimulator, time_scale: float = 0.0,
) -> tuple[SRArduinoBoard, Backend, RecordingStream]:
    stream = RecordingStream(SimulatorStream(sim, time_scale=time_scale))
    board = await Backend.from_stream(
        stream, port="sim-sr-arduino", serial_number=sim.serial_number, time_scale=0.01,
    )
    assert isinstance(board, SRArduinoBoard)
    await board.setup()
    backend = board.backend
    assert isinstance(backend, Backend)
    return board, backend, stream


async def test_handshake_and_setup_traffic() -> None:
    stream = ScriptedStream([(b"v", b"\n"), (b"v", b"SRduino:2\n"), *SETUP])
    board = await Backend.from_stream(stream, port="scripted", serial_number="SRA1")
    assert board.firmware_version == "2"
    assert isinstance(board, Ruggeduino)  # an SR Arduino is a Ruggeduino with more
    backend = board.backend
    assert isinstance(backend, Backend)
    assert backend.is_official_firmware
    await board.setup()
    stream.assert_all_used()
    await board.close()


async def test_handshake_waits_for_the_simulated_boot() -> None:
    board, _, stream = await connect(fw2(), time_scale=0.05)
    assert board.firmware_version == "2"
    assert stream.sent.startswith(b"vv")
    await board.close()


async def test_garbage_during_boot_is_asked_again() -> None:
    stream = ScriptedStream([(b"v", b"\x00\xfe\n"), (b"v", b"SRduino:2\n")])
    board = await Backend.from_stream(stream, port="scripted", serial_number="SRA1")
    assert board.firmware_version == "2"
    await board.close()


@pytest.mark.parametrize(
    ("backend_class", "reply", "found", "supported"),
    [(SRArduinoHardwareBackend, b"SRduino:1\n", "1", "2"),
     (SRV4RuggeduinoHardwareBackend, b"SRduino:2\n", "2", "1")],
)
async def test_each_firmware_refuses_the_other(
    backend_class: type[SerialHardwareBackend], reply: bytes, found: str, supported: str,
) -> None:
    stream = ScriptedStream([(b"v", reply)])
    with pytest.raises(UnsupportedFirmwareError, match=f"'{found}'.*supports only {supported}"):
        await backend_class.from_stream(stream, port="scripted", serial_number="R1")
    assert stream.is_closed


async def test_a_silent_board_gives_up_after_the_bounded_attempts() -> None:
    stream = ScriptedStream([(b"v", b"")] * 2)
    link = SerialLink(stream, name="scripted", default_timeout=1)
    with pytest.raises(CommunicationTimeoutError, match="2 tries"):
        await Backend.identify_firmware(link, time_scale=0.001, attempts=2)


async def test_identify_on_an_open_link() -> None:
    link = SerialLink(SimulatorStream(fw2(), time_scale=0), name="sim")
    assert await Backend.identify_firmware(link, attempts=1) == "2"
    await link.aclose()


async def test_pins_against_the_simulator() -> None:
    sim = fw2()
    board, _backend, stream = await connect(sim)
    assert stream.sent.endswith(b"".join(request for request, _ in SETUP))
    stream.clear()
    await board.pins[3].set_mode(GPIOPinMode.DIGITAL_OUTPUT)
    await board.pins[3].digital_write(True)
    assert stream.sent == b"ldodhd"
    assert (sim.pin_mode(3), sim.output_level(3)) == (PinMode.OUTPUT, True)
    await board.pins[4].set_mode(GPIOPinMode.DIGITAL_INPUT_PULLUP)
    assert await board.pins[4].digital_read() is True
    sim.set_input_level(4, False)
    assert await board.pins[4].digital_read() is False
    # A0-A5 take digital modes on this firmware.
    stream.clear()
    await board.pins[14].set_mode(GPIOPinMode.DIGITAL_OUTPUT)
    await board.pins[14].digital_write(True)
    assert stream.sent == b"loooho"
    assert sim.output_level(14) is True
    await board.pins[15].set_mode(GPIOPinMode.DIGITAL_INPUT)
    sim.set_input_level(15, True)
    assert await board.pins[15].digital_read() is True
    await board.pins[15].set_mode(GPIOPinMode.ANALOGUE_INPUT)
    sim.set_analogue(15, raw=256)
    stream.clear()
    assert await board.pins[15].analogue_read() == 1.25
    assert stream.sent == b"ap"
    await board.close()


async def test_ultrasound_against_the_simulator() -> None:
    sim = fw2()
    board, backend, stream = await connect(sim)
    sensor = board.ultrasound_sensors[2, 19]
    sim.set_ultrasound_distance(2, 19, 1.23)
    stream.clear()
    assert await sensor.distance() == 1.23
    assert stream.sent == b"uct"
    assert backend.pins.mode(2) is GPIOPinMode.DIGITAL_OUTPUT
    assert backend.pins.mode(19) is GPIOPinMode.DIGITAL_INPUT
    assert await board.pins[2].get_last_digital_write() is False
    sim.set_ultrasound_distance(2, 19, None)
    assert await sensor.distance() is None
    assert await sensor.pulse() is None
    await board.close()


async def test_raw_commands_as_sr_robot3() -> None:
    sim = fw2()
    board, _backend, stream = await connect(sim)
    stream.clear()
    assert await board.command("v") == "SRduino:2"
    sim.set_analogue(14, raw=100)
    assert await board.command("ao") == "100"
    assert await board.command("icid") == ""  # two replies: the second is discarded
    assert await board.command("v") == "SRduino:2"
    # The extra reply left the link out of step, so the last command was preceded by
    # the resynchronising 'v', whose answer (and the extra line) was discarded.
    assert stream.sent == b"vaoicid" + b"v" + b"v"
    await board.close()

    stream2 = ScriptedStream([(b"v", b"TeamDuino:2\n"), (b"x", b"\xff\n")])
    team_board = await Backend.from_stream(stream2, port="scripted", serial_number="T1")
    team = team_board.backend
    assert isinstance(team, Backend)
    assert not team.is_official_firmware
    with pytest.raises(UnexpectedReplyError, match="UTF-8"):
        await team.execute_string_command("x")
    await team_board.close()


async def test_bad_replies_name_the_board_and_command() -> None:
    stream = ScriptedStream([
        (b"v", b"SRduino:2\n"), (b"ic", b"x\n"), (b"rc", b"H\n"), (b"ao", b"1024\n"),
        (b"ucd", b"-1\n"),
    ])
    board = await Backend.from_stream(stream, port="scripted", serial_number="SRA1")
    backend = board.backend
    assert isinstance(backend, Backend)
    with pytest.raises(
        UnexpectedReplyError, match=r"SR Arduino on scripted: bad reply b'x' to b'ic'",
    ):
        await backend.set_gpio_pin_mode(2, GPIOPinMode.DIGITAL_INPUT)
    with pytest.raises(UnexpectedReplyError, match="b'H' to b'rc'"):
        await backend.read_gpio_pin_digital_state(2)
    backend.pins.record(14, mode=GPIOPinMode.ANALOGUE_INPUT)
    with pytest.raises(UnexpectedReplyError, match="1024"):
        await backend.read_gpio_pin_analogue_value(14)
    with pytest.raises(UnexpectedReplyError, match="-1"):
        await backend.get_ultrasound_distance(2, 3)
    assert backend.pins.mode(2) is GPIOPinMode.DIGITAL_INPUT  # unchanged by the failure
    stream.assert_all_used()
    await board.close()


async def test_bad_input_sends_nothing() -> None:
    _, backend, stream = await connect(fw2())
    stream.clear()
    for call in (
        backend.set_gpio_pin_mode(1, GPIOPinMode.DIGITAL_INPUT),
        backend.get_ultrasound_pulse(3, 20),
        backend.read_gpio_pin_analogue_value(13),
        backend.write_gpio_pin_digital_state(14, True),
    ):
        with pytest.raises((ValueError, NotSupportedByHardwareError)):
            await call
    assert stream.sent == b""
    await backend.close()


@settings(max_examples=60, deadline=None)
@given(st.binary(max_size=24).filter(lambda reply: b"\n" not in reply))
def test_any_reply_is_a_value_or_a_communication_error(reply: bytes) -> None:
    async def read() -> None:
        stream = ScriptedStream([
            (b"v", b"SRduino:2\n"), (b"rd", reply + b"\n"), (b"ucd", reply + b"\n"),
        ])
        board = await Backend.from_stream(stream, port="scripted", serial_number="SRA1")
        backend = board.backend
        assert isinstance(backend, Backend)
        with contextlib.suppress(CommunicationError):
            assert isinstance(await backend.read_gpio_pin_digital_state(3), bool)
        try:
            distance = await backend.get_ultrasound_distance(2, 3)
        except CommunicationError:
            pass
        else:
            assert distance is None or distance > 0
        await board.close()

    anyio.run(read)


async def test_make_safe_now_sends_nothing_and_a_reset_forgets_the_pins() -> None:
    board, backend, stream = await connect(fw2())
    await board.pins[3].set_mode(GPIOPinMode.DIGITAL_OUTPUT)
    stream.clear()
    assert backend.make_safe_now(0.5) is False
    assert stream.sent == b""
    backend.reset_board_state()  # the board came back: every pin is an input again
    assert await board.pins[3].get_mode() is GPIOPinMode.DIGITAL_INPUT
    await board.close()
