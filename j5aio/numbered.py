"""Numbered components of a board (``board.motors``): a tuple whose misses name the board.

``motor_board.motors[2]`` on a two-motor board raises :class:`NoSuchComponentError`,
an :class:`IndexError` that says which board it was and which numbers it has::

    IndexError: Student Robotics v4 Motor Board - SR0A1B has motors 0 to 1: there is no motor 2

Everything else is the tuple's: length, iteration, unpacking, slicing, equality.
"""

from __future__ import annotations

from collections.abc import Iterable
from typing import Any, SupportsIndex, TypeVar, overload

__all__ = ["NoSuchComponentError", "NumberedComponents"]

T_co = TypeVar("T_co", covariant=True)


class NoSuchComponentError(IndexError):
    """A board has no component of that number; the message lists the numbers it has."""


class NumberedComponents(tuple[T_co, ...]):
    """The components of one kind on a board, numbered from 0.

    :param items: the components, in number order.
    :param owner: what to call the board in a message (its ``str``).
    :param kind: what one component is called, such as ``"motor"``.
    """

    owner: str
    kind: str

    def __new__(
        cls, items: Iterable[T_co], *, owner: object, kind: str,
    ) -> NumberedComponents[T_co]:
        """Make the tuple of ``items`` belonging to ``owner``."""
        made = super().__new__(cls, items)
        made.owner = str(owner)
        made.kind = kind
        return made

    @overload
    def __getitem__(self, index: SupportsIndex) -> T_co: ...

    @overload
    def __getitem__(self, index: slice) -> tuple[T_co, ...]: ...

    def __getitem__(self, index: Any) -> Any:
        """Component ``index``; a missing number raises :class:`NoSuchComponentError`."""
        try:
            return super().__getitem__(index)
        except IndexError:
            raise NoSuchComponentError(self.describe_miss(index)) from None
        except TypeError:
            raise TypeError(
                f"{self.kind}s are numbered: use a whole number from 0 to {len(self) - 1}, "
                f"not {type(index).__name__}",
            ) from None

    def describe_miss(self, index: object) -> str:
        """The message of a miss at ``index``."""
        if not self:
            return f"{self.owner} has no {self.kind}s: there is no {self.kind} {index}"
        return (
            f"{self.owner} has {self.kind}s 0 to {len(self) - 1}: "
            f"there is no {self.kind} {index}"
        )

    def replaced(self, items: Iterable[Any]) -> NumberedComponents[Any]:
        """The same board's numbering around other items (the sync facade's wrappers)."""
        return NumberedComponents(items, owner=self.owner, kind=self.kind)
