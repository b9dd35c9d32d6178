"""bench/bench_import_share.py: its empty modules are real, importable and empty."""

from __future__ import annotations

import importlib
import sys
from pathlib import Path

import pytest

from tests.module_from_file import ROOT, load_module

BENCH = load_module("bench_import_share", ROOT / "bench" / "bench_import_share.py")


def test_the_empty_package_holds_as_many_importable_modules(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    names = BENCH.empty_package(tmp_path, 3)
    assert names == [f"j5aio_bench_empty.module_{n}" for n in range(3)]
    monkeypatch.syspath_prepend(str(tmp_path))
    try:
        modules = [importlib.import_module(name) for name in names]
        assert [module.NUMBER for module in modules] == [0, 1, 2]
        assert all(len([k for k in vars(m) if not k.startswith("__")]) == 1 for m in modules)
    finally:
        for name in [*names, "j5aio_bench_empty"]:
            sys.modules.pop(name, None)
