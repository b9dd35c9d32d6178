"""The generator of sync facades: typed ``__slots__`` wrappers of async boards and components.

j5aio's own facade (``j5aio/sync/_generated.py``) is made by it, and so is the sync module
of a third-party kit::

    python -m j5aio sync-gen beekit.boards -o beekit/sync.py          # write it
    python -m j5aio sync-gen beekit.boards -o beekit/sync.py --check  # CI: is it fresh?

The generator imports the given modules (a package is walked) and reads their public
classes by introspection: every board and component class defined there (a simulator or
a backend beside them is left alone). For j5aio's own facade (:data:`CORE_SCOPE`) that is every
class of :mod:`j5aio.components` and :mod:`j5aio.boards`, plus
:class:`~j5aio.backends.environment.Environment`, :class:`~j5aio.robot.BaseRobot`, the
module-level :class:`~j5aio.backends.environment.Environment` objects of
:mod:`j5aio.backends` and the functions of :mod:`j5aio.environments`.

For each class it writes a wrapper class with ``__slots__`` that holds the core object and
follows the naming convention: a ``get_x`` / ``set_x`` coroutine pair becomes the
read-write property ``x``, a lone ``get_x`` (with no required argument) a read-only
property, every other coroutine a blocking method of the same name; plain methods,
properties and class constants are forwarded. Anything that returns a core object returns
its wrapper instead. A class of another package that already has a wrapper (a third-party
board's base, ``j5aio.boards.Board``, or its ``Motor`` components) is referred to by that
wrapper, imported from its public module (``j5aio.sync``), so a generated third-party
module imports only public names: :mod:`j5aio.sync.wrapping` and :mod:`j5aio.sync`.

A function whose signature uses a type variable bound to a wrapped class
(``get_board_group``) is typed generically in the *sync* class (pass
``beekit.sync.BeeBoard``, get a ``BoardGroup[BeeBoard]``), with one extra ``@overload``
per core class of the module being generated (pass ``j5aio.boards.sr.v4.MotorBoard``, get
a ``BoardGroup[j5aio.sync.MotorBoard]``), so that the type checker knows the exact wrapper.
"""

from __future__ import annotations

import argparse
import ast
import enum
import importlib
import inspect
import math
import pkgutil
import re
import sys
import textwrap
import types
import typing
from collections.abc import Callable, Iterable, Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

__all__ = [
    "CORE_OUTPUT",
    "CORE_SCOPE",
    "Discovery",
    "Scope",
    "add_arguments",
    "check_or_write",
    "discover",
    "existing_wrappers",
    "generate",
    "main",
    "render_module",
    "run",
]

#: Where j5aio's own facade is written.
CORE_OUTPUT = Path(__file__).resolve().parent / "sync" / "_generated.py"

#: Dunder methods forwarded when a core class defines them.
FORWARDED_DUNDERS = ("__getitem__", "__iter__", "__len__", "__contains__", "__bool__", "__call__")

LINE_LENGTH = 100

_NONE_TYPE = type(None)


@dataclass(frozen=True)
class Scope:
    """What to wrap: the modules to read and the extras j5aio's own facade needs.

    :param modules: modules (or packages, walked) whose classes are wrapped.
    :param extra_classes: further ``(module, class name)`` pairs to wrap.
    :param environment_packages: packages searched for module-level environment objects.
    :param function_modules: modules whose public functions are wrapped when they take or
        return wrapped objects.
    :param skipped_packages: packages never imported while walking.
    """

    modules: tuple[str, ...]
    extra_classes: tuple[tuple[str, str], ...] = ()
    environment_packages: tuple[str, ...] = ()
    function_modules: tuple[str, ...] = ()
    skipped_packages: tuple[str, ...] = ()

    @property
    def is_core(self) -> bool:
        """Whether this is j5aio's own facade (which wraps no other facade's classes)."""
        return self == CORE_SCOPE


#: j5aio's own facade, ``j5aio/sync/_generated.py``.
CORE_SCOPE = Scope(
    modules=("j5aio.components", "j5aio.boards"),
    extra_classes=(
        ("j5aio.backends.environment", "Environment"),
        ("j5aio.robot", "BaseRobot"),
        ("j5aio.kit", "KitRobot"),
        ("j5aio.vision.track", "PositionTracker"),
    ),
    environment_packages=("j5aio.backends",),
    function_modules=("j5aio.environments",),
    skipped_packages=("j5aio.sync",),
)


# --------------------------------------------------------------------------- discovery


@dataclass
class Discovery:
    """What the generator wraps: core classes (bases first) and environment objects."""

    classes: list[type] = field(default_factory=list)
    environments: dict[str, tuple[str, str]] = field(default_factory=dict)
    """Exported name -> (module, attribute) of each environment object."""
    functions: list[Callable[..., Any]] = field(default_factory=list)
    """Module-level functions that take or return wrapped objects."""
    scope: Scope = CORE_SCOPE
    """What was searched."""


def _walk(package_name: str, skipped: tuple[str, ...]) -> list[types.ModuleType]:
    package = importlib.import_module(package_name)
    modules = [package]
    for info in pkgutil.walk_packages(getattr(package, "__path__", []), package_name + "."):
        if skipped and info.name.startswith(skipped):
            continue
        modules.append(importlib.import_module(info.name))
    return modules


def _is_wrappable(cls: type) -> bool:
    from j5aio.backends.backend import Backend
    from j5aio.components.component import Interface
    return not (
        issubclass(cls, enum.Enum | Interface | BaseException | Backend)
        or cls.__name__.startswith("_")
        or any(  # a sync wrapper; compared by name, so that j5aio.sync is not imported
            (k.__module__, k.__qualname__) == ("j5aio.sync.wrapping", "SyncWrapper")
            for k in cls.__mro__
        )
    )


