"""The request tables of the protocol pages (docs/internals/) say what the codecs send.

Each named ``list-table`` of those pages is read row by row and the codec is asked for the
same thing: a page and a codec that disagree fail here. A named table with no check below
fails too, so that no table is taken for checked when it is not.
"""

from __future__ import annotations

import re
from collections.abc import Callable
from pathlib import Path

import pytest

from j5aio.backends.hardware.sb import arduino_2019_codec, arduino_2024_codec
from j5aio.backends.hardware.sr.kch import KCH_PINS, START_PIN
from j5aio.backends.hardware.sr.v4 import (
    motor_fw3_codec,
    motor_fw4_codec,
    power_fw3_codec,
    power_fw4_codec,
    ruggeduino_fw1_codec,
    servo_fw4_codec,
)
from j5aio.components.flashing_led import LEDMode
from j5aio.components.gpio_pin import GPIOPinMode
from j5aio.components.motor import MotorSpecialState, MotorState
from j5aio.errors import NotSupportedByHardwareError

from .rst_tables import list_tables
from .snippets import DOCS

INTERNALS = DOCS / "internals"
Rows = list[dict[str, str]]


def line(request: str) -> bytes:
    """A request of a text protocol as sent: the table's text and a line feed."""
    return (request + "\n").encode("ascii")


def motor_state(text: str) -> MotorState:
    """A motor state as a table writes it: ``brake``, ``coast`` or a power."""
    special = {"brake": MotorSpecialState.BRAKE, "coast": MotorSpecialState.COAST}
    return special[text] if text in special else float(text)


def check_power_fw4_outputs(rows: Rows) -> None:
    assert len(rows) == power_fw4_codec.OUTPUT_COUNT
    for row in rows:
        output = int(row["Number"])
        if row["Switch it on"].startswith("refused"):
            assert output == power_fw4_codec.BRAIN_OUTPUT
            assert row["Name"] == "L2"
            with pytest.raises(NotSupportedByHardwareError):
                power_fw4_codec.encode_output_set(output, True)
        else:
            assert power_fw4_codec.encode_output_set(output, True) == line(row["Switch it on"])
        if row["Name"] == "5 V regulator":
            assert output == power_fw4_codec.FIVE_VOLT_OUTPUT


def check_power_fw3_reads(rows: Rows) -> None:
    by_index = {
        "7": power_fw3_codec.BATTERY,
        "8": power_fw3_codec.BUTTON,
        "9": power_fw3_codec.FIRMWARE_VERSION,
    }
    for row in rows:
        length = int(row["Bytes"])
        if row["wIndex"] == "0 to 5":
            outputs = range(6)
            assert len(outputs) == power_fw3_codec.OUTPUT_COUNT
            for output in outputs:
                read = power_fw3_codec.output_current_read(output)
                assert (read.index, read.length) == (output, length)
        elif row["wIndex"] == "6":  # the 5 V rail: firmware 3 does not measure it
            with pytest.raises(ValueError, match="outputs 0 to 5"):
                power_fw3_codec.output_current_read(6)
        else:
            read = by_index.pop(row["wIndex"])
            assert (read.index, read.length) == (int(row["wIndex"]), length)
    assert not by_index, f"reads of the codec missing from the table: {sorted(by_index)}"


def check_power_fw4_leds(rows: Rows) -> None:
    assert [row["Name"] for row in rows] == list(power_fw4_codec.LED_NAMES)
    for row in rows:
        led = int(row["LED"])
        for column, mode in (("Off", LEDMode.OFF), ("On", LEDMode.ON), ("Flashing", LEDMode.FLASH)):
            assert power_fw4_codec.encode_led_set(led, mode) == line(row[column])


def _percentages(text: str) -> list[int]:
    return [int(number) for number in re.findall(r"(\d+) %", text)]


def check_motor_fw3_speed_bytes(rows: Rows) -> None:
    for row in rows:
        state = motor_state(row["Power"])
        ours = motor_fw3_codec.encode_speed(state)
        j5s = motor_fw3_codec.encode_speed(state, scale=motor_fw3_codec.J5_SCALE)
        assert (ours, j5s) == (int(row["Byte (j5aio)"]), int(row["Byte (j5)"]))
        if isinstance(state, MotorSpecialState):
            assert row["Duty"] == ("braking" if state is MotorSpecialState.BRAKE else "coasting")
            continue
        # the firmware's duty: |byte - 128| %, full from 100 on
        duties = [min(abs(byte - 128), 100) for byte in (ours, j5s)]
        stated = _percentages(row["Duty"])
        assert stated == (duties[:1] if duties[0] == duties[1] else duties)


def check_motor_fw4_requests(rows: Rows) -> None:
    for row in rows:
        state = motor_state(row["State"])
        assert motor_fw4_codec.encode_set(int(row["Motor"]), state) == line(row["Request"])


