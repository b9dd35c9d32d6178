import logging
import re
from datetime import timedelta
from types import SimpleNamespace

import anyio
import pytest

from j5aio.backends.hardware import registry
from j5aio.backends.hardware.options import DiscoveryOptions
from j5aio.backends.hardware.sb import SBArduinoHardwareBackend
from j5aio.backends.hardware.sb.arduino_2019_codec import ArduinoError
from j5aio.backends.hardware.sr.v4 import SRV4RuggeduinoHardwareBackend
from j5aio.backends.hardware.transports.memory import SimulatorStream
from j5aio.boards.sb import SBArduinoBoard
from j5aio.components.gpio_pin import GPIOPinMode
from j5aio.errors import (
    BoardDisconnectionError,
    CommunicationError,
    CommunicationTimeoutError,
    NotSupportedByHardwareError,
    UnexpectedReplyError,
    UnsupportedFirmwareError,
)
from j5aio.simulator.sb_arduino_2019 import SBArduinoFirmware, SBArduinoSimulator
from j5aio.simulator.serve import serve_on_pty
from j5aio.testing.transports import RecordingStream, ScriptedStream

Backend = SBArduinoHardwareBackend
BANNER = b"# Booted\n# SBDuino GPIO v2019.8.0\r\n"
SETUP = [(f"W {pin} Z\n".encode(), f"# W {pin} Z\n+ OK\r\n".encode()) for pin in range(2, 14)]


def untagged(sent: bytes) -> bytes:
    """The requests sent, without their request ids."""
    return re.sub(rb"@[0-9]+ ", b"", sent)


async def connect(
    sim: SBArduinoSimulator,
) -> tuple[SBArduinoBoard, Backend, RecordingStream]:
    stream = RecordingStream(SimulatorStream(sim, time_scale=0))
    board = await Backend.from_stream(stream, port="sim-arduino", serial_number=sim.serial_number)
    assert isinstance(board, SBArduinoBoard)
    await board.setup()
    backend = board.backend
    assert isinstance(backend, Backend)
    return board, backend, stream


async def test_handshake_reads_banner_and_setup_applies_initial_modes() -> None:
    stream = ScriptedStream(SETUP, banner=b"\n\r\n" + BANNER)
    board = await Backend.from_stream(stream, port="scripted", serial_number="A1")
    assert board.firmware_version == "2019.8.0"
    await board.setup()
    stream.assert_all_used()
    await board.close()


@pytest.mark.parametrize(
    ("banner", "error", "match"),
    [
        (b"# Hello\n# SBDuino GPIO v2019.8.0\r\n", UnexpectedReplyError, "did not boot"),
        (b"# Booted\n# SBDuino GPIO v2018.4.0\r\n", UnsupportedFirmwareError, "'2018.4.0'"),
        (b"# Booted\n# SBDuino GPIO v2019.7\r\n", UnsupportedFirmwareError, "2019.6.0 or later"),
        (b"# Booted\n# SBDuino GPIO\r\n", UnexpectedReplyError, "version line"),
        (b"# Booted\n# no version\r\n", UnsupportedFirmwareError, "'ersion'"),
    ],
)
async def test_bad_boot(banner: bytes, error: type[Exception], match: str) -> None:
    stream = ScriptedStream([], banner=banner)
    with pytest.raises(error, match=match):
        await Backend.from_stream(stream, port="scripted", serial_number="A1", time_scale=0.01)
    assert stream.is_closed


async def test_silent_board_times_out_within_the_scaled_boot_timeout() -> None:
    stream = ScriptedStream([])
    with pytest.raises(CommunicationTimeoutError, match=r"did not finish booting within 0\.33 s"):
        await Backend.from_stream(stream, port="scripted", serial_number="A1", time_scale=0.01)


async def test_setup_sends_twelve_input_modes_against_the_simulator() -> None:
    sim = SBArduinoSimulator("A1")
    board, _, stream = await connect(sim)
    assert board.firmware_version == "2019.6.0"
    assert stream.sent == b"".join(request for request, _ in SETUP)
    assert untagged(stream.sent).startswith(b"W 2 Z\nW 3 Z\n")
    assert sim.pin_mode(2).name == "INPUT"
    await board.close()


async def test_digital_output_input_and_led() -> None:
    sim = SBArduinoSimulator("A1")
    board, backend, stream = await connect(sim)
    stream.clear()
    await board.pins[2].set_mode(GPIOPinMode.DIGITAL_OUTPUT)
    await board.pins[2].digital_write(True)
    assert untagged(stream.sent) == b"W 2 L\nW 2 H\n"
    assert sim.output_level(2) is True
    assert await board.pins[2].get_last_digital_write() is True
    # The cached level is re-applied when the mode changes back to output.
    await board.pins[2].set_mode(GPIOPinMode.DIGITAL_INPUT_PULLUP)
    await board.pins[2].set_mode(GPIOPinMode.DIGITAL_OUTPUT)
    assert untagged(stream.sent).endswith(b"W 2 P\nW 2 H\n")
    await board.pins[13].set_mode(GPIOPinMode.DIGITAL_OUTPUT)
    await board.led.set_state(True)
    assert sim.output_level(13) is True
    assert await board.led.get_state() is True
    sim.set_input_level(5, True)
    assert await board.pins[5].digital_read() is True
    sim.set_input_level(5, False)
    assert await board.pins[5].digital_read() is False
    assert await backend.get_gpio_pin_mode(2) is GPIOPinMode.DIGITAL_OUTPUT
    assert await backend.get_gpio_pin_mode(15) is GPIOPinMode.ANALOGUE_INPUT
    await board.close()


