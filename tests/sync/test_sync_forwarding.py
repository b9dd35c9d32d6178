"""Every generated member forwards to the same-named member of the core object."""

from __future__ import annotations

import inspect
from typing import Any

import pytest

from j5aio.sync import _generated
from j5aio.sync.wrapping import SyncWrapper


class Spy:
    """Stands in for a core object: records what the wrapper asked of it."""

    def __init__(self, core_class: type) -> None:
        self.calls: list[tuple[str, tuple[Any, ...], dict[str, Any]]] = []
        self.core_class = core_class
        self.assigned: dict[str, Any] = {}

    def __getattr__(self, name: str) -> Any:
        member = inspect.getattr_static(self.core_class, name, None)
        if member is None or isinstance(member, property):  # an attribute or a property
            self.calls.append((name, (), {}))
            return 42
        function = member.__func__ if isinstance(member, classmethod | staticmethod) else member
        if inspect.iscoroutinefunction(function):

            async def coroutine(*args: Any, **kwargs: Any) -> int:
                self.calls.append((name, args, kwargs))
                return 42

            return coroutine

        def plain(*args: Any, **kwargs: Any) -> int:
            self.calls.append((name, args, kwargs))
            return 42

        return plain

    def __setattr__(self, name: str, value: Any) -> None:
        if name in ("calls", "core_class", "assigned"):
            object.__setattr__(self, name, value)
        else:
            self.assigned[name] = value


def wrapper_classes() -> list[type[SyncWrapper]]:
    return [
        obj
        for name in _generated.__all__
        if isinstance(obj := getattr(_generated, name), type) and issubclass(obj, SyncWrapper)
    ]


def core_class_of(wrapper_class: type[SyncWrapper]) -> type:
    for core, wrapper in _wrapping_registry().items():
        if wrapper is wrapper_class:
            return core
    raise AssertionError(f"{wrapper_class} is not registered")


def _wrapping_registry() -> dict[type, Any]:
    from j5aio.sync import wrapping as _wrapping

    _wrapping.registered()  # (registers the classes registered by name, too)
    return {k: v for k, v in _wrapping._WRAPPER_CLASSES.items() if v is not None}


def dummy_arguments(function: Any) -> tuple[list[Any], dict[str, Any]]:
    args: list[Any] = []
    kwargs: dict[str, Any] = {}
    for index, param in enumerate(inspect.signature(function).parameters.values()):
        if index == 0 and param.name in ("self", "cls"):
            continue
        if param.kind in (param.VAR_POSITIONAL, param.VAR_KEYWORD):
            continue
        value = f"arg-{param.name}"
        if param.kind is param.KEYWORD_ONLY:
            kwargs[param.name] = value
        else:
            args.append(value)
    return args, kwargs


CASES = [
    (wrapper, name)
    for wrapper in wrapper_classes()
    for name, member in vars(wrapper).items()
    if (not name.startswith("_") or name in ("__getitem__", "__iter__", "__len__", "__contains__"))
    and (isinstance(member, property) or inspect.isfunction(member))
]


@pytest.mark.parametrize(
    ("wrapper_class", "name"), CASES, ids=[f"{w.__name__}.{n}" for w, n in CASES],
)
def test_member_forwards_to_the_core(wrapper_class: type[SyncWrapper], name: str) -> None:
    core_class = core_class_of(wrapper_class)
    spy = Spy(core_class)
    wrapper = wrapper_class._from_core(spy)
    member = vars(wrapper_class)[name]
    if isinstance(member, property):
        value = getattr(wrapper, name)
        assert value == 42
        expected = f"get_{name}" if hasattr(core_class, f"get_{name}") else name
        assert spy.calls[0][0] == expected
        if member.fset is not None:
            spy.calls.clear()
            setattr(wrapper, name, "new value")
            if hasattr(core_class, f"set_{name}"):
                assert spy.calls == [(f"set_{name}", ("new value",), {})]
            else:
                assert spy.assigned == {name: "new value"}
        return
    args, kwargs = dummy_arguments(member)
    result = getattr(wrapper, name)(*args, **kwargs)
    assert spy.calls, f"{wrapper_class.__name__}.{name} did not reach the core"
    called, called_args, called_kwargs = spy.calls[0]
    assert called == name
    assert list(called_args) == args
    assert called_kwargs == kwargs
    returns = inspect.signature(getattr(core_class, name)).return_annotation
    if returns not in (None, "None"):
        assert result == 42
