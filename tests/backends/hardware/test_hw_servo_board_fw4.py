from types import SimpleNamespace

import pytest

from j5aio.backends.hardware.options import DiscoveryOptions
from j5aio.backends.hardware.sr.v4 import (
    SERVO_FW4_BACKENDS,
    SBServoBoardHardwareBackend,
    SRV4ServoBoardFw4HardwareBackend,
)
from j5aio.backends.hardware.sr.v4 import servo_fw4_codec as servo_codec
from j5aio.backends.hardware.transports.memory import SimulatorStream
from j5aio.backends.hardware.transports.stream import ByteStream
from j5aio.boards.sb import SBServoBoard
from j5aio.boards.sr.v4 import ServoBoard, ServoBoardFw4
from j5aio.components.pulse_servo import pulse_for_position
from j5aio.errors import CommunicationError, UnexpectedReplyError, UnsupportedFirmwareError
from j5aio.simulator.sr_servo_fw4 import SBServoBoardFw4Simulator, SRServoBoardFw4Simulator
from j5aio.testing.transports import RecordingStream, ScriptedStream

SR = SRV4ServoBoardFw4HardwareBackend
SB = SBServoBoardHardwareBackend
AnyServoBackend = type[SRV4ServoBoardFw4HardwareBackend] | type[SBServoBoardHardwareBackend]
IDN_SR = (b"*IDN?\n", b"Student Robotics:SBv4B:srABC:4.3\n")


async def connect(
    backend: AnyServoBackend,
    sim: SRServoBoardFw4Simulator,
) -> tuple[ServoBoardFw4, RecordingStream]:
    stream = RecordingStream(SimulatorStream(sim, time_scale=0))
    board = await backend.from_stream(stream, port="sim", serial_number=sim.serial_number)
    assert isinstance(board, ServoBoardFw4)
    await board.setup()
    stream.clear()
    return board, stream


async def test_handshake_sends_only_the_identity_request() -> None:
    stream = ScriptedStream([IDN_SR])
    board = await SR.from_stream(stream, port="scripted", serial_number="srABC")
    stream.assert_all_used()
    assert board.firmware_version == "4.3"
    backend = board.backend
    assert isinstance(backend, SR)
    assert backend.asset_tag == "srABC"
    assert backend.pulse_limits == ((1000, 2000),) * 12
    assert backend.firmware.servo_count == 12
    await board.close()


@pytest.mark.parametrize(
    ("backend", "sim", "board_class", "count"),
    [
        (SR, SRServoBoardFw4Simulator, ServoBoardFw4, 12),
        (SB, SBServoBoardFw4Simulator, SBServoBoard, 8),
    ],
)
async def test_each_firmware_gets_its_board(
    backend: AnyServoBackend,
    sim: type[SRServoBoardFw4Simulator],
    board_class: type[ServoBoardFw4],
    count: int,
) -> None:
    board, _ = await connect(backend, sim("x"))
    assert type(board) is board_class
    assert isinstance(board, ServoBoard)  # existing programs keep working
    assert len(board.servos) == count
    assert SERVO_FW4_BACKENDS[board.firmware_version or ""] is backend
    await board.close()


@pytest.mark.parametrize(
    ("backend", "sim", "found", "supported"),
    [
        (SR, SBServoBoardFw4Simulator, "4.4", ("4.3",)),
        (SB, SRServoBoardFw4Simulator, "4.3", ("4.4",)),
    ],
)
async def test_the_other_firmware_is_unsupported(
    backend: AnyServoBackend,
    sim: type[SRServoBoardFw4Simulator],
    found: str,
    supported: tuple[str],
) -> None:
    stream = SimulatorStream(sim("x"), time_scale=0)
    with pytest.raises(UnsupportedFirmwareError) as info:
        await backend.from_stream(stream, port="sim", serial_number="x")
    assert (info.value.found, info.value.supported) == (found, supported)
    assert stream.is_closed


async def test_another_board_type_is_refused() -> None:
    stream = ScriptedStream([(b"*IDN?\n", b"Student Robotics:PBv4B:srP:4.4.2\n")])
    with pytest.raises(UnexpectedReplyError, match="PBv4B"):
        await SR.from_stream(stream, port="scripted", serial_number="x")


async def test_positions_map_through_limits_and_read_back_quantised() -> None:
    sim = SRServoBoardFw4Simulator("x")
    board, stream = await connect(SR, sim)
    servo = board.servos[2]
    await servo.set_position(0.333)
    assert stream.sent == b"SERVO:2:SET:1666\n"
    assert sim.pulse_widths[2] == 1665
    assert await servo.get_position() == 0.33
    assert await servo.get_pulse_width() == 1665
    await servo.set_pulse_limits(500, 2500)
    assert await servo.get_pulse_limits() == (500, 2500)
    assert await servo.get_pulse_range() == (500, 4000)
    stream.clear()
    await servo.set_position(-1)
    assert stream.sent == b"SERVO:2:SET:500\n"
    await servo.set_position(None)
    assert sim.pulse_widths[2] is None
    assert await servo.get_position() is None
    assert board.servos[3].identifier == 3
    await board.close()