def discover(scope: Scope = CORE_SCOPE) -> Discovery:
    """Find the classes (and, for j5aio's facade, environments and functions) of ``scope``.

    :raises ImportError: a module of the scope cannot be imported.
    """
    from j5aio.backends.environment import Environment
    from j5aio.boards.board import Board
    from j5aio.components.component import Component

    found: dict[type, None] = {}
    for package in scope.modules:
        for module in _walk(package, scope.skipped_packages):
            for obj in vars(module).values():
                if (
                    inspect.isclass(obj)
                    and obj.__module__ == module.__name__
                    and _is_wrappable(obj)
                    and (scope.is_core or issubclass(obj, Board | Component))
                ):
                    found[obj] = None
    for module_name, class_name in scope.extra_classes:
        found[getattr(importlib.import_module(module_name), class_name)] = None
    discovery = Discovery(classes=_bases_first(found), scope=scope)

    seen: dict[int, str] = {}
    for package in scope.environment_packages:
        for module in _walk(package, scope.skipped_packages):
            for name, obj in sorted(vars(module).items()):
                if (
                    isinstance(obj, Environment)
                    and not name.startswith("_")
                    and id(obj) not in seen
                ):
                    if name in discovery.environments:
                        raise RuntimeError(f"two environments are both called {name}")
                    seen[id(obj)] = name
                    discovery.environments[name] = (module.__name__, name)
    for module_name in scope.function_modules:
        module = importlib.import_module(module_name)
        for name, obj in vars(module).items():
            if (
                inspect.isfunction(obj)
                and obj.__module__ == module_name
                and not name.startswith("_")
            ):
                discovery.functions.append(obj)
    return discovery


def _bases_first(classes: Iterable[type]) -> list[type]:
    ordered: list[type] = []
    pending = sorted(classes, key=lambda c: (len(c.__mro__), c.__module__, c.__qualname__))
    placed: set[type] = set()
    while pending:
        for cls in pending:
            if all(base in placed or base not in pending for base in cls.__mro__[1:]):
                ordered.append(cls)
                placed.add(cls)
                pending.remove(cls)
                break
    return ordered


def _public_module(obj: Any) -> str:
    """The module to import ``obj`` from: its own, or the nearest public package exporting it."""
    module: str = obj.__module__
    parts = module.split(".")
    if not any(part.startswith("_") for part in parts):
        return module
    for end in range(len(parts) - 1, 0, -1):
        candidate = ".".join(parts[:end])
        if any(part.startswith("_") for part in parts[:end]):
            continue
        if getattr(sys.modules.get(candidate), obj.__qualname__, None) is obj:
            return candidate
    return module


def existing_wrappers(skip: Iterable[type] = ()) -> dict[type, tuple[str, str]]:
    """Return core class -> (public module, name) of every wrapper registered so far.

    Importing ``j5aio.sync._generated`` registers j5aio's own; a kit's generated module registers
    its own when imported. ``skip`` leaves out the classes about to be generated afresh.
    """
    import j5aio.sync._generated  # noqa: F401 - registers j5aio's own wrappers
    from j5aio.sync.wrapping import registered

    skipped = set(skip)
    return {
        core: (_public_module(wrapper), wrapper.__qualname__)
        for core, wrapper in registered().items()
        if core not in skipped
    }


# --------------------------------------------------------------------------- type hints


class _Namespace:
    """Resolves annotations, including names a module imports only under ``TYPE_CHECKING``."""

    def __init__(self) -> None:
        self._extras: dict[str, dict[str, Any]] = {}

    def module_namespace(self, module_name: str) -> dict[str, Any]:
        module = sys.modules[module_name]
        extras = self._extras.get(module_name)
        if extras is None:
            extras = self._extras[module_name] = _type_checking_imports(module)
        return {**extras, **vars(module)}

    def hints(self, obj: Any, module_name: str) -> dict[str, Any]:
        namespace = self.module_namespace(module_name)
        return typing.get_type_hints(obj, globalns=namespace, localns=None)


def _type_checking_imports(module: types.ModuleType) -> dict[str, Any]:
    """Run the imports of a module's ``if TYPE_CHECKING:`` blocks; return what they bind."""
    try:
        tree = ast.parse(inspect.getsource(module))
    except (OSError, TypeError):
        return {}
    namespace: dict[str, Any] = {}
    for node in tree.body:
        if (
            isinstance(node, ast.If)
            and isinstance(node.test, ast.Name | ast.Attribute)
            and ast.unparse(node.test).endswith("TYPE_CHECKING")
        ):
            imports: list[ast.stmt] = [
                n for n in node.body if isinstance(n, ast.Import | ast.ImportFrom)
            ]
            code = compile(ast.Module(body=imports, type_ignores=[]), module.__name__, "exec")
            exec(code, {"__name__": module.__name__, "__package__": module.__package__}, namespace)
    return namespace


# --------------------------------------------------------------------------- rendering


@dataclass
class _Member:
    name: str
    code: str


@dataclass(frozen=True)
class _SyncVar:
    """The sync-side type variable that stands for a core type variable bound to a wrapped class."""

    var: typing.TypeVar


@dataclass(frozen=True)
class _Either:
    """A wrapped class that a parameter takes as the core class or as its wrapper class."""

    cls: type


