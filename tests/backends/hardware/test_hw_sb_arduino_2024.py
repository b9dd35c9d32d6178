"""The SourceBots Arduino sb2024 hardware backend, against its simulator and scripts."""

from __future__ import annotations

import contextlib

import anyio
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from j5aio.backends.hardware.sb import SBArduino2024HardwareBackend
from j5aio.backends.hardware.transports.memory import SimulatorStream
from j5aio.backends.hardware.transports.serial_link import SerialLink
from j5aio.boards.sb import SBArduino2024Board
from j5aio.components.gpio_pin import GPIOPinMode
from j5aio.errors import (
    CommunicationError,
    CommunicationTimeoutError,
    NotSupportedByHardwareError,
    UnexpectedReplyError,
    UnsupportedFirmwareError,
)
from j5aio.simulator import PinMode, SBArduino2024Simulator
from j5aio.testing.transports import FaultyStream, RecordingStream, ScriptedStream

Backend = SBArduino2024HardwareBackend
IDN = (b"*IDN?\n", b"SourceBots:Arduino:X:2.0\n")
SETUP = [(b"PIN:%d:MODE:SET:INPUT\n" % pin, b"ACK\n") for pin in range(2, 20)]


async def connect(
    sim: SBArduino2024Simulator, time_scale: float = 0.0,
) -> tuple[SBArduino2024Board, Backend, RecordingStream]:
    stream = RecordingStream(SimulatorStream(sim, time_scale=time_scale))
    board = await Backend.from_stream(
        stream, port="sim-sb2024", serial_number=sim.serial_number, time_scale=0.01,
    )
    assert isinstance(board, SBArduino2024Board)
    await board.setup()
    backend = board.backend
    assert isinstance(backend, Backend)
    return board, backend, stream


async def test_handshake_and_setup_traffic() -> None:
    stream = ScriptedStream([IDN, *SETUP])
    board = await Backend.from_stream(stream, port="scripted", serial_number="SB1")
    assert board.firmware_version == "2.0"
    await board.setup()
    stream.assert_all_used()
    await board.close()


async def test_handshake_waits_for_the_simulated_boot() -> None:
    sim = SBArduino2024Simulator("SB1")
    board, backend, stream = await connect(sim, time_scale=0.05)  # boot takes 75 ms
    assert board.firmware_version == "2.0"
    assert stream.sent.startswith(b"*IDN?\n*IDN?\n")
    assert backend.USB_IDS  # shared with every Arduino: identity is by handshake
    await board.close()


async def test_handshake_asks_again_after_a_nack_or_garbage() -> None:
    stream = ScriptedStream([
        (b"*IDN?\n", b"NACK:Invalid command\n"), (b"*IDN?\n", b"\xfe\xff\n"), IDN,
    ])
    board = await Backend.from_stream(stream, port="scripted", serial_number="SB1")
    assert board.firmware_version == "2.0"
    stream.assert_all_used()
    await board.close()


async def test_unsupported_firmware_names_found_and_supported() -> None:
    stream = ScriptedStream([(b"*IDN?\n", b"SourceBots:Arduino:X:3.1\n")])
    with pytest.raises(UnsupportedFirmwareError, match=r"'3\.1'.*supports only 2\.0") as info:
        await Backend.from_stream(stream, port="scripted", serial_number="SB1")
    assert (info.value.found, info.value.supported) == ("3.1", ("2.0",))
    assert stream.is_closed


async def test_another_board_is_refused() -> None:
    stream = ScriptedStream([(b"*IDN?\n", b"Student Robotics:PBv4B:srABC:4.4.2\n")])
    with pytest.raises(UnexpectedReplyError, match="not a SourceBots Arduino"):
        await Backend.from_stream(stream, port="scripted", serial_number="SB1")


async def test_a_silent_board_gives_up_after_the_bounded_attempts() -> None:
    stream = ScriptedStream([(b"*IDN?\n", b"")] * 3)
    link = SerialLink(stream, name="scripted", default_timeout=1)
    with pytest.raises(CommunicationTimeoutError, match="3 tries"):
        await Backend.identify_firmware(link, time_scale=0.001, attempts=3)
    stream.assert_all_used()


async def test_identify_on_an_open_link() -> None:
    sim = SBArduino2024Simulator("SB1")
    link = SerialLink(SimulatorStream(sim, time_scale=0), name="sim")
    # A single-character probe left in the line buffer earns a NACK first.
    assert sim.receive(b"v") == b""
    assert await Backend.identify_firmware(link, time_scale=0.01, attempts=2) == "2.0"
    await link.aclose()


