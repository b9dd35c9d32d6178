"""Fixtures for the hardware backend tests."""

from __future__ import annotations

from collections.abc import Iterator

import pytest

from j5aio.backends.hardware import registry


@pytest.fixture(autouse=True)
def _fresh_port_registry() -> Iterator[None]:
    """Start and end every test with no port held by a hardware backend."""
    registry.clear()
    yield
    registry.clear()
