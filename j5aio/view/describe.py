"""What the live view shows of a board: its components, and a call turned into a value.

Nothing here knows a particular board. Components are found among a board's public
properties (a component, or a group or mapping of them), and an interface call such as
``set_motor_state(1, 0.5)`` becomes the value ``0.5`` of the field ``motor_state`` of the
component ``motor`` number 1 of that board, by the naming rule every interface follows:
a verb (``get_``, ``set_``, ``read_``, ``write_``), then the field; the component's
identifier first among the arguments, the written value last. One kind has a rule of its
own: a flashing LED's mode (off, on or flashing) is one value, so switching it on or off
(``set_led_state``) is shown as its mode ``ON`` / ``OFF``, and a read of whether it is lit
(which a flashing LED answers "lit") does not stop it showing as flashing.
"""

from __future__ import annotations

import enum
import functools
import math
import re
from collections.abc import Iterable, Iterator, Mapping
from datetime import timedelta
from typing import Any, NamedTuple

from j5aio.boards.board import Board
from j5aio.components.component import Component, DerivedComponent
from j5aio.numbered import Pins

__all__ = [
    "ComponentInfo",
    "Update",
    "board_components",
    "component_id",
    "component_names",
    "describe_call",
    "jsonable",
    "kind_of",
]

_WRITERS = ("set_", "write_")
_FLASHING = "flashingled"
_READERS = ("get_", "read_")


class ComponentInfo(NamedTuple):
    """One component as the page lists it.

    :param kind: the component's class name in lower case (``motor``, ``gpiopin``...).
    :param identifier: its identifier as text (``"3"``; ``"6-7"`` for an ultrasound sensor
        on trigger pin 6 and echo pin 7).
    """

    kind: str
    identifier: str


class Update(NamedTuple):
    """A value the page shows: ``field`` of the component ``kind``/``identifier``."""

    kind: str
    identifier: str
    field: str
    value: Any


def kind_of(component_class: type[Component]) -> str:
    """The kind of a component class as the page names it: its class name in lower case."""
    return component_class.__name__.lower()


def component_id(serial: str, info: ComponentInfo) -> str:
    """The ``data-component`` text of a component: ``serial:kind:identifier``."""
    return f"{serial}:{info.kind}:{info.identifier}"


def _properties(board: Board) -> Iterator[tuple[str, object]]:
    """The board's public properties and their values, by name (those that can be read)."""
    for name in sorted(dir(type(board))):
        if name.startswith("_") or not isinstance(getattr(type(board), name, None), property):
            continue
        try:
            value = getattr(board, name)
        except Exception:  # a property that needs the board to answer: not a component
            continue
        yield name, value


def board_components(board: Board) -> list[ComponentInfo]:
    """Every component a board shows among its public properties, in a stable order."""
    found: dict[tuple[str, str], ComponentInfo] = {}
    for _, value in _properties(board):
        for component in _components_in(value):
            if isinstance(component, DerivedComponent):
                continue
            info = ComponentInfo(kind_of(type(component)), str(component.identifier))
            found.setdefault((info.kind, info.identifier), info)
    return sorted(found.values(), key=lambda c: (c.kind, _number_first(c.identifier)))


def component_names(board: Board) -> dict[ComponentInfo, str]:
    """The property names of a board's components that have one of their own.

    A component that is a board property by itself (``run_led``, ``start_led``,
    ``start_button``) is named by it, in words (``"start LED"``); those in groups are not.
    """
    names: dict[ComponentInfo, str] = {}
    for name, value in _properties(board):
        if isinstance(value, Component) and not isinstance(value, DerivedComponent):
            info = ComponentInfo(kind_of(type(value)), str(value.identifier))
            words = re.sub(r"\bled\b", "LED", name.replace("_", " "))
            names.setdefault(info, words)
    return names


def _number_first(identifier: str) -> tuple[int, str]:
    head = identifier.split("-")[0]
    return (int(head), identifier) if head.isdigit() else (1 << 30, identifier)


def _components_in(value: object) -> Iterable[Component]:
    if isinstance(value, Component):
        return (value,)
    if isinstance(value, Mapping | Pins):  # board.pins iterates its pins, as in j5
        return tuple(v for v in value.values() if isinstance(v, Component))
    if isinstance(value, tuple | list) or type(value).__name__.endswith("Group"):
        try:
            return tuple(v for v in value if isinstance(v, Component))  # type: ignore[attr-defined]
        except TypeError:
            return ()
    return ()


