"""The API reference covers every public module, and nitpicky is not switched off for it.

The docs build itself (``sphinx-build -W -n``, the ``docs`` tox env) fails on a reference
that does not resolve; these checks keep the two ways round that from creeping back: a
public module left out of the reference (its names then resolve nowhere), and a j5aio name
quietly added to ``nitpick_ignore``.
"""

from __future__ import annotations

import ast
import importlib
import re
from pathlib import Path
from typing import TypeVar

from .snippets import DOCS, ROOT

PACKAGE = ROOT / "j5aio"
CONF = DOCS / "conf.py"
_AUTOMODULE = re.compile(r"^\s*\.\. automodule:: (\S+)\s*$", re.MULTILINE)


def public_modules() -> set[str]:
    """Every module of j5aio whose dotted name has no part starting with ``_``."""
    found: set[str] = set()
    for path in PACKAGE.rglob("*.py"):
        parts = list(path.relative_to(ROOT).with_suffix("").parts)
        if parts[-1] == "__init__":
            parts.pop()
        if any(part.startswith("_") for part in parts):
            continue
        found.add(".".join(parts))
    return found


def documented_modules() -> set[str]:
    """The modules named by an ``automodule`` directive on any page."""
    found: set[str] = set()
    for page in DOCS.rglob("*.rst"):
        found.update(_AUTOMODULE.findall(page.read_text(encoding="utf-8")))
    return found


def conf_assignments() -> dict[str, object]:
    """The literal values that docs/conf.py assigns at the top level."""
    values: dict[str, object] = {}
    for node in ast.parse(CONF.read_text(encoding="utf-8")).body:
        if isinstance(node, ast.Assign | ast.AnnAssign) and node.value is not None:
            target = node.targets[0] if isinstance(node, ast.Assign) else node.target
            if isinstance(target, ast.Name):
                try:
                    values[target.id] = ast.literal_eval(node.value)
                except ValueError:
                    continue
    return values


def test_public_modules_are_found() -> None:
    modules = public_modules()
    assert "j5aio.components.motor" in modules
    assert "j5aio.sync" in modules
    assert not any("._" in name for name in modules)


def test_every_public_module_is_in_the_api_reference() -> None:
    missing = sorted(public_modules() - documented_modules())
    assert not missing, (
        "public modules missing from the API reference (add an automodule directive to "
        f"docs/api.rst or docs/api-backends.rst): {missing}"
    )


def test_every_documented_module_exists() -> None:
    for name in documented_modules():
        importlib.import_module(name)


def test_nitpicky_is_on_with_no_hook_silencing_it() -> None:
    text = CONF.read_text(encoding="utf-8")
    assert conf_assignments()["nitpicky"] is True
    assert "warn-missing-reference" not in text
    assert "missing-reference" not in text
    assert "nitpick_ignore_regex" not in text


def test_nitpick_ignore_names_only_foreign_names_and_type_variables() -> None:
    ignored = conf_assignments()["nitpick_ignore"]
    assert isinstance(ignored, list) and ignored
    for role, name in ignored:
        assert role.startswith("py:"), (role, name)
        target = name.removeprefix("~").removeprefix("typing.~")
        if not target.startswith("j5aio."):
            continue
        module_name, _, attribute = target.rpartition(".")
        value = getattr(importlib.import_module(module_name), attribute)
        assert isinstance(value, TypeVar), (
            f"{name} is a j5aio name other than a type variable: document it and refer to "
            "it by its full name instead of ignoring it"
        )


def defined_names() -> set[str]:
    """The names of the classes and functions defined anywhere in j5aio."""
    names: set[str] = set()
    for path in PACKAGE.rglob("*.py"):
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, ast.ClassDef | ast.FunctionDef | ast.AsyncFunctionDef):
                names.add(node.name)
    return names


def test_bare_names_ignored_are_not_j5aio_classes_or_functions() -> None:
    # A bare name is how a string annotation spells a name; ignoring one of j5aio's own
    # classes that way would hide a reference that should resolve.
    ignored = conf_assignments()["nitpick_ignore"]
    assert isinstance(ignored, list)
    ours = defined_names()
    assert "Motor" in ours
    bare = {name.removeprefix("~") for _role, name in ignored if "." not in name}
    assert bare
    assert not bare & ours, sorted(bare & ours)


def test_the_reference_lists_the_members_of_enumerations_and_colour_constants() -> None:
    import runpy

    from j5aio.boards.sr.kch import Colour
    from j5aio.boards.sr.v4.power_board_fw4 import PowerBoardOutput
    from j5aio.components.piezo import Note

    conf = runpy.run_path(str(Path(__file__).resolve().parents[2] / "docs" / "conf.py"))
    keep = conf["_keep_constants"]
    for name, member in (("H0", PowerBoardOutput.H0), ("A6", Note.A6), ("RED", Colour.RED)):
        assert keep(None, "class", name, member, True, {}) is False
    # methods and module-level names are left to autodoc's own rules
    assert keep(None, "class", "buzz", lambda: None, True, {}) is None
    assert keep(None, "module", "H0", PowerBoardOutput.H0, True, {}) is None
