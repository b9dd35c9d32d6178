from __future__ import annotations

from datetime import timedelta

import pytest

from j5aio.backends.console.sr.v4 import (
    SRV4MotorBoardConsoleBackend,
    SRV4MotorBoardFw4ConsoleBackend,
    SRV4PowerBoardFw4ConsoleBackend,
)
from j5aio.boards.sr.v4 import MotorBoardFw4, PowerBoardFw4, PowerBoardOutput
from j5aio.components import MotorSpecialState
from j5aio.components.flashing_led import LEDMode
from j5aio.errors import NotSupportedByHardwareError

from .console_script import Terminal


def power_board(terminal: Terminal) -> PowerBoardFw4:
    return PowerBoardFw4(
        "SERIAL", SRV4PowerBoardFw4ConsoleBackend("SERIAL", terminal.console_class()),
    )


async def test_power_outputs_and_the_brain() -> None:
    terminal = Terminal()
    board = power_board(terminal)
    assert await board.outputs[PowerBoardOutput.L2].get_is_enabled() is True
    with pytest.raises(NotSupportedByHardwareError, match="L2"):
        await board.outputs[PowerBoardOutput.L2].set_is_enabled(False)
    await board.outputs[PowerBoardOutput.FIVE_VOLT].set_is_enabled(True)
    await board.outputs.power_off()
    assert terminal.lines[0] == "PowerBoardFw4(SERIAL): Setting output 6 to True"
    assert "Setting output 4" not in "\n".join(terminal.lines)
    assert len(terminal.lines) == 7


async def test_power_leds_reset_and_readings() -> None:
    terminal = Terminal(["true", "41.5", "no", "5.02"])
    board = power_board(terminal)
    await board.run_led.set_mode(LEDMode.FLASH)
    assert await board.run_led.get_mode() is LEDMode.FLASH
    assert await board.run_led.get_state() is True
    await board.error_led.set_state(True)
    assert await board.error_led.get_mode() is LEDMode.ON
    assert await board.outputs[1].get_is_overcurrent() is True  # type: ignore[attr-defined]
    assert await board.temperature_sensor.get_temperature() == 41.5
    assert await board.fan.get_is_running() is False
    assert await board.regulator_sensor.get_voltage() == 5.02
    await board.outputs[0].set_is_enabled(True)
    await board.make_safe()
    assert await board.outputs[0].get_is_enabled() is False
    assert await board.outputs[4].get_is_enabled() is True
    assert await board.run_led.get_mode() is LEDMode.OFF
    assert "PowerBoardFw4(SERIAL): Set LED 0 to FLASH" in terminal.lines
    assert terminal.lines[-1].startswith("PowerBoardFw4(SERIAL): Resetting the board")


async def test_power_buzzer_limits() -> None:
    terminal = Terminal()
    board = power_board(terminal)
    await board.piezo.buzz(0.25, 440)
    assert terminal.lines == ["PowerBoardFw4(SERIAL): Buzzing at 440.0Hz for 250ms"]
    with pytest.raises(NotSupportedByHardwareError, match="8 to 10000"):
        await board.piezo.buzz(0.25, 5)
    with pytest.raises(NotSupportedByHardwareError, match="1 ms"):
        await board.piezo.buzz(0.0001, 440)
    backend = board.backend
    assert isinstance(backend, SRV4PowerBoardFw4ConsoleBackend)
    with pytest.raises(ValueError, match="invalid piezo identifier"):
        await backend.buzz(1, timedelta(seconds=1), 1)
    with pytest.raises(ValueError, match="invalid power output identifier"):
        await backend.get_power_output_overcurrent(7)
    assert len(terminal.lines) == 1


async def test_fw4_motor_board_prints_the_duty() -> None:
    terminal = Terminal(["1.5", "yes", "11.9"])
    backend = SRV4MotorBoardFw4ConsoleBackend("SERIAL", terminal.console_class())
    board = MotorBoardFw4("SERIAL", backend)
    await board.motors[0].set_power(0.1234)
    await board.motors[1].set_power(-1)
    await board.motors[1].set_power(0.0)
    await board.motors[0].set_power(MotorSpecialState.COAST)
    assert terminal.lines == [
        "MotorBoardFw4(SERIAL): Setting motor 0 to 0.1234.",
        "MotorBoardFw4(SERIAL): Motor 0: forward at 12.3% duty.",
        "MotorBoardFw4(SERIAL): Setting motor 1 to -1.0.",
        "MotorBoardFw4(SERIAL): Motor 1: reverse at 100.0% duty.",
        "MotorBoardFw4(SERIAL): Setting motor 1 to 0.0.",
        "MotorBoardFw4(SERIAL): Motor 1: brake.",
        "MotorBoardFw4(SERIAL): Setting motor 0 to COAST.",
    ]
    assert await board.motors[0].get_current() == 1.5
    assert await board.motors[1].get_has_fault() is True
    assert await board.input_voltage_sensor.get_voltage() == 11.9
    with pytest.raises(ValueError, match="invalid motor identifier"):
        await backend.get_motor_current(2)
    with pytest.raises(ValueError, match="invalid motor identifier"):
        await backend.get_motor_fault(2)
    with pytest.raises(ValueError, match="invalid voltage sensor identifier"):
        await backend.get_voltage_sensor_voltage(1)


@pytest.mark.parametrize(
    ("power", "shown"),
    [(0.5, "forward at 50% duty"), (0.8, "forward at 80% duty"), (0.9, "forward at 90% duty"),
     (1.0, "forward at 100% duty"), (-0.25, "reverse at 25% duty"),
     (MotorSpecialState.BRAKE, "brake"), (MotorSpecialState.COAST, "coast")],
)
def test_fw3_console_shows_the_linear_duty(power: float | MotorSpecialState, shown: str) -> None:
    assert SRV4MotorBoardConsoleBackend.describe_drive(power) == shown


def test_fw4_describe_special_states() -> None:
    assert SRV4MotorBoardFw4ConsoleBackend.describe_drive(MotorSpecialState.BRAKE) == "brake"
    assert SRV4MotorBoardFw4ConsoleBackend.describe_drive(MotorSpecialState.COAST) == "coast"
