"""Console: how a console backend tells the user what happens and asks for readings."""

from __future__ import annotations

import inspect
from collections.abc import Awaitable, Callable
from typing import ClassVar, TypeVar, overload

import anyio.to_thread

from j5aio.backends.console.stdin import read_stdin_line

__all__ = ["Console", "InputFunction", "PrintFunction"]

T = TypeVar("T")

PrintFunction = Callable[[str], object]
"""Shows a line to the user: ``print``, or any function (or coroutine function) of a str."""

InputFunction = Callable[[str], str | Awaitable[str]]
"""Shows a prompt and returns the user's answer: ``input``-like, plain or a coroutine function.

A plain function runs in a worker thread, so a blocking one does not stop other tasks.
"""

_BOOLEAN_ANSWERS = {"true": True, "yes": True, "false": False, "no": False}


class Console:
    """Prints messages and asks questions on behalf of one console backend.

    Every line starts with the descriptor, e.g. ``"MotorBoard(SERIAL): "``. Reading an
    answer never blocks the event loop: other tasks run while the user types, and a
    question can be cancelled like any other wait.

    :param descriptor: the name shown before every line, usually ``Board(serial)``.
    :param print_function: shows a line; :attr:`default_print_function` if not given.
    :param input_function: shows a prompt and returns the answer;
        :attr:`default_input_function` if not given.
    """

    #: The print function of consoles made without one (``print``).
    default_print_function: ClassVar[PrintFunction] = print

    #: The input function of consoles made without one: reads standard input in a
    #: background thread.
    default_input_function: ClassVar[InputFunction] = read_stdin_line

    def __init__(
        self,
        descriptor: str,
        print_function: PrintFunction | None = None,
        input_function: InputFunction | None = None,
    ) -> None:
        self._descriptor = descriptor
        defaults = type(self)
        self._print = print_function or defaults.default_print_function
        self._input = input_function or defaults.default_input_function

    @property
    def descriptor(self) -> str:
        """The name shown before every line."""
        return self._descriptor

    async def info(self, message: str) -> None:
        """Show ``message`` to the user, as ``"<descriptor>: <message>"``."""
        shown = self._print(f"{self._descriptor}: {message}")
        if inspect.isawaitable(shown):
            await shown

    @overload
    async def read(self, prompt: str) -> str: ...

    @overload
    async def read(self, prompt: str, return_type: None) -> None: ...

    @overload
    async def read(self, prompt: str, return_type: Callable[[str], T]) -> T: ...

    async def read(
        self, prompt: str, return_type: Callable[[str], object] | None = str,
    ) -> object:
        """Ask the user for a value, until the answer can be turned into ``return_type``.

        The prompt is shown as ``"<descriptor>: <prompt>: "``. An answer that cannot be
        converted is reported and the question asked again. For ``bool``, the answers
        true, yes, false and no are accepted in any case.

        :param prompt: what to ask for, e.g. ``"Battery voltage [volts]"``.
        :param return_type: what to convert the answer with (``str``, ``float``,
            ``bool``, ...); ``None`` only waits for the user to press return.
        :returns: the converted answer, or ``None`` when ``return_type`` is ``None``.
        :raises EOFError: the input ran out before an acceptable answer came.
        """
        question = f"{self._descriptor}: {prompt}: "
        while True:
            answer = await self._ask(question, prompt)
            if return_type is None:
                return None
            try:
                return _convert(answer, return_type)
            except (TypeError, ValueError):
                type_name = getattr(return_type, "__name__", repr(return_type))
                await self.info(f"Unable to construct a {type_name} from '{answer}'")

    async def _ask(self, question: str, prompt: str) -> str:
        answer: object
        try:
            if inspect.iscoroutinefunction(self._input):
                answer = await self._input(question)
            else:
                answer = await anyio.to_thread.run_sync(
                    self._input, question, abandon_on_cancel=True,
                )
            if inspect.isawaitable(answer):
                answer = await answer
        except EOFError as exc:
            raise EOFError(
                f"{self._descriptor}: the console ran out of input while asking for "
                f"{prompt!r}. Run the program interactively, or give it one line of "
                "input for each question.",
            ) from exc
        if not isinstance(answer, str):
            raise TypeError(
                f"{self._descriptor}: the console's input function returned "
                f"{answer!r} (a {type(answer).__name__}); it must return a str",
            )
        return answer

    def __repr__(self) -> str:
        return f"Console({self._descriptor!r})"


def _convert(answer: str, return_type: Callable[[str], T]) -> T:
    if return_type is bool:
        try:
            return _BOOLEAN_ANSWERS[answer.strip().lower()]  # type: ignore[return-value]
        except KeyError:
            raise ValueError(answer) from None
    return return_type(answer)
