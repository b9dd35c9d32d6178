"""The live view's web server: aiohttp in a thread of its own, pushing over a WebSocket.

Imported only when a view is started (it needs the ``view`` extra). The server runs its
own event loop in a daemon thread, so it works the same beside an async program, a sync
one (whose loop is the facade's portal) or the demo, and never waits on the program.
Simulator controls are handed to the program's event loop, where the simulators live.

Every request needs the token of the printed URL; WebSocket and control requests from a
page of another origin are refused. The server serves one page (built from package data)
and reads nothing else from the disk; controls only call the simulators' control API.
"""

from __future__ import annotations

import asyncio
import contextlib
import hmac
import importlib.resources
import json
import logging
import secrets
import socket
import threading
import time
from collections.abc import Callable
from typing import Any, Final, TypeVar

from aiohttp import WSMsgType, web

from j5aio.boards.board import Board
from j5aio.simulator.kit import SimulatedKit

from .arena import describe_arena, describe_pose, kit_of
from .controls import ControlError, apply_control, controls_of
from .describe import component_id
from .state import ViewState
from .ticker import SharedTicker

__all__ = ["BOARDS_EVERY", "TICK_SECONDS", "ViewServer"]

LOGGER = logging.getLogger(__name__)
_T = TypeVar("_T")

#: How often a watching page is sent what changed: at most 20 updates a second per value.
TICK_SECONDS: Final = 0.05
#: How often the list of boards (states, firmware, controls) is sent again, in ticks.
BOARDS_EVERY: Final = 5
#: How long a control may take in the program's event loop before the request fails.
CONTROL_TIMEOUT: Final = 2.0


def _page(token: str, nonce: str) -> str:
    files = importlib.resources.files("j5aio.view") / "static"
    html = (files / "index.html").read_text(encoding="utf-8")
    return (
        html.replace("{{css}}", (files / "view.css").read_text(encoding="utf-8"))
        .replace("{{js}}", (files / "view.js").read_text(encoding="utf-8"))
        .replace("{{nonce}}", nonce)
        .replace("{{token}}", json.dumps(token))
    )


