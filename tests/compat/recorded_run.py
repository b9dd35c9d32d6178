"""Run ``python -m j5aio run ARGS`` in this process, recording what the simulated boards get.

Usage: ``python recorded_run.py REPORT.json -- run [options] program.py``; Python code in
``COMPAT_SETUP`` is run first, with the kit as ``kit`` (to set the simulators' inputs). Every serial
board of the simulated kit (``J5AIO_KIT``) has the bytes it receives recorded; once the
program has ended and j5aio has made the boards safe, REPORT.json holds, per board (by
simulator name and serial number), the bytes received (latin-1 text) and the simulator's
final state that the tests look at.
"""

from __future__ import annotations

import atexit
import json
import os
import sys
from collections.abc import Callable
from typing import Any


def _record(received: list[bytes], receive: Callable[[bytes], bytes]) -> Callable[[bytes], bytes]:
    def recording(data: bytes) -> bytes:
        received.append(bytes(data))
        return receive(data)

    return recording


def _state(simulator: Any) -> dict[str, Any]:
    state: dict[str, Any] = {}
    for name in ("outputs", "pulse_widths"):
        if hasattr(simulator, name):
            state[name] = list(getattr(simulator, name))
    if hasattr(simulator, "motors"):
        state["motors"] = [str(getattr(motor, "drive", motor)) for motor in simulator.motors]
    return state


def main() -> None:
    report_path, separator, *arguments = sys.argv[1:]
    assert separator == "--", "usage: recorded_run.py REPORT.json -- run ..."
    os.environ.setdefault("J5AIO_ENV", "sim")
    # The recording is of this process's simulated kit: the program must run here, not
    # in a child of the match supervisor.
    os.environ["J5AIO_NO_SUPERVISOR"] = "1"
    from j5aio.simulator.kit import current_kit

    setup = os.environ.get("COMPAT_SETUP")
    if setup:
        exec(setup, {"kit": current_kit()})  # the test's own settings (or kit)
    kit = current_kit()
    boards: dict[str, tuple[Any, list[bytes]]] = {}
    for name in kit.simulator_names():
        for simulator in kit.simulators(name):
            if hasattr(simulator, "receive"):
                received: list[bytes] = []
                simulator.receive = _record(received, simulator.receive)
                boards[f"{name}/{getattr(simulator, 'serial_number', '?')}"] = (
                    simulator, received)

    def report() -> None:  # registered first, so it runs after j5aio's own exit work
        found = {
            name: {
                "received": b"".join(received).decode("latin-1"),
                "state": _state(simulator),
            }
            for name, (simulator, received) in boards.items()
        }
        with open(report_path, "w", encoding="utf-8") as file:
            json.dump(found, file)

    atexit.register(report)
    from j5aio.competition.timer import add_game_over_hook

    add_game_over_hook(report)  # (the process then ends with os._exit: no atexit)
    from j5aio.__main__ import main as j5aio_main

    sys.exit(j5aio_main(arguments))


if __name__ == "__main__":
    main()
