"""The j5aio pytest plugin: fixtures for people who test robot backends.

Registered through the ``pytest11`` entry point, so installing j5aio makes its fixtures
available in every test suite, sync tests and async tests alike:

``j5aio_sim_kit``
    A fresh simulated kit with every board found and set up
    (an :class:`~j5aio.testing.simkit.OpenSimulatedKit`); the boards are closed and
    unregistered afterwards. Choose the boards with the ``j5aio_kit`` marker: a
    registered kit by name (a plugin's own kit too) or a
    :class:`~j5aio.board_kinds.KitDefinition`, or the keyword arguments of
    :class:`~j5aio.simulator.kit.KitConfig`::

        @pytest.mark.j5aio_kit(motor_boards=1, power_boards=0)
        async def test_drive(j5aio_sim_kit):
            ...

        @pytest.mark.j5aio_kit("bee")
        async def test_bee(j5aio_sim_kit):
            ...

``j5aio_pty_simulator``
    A factory: ``j5aio_pty_simulator("sb-arduino")`` serves a board simulator (by name,
    see :data:`~j5aio.simulator.SERIAL_SIMULATORS`, or a simulator object) on a
    pseudo-terminal and returns the path to open; every server is stopped afterwards.

``j5aio_faulty_stream``
    A factory: ``j5aio_faulty_stream(stream, schedule={2: Fault.drop()})`` wraps a byte
    stream in a :class:`~j5aio.testing.transports.FaultyStream`; every stream it made is
    closed afterwards.

``j5aio_clean_boards``
    Empties :attr:`Board.BOARDS <j5aio.boards.board.Board.BOARDS>` after the test, so
    that boards a test set up do not leak into the next one.

At the end of a run the plugin lists every conformance check that was skipped because
the subject lacked a hook (see :mod:`j5aio.testing.conformance`), so that a green run
cannot hide them.

The plugin loads in any test suite. ``j5aio_sim_kit`` is an async fixture and needs
pytest-asyncio; without it, a test that asks for the fixture fails with a message
saying what to install, and every other test runs as usual.
"""

from __future__ import annotations

import re
import sys
from collections.abc import AsyncIterator, Iterable, Iterator, Mapping
from typing import TYPE_CHECKING, Any

import pytest

try:
    import pytest_asyncio
except ImportError:  # the plugin must load anyway: only the async fixture needs it
    pytest_asyncio = None  # type: ignore[assignment]

if TYPE_CHECKING:
    from j5aio.backends.hardware.transports.memory import SerialSimulatorLike
    from j5aio.backends.hardware.transports.stream import ByteStream
    from j5aio.board_kinds import KitDefinition
    from j5aio.simulator.kit import KitConfig
    from j5aio.simulator.serve import PtyServer
    from j5aio.testing.simkit import OpenSimulatedKit
    from j5aio.testing.transports import Fault, FaultyStream

__all__ = [
    "FaultyStreamFactory",
    "PtySimulatorFactory",
    "j5aio_clean_boards",
    "j5aio_faulty_stream",
    "j5aio_pty_simulator",
    "j5aio_sim_kit",
    "pytest_configure",
    "pytest_terminal_summary",
]

KIT_MARKER = "j5aio_kit"


def pytest_configure(config: pytest.Config) -> None:
    """Register the plugin's marker."""
    config.addinivalue_line(
        "markers",
        f"{KIT_MARKER}(kit=None, **counts): the j5aio_sim_kit fixture's kit: a registered "
        "kit's name (a plugin's too) or a KitDefinition, or its boards as the keyword "
        "arguments of j5aio.simulator.kit.KitConfig",
    )


def pytest_terminal_summary(terminalreporter: pytest.TerminalReporter) -> None:
    """Say which conformance checks were skipped for want of a subject's hook.

    One line counts them and names the hooks; with ``-rs`` (or ``-v``) every skipped
    check is listed with its reason.
    """
    # Only a run that used the suites can have such skips; importing them otherwise
    # would need pytest-asyncio, which a suite without async tests may not have.
    base = sys.modules.get("j5aio.testing.conformance._base")
    if base is None:
        return
    mark: str = base.HOOK_SKIP_MARK
    lines: list[str] = []
    for report in terminalreporter.stats.get("skipped", []):
        longrepr = getattr(report, "longrepr", None)
        if isinstance(longrepr, tuple) and len(longrepr) == 3 and mark in longrepr[2]:
            lines.append(f"{report.nodeid}: {longrepr[2].removeprefix('Skipped: ')}")
    if not lines:
        return
    config = terminalreporter.config
    report_chars = config.getoption("reportchars", "") or ""
    if config.getoption("verbose", 0) > 0 or any(char in report_chars for char in "saA"):
        terminalreporter.section("j5aio conformance: checks not run for want of a hook")
        for line in lines:
            terminalreporter.write_line(line)
        return
    hooks = sorted({name for line in lines for name in re.findall(r"'(\w+)'", line)})
    terminalreporter.write_line(
        f"j5aio conformance: {len(lines)} check{'s' if len(lines) != 1 else ''} not run for "
        f"want of a subject's hook ({', '.join(repr(name) for name in hooks)}); "
        "-rs lists them"
    )


@pytest.fixture
def j5aio_clean_boards() -> Iterator[None]:
    """Empty ``Board.BOARDS`` after the test."""
    from j5aio.boards.board import Board

    yield
    Board.BOARDS.clear()