class ViewServer:
    """The web server of the live view, fed by a :class:`~j5aio.view.state.ViewState`.

    :param state: the values to show.
    :param program_loop: the program's event loop, where simulator controls run; ``None``:
        the loop of the latest board call the state observed.
    :param host: the address to bind.
    :param port: the port to bind (0: a free one).
    """

    def __init__(
        self,
        state: ViewState,
        program_loop: asyncio.AbstractEventLoop | None,
        host: str,
        port: int,
    ) -> None:
        self._state = state
        self._program_loop = program_loop
        self._host = host
        self._requested_port = port
        self.token = secrets.token_urlsafe(24)
        self.port = 0
        self._thread: threading.Thread | None = None
        self._loop: asyncio.AbstractEventLoop | None = None
        self._stop: asyncio.Event | None = None
        self._ready = threading.Event()
        self._failure: BaseException | None = None
        self.watchers = 0
        self._kit: SimulatedKit | None = None  # the simulated kit of the boards, if any
        self._arena: dict[str, Any] | None = None  # how the page draws its arena
        # The boards as last read, and how many times they have been read.
        self._boards_seen: list[dict[str, Any]] | None = None
        self._boards_version = 0
        self._ticker: SharedTicker[dict[str, Any]] | None = None  # made in the server loop

    @property
    def url(self) -> str:
        """The page's address with its token: what the program prints."""
        host = f"[{self._host}]" if ":" in self._host else self._host
        return f"http://{host}:{self.port}/?token={self.token}"

    def start(self) -> None:
        """Start serving in a new thread; return once the port is bound.

        :raises OSError: the port could not be bound.
        """
        self._thread = threading.Thread(target=self._run, name="j5aio view", daemon=True)
        self._thread.start()
        self._ready.wait()
        if self._failure is not None:
            raise self._failure

    def stop(self) -> None:
        """Stop serving and wait for the thread to end (open pages see the robot go)."""
        loop, stop = self._loop, self._stop
        if loop is not None and stop is not None and not loop.is_closed():
            with contextlib.suppress(RuntimeError):  # the loop ended on its own
                loop.call_soon_threadsafe(stop.set)
        if self._thread is not None:
            self._thread.join(5)
            self._thread = None

    def _run(self) -> None:
        try:
            asyncio.run(self._serve())
        except BaseException as error:  # handed to start(): bind failures
            self._failure = error
            self._ready.set()

    async def _serve(self) -> None:
        self._loop = asyncio.get_running_loop()
        self._stop = asyncio.Event()
        self._ticker = SharedTicker(self._read_program, TICK_SECONDS)
        app = web.Application(middlewares=[self._guard])
        app.router.add_get("/", self._index)
        app.router.add_get("/ws", self._websocket)
        app.router.add_post("/control", self._control)
        family = socket.AF_INET6 if ":" in self._host else socket.AF_INET
        listener = socket.socket(family, socket.SOCK_STREAM)
        try:
            listener.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
            listener.bind((self._host, self._requested_port))
        except OSError:
            listener.close()
            raise
        self.port = listener.getsockname()[1]
        runner = web.AppRunner(app, access_log=None, handle_signals=False)
        await runner.setup()
        try:
            await web.SockSite(runner, listener).start()
            self._ready.set()
            await self._stop.wait()
        finally:
            await runner.cleanup()

    # --- security ---

    @web.middleware
    async def _guard(
        self, request: web.Request, handler: Callable[[web.Request], Any]
    ) -> web.StreamResponse:
        token = request.query.get("token", "")
        if not hmac.compare_digest(token.encode(), self.token.encode()):
            return web.Response(status=403, text="j5aio view: wrong or missing token\n")
        origin = request.headers.get("Origin")
        if origin is not None and origin != f"http://{request.host}":
            return web.Response(status=403, text="j5aio view: requests from other sites refused\n")
        response: web.StreamResponse = await handler(request)
        response.headers.setdefault("Referrer-Policy", "no-referrer")
        response.headers.setdefault("X-Content-Type-Options", "nosniff")
        response.headers.setdefault("Cache-Control", "no-store")
        return response

    # --- handlers ---

    async def _index(self, request: web.Request) -> web.Response:
        nonce = secrets.token_urlsafe(16)
        response = web.Response(text=_page(self.token, nonce), content_type="text/html")
        response.headers["Content-Security-Policy"] = (
            f"default-src 'none'; script-src 'nonce-{nonce}'; style-src 'unsafe-inline'; "
            "connect-src 'self'; img-src 'self' data:; base-uri 'none'; form-action 'none'; "
            "frame-ancestors 'none'"
        )
        return response

    async def _websocket(self, request: web.Request) -> web.WebSocketResponse:
        ws = web.WebSocketResponse(heartbeat=10)
        await ws.prepare(request)
        self.watchers += 1
        self._state.watch_wire()
        pusher = asyncio.create_task(self._push(ws))
        try:
            async for message in ws:  # the page sends nothing that matters; wait for close
                if message.type == WSMsgType.ERROR:  # pragma: no cover - network error
                    break
        finally:
            pusher.cancel()
            self._state.unwatch_wire()
            self.watchers -= 1
        return ws

    @property
    def readings(self) -> int:
        """How many times the program has been read for the pages (one per tick, shared)."""
        return 0 if self._ticker is None else self._ticker.readings

    async def _read_program(self, tick: int) -> dict[str, Any]:
        """The ticker's reading: what every page is sent from the program this tick."""
        with_boards = tick % BOARDS_EVERY == 0
        snapshot: dict[str, Any] = {}
        if with_boards or self._kit is not None:  # else nothing to read in the program
            snapshot = await self._snapshot_if_running(with_boards)
        if "boards" in snapshot:
            self._boards_seen = snapshot["boards"]
            self._boards_version += 1
        return snapshot

    async def _push(self, ws: web.WebSocketResponse) -> None:
        """Send one page what changed, every tick. A slow page waits in send: never a queue.

        What is read in the program is read once per tick for every page together (see
        :mod:`.ticker`), so another page costs the robot's loop nothing more.
        """
        assert self._ticker is not None
        value_mark = log_mark = boards_version = 0
        tick = -1
        arena_key: str | None = None  # the arena this page has
        pose: dict[str, Any] | None = None  # the pose this page shows
        self._ticker.add_listener()
        try:
            while not ws.closed:
                tick, snapshot = await self._ticker.next_after(tick)
                message: dict[str, Any] = {"t": time.time()}
                if self._boards_version > boards_version and self._boards_seen is not None:
                    message["boards"] = self._boards_seen
                    boards_version = self._boards_version
                arena = snapshot.get("arena")
                if arena is not None and arena["key"] != arena_key:
                    message["arena"], arena_key = arena, arena["key"]
                if snapshot.get("pose") not in (None, pose):
                    message["pose"] = pose = snapshot["pose"]
                changes = self._state.changes(value_mark, log_mark)
                value_mark, log_mark = changes.value_mark, changes.log_mark
                if changes.values:
                    message["values"] = changes.values
                if changes.log:
                    message["log"] = changes.log
                if changes.dropped_log_lines:
                    message["dropped"] = changes.dropped_log_lines
                if len(message) > 1:
                    await ws.send_str(json.dumps(message))
        except (ConnectionError, asyncio.CancelledError):
            return
        except Exception:  # pragma: no cover - never let a page break the robot
            LOGGER.exception("live view: could not update a page")
            await ws.close()
        finally:
            self._ticker.remove_listener()

    async def _in_program(self, function: Callable[[], _T]) -> _T:
        """Run ``function`` in the program's event loop (where boards and simulators live)."""

        async def call() -> _T:
            return function()

        loop = self._program_loop or self._state.loop
        if loop is None:
            raise RuntimeError("the program has not called a board yet")
        future = asyncio.run_coroutine_threadsafe(call(), loop)
        return await asyncio.wait_for(asyncio.wrap_future(future), CONTROL_TIMEOUT)

    async def _snapshot_if_running(self, with_boards: bool) -> dict[str, Any]:
        try:
            return await self._in_program(lambda: self._snapshot(with_boards))
        except (RuntimeError, TimeoutError):  # the program's loop has ended or is stuck
            return {}

    def _snapshot(self, with_boards: bool) -> dict[str, Any]:
        """The boards (if asked), and the simulated arena and pose, read in the program."""
        snapshot: dict[str, Any] = {}
        if with_boards:
            snapshot["boards"] = self._boards()
            kit = kit_of(record.board for record in self._state.boards())
            if kit is not self._kit:
                self._kit, self._arena = kit, None if kit is None else describe_arena(kit)
        kit = self._kit
        if kit is not None:
            from j5aio.simulator.camera import update_world

            update_world(kit)  # to now, at the motors' powers: the page sees it move
            snapshot["arena"] = self._arena
            snapshot["pose"] = describe_pose(kit)
        return snapshot

    def _boards(self) -> list[dict[str, Any]]:
        shown = []
        for record in self._state.boards():
            board = record.board
            controls = controls_of(board, record.components)
            plugged = next((c["value"] for c in controls if c["name"] == "plug"), True)
            backend_state = getattr(board.backend, "connection_state", None)
            if record.closed:
                state = "closed"
            elif not plugged or self._state.error_of(board) is not None:
                state = "disconnected"
            elif backend_state is not None:
                state = str(getattr(backend_state, "value", backend_state))
            else:
                state = "connected"
            shown.append({
                "serial": board.serial_number,
                "name": board.name,
                "type": type(board).__name__,
                "firmware": board.firmware_version,
                "state": state,
                "error": self._state.error_of(board),
                "simulated": bool(controls),
                "components": [
                    {"id": component_id(board.serial_number, c), "kind": c.kind,
                     "identifier": c.identifier, "name": record.names.get(c)}
                    for c in record.components
                ],
                "controls": controls,
            })
        return shown

    async def _control(self, request: web.Request) -> web.Response:
        try:
            body = await request.json()
            target, value = str(body["control"]), body.get("value")
        except (ValueError, KeyError, TypeError):
            return web.json_response({"error": "send JSON: {control, value}"}, status=400)
        serial, _, name = target.partition(":")
        board = next((b for b in list(Board.BOARDS) if b.serial_number == serial), None)
        if board is None:
            return web.json_response({"error": f"no board {serial!r}"}, status=404)
        try:
            await self._in_program(lambda: apply_control(board, name, value))
        except ControlError as error:
            return web.json_response({"error": str(error)}, status=400)
        except (RuntimeError, TimeoutError) as error:
            message = f"the program's event loop cannot take the control now ({error})"
            return web.json_response({"error": message}, status=503)
        return web.json_response({"ok": True})
