"""The board kind registry imports lightly, and its modules are in no import cycle."""

from __future__ import annotations

import ast
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]

#: The modules of the registry and of what it names, kept out of every import cycle.
ACYCLIC = (
    "j5aio.board_kinds",
    "j5aio.backends._kinds",
    "j5aio.backends._kind_types",
    "j5aio.backends._builtin_kinds",
    "j5aio.import_paths",
    "j5aio.simulator.environment",
    "j5aio.simulator.sim_backends",
    "j5aio.simulator.sim_backends_2023",
    "j5aio.simulator._sim_sb_arduino_2019",
    "j5aio.simulator._sim_sr_ruggeduino_fw1",
    "j5aio.simulator._sim_sr_arduino_fw2",
    "j5aio.simulator._sim_sb_arduino_2024",
    "j5aio.simulator.discovery",
    "j5aio.backends.hardware.transports.lent",
)


def _module_names() -> dict[str, Path]:
    names = {}
    for path in (ROOT / "j5aio").rglob("*.py"):
        parts = list(path.relative_to(ROOT).with_suffix("").parts)
        if parts[-1] == "__init__":
            parts.pop()
        names[".".join(parts)] = path
    return names


def _imports(name: str, path: Path, known: dict[str, Path]) -> set[str]:
    """What ``name`` imports, anywhere in it (functions too), but for ``TYPE_CHECKING``."""
    tree = ast.parse(path.read_text(encoding="utf-8"))
    skipped: set[int] = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.If) and "TYPE_CHECKING" in ast.unparse(node.test):
            skipped.update(id(sub) for child in node.body for sub in ast.walk(child))
    package = name if path.name == "__init__.py" else name.rpartition(".")[0]
    found: set[str] = set()
    for node in ast.walk(tree):
        if id(node) in skipped:
            continue
        if isinstance(node, ast.Import):
            found.update(alias.name for alias in node.names)
        elif isinstance(node, ast.ImportFrom):
            base = package.split(".")[: len(package.split(".")) - (node.level - 1)]
            target = ".".join([*base, node.module] if node.module else base) if node.level else (
                node.module or ""
            )
            found.add(target)
            found.update(f"{target}.{alias.name}" for alias in node.names)
        elif (
            isinstance(node, ast.Call)
            and ast.unparse(node.func).endswith("import_module")
            and node.args
            and isinstance(node.args[0], ast.Constant)
        ):
            found.add(str(node.args[0].value))
    return {module for module in found if module in known and module != name}


def test_the_registry_s_modules_are_in_no_import_cycle() -> None:
    known = _module_names()
    graph = {name: _imports(name, path, known) for name, path in known.items()}
    for start in ACYCLIC:
        assert start in graph, start
        # every module reachable from start; a cycle through start reaches it again
        seen: set[str] = set()
        stack = list(graph[start])
        while stack:
            module = stack.pop()
            if module in seen:
                continue
            seen.add(module)
            stack.extend(graph[module])
        assert start not in seen, f"{start} is in an import cycle"


def test_importing_the_command_line_builds_no_simulator() -> None:
    program = (
        "import sys, warnings\n"
        "warnings.simplefilter('ignore')\n"
        "import j5aio.__main__\n"
        "print(sorted(m for m in ('gpiozero', 'j5aio.simulator.kch', "
        "'j5aio.simulator.sim_backends', 'j5aio.simulator.sim_backends_2023') "
        "if m in sys.modules))\n"
    )
    result = subprocess.run(
        [sys.executable, "-c", program], capture_output=True, text=True, timeout=60,
        check=False, cwd=ROOT,
    )
    assert result.returncode == 0, result.stderr
    assert result.stdout.strip() == "[]"
