from __future__ import annotations

import errno
import struct

import pytest
import usb.core

from j5aio.simulator import PiezoNote, SRPowerBoardFw3Simulator

from .usb_helpers import READ, REQUEST, WRITE, read, read_u32, write

VERSION = 9
BUTTON = 8
BATTERY = 7
RAIL_5V = 6
RUN_LED = 6
ERROR_LED = 7
PIEZO = 8


def notes(*samples: tuple[int, int]) -> bytes:
    return b"".join(struct.pack("<HH", frequency, ms) for frequency, ms in samples)


@pytest.fixture
def board() -> SRPowerBoardFw3Simulator:
    return SRPowerBoardFw3Simulator("srABC")


def assert_stalls(board: SRPowerBoardFw3Simulator, *args: object) -> None:
    with pytest.raises(usb.core.USBError) as raised:
        board.ctrl_transfer(*args)  # type: ignore[arg-type]
    assert raised.value.errno == errno.EPIPE
    assert raised.value.backend_error_code == -9


# --- discovery ---


def test_usb_identity(board: SRPowerBoardFw3Simulator) -> None:
    assert (board.idVendor, board.idProduct, board.bcdDevice) == (0x1BDA, 0x0010, 0x0403)
    assert board.manufacturer == "Student Robotics"
    assert board.product == "Power board v4"
    assert board.serial_number == "srABC"
    assert SRPowerBoardFw3Simulator(None).serial_number is None


def test_exactly_one_interface_for_legacy_detection(board: SRPowerBoardFw3Simulator) -> None:
    assert len(board.get_active_configuration().interfaces()) == 1
    assert len(board[0].interfaces()) == 1
    assert len(next(iter(board)).interfaces()) == 1
    assert board.get_active_configuration()[(0, 0)].bInterfaceClass == 0xFE


# --- reads ---


def test_version_is_3(board: SRPowerBoardFw3Simulator) -> None:
    assert read(board, VERSION, 4) == b"\x03\x00\x00\x00"
    assert board.version == 3


def test_a_longer_wlength_gets_the_reply_size(board: SRPowerBoardFw3Simulator) -> None:
    assert read(board, VERSION, 64) == b"\x03\x00\x00\x00"


@pytest.mark.parametrize(("index", "size"), [(0, 4), (5, 4), (6, 4), (7, 8), (8, 4), (9, 4)])
def test_a_short_wlength_stalls(board: SRPowerBoardFw3Simulator, index: int, size: int) -> None:
    assert_stalls(board, READ, REQUEST, 0, index, size - 1)
    assert len(read(board, index, size)) == size


@pytest.mark.parametrize("index", [10, 11, 64, 0xFFFF])
def test_unknown_read_stalls(board: SRPowerBoardFw3Simulator, index: int) -> None:
    assert_stalls(board, READ, REQUEST, 0, index, 8)


@pytest.mark.parametrize(
    ("request_type", "b_request"),
    [(0x80, 63), (0x80, 0), (0xC0, 64), (0x81, 64), (0xC1, 64), (0x40, 64), (0x01, 64)],
)
def test_only_standard_device_request_64_is_answered(
    board: SRPowerBoardFw3Simulator, request_type: int, b_request: int
) -> None:
    assert_stalls(board, request_type, b_request, 0, VERSION, 4)


def test_output_currents_in_milliamps(board: SRPowerBoardFw3Simulator) -> None:
    board.set_output_current(0, 1.5)
    board.set_output_current(5, 0.25)
    assert read_u32(board, 0) == 1500
    assert read_u32(board, 5) == 250
    assert read_u32(board, 3) == 0
    assert board.output_current(0) == 1.5


def test_battery_reads_current_then_voltage(board: SRPowerBoardFw3Simulator) -> None:
    board.battery_voltage = 12.3
    board.battery_current = 1.5
    assert struct.unpack("<II", read(board, BATTERY, 8)) == (1500, 12300)
    assert board.battery_voltage_mv == 12300
    assert board.battery_current_ma == 1500
    assert board.battery_voltage == 12.3
    assert board.battery_current == 1.5