@pytest.mark.parametrize(
    ("backend", "sim", "limits"),
    [
        (SR, SRServoBoardFw4Simulator, None),
        (SR, SRServoBoardFw4Simulator, (500, 4000)),
        (SB, SBServoBoardFw4Simulator, None),
        (SB, SBServoBoardFw4Simulator, (300, 4000)),
    ],
)
async def test_every_position_sends_what_the_codec_encodes(
    backend: AnyServoBackend,
    sim: type[SRServoBoardFw4Simulator],
    limits: tuple[int, int] | None,
) -> None:
    board, stream = await connect(backend, sim("x"))
    servo_backend = board.backend
    assert isinstance(servo_backend, backend)
    if limits is not None:
        await servo_backend.set_servo_pulse_limits(1, limits)
    firmware, used = servo_backend.firmware, servo_backend.pulse_limits[1]
    for step in range(-200, 201):
        for position in (step / 200, -1, 1, 0):  # floats, and ints given to the backend
            stream.clear()
            await servo_backend.set_servo_position(1, position)
            pulse = pulse_for_position(position, used)
            assert stream.sent == servo_codec.encode_set(firmware, 1, pulse)
    await board.close()


async def test_the_fork_accepts_its_shorter_pulses() -> None:
    sim = SBServoBoardFw4Simulator("x")
    board, _ = await connect(SB, sim)
    await board.servos[7].set_pulse_limits(300, 4000)
    await board.servos[7].set_position(-1)
    assert sim.pulse_widths[7] == 300
    with pytest.raises(ValueError, match="300 to 4000"):
        await board.servos[7].set_pulse_limits(299, 4000)
    await board.close()


@pytest.mark.parametrize(
    ("backend", "sim", "limits", "pulse_at_minus_one", "pulse_at_one"),
    [
        (SR, SRServoBoardFw4Simulator, (1000, 2000), 1000, 2000),  # sr-robot3's defaults
        (SB, SBServoBoardFw4Simulator, (350, 1980), 350, 1980),  # sbot's defaults
    ],
)
async def test_each_firmware_starts_with_its_kit_librarys_pulse_limits(
    backend: AnyServoBackend,
    sim: type[SRServoBoardFw4Simulator],
    limits: tuple[int, int],
    pulse_at_minus_one: int,
    pulse_at_one: int,
) -> None:
    simulator = sim("x")
    board, _ = await connect(backend, simulator)
    assert await board.servos[0].get_pulse_limits() == limits
    await board.servos[0].set_position(-1)
    assert simulator.pulse_widths[0] == pulse_at_minus_one
    await board.servos[0].set_position(1)
    assert simulator.pulse_widths[0] == pulse_at_one
    await board.close()


@pytest.mark.parametrize(
    ("lower", "upper", "error", "match"),
    [
        (400, 2000, ValueError, "500 to 4000"),
        (1000, 4100, ValueError, "500 to 4000"),
        (2000, 1000, ValueError, "below the upper"),
        (1500, 1500, ValueError, "below the upper"),
        (1000.0, 2000, TypeError, "lower pulse limit"),
        (1000, True, TypeError, "upper pulse limit"),
    ],
)
async def test_bad_limits_are_refused_sending_nothing(
    lower: object,
    upper: object,
    error: type[Exception],
    match: str,
) -> None:
    board, stream = await connect(SR, SRServoBoardFw4Simulator("x"))
    with pytest.raises(error, match=match):
        await board.servos[0].set_pulse_limits(lower, upper)  # type: ignore[arg-type]
    assert await board.servos[0].get_pulse_limits() == (1000, 2000)
    assert stream.sent == b""
    await board.close()


async def test_backend_refuses_bad_identifiers_and_limits_sending_nothing() -> None:
    board, stream = await connect(SR, SRServoBoardFw4Simulator("x"))
    backend = board.backend
    assert isinstance(backend, SR)
    with pytest.raises(ValueError, match="0 to 11"):
        await backend.set_servo_position(12, 0.0)
    with pytest.raises(ValueError, match="0 to 11"):
        await backend.set_servo_position(12, None)
    with pytest.raises(ValueError, match="0 to 11"):
        await backend.get_servo_pulse_limits(-1)
    with pytest.raises(ValueError, match="lower first"):
        await backend.set_servo_pulse_limits(0, (2000, 1000))
    with pytest.raises(ValueError, match="supply sensor 0 to 0"):
        await backend.get_supply_voltage(1)
    with pytest.raises(ValueError, match="flags 0 to 1"):
        await backend.get_flag_state(2)
    with pytest.raises(ValueError, match="flags"):
        await backend.get_flag_state(True)
    assert stream.sent == b""
    await board.close()


