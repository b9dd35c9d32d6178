"""Tests of the simulated kit's power wiring: boards fed by outputs, loads, battery, trips."""

from __future__ import annotations

from typing import TypeVar

import pytest

from j5aio.board_kinds import KitDefinition
from j5aio.power_outputs import BRAIN_OUTPUT
from j5aio.simulator.kit import KitConfig, SimulatedKit
from j5aio.simulator.loads import (
    BATTERY_INTERNAL_RESISTANCE,
    MOTOR_BOARD_IDLE_CURRENT,
    MOTOR_FULL_POWER_CURRENT,
    SERVO_BOARD_IDLE_CURRENT,
    SERVO_HOLDING_CURRENT,
)
from j5aio.simulator.sr_motor_fw3 import MotorMode, SRMotorBoardFw3Simulator
from j5aio.simulator.sr_motor_fw4 import MotorDrive, SRMotorBoardFw4Simulator
from j5aio.simulator.sr_power_fw3 import SRPowerBoardFw3Simulator
from j5aio.simulator.sr_power_fw4 import SRPowerBoardFw4Simulator
from j5aio.simulator.sr_servo_fw2 import SRServoBoardFw2Simulator
from j5aio.simulator.sr_servo_fw4 import SRServoBoardFw4Simulator
from j5aio.simulator.wiring import KitWiring, PowerFed, default_outputs

FW3_FULL_FORWARDS = bytes([0x02, 128 + 100])  # motor 0 at full power


T = TypeVar("T")


def only(kit: SimulatedKit, name: str, kind: type[T]) -> T:
    """The kit's one simulator called ``name``, checked to be a ``kind``."""
    (simulator,) = kit.simulators(name)
    assert isinstance(simulator, kind)
    return simulator


def mode(board: SRMotorBoardFw3Simulator, motor: int = 0) -> MotorMode:
    return board.motors[motor].mode


def switch_fw3(power: SRPowerBoardFw3Simulator, output: int, on: bool) -> None:
    """Switch an output of a firmware 3 power board as the host does (a USB write)."""
    power.ctrl_transfer(0x00, 64, int(on), output)


# --- each board without its 12 V ---


def test_a_motor_board_without_power_is_silent_and_boots_when_power_comes() -> None:
    board = SRMotorBoardFw3Simulator("MB")
    board.receive(FW3_FULL_FORWARDS)
    assert mode(board) is MotorMode.FORWARD
    board.powered = False
    assert mode(board) is MotorMode.COAST  # its controller is off
    assert board.receive(b"\x01") == b""  # the version query goes unanswered
    assert board.receive(FW3_FULL_FORWARDS) == b""
    assert mode(board) is MotorMode.COAST
    assert board.supply_current() == 0.0
    booted: list[bool] = []
    board.listen(lambda: booted.append(board.powered))
    board.powered = True
    assert booted == [True]
    assert board.receive(b"\x01") == b"MCV4B:3\n"


def test_a_firmware_4_motor_board_without_power_is_silent_too() -> None:
    board = SRMotorBoardFw4Simulator("MB")
    assert board.receive(b"MOT:0:SET:1000\n") == b"ACK\n"
    assert board.supply_current() == pytest.approx(MOTOR_FULL_POWER_CURRENT)
    board.powered = False
    assert board.motors[0].drive is MotorDrive.COAST
    assert board.receive(b"*IDN?\n") == b""
    assert board.supply_current() == 0.0
    board.powered = True
    assert board.receive(b"*IDN?\n").startswith(b"Student Robotics:MCv4B:MB:")


def test_a_stalled_motor_draws_what_it_is_told() -> None:
    fw3 = SRMotorBoardFw3Simulator("MB3")
    fw3.receive(bytes([0x02, 128 + 50]))  # half power
    assert fw3.supply_current() == pytest.approx(MOTOR_FULL_POWER_CURRENT / 2)
    fw3.set_motor_current(0, 12.0)
    assert fw3.supply_current() == pytest.approx(12.0)
    fw4 = SRMotorBoardFw4Simulator("MB4")
    fw4.receive(b"MOT:1:SET:-500\n")
    fw4.set_motor_current(1, 7.0)
    assert fw4.supply_current() == pytest.approx(7.0)


