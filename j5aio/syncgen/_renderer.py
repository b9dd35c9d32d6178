"""Writing type annotations and default values as source, and which names that needs imported."""

from __future__ import annotations

import enum
import inspect
import math
import types
import typing
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any

from j5aio.syncgen._discovery import Discovery, _public_module
from j5aio.syncgen._namespace import _Namespace
from j5aio.syncgen._scope import _NONE_TYPE

__all__ = []

#: Foreign names j5aio's own facade imports from a j5aio module that gives the same object
#: for less: the facade then loads nothing its core does not (see :mod:`j5aio._timedelta`).
_LIGHTER_HOMES = {"datetime.timedelta": "j5aio._timedelta"}

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
        facade: Sequence[type] | None = None,
        *,
        external_by_name: bool = False,
    ) -> None:
        """Render for the classes of ``discovery``.

        :param external: core class -> (module, name) of wrappers defined elsewhere.
        :param facade: every class of the facade being generated, when it is written as
            several modules (``discovery`` holding those of one); the classes of
            ``discovery`` by default.
        :param external_by_name: refer to the wrappers of ``external`` by their names,
            imported from their modules (:attr:`wrapper_imports`), rather than through
            their modules: the other modules of a facade written as several.
        """
        self.discovery = discovery
        self.public_only = not discovery.scope.is_core
        self.wrapped: dict[type, str] = {}
        for cls in discovery.classes:
            if cls.__name__ in self.wrapped.values():
                raise RuntimeError(f"two wrapped classes are called {cls.__name__}")
            self.wrapped[cls] = cls.__name__
        self.external = {k: v for k, v in (external or {}).items() if k not in self.wrapped}
        self.facade: list[type] = list(discovery.classes if facade is None else facade)
        self.external_by_name = external_by_name
        self.wrapper_imports: dict[str, str] = {}
        """Name -> module of each wrapper of ``external`` referred to by name."""
        self.module_aliases: dict[str, str] = {}
        self.name_imports: dict[str, str] = {}  # name -> module
        self.typevars: dict[typing.TypeVar | _SyncVar, str] = {}
        self.sync_typevars: dict[type, _SyncVar] = {}
        self.typevar_defs: dict[str, str] = {}
        self.namespace = _Namespace()
        self.used_typing: set[str] = set()
        self.exported: list[str] = []
        """The public names of the module written (once it is)."""

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
        if self.external_by_name:
            self.wrapper_imports[name] = module
            return name
        return f"{self.module_ref(module)}.{name}"

    @property
    def external_names(self) -> set[str]:
        """The names of the wrappers of ``external``."""
        return {name for _, name in self.external.values()}

    def name_ref(self, obj: Any) -> str:
        module: str = self.home(obj)
        name: str = obj.__qualname__
        if module == "builtins":
            return name
        top = name.split(".")[0]
        if (
            module.startswith("j5aio")
            or top in self.wrapped.values()
            or (self.external_by_name and top in self.external_names)
            or (self.public_only and module.startswith(self.discovery.scope.modules))
        ):
            return f"{self.module_ref(module)}.{name}"
        if self.discovery.scope.is_core:
            module = _LIGHTER_HOMES.get(f"{module}.{name}", module)
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
