"""The SR power board fw 4.4 simulator, byte for byte against
the power board's page of the internals docs (docs/internals/sr-power-board.rst)."""

import pytest

from j5aio.simulator import BuzzerNote, SRPowerBoardFw4Simulator
from j5aio.simulator.base import SimulatorUnpluggedError
from tests.dataclass_twins import assert_like_generated


def ask(sim: SRPowerBoardFw4Simulator, line: bytes) -> bytes:
    return sim.receive(line + b"\n")


@pytest.fixture
def sim() -> SRPowerBoardFw4Simulator:
    return SRPowerBoardFw4Simulator("srABC")


def test_identity_and_usb(sim: SRPowerBoardFw4Simulator) -> None:
    assert ask(sim, b"*IDN?") == b"Student Robotics:PBv4B:srABC:4.4.2\n"
    assert (sim.usb_vid, sim.usb_pid) == (0x1BDA, 0x0010)
    assert (sim.manufacturer, sim.product) == ("Student Robotics", "Power Board v4")
    assert sim.open() == b""
    assert ask(SRPowerBoardFw4Simulator("x", version="4.4"), b"*IDN?").endswith(b":4.4\n")


def test_power_up_state(sim: SRPowerBoardFw4Simulator) -> None:
    assert sim.outputs == (False, False, False, False, True, False, False)
    assert sim.led_modes == ("1", "0")
    assert sim.playing is not None and sim.playing.frequency == 523
    sim.advance(0.2)
    assert sim.playing is None


def test_outputs_and_brain(sim: SRPowerBoardFw4Simulator) -> None:
    assert ask(sim, b"OUT:0:SET:1") == b"ACK\n"
    assert ask(sim, b"OUT:6:SET:1xyz") == b"ACK\n"  # only the first character counts
    assert sim.outputs[0] and sim.outputs[6]
    assert ask(sim, b"OUT:0:GET?") == b"1\n"
    assert ask(sim, b"OUT:4:SET:0") == b"NACK:Brain output cannot be controlled\n"
    assert sim.outputs[4]
    assert ask(sim, b"OUT:4:GET?") == b"1\n"
    sim.set_output_current(0, 2.5)
    assert ask(sim, b"OUT:0:I?") == b"2500\n"
    assert ask(sim, b"OUT:1:I?") == b"0\n"  # an output that is off draws nothing
    assert ask(sim, b"*SYS:BRAIN:SET:0") == b"ACK\n"
    assert not sim.outputs[4]


@pytest.mark.parametrize(
    ("line", "reply"),
    [
        (b"OUT", b"NACK:Missing output number"),
        (b"OUT:7:SET:1", b"NACK:Invalid output number"),
        (b"OUT:x:SET:1", b"NACK:Invalid output number"),
        (b"OUT:1", b"NACK:Missing output command"),
        (b"OUT:1:SET", b"NACK:Missing output enable argument"),
        (b"OUT:1:SET:2", b"NACK:Invalid output enable argument"),
        (b"OUT:1:TOGGLE", b"NACK:Unknown output command"),
        (b"LED", b"NACK:Missing LED name"),
        (b"LED:BLUE:SET:1", b"NACK:Invalid LED name"),
        (b"LED:RUN", b"NACK:Missing LED argument"),
        (b"LED:RUN:SET", b"NACK:Missing LED value"),
        (b"LED:RUN:SET:2", b"NACK:Invalid LED value"),
        (b"LED:RUN:BLINK", b"NACK:Invalid LED argument"),
        (b"BATT", b"NACK:Missing argument"),
        (b"BATT:P?", b"NACK:Unknown battery command"),
        (b"BTN", b"NACK:Missing button name"),
        (b"BTN:STOP:GET?", b"NACK:Invalid button name"),
        (b"BTN:START", b"NACK:Missing button command"),
        (b"BTN:START:SET", b"NACK:Invalid button command"),
        (b"NOTE", b"NACK:Missing note frequency"),
        (b"NOTE:abc:100", b"NACK:Invalid note frequency"),
        (b"NOTE:440", b"NACK:Missing note duration"),
        (b"NOTE:440:x", b"NACK:Invalid note duration"),
        (b"*SYS", b"NACK:Missing system command"),
        (b"*SYS:WHAT", b"NACK:Invalid system command"),
        (b"HELLO:1", b"NACK:Unknown command: 'HELLO'"),
    ],
)
def test_nack_texts(sim: SRPowerBoardFw4Simulator, line: bytes, reply: bytes) -> None:
    assert ask(sim, line) == reply + b"\n"