def test_a_servo_board_without_power_answers_but_reports_it_and_moves_nothing() -> None:
    board = SRServoBoardFw4Simulator("SB")
    assert board.receive(b"SERVO:0:SET:1500\n") == b"ACK\n"
    assert board.pulse_widths[0] == 1500
    assert board.supply_current() == pytest.approx(SERVO_HOLDING_CURRENT)
    board.powered = False
    assert board.receive(b"*STATUS?\n") == b"1:0\n"  # watchdog failed, power not good
    assert board.receive(b"SERVO:1:SET:2000\n") == b"ACK\n"  # the setpoint is taken...
    assert board.pulse_widths == (None,) * board.SERVO_COUNT  # ...but nothing pulses
    assert board.receive(b"SERVO:V?\n") == b"0\n"
    assert board.receive(b"SERVO:I?\n") == b"0\n"
    assert board.supply_current() == 0.0
    board.powered = True
    assert board.receive(b"*STATUS?\n") == b"0:1\n"
    assert board.pulse_widths[:2] == (1500, 2000)


def test_a_firmware_2_servo_board_without_power_hangs_and_pulses_nothing() -> None:
    board = SRServoBoardFw2Simulator("SB", has_12v=True)
    assert board.pulse_widths_us == (None,) * board.SERVO_COUNT  # not initialised yet
    assert board.supply_current() == pytest.approx(SERVO_BOARD_IDLE_CURRENT)
    board.ctrl_transfer(0x00, 64, 0, 12)  # initialise
    board.ctrl_transfer(0x00, 64, 50, 0)
    assert board.pulse_widths_us[0] == 1750
    assert board.supply_current() == pytest.approx(12 * SERVO_HOLDING_CURRENT)
    board.powered = False
    assert not board.has_12v
    assert board.pulse_widths_us == (None,) * board.SERVO_COUNT
    assert board.supply_current() == 0.0
    board.powered = True
    assert board.pulse_widths_us[0] == 1750
    assert board.supply_current() == pytest.approx(12 * SERVO_HOLDING_CURRENT)


# --- the kit's wiring ---


def test_a_wired_kit_starts_with_its_fed_boards_unpowered() -> None:
    kit = SimulatedKit(wired=True)
    assert kit.wiring is not None
    motors, servo = kit.motor_boards, kit.servo_boards[0]
    assert [board.powered for board in motors] == [False, False]
    assert not servo.powered
    # The default kit's wiring: the motor boards on H0 and H1, the servo board on L0.
    assert [kit.wiring.output_feeding(board) for board in (*motors, servo)] == [0, 1, 2]
    assert kit.wiring.output_feeding(kit.sb_arduinos[0]) is None  # powered over USB
    power = kit.power_boards[0]
    switch_fw3(power, 1, True)
    assert [board.powered for board in motors] == [False, True]
    switch_fw3(power, 1, False)
    assert not motors[1].powered
    assert "H0: SRMotorBoardFw3Simulator SIMMB0" in repr(kit.wiring)


def test_a_kit_made_in_code_is_powered_until_a_robot_wires_it() -> None:
    kit = SimulatedKit()
    assert kit.wiring is None
    assert kit.motor_boards[0].powered
    wiring = kit.wire()
    assert wiring is kit.wiring is not None
    assert not kit.motor_boards[0].powered  # the outputs are off, as at power-up
    assert kit.wire() is wiring  # only once


def test_an_unwired_kit_stays_powered() -> None:
    kit = SimulatedKit(wired=False)
    assert kit.wire() is None
    assert kit.motor_boards[0].powered


def test_a_kit_without_a_power_board_is_never_wired() -> None:
    kit = SimulatedKit(KitConfig(power_boards=0, motor_boards=1), wired=True)
    assert kit.wiring is None
    assert kit.motor_boards[0].powered