class _Renderer:
    def __init__(
        self,
        discovery: Discovery,
        external: Mapping[type, tuple[str, str]] | None = None,
    ) -> None:
        self.discovery = discovery
        self.public_only = not discovery.scope.is_core
        self.wrapped: dict[type, str] = {}
        for cls in discovery.classes:
            if cls.__name__ in self.wrapped.values():
                raise RuntimeError(f"two wrapped classes are called {cls.__name__}")
            self.wrapped[cls] = cls.__name__
        self.external = {k: v for k, v in (external or {}).items() if k not in self.wrapped}
        self.module_aliases: dict[str, str] = {}
        self.name_imports: dict[str, str] = {}  # name -> module
        self.typevars: dict[typing.TypeVar | _SyncVar, str] = {}
        self.sync_typevars: dict[type, _SyncVar] = {}
        self.typevar_defs: dict[str, str] = {}
        self.namespace = _Namespace()
        self.used_typing: set[str] = set()

    # --- references ---------------------------------------------------------------

    def module_ref(self, module_name: str) -> str:
        alias = self.module_aliases.get(module_name)
        if alias is None:
            parts = module_name.split(".")
            if parts[0] == "j5aio" and len(parts) > 1:
                parts = parts[1:]
            alias = "_" + "_".join(p.strip("_") for p in parts)
            self.module_aliases[module_name] = alias
        return alias

    def home(self, obj: Any) -> str:
        """The module a reference to ``obj`` imports."""
        return _public_module(obj) if self.public_only else str(obj.__module__)

    def core_ref(self, cls: type) -> str:
        return f"{self.module_ref(self.home(cls))}.{cls.__qualname__}"

    def wrapper_ref(self, cls: type) -> str:
        """The wrapper of core class ``cls``: generated here, or imported from its module."""
        local = self.wrapped.get(cls)
        if local is not None:
            return local
        module, name = self.external[cls]
        return f"{self.module_ref(module)}.{name}"

    def name_ref(self, obj: Any) -> str:
        module: str = self.home(obj)
        name: str = obj.__qualname__
        if module == "builtins":
            return name
        top = name.split(".")[0]
        if (
            module.startswith("j5aio")
            or top in self.wrapped.values()
            or (self.public_only and module.startswith(self.discovery.scope.modules))
        ):
            return f"{self.module_ref(module)}.{name}"
        known = self.name_imports.get(top)
        if known is not None and known != module:
            return f"{self.module_ref(module)}.{name}"
        self.name_imports[top] = module
        return name

    def typing_ref(self, name: str) -> str:
        self.used_typing.add(name)
        return name

    def typevar_ref(self, var: typing.TypeVar) -> str:
        name = self.typevars.get(var)
        if name is not None:
            return name
        bound = var.__bound__
        wrapped_bound = self.is_wrapped_class(bound)
        name = var.__name__
        while name in self.typevar_defs:
            name += "_"
        self.typevars[var] = name
        args = [f'"{name}"']
        if bound is not None:
            args.append(f'bound="{self.render(bound)}"')
        if var.__covariant__ or wrapped_bound:
            args.append("covariant=True")
        elif var.__contravariant__:
            args.append("contravariant=True")
        self.typevar_defs[name] = f"{name} = {self.typing_ref('TypeVar')}({', '.join(args)})"
        return name

    def sync_typevar_ref(self, var: typing.TypeVar) -> str:
        """The sync-side twin of ``var``: a type variable bound to the wrapper of its bound."""
        bound_class = typing.cast(type, var.__bound__)
        key = self.sync_typevars.get(bound_class)
        if key is None:  # one sync type variable per bound, however many core ones
            key = self.sync_typevars[bound_class] = _SyncVar(var)
        name = self.typevars.get(key)
        if name is not None:
            return name
        name = "Sync" + var.__name__
        while name in self.typevar_defs:
            name += "_"
        self.typevars[key] = name
        bound = self.wrapper_ref(bound_class)
        type_var = self.typing_ref("TypeVar")
        self.typevar_defs[name] = f'{name} = {type_var}("{name}", bound="{bound}")'
        return name

    def is_wrapped_class(self, obj: Any) -> bool:
        return inspect.isclass(obj) and (obj in self.wrapped or obj in self.external)

    def wrapped_typevar(self, var: Any) -> bool:
        return isinstance(var, typing.TypeVar) and self.is_wrapped_class(var.__bound__)

    # --- types --------------------------------------------------------------------

    def render(
        self,
        tp: Any,
        *,
        in_type: bool = False,
        subst: Mapping[Any, Any] | None = None,
        accept: bool = False,
    ) -> str:
        """Render annotation ``tp``; ``accept``: a ``type[C]`` also takes C's wrapper class."""
        subst = subst or {}
        if isinstance(tp, _SyncVar):
            return self.sync_typevar_ref(tp.var)
        if isinstance(tp, _Either):
            if in_type:
                return f"{self.core_ref(tp.cls)} | {self.wrapper_ref(tp.cls)}"
            return self.wrapper_ref(tp.cls)
        if tp is None or tp is _NONE_TYPE:
            return "None"
        if tp is Any:
            return self.typing_ref("Any")
        if tp is Ellipsis:
            return "..."
        if tp is typing.Generic:
            return self.typing_ref("Generic")
        if isinstance(tp, typing.TypeVar):
            if tp in subst:
                return self.render(subst[tp], in_type=in_type)
            if in_type and self.wrapped_typevar(tp):
                return self.render(tp.__bound__, in_type=True)
            return self.typevar_ref(tp)
        if isinstance(tp, list):
            return "[" + ", ".join(self.render(a, in_type=in_type, subst=subst) for a in tp) + "]"
        origin = typing.get_origin(tp)
        args = typing.get_args(tp)
        if origin is typing.Union or isinstance(tp, types.UnionType):
            return " | ".join(
                self.render(a, in_type=in_type, subst=subst, accept=accept) for a in args
            )
        if origin is typing.ClassVar:
            return self.render(args[0], in_type=in_type, subst=subst)
        if origin is typing.Literal:
            return f"{self.typing_ref('Literal')}[{', '.join(map(repr, args))}]"
        if origin is type:
            if accept and self.is_wrapped_class(args[0]):
                return f"type[{self.render(_Either(args[0]), in_type=True)}]"
            return f"type[{self.render(args[0], in_type=True, subst=subst)}]"
        if origin is not None:
            head = self.render(origin, in_type=in_type)
            if not args:
                return head
            inner = ", ".join(self.render(a, in_type=in_type, subst=subst) for a in args)
            return f"{head}[{inner}]"
        if inspect.isclass(tp):
            if self.is_wrapped_class(tp) and not in_type:
                return self.wrapper_ref(tp)
            if self.is_wrapped_class(tp):
                return self.core_ref(tp)
            if tp.__module__ == "typing":
                return self.typing_ref(tp.__name__)
            return self.name_ref(tp)
        if tp is typing.Self:
            return self.typing_ref("Self")
        raise TypeError(f"cannot render the annotation {tp!r}")

    def mentions_wrapped(self, tp: Any, *, in_type: bool = False) -> bool:
        """Whether a value of type ``tp`` may hold core objects that need wrapping."""
        if isinstance(tp, typing.TypeVar):
            return not in_type and self.wrapped_typevar(tp)
        origin = typing.get_origin(tp)
        if origin is type:
            return False
        if origin is not None:
            return self.is_wrapped_class(origin) or any(
                self.mentions_wrapped(a, in_type=in_type) for a in typing.get_args(tp)
            )
        if isinstance(tp, types.UnionType):
            return any(self.mentions_wrapped(a) for a in typing.get_args(tp))
        return self.is_wrapped_class(tp)

    def takes_wrapper_class(self, tp: Any) -> bool:
        """Whether a parameter of type ``tp`` may be given a wrapper class to unwrap."""
        if isinstance(tp, types.UnionType) or typing.get_origin(tp) is typing.Union:
            return any(self.takes_wrapper_class(a) for a in typing.get_args(tp))
        origin = typing.get_origin(tp)
        if origin is None:
            return False
        if origin is not type:  # a container (a mapping to board classes, say)
            return any(self.takes_wrapper_class(a) for a in typing.get_args(tp))
        (arg,) = typing.get_args(tp)
        return self.is_wrapped_class(arg) or self.wrapped_typevar(arg)

    def wrapped_typevars_in_types(self, tp: Any, found: set[typing.TypeVar]) -> None:
        if isinstance(tp, typing.TypeVar):
            if self.wrapped_typevar(tp):
                found.add(tp)
            return
        for arg in typing.get_args(tp):
            self.wrapped_typevars_in_types(arg, found)

    # --- values -------------------------------------------------------------------

    def render_default(self, value: Any) -> str:
        if isinstance(value, enum.Enum):
            return f"{self.name_ref(type(value))}.{value.name}"
        if value is None or isinstance(value, bool | int | str | bytes):
            return repr(value)
        if isinstance(value, float):
            return repr(value) if math.isfinite(value) else f'float("{value}")'
        if isinstance(value, tuple):
            items = [self.render_default(v) for v in value]
            return "(" + ", ".join(items) + ("," if len(items) == 1 else "") + ")"
        if isinstance(value, frozenset | set):
            items = sorted(self.render_default(v) for v in value)
            inner = "{" + ", ".join(items) + "}" if items else ""
            return f"{type(value).__name__}({inner})"
        raise TypeError(f"cannot render the default value {value!r}")


