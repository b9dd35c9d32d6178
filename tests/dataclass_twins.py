"""Checking a dataclass whose methods are written by hand against what ``@dataclass`` makes.

Some of j5aio's dataclasses are imported by every program and write their own
``__init__``, ``__repr__``, ``__eq__`` and ``__hash__`` (making the generated ones costs
time at start-up). :func:`assert_like_generated` checks that such a class behaves as the
plain ``@dataclass(frozen=True)`` of the same fields would: its twin, made here with
:func:`dataclasses.make_dataclass` from the class's own fields.
"""

from __future__ import annotations

import copy
import dataclasses
import inspect
import pickle
import re
from collections.abc import Mapping
from typing import Any

import pytest

__all__ = ["assert_like_generated", "twin_of"]


def twin_of(cls: type, *, frozen: bool = True) -> type:
    """The dataclass ``@dataclass`` makes from ``cls``'s fields (no methods of its own)."""
    specs: list[tuple[str, Any, Any]] = []
    for spec in dataclasses.fields(cls):
        options: dict[str, Any] = {
            "kw_only": spec.kw_only,
            "repr": spec.repr,
            "hash": spec.hash,
            "compare": spec.compare,
        }
        if spec.default is not dataclasses.MISSING:
            options["default"] = spec.default
        if spec.default_factory is not dataclasses.MISSING:
            options["default_factory"] = spec.default_factory
        specs.append((spec.name, spec.type, dataclasses.field(**options)))
    return dataclasses.make_dataclass(cls.__name__, specs, frozen=frozen)


def _values(obj: object) -> dict[str, Any]:
    return {spec.name: getattr(obj, spec.name) for spec in dataclasses.fields(obj)}  # type: ignore[arg-type]


def _refusal(action: Any, *args: Any) -> str | None:
    try:
        action(*args)
    except dataclasses.FrozenInstanceError as error:
        return str(error)
    return None


def _assert_frozen_alike(obj: object, twin_obj: object, names: list[str]) -> None:
    """Assigning or deleting each of ``names`` is refused (or let be) as by the twin."""
    for name in names:
        refused = _refusal(setattr, twin_obj, name, None)
        assert _refusal(setattr, obj, name, None) == refused
        assert _refusal(delattr, twin_obj, name) == _refusal(delattr, obj, name)
        if refused is None:  # (the attribute was made, and deleted: the objects are unchanged)
            assert not hasattr(obj, name)


def _assert_copies(obj: object, twin_obj: object) -> None:
    """Copies of ``obj`` are made (or refused) as the twin's; pickles, if its fields pickle."""
    for make in (copy.copy, copy.deepcopy):
        try:
            twin_copy = make(twin_obj)
        except TypeError as error:  # (a field that cannot be copied)
            with pytest.raises(TypeError, match=re.escape(str(error))):
                make(obj)
        else:
            assert (make(obj) == obj) == (twin_copy == twin_obj)
    try:
        fields = pickle.dumps(tuple(_values(obj).values()))
    except (pickle.PicklingError, AttributeError, TypeError):
        return  # (a field that cannot be pickled: a function made in a function, say)
    assert fields
    made = pickle.loads(pickle.dumps(obj))
    assert made == obj and type(made) is type(obj) and made is not obj


def assert_like_generated(
    cls: type, samples: list[tuple[tuple[Any, ...], Mapping[str, Any]]], *, frozen: bool = True
) -> None:
    """Check ``cls`` against its twin, made from each of ``samples`` (args, keyword args).

    The samples should hold at least two that differ (for ``==``). Their fields are
    compared as the constructors leave them, with ``repr``, ``==``, ``hash`` (or the
    same error from it), the signature's parameters, ``dataclasses.replace`` and the
    errors that assigning or deleting an attribute raise (none, for a class that is not
    ``frozen``: the twin is then a mutable dataclass); copies and pickles are equal.
    """
    twin = twin_of(cls, frozen=frozen)
    params = dataclasses.fields(cls)
    assert dataclasses.is_dataclass(cls)
    assert cls.__dataclass_params__.frozen == frozen  # type: ignore[attr-defined]
    assert [(p.name, p.kind) for p in inspect.signature(cls).parameters.values()] == [
        (p.name, p.kind) for p in inspect.signature(twin).parameters.values()
    ]
    assert cls.__match_args__ == twin.__match_args__  # type: ignore[attr-defined]
    subclass = type(f"{cls.__name__}Subclass", (cls,), {})
    made = [cls(*args, **kwargs) for args, kwargs in samples]
    twins = [twin(**_values(obj)) for obj in made]
    for obj, other in zip(made, twins, strict=True):
        assert repr(obj) == repr(other)
        assert _values(cls(*[], **{p.name: getattr(obj, p.name) for p in params})) == _values(obj)
        assert dataclasses.replace(obj) == obj
        try:
            expected: object = hash(other)
        except TypeError as error:
            with pytest.raises(TypeError, match=str(error)):
                hash(obj)
        else:
            assert hash(obj) == expected
        if frozen:
            _assert_frozen_alike(obj, other, [params[0].name, params[-1].name, "not_a_field"])
            # A subclass that is no dataclass freezes its fields only (as the twin's does).
            _assert_frozen_alike(
                subclass(**_values(obj)),
                type(f"{cls.__name__}TwinSubclass", (twin,), {})(**_values(obj)),
                [params[0].name, "not_a_field"],
            )
        else:
            changed = copy.copy(obj)
            setattr(changed, params[0].name, getattr(other, params[-1].name))
            assert getattr(changed, params[0].name) is getattr(other, params[-1].name)
        _assert_copies(obj, other)
        # Another class, even with equal fields (a subclass too), is not compared.
        assert obj.__eq__(other) is NotImplemented
        assert obj.__eq__(subclass(**_values(obj))) is NotImplemented
    for obj, twin_obj in zip(made, twins, strict=True):
        for other, other_twin in zip(made, twins, strict=True):
            assert (obj == other) == (twin_obj == other_twin)
            assert (obj != other) == (twin_obj != other_twin)
