"""A scripted terminal for the console tests: answers from a list, lines into a list.

(A module with a unique name, not a conftest, so test modules can import it and mypy
sees one module of that name.)
"""

from __future__ import annotations

from collections import deque
from collections.abc import Iterable

from j5aio.backends.console import Console
from j5aio.backends.console.console import InputFunction, PrintFunction


class Terminal:
    """Records every printed line and prompt in ``lines``; answers prompts in order.

    When the answers run out, a prompt raises ``EOFError``, as ``input()`` does at the
    end of a pipe.
    """

    def __init__(self, answers: Iterable[str] = ()) -> None:
        self.answers: deque[str] = deque(answers)
        self.lines: list[str] = []
        self.prompts: list[str] = []

    def print(self, line: str) -> None:
        self.lines.append(line)

    async def input(self, prompt: str) -> str:
        self.lines.append(prompt)
        self.prompts.append(prompt)
        if not self.answers:
            raise EOFError
        return self.answers.popleft()

    def answer(self, *answers: str) -> None:
        self.answers.extend(answers)

    def console_class(self) -> type[Console]:
        """A Console class whose consoles all talk to this terminal."""
        terminal = self

        class ScriptedConsole(Console):
            def __init__(
                self,
                descriptor: str,
                print_function: PrintFunction | None = None,
                input_function: InputFunction | None = None,
            ) -> None:
                super().__init__(
                    descriptor,
                    print_function or terminal.print,
                    input_function or terminal.input,
                )

        return ScriptedConsole
