import pytest

from j5aio.simulator import SERIAL_SIMULATORS
from j5aio.simulator.sr_servo_fw4 import SBServoBoardFw4Simulator, SRServoBoardFw4Simulator


def ask(sim: SRServoBoardFw4Simulator, line: bytes) -> bytes:
    return sim.receive(line + b"\n")


def test_registered_names() -> None:
    assert SERIAL_SIMULATORS["sr-servo-fw4"] is SRServoBoardFw4Simulator
    assert SERIAL_SIMULATORS["sb-servo-fw4"] is SBServoBoardFw4Simulator


def test_identity_and_usb_descriptors() -> None:
    sim = SRServoBoardFw4Simulator("srABC")
    assert ask(sim, b"*IDN?") == b"Student Robotics:SBv4B:srABC:4.3\n"
    assert (sim.usb_vid, sim.usb_pid) == (0x1BDA, 0x0011)
    assert (sim.manufacturer, sim.product) == ("Student Robotics", "Servo Board v4")
    assert sim.open() == b""
    fork = SBServoBoardFw4Simulator("sbXYZ")
    assert ask(fork, b"*IDN?") == b"Student Robotics:SBv4B:sbXYZ:4.4\n"


def test_set_get_quantises_down_to_5us_and_disable() -> None:
    sim = SRServoBoardFw4Simulator("sr1")
    assert ask(sim, b"SERVO:3:GET?") == b"0\n"
    assert ask(sim, b"SERVO:3:SET:1499") == b"ACK\n"
    assert ask(sim, b"SERVO:3:GET?") == b"1495\n"
    assert sim.pulse_widths[3] == 1495
    assert ask(sim, b"SERVO:3:DISABLE") == b"ACK\n"
    assert ask(sim, b"SERVO:3:GET?") == b"0\n"
    assert sim.pulse_widths[3] is None


@pytest.mark.parametrize(
    ("sim_class", "count", "lowest"),
    [(SRServoBoardFw4Simulator, 12, 500), (SBServoBoardFw4Simulator, 8, 300)],
)
def test_channel_count_and_range_per_variant(
    sim_class: type[SRServoBoardFw4Simulator], count: int, lowest: int,
) -> None:
    sim = sim_class("x")
    assert len(sim.pulse_widths) == count
    assert ask(sim, b"SERVO:%d:SET:1500" % (count - 1)) == b"ACK\n"
    assert ask(sim, b"SERVO:%d:SET:1500" % count) == b"NACK:Invalid servo number\n"
    assert ask(sim, b"SERVO:0:SET:%d" % lowest) == b"ACK\n"
    assert ask(sim, b"SERVO:0:SET:%d" % (lowest - 1)) == b"NACK:Invalid servo setpoint\n"
    assert ask(sim, b"SERVO:0:SET:4000") == b"ACK\n"
    assert ask(sim, b"SERVO:0:SET:4001") == b"NACK:Invalid servo setpoint\n"


@pytest.mark.parametrize(
    ("line", "reply"),
    [
        (b"SERVO", b"NACK:Missing servo number"),
        (b"SERVO:", b"NACK:Missing servo number"),
        (b"SERVO:x:SET:1500", b"NACK:Invalid servo number"),
        (b"SERVO:1", b"NACK:Missing servo command"),
        (b"SERVO:1:SET", b"NACK:Missing servo setpoint"),
        (b"SERVO:1:SET:x", b"NACK:Invalid servo setpoint"),
        (b"SERVO:1:SPIN", b"NACK:Unknown servo command"),
        (b"*DBG", b"NACK:Missing debug command"),
        (b"*DBG:MOTORS", b"NACK:Unknown debug command"),
        (b"*DBG:SERVOS", b"NACK:Missing phase number"),
        (b"*DBG:SERVOS:4", b"NACK:Invalid phase number"),
        (b"FOO:1", b"NACK:Unknown command: 'FOO'"),
        (b"", b"NACK:Unknown command: ''"),
        (b"ECHO:hello:there", b"hello"),
        (b"ECHO", b""),
    ],
)
def test_replies_and_nack_texts(line: bytes, reply: bytes) -> None:
    assert ask(SRServoBoardFw4Simulator("x"), line) == reply + b"\n"


def test_status_meters_and_outside_control() -> None:
    sim = SRServoBoardFw4Simulator("x")
    assert ask(sim, b"*STATUS?") == b"0:1\n"
    sim.power_good = False
    sim.watchdog_failed = True
    assert ask(sim, b"*STATUS?") == b"1:0\n"
    sim.set_supply(voltage=5.25, current=1.5)
    assert ask(sim, b"SERVO:V?") == b"5250\n"
    assert ask(sim, b"SERVO:I?") == b"1500\n"
    sim.set_supply()
    assert ask(sim, b"SERVO:I?") == b"1500\n"


def test_reset_disables_every_servo_and_debug_lists_a_phase() -> None:
    sim = SRServoBoardFw4Simulator("x")
    for servo in (0, 3, 4):
        ask(sim, b"SERVO:%d:SET:1200" % servo)
    assert ask(sim, b"*DBG:SERVOS:1") == b"1200,1200,0,0\n"
    assert ask(sim, b"*DBG:SERVOS:2") == b"0,1200,0,0\n"  # servos 1, 4, 7, 10
    assert ask(sim, b"*RESET") == b"ACK\n"
    assert sim.pulse_widths == (None,) * 12


def test_framing_cr_truncation_split_writes_and_long_lines() -> None:
    sim = SRServoBoardFw4Simulator("x")
    assert sim.receive(b"SERVO:1:SE") == b""
    assert sim.receive(b"T:1500\r junk\n") == b"ACK\n"
    assert sim.pulse_widths[1] == 1500
    assert sim.receive(b"A" * 63) == b""  # 63 bytes without a newline are thrown away
    assert sim.receive(b"*IDN?\n") == b"Student Robotics:SBv4B:x:4.3\n"


def test_replies_to_one_packet_share_a_64_byte_buffer() -> None:
    sim = SRServoBoardFw4Simulator("srABC")
    reply = sim.receive(b"*IDN?\n*IDN?\n*IDN?\n")
    assert len(reply) == 64
    assert reply.startswith(b"Student Robotics:SBv4B:srABC:4.3\nStudent")


def test_servos_keep_pulsing_when_unplugged_but_a_new_boot_disables_them() -> None:
    sim = SRServoBoardFw4Simulator("x")
    ask(sim, b"SERVO:0:SET:1500")
    sim.unplug()
    assert not sim.connected
    assert sim.pulse_widths[0] == 1500
    sim.plug()  # USB-powered: plugging in boots it
    assert sim.pulse_widths[0] is None
    ask(sim, b"SERVO:0:SET:1500")
    assert sim.reset() == b""
    assert sim.pulse_widths[0] is None
