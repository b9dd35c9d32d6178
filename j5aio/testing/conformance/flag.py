"""The conformance suite of :class:`~j5aio.components.flag.FlagInterface`."""

from __future__ import annotations

from collections.abc import Awaitable, Callable
from dataclasses import dataclass

from j5aio.components.flag import FlagInterface

from ._base import InterfaceConformance, Subject, require

__all__ = ["FlagInterfaceConformance", "FlagSubject"]


@dataclass(kw_only=True)
class FlagSubject(Subject):
    """A backend implementing :class:`~j5aio.components.flag.FlagInterface`.

    :param set_flag: raises (``True``) or lowers flag ``identifier`` on the board.
    """

    backend: FlagInterface
    set_flag: Callable[[int, bool], Awaitable[None]] | None = None


class FlagInterfaceConformance(InterfaceConformance[FlagSubject]):
    """What every implementation of :class:`~j5aio.components.flag.FlagInterface` must do.

    * each flag reads as a bool that follows the board, independently of the others;
    * an identifier the board does not have is refused, sending nothing.
    """

    async def test_flags_follow_the_board(self, subject: FlagSubject) -> None:
        """Each flag reads as the board raises and lowers it, the others unchanged."""
        set_flag = require(subject.set_flag, "set_flag")
        with self.bounded():
            for identifier in subject.identifiers:
                await set_flag(identifier, False)
            await self.assert_each_alone(
                subject.identifiers, set_flag, subject.backend.get_flag_state,
                lambda raised, other, got: (
                    f"flag {other} reads {got!r} with only flag {raised} raised"
                ),
            )

    async def test_out_of_range_identifier_raises(self, subject: FlagSubject) -> None:
        """A flag the board does not have is refused."""
        await self.assert_refused(subject, subject.backend.get_flag_state)