async def test_analogue_read() -> None:
    sim = SBArduinoSimulator("A1")
    board, backend, _ = await connect(sim)
    sim.set_analogue(15, raw=512)
    assert await board.pins[15].analogue_read() == 2.5
    with pytest.raises(NotSupportedByHardwareError, match="pins 14 to 17"):
        await backend.read_gpio_pin_analogue_value(18)
    with pytest.raises(NotSupportedByHardwareError, match="pins 14 to 17"):
        await backend.read_gpio_pin_analogue_value(3)
    await board.close()


async def test_pin_rules_send_nothing() -> None:
    sim = SBArduinoSimulator("A1")
    board, backend, stream = await connect(sim)
    stream.clear()
    with pytest.raises(ValueError, match="DIGITAL_OUTPUT mode to write"):
        await backend.write_gpio_pin_digital_state(3, True)
    with pytest.raises(ValueError, match="DIGITAL_OUTPUT mode to read back"):
        await backend.get_gpio_pin_digital_state(3)
    with pytest.raises(ValueError, match="only LED 0"):
        await backend.set_led_state(1, True)
    with pytest.raises(ValueError, match="DIGITAL_OUTPUT"):
        await backend.get_led_state(0)
    with pytest.raises(ValueError, match="pins 2 to 19, not pin 1"):
        await backend.set_gpio_pin_mode(1, GPIOPinMode.DIGITAL_INPUT)
    with pytest.raises(TypeError, match="int"):
        await backend.get_gpio_pin_mode("3")  # type: ignore[arg-type]
    with pytest.raises(NotSupportedByHardwareError, match="ANALOGUE_INPUT"):
        await backend.set_gpio_pin_mode(14, GPIOPinMode.DIGITAL_OUTPUT)
    with pytest.raises(NotSupportedByHardwareError, match="cannot be put in mode PWM_OUTPUT"):
        await backend.set_gpio_pin_mode(3, GPIOPinMode.PWM_OUTPUT)
    with pytest.raises(NotSupportedByHardwareError, match="analogue input"):
        await backend.write_gpio_pin_digital_state(14, True)
    with pytest.raises(NotSupportedByHardwareError, match="no DAC"):
        await backend.write_gpio_pin_dac_value(3, 0.5)
    with pytest.raises(NotSupportedByHardwareError, match="PWM"):
        await backend.write_gpio_pin_pwm_value(3, 0.5)
    await backend.set_gpio_pin_mode(14, GPIOPinMode.ANALOGUE_INPUT)  # no traffic
    await board.pins[3].set_mode(GPIOPinMode.DIGITAL_OUTPUT)
    stream.clear()
    with pytest.raises(ValueError, match="DIGITAL_INPUT or DIGITAL_INPUT_PULLUP"):
        await backend.read_gpio_pin_digital_state(3)
    assert stream.sent == b""
    await board.close()


async def test_ultrasound_and_pin_modes_afterwards() -> None:
    sim = SBArduinoSimulator("A1")
    board, backend, stream = await connect(sim)
    sim.set_ultrasound_echo(3, 4, 2345)
    stream.clear()
    assert await backend.get_ultrasound_pulse(3, 4) == timedelta(microseconds=2345)
    assert untagged(stream.sent) == b"T 3 4\n"
    sim.set_ultrasound_distance(3, 4, 1.23)
    assert await backend.get_ultrasound_distance(3, 4) == 1.23
    assert await backend.get_gpio_pin_mode(3) is GPIOPinMode.DIGITAL_OUTPUT
    assert await backend.get_gpio_pin_digital_state(3) is False
    assert await backend.get_gpio_pin_mode(4) is GPIOPinMode.DIGITAL_INPUT
    sim.set_ultrasound_echo(3, 4, None)
    assert await backend.get_ultrasound_distance(3, 4) is None
    with pytest.raises(NotSupportedByHardwareError, match="digital pins 2 to 13"):
        await backend.get_ultrasound_pulse(3, 14)
    await board.close()


