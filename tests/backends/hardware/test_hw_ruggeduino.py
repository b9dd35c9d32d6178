import pytest

from j5aio.backends.hardware.sr.v4 import SRV4RuggeduinoHardwareBackend
from j5aio.backends.hardware.transports.memory import SimulatorStream
from j5aio.boards.sr.v4 import Ruggeduino
from j5aio.components.gpio_pin import GPIOPinMode
from j5aio.errors import (
    CommunicationTimeoutError,
    NotSupportedByHardwareError,
    UnexpectedReplyError,
    UnsupportedFirmwareError,
)
from j5aio.simulator.sr_ruggeduino_fw1 import SRRuggeduinoSimulator
from j5aio.testing.transports import RecordingStream, ScriptedStream

Backend = SRV4RuggeduinoHardwareBackend
SETUP = [(f"i{chr(ord('a') + pin)}".encode(), b"\n") for pin in range(2, 14)]


async def connect(
    sim: SRRuggeduinoSimulator, time_scale: float = 0.0
) -> tuple[Ruggeduino, Backend, RecordingStream]:
    stream = RecordingStream(SimulatorStream(sim, time_scale=time_scale))
    board = await Backend.from_stream(
        stream, port="sim-ruggeduino", serial_number=sim.serial_number, time_scale=0.01
    )
    assert isinstance(board, Ruggeduino)
    await board.setup()
    backend = board.backend
    assert isinstance(backend, Backend)
    return board, backend, stream


async def test_handshake_retries_v_while_the_reply_is_empty() -> None:
    stream = ScriptedStream([(b"v", b"\n"), (b"v", b"\n"), (b"v", b"SRduino:1\n"), *SETUP])
    board = await Backend.from_stream(stream, port="scripted", serial_number="R1")
    assert board.firmware_version == "1"
    await board.setup()
    stream.assert_all_used()
    await board.close()


async def test_handshake_waits_for_the_simulated_boot() -> None:
    sim = SRRuggeduinoSimulator("R1")
    board, _, stream = await connect(sim, time_scale=0.05)  # boot takes 75 ms
    assert board.firmware_version == "1"
    assert stream.sent.startswith(b"v")
    # Late answers to the boot-time queries are followed by a resynchronising "v".
    assert stream.sent.lstrip(b"v").replace(b"v", b"") == b"icidieifigihiiijikilimin"
    await board.close()


async def test_a_silent_board_gives_up_after_the_bounded_attempts() -> None:
    stream = ScriptedStream([(b"v", b"\n")] * Backend.VERSION_ATTEMPTS)
    with pytest.raises(CommunicationTimeoutError, match="26 tries"):
        await Backend.from_stream(stream, port="scripted", serial_number="R1", time_scale=0.01)
    stream.assert_all_used()


async def test_a_board_that_never_answers_times_out() -> None:
    stream = ScriptedStream([(b"v", b"")] * Backend.VERSION_ATTEMPTS)
    with pytest.raises(CommunicationTimeoutError, match="did not answer"):
        await Backend.from_stream(stream, port="scripted", serial_number="R1", time_scale=0.001)


@pytest.mark.parametrize("reply", [b"SRduino:2\n", b"SRduino:x\n"])
async def test_unsupported_firmware(reply: bytes) -> None:
    stream = ScriptedStream([(b"v", reply)])
    with pytest.raises(UnsupportedFirmwareError, match="supports only 1") as info:
        await Backend.from_stream(stream, port="scripted", serial_number="R1")
    assert info.value.found == reply.decode().strip().split(":")[1]
    assert stream.is_closed


async def test_version_line_without_colon() -> None:
    stream = ScriptedStream([(b"v", b"hello\n")])
    with pytest.raises(UnexpectedReplyError, match="SRduino:1"):
        await Backend.from_stream(stream, port="scripted", serial_number="R1")


async def test_pins_against_the_simulator() -> None:
    sim = SRRuggeduinoSimulator("R1")
    board, _backend, stream = await connect(sim)
    stream.clear()
    await board.pins[3].set_mode(GPIOPinMode.DIGITAL_OUTPUT)
    await board.pins[3].digital_write(True)
    assert stream.sent == b"odldhd"
    assert sim.output_level(3) is True
    await board.pins[4].set_mode(GPIOPinMode.DIGITAL_INPUT_PULLUP)
    assert await board.pins[4].digital_read() is True  # the pull-up holds it high
    sim.set_input_level(4, False)
    assert await board.pins[4].digital_read() is False
    sim.set_analogue(19, raw=256)
    assert await board.pins[19].analogue_read() == 1.25
    stream.clear()
    await board.pins[13].set_mode(GPIOPinMode.DIGITAL_OUTPUT)
    await board.led.set_state(True)
    assert stream.sent == b"onlnhn"
    assert await board.led.get_state() is True
    await board.close()


async def test_string_commands_need_custom_firmware() -> None:
    sim = SRRuggeduinoSimulator("R1")
    _, backend, _ = await connect(sim)
    with pytest.raises(NotSupportedByHardwareError, match="own firmware"):
        await backend.execute_string_command("x")
    await backend.close()

    stream = ScriptedStream([(b"v", b"MyBot:1\n"), (b"spin", b"done\r\n")])
    board = await Backend.from_stream(stream, port="scripted", serial_number="R2")
    custom = board.backend
    assert isinstance(custom, Backend)
    assert not custom.is_official_firmware
    assert await custom.execute_string_command("spin") == "done"
    stream.assert_all_used()


async def test_bad_replies() -> None:
    stream = ScriptedStream([(b"v", b"SRduino:1\n"), (b"rc", b"?\n"), (b"aa", b"lots\n")])
    board = await Backend.from_stream(stream, port="scripted", serial_number="R1")
    backend = board.backend
    assert isinstance(backend, Backend)
    with pytest.raises(UnexpectedReplyError, match="'h' or 'l'"):
        await backend.read_gpio_pin_digital_state(2)
    with pytest.raises(UnexpectedReplyError, match="0 to 1023"):
        await backend.read_gpio_pin_analogue_value(14)
    stream.assert_all_used()


async def test_analogue_pins_take_the_digital_modes_too() -> None:
    sim = SRRuggeduinoSimulator("R1")
    board, backend, stream = await connect(sim)
    stream.clear()
    a0 = board.pins[14]
    await a0.set_mode(GPIOPinMode.DIGITAL_OUTPUT)
    await a0.digital_write(True)
    assert stream.sent == b"ooloho"  # pin 14 is the letter o
    assert sim.output_level(14) is True
    assert await backend.get_gpio_pin_mode(14) is GPIOPinMode.DIGITAL_OUTPUT
    a5 = board.pins[19]
    await a5.set_mode(GPIOPinMode.DIGITAL_INPUT_PULLUP)
    sim.set_input_level(19, False)
    assert await a5.digital_read() is False
    stream.clear()
    await a0.set_mode(GPIOPinMode.ANALOGUE_INPUT)  # stop driving it, then read volts
    assert stream.sent == b"io"
    sim.set_analogue(14, raw=512)
    assert await a0.analogue_read() == 2.5
    stream.clear()
    await a0.set_mode(GPIOPinMode.ANALOGUE_INPUT)  # already an analogue input: no traffic
    assert stream.sent == b""
    await board.close()
