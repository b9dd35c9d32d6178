from __future__ import annotations

import threading
from collections.abc import Iterator

import anyio
import anyio.lowlevel
import pytest

from j5aio.backends.console import Console
from j5aio.backends.console.stdin import read_stdin_line

from .console_script import Terminal


def console(terminal: Terminal) -> Console:
    return Console("Board(SERIAL)", terminal.print, terminal.input)


async def test_info_prefixes_the_descriptor() -> None:
    terminal = Terminal()
    shown = console(terminal)
    await shown.info("Setting motor 0 to 0.5.")
    assert terminal.lines == ["Board(SERIAL): Setting motor 0 to 0.5."]
    assert shown.descriptor == "Board(SERIAL)"
    assert repr(shown) == "Console('Board(SERIAL)')"


async def test_read_str_by_default() -> None:
    terminal = Terminal(["hello there"])
    assert await console(terminal).read("Say something") == "hello there"
    assert terminal.prompts == ["Board(SERIAL): Say something: "]


@pytest.mark.parametrize(
    ("return_type", "answer", "expected"),
    [(float, "1.5", 1.5), (int, "42", 42), (str, " x ", " x "), (float, " -2 ", -2.0)],
)
async def test_read_converts(return_type: type, answer: str, expected: object) -> None:
    terminal = Terminal([answer])
    result = await console(terminal).read("Value", return_type)
    assert result == expected
    assert type(result) is return_type


@pytest.mark.parametrize(
    ("answer", "expected"),
    [("true", True), ("YES", True), (" True ", True), ("false", False), ("No", False)],
)
async def test_read_bool(answer: str, expected: bool) -> None:
    terminal = Terminal([answer])
    assert await console(terminal).read("Pressed [true/false]", bool) is expected


async def test_bad_answers_are_reported_and_asked_again() -> None:
    terminal = Terminal(["twelve", "", "12.5"])
    assert await console(terminal).read("Battery voltage [volts]", float) == 12.5
    assert terminal.lines == [
        "Board(SERIAL): Battery voltage [volts]: ",
        "Board(SERIAL): Unable to construct a float from 'twelve'",
        "Board(SERIAL): Battery voltage [volts]: ",
        "Board(SERIAL): Unable to construct a float from ''",
        "Board(SERIAL): Battery voltage [volts]: ",
    ]


async def test_bad_bool_answer_is_asked_again() -> None:
    terminal = Terminal(["1", "y", "no"])
    assert await console(terminal).read("Pressed", bool) is False
    assert terminal.lines.count("Board(SERIAL): Unable to construct a bool from '1'") == 1
    assert terminal.lines.count("Board(SERIAL): Unable to construct a bool from 'y'") == 1
    assert len(terminal.prompts) == 3


async def test_return_type_none_waits_for_return_whatever_is_typed() -> None:
    terminal = Terminal(["anything"])
    await console(terminal).read("Hit return to press start button", None)
    assert not terminal.answers
    assert terminal.prompts == ["Board(SERIAL): Hit return to press start button: "]


async def test_end_of_input_is_a_clear_error() -> None:
    terminal = Terminal(["nope"])
    with pytest.raises(EOFError, match=r"ran out of input while asking for 'Voltage'"):
        await console(terminal).read("Voltage", float)
    assert len(terminal.prompts) == 2  # asked again once, then the input ended


async def test_sync_input_function_runs_in_a_worker_thread() -> None:
    threads: list[threading.Thread] = []

    def blocking_input(prompt: str) -> str:
        threads.append(threading.current_thread())
        return "3"

    shown = Console("B(S)", print, blocking_input)
    assert await shown.read("n", int) == 3
    assert threads and threads[0] is not threading.main_thread()


async def test_sync_input_raising_eof_is_reported() -> None:
    def empty_input(prompt: str) -> str:
        raise EOFError

    with pytest.raises(EOFError, match="ran out of input"):
        await Console("B(S)", print, empty_input).read("x")


async def test_input_function_must_return_text() -> None:
    async def bad_input(prompt: str) -> str:
        return 5  # type: ignore[return-value]

    with pytest.raises(TypeError, match="must return a str"):
        await Console("B(S)", print, bad_input).read("x")


async def test_async_print_function_is_awaited() -> None:
    shown: list[str] = []

    async def slow_print(line: str) -> None:
        await anyio.lowlevel.checkpoint()
        shown.append(line)

    await Console("B(S)", slow_print).info("hi")
    assert shown == ["B(S): hi"]


@pytest.fixture
def swapped_defaults() -> Iterator[Terminal]:
    terminal = Terminal()
    saved = Console.default_print_function, Console.default_input_function
    Console.default_print_function = terminal.print
    Console.default_input_function = terminal.input
    try:
        yield terminal
    finally:
        Console.default_print_function, Console.default_input_function = saved


async def test_class_level_defaults_can_be_swapped(swapped_defaults: Terminal) -> None:
    swapped_defaults.answer("7")
    shown = Console("B(S)")
    await shown.info("hello")
    assert await shown.read("n", int) == 7
    assert swapped_defaults.lines == ["B(S): hello", "B(S): n: "]


def test_the_defaults_are_print_and_the_stdin_reader() -> None:
    assert Console.default_print_function is print
    assert Console.default_input_function is read_stdin_line


async def test_other_tasks_keep_running_while_a_prompt_waits() -> None:
    release = threading.Event()

    def slow_user(prompt: str) -> str:
        release.wait(5)
        return "1.0"

    ticks = 0

    async def ticker() -> None:
        nonlocal ticks
        while True:
            ticks += 1
            await anyio.sleep(0.01)

    shown = Console("B(S)", print, slow_user)
    async with anyio.create_task_group() as tasks:
        tasks.start_soon(ticker)
        with anyio.fail_after(5):
            async with anyio.create_task_group() as reading:
                reading.start_soon(shown.read, "x", float)
                await anyio.sleep(0.2)
                ticks_while_waiting = ticks
                release.set()
        tasks.cancel_scope.cancel()
    assert ticks_while_waiting >= 5


async def test_a_waiting_prompt_can_be_cancelled() -> None:
    never = anyio.Event()

    async def silent_user(prompt: str) -> str:
        await never.wait()
        return ""

    with anyio.move_on_after(0.05) as scope:
        await Console("B(S)", print, silent_user).read("x")
    assert scope.cancelled_caught


async def test_a_blocking_prompt_can_be_cancelled() -> None:
    release = threading.Event()

    def blocked_user(prompt: str) -> str:
        release.wait(5)
        return ""

    try:
        with anyio.move_on_after(0.05) as scope:
            await Console("B(S)", print, blocked_user).read("x")
        assert scope.cancelled_caught
    finally:
        release.set()


async def test_callable_object_with_async_call_is_awaited() -> None:
    class AsyncUser:
        async def __call__(self, prompt: str) -> str:
            return "4"

    assert await Console("B(S)", print, AsyncUser()).read("n", int) == 4