async def test_servos_on_2019_6_0_and_refusal_on_2019_8_0() -> None:
    sim = SBArduinoSimulator("A1")
    board, backend, stream = await connect(sim)
    stream.clear()
    await board.servos[3].set_position(0.0)
    await board.servos[4].set_position(-1.0)
    await board.servos[4].set_position(None)
    assert untagged(stream.sent) == b"S 3 350\nS 4 150\nS 4 0\n"
    assert await board.servos[3].get_position() == 0.0
    assert await backend.get_servo_position(4) is None
    with pytest.raises(ValueError, match="servos 0 to 15"):
        await backend.set_servo_position(16, 0.0)
    await board.close()

    old = SBArduinoSimulator("A2", firmware_version=SBArduinoFirmware.V2019_8_0)
    board, backend, _ = await connect(old)
    with pytest.raises(ArduinoError, match="not implemented"):
        await backend.set_servo_position(0, 0.5)
    assert await backend.get_servo_position(0) is None
    await board.close()


async def test_error_and_garbage_replies() -> None:
    script = [
        (b"R 2\n", b"# R 2\n- Error: pin must be between 2 and 13\r\n"),
        (b"R 2\n", b"# R 2\n? garbage\r\n"),
        # The garbage left the link dirty: the next request carries a request id.
        (b"@1 A\n", b"# @1 A\n@1 > a1 7\r\n@1 + OK\r\n"),
        (b"R 2\n", b""),
    ]
    stream = ScriptedStream(script, banner=BANNER)
    board = await Backend.from_stream(stream, port="scripted", serial_number="A1")
    backend = board.backend
    assert isinstance(backend, Backend)
    with pytest.raises(CommunicationError, match="pin must be between 2 and 13"):
        await backend.read_gpio_pin_digital_state(2)
    with pytest.raises(UnexpectedReplyError, match="unrecognised"):
        await backend.read_gpio_pin_digital_state(2)
    with pytest.raises(UnexpectedReplyError, match="no reading for a0"):
        await backend.read_gpio_pin_analogue_value(14)
    with pytest.raises(CommunicationTimeoutError):
        await backend.read_gpio_pin_digital_state(2)
    stream.assert_all_used()
    await board.close()


async def test_unplugged_board_is_a_disconnection() -> None:
    sim = SBArduinoSimulator("A1")
    board, _, _ = await connect(sim)
    sim.unplug()
    with pytest.raises(BoardDisconnectionError):
        await board.pins[5].digital_read()
    await board.close()


def comport(device: str, serial_number: str | None, vid: int = 0x2341) -> SimpleNamespace:
    return SimpleNamespace(
        device=device,
        vid=vid,
        pid=0x0043,
        serial_number=serial_number,
        manufacturer="Arduino (www.arduino.cc)",
        product=None,
        description="Arduino Uno",
    )


async def test_attach_and_discover_over_a_real_pseudo_terminal(
    caplog: pytest.LogCaptureFixture,
) -> None:
    sim = SBArduinoSimulator("A1")
    with serve_on_pty(sim, time_scale=0.02) as server:
        board = await Backend.attach(server.path, time_scale=0.1)
        assert isinstance(board, SBArduinoBoard)
        assert board.serial_number == server.path
        assert board.firmware_version == "2019.6.0"
        await board.setup()
        sim.set_input_level(7, True)
        assert await board.pins[7].digital_read() is True
        await board.pins[8].set_mode(GPIOPinMode.DIGITAL_OUTPUT)
        await board.pins[8].digital_write(True)
        assert sim.output_level(8) is True
        # Attaching again, or discovering the same port, gives the same board.
        assert await Backend.attach(server.path) is board

        ports = [
            comport(server.path, "ARDUINO1"),
            comport("/dev/ttyNOSERIAL", None),
            comport("/dev/ttyOTHER", "X", vid=0x1234),
        ]
        options = DiscoveryOptions(port_source=lambda: ports)
        with caplog.at_level(logging.WARNING):
            found = await Backend.discover(options=options)
        assert found == [board]
        assert "no USB serial number" in caplog.text
        assert server.opened_count == 1
        with pytest.raises(registry.PortInUseError, match="already in use"):
            await SRV4RuggeduinoHardwareBackend.attach(server.path)
        assert await SRV4RuggeduinoHardwareBackend.discover(options=options) == []
        await board.close()
        assert registry.holder(server.path) is None

        # Now closed, discovery opens it afresh under its USB serial number. (The pty
        # server notices a close by polling, so give it time to see the hang-up.)
        await anyio.sleep(0.1)
        found = await Backend.discover(
            options=DiscoveryOptions(port_source=lambda: ports, time_scale=0.1)
        )
        assert [b.serial_number for b in found] == ["ARDUINO1"]
        # Opened twice more: the sb2024 kind's probe, then this kind's handshake.
        assert server.opened_count == 3
        await found[0].close()


async def test_attach_to_a_missing_port_is_a_disconnection() -> None:
    with pytest.raises(BoardDisconnectionError, match="no such port"):
        await Backend.attach("/dev/ttyDOESNOTEXIST")
    assert registry.holder("/dev/ttyDOESNOTEXIST") is None


def test_make_safe_now_leaves_the_pins_as_they_are() -> None:
    assert SBArduinoHardwareBackend.make_safe_now(object(), 0.5) is False  # type: ignore[arg-type]