def test_the_load_pulls_the_battery_down_and_shows_on_the_outputs() -> None:
    kit = SimulatedKit("sr2023", wired=True)
    power = only(kit, "sr-power-fw4", SRPowerBoardFw4Simulator)
    motor = only(kit, "sr-motor-fw4", SRMotorBoardFw4Simulator)
    idle = power.receive(b"BATT:V?\n")
    assert idle == b"12000\n"
    power.receive(b"OUT:0:SET:1\n")  # H0: the motor board
    motor.receive(b"MOT:0:SET:1000\nMOT:1:SET:-1000\n")
    load = 2 * MOTOR_FULL_POWER_CURRENT
    expected_mv = round((12.0 - load * BATTERY_INTERNAL_RESISTANCE) * 1000)
    assert power.receive(b"BATT:V?\n") == f"{expected_mv}\n".encode()
    assert power.receive(b"BATT:I?\n") == f"{round(load * 1000)}\n".encode()
    assert power.receive(b"OUT:0:I?\n") == f"{round(load * 1000)}\n".encode()
    assert power.receive(b"OUT:2:I?\n") == b"0\n"  # L0 is off
    assert power.loaded_voltage == pytest.approx(expected_mv / 1000)
    motor.receive(b"MOT:0:SET:0\nMOT:1:DISABLE\n")
    assert power.receive(b"BATT:V?\n") == idle


def test_the_firmware_3_board_reads_the_load_too() -> None:
    kit = SimulatedKit("sr2019", wired=True)
    power, motor = kit.power_boards[0], kit.motor_boards[0]
    switch_fw3(power, 0, True)
    motor.receive(FW3_FULL_FORWARDS)
    assert power.output_current(0) == pytest.approx(MOTOR_FULL_POWER_CURRENT)
    assert power.load_current == pytest.approx(MOTOR_FULL_POWER_CURRENT)
    sag = MOTOR_FULL_POWER_CURRENT * BATTERY_INTERNAL_RESISTANCE
    assert power.loaded_voltage == pytest.approx(12.0 - sag)
    reply = bytes(power.ctrl_transfer(0x80, 64, 0, 7, 8))
    current_ma = int.from_bytes(reply[:4], "little")
    voltage_mv = int.from_bytes(reply[4:], "little")
    assert voltage_mv == (12_000 - round(sag * 1000)) // 4 * 4  # the INA219's 4 mV steps
    assert current_ma == 2500
    out0 = bytes(power.ctrl_transfer(0x80, 64, 0, 0, 4))
    assert int.from_bytes(out0, "little") == 2500


def test_an_output_over_its_limit_trips_and_latches() -> None:
    kit = SimulatedKit("sr2023", wired=True)
    power = only(kit, "sr-power-fw4", SRPowerBoardFw4Simulator)
    motor = only(kit, "sr-motor-fw4", SRMotorBoardFw4Simulator)
    power.receive(b"OUT:0:SET:1\n")
    motor.set_motor_current(0, 25.0)  # a stalled motor: over H0's 20 A
    motor.receive(b"MOT:0:SET:1000\n")
    assert not power.outputs[0]
    assert power.overcurrent_latches[0]
    assert power.receive(b"*STATUS?\n").startswith(b"1,0,0,0,0,0,0:")
    assert not motor.powered  # its 12 V went with the output
    assert power.receive(b"OUT:0:SET:1\n") == b"ACK\n"  # latched: still off
    assert not power.outputs[0]
    power.receive(b"*RESET\n")
    motor.set_motor_current(0, 0)
    assert power.receive(b"OUT:0:SET:1\n") == b"ACK\n"
    assert power.outputs[0] and motor.powered


def test_the_whole_board_over_its_limit_switches_every_output_off() -> None:
    definition = KitDefinition(
        "three",
        "three motor boards",
        {"sr-power-fw4": 1, "sr-motor-fw4": 3},
        wiring={"sr-motor-fw4": ("H0", "H1", "L0")},
    )
    kit = SimulatedKit(definition, wired=True)
    power = only(kit, "sr-power-fw4", SRPowerBoardFw4Simulator)
    motors = [m for m in kit.simulators("sr-motor-fw4") if isinstance(m, SRMotorBoardFw4Simulator)]
    for output in (0, 1, 2):
        power.receive(f"OUT:{output}:SET:1\n".encode())
    for motor, amps in zip(motors, (12.0, 12.0, 9.0), strict=True):
        motor.set_motor_current(0, amps)  # each under its own output's limit...
        motor.receive(b"MOT:0:SET:1000\n")  # ...33 A in all, over the board's 30 A
    assert power.outputs == (False, False, False, False, True, False, False)
    assert not any(motor.powered for motor in motors)


def test_a_tripped_fw3_output_cuts_its_board() -> None:
    kit = SimulatedKit("sr2019", wired=True)
    power, motor = kit.power_boards[0], kit.motor_boards[0]
    switch_fw3(power, 0, True)
    assert motor.powered
    power.trip_output(0)
    assert not motor.powered
    switch_fw3(power, 0, True)  # tripped: stays off until the board is reset
    assert not motor.powered
    power.bus_reset()
    switch_fw3(power, 0, True)
    assert motor.powered
    power.power_cycle()
    assert not motor.powered


