"""``run --api``: the competition's package names resolve to j5aio's modules for the program."""

from __future__ import annotations

import importlib
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


@pytest.mark.usefixtures("clean_modules")
@pytest.mark.parametrize(("name", "api"), [("sr.robot3", "sr-robot3"), ("sbot", "sbot")])
def test_without_the_api_the_error_names_the_flag(name: str, api: str) -> None:
    if find_spec(name.split(".")[0]) is not None:
        pytest.skip(f"{name} is installed here, so it is imported rather than hinted at")
    imports.install_hint()
    with pytest.raises(ModuleNotFoundError, match=f"add --api {api}") as caught:
        importlib.import_module(name)
    assert caught.value.name == name.split(".")[0]
    assert importlib.import_module("json")  # other names are not its business


def test_a_program_run_without_the_api_is_told_to_add_it(tmp_path: Path) -> None:
    import os
    import subprocess

    if find_spec("sr") is not None:
        pytest.skip("sr-robot3 is installed here, so the program would run on it")
    (tmp_path / "robot.py").write_text("from sr.robot3 import Robot\n")
    env = dict(os.environ)
    env["PYTHONPATH"] = os.pathsep.join([str(ROOT), env.get("PYTHONPATH", "")])
    result = subprocess.run(
        [sys.executable, "-m", "j5aio", "run", "--sim", "--no-log", "robot.py"],
        capture_output=True, text=True, timeout=60, env=env, cwd=tmp_path, check=False,
    )
    assert result.returncode == 1
    assert "add --api sr-robot3: python -m j5aio run --api sr-robot3" in result.stderr