def check_servo_fw4_firmwares(rows: Rows) -> None:
    assert {row["Version"] for row in rows} == set(servo_fw4_codec.FIRMWARES)
    for row in rows:
        firmware = servo_fw4_codec.FIRMWARES[row["Version"]]
        assert firmware.maker == row["Made by"]
        assert firmware.servo_count == int(row["Channels"])
        assert firmware.min_pulse == int(row["Shortest pulse (µs)"])
        assert firmware.max_pulse == int(row["Longest pulse (µs)"])


def check_ruggeduino_pin_letters(rows: Rows) -> None:
    for row in rows:
        assert ruggeduino_fw1_codec.encode_pin(int(row["Pin"])) == row["Letter"]


def check_ruggeduino_modes(rows: Rows) -> None:
    assert len(rows) == 3
    for row in rows:
        mode = GPIOPinMode[row["Mode"]]
        assert ruggeduino_fw1_codec.encode_mode(2, mode) == row["Request"].encode("ascii")


def check_sb2019_pin_requests(rows: Rows) -> None:
    for row in rows:
        mode = GPIOPinMode[row["Mode"]]
        high = {"high": True, "low": False}[row["Level"]]
        request = arduino_2019_codec.encode_pin_state(int(row["Pin"]), mode, high)
        assert request == line(row["Request"])


def check_sb2019_servo_requests(rows: Rows) -> None:
    for row in rows:
        position = None if row["Position"] == "none" else float(row["Position"])
        request = arduino_2019_codec.encode_servo(int(row["Servo"]), position)
        assert request == line(row["Request"])


def check_sb2024_mode_requests(rows: Rows) -> None:
    assert len(rows) == 3
    for row in rows:
        mode = GPIOPinMode[row["Mode"]]
        assert arduino_2024_codec.encode_mode(3, mode) == line(row["Request"])


def check_kch_pins(rows: Rows) -> None:
    assert [row["LED"] for row in rows] == ["A", "B", "C"]
    pins = tuple(tuple(int(row[colour]) for colour in ("Red", "Green", "Blue")) for row in rows)
    assert pins == KCH_PINS


def check_kch_start_pin(rows: Rows) -> None:
    assert rows == [{"LED": "START", "Pin": str(START_PIN)}]


CHECKS: dict[str, Callable[[Rows], None]] = {
    "power-fw4-outputs": check_power_fw4_outputs,
    "power-fw3-reads": check_power_fw3_reads,
    "power-fw4-leds": check_power_fw4_leds,
    "motor-fw3-speed-bytes": check_motor_fw3_speed_bytes,
    "motor-fw4-requests": check_motor_fw4_requests,
    "servo-fw4-firmwares": check_servo_fw4_firmwares,
    "ruggeduino-pin-letters": check_ruggeduino_pin_letters,
    "ruggeduino-modes": check_ruggeduino_modes,
    "sb2019-pin-requests": check_sb2019_pin_requests,
    "sb2019-servo-requests": check_sb2019_servo_requests,
    "sb2024-mode-requests": check_sb2024_mode_requests,
    "kch-pins": check_kch_pins,
    "kch-start-pin": check_kch_start_pin,
}


def named_tables() -> dict[str, Rows]:
    tables: dict[str, Rows] = {}
    for page in sorted(INTERNALS.glob("*.rst")):
        for name, rows in list_tables(page).items():
            assert name not in tables, f"two tables named {name}"
            tables[name] = rows
    return tables


TABLES = named_tables()


def test_every_named_table_is_checked_and_every_check_has_its_table() -> None:
    assert set(TABLES) == set(CHECKS)


@pytest.mark.parametrize("name", sorted(CHECKS))
def test_the_table_says_what_the_codec_does(name: str) -> None:
    CHECKS[name](TABLES[name])


def test_a_table_that_disagrees_with_its_codec_fails(tmp_path: Path) -> None:
    page = (INTERNALS / "sr-motor-board.rst").read_text(encoding="utf-8")
    wrong = page.replace("``MOT:1:SET:-500``", "``MOT:1:SET:-499``")
    assert wrong != page
    (tmp_path / "page.rst").write_text(wrong, encoding="utf-8")
    rows = list_tables(tmp_path / "page.rst")["motor-fw4-requests"]
    with pytest.raises(AssertionError):
        check_motor_fw4_requests(rows)


def test_a_row_of_the_wrong_width_is_refused(tmp_path: Path) -> None:
    (tmp_path / "page.rst").write_text(
        ".. list-table::\n   :name: t\n   :header-rows: 1\n\n"
        "   * - A\n     - B\n   * - 1\n",
        encoding="utf-8",
    )
    with pytest.raises(ValueError, match="table t has rows that do not fit its header"):
        list_tables(tmp_path / "page.rst")