def _docstring(doc: str | None, indent: str, fallback: str) -> list[str]:
    text = (doc or fallback).strip()
    quote = '"""'
    prefix = "r" if "\\" in text else ""
    text = text.replace('"""', '\\"\\"\\"')
    lines = text.splitlines()
    if len(lines) == 1:
        return [f"{indent}{prefix}{quote}{lines[0]}{quote}"]
    body = [f"{indent}{prefix}{quote}{lines[0]}"]
    body += [f"{indent}{line}".rstrip() for line in lines[1:]]
    body.append(f"{indent}{quote}")
    return body


def _is_coroutine_function(obj: Any) -> bool:
    return inspect.iscoroutinefunction(obj) or inspect.iscoroutinefunction(
        getattr(obj, "__wrapped__", None),
    )


def _required_params(func: Callable[..., Any]) -> list[inspect.Parameter]:
    params = list(inspect.signature(func).parameters.values())[1:]
    return [
        p
        for p in params
        if p.default is p.empty and p.kind not in (p.VAR_POSITIONAL, p.VAR_KEYWORD)
    ]


def _getter_property_name(name: str, func: Any) -> str | None:
    if (
        inspect.isfunction(func)
        and name.startswith("get_")
        and name.isidentifier()
        and _is_coroutine_function(func)
        and not _required_params(func)
    ):
        return name[4:]
    return None


def _is_setter(func: Any) -> bool:
    if not (inspect.isfunction(func) and _is_coroutine_function(func)):
        return False
    params = list(inspect.signature(func).parameters.values())[1:]
    positional = [p for p in params if p.kind in (p.POSITIONAL_ONLY, p.POSITIONAL_OR_KEYWORD)]
    return len(_required_params(func)) == 1 and len(positional) >= 1