def test_battery_readings_are_quantised_like_the_sensor(board: SRPowerBoardFw3Simulator) -> None:
    board.battery_voltage = 12.345  # 4 mV bus-voltage steps
    board.battery_current = 1.234  # 20 mA shunt steps
    assert struct.unpack("<II", read(board, BATTERY, 8)) == (1220, 12344)
    board.battery_voltage = 40.0  # beyond the INA219's 32 V range
    assert struct.unpack("<II", read(board, BATTERY, 8))[1] == 32764


@pytest.mark.parametrize(("amps", "reported"), [(-0.5, 1), (-0.001, 1), (0.0, 0), (0.019, 0)])
def test_battery_current_below_the_offset_reads_1ma(
    board: SRPowerBoardFw3Simulator, amps: float, reported: int
) -> None:
    board.battery_current = amps
    assert struct.unpack("<II", read(board, BATTERY, 8))[0] == reported


def test_start_button_is_a_level_not_a_latch(board: SRPowerBoardFw3Simulator) -> None:
    assert read_u32(board, BUTTON) == 0
    board.press_start()
    assert board.start_button_pressed
    assert read_u32(board, BUTTON) == 1
    assert read_u32(board, BUTTON) == 1
    board.release_start()
    assert read_u32(board, BUTTON) == 0
    board.press_start()
    board.release_start()  # a press between two polls is missed
    assert read_u32(board, BUTTON) == 0


def test_external_start_button(board: SRPowerBoardFw3Simulator) -> None:
    board.press_start(external=True)
    assert read_u32(board, BUTTON) == 1
    board.release_start()  # the internal one was not held
    assert read_u32(board, BUTTON) == 1
    board.release_start(external=True)
    assert read_u32(board, BUTTON) == 0


def test_a_button_change_or_a_pulled_cable_rings_the_doorbells(
    board: SRPowerBoardFw3Simulator,
) -> None:
    rings: list[tuple[str, bool]] = []
    stop = board.add_doorbell(lambda: rings.append(("first", board.start_button_pressed)))
    board.add_doorbell(lambda: rings.append(("second", board.start_button_pressed)))
    board.press_start()
    board.release_start(external=True)
    write(board, 0, 1)  # the host's own transfers ring nothing
    read_u32(board, BUTTON)
    # Each ring comes after the change, so a read it causes sees the change.
    assert rings == [("first", True), ("second", True), ("first", True), ("second", True)]
    stop()
    stop()  # stopping twice is harmless
    rings.clear()
    board.release_start()
    board.unplug()
    assert rings == [("second", False), ("second", False)]


def test_5v_rail_returns_whatever_the_buffer_holds(board: SRPowerBoardFw3Simulator) -> None:
    assert read(board, RAIL_5V, 4) == bytes(4)
    read(board, VERSION, 4)
    assert read(board, RAIL_5V, 4) == b"\x03\x00\x00\x00"
    write(board, PIEZO, 0, notes((440, 100)))
    assert read(board, RAIL_5V, 4) == notes((440, 100))


# --- writes ---


def test_outputs_switch(board: SRPowerBoardFw3Simulator) -> None:
    assert board.outputs == (False,) * 6
    assert write(board, 0, 1) == 0
    write(board, 4, 1)
    assert board.outputs == (True, False, False, False, True, False)
    write(board, 4, 0)
    write(board, 5, 0x0100)  # any non-zero value is "on"
    assert board.outputs == (True, False, False, False, False, True)


def test_make_safe_traffic_switches_everything_off(board: SRPowerBoardFw3Simulator) -> None:
    for output in range(6):
        write(board, output, 1)
    for output in range(6):
        write(board, output, 0)
    assert board.outputs == (False,) * 6


def test_leds(board: SRPowerBoardFw3Simulator) -> None:
    assert (board.run_led, board.error_led) == (True, False)  # enumerated
    write(board, RUN_LED, 0)
    write(board, ERROR_LED, 1)
    assert (board.run_led, board.error_led) == (False, True)
    write(board, RUN_LED, 1)
    write(board, ERROR_LED, 0)
    assert (board.run_led, board.error_led) == (True, False)


