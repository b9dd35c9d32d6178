import pytest

from j5aio.backends.hardware.sr.v4 import (
    SRV4MotorBoardFw4HardwareBackend,
    SRV4MotorBoardHardwareBackend,
    identify_motor_board,
)
from j5aio.backends.hardware.sr.v4.text_protocol import NackError
from j5aio.backends.hardware.transports.memory import SimulatorStream
from j5aio.boards.sr.v4 import MotorBoard, MotorBoardFw4
from j5aio.components.motor import MotorSpecialState
from j5aio.errors import (
    CommunicationError,
    CommunicationTimeoutError,
    UnexpectedReplyError,
    UnsupportedFirmwareError,
)
from j5aio.simulator import (
    MotorDrive,
    MotorMode,
    SRMotorBoardFw3Simulator,
    SRMotorBoardFw4Simulator,
)
from j5aio.testing.transports import RecordingStream, ScriptedStream

Backend = SRV4MotorBoardFw4HardwareBackend
PROBE = b"\x00\n*IDN?\n"
PROBE_REPLY = b"NACK:Unknown command: '\x00'\nStudent Robotics:MCv4B:srM:4.4.1\n"


async def connect(
    sim: SRMotorBoardFw4Simulator,
) -> tuple[MotorBoardFw4, SRV4MotorBoardFw4HardwareBackend, RecordingStream]:
    stream = RecordingStream(SimulatorStream(sim, time_scale=0))
    board = await Backend.from_stream(stream, port="sim-motor", serial_number=sim.serial_number)
    assert isinstance(board, MotorBoardFw4)
    await board.setup()
    backend = board.backend
    assert isinstance(backend, Backend)
    stream.clear()
    return board, backend, stream


async def test_handshake_bytes() -> None:
    stream = ScriptedStream([(PROBE, PROBE_REPLY)])
    board = await Backend.from_stream(stream, port="scripted", serial_number="srM")
    stream.assert_all_used()
    assert board.firmware_version == "4.4.1"
    assert board.backend.asset_tag == "srM"  # type: ignore[attr-defined]
    assert isinstance(board, MotorBoard)  # existing programs keep working
    await board.close()


async def test_a_sourcebots_45_board_is_driven() -> None:
    board, _, _ = await connect(SRMotorBoardFw4Simulator("sbM", version="4.5.0"))
    assert board.firmware_version == "4.5.0"
    await board.close()


async def test_unsupported_fw4_version() -> None:
    stream = ScriptedStream([(PROBE, b"NACK:x\nStudent Robotics:MCv4B:srM:4.6\n")])
    with pytest.raises(UnsupportedFirmwareError) as info:
        await Backend.from_stream(stream, port="scripted", serial_number="srM")
    assert info.value.found == "4.6"
    assert stream.is_closed


async def test_firmware_3_is_told_apart_by_its_answer() -> None:
    sim = SRMotorBoardFw3Simulator("srM")
    sim.receive(b"\x02")  # a previous host died between a motor command and its speed
    stream = RecordingStream(SimulatorStream(sim, time_scale=0))
    with pytest.raises(UnsupportedFirmwareError) as info:
        await Backend.from_stream(stream, port="sim", serial_number="srM")
    assert info.value.found == "3"
    assert "4.4" in info.value.supported
    # The probe moved no motor: the stranded speed byte was the harmless 0x00.
    assert [m.mode for m in sim.motors] == [MotorMode.COAST, MotorMode.COAST]


async def test_a_silent_port_times_out() -> None:
    stream = ScriptedStream([(PROBE, b""), (b"\x00\x01", b"")])
    with pytest.raises(CommunicationTimeoutError):
        await Backend.from_stream(stream, port="scripted", serial_number="srM")


async def test_identify_fw4_then_hand_the_stream_on() -> None:
    sim = SRMotorBoardFw4Simulator("srM")
    stream = SimulatorStream(sim, time_scale=0)
    identity = await identify_motor_board(stream, port="sim")
    assert (identity.generation, identity.version, identity.asset_tag) == (4, "4.4.1", "srM")
    board = await Backend.from_stream(stream, port="sim", serial_number="srM")
    await board.close()


async def test_identify_fw3() -> None:
    sim = SRMotorBoardFw3Simulator("srM")
    stream = SimulatorStream(sim, time_scale=0)
    identity = await identify_motor_board(stream, port="sim", timeout=0.1)
    assert (identity.generation, identity.version, identity.asset_tag) == (3, "3", None)
    board = await SRV4MotorBoardHardwareBackend.from_stream(
        stream, port="sim", serial_number="srM",
    )
    assert board.firmware_version == "3"
    await board.close()


async def test_identify_nothing() -> None:
    stream = ScriptedStream([(PROBE, b""), (b"\x00\x01", b"")])
    with pytest.raises(CommunicationError, match="neither firmware"):
        await identify_motor_board(stream, timeout=0.05)


async def test_brake_coast_and_powers() -> None:
    sim = SRMotorBoardFw4Simulator("srM")
    board, backend, stream = await connect(sim)
    motor = board.motors[0]
    assert await motor.get_power() is MotorSpecialState.COAST
    stream.clear()
    await motor.set_power(MotorSpecialState.BRAKE)
    await motor.set_power(0.5)
    await motor.set_power(MotorSpecialState.COAST)
    await motor.set_power(-0.123)
    assert stream.sent == b"MOT:0:SET:0\nMOT:0:SET:500\nMOT:0:DISABLE\nMOT:0:SET:-123\n"
    assert sim.motors[0].drive is MotorDrive.REVERSE
    assert await motor.get_power() == -0.123
    await motor.set_power(0.0)
    assert await motor.get_power() == 0.0
    await motor.set_power(MotorSpecialState.BRAKE)
    assert await motor.get_power() is MotorSpecialState.BRAKE
    backend.forget_cached_state()
    assert backend.last_sent == [None, None]
    await board.make_safe()
    assert [m.drive for m in sim.motors] == [MotorDrive.BRAKE, MotorDrive.BRAKE]
    await board.close()


