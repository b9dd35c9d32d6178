"""Lazy imports: ``import j5aio`` and ``import j5aio.sync`` stay light; every name resolves."""

from __future__ import annotations

import ast
import importlib
import json
import os
import pkgutil
import subprocess
import sys
import textwrap
from pathlib import Path
from typing import Any

import pytest

import j5aio
from j5aio._lazy import LazyModule, lazy_exports, lazy_modules

ROOT = Path(j5aio.__file__).resolve().parent.parent

#: What neither ``import j5aio`` nor ``import j5aio.sync`` may import.
HEAVY = (
    "asyncio",
    "anyio",
    "ssl",
    "serial",
    "usb",
    "numpy",
    "cv2",
    "aiohttp",
    "j5aio.vision",
    "j5aio.view",
    "j5aio.competition",
    "j5aio.simulator",
    "j5aio.backends",
    "j5aio.boards",
    "j5aio.sync._generated",
)


def imported_by(statement: str) -> list[str]:
    """The modules loaded in a fresh interpreter after ``statement``."""
    code = f"import sys\n{statement}\nimport json\nprint(json.dumps(sorted(sys.modules)))"
    path = os.pathsep.join([str(ROOT), os.environ.get("PYTHONPATH", "")])
    env = {**os.environ, "PYTHONPATH": path}
    done = subprocess.run(
        [sys.executable, "-c", code],
        capture_output=True,
        text=True,
        env=env,
        check=True,
        timeout=120,
    )
    modules: list[str] = json.loads(done.stdout.splitlines()[-1])
    return modules


def heavy_in(modules: list[str]) -> list[str]:
    return [
        name
        for name in modules
        if any(name == heavy or name.startswith(heavy + ".") for heavy in HEAVY)
    ]


@pytest.mark.parametrize(
    "statement",
    ["import j5aio", "import j5aio.sync", "import j5aio.sync, j5aio"],
)
def test_importing_the_package_loads_nothing_heavy(statement: str) -> None:
    modules = imported_by(statement)
    assert "j5aio" in modules
    assert heavy_in(modules) == []


def test_a_first_program_loads_no_vision_view_or_simulator() -> None:
    modules = imported_by("from j5aio.sync import KitRobot")
    assert "j5aio.sync._generated" in modules
    unwanted = ("cv2", "numpy", "aiohttp", "j5aio.view", "j5aio.simulator", "j5aio.vision.detect")
    assert [m for m in modules if m.split(".")[0] in unwanted or m in unwanted] == []


def test_the_simulated_environment_loads_no_console_or_webcam_backend() -> None:
    modules = imported_by("import j5aio.simulator.environment")
    # (the example kit's plugin, installed here, brings the console base class itself)
    ours = ("j5aio.backends.console.sr", "j5aio.backends.console.sb", "j5aio.backends.console.cam")
    assert [m for m in modules if m.startswith(ours)] == []
    assert "j5aio.backends.camera.opencv" not in modules
    assert "importlib.metadata" not in modules


def test_the_simulated_kit_loads_the_backends_of_its_own_boards_only() -> None:
    program = textwrap.dedent("""
        import os
        os.environ["J5AIO_LOCK_PORT"] = "0"
        import anyio
        from j5aio.kit import KitRobot
        from j5aio.simulator.environment import SIMULATED_ENVIRONMENT
        from j5aio.simulator.kit import use_kit

        async def main():
            use_kit("sb2019")
            async with KitRobot(environment=SIMULATED_ENVIRONMENT) as robot:
                assert len(robot.motor_boards) == 1 and robot.arduinos

        anyio.run(main)
    """)
    modules = imported_by(program)
    assert "j5aio.backends.hardware.sr.v4.motor_board" in modules
    fw4 = [m for m in modules if m.endswith(("_fw4", "fw4_codec", "arduino_2024"))]
    assert [m for m in fw4 if m.startswith("j5aio.backends")] == []