async def test_pins_against_the_simulator() -> None:
    sim = SBArduino2024Simulator("SB1")
    board, backend, stream = await connect(sim)
    stream.clear()
    await board.pins[3].set_mode(GPIOPinMode.DIGITAL_OUTPUT)
    await board.pins[3].digital_write(True)
    assert stream.sent == (
        b"PIN:3:DIGITAL:SET:0\nPIN:3:MODE:SET:OUTPUT\nPIN:3:DIGITAL:SET:1\n"
    )
    assert (sim.pin_mode(3), sim.output_level(3)) == (PinMode.OUTPUT, True)
    # An output goes back to the level last written to it, set before the mode.
    await board.pins[3].set_mode(GPIOPinMode.DIGITAL_INPUT)
    stream.clear()
    await board.pins[3].set_mode(GPIOPinMode.DIGITAL_OUTPUT)
    assert stream.sent == b"PIN:3:DIGITAL:SET:1\nPIN:3:MODE:SET:OUTPUT\n"
    assert await backend.read_pin_mode(3) is GPIOPinMode.DIGITAL_OUTPUT

    await board.pins[4].set_mode(GPIOPinMode.DIGITAL_INPUT_PULLUP)
    assert await board.pins[4].digital_read() is True
    sim.set_input_level(4, False)
    assert await board.pins[4].digital_read() is False

    # A0-A5 are digital pins too, and analogue inputs.
    await board.pins[18].set_mode(GPIOPinMode.DIGITAL_OUTPUT)
    await board.pins[18].digital_write(True)
    assert sim.output_level(18) is True
    sim.set_analogue(19, volts=3.3)
    assert await board.pins[19].analogue_read() == pytest.approx(3.3, abs=0.005)
    stream.clear()
    await board.pins[18].set_mode(GPIOPinMode.ANALOGUE_INPUT)
    assert stream.sent == b"PIN:18:MODE:SET:INPUT\n"
    assert sim.pin_mode(18) is PinMode.INPUT

    await board.pins[13].set_mode(GPIOPinMode.DIGITAL_OUTPUT)
    await board.led.set_state(True)
    assert sim.output_level(13) is True
    assert await board.led.get_state() is True
    await board.close()


async def test_ultrasound_against_the_simulator() -> None:
    sim = SBArduino2024Simulator("SB1")
    board, backend, stream = await connect(sim)
    sensor = board.ultrasound_sensors[5, 14]
    sim.set_ultrasound_distance(5, 14, 0.75)
    stream.clear()
    assert await sensor.distance() == 0.75
    assert stream.sent == b"ULTRASOUND:5:14:MEASURE?\n"
    assert backend.pins.mode(5) is GPIOPinMode.DIGITAL_OUTPUT
    assert backend.pins.mode(14) is GPIOPinMode.DIGITAL_INPUT
    pulse = await sensor.pulse()
    assert pulse is not None
    assert pulse.total_seconds() == pytest.approx(0.75 * 5.8e-3, rel=1e-3)
    for echo in (None, 40_000, 60_000, 70_000):  # none, wrapped negative, wrapped, timeout
        sim.set_ultrasound_echo(5, 14, echo)
        assert await sensor.distance() is None
        assert await sensor.pulse() is None
    await board.close()


async def test_bad_input_sends_nothing() -> None:
    sim = SBArduino2024Simulator("SB1")
    _, backend, stream = await connect(sim)
    stream.clear()
    with pytest.raises(ValueError, match="pins 2 to 19"):
        await backend.set_gpio_pin_mode(20, GPIOPinMode.DIGITAL_INPUT)
    with pytest.raises(ValueError, match="pins 2 to 19"):
        await backend.get_ultrasound_distance(1, 3)
    with pytest.raises(TypeError, match="int"):
        await backend.read_gpio_pin_digital_state("3")  # type: ignore[arg-type]
    with pytest.raises(NotSupportedByHardwareError, match="ANALOGUE_INPUT"):
        await backend.set_gpio_pin_mode(3, GPIOPinMode.ANALOGUE_INPUT)
    with pytest.raises(NotSupportedByHardwareError, match="PWM_OUTPUT"):
        await backend.set_gpio_pin_mode(15, GPIOPinMode.PWM_OUTPUT)
    with pytest.raises(NotSupportedByHardwareError, match="A0 to A5"):
        await backend.read_gpio_pin_analogue_value(3)
    await backend.set_gpio_pin_mode(14, GPIOPinMode.DIGITAL_OUTPUT)
    stream.clear()
    with pytest.raises(ValueError, match="ANALOGUE_INPUT mode"):
        await backend.read_gpio_pin_analogue_value(14)
    with pytest.raises(ValueError, match="DIGITAL_OUTPUT mode"):
        await backend.write_gpio_pin_digital_state(3, True)
    with pytest.raises(ValueError, match="DIGITAL_OUTPUT mode"):
        await backend.get_gpio_pin_digital_state(3)
    with pytest.raises(ValueError, match="DIGITAL_INPUT"):
        await backend.read_gpio_pin_digital_state(14)
    with pytest.raises(ValueError, match="only LED 0"):
        await backend.set_led_state(1, True)
    with pytest.raises(NotSupportedByHardwareError, match="DAC"):
        await backend.write_gpio_pin_dac_value(3, 0.5)
    with pytest.raises(NotSupportedByHardwareError, match="PWM"):
        await backend.write_gpio_pin_pwm_value(3, 0.5)
    assert stream.sent == b""
    await backend.close()


