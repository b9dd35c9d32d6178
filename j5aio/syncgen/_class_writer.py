"""Writing the wrapper class of one core class."""

from __future__ import annotations

import ast
import inspect
import math
import sys
import textwrap
import typing
from collections.abc import Callable, Mapping
from typing import Any

from j5aio.syncgen._members import (
    _docstring,
    _getter_property_name,
    _is_coroutine_function,
    _is_setter,
    _required_params,
)
from j5aio.syncgen._namespace import evaluate
from j5aio.syncgen._renderer import _Either, _Member, _Renderer, _SyncVar
from j5aio.syncgen._scope import _NONE_TYPE, FORWARDED_DUNDERS, LINE_LENGTH

__all__ = []


def _is_plain_literal(value: object) -> bool:
    """Whether ``repr(value)`` is Python source for an equal value.

    That is a bool, int, finite float, str or None, a range, or a tuple of such.
    """
    if value is None or type(value) in (bool, int, str, range):
        return True
    if type(value) is float:
        return math.isfinite(value)
    return type(value) is tuple and all(_is_plain_literal(item) for item in value)


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
        choices = [c for c in self.r.facade if issubclass(c, bound) and c is not bound]
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
        decorator = {"instance": [], "class": ["@classmethod"], "static": ["@staticmethod"]}[kind]
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
                _SyncVar(var),
                *self.wrapped_typevar_choices(var),
                bound,
            ]
            # The overloads are for type checkers alone: at run time the class would only
            # make (and the typing module record) a function per board class at import.
            lines.append(f"    if {self.r.typing_ref('TYPE_CHECKING')}:")
            for choice in choices:
                decls, _call, returns = self.signature(
                    func,
                    skip_first=skip_first,
                    subst={var: choice},
                )
                lines.append(f"        @{self.r.typing_ref('overload')}")
                lines += [f"        {d}" for d in decorator]
                lines += self.def_line(
                    "        ",
                    name,
                    first + decls,
                    self.r.render(returns, subst={var: choice}),
                )
                lines.append("            ...")
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

    def property_lines(
        self,
        name: str,
        returns: Any,
        doc: str,
        expr: str,
        *,
        kept: bool = False,
    ) -> list[str]:
        """A read-only property ``name`` returning ``expr`` (wrapped if it must be).

        With ``kept``, ``expr`` reads an attribute of the core object, and the sync face
        of a fixed collection it gives is kept by the wrapper (``wrap_kept``).
        """
        lines = ["    @property"]
        lines += self.def_line("    ", name, ["self"], self.r.render(returns))
        lines += _docstring(doc, "        ", "")
        result = self.result_expr(expr, returns, None)
        if kept and result != expr:
            result = result.replace(f"_wrap({expr})", f'_wrap_kept(self, "{name}", {expr})')
        lines.append(f"        return {result}")
        return lines

    def setter_lines(self, name: str, function: Any, value_name: str, body: str) -> list[str]:
        """The setter of property ``name``; ``body`` is formatted with the (unwrapped) value."""
        annotation = self.hints(function).get(value_name, Any)
        value = f"_unwrap({value_name})" if self.r.mentions_wrapped(annotation) else value_name
        lines = ["", f"    @{name}.setter"]
        lines += self.def_line(
            "    ",
            name,
            ["self", f"{value_name}: {self.r.render(annotation)}"],
            "None",
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
        lines = self.property_lines(name, returns, doc, f"self._core.{name}", kept=True)
        if prop.fset is not None:
            value_name = list(inspect.signature(prop.fset).parameters)[1]
            body = f"self._core.{name} = {{value}}"
            lines += self.setter_lines(name, prop.fset, value_name, body)
        return lines

    def instance_attribute(self, name: str, annotation: Any) -> list[str]:
        doc = f"The ``{name}`` of the wrapped object."
        return self.property_lines(name, annotation, doc, f"self._core.{name}", kept=True)

    def class_constant(self, name: str, annotation: Any) -> list[str]:
        rendered = self.r.render(annotation)
        value = getattr(self.cls, name)
        if self.r.discovery.scope.is_core and _is_plain_literal(value):
            # Written out (a test fails when it changes): defining the wrapper does not
            # import the core module for it (see ``render_module``).
            ref = repr(value)
        else:
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
                    annotations[key] = (
                        evaluate(value, namespace) if isinstance(value, str) else value
                    )
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
                    found[target.attr] = evaluate(ast.unparse(node.annotation), module_ns)
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
                bases.append(self._base(base))
        if not any(
            self.r.is_wrapped_class(typing.get_origin(b) or b)
            for b in self.cls.__dict__.get("__orig_bases__", self.cls.__bases__)
        ):
            bases.insert(0, "_SyncWrapper")
        return bases

    def _base(self, base: Any) -> str:
        """Render a base class; in j5aio's facade, a core class as a type argument is quoted.

        ``IdentifiedComponent["_components_fan.FanInterface"]``: type checkers read it as
        ever, and defining the class does not import the core module (see
        ``render_module``).
        """
        origin, args = typing.get_origin(base), typing.get_args(base)
        if not self.r.discovery.scope.is_core or origin is None or not args:
            return self.r.render(base)
        rendered = [
            self.r.render(arg) if isinstance(arg, typing.TypeVar) else f'"{self.r.render(arg)}"'
            for arg in args
        ]
        return f"{self.r.render(origin)}[{', '.join(rendered)}]"

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
            annotation = evaluate(value, namespace) if isinstance(value, str) else value
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
        facade = self.r.facade
        if any("__new__" in base.__dict__ for base in cls.__mro__[1:] if base in facade):
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