def test_unplugging_a_fw4_power_board_cuts_its_boards() -> None:
    kit = SimulatedKit("sr2023", wired=True)
    power = only(kit, "sr-power-fw4", SRPowerBoardFw4Simulator)
    motor = only(kit, "sr-motor-fw4", SRMotorBoardFw4Simulator)
    power.receive(b"OUT:0:SET:1\n")
    assert motor.powered
    power.unplug()  # the board's own safe state: every output off but the brain's
    assert not motor.powered


class _CountingPowerBoard(SRPowerBoardFw4Simulator):
    """A firmware 4 power board that counts the wiring's updates of its loads."""

    def __init__(self, serial: str) -> None:
        self.load_updates = 0
        super().__init__(serial)

    def set_supplied_current(self, output: int, amps: float) -> None:
        self.load_updates += 1
        super().set_supplied_current(output, amps)


def _reported_ma(power: SRPowerBoardFw4Simulator, output: int) -> int:
    """The current the board reports on ``output``, in mA (as the host reads it)."""
    return int(power.receive(f"OUT:{output}:I?\n".encode()))


def _counted_kit() -> tuple[_CountingPowerBoard, SRMotorBoardFw4Simulator, KitWiring]:
    power = _CountingPowerBoard("PB")
    motor = SRMotorBoardFw4Simulator("MB")
    return power, motor, KitWiring(power, [(motor, 0)])


def test_a_change_that_leaves_outputs_power_and_loads_alone_updates_nothing() -> None:
    power, motor, _ = _counted_kit()
    power.receive(b"OUT:0:SET:1\n")
    assert motor.powered
    power.load_updates = 0
    power.receive(b"BATT:V?\n")  # readings: nothing the wiring follows changes
    motor.receive(b"*IDN?\n")
    motor.receive(b"MOT:0:SET:0\n")  # a motor at 0 draws nothing more
    assert power.load_updates == 0


def test_each_change_of_an_output_or_a_load_updates_the_wiring() -> None:
    power, motor, wiring = _counted_kit()
    power.receive(b"OUT:0:SET:1\n")
    power.load_updates = 0
    motor.receive(b"MOT:0:SET:1000\n")  # the motor draws: the load changes
    assert power.load_updates == power.OUTPUT_COUNT
    assert wiring.output_current(0) == pytest.approx(motor.supply_current())
    assert _reported_ma(power, 0) == round(motor.supply_current() * 1000)
    power.receive(b"OUT:0:SET:0\n")  # the output goes off: the board loses its power
    assert not motor.powered
    assert _reported_ma(power, 0) == 0


def test_a_motor_told_what_it_draws_loads_its_output_at_once() -> None:
    power, motor, _ = _counted_kit()
    power.receive(b"OUT:0:SET:1\n")
    motor.receive(b"MOT:0:SET:1000\n")
    motor.set_motor_current(0, 5.0)  # (a test's stalled motor)
    assert motor.supply_current() == pytest.approx(5.0 + MOTOR_BOARD_IDLE_CURRENT)
    assert _reported_ma(power, 0) == round(motor.supply_current() * 1000)
    fw3 = SRMotorBoardFw3Simulator("MB3")
    heard: list[bool] = []
    fw3.listen(lambda: heard.append(True))
    fw3.set_motor_current(0, 2.0)
    assert heard == [True]


def test_only_the_board_that_changed_is_looked_at() -> None:
    power = _CountingPowerBoard("PB")
    motors = [SRMotorBoardFw4Simulator(f"MB{i}") for i in range(2)]
    KitWiring(power, [(motors[0], 0), (motors[1], 1)])
    power.receive(b"OUT:0:SET:1\n")
    power.receive(b"OUT:1:SET:1\n")
    motors[0].receive(b"MOT:0:SET:1000\n")
    power.load_updates = 0
    motors[1].receive(b"*IDN?\n")  # the other board: unchanged
    power.receive(b"BATT:I?\n")
    assert power.load_updates == 0
    motors[1].receive(b"MOT:1:SET:-500\n")
    assert power.load_updates == power.OUTPUT_COUNT
    assert _reported_ma(power, 1) == round(motors[1].supply_current() * 1000)


