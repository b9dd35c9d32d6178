"""Small immutable records made without a dataclass's cost at start-up.

Making a dataclass generates and compiles its methods: about a third of a millisecond
each, paid by every program that imports it. The records a robot imports at every start
(the simulated arena's markers and poses, the camera's calibration) are
written as plain classes with ``__slots__`` and decorated with :func:`record`, which gives
them a frozen dataclass's equality, hash, repr, copying, pickling and immutability from
functions written once here.
"""

from __future__ import annotations

from dataclasses import FrozenInstanceError
from typing import TypeVar

from typing_extensions import dataclass_transform

__all__ = ["record", "set_fields"]

_R = TypeVar("_R")


@dataclass_transform(frozen_default=True)  # (type checkers: a frozen dataclass)
def record(cls: type[_R]) -> type[_R]:
    """Make ``cls`` (with ``__slots__`` and ``_fields``) a small immutable record.

    ``_fields`` names the fields in order; an optional ``_shown_fields`` names those its
    repr shows (all of them if it is not given: leave out a password, say).

    It is equal, hashed and shown by its fields, like a frozen dataclass; assigning or
    deleting raises :class:`dataclasses.FrozenInstanceError`. ``__init__`` sets the
    fields with :func:`set_fields`.
    """
    fields: tuple[str, ...] = vars(cls)["_fields"]
    shown_fields: tuple[str, ...] = vars(cls).get("_shown_fields", fields)

    def values(self: object) -> tuple[object, ...]:
        return tuple(getattr(self, name) for name in fields)

    def equal(self: object, other: object) -> object:  # (bool, or NotImplemented)
        if other.__class__ is not self.__class__:
            return NotImplemented
        return values(self) == values(other)

    def hashed(self: object) -> int:
        return hash(values(self))

    def shown(self: object) -> str:
        listed = ", ".join(f"{name}={getattr(self, name)!r}" for name in shown_fields)
        return f"{type(self).__qualname__}({listed})"

    def refuse_set(self: object, name: str, value: object) -> None:
        raise FrozenInstanceError(f"cannot assign to field {name!r}")

    def refuse_delete(self: object, name: str) -> None:
        raise FrozenInstanceError(f"cannot delete field {name!r}")

    def copied(self: _R) -> _R:
        return self

    def deep_copied(self: _R, memo: object) -> _R:
        return self

    def pickled(self: object) -> tuple[type, tuple[object, ...]]:
        return (type(self), values(self))

    methods = {
        "__eq__": equal, "__hash__": hashed, "__repr__": shown, "__setattr__": refuse_set,
        "__delattr__": refuse_delete, "__copy__": copied, "__deepcopy__": deep_copied,
        "__reduce__": pickled,
    }
    for name, method in methods.items():
        method.__name__ = name
        method.__qualname__ = f"{cls.__qualname__}.{name}"
        setattr(cls, name, method)
    return cls


def set_fields(obj: object, **values: object) -> None:
    """Set a record's fields (in its ``__init__``: a record refuses assignment after)."""
    for name, value in values.items():
        object.__setattr__(obj, name, value)