def lazy_packages() -> list[str]:
    """Every package of j5aio whose ``__init__`` exports names lazily."""
    found = []
    for info in pkgutil.walk_packages([str(ROOT / "j5aio")], "j5aio."):
        if info.ispkg:
            init = ROOT / Path(*info.name.split(".")) / "__init__.py"
            if "lazy_exports(" in init.read_text():
                found.append(info.name)
    return ["j5aio", *found]


def declared(package: str) -> tuple[dict[str, str], dict[str, tuple[str, str]]]:
    """A lazy package's names as type checkers see them and as it exports them at run time.

    :returns: name -> module of its ``if TYPE_CHECKING:`` imports, and name -> (module,
        attribute) of its ``lazy_exports`` table.
    """
    init = ROOT / Path(*package.split(".")) / "__init__.py"
    tree = ast.parse(init.read_text())
    typed: dict[str, str] = {}
    table: dict[str, tuple[str, str]] = {}
    for node in ast.walk(tree):
        if isinstance(node, ast.If) and ast.unparse(node.test) == "TYPE_CHECKING":
            for item in node.body:
                if isinstance(item, ast.ImportFrom) and item.module:
                    for alias in item.names:
                        typed[alias.asname or alias.name] = f"{item.module}:{alias.name}"
        if (
            isinstance(node, ast.Call)
            and isinstance(node.func, ast.Name)
            and node.func.id == "lazy_exports"
        ):
            for module, names in ast.literal_eval(node.args[1]).items():
                for spec in names:
                    name, _, attribute = spec.partition(":")
                    table[name] = (module, attribute or name)
    return typed, table


@pytest.mark.parametrize("package", lazy_packages())
def test_type_checkers_see_what_is_exported(package: str) -> None:
    typed, table = declared(package)
    assert table, f"{package} has no lazy_exports table"
    assert {name: f"{m}:{a}" for name, (m, a) in table.items()} == typed
    module = importlib.import_module(package)
    assert set(table) <= set(module.__all__)


@pytest.mark.parametrize("package", lazy_packages())
def test_every_exported_name_resolves(package: str) -> None:
    module = importlib.import_module(package)
    _, table = declared(package)
    for name in module.__all__:
        value = getattr(module, name)
        if name in table:
            home, attribute = table[name]
            assert value is getattr(importlib.import_module(home), attribute)
    assert set(module.__all__) <= set(dir(module))
    star: dict[str, Any] = {}
    exec(f"from {package} import *", star)  # the star import of a user
    assert set(module.__all__) <= set(star)


def test_sync_exports_every_wrapper_and_environment() -> None:
    import j5aio.sync as sync
    from j5aio.sync import _generated

    assert set(_generated.__all__) | {"__version__", "shutdown"} == set(sync.__all__)
    for name in sync.__all__:
        assert getattr(sync, name) is not None
    assert sync.CONSOLE_ENVIRONMENT.name == "ConsoleEnvironment"
    assert sync.HARDWARE_ENVIRONMENT.name == "HardwareEnvironment"
    assert sync.CONSOLE_ENVIRONMENT is sync.CONSOLE_ENVIRONMENT
    assert set(sync.__all__) <= set(dir(sync))


@pytest.mark.parametrize("package", ["j5aio", "j5aio.sync", "j5aio.components"])
def test_an_unknown_name_is_an_attribute_error(package: str) -> None:
    module = importlib.import_module(package)
    with pytest.raises(AttributeError, match="has no attribute 'NoSuchThing'"):
        module.NoSuchThing  # noqa: B018
    with pytest.raises(AttributeError):
        module.__no_such_dunder__  # noqa: B018
    with pytest.raises(ImportError):
        exec(f"from {package} import NoSuchThing", {})


def test_a_submodule_is_reached_as_an_attribute() -> None:
    import j5aio.vision

    markers = j5aio.vision.markers
    assert markers is importlib.import_module("j5aio.vision.markers")
    import j5aio.sync

    assert j5aio.sync.wrapping is importlib.import_module("j5aio.sync.wrapping")


def test_a_name_exported_twice_is_refused() -> None:
    with pytest.raises(ValueError, match="exports 'x' from two modules"):
        lazy_exports("pkg", {"a": ["x"], "b": ["x"]})


