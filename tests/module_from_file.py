"""Load a script from outside any package (a bench, a tool, an example) as a module."""

from __future__ import annotations

import importlib.util
import sys
from pathlib import Path
from types import ModuleType

ROOT = Path(__file__).resolve().parents[1]


def load_module(name: str, path: Path, *, register: bool = False) -> ModuleType:
    """Run the file at ``path`` as a new module called ``name`` and return it.

    :param register: put it in ``sys.modules`` under ``name`` before running it, as an
        import would (a module that defines dataclasses, or pickles its own objects,
        needs that to find itself).
    """
    spec = importlib.util.spec_from_file_location(name, path)
    assert spec is not None and spec.loader is not None, f"no module can be loaded from {path}"
    module = importlib.util.module_from_spec(spec)
    if register:
        sys.modules[name] = module
    spec.loader.exec_module(module)
    return module
