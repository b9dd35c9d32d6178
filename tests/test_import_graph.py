"""No import cycle anywhere in j5aio: the whole module graph, imports inside functions too.

The graph is built by grimp, the library behind import-linter (``tox -e layers``), from
the source, without importing it. An edge is one module importing another:

- an import inside a function counts (it runs all the same, only later);
- an import under ``if TYPE_CHECKING:`` does not (it never runs);
- ``from package import name`` is an edge to the submodule ``package.name`` when there is
  one, and otherwise to the package itself (its ``__init__``), which is what runs;
- the package a module belongs to is not an edge of its own: Python runs a package's
  ``__init__`` before any of its modules, but that is the package's import, not one the
  module makes. So a package whose ``__init__`` imports its submodules (eagerly, or lazily
  on first use through :mod:`j5aio._lazy`) is no cycle; an ``__init__`` that eagerly
  imports a submodule which imports names from the package back (``from package import
  name``) is one, and is reported.

The layers' contracts in ``.importlinter`` check the packages' order; this test checks
the modules one by one, so that no two modules of j5aio ever wait on each other.
"""

from __future__ import annotations

from pathlib import Path

import grimp
import pytest


def _graph(package: str = "j5aio") -> dict[str, set[str]]:
    """Every module of ``package`` -> the modules of it that it imports (from the source)."""
    graph = grimp.build_graph(package, exclude_type_checking_imports=True, cache_dir=None)
    return {module: graph.find_modules_directly_imported_by(module) for module in graph.modules}


def find_cycle(graph: dict[str, set[str]]) -> list[str] | None:
    """Return one import cycle as a chain of modules (first == last), or ``None``."""
    done: set[str] = set()
    for start in sorted(graph):
        if start in done:
            continue
        # depth-first, without recursion: the path and, per module, the imports left to try
        path: list[str] = [start]
        on_path = {start}
        pending = [iter(sorted(graph[start]))]
        while pending:
            following = next(pending[-1], None)
            if following is None:  # every import of path[-1] tried: no cycle through it
                pending.pop()
                finished = path.pop()
                on_path.discard(finished)
                done.add(finished)
                continue
            if following in on_path:
                return [*path[path.index(following):], following]
            if following in done or following not in graph:
                continue
            path.append(following)
            on_path.add(following)
            pending.append(iter(sorted(graph[following])))
    return None


def test_find_cycle_reports_the_chain() -> None:
    graph = {"a": {"b"}, "b": {"c"}, "c": {"a", "d"}, "d": set()}
    assert find_cycle(graph) == ["a", "b", "c", "a"]
    assert find_cycle({"a": {"a"}}) == ["a", "a"]


def test_find_cycle_passes_a_graph_without_one() -> None:
    # a diamond is no cycle, and a module outside the graph is ignored
    assert find_cycle({"a": {"b", "c"}, "b": {"d"}, "c": {"d"}, "d": {"os"}}) is None


def _write_package(root: Path, name: str, files: dict[str, str]) -> None:
    package = root / name
    package.mkdir()
    for module, text in files.items():
        (package / f"{module}.py").write_text(text, encoding="utf-8")


def test_how_a_package_s_init_counts(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
) -> None:
    monkeypatch.syspath_prepend(str(tmp_path))
    # An __init__ importing its submodules, one of which imports a sibling: no cycle.
    _write_package(tmp_path, "acyclic_plain", {
        "__init__": "from acyclic_plain.motor import Motor\nfrom acyclic_plain import led\n",
        "motor": "from acyclic_plain.led import LED\n\nclass Motor:\n    pass\n",
        "led": "class LED:\n    pass\n",
    })
    assert find_cycle(_graph("acyclic_plain")) is None
    # An __init__ eagerly importing a submodule that imports a name of the package back.
    _write_package(tmp_path, "acyclic_back", {
        "__init__": "VERSION = 1\nfrom acyclic_back.motor import Motor\n",
        "motor": "from acyclic_back import VERSION\n\nclass Motor:\n    pass\n",
    })
    assert find_cycle(_graph("acyclic_back")) == [
        "acyclic_back", "acyclic_back.motor", "acyclic_back",
    ]
    # An import inside a function counts: it runs, only later.
    _write_package(tmp_path, "acyclic_late", {
        "__init__": "",
        "motor": "from acyclic_late.led import LED\n",
        "led": "class LED:\n    pass\n\ndef motor():\n    import acyclic_late.motor\n",
    })
    assert find_cycle(_graph("acyclic_late")) == [
        "acyclic_late.led", "acyclic_late.motor", "acyclic_late.led",
    ]


def test_no_two_j5aio_modules_import_each_other() -> None:
    graph = _graph()
    assert len(graph) > 100, "grimp found too few modules: is j5aio the package it read?"
    cycle = find_cycle(graph)
    assert cycle is None, "an import cycle between j5aio's modules: " + " -> ".join(cycle or ())


def test_the_graph_counts_imports_inside_functions_and_not_type_checking_ones() -> None:
    graph = _graph()
    # j5aio.environments imports the simulated environment inside a function only
    assert "j5aio.simulator.environment" in graph["j5aio.environments"]
    # j5aio.boards.board imports Backend for the type checker only
    assert "j5aio.backends.backend" not in graph["j5aio.boards.board"]
