"""The methods ``@dataclass`` would generate for a class, written once for all of them.

``@dataclass`` writes each class's methods out as source and compiles them when the class
is made: a frozen dataclass costs between a tenth and a third of a millisecond to make,
most of it its ``__setattr__``, ``__delattr__``, ``__init__``, ``__repr__`` and ``__eq__``.
The dataclasses that every program imports are made without them:

* a frozen one is declared with :func:`frozen_record` (to Python,
  ``@dataclass(init=False, repr=False, eq=False)``, its parameters then saying it is
  frozen; to a type checker, ``@dataclass(frozen=True)``), writes its own ``__init__``
  (setting its fields with ``object.__setattr__``) and takes freezing, ``__repr__``,
  ``__eq__`` and ``__hash__`` from :class:`FrozenRecord`;
* a mutable one is declared ``@dataclass(init=False, repr=False, eq=False)``, writes its
  own ``__init__`` and takes ``__repr__`` and ``__eq__`` from :class:`Record` (and, as a
  mutable dataclass comparing its fields, no hash).

Their fields are still written once, as annotations, so :func:`dataclasses.fields`,
:func:`dataclasses.replace`, :func:`dataclasses.asdict`, :func:`dataclasses.is_dataclass`
and ``__match_args__`` work as on any dataclass. The shared methods read the class's
fields (the first time, for each class) and behave as the generated ones.
"""

from __future__ import annotations

import contextlib
import dataclasses
from typing import TYPE_CHECKING, Any, ClassVar, TypeVar

__all__ = ["FrozenRecord", "Record", "frozen_record"]

_T = TypeVar("_T")

# The fields of each record class, and those it compares, hashes and shows (read once).
_FIELDS: dict[type, tuple[str, ...]] = {}
_COMPARED: dict[type, tuple[str, ...]] = {}
_HASHED: dict[type, tuple[str, ...]] = {}
_SHOWN: dict[type, tuple[str, ...]] = {}


def _names(cls: type, table: dict[type, tuple[str, ...]]) -> tuple[str, ...]:
    names = table.get(cls)
    if names is None:
        fields = dataclasses.fields(cls)
        _FIELDS[cls] = tuple(f.name for f in fields)
        _COMPARED[cls] = tuple(f.name for f in fields if f.compare)
        _HASHED[cls] = tuple(f.name for f in fields if (f.compare if f.hash is None else f.hash))
        _SHOWN[cls] = tuple(f.name for f in fields if f.repr)
        names = table[cls]
    return names


if TYPE_CHECKING:
    from typing_extensions import dataclass_transform

    @dataclass_transform(frozen_default=True, field_specifiers=(dataclasses.field,))
    def frozen_record(cls: type[_T]) -> type[_T]:
        """See below."""

else:

    def frozen_record(cls):
        """Make ``cls``, a :class:`FrozenRecord` subclass, a dataclass of its annotated fields.

        It is ``@dataclass(init=False, repr=False, eq=False)``: ``cls`` writes its own
        ``__init__`` and takes the rest from :class:`FrozenRecord`. Type checkers see
        ``@dataclass(frozen=True)``, and so refuse an assignment to a field.

        :raises TypeError: ``cls`` is not a :class:`FrozenRecord` (it would not be frozen),
            or does not write its own ``__init__`` (it would have none that sets its fields).
        """
        if not (isinstance(cls, type) and issubclass(cls, FrozenRecord)):
            raise TypeError(f"frozen_record makes FrozenRecord subclasses, not {cls!r}")
        if "__init__" not in vars(cls):
            raise TypeError(
                f"{cls.__qualname__} must define __init__, setting its fields with "
                "object.__setattr__ (frozen_record generates none)"
            )
        record = dataclasses.dataclass(cls, init=False, repr=False, eq=False)
        _say_frozen(record)
        return record


def _say_frozen(cls: type) -> None:
    """Record in ``cls``'s dataclass parameters that its instances are frozen.

    They are, by :class:`FrozenRecord`; saying so lets a subclass be a frozen dataclass,
    as a subclass of any frozen dataclass can (and not a mutable one). Where the
    parameters cannot be changed (a later Python's), the record works the same, but
    ``@dataclass(frozen=True)`` refuses to subclass it.
    """
    with contextlib.suppress(AttributeError):
        cls.__dataclass_params__.frozen = True  # type: ignore[attr-defined]


class Record:
    """The ``__repr__`` and ``__eq__`` a dataclass would generate, from its fields.

    For a dataclass declared with ``init=False, repr=False, eq=False``: the ``repr``
    shows the fields as the generated one does; two records are equal when they are of
    the same class and their compared fields are equal (as tuples: an object is equal to
    itself, ``nan`` included). Like a mutable dataclass that compares its fields, a
    record is not hashable (:class:`FrozenRecord` is).
    """

    __slots__ = ()

    # (A mutable dataclass with eq=True sets __hash__ to None: equal records could change.)
    __hash__: ClassVar[Any] = None

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


class FrozenRecord(Record):
    """What ``@dataclass(frozen=True)`` gives a class beyond its ``__init__``, from its fields.

    For a dataclass declared with :func:`frozen_record`: assigning or deleting an
    attribute raises :class:`dataclasses.FrozenInstanceError` (with the message a frozen
    dataclass gives; on a subclass that is not itself a dataclass, only its fields are
    frozen, as there); ``repr`` and ``==`` are :class:`Record`'s; the hash is that of the
    hashed fields. Its ``__init__`` sets the fields with ``object.__setattr__``. Copies
    and pickles are made as for any object (they set the ``__dict__``, not attributes).
    """

    __slots__ = ()

    def __setattr__(self, name: str, value: object) -> None:
        cls = type(self)
        if "__dataclass_fields__" in vars(cls) or name in _names(cls, _FIELDS):
            raise dataclasses.FrozenInstanceError(f"cannot assign to field {name!r}")
        super().__setattr__(name, value)

    def __delattr__(self, name: str) -> None:
        cls = type(self)
        if "__dataclass_fields__" in vars(cls) or name in _names(cls, _FIELDS):
            raise dataclasses.FrozenInstanceError(f"cannot delete field {name!r}")
        super().__delattr__(name)

    def __hash__(self) -> int:
        return hash(tuple(getattr(self, name) for name in _names(type(self), _HASHED)))