async def test_a_nack_leaves_the_cache_as_the_board_is() -> None:
    stream = ScriptedStream([
        IDN,
        (b"PIN:3:DIGITAL:SET:0\n", b"ACK\n"),
        (b"PIN:3:MODE:SET:OUTPUT\n", b"NACK:Invalid command\n"),
        (b"PIN:3:DIGITAL:SET:0\n", b"ACK\n"),
        (b"PIN:3:MODE:SET:OUTPUT\n", b"ACK\n"),
        (b"PIN:3:DIGITAL:SET:1\n", b"2\n"),
        (b"PIN:3:DIGITAL:GET?\n", b"1\n"),
        (b"PIN:14:ANALOG:GET?\n", b"4096\n"),
    ])
    board = await Backend.from_stream(stream, port="scripted", serial_number="SB1")
    backend = board.backend
    assert isinstance(backend, Backend)
    with pytest.raises(UnexpectedReplyError, match=r"SourceBots Arduino \(sb2024\) on scripted.*"
                       r"NACK:Invalid command.*PIN:3:MODE:SET:OUTPUT"):
        await backend.set_gpio_pin_mode(3, GPIOPinMode.DIGITAL_OUTPUT)
    assert backend.pins.mode(3) is GPIOPinMode.DIGITAL_INPUT
    await backend.set_gpio_pin_mode(3, GPIOPinMode.DIGITAL_OUTPUT)
    with pytest.raises(UnexpectedReplyError, match=r"b'2' to b'PIN:3:DIGITAL:SET:1\\n'"):
        await backend.write_gpio_pin_digital_state(3, True)
    assert await backend.get_gpio_pin_digital_state(3) is False
    backend.pins.record(3, mode=GPIOPinMode.DIGITAL_INPUT)
    assert await backend.read_gpio_pin_digital_state(3) is True
    backend.pins.record(14, mode=GPIOPinMode.ANALOGUE_INPUT)
    with pytest.raises(UnexpectedReplyError, match="4096"):
        await backend.read_gpio_pin_analogue_value(14)
    stream.assert_all_used()
    backend.forget_board_state()
    assert backend.pins.mode(14) is GPIOPinMode.DIGITAL_INPUT
    await board.close()


async def test_a_cancelled_mode_change_leaves_the_cache_as_the_board_is() -> None:
    sim = SBArduino2024Simulator("SB1")
    faulty = FaultyStream(SimulatorStream(sim, time_scale=0))
    board = await Backend.from_stream(faulty, port="faulty", serial_number="SB1", time_scale=0)
    backend = board.backend
    assert isinstance(backend, Backend)
    faulty.delay_next_reply(0.2)
    with anyio.move_on_after(0.05):
        await backend.set_gpio_pin_mode(3, GPIOPinMode.DIGITAL_OUTPUT)
    # The level and the mode went as one exchange, which ran to its end (shielded):
    # the board and the cache agree that the pin is an output.
    assert backend.pins.mode(3) is GPIOPinMode.DIGITAL_OUTPUT
    assert sim.pin_mode(3) is PinMode.OUTPUT
    await backend.set_gpio_pin_mode(3, GPIOPinMode.DIGITAL_INPUT)
    assert sim.pin_mode(3) is PinMode.INPUT
    await board.close()


@settings(max_examples=60, deadline=None)
@given(st.binary(max_size=24).filter(lambda reply: b"\n" not in reply))
def test_any_reply_is_a_value_or_a_communication_error(reply: bytes) -> None:
    async def read() -> None:
        stream = ScriptedStream([
            IDN,
            (b"PIN:3:DIGITAL:GET?\n", reply + b"\n"),
            (b"ULTRASOUND:2:3:MEASURE?\n", reply + b"\n"),
        ])
        board = await Backend.from_stream(stream, port="scripted", serial_number="SB1")
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


async def test_a_board_that_stops_answering_is_named() -> None:
    sim = SBArduino2024Simulator("SB1")
    faulty = FaultyStream(SimulatorStream(sim, time_scale=0))
    board = await Backend.from_stream(faulty, port="faulty", serial_number="SB1", time_scale=0)
    assert isinstance(board, SBArduino2024Board)
    faulty.silence()
    with pytest.raises(CommunicationTimeoutError, match=r"SourceBots Arduino \(sb2024\) did not"):
        await board.pins[3].digital_read()
    await board.close()


async def test_make_safe_now_sends_nothing_and_a_reset_forgets_the_pins() -> None:
    board, backend, stream = await connect(SBArduino2024Simulator("SB1"))
    await board.pins[3].set_mode(GPIOPinMode.DIGITAL_OUTPUT)
    stream.clear()
    assert backend.make_safe_now(0.5) is False
    assert stream.sent == b""
    assert await board.pins[3].get_mode() is GPIOPinMode.DIGITAL_OUTPUT
    backend.reset_board_state()  # the board came back: every pin is an input again
    assert await board.pins[3].get_mode() is GPIOPinMode.DIGITAL_INPUT
    await board.close()