class _ClassWriter:
    """Writes the wrapper class of one core class."""

    def __init__(self, renderer: _Renderer, cls: Any) -> None:
        self.r = renderer
        self.cls = cls
        self.module = cls.__module__

    # --- helpers ------------------------------------------------------------------

    def hints(self, obj: Any) -> dict[str, Any]:
        return self.r.namespace.hints(obj, getattr(obj, "__module__", None) or self.module)

    def signature(
        self,
        func: Callable[..., Any],
        *,
        skip_first: bool,
        subst: Mapping[Any, Any] | None = None,
        drop_params: bool = False,
    ) -> tuple[list[str], list[str], Any]:
        """Return (parameter declarations, call arguments, return annotation)."""
        sig = inspect.signature(func)
        hints = self.hints(func)
        decls: list[str] = []
        call: list[str] = []
        params = list(sig.parameters.values())
        if skip_first:
            params = params[1:]
        star_done = False
        saw_positional_only = False
        for param in params:
            if param.kind is param.POSITIONAL_ONLY:
                saw_positional_only = True
            elif saw_positional_only:
                decls.append("/")
                saw_positional_only = False
            annotation = hints.get(param.name, Any)
            rendered = self.r.render(annotation, subst=subst, accept=True)
            text = f"{param.name}: {rendered}"
            if param.default is not param.empty:
                text += f" = {self.r.render_default(param.default)}"
            value = param.name
            if self.r.mentions_wrapped(annotation) or self.r.takes_wrapper_class(annotation):
                value = f"_unwrap({param.name})"
            if param.kind is param.VAR_POSITIONAL:
                decls.append(f"*{param.name}: {rendered}")
                call.append(f"*{value}")
                star_done = True
            elif param.kind is param.VAR_KEYWORD:
                decls.append(f"**{param.name}: {rendered}")
                call.append(f"**{value}")
            elif param.kind is param.KEYWORD_ONLY:
                if not star_done:
                    decls.append("*")
                    star_done = True
                decls.append(text)
                call.append(f"{param.name}={value}")
            else:
                decls.append(text)
                call.append(value)
        if saw_positional_only:
            decls.append("/")
        return decls, call, hints.get("return", Any)

    def def_line(self, indent: str, name: str, params: list[str], returns: str) -> list[str]:
        one = f"{indent}def {name}({', '.join(params)}) -> {returns}:"
        if len(one) <= LINE_LENGTH:
            return [one]
        lines = [f"{indent}def {name}("]
        lines += [f"{indent}    {p}," for p in params]
        lines.append(f"{indent}) -> {returns}:")
        return lines

    def result_expr(self, expr: str, returns: Any, subst: Mapping[Any, Any] | None) -> str:
        if self.r.mentions_wrapped(returns):
            rendered = self.r.render(returns, subst=subst)
            return f'{self.r.typing_ref("cast")}("{rendered}", _wrap({expr}))'
        return expr

    def body_line(self, indent: str, expr: str, returns: Any) -> str:
        if returns is None or returns is _NONE_TYPE:
            return f"{indent}{expr}"
        return f"{indent}return {expr}"

    def wrapped_typevar_choices(self, var: typing.TypeVar) -> list[type]:
        bound: type = var.__bound__  # type: ignore[assignment]
        choices = [c for c in self.r.wrapped if issubclass(c, bound) and c is not bound]
        return sorted(choices, key=lambda c: (-len(c.__mro__), c.__name__))

    # --- members ------------------------------------------------------------------

    def function(
        self,
        name: str,
        func: Callable[..., Any],
        *,
        kind: str,
        is_coroutine: bool,
        doc_source: Any,
    ) -> list[str]:
        """A method, static method or class method."""
        skip_first = kind != "static"
        first = {"instance": ["self"], "class": ["cls"], "static": []}[kind]
        target = {
            "instance": f"self._core.{name}",
            "class": f"{self.r.core_ref(self.cls)}.{name}",
            "static": f"{self.r.core_ref(self.cls)}.{name}",
        }[kind]
        decorator = {"instance": [], "class": ["@classmethod"], "static": ["@staticmethod"]}[
            kind
        ]
        hints = self.hints(func)
        found: set[typing.TypeVar] = set()
        for key, annotation in hints.items():
            if key != "return":
                self.r.wrapped_typevars_in_types(annotation, found)
        lines: list[str] = []
        doc = _docstring(inspect.getdoc(doc_source), "        ", f"Call ``{name}``.")
        if found:
            variables = sorted(found, key=lambda v: v.__name__)
            if len(variables) != 1:
                raise TypeError(f"{self.cls.__name__}.{name}: several wrapped type variables")
            var = variables[0]
            # Generic in the sync class first, then one overload per core class generated
            # here, then the bound's core class for any other core class.
            bound = typing.cast(type, var.__bound__)
            choices: list[Any] = [
                _SyncVar(var), *self.wrapped_typevar_choices(var), bound,
            ]
            for choice in choices:
                decls, _call, returns = self.signature(
                    func, skip_first=skip_first, subst={var: choice},
                )
                lines.append(f"    @{self.r.typing_ref('overload')}")
                lines += [f"    {d}" for d in decorator]
                lines += self.def_line(
                    "    ", name, first + decls, self.r.render(returns, subst={var: choice}),
                )
                lines.append("        ...")
                lines.append("")
            subst: dict[Any, Any] = {var: _Either(bound)}
        else:
            subst = {}
        decls, call, returns = self.signature(func, skip_first=skip_first, subst=subst)
        expr = f"{target}({', '.join(call)})"
        if is_coroutine:
            expr = f"_call({', '.join([target, *call])})"
        lines += [f"    {d}" for d in decorator]
        lines += self.def_line("    ", name, first + decls, self.r.render(returns, subst=subst))
        lines += doc
        lines.append(self.body_line("        ", self.result_expr(expr, returns, subst), returns))
        return lines

    def property_lines(self, name: str, returns: Any, doc: str, expr: str) -> list[str]:
        """A read-only property ``name`` returning ``expr`` (wrapped if it must be)."""
        lines = ["    @property"]
        lines += self.def_line("    ", name, ["self"], self.r.render(returns))
        lines += _docstring(doc, "        ", "")
        lines.append(f"        return {self.result_expr(expr, returns, None)}")
        return lines

    def setter_lines(self, name: str, function: Any, value_name: str, body: str) -> list[str]:
        """The setter of property ``name``; ``body`` is formatted with the (unwrapped) value."""
        annotation = self.hints(function).get(value_name, Any)
        value = f"_unwrap({value_name})" if self.r.mentions_wrapped(annotation) else value_name
        lines = ["", f"    @{name}.setter"]
        lines += self.def_line(
            "    ", name, ["self", f"{value_name}: {self.r.render(annotation)}"], "None",
        )
        lines.append("        " + body.format(value=value))
        return lines

    def module_function(self, func: Callable[..., Any]) -> list[str] | None:
        """A module-level function, if its signature mentions a wrapped class."""
        hints = self.hints(func)
        if not any(self.r.mentions_wrapped(h) for h in hints.values()):
            return None
        decls, call, returns = self.signature(func, skip_first=False)
        target = f"{self.r.module_ref(func.__module__)}.{func.__name__}"
        expr = f"{target}({', '.join(call)})"
        if _is_coroutine_function(func):
            expr = f"_call({', '.join([target, *call])})"
        lines = self.def_line("", func.__name__, decls, self.r.render(returns))
        lines += _docstring(inspect.getdoc(func), "    ", f"Call ``{func.__name__}``.")
        lines.append(self.body_line("    ", self.result_expr(expr, returns, None), returns))
        return lines

    def getter_property(self, prop: str, getter: Any, setter: Any | None) -> list[str]:
        returns = self.hints(getter).get("return", Any)
        doc = inspect.getdoc(getter) or f"The {prop}."
        setter_doc = inspect.getdoc(setter) if setter is not None else None
        if setter_doc:
            doc += "\n\nSetting it: " + setter_doc
        lines = self.property_lines(prop, returns, doc, f"_call(self._core.get_{prop})")
        if setter is not None:
            value_name = _required_params(setter)[0].name
            body = f"_call(self._core.set_{prop}, {{value}})"
            lines += self.setter_lines(prop, setter, value_name, body)
        return lines

    def plain_property(self, name: str, prop: property) -> list[str]:
        returns = self.hints(prop.fget).get("return", Any)
        doc = inspect.getdoc(prop) or f"The {name}."
        lines = self.property_lines(name, returns, doc, f"self._core.{name}")
        if prop.fset is not None:
            value_name = list(inspect.signature(prop.fset).parameters)[1]
            body = f"self._core.{name} = {{value}}"
            lines += self.setter_lines(name, prop.fset, value_name, body)
        return lines

    def instance_attribute(self, name: str, annotation: Any) -> list[str]:
        doc = f"The ``{name}`` of the wrapped object."
        return self.property_lines(name, annotation, doc, f"self._core.{name}")

    def class_constant(self, name: str, annotation: Any) -> list[str]:
        rendered = self.r.render(annotation)
        ref = f"{self.r.core_ref(self.cls)}.{name}"
        return [f"    {name}: {self.r.typing_ref('ClassVar')}[{rendered}] = {ref}"]

    def class_annotations(self) -> dict[str, Any]:
        annotations: dict[str, Any] = {}
        for klass in reversed(self.cls.__mro__):
            own = inspect.get_annotations(klass)
            if not own or klass.__module__ not in sys.modules:
                continue
            namespace = self.r.namespace.module_namespace(klass.__module__)
            for key, value in own.items():
                try:
                    annotations[key] = eval(value, namespace) if isinstance(value, str) else value
                except NameError:
                    continue
        return annotations

    def init_attributes(self) -> dict[str, Any]:
        """Public attributes that ``__init__`` assigns, with their types."""
        init = self.cls.__dict__.get("__init__")
        if init is None:
            return {}
        try:
            tree = ast.parse(textwrap.dedent(inspect.getsource(init)))
        except (OSError, TypeError):  # pragma: no cover - source always available here
            return {}
        param_hints = self.hints(init)
        found: dict[str, Any] = {}
        module_ns = self.r.namespace.module_namespace(self.module)
        for node in ast.walk(tree):
            if isinstance(node, ast.AnnAssign):
                target = node.target
                if (
                    isinstance(target, ast.Attribute)
                    and isinstance(target.value, ast.Name)
                    and target.value.id == "self"
                    and not target.attr.startswith("_")
                ):
                    found[target.attr] = eval(  # our own annotations, from our own source
                        ast.unparse(node.annotation), module_ns,
                    )
            elif isinstance(node, ast.Assign) and len(node.targets) == 1:
                assigned = node.targets[0]
                if (
                    isinstance(assigned, ast.Attribute)
                    and isinstance(assigned.value, ast.Name)
                    and assigned.value.id == "self"
                    and not assigned.attr.startswith("_")
                    and isinstance(node.value, ast.Name)
                    and node.value.id in param_hints
                ):
                    found[assigned.attr] = param_hints[node.value.id]
        return found

    # --- the class ----------------------------------------------------------------

    def bases(self) -> list[str]:
        bases: list[str] = []
        for base in self.cls.__dict__.get("__orig_bases__", self.cls.__bases__):
            origin = typing.get_origin(base) or base
            if (
                self.r.is_wrapped_class(origin)
                or origin is typing.Generic
                or getattr(origin, "__module__", "") == "collections.abc"
            ):
                bases.append(self.r.render(base))
        if not any(
            self.r.is_wrapped_class(typing.get_origin(b) or b)
            for b in self.cls.__dict__.get("__orig_bases__", self.cls.__bases__)
        ):
            bases.insert(0, "_SyncWrapper")
        return bases

    def core_annotation(self) -> str:
        params = getattr(self.cls, "__parameters__", ())
        ref = self.r.core_ref(self.cls)
        if params:
            ref += "[" + ", ".join(self.r.typing_ref("Any") for _ in params) + "]"
        return ref

    def members(self) -> list[_Member]:
        cls = self.cls
        own = cls.__dict__
        members: list[_Member] = []
        done: set[str] = set()
        names = [n for n in own if not n.startswith("_") or n in FORWARDED_DUNDERS]

        properties: dict[str, tuple[Any, Any]] = {}
        for name in names:
            raw = own[name]
            if (
                name.startswith(("get_", "set_"))
                and inspect.isfunction(raw)
                and _is_coroutine_function(raw)
            ):
                prop = name[4:]
                getter = inspect.getattr_static(cls, f"get_{prop}", None)
                setter = inspect.getattr_static(cls, f"set_{prop}", None)
                if _getter_property_name(f"get_{prop}", getter) is None:
                    continue
                if setter is not None and not _is_setter(setter):
                    setter = None
                if inspect.getattr_static(cls, prop, None) is not None:
                    continue  # an attribute of that name exists: keep the methods
                properties[prop] = (getter, setter)
                done.add(f"get_{prop}")
                if setter is not None:
                    done.add(f"set_{prop}")
        for prop, (getter, setter) in properties.items():
            members.append(_Member(prop, "\n".join(self.getter_property(prop, getter, setter))))

        annotations = self.class_annotations()
        for name in names:
            if name in done:
                continue
            raw = own[name]
            if isinstance(raw, staticmethod | classmethod):
                func = raw.__func__
                kind = "static" if isinstance(raw, staticmethod) else "class"
                code = self.function(
                    name,
                    func,
                    kind=kind,
                    is_coroutine=_is_coroutine_function(func),
                    doc_source=getattr(cls, name),
                )
            elif isinstance(raw, property):
                code = self.plain_property(name, raw)
            elif inspect.isfunction(raw):
                code = self.function(
                    name,
                    raw,
                    kind="instance",
                    is_coroutine=_is_coroutine_function(raw),
                    doc_source=getattr(cls, name),
                )
            elif inspect.isclass(raw):
                code = [f"    {name} = {self.r.core_ref(cls)}.{name}"]
            elif name in annotations:
                if self.r.mentions_wrapped(annotations[name]):
                    continue
                code = self.class_constant(name, annotations[name])
            elif isinstance(raw, bool | int | float | str):
                code = self.class_constant(name, type(raw))
            else:
                continue
            members.append(_Member(name, "\n".join(code)))
        attributes = {**self.declared_attributes(), **self.init_attributes()}
        for name, annotation in attributes.items():
            if name not in own:
                members.append(_Member(name, "\n".join(self.instance_attribute(name, annotation))))
        return members

    def declared_attributes(self) -> dict[str, Any]:
        """Public instance attributes the class body declares (``power_board: PowerBoard``)."""
        own = inspect.get_annotations(self.cls)
        namespace = self.r.namespace.module_namespace(self.module)
        found: dict[str, Any] = {}
        for name, value in own.items():
            if name.startswith("_") or name in self.cls.__dict__:
                continue
            annotation = eval(value, namespace) if isinstance(value, str) else value
            if typing.get_origin(annotation) is not typing.ClassVar:
                found[name] = annotation
        return found

    def constructor(self) -> list[str]:
        cls = self.cls
        if "__new__" in cls.__dict__:
            return [
                f"    def __new__(cls, *args: {self.r.typing_ref('Any')}, "
                f"**kwargs: Any) -> {self.r.typing_ref('Self')}:",
                f"        return _adopt(cls, {self.r.core_ref(cls)}())",
            ]
        init = cls.__dict__.get("__init__")
        parameters: tuple[Any, ...] = getattr(cls, "__parameters__", ())
        if (
            init is None
            or inspect.isabstract(cls)
            or any(self.r.wrapped_typevar(p) for p in parameters)
        ):
            return []
        decls, call, _ = self.signature(init, skip_first=True)
        if any("__new__" in base.__dict__ for base in cls.__mro__[1:] if base in self.r.wrapped):
            return self.robot_constructor(decls, call)
        lines = self.def_line("    ", "__init__", ["self", *decls], "None")
        lines.append(f"        _adopt_into(self, {self.r.core_ref(cls)}({', '.join(call)}))")
        return lines

    def robot_constructor(self, decls: list[str], call: list[str]) -> list[str]:
        """``__new__`` of a robot that finds its own boards, as j5's robots do on creation.

        A base's ``__new__`` (the robot lock) must not run as well, and a subclass written
        by a student may take arguments of its own (for its ``__init__``): they are let by.
        Its ``setup`` runs at once, then ``after_setup`` (what ``async with`` does next: the
        robot service, the watch for the start, ``wait_for_start``); if either fails, the
        robot gives up its lock.
        """
        any_ = self.r.typing_ref("Any")
        keywords = [d for d in decls if d not in ("*", "/") and not d.startswith("*")]
        params = ["cls", f"*args: {any_}", *keywords, f"**kwargs: {any_}"]
        keyword_call = [c if "=" in c else f"{c.split('(')[-1].rstrip(')')}={c}" for c in call]
        lines = self.def_line("    ", "__new__", params, self.r.typing_ref("Self"))
        lines += [
            f"        robot = _adopt(cls, {self.r.core_ref(self.cls)}({', '.join(keyword_call)}))",
            "        try:",
            "            _call(robot._core.setup)",
            "            _call(robot._core.after_setup)",
            "        except BaseException:",
            "            robot._core.release_lock()",
            "            raise",
            "        return robot",
        ]
        return lines

    def write(self, inherited: Mapping[str, str]) -> tuple[list[str], dict[str, str]]:
        cls = self.cls
        name = self.r.wrapped[cls]
        lines = [f"class {name}({', '.join(self.bases())}):"]
        lines += _docstring(inspect.getdoc(cls), "    ", f"The sync face of {cls.__name__}.")
        lines.append("")
        lines.append("    __slots__ = ()")
        lines.append("")
        lines.append(f"    _core: {self.core_annotation()}")
        constructor = self.constructor()
        if constructor:
            lines.append("")
            lines += constructor
        table = dict(inherited)
        for member in self.members():
            if table.get(member.name) == member.code:
                continue
            table[member.name] = member.code
            lines.append("")
            lines += member.code.splitlines()
        return lines, table


