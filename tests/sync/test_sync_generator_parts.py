"""The generator's package: loaded piece by piece, and its annotation reading without exec."""

from __future__ import annotations

import subprocess
import sys
import types
from pathlib import Path
from typing import Annotated, ClassVar

import pytest

from j5aio.syncgen import _namespace as namespace

from .sync_fakes import ROOT, child_env

SOURCE = """\
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    import collections.abc
    import os.path as where
    from . import sibling
    from .sibling import Thing as Renamed
    from .deeper import leaf

    Alias = int | str
    Hidden: type[int] = int


def __getattr__(name):  # the alias is made when looked up (Hidden is for types only)
    if name == "Alias":
        return int | str
    raise AttributeError(name)
"""


@pytest.fixture
def package(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> types.ModuleType:
    """A package on disk whose module imports names only for type checkers."""
    root = tmp_path / "typed_only_pkg"
    (root / "deeper").mkdir(parents=True)
    (root / "__init__.py").write_text("", encoding="utf-8")
    (root / "sibling.py").write_text("class Thing:\n    pass\n", encoding="utf-8")
    (root / "deeper" / "__init__.py").write_text("", encoding="utf-8")
    (root / "deeper" / "leaf.py").write_text("VALUE = 1\n", encoding="utf-8")
    (root / "user.py").write_text(SOURCE, encoding="utf-8")
    monkeypatch.syspath_prepend(str(tmp_path))
    import importlib

    return importlib.import_module("typed_only_pkg.user")


def test_the_names_imported_for_type_checkers_are_bound_as_the_imports_would(
    package: types.ModuleType,
) -> None:
    import collections
    import os.path

    bound = namespace._type_checking_imports(package)
    assert bound["collections"] is collections
    assert bound["where"] is os.path
    assert bound["sibling"].__name__ == "typed_only_pkg.sibling"
    assert bound["Renamed"] is bound["sibling"].Thing
    assert bound["leaf"].VALUE == 1  # a submodule nobody had imported yet
    assert "TYPE_CHECKING" not in bound
    # an alias assigned for type checkers is bound when the module gives it on demand
    assert bound["Alias"] == int | str
    assert "Hidden" not in bound


def test_a_module_without_source_binds_nothing() -> None:
    assert namespace._type_checking_imports(types.ModuleType("no_source")) == {}


def test_annotations_are_evaluated_without_eval() -> None:
    names = {"Annotated": Annotated, "ClassVar": ClassVar, "Path": Path}
    assert namespace.evaluate("None", names) is None
    assert namespace.evaluate("Path | None", names) == Path | None
    assert namespace.evaluate("ClassVar[int]", names) == ClassVar[int]
    assert namespace.evaluate('Annotated[int, "units"]', names) == Annotated[int, "units"]
    assert namespace.evaluate("list['Path']", names) == list[Path]
    with pytest.raises(NameError):
        namespace.evaluate("Missing", names)


def _python(*arguments: str) -> subprocess.CompletedProcess[str]:
    """Run this Python with ``arguments`` from the checkout, as a student's shell would."""
    return subprocess.run(
        [sys.executable, *arguments],
        capture_output=True,
        text=True,
        timeout=60,
        cwd=ROOT,
        env=child_env(),
        check=False,
    )


def test_the_package_loads_its_parts_on_first_use() -> None:
    code = (
        "import sys, j5aio.syncgen as g\n"
        "before = sorted(m for m in sys.modules if m.startswith('j5aio.syncgen.'))\n"
        "g.add_arguments\n"
        "after_cli = sorted(m for m in sys.modules if m.startswith('j5aio.syncgen.'))\n"
        "assert 'generate' in dir(g)\n"
        "g.generate\n"
        "print(before, after_cli, 'j5aio.syncgen._class_writer' in sys.modules)\n"
        "try:\n"
        "    g.nothing_here\n"
        "except AttributeError as error:\n"
        "    print(error)\n"
    )
    result = _python("-c", code)
    assert result.returncode == 0, result.stderr
    first, second = result.stdout.splitlines()
    assert first == "[] ['j5aio.syncgen._cli'] True"
    assert second == "module 'j5aio.syncgen' has no attribute 'nothing_here'"


def test_python_m_j5aio_syncgen_is_the_command_line(tmp_path: Path) -> None:
    result = _python("-m", "j5aio.syncgen", "no_such_module_here", "-o", str(tmp_path / "x"))
    assert result.returncode == 2
    assert "sync-gen: " in result.stderr and "no_such_module_here" in result.stderr


def test_overloads_are_written_for_type_checkers_only() -> None:
    import typing

    from j5aio.sync import BoardGroup, KitRobot

    source = (ROOT / "j5aio" / "sync" / "_generated" / "robot.py").read_text(encoding="utf-8")
    assert "    if TYPE_CHECKING:\n        @overload\n" in source
    assert "\n    @overload" not in source  # none at class level, made at run time
    # nothing is recorded at run time; the implementation is what runs
    assert typing.get_overloads(BoardGroup.get_board_group) == []
    assert typing.get_overloads(KitRobot.board_group) == []
    assert callable(BoardGroup.get_board_group)