def test_a_name_may_be_exported_under_another_name() -> None:
    name = "j5aio_lazy_test_package"
    package = type(sys)(name)
    vars(package)["__getattr__"], vars(package)["__dir__"] = lazy_exports(
        name,
        {"os.path": ["joined:join"]},
    )
    sys.modules[name] = package
    try:
        assert package.joined is os.path.join
        assert "joined" in dir(package)
        assert "joined" in vars(package)  # kept: the next look-up is a plain one
    finally:
        del sys.modules[name]


def test_the_table_holds_each_module_name_once_and_nothing_per_plain_name() -> None:
    # (every package imported on a start builds its table: a tuple per name would be
    # paid for on every start)
    module = "os.path"
    getter, _ = lazy_exports("pkg", {module: ["join", "split", "joined:join"]})
    tables = [
        cell.cell_contents
        for cell in getter.__closure__ or ()
        if isinstance(cell.cell_contents, dict)
    ]
    where = next(table for table in tables if "split" in table)
    assert all(value is module for value in where.values())
    renamed = next(table for table in tables if table is not where)
    assert renamed == {"joined": "join"}


def test_an_import_error_inside_a_submodule_is_not_hidden(tmp_path: Path) -> None:
    (tmp_path / "lazypkg").mkdir()
    (tmp_path / "lazypkg" / "__init__.py").write_text(
        textwrap.dedent("""
        from j5aio._lazy import lazy_exports
        __getattr__, __dir__ = lazy_exports(__name__, {})
    """)
    )
    (tmp_path / "lazypkg" / "broken.py").write_text("import no_such_module_here\n")
    sys.path.insert(0, str(tmp_path))
    try:
        import lazypkg  # type: ignore[import-not-found]

        with pytest.raises(ModuleNotFoundError, match="no_such_module_here"):
            lazypkg.broken  # noqa: B018
    finally:
        sys.path.remove(str(tmp_path))
        for module in [m for m in sys.modules if m.split(".")[0] == "lazypkg"]:
            del sys.modules[module]


def test_a_lazy_module_becomes_the_module_on_first_use() -> None:
    namespace: dict[str, Any] = {}
    lazy_modules(namespace, {"_json": "json"})
    stand_in = namespace["_json"]
    assert isinstance(stand_in, LazyModule)
    assert "json" in repr(stand_in)
    assert stand_in.dumps([1]) == "[1]"
    assert namespace["_json"] is json
    # A stand-in whose global was rebound since leaves the new binding alone.
    other = object()
    namespace["_json"] = other
    assert stand_in.loads("2") == 2
    assert namespace["_json"] is other


def test_all_is_made_from_the_table_and_the_packages_own_names() -> None:
    name = "j5aio_lazy_test_all"
    package = type(sys)(name)
    vars(package)["__getattr__"], vars(package)["__dir__"] = lazy_exports(
        name,
        {"os.path": ["join", "joined:join"], "json": ["dumps"]},
        own=("VERSION",),
    )
    vars(package)["VERSION"] = "1"
    sys.modules[name] = package
    try:
        assert package.__all__ == ["VERSION", "dumps", "join", "joined"]
        assert "__all__" in vars(package)  # made once
        star: dict[str, Any] = {}
        exec(f"from {name} import *", star)
        assert star["joined"] is os.path.join
        assert star["VERSION"] == "1"
    finally:
        del sys.modules[name]


def test_a_package_that_lists_its_own_all_keeps_it() -> None:
    name = "j5aio_lazy_test_own_all"
    package = type(sys)(name)
    vars(package)["__getattr__"], vars(package)["__dir__"] = lazy_exports(
        name,
        {"json": ["dumps", "loads"]},
    )
    vars(package)["__all__"] = ["dumps"]
    sys.modules[name] = package
    try:
        star: dict[str, Any] = {}
        exec(f"from {name} import *", star)
        assert "dumps" in star
        assert "loads" not in star
    finally:
        del sys.modules[name]
