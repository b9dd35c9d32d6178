"""attach's quick round: every kind asked over one opening of the port per baud rate."""

from __future__ import annotations

import pytest

from j5aio.backends.hardware import identify
from j5aio.backends.hardware.identify import attach, serial_backends
from j5aio.errors import CommunicationError


async def test_a_port_that_will_not_open_is_left_to_the_full_round_to_report() -> None:
    missing = "/dev/j5aio-no-such-port"
    assert await identify._answering_kind(missing, serial_backends(), None, 1.0) is None
    with pytest.raises(CommunicationError):
        await attach(missing)

