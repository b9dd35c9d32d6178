"""The newcomer's path, exactly as the README tells it, in a fresh copy of the repository.

A copy of every tracked file (what a clone holds), then the README's commands: the
set-up command's demo, the first program saved as the README says and run with the
README's ``--sim`` command, and the async program likewise. Only the virtual environment
and ``pip install -e .`` are not repeated here: the test suite already runs from an
installed checkout, and CI's ``.ci/run`` follows the README's test command into a fresh
virtual environment of its own. ``python3`` or ``python`` in a command is this
interpreter.
"""

from __future__ import annotations

import os
import shlex
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from .snippets import ROOT, markdown_snippets

SETUP = (
    "python3 -m venv .venv",
    ". .venv/bin/activate",
    "python -m pip install -e .",
)


def fresh_copy(target: Path) -> Path:
    """Copy the repository's tracked files to ``target``, as a clone would have them."""
    listed = subprocess.run(
        ["git", "ls-files", "-z"], cwd=ROOT, capture_output=True, check=True,
    ).stdout.decode().split("\0")
    for name in filter(None, listed):
        source = ROOT / name
        if source.is_file():
            (target / name).parent.mkdir(parents=True, exist_ok=True)
            shutil.copy2(source, target / name)
    return target


def run(command: str, cwd: Path) -> subprocess.CompletedProcess[str]:
    """Run one README command line, with ``python3`` or ``python`` meaning this interpreter."""
    words = shlex.split(command)
    assert words[0] in ("python3", "python"), command
    env = {k: v for k, v in os.environ.items() if k != "J5AIO_ENV"}
    env["PYTHONPATH"] = str(cwd)
    return subprocess.run(
        [sys.executable, *words[1:]], cwd=cwd, env=env, capture_output=True, text=True,
        timeout=120, stdin=subprocess.DEVNULL, check=False,
    )


@pytest.fixture(scope="module")
def clone(tmp_path_factory: pytest.TempPathFactory) -> Path:
    if shutil.which("git") is None or not (ROOT / ".git").exists():
        pytest.skip("needs a git checkout")
    return fresh_copy(tmp_path_factory.mktemp("clone"))


def test_the_readme_has_no_links_outside_the_clone(clone: Path) -> None:
    readme = (clone / "README.md").read_text(encoding="utf-8")
    assert "../" not in readme


def test_the_setup_command_runs_the_demo(clone: Path) -> None:
    blocks = [s for s in markdown_snippets(clone / "README.md") if s.language == "sh"]
    setup = blocks[0].code.strip()
    *steps, demo = (part.strip() for part in setup.split("&&"))
    assert tuple(steps) == SETUP
    result = run(demo, clone)
    assert result.returncode == 0, result.stderr
    assert "every simulated motor is braked" in result.stdout


def test_the_first_program_and_the_async_program_run_with_sim(clone: Path) -> None:
    readme = (clone / "README.md").read_text(encoding="utf-8")
    python = [s for s in markdown_snippets(clone / "README.md") if s.language == "python"]
    first, async_program = python[0], python[1]
    assert "Save this as `first.py`" in readme
    (clone / "first.py").write_text(first.code, encoding="utf-8")
    sim_command = next(
        line for s in markdown_snippets(clone / "README.md") if s.language == "sh"
        for line in s.code.splitlines() if "run --sim first.py" in line
    )
    result = run(sim_command, clone)
    assert result.returncode == 0, result.stderr
    assert result.stdout.startswith("Battery: ")

    assert "`python -m j5aio run --sim robot.py`" in readme
    (clone / "robot.py").write_text(async_program.code, encoding="utf-8")
    result = run("python -m j5aio run --sim robot.py", clone)
    assert result.returncode == 0, result.stderr