@pytest.mark.parametrize("power", [0.5, 0.8, 0.9, 1.0, -0.25])
async def test_duty_is_linear_in_power(power: float) -> None:
    sim = SRMotorBoardFw4Simulator("srM")
    board, _, _ = await connect(sim)
    await board.motors[1].set_power(power)
    assert sim.motors[1].power == pytest.approx(power)
    await board.close()


async def test_current_faults_and_voltage() -> None:
    sim = SRMotorBoardFw4Simulator("srM")
    board, backend, stream = await connect(sim)
    sim.set_motor_current(0, 2.5)
    await board.motors[0].set_power(0.7)
    assert await board.motors[0].get_current() == 2.5
    sim.set_fault(1)
    assert await board.motors[1].get_has_fault() is True
    assert await board.motors[0].get_has_fault() is False
    sim.input_voltage = 11.5
    assert await board.input_voltage_sensor.get_voltage() == 11.5
    stream.clear()
    for call in (backend.get_motor_current, backend.get_motor_fault, backend.get_motor_state):
        with pytest.raises(ValueError, match="motors 0 and 1"):
            await call(2)
    with pytest.raises(ValueError, match="only voltage sensor 0"):
        await backend.get_voltage_sensor_voltage(1)
    with pytest.raises(ValueError, match="between -1 and 1"):
        await backend.set_motor_state(0, 1.5)
    assert stream.sent == b""
    await board.close()


async def test_nack_and_bad_replies() -> None:
    stream = ScriptedStream([
        (PROBE, PROBE_REPLY),
        (b"MOT:0:SET:500\n", b"NACK:Invalid motor power\n"),
        (b"MOT:0:GET?\n", b"1:5000\n"),
        (b"*STATUS?\n", b"0,0\n"),
    ])
    board = await Backend.from_stream(stream, port="scripted", serial_number="srM")
    assert isinstance(board, MotorBoardFw4)
    with pytest.raises(NackError, match="MOT:0:SET:500") as info:
        await board.motors[0].set_power(0.5)
    assert board.name in str(info.value)
    with pytest.raises(UnexpectedReplyError, match="1:5000"):
        await board.motors[0].get_power()
    with pytest.raises(UnexpectedReplyError, match=r"\*STATUS\?"):
        await board.input_voltage_sensor.get_voltage()
    await board.close()


async def test_make_safe_now_brakes_both_motors_synchronously() -> None:
    sim = SRMotorBoardFw4Simulator("srM")
    board, backend, stream = await connect(sim)
    await board.motors[0].set_power(0.5)
    await board.motors[1].set_power(MotorSpecialState.COAST)
    stream.clear()
    assert backend.make_safe_now(0.5) is True
    assert stream.sent == b"\nMOT:0:SET:0\nMOT:1:SET:0\n"
    assert [motor.drive for motor in sim.motors] == [MotorDrive.BRAKE, MotorDrive.BRAKE]
    assert backend.last_sent == [MotorSpecialState.BRAKE] * 2
    # The unanswered replies are drained; the next exchange gets its own reply.
    assert await board.motors[1].get_power() is MotorSpecialState.BRAKE
    backend.close_now()
    assert backend.make_safe_now(0.5) is False
    await board.close()


async def test_the_motor_cache_changes_only_once_the_board_has_acknowledged() -> None:
    stream = ScriptedStream([
        (PROBE, PROBE_REPLY),
        (b"MOT:0:SET:0\n", b"NACK:Invalid motor power\n"),
        (b"MOT:0:SET:0\n", b"ACK\n"),
    ])
    board = await Backend.from_stream(stream, port="scripted", serial_number="srM")
    backend = board.backend
    assert isinstance(backend, Backend)
    with pytest.raises(NackError):
        await backend.set_motor_state(0, MotorSpecialState.BRAKE)
    assert backend.last_sent == [None, None]
    await backend.set_motor_state(0, MotorSpecialState.BRAKE)
    assert backend.last_sent == [MotorSpecialState.BRAKE, None]
    backend.reset_board_state()  # the board came back: it has reset
    assert backend.last_sent == [None, None]
    stream.assert_all_used()
    await board.close()


async def test_a_refused_query_raises_the_boards_reason() -> None:
    stream = ScriptedStream([
        (PROBE, PROBE_REPLY),
        (b"MOT:1:GET?\n", b"NACK:Busy\n"),
        (b"MOT:1:GET?\n", b"0:0\n"),
        (b"*STATUS?\n", b"NACK:Later\n"),
    ])
    board = await Backend.from_stream(stream, port="scripted", serial_number="srM")
    backend = board.backend
    assert isinstance(backend, Backend)
    with pytest.raises(NackError, match=r"MOT:1:GET\?.*Busy"):
        await backend.get_motor_state(1)
    assert await backend.get_motor_state(1) is MotorSpecialState.COAST
    seen: list[bytes] = []
    with pytest.raises(NackError, match=r"\*STATUS\?.*Later"):
        await backend._query_then(b"*STATUS?\n", seen.append)
    assert seen == []  # a refusal never reaches the reply's reader
    stream.assert_all_used()
    await board.close()