# --------------------------------------------------------------------------- module


_CORE_HEADER = '''"""The sync facade's wrapper classes. GENERATED by j5aio.syncgen: do not edit.

Regenerate with ``python tools/gen_sync.py`` whenever a public async class changes; a test
fails while this file is stale. Every wrapper holds one core object and calls it through
the portal (:func:`j5aio.sync.wrapping.call`); no wrapper contains logic of its own.
"""
'''

_KIT_HEADER = '''"""The sync facade of {modules}. GENERATED by j5aio's generator: do not edit.

Regenerate with ``python -m j5aio sync-gen {modules} -o <this file>`` whenever a
public async class changes; ``--check`` fails while this file is stale. Every wrapper holds
one core object and calls it through j5aio's portal; no wrapper contains logic of its own.
"""
'''


def render_module(
    discovery: Discovery, external: Mapping[type, tuple[str, str]] | None = None,
) -> str:
    """Return the source of the generated module for ``discovery``.

    :param external: core class -> (module, name) of wrappers that exist already
        (see :func:`existing_wrappers`); classes of ``discovery`` are generated afresh.
    """
    renderer = _Renderer(discovery, external)
    bodies: list[str] = []
    tables: dict[type, dict[str, str]] = {}
    for cls in discovery.classes:
        inherited: dict[str, str] = {}
        for base in reversed(cls.__mro__[1:]):
            inherited.update(tables.get(base, {}))
        lines, table = _ClassWriter(renderer, cls).write(inherited)
        tables[cls] = table
        bodies.append("\n".join(lines))

    registrations = [
        f"_register({renderer.core_ref(cls)}, {renderer.wrapped[cls]})"
        for cls in discovery.classes
    ]
    # Environment constants are made on first use (their core twins import every
    # backend): a module ``__getattr__`` that type checkers do not see, and declarations
    # that they do.
    environment_decls: list[str] = []
    environment_lines: list[str] = []
    for name, (module, attribute) in discovery.environments.items():
        ref = f"{renderer.module_ref(module)}.{attribute}"
        environment_decls.append(f"    {name}: Environment")
        environment_decls.append(f'    """The sync face of ``{module}.{attribute}``."""')
        keyword = "elif" if environment_lines else "if"
        environment_lines.append(f'        {keyword} name == "{name}":')
        environment_lines.append(f"            core = {ref}")
    functions: list[str] = []
    function_names: list[str] = []
    for func in discovery.functions:
        function_lines = _ClassWriter(renderer, func).module_function(func)
        if function_lines is not None:
            functions.append("\n".join(function_lines))
            function_names.append(func.__name__)
    if discovery.environments:
        renderer.used_typing.update({"Any", "cast"})

    exported = sorted(
        [*renderer.wrapped.values(), *discovery.environments, *function_names],
        key=lambda n: (0 if n.isupper() else 1 if n[0].isupper() else 2, n),
    )
    if discovery.scope.is_core:
        header = _CORE_HEADER
    else:
        header = _KIT_HEADER.format(modules=" ".join(discovery.scope.modules))
    # In j5aio's own facade only the modules of the wrapped classes are imported with the
    # module (registering a wrapper needs its core class); the others, used by the
    # wrappers' methods and types alone, are imported when first used. A kit's module
    # imports them all, through public names only.
    eager = {renderer.module_ref(renderer.home(cls)) for cls in discovery.classes}
    lazy = {
        alias: module
        for module, alias in sorted(renderer.module_aliases.items())
        if alias not in eager and discovery.scope.is_core
    }
    if lazy or environment_decls:
        renderer.used_typing.add("TYPE_CHECKING")
    future = "from __future__ import annotations"
    out = [header.rstrip("\n"), "", future, ""]
    by_module: dict[str, set[str]] = {}
    if renderer.used_typing:
        by_module["typing"] = set(renderer.used_typing)
    for name, module in renderer.name_imports.items():
        by_module.setdefault(module, set()).add(name)
    for module, names in sorted(by_module.items()):
        ordered = sorted(names, key=lambda n: (0 if n.isupper() else 1 if n[0].isupper() else 2, n))
        out.append(f"from {module} import {', '.join(ordered)}")
    out.append("")
    for module, alias in sorted(renderer.module_aliases.items()):
        if alias not in lazy:
            out.append(f"import {module} as {alias}")
    if lazy:
        out.append("from j5aio._lazy import lazy_modules as _lazy_modules")
    used = "\n".join([*bodies, *functions, *environment_lines])
    for name in ("SyncWrapper", "adopt", "adopt_into", "call", "register", "unwrap", "wrap"):
        if name == "register" or re.search(rf"\b_{name}\b", used):
            out.append(f"from j5aio.sync.wrapping import {name} as _{name}")
    out.append("")
    if lazy or environment_decls:
        out.append("if TYPE_CHECKING:")
        out += [f"    import {module} as {alias}" for alias, module in lazy.items()]
        out += environment_decls
        if lazy:
            out.append("else:")
            out.append("    _lazy_modules(globals(), {")
            out += [f'        "{alias}": "{module}",' for alias, module in lazy.items()]
            out.append("    })")
        out.append("")
    out.append("__all__ = [")
    out += [f'    "{name}",' for name in exported]
    out.append("]")
    out.append("")
    out += list(renderer.typevar_defs.values())
    for body in bodies:
        out.append("")
        out.append("")
        out.append(body)
    for body in functions:
        out.append("")
        out.append("")
        out.append(body)
    out.append("")
    out.append("")
    out += registrations
    if environment_lines:
        out += [
            "",
            "",
            "if not TYPE_CHECKING:",
            "",
            "    def __getattr__(name: str) -> Any:",
            '        """Make the sync face of an environment when it is first used."""',
            *environment_lines,
            "        else:",
            '            raise AttributeError(f"module {__name__!r} has no attribute {name!r}")',
            '        value = cast("Environment", _wrap(core))',
            "        globals()[name] = value",
            "        return value",
        ]
    source = re.sub(r"\n{4,}", "\n\n\n", "\n".join(out) + "\n")
    # A kit's linter settings are unknown (line length, import sections): its generated
    # module is exempt from ruff as a whole; mypy --strict checks it all the same.
    noqa = "" if discovery.scope.is_core else "# ruff: noqa"
    if not noqa and any(len(line) > LINE_LENGTH for line in source.splitlines()):
        noqa = "# ruff: noqa: E501"
    if noqa:
        source = source.replace(f"\n\n{future}\n", f"\n\n{noqa}\n\n{future}\n", 1)
    return source