def test_sync_updates_even_when_nothing_seems_changed() -> None:
    power, motor, wiring = _counted_kit()
    power.receive(b"OUT:0:SET:1\n")
    power.set_supplied_current(0, 9.0)  # set behind the wiring's back
    power.load_updates = 0
    wiring.sync()
    assert power.load_updates == power.OUTPUT_COUNT
    assert _reported_ma(power, 0) == round(motor.supply_current() * 1000)


def test_closing_the_wiring_stops_following_the_boards() -> None:
    kit = SimulatedKit(wired=True)
    assert kit.wiring is not None
    kit.wiring.close()
    switch_fw3(kit.power_boards[0], 0, True)
    assert not kit.motor_boards[0].powered


def test_every_motor_and_servo_simulator_is_power_fed() -> None:
    for board in (
        SRMotorBoardFw3Simulator("A"),
        SRMotorBoardFw4Simulator("B"),
        SRServoBoardFw2Simulator("C"),
        SRServoBoardFw4Simulator("D"),
    ):
        assert isinstance(board, PowerFed)


def test_the_default_wiring_puts_motors_on_h_and_servos_on_l_outputs() -> None:
    motors = [SRMotorBoardFw3Simulator(f"M{i}") for i in range(6)]
    servos = [SRServoBoardFw4Simulator(f"S{i}") for i in range(2)]
    assert default_outputs(motors[:2]) == [0, 1]
    assert default_outputs(servos) == [2, 3]
    assert default_outputs([*motors[:2], *servos]) == [0, 1, 2, 3]
    # Every output but the brain's feeds a board, then they are shared.
    assert default_outputs(motors) == [0, 1, 2, 3, 5, 0]
    assert default_outputs(servos, taken=[2]) == [3, 5]
    assert BRAIN_OUTPUT not in default_outputs([*motors, *servos, *motors])


def test_a_kit_definition_wires_and_numbers_its_boards() -> None:
    definition = KitDefinition(
        "ours",
        "our robot",
        {"sr-power-fw4": 1, "sr-motor-fw4": 2, "sr-servo-fw4": 1},
        wiring={"sr-motor-fw4": ("L1", 5)},
        serials={"sr-motor-fw4": ("SR0UK1L", "SR0AB12"), "sr-power-fw4": ("SRPB1",)},
    )
    kit = SimulatedKit(definition, wired=True)
    motors = kit.simulators("sr-motor-fw4")
    assert [getattr(m, "serial_number", None) for m in motors] == ["SR0UK1L", "SR0AB12"]
    assert kit.wiring is not None
    assert [kit.wiring.output_feeding(m) for m in motors] == [3, 5]
    # The servo board, not wired by the definition, gets the first free L output.
    assert kit.wiring.output_feeding(kit.simulators("sr-servo-fw4")[0]) == 2


def test_wiring_to_an_output_the_power_board_lacks_is_an_error() -> None:
    definition = KitDefinition(
        "five-volt",
        "a motor board on the 5 V rail of a fw 3 board",
        {"sr-power": 1, "sr-motor": 1},
        wiring={"sr-motor": ("5V",)},
    )
    with pytest.raises(ValueError, match="no output '5V'"):
        SimulatedKit(definition, wired=True)


def test_kit_wiring_checks_its_outputs() -> None:
    power = SRPowerBoardFw3Simulator("PB")
    motor = SRMotorBoardFw3Simulator("MB")
    with pytest.raises(ValueError, match="does not have"):
        KitWiring(power, [(motor, 6)])
    with pytest.raises(ValueError, match="L2"):
        KitWiring(power, [(motor, BRAIN_OUTPUT)])
    wiring = KitWiring(power, [(motor, 0)])
    assert wiring.power_board == power
    assert wiring.feeds == ((motor, 0),)
    assert wiring.output_current(0) == 0.0


def test_two_boards_with_one_serial_number_are_an_error() -> None:
    definition = KitDefinition(
        "twins",
        "a given serial number that another board makes",
        {"sr-motor-fw4": 1, "sr-servo-fw4": 1},
        serials={"sr-motor-fw4": ("SIMSB0",)},
    )
    with pytest.raises(ValueError, match="serial number 'SIMSB0'"):
        SimulatedKit(definition)
