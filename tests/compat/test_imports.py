"""``run --api``: the competition's package names resolve to j5aio's modules for the program."""

from __future__ import annotations

import importlib
import os
import subprocess
import sys
from collections.abc import Iterator
from importlib.util import find_spec
from pathlib import Path

import pytest

from j5aio.__main__ import build_parser
from j5aio.compat import imports

from .compat_support import ROOT


@pytest.fixture
def clean_modules() -> Iterator[None]:
    """Forget the redirected names the test imported, and take its finders off."""
    finders = list(sys.meta_path)
    yield
    sys.meta_path[:] = finders
    for name in list(sys.modules):
        if name in ("sr", "sbot") or name.startswith(("sr.", "sbot.")):
            del sys.modules[name]


@pytest.mark.usefixtures("clean_modules")
def test_sr_robot3_is_j5aios_module_under_the_api() -> None:
    finder = imports.install("sr-robot3")
    assert sys.meta_path[0] is finder
    robot3 = importlib.import_module("sr.robot3")
    compat = importlib.import_module("j5aio.compat.sr_robot3")
    assert robot3 is compat
    assert importlib.import_module("sr.robot3.power_board") is importlib.import_module(
        "j5aio.compat.sr_robot3.power_board")
    assert importlib.import_module("sr").robot3 is compat  # (sr: ours, or sr-robot3's)
    with pytest.raises(ModuleNotFoundError):
        importlib.import_module("sr.robot3.no_such_module")
    with pytest.raises(ModuleNotFoundError):
        importlib.import_module("sr.other")
    imports.uninstall(finder)
    assert finder not in sys.meta_path
    imports.uninstall(finder)  # twice is harmless


@pytest.mark.usefixtures("clean_modules")
def test_sbot_is_redirected_to_j5aios_sbot_module() -> None:
    assert imports.API_NAMES["sbot"] == {"sbot": "j5aio.compat.sbot"}
    finder = imports.CompatFinder({"sbot": "json"})  # (any module stands in, here)
    sys.meta_path.insert(0, finder)
    assert importlib.import_module("sbot") is importlib.import_module("json")
    assert importlib.import_module("sbot.decoder") is importlib.import_module("json.decoder")
    assert finder.find_spec("sbotanical") is None


@pytest.mark.usefixtures("clean_modules")
def test_a_dotted_name_gets_an_empty_parent_package() -> None:
    sys.meta_path.insert(0, imports.CompatFinder({"sbot.inner": "json"}))
    assert importlib.import_module("sbot.inner") is importlib.import_module("json")
    assert list(importlib.import_module("sbot").__path__) == []


def test_an_unknown_api_is_refused() -> None:
    with pytest.raises(ValueError, match="unknown API 'sr-robot4': choose one of sr-robot3, sbot"):
        imports.install("sr-robot4")
    with pytest.raises(SystemExit):
        build_parser().parse_args(["run", "--api", "sr-robot4", "robot.py"])
    args = build_parser().parse_args(["run", "--api", "sr-robot3", "robot.py"])
    assert args.api == "sr-robot3"


@pytest.mark.parametrize(("name", "api"), [
    ("sr", "sr-robot3"), ("sr.robot3", "sr-robot3"), ("sbot", "sbot"),
])
def test_the_hint_names_the_flag(name: str, api: str) -> None:
    hint = imports.missing_package_hint(ModuleNotFoundError(f"No module named {name!r}",
                                                            name=name))
    assert hint is not None
    assert f"add --api {api}: python -m j5aio run --api {api} [options] program.py" in hint


def test_no_hint_for_other_errors() -> None:
    assert imports.missing_package_hint(ModuleNotFoundError("x", name="numpy")) is None
    assert imports.missing_package_hint(ModuleNotFoundError("x", name="sr2")) is None
    assert imports.missing_package_hint(ValueError("sbot")) is None


def run_without_the_api(tmp_path: Path, source: str) -> subprocess.CompletedProcess[str]:
    (tmp_path / "robot.py").write_text(source)
    env = dict(os.environ)
    env["PYTHONPATH"] = os.pathsep.join([str(ROOT), env.get("PYTHONPATH", "")])
    return subprocess.run(
        [sys.executable, "-m", "j5aio", "run", "--sim", "--no-log", "robot.py"],
        capture_output=True, text=True, timeout=60, env=env, cwd=tmp_path, check=False,
    )


def test_a_program_run_without_the_api_is_told_to_add_it(tmp_path: Path) -> None:
    if find_spec("sr") is not None:
        pytest.skip("sr-robot3 is installed here, so the program would run on it")
    result = run_without_the_api(tmp_path, "from sr.robot3 import Robot\n")
    assert result.returncode == 1
    assert "ModuleNotFoundError: No module named 'sr'" in result.stderr
    assert result.stderr.rstrip().endswith(
        "add --api sr-robot3: python -m j5aio run --api sr-robot3 [options] program.py")


def test_without_the_api_a_program_may_still_look_for_the_package(tmp_path: Path) -> None:
    if find_spec("sbot") is not None:
        pytest.skip("sbot is installed here")
    result = run_without_the_api(
        tmp_path,
        "import importlib.util\n"
        "print('found', importlib.util.find_spec('sbot') is not None)\n"
        "try:\n"
        "    import sbot\n"
        "except ImportError:\n"
        "    print('no sbot')\n",
    )
    assert result.returncode == 0, result.stderr
    assert result.stdout.splitlines() == ["found False", "no sbot"]
    assert "--api" not in result.stderr  # (handled by the program: no hint)