def generate(modules: Sequence[str] | None = None) -> str:
    """Return the source of the sync module of ``modules`` (j5aio's own facade by default).

    :param modules: the modules (or packages) holding a kit's boards and components.
    :raises ImportError: a module cannot be imported.
    """
    if modules is None:
        return render_module(discover(CORE_SCOPE))
    discovery = discover(Scope(modules=tuple(modules)))
    if not discovery.classes:
        raise ValueError(
            f"found no board or component classes to wrap in {', '.join(modules)}: name the "
            "modules that define them",
        )
    return render_module(discovery, existing_wrappers(skip=discovery.classes))


def check_or_write(source: str, output: Path, *, check: bool, command: str) -> int:
    """Write ``source`` to ``output`` if it differs; with ``check``, only compare.

    :param command: how to regenerate, for the message when ``output`` is stale.
    :returns: the exit status: 1 if ``check`` found ``output`` stale, else 0.
    """
    current = output.read_text(encoding="utf-8") if output.exists() else None
    if check:
        if current != source:
            print(f"{output} is stale: run {command}", file=sys.stderr)
            return 1
        print(f"{output} is up to date")
        return 0
    if current != source:
        output.write_text(source, encoding="utf-8")
        print(f"wrote {output}")
    else:
        print(f"{output} is up to date")
    return 0


