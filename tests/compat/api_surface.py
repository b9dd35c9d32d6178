"""The public surface of a competition's API, as data that two packages can be compared by.

``python api_surface.py PACKAGE MODULE:CLASS ...`` prints (as JSON) every name in
``PACKAGE.__all__`` and every listed class: for a class its public members (methods with
their parameters and defaults, properties and whether they can be set, an enum's members),
for an exception its built-in bases, for a value its type and ``repr``. The tests run it on
the competition's own package (in a Python that has it) and on j5aio's module.
"""

from __future__ import annotations

import enum
import importlib
import inspect
import json
import sys
from typing import Any


def describe_callable(value: Any) -> dict[str, Any]:
    try:
        signature = inspect.signature(value)
    except (TypeError, ValueError):
        return {"kind": "callable"}
    parameters = [
        [
            parameter.name,
            parameter.kind.name,
            None if parameter.default is inspect.Parameter.empty else repr(parameter.default),
        ]
        for parameter in signature.parameters.values()
        if parameter.name not in ("self", "cls")
    ]
    return {"kind": "function", "parameters": parameters}


def builtin_bases(cls: type) -> list[str]:
    return sorted({
        base.__name__ for base in cls.__mro__[1:]
        if base.__module__ == "builtins" and base is not object
    })


def describe_class(cls: type) -> dict[str, Any]:
    if issubclass(cls, enum.Enum):
        return {
            "kind": "enum",
            "members": {member.name: repr(member.value) for member in cls},
            "bases": builtin_bases(cls),
        }
    members: dict[str, Any] = {}
    for name in dir(cls):
        if name.startswith("_") and name != "__init__":
            continue
        if name in {"count", "index"} and issubclass(cls, tuple):
            continue
        attribute = inspect.getattr_static(cls, name)
        if isinstance(attribute, property):
            members[name] = {"kind": "property", "settable": attribute.fset is not None}
        elif isinstance(attribute, (staticmethod, classmethod)):
            members[name] = describe_callable(getattr(cls, name))
        elif inspect.isfunction(attribute):
            if name == "__init__" and attribute is object.__init__:
                continue
            members[name] = describe_callable(attribute)
        elif isinstance(attribute, tuple) and issubclass(cls, tuple):
            members[name] = {"kind": "field"}  # (a NamedTuple's field)
        else:
            members[name] = {"kind": "value", "type": type(attribute).__name__}
    fields = list(getattr(cls, "_fields", ()))
    return {"kind": "class", "members": members, "bases": builtin_bases(cls), "fields": fields}


def describe(value: Any) -> dict[str, Any]:
    if inspect.isclass(value):
        return describe_class(value)
    if isinstance(value, enum.Enum):
        return {"kind": "member", "enum": type(value).__name__, "value": repr(value.value)}
    if callable(value):
        return describe_callable(value)
    return {"kind": "value", "type": type(value).__name__, "repr": repr(value)}


def surface(package: str, classes: list[str]) -> dict[str, Any]:
    module = importlib.import_module(package)
    found: dict[str, Any] = {
        name: describe(getattr(module, name)) for name in sorted(module.__all__)
    }
    for reference in classes:
        module_name, _, class_name = reference.partition(":")
        submodule = importlib.import_module(f"{package}.{module_name}")
        found[reference] = describe(getattr(submodule, class_name))
    return found


if __name__ == "__main__":
    package, *listed = sys.argv[1:]
    print(json.dumps(surface(package, listed)))
