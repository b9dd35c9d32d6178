"""The live view: a web page showing every board while a program runs.

Start it with ``python -m j5aio run --view program.py`` (or ``--sim --view``, or
``python -m j5aio demo --view``), with ``KitRobot(view=True)``, or, in any async program::

    from j5aio.view import serve_view

    async with serve_view() as view:     # prints "View: http://127.0.0.1:PORT/?token=..."
        ...                               # the program

It needs the ``view`` extra (``pip install 'j5aio[view]'``, which brings aiohttp);
``import j5aio`` and ``import j5aio.view`` never import the web stack, only starting a view
does. See the "Live view" page of the documentation.
"""

from __future__ import annotations

import asyncio
import contextlib
import os
import sys
from collections.abc import AsyncIterator
from dataclasses import dataclass
from typing import TYPE_CHECKING, Final, TextIO

from j5aio.backends.backend import CALL_OBSERVERS

if TYPE_CHECKING:
    from .server import ViewServer
    from .state import ViewState

__all__ = [
    "DEFAULT_HOST",
    "INSTALL_HINT",
    "VIEW_HOST_VARIABLE",
    "VIEW_PORT_VARIABLE",
    "VIEW_VARIABLE",
    "LiveView",
    "ViewNotInstalledError",
    "current_view",
    "serve_view",
    "start_view",
    "view_requested",
    "web_stack_installed",
]

#: The address the view binds unless told otherwise: this computer only.
DEFAULT_HOST: Final = "127.0.0.1"
#: Set to ``1`` (``python -m j5aio run --view`` does) to make ``KitRobot`` start a view.
VIEW_VARIABLE: Final = "J5AIO_VIEW"
#: The port of the view started through :data:`VIEW_VARIABLE` (default: a free one).
VIEW_PORT_VARIABLE: Final = "J5AIO_VIEW_PORT"
#: The address of the view started through :data:`VIEW_VARIABLE` (default 127.0.0.1).
VIEW_HOST_VARIABLE: Final = "J5AIO_VIEW_HOST"
#: What to install for the view.
INSTALL_HINT: Final = "pip install 'j5aio[view]'"


class ViewNotInstalledError(ImportError):
    """The live view was asked for, but its web stack (the ``view`` extra) is not installed."""


@dataclass
class LiveView:
    """A running live view: its address, and how to stop it.

    :param url: the page's address, with its token.
    :param server: the web server.
    :param state: the observer feeding it.
    """

    url: str
    server: ViewServer
    state: ViewState

    @property
    def watchers(self) -> int:
        """How many pages are watching now."""
        return self.server.watchers

    def close(self) -> None:
        """Stop observing and serving. Safe to call twice."""
        global _current
        if self.state in CALL_OBSERVERS:
            CALL_OBSERVERS.remove(self.state)
        self.server.stop()
        if _current is self:
            _current = None


_current: LiveView | None = None


def current_view() -> LiveView | None:
    """The live view running in this program, if one is (the first one started)."""
    return _current


def web_stack_installed() -> bool:
    """Whether the view's web stack (the ``view`` extra) can be imported. Imports it if so."""
    try:
        import aiohttp  # noqa: F401
    except ImportError:
        return False
    return True


def view_requested() -> bool:
    """Whether the environment asks for a view (``J5AIO_VIEW=1``, set by ``--view``)."""
    return os.environ.get(VIEW_VARIABLE, "") not in ("", "0")


def start_view(
    *,
    host: str | None = None,
    port: int | None = None,
    loop: asyncio.AbstractEventLoop | None = None,
    out: TextIO | None = None,
) -> LiveView:
    """Start observing every board and serving the page; print its one ``View:`` line.

    It may be called before the program's event loop runs (``python -m j5aio run --view``
    does): simulator controls then go to the loop of the latest board call. Without ``host`` and
    ``port`` the environment's :data:`VIEW_HOST_VARIABLE` / :data:`VIEW_PORT_VARIABLE`
    apply, else 127.0.0.1 on a free port. Any other address than the loopback prints a
    warning: anyone who can reach it and has the token sees the robot.

    :param host: the address to bind.
    :param port: the port to bind (0: a free one).
    :param loop: the program's event loop; by default the running one, if any, else the
        loop of the latest board call.
    :param out: where the ``View:`` line goes (standard output by default).
    :raises ViewNotInstalledError: the ``view`` extra is not installed.
    :raises ValueError: ``port`` is not 0 to 65535.
    :raises OSError: the address could not be bound.
    """
    if not web_stack_installed():
        raise ViewNotInstalledError(
            f"the live view needs the 'view' extra: {INSTALL_HINT} (it brings aiohttp)"
        )
    from .server import ViewServer
    from .state import ViewState

    host = host if host is not None else os.environ.get(VIEW_HOST_VARIABLE, DEFAULT_HOST)
    if port is None:
        text = os.environ.get(VIEW_PORT_VARIABLE, "0")
        try:
            port = int(text)
        except ValueError:
            raise ValueError(f"{VIEW_PORT_VARIABLE} must be a port number, not {text!r}") from None
    if isinstance(port, bool) or not isinstance(port, int) or not 0 <= port <= 65535:
        raise ValueError(f"the view's port must be an int from 0 to 65535, not {port!r}")
    if host not in (DEFAULT_HOST, "localhost", "::1"):
        print(
            f"j5aio: WARNING: the live view listens on {host}, not only on this computer: "
            "anyone who can reach it and has the link can watch the robot and use the "
            "simulator controls.",
            file=sys.stderr,
            flush=True,
        )
    if loop is None:
        with contextlib.suppress(RuntimeError):
            loop = asyncio.get_running_loop()
    state = ViewState()
    server = ViewServer(state, loop, host, port)
    server.start()
    CALL_OBSERVERS.append(state)
    view = LiveView(server.url, server, state)
    global _current
    if _current is None:
        _current = view
    print(f"View: {view.url}", file=out if out is not None else sys.stdout, flush=True)
    return view


@contextlib.asynccontextmanager
async def serve_view(
    *, host: str | None = None, port: int | None = None, out: TextIO | None = None
) -> AsyncIterator[LiveView]:
    """Serve the live view for the duration of an ``async with`` block (see :func:`start_view`)."""
    view = start_view(host=host, port=port, out=out)
    try:
        yield view
    finally:
        view.close()