@pytest.mark.parametrize("index", [9, 10, 0xFFFF])
def test_unknown_write_stalls(board: SRPowerBoardFw3Simulator, index: int) -> None:
    assert_stalls(board, WRITE, REQUEST, 1, index, None)


def test_data_stage_longer_than_the_buffer_stalls(board: SRPowerBoardFw3Simulator) -> None:
    assert_stalls(board, WRITE, REQUEST, 1, 0, bytes(129))
    assert board.outputs[0] is False
    assert write(board, 0, 1, bytes(128)) == 128
    assert board.outputs[0] is True


def test_a_tripped_output_ignores_on(board: SRPowerBoardFw3Simulator) -> None:
    write(board, 2, 1)
    board.trip_output(2)
    assert board.outputs[2] is False
    assert board.trips == (False, False, True, False, False, False)
    write(board, 2, 1)
    assert board.outputs[2] is False
    write(board, 2, 0)
    board.bus_reset()
    assert board.trips == (False,) * 6
    write(board, 2, 1)
    assert board.outputs[2] is True


def test_a_flat_battery_at_boot_keeps_the_drivers_off(board: SRPowerBoardFw3Simulator) -> None:
    board.battery_voltage = 10.2
    board.power_cycle()
    assert not board.output_drivers_ready
    write(board, 0, 1)
    assert board.outputs[0] is False
    board.battery_voltage = 12.0  # charging now does not start them
    write(board, 0, 1)
    assert board.outputs[0] is False
    board.power_cycle()
    assert board.output_drivers_ready
    write(board, 0, 1)
    assert board.outputs[0] is True


def test_constructor_battery() -> None:
    flat = SRPowerBoardFw3Simulator("x", battery_voltage=9.0, battery_current=0.5)
    assert not flat.output_drivers_ready
    assert flat.battery_current_ma == 500


# --- piezo ---


def test_piezo_queues_notes(board: SRPowerBoardFw3Simulator) -> None:
    assert write(board, PIEZO, 0, notes((1760, 100))) == 4
    write(board, PIEZO, 0, notes((440, 50), (0, 20)))
    assert board.note_queue == [(1760, 100), (440, 50), (0, 20)]
    assert board.note_queue[0] == PiezoNote(frequency=1760, duration_ms=100)


def test_piezo_payload_forms(board: SRPowerBoardFw3Simulator) -> None:
    board.ctrl_transfer(WRITE, REQUEST, 0, PIEZO, list(notes((262, 10))))
    assert board.note_queue == [(262, 10)]


def test_wvalue_of_a_piezo_write_is_ignored(board: SRPowerBoardFw3Simulator) -> None:
    write(board, PIEZO, 1234, notes((300, 10)))
    assert board.note_queue == [(300, 10)]


@pytest.mark.parametrize("payload", [None, b"", b"\x01\x02\x03", b"\x01\x02\x03\x04\x05"])
def test_bad_piezo_payload_stalls(board: SRPowerBoardFw3Simulator, payload: bytes | None) -> None:
    assert_stalls(board, WRITE, REQUEST, 0, PIEZO, payload)
    assert board.note_queue == []


def test_the_32nd_queued_note_stalls(board: SRPowerBoardFw3Simulator) -> None:
    for _ in range(31):
        write(board, PIEZO, 0, notes((440, 100)))
    assert len(board.note_queue) == board.NOTE_QUEUE_CAPACITY == 31
    assert_stalls(board, WRITE, REQUEST, 0, PIEZO, notes((440, 100)))
    assert len(board.note_queue) == 31


def test_a_write_of_more_notes_than_fit_stalls_whole(board: SRPowerBoardFw3Simulator) -> None:
    write(board, PIEZO, 0, notes(*[(440, 10)] * 30))
    assert_stalls(board, WRITE, REQUEST, 0, PIEZO, notes((1, 1), (2, 2)))
    assert len(board.note_queue) == 30
    write(board, PIEZO, 0, notes((3, 3)))
    assert len(board.note_queue) == 31


