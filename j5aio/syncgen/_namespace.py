"""Resolving annotations, including the names a module imports only for type checkers."""

from __future__ import annotations

import ast
import importlib
import importlib.util
import inspect
import sys
import types
import typing
from typing import Any

__all__ = ["evaluate"]

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
    """Import what a module's ``if TYPE_CHECKING:`` blocks import; return the names bound."""
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
            for statement in node.body:
                if isinstance(statement, ast.Import):
                    _bind_import(statement, namespace)
                elif isinstance(statement, ast.ImportFrom):
                    _bind_import_from(statement, module, namespace)
                elif isinstance(statement, ast.Assign | ast.AnnAssign):
                    _bind_assigned(statement, module, namespace)
    return namespace


def _bind_assigned(
    statement: ast.Assign | ast.AnnAssign,
    module: types.ModuleType,
    namespace: dict[str, Any],
) -> None:
    """Bind a name assigned for type checkers that the module gives at run time on demand.

    An alias a module makes only when it is first looked up (PEP 562's ``__getattr__``;
    ``Duration`` and ``Pitch`` of :mod:`j5aio.components.piezo`) is written for type
    checkers as a plain assignment; looking it up makes it.
    """
    targets = statement.targets if isinstance(statement, ast.Assign) else [statement.target]
    for target in targets:
        if isinstance(target, ast.Name) and hasattr(module, target.id):  # (else: types only)
            namespace[target.id] = getattr(module, target.id)


def _bind_import(statement: ast.Import, namespace: dict[str, Any]) -> None:
    """Bind the names of ``import a.b`` / ``import a.b as c``, as the statement would."""
    for alias in statement.names:
        imported = importlib.import_module(alias.name)
        if alias.asname is not None:
            namespace[alias.asname] = imported
        else:
            top = alias.name.partition(".")[0]
            namespace[top] = sys.modules[top]


def _bind_import_from(
    statement: ast.ImportFrom,
    module: types.ModuleType,
    namespace: dict[str, Any],
) -> None:
    """Bind the names of ``from m import x [as y]`` (relative to ``module`` if need be)."""
    relative = "." * statement.level + (statement.module or "")
    source = importlib.import_module(
        importlib.util.resolve_name(relative, module.__package__ or "")
        if statement.level
        else relative,
    )
    for alias in statement.names:
        try:
            value = getattr(source, alias.name)
        except AttributeError:  # a submodule not imported yet
            value = importlib.import_module(f"{source.__name__}.{alias.name}")
        namespace[alias.asname or alias.name] = value


def evaluate(annotation: str, namespace: dict[str, Any]) -> Any:
    """Return the object that the annotation written as ``annotation`` stands for.

    ``namespace`` holds the names the annotation may use (a module's, with the names it
    imports for type checkers). Evaluated as :func:`typing.get_type_hints` evaluates a
    class's annotations (``ClassVar`` allowed), keeping ``Annotated`` and ``None`` as
    written.

    :raises NameError: the annotation uses a name ``namespace`` does not have.
    """
    if annotation == "None":
        return None
    holder = type("Annotation", (), {"__annotations__": {"value": annotation}})
    hints = typing.get_type_hints(
        holder,
        globalns=namespace,
        localns=namespace,
        include_extras=True,
    )
    return hints["value"]