def add_arguments(parser: argparse.ArgumentParser) -> None:
    """Add the options of ``python -m j5aio sync-gen`` to ``parser``."""
    parser.add_argument(
        "modules",
        nargs="+",
        metavar="MODULE",
        help="the modules (or packages) that define the kit's boards and components, "
        "e.g. beekit.boards",
    )
    parser.add_argument(
        "-o",
        "--output",
        type=Path,
        required=True,
        help="the file to write, e.g. beekit/sync.py",
    )
    parser.add_argument(
        "--check",
        action="store_true",
        help="write nothing; exit with status 1 if the file is missing or stale (for CI)",
    )


def run(options: argparse.Namespace) -> int:
    """Run ``sync-gen`` with parsed ``options`` (see :func:`add_arguments`)."""
    modules: list[str] = list(options.modules)
    command = f"python -m j5aio sync-gen {' '.join(modules)} -o {options.output}"
    try:
        source = generate(modules)
    except (ImportError, ValueError) as exc:
        print(f"sync-gen: {exc}", file=sys.stderr)
        return 2
    return check_or_write(source, options.output, check=options.check, command=command)


def main(argv: Sequence[str] | None = None) -> int:
    """The command line ``python -m j5aio.syncgen MODULE... -o FILE [--check]``."""
    parser = argparse.ArgumentParser(
        prog="python -m j5aio sync-gen",
        description="Generate the typed sync facade of a kit's boards and components.",
    )
    add_arguments(parser)
    return run(parser.parse_args(argv))


if __name__ == "__main__":
    raise SystemExit(main())