#: What a test that asks for an async fixture without pytest-asyncio is told.
NEEDS_PYTEST_ASYNCIO = (
    "the j5aio fixture {name!r} is async and needs pytest-asyncio: install it "
    "(pip install pytest-asyncio, or j5aio's 'test' extra) and enable it"
)


async def _sim_kit(request: pytest.FixtureRequest) -> AsyncIterator[OpenSimulatedKit]:
    """A fresh simulated kit, its boards set up; closed and unregistered afterwards."""
    from j5aio.testing.simkit import open_simulated_kit

    marker = request.node.get_closest_marker(KIT_MARKER)
    kit: KitConfig | KitDefinition | str | None = None
    if marker is not None:
        kit = _marked_kit(marker.args, marker.kwargs)
    async with open_simulated_kit(kit) as sim:
        yield sim


def _marked_kit(args: tuple[object, ...], counts: Mapping[str, object]) -> Any:
    """The kit a ``j5aio_kit`` marker chooses: a named kit, a definition, or board counts.

    :raises TypeError: the marker gives more than one kit, a kit together with counts,
        or something else than a kit's name, a KitDefinition or a KitConfig.
    """
    from j5aio.board_kinds import KitDefinition
    from j5aio.simulator.kit import KitConfig

    if not args:
        return KitConfig(**counts)  # type: ignore[arg-type]  # (KitConfig checks them)
    if len(args) > 1 or counts:
        raise TypeError(
            f"the {KIT_MARKER} marker takes one kit (a name, a KitDefinition or a KitConfig) "
            f"or KitConfig's keyword arguments, not both: it was given {args!r} and "
            f"{dict(counts)!r}"
        )
    kit = args[0]
    if not isinstance(kit, str | KitDefinition | KitConfig):
        raise TypeError(
            f"the {KIT_MARKER} marker's kit is a kit's name (such as 'sr2019' or a "
            f"plugin's), a KitDefinition or a KitConfig, not {kit!r}"
        )
    return kit


def _sim_kit_unavailable() -> None:
    """Stand in for ``j5aio_sim_kit`` without pytest-asyncio: say what to install."""
    pytest.fail(NEEDS_PYTEST_ASYNCIO.format(name="j5aio_sim_kit"), pytrace=False)


if pytest_asyncio is not None:
    j5aio_sim_kit = pytest_asyncio.fixture(_sim_kit, name="j5aio_sim_kit")
else:
    j5aio_sim_kit = pytest.fixture(_sim_kit_unavailable, name="j5aio_sim_kit")


class PtySimulatorFactory:
    """Serves board simulators on pseudo-terminals for one test; see ``j5aio_pty_simulator``."""

    def __init__(self) -> None:
        #: Every server started, in order.
        self.servers: list[PtyServer] = []

    def __call__(
        self,
        simulator: str | SerialSimulatorLike,
        *,
        serial_number: str = "SIM0",
        time_scale: float = 0.0,
    ) -> str:
        """Serve ``simulator`` on a new pseudo-terminal and return the path to open.

        :param simulator: a simulator, or the name of one in
            :data:`~j5aio.simulator.SERIAL_SIMULATORS` (``"sr-motor"``, ...).
        :param serial_number: the serial number of a simulator made by name.
        :param time_scale: multiplies the simulator's boot delay; ``0``: boot at once.
        :raises ValueError: no simulator has that name (the message lists them).
        """
        from j5aio.simulator import SERIAL_SIMULATORS
        from j5aio.simulator.serve import serve_on_pty

        if isinstance(simulator, str):
            try:
                factory = SERIAL_SIMULATORS[simulator]
            except KeyError:
                names = ", ".join(sorted(SERIAL_SIMULATORS))
                raise ValueError(
                    f"no simulator is called {simulator!r}; choose one of {names}",
                ) from None
            simulator = factory(serial_number)
        server = serve_on_pty(simulator, time_scale=time_scale)
        self.servers.append(server)
        return server.path

    def close(self) -> None:
        """Stop every server started."""
        while self.servers:
            self.servers.pop().close()


@pytest.fixture
def j5aio_pty_simulator() -> Iterator[PtySimulatorFactory]:
    """Factory: serve a simulator on a pseudo-terminal, get its path; stopped afterwards."""
    factory = PtySimulatorFactory()
    try:
        yield factory
    finally:
        factory.close()


class FaultyStreamFactory:
    """Wraps streams in :class:`.FaultyStream` for one test; see ``j5aio_faulty_stream``."""

    def __init__(self) -> None:
        #: Every stream made, in order.
        self.streams: list[FaultyStream] = []

    def __call__(
        self,
        inner: ByteStream,
        *,
        schedule: Mapping[int, Fault | Iterable[Fault]] | None = None,
    ) -> FaultyStream:
        """Wrap ``inner`` in a :class:`.FaultyStream` with the given fault ``schedule``."""
        from j5aio.testing.transports import FaultyStream

        stream = FaultyStream(inner, schedule=schedule)
        self.streams.append(stream)
        return stream

    def close(self) -> None:
        """Close every stream made (and so the streams they wrap)."""
        while self.streams:
            self.streams.pop().close_now()


@pytest.fixture
def j5aio_faulty_stream() -> Iterator[FaultyStreamFactory]:
    """Factory: wrap a byte stream in a FaultyStream; every one is closed afterwards."""
    factory = FaultyStreamFactory()
    try:
        yield factory
    finally:
        factory.close()