@functools.cache
def _kinds_by_method(board_class: type[Board]) -> Mapping[str, tuple[str, ...]]:
    kinds: dict[str, list[str]] = {}
    for component in sorted(board_class.supported_components(), key=lambda c: c.__name__):
        for method in component.interface_class().__abstractmethods__:
            kinds.setdefault(method, []).append(kind_of(component))
    return {method: tuple(k) for method, k in kinds.items()}


class _Plan(NamedTuple):
    """How the calls of one method of one board class become values (worked out once)."""

    kinds: tuple[str, ...]
    field: str
    how: str  # "write": the last argument; "read": the result; "wait", "buzz"
    pins: int  # how many leading arguments identify the component


@functools.cache
def _plan(board_class: type[Board], method_name: str) -> _Plan | None:
    kinds = _kinds_by_method(board_class).get(method_name)
    if not kinds:
        return None
    pins = 2 if "ultrasound" in method_name else 1
    if method_name.startswith("wait_until_") and method_name.endswith("_pressed"):
        field = method_name[len("wait_until_") : -len("_pressed")] + "_state"
        return _Plan(kinds, field, "wait", pins)
    if method_name == "buzz":
        return _Plan(kinds, "note", "buzz", pins)
    if method_name.startswith(_WRITERS):
        return _Plan(kinds, method_name.split("_", 1)[1], "write", pins)
    if method_name.startswith(_READERS):
        return _Plan(kinds, method_name.split("_", 1)[1], "read", pins)
    return _Plan(kinds, method_name, "read", pins)


def describe_call(
    board: Board,
    method_name: str,
    arguments: tuple[Any, ...],
    result: Any,
    known: Iterable[ComponentInfo] = (),
) -> Update | None:
    """Turn one interface call of ``board``'s backend into the value the page shows.

    :param board: the board whose backend was called.
    :param method_name: the interface method, such as ``set_motor_state``.
    :param arguments: its arguments after ``self``.
    :param result: what it returned.
    :param known: the board's components, to choose between kinds that share a method.
    :returns: the update, or ``None`` for a call that shows nothing (one without an
        identifier, such as a string command).
    """
    plan = _plan(type(board), method_name)
    if plan is None or len(arguments) < plan.pins:
        return None
    identifier = f"{arguments[0]}-{arguments[1]}" if plan.pins == 2 else str(arguments[0])
    extra = arguments[plan.pins :]
    kind = plan.kinds[0]
    if len(plan.kinds) > 1:
        present = {c.kind for c in known if c.identifier == identifier}
        kind = next((k for k in plan.kinds if k in present), kind)
    field, value = plan.field, result
    if plan.how == "wait":
        return Update(kind, identifier, field, True)
    if plan.how == "buzz":
        if len(extra) < 2:
            return None
        duration, pitch = extra[0], extra[1]
        seconds = duration.total_seconds() if isinstance(duration, timedelta) else duration
        return Update(kind, identifier, field, {"pitch": jsonable(pitch), "seconds": seconds})
    if plan.how == "write" and extra:
        extra, value = extra[:-1], extra[-1]
        if kind == _FLASHING and field == "led_state" and not extra:
            return Update(kind, identifier, "led_mode", "ON" if value else "OFF")
    if extra:
        field += "." + ".".join(_label(e) for e in extra)
    return Update(kind, identifier, field, jsonable(value))


def _label(value: object) -> str:
    return value.name.lower() if isinstance(value, enum.Enum) else str(value)


def jsonable(value: object) -> Any:
    """``value`` as JSON can carry it.

    Enums go by name (a note, a float enum, by its pitch), durations in seconds, sequences
    as lists, anything else as text.
    """
    if value is None or isinstance(value, bool):
        return value
    if isinstance(value, enum.Enum) and not isinstance(value, float):
        return value.name
    if isinstance(value, int):
        return int(value)
    if isinstance(value, float):
        return float(value) if math.isfinite(value) else str(value)
    if isinstance(value, str):
        return str(value)
    if isinstance(value, timedelta):
        return value.total_seconds()
    if isinstance(value, tuple | list):
        return [jsonable(v) for v in value]
    return str(value)
