"""The simulator controls of the live view: the student plays the world's part.

Only boards of the simulated kit have controls, and every control goes through the
simulator's own control API (``press_start``, ``set_analogue``, ``unplug``...). Controls
are named as the page's ``data-control`` attributes: ``start-button``, ``pin-<n>``,
``analog-<pin>``, ``ultrasound-<trigger>-<echo>``, ``battery-voltage`` and ``plug``.

Simulators are plain state machines of the program's event-loop thread, so
:func:`apply_control` must run in that thread (the server hands it over).
"""

from __future__ import annotations

import asyncio
import math
from typing import Any, Final

from j5aio.boards.board import Board
from j5aio.simulator.arduino_base import ArduinoBoardSimulator
from j5aio.simulator.kit import current_kit

from .describe import ComponentInfo

__all__ = ["PRESS_SECONDS", "ControlError", "apply_control", "controls_of", "simulator_of"]

#: How long a click holds the start button down, in seconds.
PRESS_SECONDS: Final = 0.3

_DIGITAL_PINS: Final = range(2, 14)
_ANALOGUE_PINS: Final = range(14, 20)
#: The highest voltage an Arduino's analogue input takes.
_MAX_VOLTS: Final = 5.0
_MAX_BATTERY_VOLTS: Final = 30.0
_MAX_METRES: Final = 10.0
#: Metres to the object per microsecond of echo (sound at 343 m/s, there and back).
_METRES_PER_ECHO_US: Final = 343.0e-6 / 2


class ControlError(ValueError):
    """A control request the view refuses: unknown board or control, or a bad value."""


def simulator_of(board: Board) -> Any | None:
    """The simulator behind ``board`` on the current simulated kit, or ``None`` (hardware)."""
    from j5aio.simulator.environment import SIMULATED_BACKENDS

    backend = board.backend
    # A kind without a simulated backend of its own is found by a subclass of its hardware
    # backend made for it (named ...Simulated), which lives in the hardware backend's module.
    if not (
        type(backend).__module__.startswith("j5aio.simulator")
        or isinstance(backend, SIMULATED_BACKENDS)
    ):
        return None
    kit = current_kit()
    for simulator in (*kit, *kit.other_simulators()):
        if getattr(simulator, "serial_number", None) == board.serial_number:
            return simulator
    return None


def controls_of(board: Board, components: list[ComponentInfo]) -> list[dict[str, Any]]:
    """The controls the page offers for ``board``, with their current values (none on hardware)."""
    simulator = simulator_of(board)
    if simulator is None:
        return []
    found: list[dict[str, Any]] = []
    if hasattr(simulator, "press_start"):
        # fw 3 tells whether the button is down; fw 4 whether a press is latched, unread.
        pressed = getattr(simulator, "start_button_pressed", None)
        if pressed is None:
            pressed = any(getattr(simulator, "start_latches", ()))
        found.append({"name": "start-button", "type": "button", "value": bool(pressed)})
    if hasattr(simulator, "battery_voltage"):
        found.append({"name": "battery-voltage", "type": "number", "min": 0,
                      "max": _MAX_BATTERY_VOLTS, "step": 0.1,
                      "value": simulator.battery_voltage})
    if isinstance(simulator, ArduinoBoardSimulator):
        pins = simulator.pins
        for pin in _DIGITAL_PINS:
            level = pins.input_level(pin)
            found.append({"name": f"pin-{pin}", "type": "level",
                          "value": "float" if level is None else ("high" if level else "low")})
        for pin in _ANALOGUE_PINS:
            found.append({"name": f"analog-{pin}", "type": "number", "min": 0,
                          "max": _MAX_VOLTS, "step": 0.01,
                          "value": round(pins.analogue(pin) * _MAX_VOLTS / 1023, 3)})
        for info in components:
            if info.kind == "ultrasoundsensor":
                trigger, echo = (int(p) for p in info.identifier.split("-"))
                echo_us = simulator.ultrasound_echo(trigger, echo)
                metres = None if echo_us is None else round(echo_us * _METRES_PER_ECHO_US, 3)
                found.append({"name": f"ultrasound-{trigger}-{echo}", "type": "number",
                              "min": 0, "max": _MAX_METRES, "step": 0.01, "value": metres})
    if hasattr(simulator, "unplug"):
        found.append({"name": "plug", "type": "plug", "value": bool(simulator.connected)})
    return found


def apply_control(board: Board, name: str, value: object) -> None:
    """Set control ``name`` of ``board``'s simulator to ``value``, in the event-loop thread.

    :raises ControlError: the board has no simulator, there is no such control, or the
        value is not one the control takes (nothing is changed then).
    """
    simulator = simulator_of(board)
    if simulator is None:
        raise ControlError(f"{board.serial_number} is real hardware: the view is read-only")
    kind, _, rest = name.partition("-")
    if name == "start-button" and hasattr(simulator, "press_start"):
        simulator.press_start()
        asyncio.get_running_loop().call_later(PRESS_SECONDS, simulator.release_start)
    elif name == "battery-voltage" and hasattr(simulator, "battery_voltage"):
        simulator.battery_voltage = _number(value, 0, _MAX_BATTERY_VOLTS, name)
    elif name == "plug" and hasattr(simulator, "unplug"):
        if not isinstance(value, bool):
            raise ControlError("plug takes true (plug in) or false (unplug)")
        simulator.plug() if value else simulator.unplug()
    elif isinstance(simulator, ArduinoBoardSimulator) and kind in ("pin", "analog", "ultrasound"):
        _arduino_control(simulator, kind, rest, value, name)
    else:
        raise ControlError(f"{board.serial_number} has no control {name!r}")


def _arduino_control(
    simulator: ArduinoBoardSimulator, kind: str, rest: str, value: object, name: str
) -> None:
    try:
        pins = [int(part) for part in rest.split("-")]
    except ValueError:
        raise ControlError(f"no control {name!r}: pins are numbers") from None
    if kind == "pin" and len(pins) == 1 and pins[0] in _DIGITAL_PINS:
        levels = {"high": True, "low": False, "float": None}
        if value not in levels:
            raise ControlError(f"{name} takes 'high', 'low' or 'float', not {value!r}")
        simulator.set_input_level(pins[0], levels[value])
    elif kind == "analog" and len(pins) == 1 and pins[0] in _ANALOGUE_PINS:
        simulator.set_analogue(pins[0], volts=_number(value, 0, _MAX_VOLTS, name))
    elif kind == "ultrasound" and len(pins) == 2 and all(p in range(20) for p in pins):
        metres = None if value is None else _number(value, 0, _MAX_METRES, name)
        simulator.set_ultrasound_distance(pins[0], pins[1], metres)
    else:
        raise ControlError(f"no control {name!r} on this board")


def _number(value: object, low: float, high: float, name: str) -> float:
    if isinstance(value, bool) or not isinstance(value, int | float) or not math.isfinite(value):
        raise ControlError(f"{name} takes a number from {low} to {high}, not {value!r}")
    if not low <= value <= high:
        raise ControlError(f"{name} takes a number from {low} to {high}, not {value}")
    return float(value)
