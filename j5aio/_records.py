"""The ``__repr__``, ``__eq__`` and ``__hash__`` of ``@dataclass(frozen=True)``, written once.

``@dataclass`` writes each class's methods out as source and compiles them when the class
is made, about a quarter of a millisecond a class. A few of j5aio's frozen dataclasses
that every program imports are declared ``@dataclass(frozen=True, init=False, repr=False,
eq=False)`` with an ``__init__`` of their own, and take the other three methods from
:class:`FrozenRecord`, which reads the class's fields (:func:`dataclasses.fields`): the
fields are still written once, as annotations, and ``dataclasses.fields``, ``replace``
and ``asdict`` work as on any dataclass.
"""

from __future__ import annotations

import dataclasses

__all__ = ["FrozenRecord"]

# The fields each record class compares, hashes and shows, by class (read once).
_COMPARED: dict[type, tuple[str, ...]] = {}
_HASHED: dict[type, tuple[str, ...]] = {}
_SHOWN: dict[type, tuple[str, ...]] = {}


def _names(cls: type, table: dict[type, tuple[str, ...]]) -> tuple[str, ...]:
    names = table.get(cls)
    if names is None:
        fields = dataclasses.fields(cls)
        _COMPARED[cls] = tuple(f.name for f in fields if f.compare)
        _HASHED[cls] = tuple(f.name for f in fields if (f.compare if f.hash is None else f.hash))
        _SHOWN[cls] = tuple(f.name for f in fields if f.repr)
        names = table[cls]
    return names


class FrozenRecord:
    """The methods ``@dataclass(frozen=True)`` would give a class, from its fields.

    For a dataclass declared with ``init=False, repr=False, eq=False`` (and ``frozen=True``):
    the ``repr`` shows the fields as the generated one does; two records are equal when
    they are of the same class and their compared fields are equal; the hash is that of
    the hashed fields.
    """

    __slots__ = ()

    def __repr__(self) -> str:
        shown = ", ".join(f"{name}={getattr(self, name)!r}" for name in _names(type(self), _SHOWN))
        return f"{type(self).__qualname__}({shown})"

    def __eq__(self, other: object) -> bool:
        if other.__class__ is not self.__class__:
            return NotImplemented
        names = _names(type(self), _COMPARED)
        return tuple(getattr(self, name) for name in names) == tuple(
            getattr(other, name) for name in names
        )

    def __hash__(self) -> int:
        return hash(tuple(getattr(self, name) for name in _names(type(self), _HASHED)))
