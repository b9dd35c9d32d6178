"""A scripted user for console backends: answers their prompts and keeps what they print.

A console backend asks its user for readings through a
:class:`~j5aio.backends.console.console.Console`. In a test, :class:`ConsoleScript` plays that
user: queue the answers, hand :meth:`ConsoleScript.console_class` to the backend, and read
back what it printed (:attr:`ConsoleScript.printed`) and asked
(:attr:`ConsoleScript.prompts`)::

    script = ConsoleScript()
    backend = SRV4PowerBoardConsoleBackend("SERIAL", console_class=script.console_class())
    script.answer("Battery voltage", "12.5")
    assert await backend.get_battery_sensor_voltage(0) == 12.5
    assert script.prompts == ["PowerBoard(SERIAL): Battery voltage [volts]: "]

A prompt with no matching answer waits until one is queued (so a test can answer a
prompt that is already showing, such as "press the start button"), and is cancellable
like any other wait.

In a conformance suite (:mod:`j5aio.testing.conformance`) the script gives a console
backend's subject its hooks: ``traffic=script.traffic`` (a refused call prints and asks
nothing); an ``observe`` hook that reads the state the backend last printed from
:attr:`ConsoleScript.printed`; and ``set_...`` hooks that queue the answer to the prompt
the backend will show (``script.answer("Battery voltage", "12.5", replace=True)``).
"""

from __future__ import annotations

from collections import deque

import anyio
import anyio.lowlevel

from j5aio.backends.console.console import Console

__all__ = ["ConsoleScript"]


class ConsoleScript:
    """The answers a test gives to a console backend's prompts, and the lines it printed."""

    def __init__(self) -> None:
        self._answers: deque[tuple[str, str]] = deque()
        self._queued = anyio.Event()
        #: Every line the console printed, in order.
        self.printed: list[str] = []
        #: Every prompt the console showed, in order.
        self.prompts: list[str] = []

    def answer(self, prompt_part: str, answer: str, *, replace: bool = False) -> None:
        """Queue ``answer`` for the next prompt containing ``prompt_part``.

        Answers for the same prompt are given in the order queued; ``""`` is pressing
        return.

        :param replace: first drop the answers still queued for ``prompt_part``, as when
            the answer describes how the world is now (a sensor reading).
        """
        if replace:
            self._answers = deque(item for item in self._answers if item[0] != prompt_part)
        self._answers.append((prompt_part, answer))
        self._queued.set()
        self._queued = anyio.Event()

    @property
    def unanswered(self) -> list[tuple[str, str]]:
        """The answers queued but not yet given, as (prompt part, answer)."""
        return list(self._answers)

    async def ask(self, prompt: str) -> str:
        """Show ``prompt`` and return the first queued answer that matches it.

        Waits for a matching answer if there is none yet.
        """
        self.prompts.append(prompt)
        while True:
            for index, (part, answer) in enumerate(self._answers):
                if part in prompt:
                    del self._answers[index]
                    await anyio.lowlevel.checkpoint()
                    return answer
            await self._queued.wait()

    def show(self, line: str) -> None:
        """Keep a line the console printed."""
        self.printed.append(line)

    def traffic(self) -> bytes:
        """Return every line printed and every prompt shown so far, as bytes.

        This is a console backend's ``traffic`` hook for a conformance subject
        (``Subject(..., traffic=script.traffic)``): a console backend "sends" by printing
        and asking, so the suite can check that a refused call does neither. (Printed
        lines come first, then prompts: what matters is that the bytes grow with each.)
        """
        return "".join(f"{line}\n" for line in (*self.printed, *self.prompts)).encode()

    def console_class(self) -> type[Console]:
        """A :class:`.Console` class whose consoles print to and ask this script."""
        script = self

        class ScriptedConsole(Console):
            """A console that prints to and asks a :class:`ConsoleScript`."""

            def __init__(self, descriptor: str, *_ignored: object) -> None:
                super().__init__(descriptor, script.show, script.ask)

        return ScriptedConsole