def test_playing_frees_room_in_the_queue(board: SRPowerBoardFw3Simulator) -> None:
    write(board, PIEZO, 0, notes(*[(440, 100)] * 31))
    assert board.advance_piezo(150) == [(440, 100)]
    assert len(board.note_queue) == 30  # the second note is half played
    write(board, PIEZO, 0, notes((880, 10)))
    assert_stalls(board, WRITE, REQUEST, 0, PIEZO, notes((880, 10)))
    assert board.advance_piezo(50) == [(440, 100)]


def test_advance_piezo_plays_notes_back_to_back(board: SRPowerBoardFw3Simulator) -> None:
    write(board, PIEZO, 0, notes((440, 100), (0, 50), (20000, 10), (523, 0)))
    assert board.advance_piezo(0) == []
    assert board.advance_piezo(99) == []
    assert board.advance_piezo(1) == [(440, 100)]
    finished = board.advance_piezo(1000)
    assert finished == [(0, 50), (20000, 10), (523, 0)]
    assert [note.played_frequency for note in finished] == [0, 10000, 523]
    assert board.note_queue == []
    with pytest.raises(ValueError):
        board.advance_piezo(-1)


def test_a_zero_length_note_finishes_at_once(board: SRPowerBoardFw3Simulator) -> None:
    write(board, PIEZO, 0, notes((440, 0)))
    assert board.advance_piezo(0) == [(440, 0)]


# --- resets, plugging ---


def test_bus_reset(board: SRPowerBoardFw3Simulator) -> None:
    write(board, 1, 1)
    write(board, RUN_LED, 0)
    write(board, PIEZO, 0, notes((440, 100)))
    board.bus_reset()
    assert board.outputs == (False,) * 6
    assert board.note_queue == []
    assert (board.run_led, board.error_led) == (True, False)


def test_unplugged_transfers_raise_enodev(board: SRPowerBoardFw3Simulator) -> None:
    write(board, 0, 1)
    board.unplug()
    assert not board.connected
    for args in ((READ, REQUEST, 0, VERSION, 4), (WRITE, REQUEST, 1, 0, None)):
        with pytest.raises(usb.core.USBError) as raised:
            board.ctrl_transfer(*args)
        assert raised.value.errno == errno.ENODEV
        assert raised.value.backend_error_code == -4
    assert board.outputs[0] is True  # fw 3 has no suspend handler


def test_plugging_in_resets_and_enumerates(board: SRPowerBoardFw3Simulator) -> None:
    write(board, 0, 1)
    board.trip_output(3)
    write(board, PIEZO, 0, notes((440, 100)))
    board.unplug()
    board.plug()
    assert board.connected
    assert board.outputs == (False,) * 6
    assert board.trips == (False,) * 6
    assert board.note_queue == []
    assert (board.run_led, board.error_led) == (True, False)
    assert read_u32(board, VERSION) == 3
    board.plug()  # already plugged in: no reset
    write(board, 0, 1)
    board.plug()
    assert board.outputs[0] is True


def test_power_cycle_while_unplugged_leaves_the_error_led_on(
    board: SRPowerBoardFw3Simulator,
) -> None:
    board.unplug()
    board.power_cycle()
    assert (board.run_led, board.error_led) == (True, True)
    board.plug()
    assert (board.run_led, board.error_led) == (True, False)


def test_outside_control_is_checked(board: SRPowerBoardFw3Simulator) -> None:
    with pytest.raises(IndexError):
        board.trip_output(6)
    with pytest.raises(IndexError):
        board.set_output_current(-1, 1.0)
    with pytest.raises(IndexError):
        board.output_current(6)
    with pytest.raises(ValueError):
        board.set_output_current(0, -1.0)
    with pytest.raises(ValueError):
        board.battery_voltage = -1.0


def test_j5_construction_traffic(board: SRPowerBoardFw3Simulator) -> None:
    # j5 reads the serial at discovery, then only the version.
    assert board.serial_number == "srABC"
    assert read_u32(board, VERSION) == 3
    # buzz(0.1 s, 1760 Hz) then wait_for_start_flash: poll, toggle RUN LED, press.
    write(board, PIEZO, 0, notes((1760, 100)))
    assert read_u32(board, BUTTON) == 0
    write(board, RUN_LED, 0)
    board.press_start()
    assert read_u32(board, BUTTON) == 1
    write(board, RUN_LED, 1)
    assert board.run_led
