"""ConsoleScript: plays the user of a console backend in tests."""

from __future__ import annotations

import anyio
import pytest

from j5aio.backends.console.sr.v4 import SRV4PowerBoardConsoleBackend
from j5aio.testing import ConsoleScript


async def test_answers_go_to_matching_prompts_in_order() -> None:
    script = ConsoleScript()
    script.answer("Battery voltage", "12.5")
    script.answer("Battery current", "1.5")
    script.answer("Battery voltage", "11.0")
    assert await script.ask("B: Battery current [amps]: ") == "1.5"
    assert await script.ask("B: Battery voltage [volts]: ") == "12.5"
    assert await script.ask("B: Battery voltage [volts]: ") == "11.0"
    assert script.prompts == [
        "B: Battery current [amps]: ", "B: Battery voltage [volts]: ",
        "B: Battery voltage [volts]: ",
    ]
    assert script.unanswered == []


def test_replace_drops_answers_still_queued_for_that_prompt() -> None:
    script = ConsoleScript()
    script.answer("voltage", "1")
    script.answer("current", "2")
    script.answer("voltage", "3", replace=True)
    assert script.unanswered == [("current", "2"), ("voltage", "3")]


async def test_a_prompt_waits_for_its_answer() -> None:
    script = ConsoleScript()
    got: list[str] = []

    async def ask(prompt: str) -> None:
        got.append(await script.ask(prompt))

    async with anyio.create_task_group() as group:
        group.start_soon(ask, "press start: ")
        group.start_soon(ask, "voltage: ")
        await anyio.sleep(0.01)
        assert got == []
        script.answer("voltage", "12")
        await anyio.sleep(0.01)
        assert got == ["12"]
        script.answer("unrelated", "x")
        script.answer("press", "")
    assert got == ["12", ""]
    assert script.unanswered == [("unrelated", "x")]


async def test_a_waiting_prompt_is_cancellable() -> None:
    script = ConsoleScript()
    with anyio.move_on_after(0.05) as scope:
        await script.ask("never answered: ")
    assert scope.cancelled_caught
    script.answer("never answered", "late")
    assert await script.ask("never answered: ") == "late"


async def test_console_class_drives_a_console_backend() -> None:
    script = ConsoleScript()
    backend = SRV4PowerBoardConsoleBackend("SERIAL", script.console_class())
    script.answer("Battery voltage", "12.5")
    assert await backend.get_battery_sensor_voltage(0) == 12.5
    await backend.set_led_state(1, True)
    assert script.prompts == ["PowerBoard(SERIAL): Battery voltage [volts]: "]
    assert script.printed == ["PowerBoard(SERIAL): Set LED 1 to True"]


async def test_a_bad_answer_is_reported_and_asked_again() -> None:
    script = ConsoleScript()
    backend = SRV4PowerBoardConsoleBackend("SERIAL", script.console_class())
    script.answer("Battery voltage", "lots")
    script.answer("Battery voltage", "9")
    assert await backend.get_battery_sensor_voltage(0) == 9.0
    assert len(script.prompts) == 2
    assert "Unable to construct a float from 'lots'" in script.printed[0]


@pytest.mark.parametrize("answer", ["true", "yes", "false"])
async def test_answers_are_plain_text(answer: str) -> None:
    script = ConsoleScript()
    backend = SRV4PowerBoardConsoleBackend("SERIAL", script.console_class())
    script.answer("Start button state", answer)
    assert await backend.get_button_state(0) is (answer != "false")


async def test_traffic_grows_with_every_line_printed_and_prompt_shown() -> None:
    script = ConsoleScript()
    backend = SRV4PowerBoardConsoleBackend("SERIAL", script.console_class())
    assert script.traffic() == b""
    await backend.set_led_state(0, True)
    printed = script.traffic()
    assert printed.endswith(b"\n") and b"SERIAL" in printed
    script.answer("Battery voltage", "12.5")
    await backend.get_battery_sensor_voltage(0)
    assert script.traffic().startswith(printed)
    assert script.traffic().endswith(b"Battery voltage [volts]: \n")
    with pytest.raises(ValueError):
        await backend.set_led_state(7, True)  # refused: nothing printed or asked
    assert script.traffic() == printed + b"PowerBoard(SERIAL): Battery voltage [volts]: \n"
