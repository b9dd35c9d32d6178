"""Docs as tests: every code block of README.md and docs/ runs, or is a fragment on purpose.

The convention:

- **README.md**: a ```` ```python ```` block is a whole program. It is run with
  ``python -m j5aio run --sim`` (the simulated kit, no input, a time limit) and must end
  well. A block that is only part of a program has the line ``<!-- fragment -->`` just
  above its fence.
- **docs/*.rst**: Python is shown with ``.. code-block:: python``, and such a block is a
  whole program, run the same way. A part of a program carries the option
  ``:class: fragment``. A ``::`` literal block is for shell commands, output and
  pictures: Python hidden in one fails a test, so nothing escapes both rules.
- A fragment still has to be valid Python (``await`` allowed at the top level): a
  misspelt keyword or an unclosed bracket fails here too.
"""

from __future__ import annotations

import ast
import os
import subprocess
import sys
from pathlib import Path

import pytest

from .snippets import ROOT, Snippet, all_snippets

SNIPPETS = all_snippets()
PYTHON = [s for s in SNIPPETS if s.language == "python"]
RUNNABLE = [s for s in PYTHON if not s.fragment]
FRAGMENTS = [s for s in PYTHON if s.fragment]
LITERALS = [s for s in SNIPPETS if s.language == "literal"]

#: How long one snippet may take on the simulated kit, in seconds.
SNIPPET_TIMEOUT = 60


def _ids(snippets: list[Snippet]) -> list[str]:
    return [s.name for s in snippets]


def parses(code: str) -> bool:
    """Whether ``code`` is Python (with top-level ``await`` allowed)."""
    try:
        compile(code, "<snippet>", "exec", flags=ast.PyCF_ONLY_AST | ast.PyCF_ALLOW_TOP_LEVEL_AWAIT)
    except SyntaxError:
        return False
    return True


def test_the_docs_have_snippets_of_both_kinds() -> None:
    assert len(RUNNABLE) >= 5
    assert FRAGMENTS
    assert any(s.path.name == "README.md" for s in RUNNABLE)


@pytest.mark.parametrize("snippet", RUNNABLE, ids=_ids(RUNNABLE))
def test_snippet_runs_on_the_simulated_kit(snippet: Snippet, tmp_path: Path) -> None:
    program = tmp_path / "snippet.py"
    program.write_text(snippet.code, encoding="utf-8")
    path = os.pathsep.join([str(ROOT), os.environ.get("PYTHONPATH", "")])
    env = {**os.environ, "PYTHONPATH": path}
    result = subprocess.run(
        [sys.executable, "-m", "j5aio", "run", "--sim", str(program)],
        stdin=subprocess.DEVNULL, capture_output=True, text=True,
        timeout=SNIPPET_TIMEOUT, cwd=tmp_path, env=env, check=False,
    )
    assert result.returncode == 0, f"{snippet.name} failed:\n{result.stderr}"


@pytest.mark.parametrize("snippet", FRAGMENTS, ids=_ids(FRAGMENTS))
def test_fragment_is_valid_python(snippet: Snippet) -> None:
    assert parses(snippet.code), f"{snippet.name} is not valid Python"


@pytest.mark.parametrize("snippet", LITERALS, ids=_ids(LITERALS))
def test_no_python_hides_in_a_literal_block(snippet: Snippet) -> None:
    assert not parses(snippet.code), (
        f"{snippet.name}: Python in a '::' block is neither run nor checked; use "
        "'.. code-block:: python' (a whole program, run by the tests) or add "
        "':class: fragment'"
    )
