"""Sphinx configuration for the j5aio documentation."""

project = "j5aio"
author = "j5aio developers"
copyright = "2026, j5aio developers"
extensions = ["sphinx.ext.autodoc", "sphinx.ext.intersphinx", "sphinx.ext.viewcode"]
autodoc_member_order = "bysource"
autodoc_typehints = "description"
autodoc_default_options = {"members": True, "show-inheritance": True}
nitpicky = True
exclude_patterns = ["_build"]
html_theme = "alabaster"
intersphinx_mapping: dict[str, tuple[str, None]] = {}

# Every reference must resolve (nitpicky), with no exception for the API pages. The docs
# build offline (fetching an intersphinx inventory would tie the build to the network), so names
# outside j5aio cannot be cross-referenced; each one that the API's signatures and base
# classes name is listed here, and nothing else is ignored. A new foreign name in a
# signature fails the build until it is added below, on purpose.
nitpick_ignore = [
    # The standard library. ``Path``, ``datetime`` and ``timedelta`` are how the string
    # annotations of modules with ``from __future__ import annotations`` name them.
    ("py:class", "Path"),
    ("py:class", "abc.ABC"),
    ("py:class", "abc.ABCMeta"),
    ("py:class", "argparse.ArgumentParser"),
    ("py:class", "argparse.Namespace"),
    ("py:class", "array.array"),
    ("py:class", "asyncio.AbstractEventLoop"),
    ("py:class", "asyncio.events.AbstractEventLoop"),
    ("py:class", "collections.abc.AsyncIterator"),
    ("py:class", "collections.abc.Awaitable"),
    ("py:class", "collections.abc.Callable"),
    ("py:class", "collections.abc.Collection"),
    ("py:class", "collections.abc.ItemsView"),
    ("py:class", "collections.abc.Iterable"),
    ("py:class", "collections.abc.Iterator"),
    ("py:class", "collections.abc.KeysView"),
    ("py:class", "collections.abc.Mapping"),
    ("py:class", "collections.abc.Sequence"),
    ("py:class", "collections.abc.ValuesView"),
    ("py:class", "datetime"),
    ("py:class", "datetime.timedelta"),
    ("py:class", "timedelta"),
    ("py:class", "Enum"),
    ("py:class", "enum.Enum"),
    ("py:class", "enum.IntEnum"),
    ("py:class", "enum.StrEnum"),
    ("py:class", "logging.Logger"),
    ("py:class", "os.PathLike"),
    ("py:class", "pathlib.Path"),
    ("py:class", "random.Random"),
    ("py:class", "tempfile.TemporaryDirectory"),
    ("py:class", "threading.Thread"),
    ("py:func", "time.monotonic"),
    ("py:func", "time.perf_counter"),
    # Third-party libraries: anyio, pytest (the plugin's hooks), pyserial, pyusb.
    ("py:class", "_pytest.config.Config"),
    ("py:class", "_pytest.terminal.TerminalReporter"),
    ("py:class", "anyio.Lock"),
    ("py:class", "anyio.abc.AsyncResource"),
    ("py:class", "pytest.FixtureRequest"),
    ("py:class", "serial.SerialBase"),
    ("py:class", "serial.serialutil.SerialBase"),
    ("py:class", "usb.core.USBError"),
    ("py:class", "usb.core.USBTimeoutError"),
    # How the generated sync facade's string annotations name a core class inside a
    # container (KitRobot's boards=).
    ("py:class", "_boards_board.Board"),
    # Type variables of generic j5aio classes and functions: Sphinx has no target for a
    # TypeVar (the short names are how string annotations spell them).
    ("py:class", "InterfaceT"),
    ("py:class", "K"),
    ("py:class", "P_co"),
    ("py:class", "ReadingT"),
    ("py:class", "T_co"),
    ("py:class", "j5aio.backends.console.console.T"),
    ("py:class", "j5aio.concurrency._T1"),
    ("py:class", "j5aio.concurrency._T2"),
    ("py:class", "j5aio.concurrency._T3"),
    ("py:class", "j5aio.concurrency._T4"),
    ("py:class", "j5aio.concurrency._T5"),
    ("py:class", "j5aio.concurrency._T6"),
    ("py:class", "j5aio.backends.environment.BoardT"),
    ("py:class", "j5aio.backends.hardware.serial_backend.T"),
    ("py:class", "j5aio.backends.hardware.serial_backend.U"),
    ("py:class", "j5aio.backends.hardware.transports.completion.T"),
    ("py:class", "j5aio.backends.hardware.transports.readers.T_co"),
    ("py:class", "j5aio.backends.hardware.transports.serial_link.T"),
    ("py:class", "j5aio.backends.hardware.transports.serial_link.U"),
    ("py:class", "j5aio.backends.hardware.transports.usb_link.T"),
    ("py:class", "j5aio.boards.board_group.BoardT"),
    ("py:class", "j5aio.kit.BoardT"),
    ("py:class", "j5aio.numbered.P_co"),
    ("py:class", "j5aio.sync._runtime.T"),
    ("py:class", "j5aio.sync.wrapping.W"),
    ("py:class", "j5aio.testing.conformance._base.SubjectT"),
    ("py:class", "j5aio.testing.conformance._base.ValueT"),
    ("py:class", "j5aio.testing.simkit.BoardT"),
    ("py:class", "j5aio.view.ticker.ReadingT"),
    ("py:class", "j5aio.vision.worker.T"),
    ("py:class", "~P"),
    ("py:obj", "j5aio.backends.hardware.transports.readers.T_co"),
    ("py:obj", "j5aio.boards.board_group.BoardT"),
    ("py:obj", "j5aio.kit.BoardT"),
    ("py:obj", "j5aio.components.identified.InterfaceT"),
    ("py:obj", "j5aio.components.power_output.K"),
    ("py:obj", "j5aio.numbered.P_co"),
    ("py:obj", "j5aio.numbered.T_co"),
    ("py:obj", "j5aio.sync.wrapping.K"),
    ("py:obj", "j5aio.sync.wrapping.V"),
    ("py:obj", "j5aio.testing.conformance._base.SubjectT"),
    ("py:obj", "j5aio.view.ticker.ReadingT"),
    ("py:obj", "typing.~P"),
]


def _keep_constants(
    app: object, what: str, name: str, obj: object, skip: bool, options: object
) -> bool | None:
    """Show a class's named constants (an Enum's members, ``Colour.RED``) with no docstring.

    Autodoc leaves out members without a docstring; an enumeration's members are its whole
    point (``PowerBoardOutput.H0``, ``Note.A6``), so they are always listed.
    """
    import enum

    if what == "class" and (isinstance(obj, enum.Enum) or (name.isupper() and not callable(obj))):
        return False
    return None


def _hide_record_base(
    app: object, name: str, obj: object, options: object, bases: list[type]
) -> None:
    """Leave j5aio's private ``Record`` and ``FrozenRecord`` out of a class's listed bases.

    They only supply the methods ``@dataclass`` would generate to a few dataclasses that
    write their own ``__init__`` (a start-up saving); to a reader they are plain dataclasses.
    """
    from j5aio._records import FrozenRecord, Record

    bases[:] = [base for base in bases if base not in (Record, FrozenRecord)] or [object]


def setup(app: object) -> None:
    """Connect the hooks above."""
    app.connect("autodoc-skip-member", _keep_constants)  # type: ignore[attr-defined]
    app.connect("autodoc-process-bases", _hide_record_base)  # type: ignore[attr-defined]