def test_overcurrent_latch_and_status(sim: SRPowerBoardFw4Simulator) -> None:
    ask(sim, b"OUT:1:SET:1")
    sim.trip_output(1)
    assert not sim.outputs[1]
    assert ask(sim, b"OUT:1:SET:1") == b"ACK\n"  # ACKed, but stays off
    assert ask(sim, b"OUT:1:GET?") == b"0\n"
    sim.temperature = 45
    sim.regulator_voltage = 5.1
    assert ask(sim, b"*STATUS?") == b"0,1,0,0,0,0,0:45:1:5100\n"
    sim.temperature = 30
    assert ask(sim, b"*STATUS?") == b"0,1,0,0,0,0,0:30:0:5100\n"
    ask(sim, b"*SYS:FAN:SET:1")
    assert sim.fan
    ask(sim, b"*RESET")
    assert sim.overcurrent_latches == (False,) * 7
    assert ask(sim, b"OUT:1:SET:1") == b"ACK\n" and sim.outputs[1]


def test_reset_is_the_safe_state(sim: SRPowerBoardFw4Simulator) -> None:
    for line in (
        b"OUT:0:SET:1",
        b"OUT:6:SET:1",
        b"LED:RUN:SET:F",
        b"LED:ERR:SET:1",
        b"NOTE:440:5000",
    ):
        assert ask(sim, line) == b"ACK\n"
    sim.click_start()
    assert ask(sim, b"*RESET") == b"ACK\n"
    assert sim.outputs == (False, False, False, False, True, False, False)
    assert sim.led_modes == ("0", "0")
    assert sim.playing is None
    assert ask(sim, b"BTN:START:GET?") == b"0:0\n"


def test_start_button_is_latched(sim: SRPowerBoardFw4Simulator) -> None:
    assert ask(sim, b"BTN:START:GET?") == b"0:0\n"
    sim.click_start()
    sim.click_start(external=True)
    assert ask(sim, b"BTN:START:GET?") == b"1:1\n"
    assert ask(sim, b"BTN:START:GET?") == b"0:0\n"  # reading cleared both
    sim.press_start()
    assert ask(sim, b"BTN:START:GET?") == b"1:0\n"
    sim.press_start()  # still held: not a new press
    assert ask(sim, b"BTN:START:GET?") == b"0:0\n"
    sim.release_start()
    sim.press_start(external=True)
    sim.release_start(external=True)
    assert ask(sim, b"BTN:START:GET?") == b"0:1\n"  # pressed since the last read
    assert ask(sim, b"BTN:START:GET?") == b"0:0\n"


def test_buzzer_replaces_and_counts_down(sim: SRPowerBoardFw4Simulator) -> None:
    sim.advance(1)
    assert ask(sim, b"NOTE:GET?") == b"0:0\n"
    assert ask(sim, b"NOTE:440:1000") == b"ACK\n"
    sim.advance(0.25)
    assert ask(sim, b"NOTE:GET?") == b"440:750\n"
    assert ask(sim, b"NOTE:1760:100") == b"ACK\n"  # no queue: replaces the first
    assert ask(sim, b"NOTE:GET?") == b"1760:100\n"
    assert ask(sim, b"NOTE:20000:100") == b"ACK\n"
    assert ask(sim, b"NOTE:GET?") == b"10000:100\n"  # capped at 10 kHz
    assert ask(sim, b"NOTE:440:0") == b"ACK\n"
    assert sim.playing is None
    assert [n.frequency for n in sim.note_history] == [440, 1760, 20000, 440]