async def test_supply_flags_and_reset() -> None:
    sim = SRServoBoardFw4Simulator("x")
    board, _ = await connect(SR, sim)
    sim.set_supply(voltage=5.5, current=0.75)
    assert await board.supply.get_voltage() == 5.5
    assert await board.supply.get_current() == 0.75
    assert await board.power_good.get_state() is True
    assert await board.watchdog_failed.get_state() is False
    sim.power_good = False
    sim.watchdog_failed = True
    assert await board.power_good.get_state() is False
    assert await board.watchdog_failed.get_state() is True
    await board.servos[0].set_position(0)
    backend = board.backend
    assert isinstance(backend, SR)
    await backend.reset()
    assert sim.pulse_widths == (None,) * 12
    await board.make_safe()  # leaves the servos alone, as on firmware 2
    await board.close()


async def test_nack_and_malformed_replies_are_communication_errors() -> None:
    stream = ScriptedStream(
        [
            IDN_SR,
            (b"SERVO:0:SET:1500\n", b"NACK:Invalid servo setpoint\n"),
            (b"SERVO:0:GET?\n", b"1502\n"),
            (b"*STATUS?\n", b"0:1:1\n"),
            (b"SERVO:V?\n", b"lots\n"),
        ]
    )
    board = await SR.from_stream(stream, port="scripted", serial_number="x")
    assert isinstance(board, ServoBoardFw4)
    with pytest.raises(CommunicationError, match="refused 'SERVO:0:SET:1500'"):
        await board.servos[0].set_position(0)
    with pytest.raises(UnexpectedReplyError, match=r"answered 'SERVO:0:GET\?' with b'1502'"):
        await board.servos[0].get_position()
    with pytest.raises(UnexpectedReplyError, match=r"\*STATUS\?"):
        await board.power_good.get_state()
    with pytest.raises(UnexpectedReplyError, match=r"SERVO:V\?"):
        await board.supply.get_voltage()
    stream.assert_all_used()
    await board.close()


def test_firmware_before_the_handshake_is_an_error() -> None:
    backend = SR.__new__(SR)
    backend._firmware = None
    backend._port = "nowhere"
    with pytest.raises(RuntimeError, match="not been identified"):
        backend.firmware  # noqa: B018


def servo_port(device: str, serial_number: str) -> SimpleNamespace:
    return SimpleNamespace(
        device=device,
        vid=0x1BDA,
        pid=0x0011,
        serial_number=serial_number,
        manufacturer="Student Robotics",
        product="Servo Board v4",
        description="Servo Board v4",
    )


async def test_discovery_and_attach_by_usb_identity() -> None:
    sims = {
        "/dev/s1": SRServoBoardFw4Simulator("srS1"),
        "/dev/s2": SRServoBoardFw4Simulator("srS2"),
    }
    opened: list[str] = []

    async def opener(port: str, baudrate: int) -> ByteStream:
        opened.append(port)
        return SimulatorStream(sims[port], time_scale=0)

    ports = [
        servo_port("/dev/s2", "srS2"),
        servo_port("/dev/s1", "srS1"),
        SimpleNamespace(**{**vars(servo_port("/dev/p", "srP")), "pid": 0x0010}),
    ]
    boards = await SR.discover(options=DiscoveryOptions(port_source=lambda: ports, opener=opener))
    assert [board.serial_number for board in boards] == ["srS1", "srS2"]
    assert sorted(opened) == ["/dev/s1", "/dev/s2"]
    for board in boards:
        await board.close()
    attached = await SR.attach("/dev/s1", opener=opener)
    assert attached.serial_number == "/dev/s1"
    await attached.close()


async def test_a_repeated_handshake_keeps_the_limits_and_refreshes_the_identity() -> None:
    sim = SRServoBoardFw4Simulator("srOLD")
    board, _ = await connect(SR, sim)
    await board.servos[0].set_pulse_limits(600, 2400)
    sim.serial_number = "srNEW"  # another board of the same firmware came back
    backend = board.backend
    assert isinstance(backend, SR)
    await backend._handshake(time_scale=0)
    assert backend.asset_tag == "srNEW"
    assert backend.pulse_limits[0] == (600, 2400)
    await board.close()


async def test_make_safe_now_leaves_the_servos_as_they_are() -> None:
    sim = SRServoBoardFw4Simulator("x")
    board, stream = await connect(SR, sim)
    await board.servos[0].set_position(0.5)
    stream.clear()
    assert board.backend.make_safe_now(0.5) is False
    assert stream.sent == b""
    await board.close()


async def test_the_handshake_tolerates_leftovers_ahead_of_its_line() -> None:
    sim = SRServoBoardFw4Simulator("x")
    sim.receive(b"\x01v")  # half a line from another kind's probe
    board, _ = await connect(SR, sim)
    assert board.firmware_version == "4.3"
    await board.close()
