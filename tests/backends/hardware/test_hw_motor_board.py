import pytest

from j5aio.backends.hardware import registry
from j5aio.backends.hardware.sr.v4 import SRV4MotorBoardHardwareBackend
from j5aio.backends.hardware.transports.memory import SimulatorStream
from j5aio.boards.sr.v4 import MotorBoard
from j5aio.components.motor import MotorSpecialState
from j5aio.errors import (
    BoardDisconnectionError,
    CommunicationTimeoutError,
    UnexpectedReplyError,
    UnsupportedFirmwareError,
)
from j5aio.simulator.sr_motor_fw3 import MotorMode, SRMotorBoardFw3Simulator
from j5aio.testing.transports import RecordingStream, ScriptedStream

Backend = SRV4MotorBoardHardwareBackend
HANDSHAKE = [(b"\x00\x01", b"MCV4B:3\n"), (b"\x02\x02", b""), (b"\x03\x02", b"")]


async def connect(sim: SRMotorBoardFw3Simulator) -> tuple[MotorBoard, RecordingStream]:
    stream = RecordingStream(SimulatorStream(sim, time_scale=0))
    board = await Backend.from_stream(stream, port="sim-motor", serial_number=sim.serial_number)
    assert isinstance(board, MotorBoard)
    await board.setup()
    return board, stream


async def test_handshake_bytes_and_cached_brake() -> None:
    stream = ScriptedStream(HANDSHAKE)
    board = await Backend.from_stream(stream, port="scripted", serial_number="SR0M")
    stream.assert_all_used()
    assert board.firmware_version == "3"
    assert board.serial_number == "SR0M"
    assert await board.backend.get_motor_state(0) is MotorSpecialState.BRAKE  # type: ignore[attr-defined]
    await board.close()
    assert stream.is_closed


async def test_unsupported_firmware_names_found_and_supported() -> None:
    stream = ScriptedStream([(b"\x00\x01", b"MCV4B:2\n")])
    with pytest.raises(UnsupportedFirmwareError) as info:
        await Backend.from_stream(stream, port="scripted", serial_number="SR0M")
    assert info.value.found == "2"
    assert info.value.supported == ("3",)
    assert "'2'" in str(info.value)
    assert stream.is_closed


async def test_wrong_model_is_an_unexpected_reply() -> None:
    stream = ScriptedStream([(b"\x00\x01", b"SRduino:1\n")])
    with pytest.raises(UnexpectedReplyError, match="MCV4B"):
        await Backend.from_stream(stream, port="scripted", serial_number="SR0M")


async def test_silent_board_times_out() -> None:
    stream = ScriptedStream([(b"\x00\x01", b"")])
    with pytest.raises(CommunicationTimeoutError):
        await Backend.from_stream(stream, port="scripted", serial_number="SR0M")
    assert stream.is_closed


async def test_resync_byte_recovers_a_board_waiting_for_a_speed() -> None:
    sim = SRMotorBoardFw3Simulator("SR0M")
    sim.receive(b"\x02")  # a previous host died half way through a command
    assert sim.awaiting_speed == 0
    board, _ = await connect(sim)
    assert board.firmware_version == "3"
    assert [m.mode for m in sim.motors] == [MotorMode.BRAKE, MotorMode.BRAKE]
    await board.close()


@pytest.mark.parametrize(
    ("power", "byte"),
    [(1.0, 0xE4), (0.65, 0xC1), (-1.0, 0x1C), (0.0, 0x80), (0.5, 178)],
)
async def test_set_power_sends_the_scaled_byte(power: float, byte: int) -> None:
    sim = SRMotorBoardFw3Simulator("SR0M")
    board, stream = await connect(sim)
    stream.clear()
    await board.motors[1].set_power(power)
    assert stream.sent == bytes([0x03, byte])
    assert await board.motors[1].get_power() == power
    await board.close()


async def test_special_states_and_make_safe() -> None:
    sim = SRMotorBoardFw3Simulator("SR0M")
    board, _ = await connect(sim)
    await board.motors[0].set_power(MotorSpecialState.COAST)
    assert sim.motors[0].mode is MotorMode.COAST
    assert await board.motors[0].get_power() is MotorSpecialState.COAST
    await board.motors[0].set_power(0.3)
    await board.make_safe()
    assert [m.mode for m in sim.motors] == [MotorMode.BRAKE, MotorMode.BRAKE]
    await board.close()


async def test_make_safe_uses_the_boards_safe_state() -> None:
    sim = SRMotorBoardFw3Simulator("SR0M")
    board, _ = await connect(sim)
    coasting = MotorBoard("SR0M", board.backend, safe_state=MotorSpecialState.COAST)
    await coasting.make_safe()
    assert [m.mode for m in sim.motors] == [MotorMode.COAST, MotorMode.COAST]
    await board.close()


async def test_bad_motor_identifiers_send_nothing() -> None:
    sim = SRMotorBoardFw3Simulator("SR0M")
    board, stream = await connect(sim)
    backend = board.backend
    assert isinstance(backend, Backend)
    stream.clear()
    with pytest.raises(ValueError, match="motors 0 and 1"):
        await backend.set_motor_state(2, 0.5)
    with pytest.raises(ValueError, match="motors 0 and 1"):
        await backend.get_motor_state(-1)
    with pytest.raises(ValueError, match="between -1 and 1"):
        await backend.set_motor_state(0, 1.5)
    assert stream.sent == b""
    await board.close()


async def test_a_vanished_port_is_a_disconnection_and_frees_the_port() -> None:
    sim = SRMotorBoardFw3Simulator("SR0M")

    async def opener(port: str, baudrate: int) -> SimulatorStream:
        assert baudrate == 1_000_000
        return SimulatorStream(sim, time_scale=0)

    board = await Backend.attach("sim://motor", opener=opener)
    assert registry.holder("sim://motor") is board
    assert repr(board.backend) == "<SRV4MotorBoardHardwareBackend port='sim://motor'>"
    assert board.backend.link.name == "sim://motor"  # type: ignore[attr-defined]
    assert board.serial_number == "sim://motor"
    sim.unplug()
    with pytest.raises(BoardDisconnectionError):
        await board.backend.set_motor_state(0, 0.5)  # type: ignore[attr-defined]
    assert registry.holder("sim://motor") is None
    with pytest.raises(BoardDisconnectionError):
        await board.backend.set_motor_state(0, 0.5)  # type: ignore[attr-defined]


async def test_make_safe_now_brakes_both_motors_synchronously() -> None:
    sim = SRMotorBoardFw3Simulator("SR0M")
    board, stream = await connect(sim)
    await board.motors[0].set_power(0.6)
    await board.motors[1].set_power(MotorSpecialState.COAST)
    stream.clear()
    assert board.backend.make_safe_now(0.5) is True
    assert stream.sent == b"\x00\x02\x02\x03\x02"  # resync first, then brake each
    assert [m.mode for m in sim.motors] == [MotorMode.BRAKE, MotorMode.BRAKE]
    assert await board.motors[0].get_power() is MotorSpecialState.BRAKE
    await board.close()
    assert board.backend.make_safe_now(0.5) is False  # a closed link: nothing to send


async def test_close_now_closes_the_port_synchronously() -> None:
    sim = SRMotorBoardFw3Simulator("SR0M")
    board, stream = await connect(sim)
    board.close_now()
    assert stream.is_closed
    assert board not in MotorBoard.BOARDS
    await board.close()  # already closed
