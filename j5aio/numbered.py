"""Numbered parts of a board: ``board.motors`` (a tuple) and ``board.pins``; misses name the board.

``motor_board.motors[2]`` on a two-motor board raises :class:`NoSuchComponentError`,
an :class:`IndexError` that says which board it was and which numbers it has::

    IndexError: Student Robotics v4 Motor Board - SR0A1B has motors 0 to 1: there is no motor 2

Everything else is the tuple's: length, iteration, unpacking, slicing, equality.
"""

from __future__ import annotations

from collections.abc import ItemsView, Iterable, Iterator, KeysView, Mapping, ValuesView
from typing import Any, Generic, SupportsIndex, TypeVar, overload

__all__ = ["NoSuchComponentError", "NoSuchPinError", "NumberedComponents", "Pins"]

T_co = TypeVar("T_co", covariant=True)
P_co = TypeVar("P_co", covariant=True)


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


class NoSuchPinError(KeyError):
    """A board has no pin of that number; the message says which pins it has."""

    def __str__(self) -> str:
        return str(self.args[0]) if self.args else ""


class Pins(Generic[P_co]):
    """A board's pins by number: ``pins[3]``, ``pins[AnaloguePin.A0]``.

    Iterating gives the *pins*, as j5 did (``for pin in board.pins: pin.mode = ...``),
    so this is deliberately not a :class:`~collections.abc.Mapping`, whose iteration
    gives keys. The numbers are :meth:`keys`; :meth:`values` and :meth:`items` are there
    too, and ``3 in pins`` asks whether pin 3 exists.

    :param pins: the pins, by number.
    :param owner: what to call the board in a message (its ``str``).
    """

    __slots__ = ("_pins", "owner")

    def __init__(self, pins: Mapping[int, P_co], *, owner: object) -> None:
        self._pins = dict(pins)
        self.owner = str(owner)

    def __getitem__(self, number: int) -> P_co:
        """Pin ``number``; a missing one raises :class:`NoSuchPinError` naming the board."""
        try:
            return self._pins[number]
        except KeyError:
            raise NoSuchPinError(
                f"{self.owner} has no pin {number!r}; its pins are "
                f"{min(self._pins)} to {max(self._pins)}",
            ) from None
        except TypeError:
            raise TypeError(
                f"pins are numbered: use a whole number, not {type(number).__name__}",
            ) from None

    def __iter__(self) -> Iterator[P_co]:
        """The pins, in number order (as j5's board.pins gave them)."""
        return iter(self._pins.values())

    def __len__(self) -> int:
        return len(self._pins)

    def __contains__(self, number: object) -> bool:
        """Whether the board has a pin of that number."""
        try:
            return number in self._pins
        except TypeError:
            return False

    def keys(self) -> KeysView[int]:
        """The pin numbers."""
        return self._pins.keys()

    def values(self) -> ValuesView[P_co]:
        """The pins."""
        return self._pins.values()

    def items(self) -> ItemsView[int, P_co]:
        """``(number, pin)`` pairs."""
        return self._pins.items()

    def get(self, number: int, default: Any = None) -> Any:
        """Pin ``number``, or ``default`` when the board has none of that number."""
        return self._pins.get(number, default)

    def replaced(self, pins: Mapping[int, Any]) -> Pins[Any]:
        """The same board's pins as other objects (the sync facade's wrappers)."""
        return Pins(pins, owner=self.owner)

    def __repr__(self) -> str:
        return f"<pins {', '.join(map(str, self._pins))} of {self.owner}>"