def test_leds_flash_once_a_second(sim: SRPowerBoardFw4Simulator) -> None:
    assert ask(sim, b"LED:RUN:SET:F") == b"ACK\n"
    assert ask(sim, b"LED:RUN:GET?") == b"F\n"
    seen = []
    for _ in range(4):
        seen.append(sim.run_led)
        sim.advance(1)
    assert seen == [True, False, True, False]
    ask(sim, b"LED:ERR:SET:1")
    assert sim.error_led and ask(sim, b"LED:ERR:GET?") == b"1\n"


def test_battery(sim: SRPowerBoardFw4Simulator) -> None:
    sim.battery_voltage = 11.5
    sim.battery_current = -0.25
    assert ask(sim, b"BATT:V?") == b"11500\n"
    assert ask(sim, b"BATT:I?") == b"-250\n"
    assert (sim.battery_voltage, sim.battery_current) == (11.5, -0.25)


def test_line_rules(sim: SRPowerBoardFw4Simulator) -> None:
    assert sim.receive(b"*ID") == b""
    assert sim.receive(b"N?\r junk\n") == b"Student Robotics:PBv4B:srABC:4.4.2\n"
    assert sim.receive(b"X" * 63) == b""  # 63 bytes without a newline: discarded
    assert ask(sim, b"ECHO:hi:there") == b"hi\n"
    # Replies made from one packet share a 64-byte buffer.
    reply = sim.receive(b"*IDN?\n*IDN?\n")
    assert len(reply) == 64 and reply.startswith(b"Student Robotics:PBv4B")


def test_system_delay_coefficients(sim: SRPowerBoardFw4Simulator) -> None:
    assert ask(sim, b"*SYS:DELAY_COEFF:GET?") == b"100:100:20:40:2000\n"
    assert ask(sim, b"*SYS:DELAY_COEFF:SET:1:2:3:4:5") == b"ACK\n"
    assert ask(sim, b"*SYS:DELAY_COEFF:GET?") == b"1:2:3:4:5\n"
    assert ask(sim, b"*SYS:DELAY_COEFF:SET:1:2") == b"NACK:Invalid system command\n"


def test_unplug_is_the_boards_own_safe_state(sim: SRPowerBoardFw4Simulator) -> None:
    ask(sim, b"OUT:0:SET:1")
    ask(sim, b"NOTE:440:10000")
    sim.unplug()
    with pytest.raises(SimulatorUnpluggedError):
        sim.receive(b"*IDN?\n")
    assert sim.outputs == (False, False, False, False, True, False, False)
    assert sim.playing is None and sim.led_modes == ("1", "1")
    sim.plug()
    assert sim.led_modes == ("1", "0")
    assert sim.reset() == b""


def test_partial_line_is_kept_until_its_newline(sim: SRPowerBoardFw4Simulator) -> None:
    sim.receive(b"OUT:0:")
    assert sim._input.pending == b"OUT:0:"
    assert sim.receive(b"GET?\n") == b"0\n"
    assert sim._input.pending == b""


def test_a_buzzer_note_is_the_generated_dataclass(sim: SRPowerBoardFw4Simulator) -> None:
    assert_like_generated(
        BuzzerNote, [((523, 150), {}), ((440, 150), {}), ((), {"frequency": 1, "duration_ms": 0})]
    )
    assert ask(sim, b"NOTE:440:100") == b"ACK\n"
    assert sim.playing == BuzzerNote(440, 100) != BuzzerNote(440, 101)
    assert sim.note_history[-1] == BuzzerNote(frequency=440, duration_ms=100)
