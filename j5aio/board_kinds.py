"""The registry of board kinds: every kind of board j5aio (or a plugin) knows how to drive.

A :class:`BoardKind` is one generation of one board: its board class, the hardware
backend that finds it, the simulators that stand in for it (each with a command-line
name), its console backend, and the named simulated kits it belongs to. Everything that
needs a list of boards reads it from here:

- the hardware environment and ``python -m j5aio list`` (hardware backends);
- :func:`j5aio.backends.hardware.attach <j5aio.backends.hardware.identify.attach>` (serial backends'
  identification);
- the simulated environment, ``J5AIO_ENV=sim`` and ``run --sim`` (simulators);
- ``python -m j5aio simulate NAME`` (serial simulators, by name);
- the named kits (``--kit NAME``, ``J5AIO_KIT``, :func:`~j5aio.simulator.kit.use_kit`);
- the console environment (console backends).

j5aio's own boards are registered in ``j5aio.backends._builtin_kinds``. Other packages register
theirs through the ``j5aio.boards`` entry point group (:data:`ENTRY_POINT_GROUP`). An
entry point names an object that is one of:

- a :class:`BoardKind`;
- a :class:`KitDefinition` (a named simulated kit);
- an iterable of those;
- a callable taking no arguments that returns any of the above.

For example, in a plugin's ``pyproject.toml``::

    [project.entry-points."j5aio.boards"]
    beekit = "beekit.kinds:entries"

Plugins are loaded the first time the registry is read. A plugin that cannot be loaded,
or that returns something else, or that reuses a name already taken, is left out with a
:class:`BoardPluginWarning` naming the package and the entry point; j5aio itself carries
on.

This registry is not :mod:`j5aio.backends.hardware.registry`, which records which
board holds each open port.

The registry itself is kept among the backends (``j5aio.backends._kinds``), whose
environments and identification read it; it names the backends by import path, so it
imports none of them. This module is its public face: every name is documented, and
imported, from here.
"""

from __future__ import annotations

from typing import Final

from j5aio.backends import _kind_types, _kinds
from j5aio.backends._kinds import (
    DEFAULT_KIT,
    BackendField,
    BoardField,
    BoardKind,
    BoardPluginWarning,
    KitDefinition,
    SimulatorClass,
    SimulatorEntry,
    board_kinds,
    find_simulator,
    get_kit,
    kits,
    register,
    simulator_entries,
    unregister,
)

__all__ = [
    "DEFAULT_KIT",
    "ENTRY_POINT_GROUP",
    "BackendField",
    "BoardField",
    "BoardKind",
    "BoardPluginWarning",
    "KitDefinition",
    "SimulatorClass",
    "SimulatorEntry",
    "SimulatorFactory",
    "SimulatorTransport",
    "board_kinds",
    "find_simulator",
    "get_kit",
    "kits",
    "register",
    "simulator_entries",
    "unregister",
]

SimulatorFactory = _kind_types.SimulatorFactory
"""Makes a simulator given the serial number it reports: a
:class:`~j5aio.simulator.base.SerialBoardSimulator` (which ``simulate`` can serve on a
pty), a :class:`~j5aio.simulator.base.UsbBoardSimulator`, or, for a board reached
otherwise (a HAT's GPIO), a simulator of its own that the kind's ``simulated`` backend
finds in the kit."""

SimulatorTransport = _kind_types.SimulatorTransport
"""How a simulator's board is reached, as its :class:`SimulatorEntry` declares:
``"serial"`` (a :class:`~j5aio.simulator.base.SerialBoardSimulator`, which ``simulate``
can serve on a pty), ``"usb"`` (a :class:`~j5aio.simulator.base.UsbBoardSimulator`) or
``"other"`` (a HAT's GPIO, say)."""

#: The entry point group through which other packages register board kinds and kits.
ENTRY_POINT_GROUP: Final = _kinds.ENTRY_POINT_GROUP
