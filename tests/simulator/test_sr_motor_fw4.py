"""The SR motor board fw 4.4 / 4.5 simulator, byte for byte against
the motor board's page of the internals docs (docs/internals/sr-motor-board.rst)."""

import pytest

from j5aio.simulator import MotorChannel, MotorDrive, SRMotorBoardFw4Simulator
from tests.dataclass_twins import assert_like_generated


def ask(sim: SRMotorBoardFw4Simulator, line: bytes) -> bytes:
    return sim.receive(line + b"\n")


@pytest.fixture
def sim() -> SRMotorBoardFw4Simulator:
    return SRMotorBoardFw4Simulator("srMOT")


def test_identity(sim: SRMotorBoardFw4Simulator) -> None:
    assert ask(sim, b"*IDN?") == b"Student Robotics:MCv4B:srMOT:4.4.1\n"
    assert (sim.usb_vid, sim.usb_pid, sim.product) == (0x0403, 0x6001, "MCV4B")
    assert SRMotorBoardFw4Simulator.baudrate == 115_200
    assert ask(SRMotorBoardFw4Simulator("s", version="4.5.0"), b"*IDN?").endswith(b":4.5.0\n")


def test_brake_is_set_zero_and_coast_is_disable(sim: SRMotorBoardFw4Simulator) -> None:
    assert [m.drive for m in sim.motors] == [MotorDrive.COAST, MotorDrive.COAST]
    assert ask(sim, b"MOT:0:GET?") == b"0:0\n"
    assert ask(sim, b"MOT:0:SET:0") == b"ACK\n"
    assert sim.motors[0].drive is MotorDrive.BRAKE
    assert ask(sim, b"MOT:0:GET?") == b"1:0\n"
    assert ask(sim, b"MOT:0:SET:-250") == b"ACK\n"
    reversing = sim.motors[0]
    assert reversing.drive is MotorDrive.REVERSE
    assert reversing.power == -0.25
    assert ask(sim, b"MOT:0:GET?") == b"1:-250\n"
    assert ask(sim, b"MOT:0:DISABLE") == b"ACK\n"
    assert ask(sim, b"MOT:0:GET?") == b"0:0\n"  # 0 whenever disabled
    assert ask(sim, b"MOT:1:SET:1000") == b"ACK\n"
    assert sim.motors[1].duty == 1.0 and sim.motors[1].drive is MotorDrive.FORWARD


@pytest.mark.parametrize(
    ("line", "reply"),
    [
        (b"MOT", b"NACK:Missing motor number"),
        (b"MOT:2:SET:0", b"NACK:Invalid motor number"),
        (b"MOT:0", b"NACK:Missing motor command"),
        (b"MOT:0:SET", b"NACK:Missing motor power"),
        (b"MOT:0:SET:1001", b"NACK:Invalid motor power"),
        (b"MOT:0:SET:0.5", b"NACK:Invalid motor power"),
        (b"MOT:0:SPIN", b"NACK:Unknown motor command"),
        (b"*SYS", b"NACK:Missing system command"),
        (b"*SYS:REBOOT", b"NACK:Invalid system command"),
        (b"GO", b"NACK:Unknown command: 'GO'"),
    ],
)
def test_nack_texts(sim: SRMotorBoardFw4Simulator, line: bytes, reply: bytes) -> None:
    assert ask(sim, line) == reply + b"\n"


def test_current_faults_voltage_and_reset(sim: SRMotorBoardFw4Simulator) -> None:
    sim.set_motor_current(1, 6.0)
    assert ask(sim, b"MOT:1:I?") == b"0\n"  # coasting: no current
    ask(sim, b"MOT:1:SET:800")
    assert ask(sim, b"MOT:1:I?") == b"6000\n"
    assert sim.current_leds == (False, True)
    sim.set_fault(0)
    sim.input_voltage = 11.8
    assert ask(sim, b"*STATUS?") == b"1,0:11800\n"
    assert sim.faults == (True, False) and sim.input_voltage == 11.8
    assert ask(sim, b"*RESET") == b"ACK\n"
    assert ask(sim, b"*STATUS?") == b"0,0:11800\n"
    assert [m.drive for m in sim.motors] == [MotorDrive.COAST, MotorDrive.COAST]


def test_line_rules(sim: SRMotorBoardFw4Simulator) -> None:
    assert sim.receive(b"*I\rDN?\r\n") == b"Student Robotics:MCv4B:srMOT:4.4.1\n"
    assert sim.receive(b"Y" * 63 + b"*IDN?\n").startswith(b"Student")
    assert ask(sim, b"ECHO:abc") == b"abc\n"


def test_fw3_probe_gets_a_nack_then_the_identity(sim: SRMotorBoardFw4Simulator) -> None:
    assert sim.receive(b"\x00\n*IDN?\n") == (
        b"NACK:Unknown command: '\x00'\nStudent Robotics:MCv4B:srMOT:4.4.1\n"
    )


def test_bootloader_then_silence(sim: SRMotorBoardFw4Simulator) -> None:
    ask(sim, b"MOT:0:SET:500")
    assert ask(sim, b"*SYS:BOOTLOADER") == b"ACK\n\n\n"
    assert sim.in_bootloader
    assert ask(sim, b"*IDN?") == b""
    assert sim.reset() == b""
    assert not sim.in_bootloader


def test_unplugging_changes_nothing(sim: SRMotorBoardFw4Simulator) -> None:
    ask(sim, b"MOT:0:SET:500")
    sim.unplug()
    sim.plug()
    assert sim.motors[0].value == 500


def test_a_motor_channel_is_the_generated_dataclass(sim: SRMotorBoardFw4Simulator) -> None:
    assert_like_generated(
        MotorChannel, [((), {}), ((True, -500), {}), ((), {"value": 7}), ((True,), {})]
    )
    assert sim.motors == (MotorChannel(), MotorChannel(False, 0))
    assert ask(sim, b"MOT:1:SET:-250") == b"ACK\n"
    assert sim.motors[1] == MotorChannel(enabled=True, value=-250) != MotorChannel(True, 250)
    assert sim.motors[1].power == -0.25
