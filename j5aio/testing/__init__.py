"""The kit for people who write backends: fakes, fault injection, conformance suites.

* :mod:`j5aio.testing.transports`: byte streams to hand a backend in place of a serial
  port. :class:`~j5aio.testing.transports.ScriptedStream` answers a fixed script of requests,
  :class:`~j5aio.testing.transports.RecordingStream` records the traffic of any stream, and
  :class:`~j5aio.testing.transports.FaultyStream` injects faults into any stream (a delayed, dropped
  or corrupted reply, a disconnection, a board gone silent).
* :mod:`j5aio.testing.conformance`: one suite of tests per interface, which any backend
  claiming that interface runs against itself by subclassing the suite.
* :class:`~j5aio.testing.console.ConsoleScript`: plays the user of a console backend, answering its
  prompts.
* :func:`~j5aio.testing.simkit.open_simulated_kit`: a fresh simulated kit with its boards set up.
* :mod:`j5aio.testing.mosquitto`: a real MQTT broker of a test's own, for code that talks
  to the robot service's broker.
* :mod:`j5aio.testing.plugin`: the pytest plugin (fixtures ``j5aio_sim_kit``,
  ``j5aio_pty_simulator``, ``j5aio_faulty_stream`` and ``j5aio_clean_boards``), active
  wherever j5aio is installed.

``docs/testing-backends.rst`` walks through adding a board of your own (a backend, its
simulator, its tests and its sync face) with all of these.
"""

from j5aio.testing.console import ConsoleScript
from j5aio.testing.simkit import OpenSimulatedKit, open_simulated_kit
from j5aio.testing.transports import (
    Fault,
    FaultKind,
    FaultyStream,
    RecordingStream,
    ScriptedStream,
    WireEvent,
)

__all__ = [
    "ConsoleScript",
    "Fault",
    "FaultKind",
    "FaultyStream",
    "OpenSimulatedKit",
    "RecordingStream",
    "ScriptedStream",
    "WireEvent",
    "open_simulated_kit",
]
