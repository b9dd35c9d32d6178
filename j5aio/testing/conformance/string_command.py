"""The conformance suite of the string command interface (raw commands to a board)."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import anyio

from j5aio.components.string_command import StringCommandComponentInterface

from ._base import InterfaceConformance, Subject

__all__ = ["StringCommandInterfaceConformance", "StringCommandSubject"]


@dataclass(kw_only=True)
class StringCommandSubject(Subject):
    """A backend implementing :class:`.StringCommandComponentInterface`.

    A string command has no identifier, so ``identifiers`` is not used.

    :param exchanges: commands the board understands, each with the reply it gives, or
        ``None`` where any reply will do. Give commands with different replies, so that
        the suite can tell whose reply is whose. For a console backend, whatever answers
        the prompts must answer these.
    """

    backend: StringCommandComponentInterface
    exchanges: Sequence[tuple[str, str | None]] = ()


class StringCommandInterfaceConformance(InterfaceConformance[StringCommandSubject]):
    """What every implementation of :class:`.StringCommandComponentInterface` must do.

    * each command gets a ``str`` reply: its own reply;
    * commands sent together from several tasks each get their own reply (requests are
      serialised; no reply is handed to the wrong caller).
    """

    async def test_each_command_gets_its_reply(self, subject: StringCommandSubject) -> None:
        """Commands sent one after another each get their own reply, as a str."""
        with self.bounded():
            for _ in range(2):
                for command, expected in subject.exchanges:
                    reply = await subject.backend.execute_string_command(command)
                    assert isinstance(reply, str), f"{command!r} got {reply!r}, not a str"
                    if expected is not None:
                        assert reply == expected, (
                            f"{command!r} should get {expected!r} but got {reply!r}"
                        )

    async def test_concurrent_commands_get_their_own_replies(
        self, subject: StringCommandSubject,
    ) -> None:
        """Commands sent at once from several tasks do not get each other's replies."""
        replies: dict[int, str] = {}

        async def send(index: int, command: str) -> None:
            replies[index] = await subject.backend.execute_string_command(command)

        with self.bounded():
            async with anyio.create_task_group() as group:
                for index, (command, _) in enumerate(subject.exchanges):
                    group.start_soon(send, index, command)
        for index, (command, expected) in enumerate(subject.exchanges):
            if expected is not None:
                assert replies[index] == expected, (
                    f"{command!r} should get {expected!r} but got {replies[index]!r}"
                )
