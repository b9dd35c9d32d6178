"""How many j5aio functions a call runs before its bytes reach the board.

For each case, on the simulated kit, every distinct j5aio function entered (in any thread:
the caller's, the event loop's, a USB link's worker) from the start of the call until the
request's bytes are handed over is recorded with ``sys.setprofile`` and
``threading.setprofile``, and printed as ``module:function``, with the count:

* ``motor.power = 0.5`` through the sync facade, and ``await motor.set_power(0.5)``, on
  the sr2019 kit (motor board firmware 3) and the sr2023 kit (firmware 4);
* ``start_button.wait_until_pressed()``, sync and async, on the sr2019 kit's power board
  (firmware 3: USB control transfers, the button read on the link's worker thread) and
  the sr2023 kit's (firmware 4: serial text): from the call to the first poll's bytes
  (``call``); then, while nobody presses, what one poll runs, from one poll's bytes to
  the next's (``per poll``); and from the press to the call returning (``press``).

What counts: a function whose code is in a file of the j5aio package, the generated sync
facade included, but not the board simulators (``j5aio/simulator``: they stand for the
board, on the far side of the wire). Lambdas and closures count as functions of their
own. A function counts once however often it runs (a coroutine resumed counts once).

Where counting stops (the *hand-over*): the first call, from j5aio's host code, of a
simulated board's ``receive`` (what a serial port's bytes reach) or of a device's
``ctrl_transfer`` (pyusb's, or the simulated device's standing in for it), or of
``os.write``. The simulator's own functions under a hand-over are never counted.

Each case runs in a fresh interpreter, with the profiler installed before the robot
starts (``threading.setprofile`` reaches only threads started after it), and each call is
made once to warm up, then measured. Run::

    python bench/bench_call_path.py [--cases NAME,...] [--quiet]

``motor.power = 0.5`` is measured twice. The sync facade confirms acknowledgements later
(see :mod:`j5aio.backends.acknowledgements`): on the firmware 4 board, a command returns
once written, and the board's next request first reads the ``ACK`` it is owed. So what a
command runs depends on what came before it on that board:

* ``nothing owed`` (the goal's figure): the board's previous request was a query (the
  motor's power read back), which read the last ``ACK``; this is the path of a command
  in a loop that also reads something from the board, and of every command on
  firmware 3 (whose board sends no acknowledgement);
* ``the last ACK owed``: the previous request was a command too (the warm-up's), so this
  one reads its ``ACK`` first. That is real work on the command's path, counted in
  full: the figure is printed beside the goal's, never hidden.

Goal: ``motor.power = 0.5`` (nothing owed) and ``wait_until_pressed`` each <= 15 j5aio
functions to the bytes.
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import threading
from collections.abc import Callable, Iterable, Iterator
from contextlib import contextmanager
from dataclasses import dataclass, field
from pathlib import Path
from types import CodeType, FrameType
from typing import Any

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
GOAL = 15

#: The names of the functions that take a request's bytes from the host (see the module).
HANDOVER_NAMES = frozenset({"receive", "ctrl_transfer"})
#: The C functions that hand bytes to the operating system.
HANDOVER_C_FUNCTIONS: tuple[object, ...] = (os.write,)


@dataclass
class Segment:
    """The functions entered between two events (a start, a hand-over, an end)."""

    functions: list[str] = field(default_factory=list)
    #: The hand-over that ended the segment (``None``: it ended otherwise).
    ended_by: str | None = None


class CallPathCounter:
    """Records the distinct functions of a package entered in every thread.

    Install it (:meth:`installed`) before the threads of interest start. Then
    :meth:`record` starts a recording of ``segments`` segments: each hand-over ends the
    current segment, and the recording stops after the last (or at :meth:`stop`).

    :param package: the directory whose code counts.
    :param board_side: directories inside it whose code is the board's (never counted);
        a call from counted code into a function of these named in ``handover_names`` is
        a hand-over.
    :param handover_names: the function names of a hand-over (see above), and of a call
        into code outside ``package`` that is one (a pyusb device's ``ctrl_transfer``).
    :param handover_c_functions: C functions whose call is a hand-over (``os.write``).
    """

    def __init__(
        self,
        package: Path,
        *,
        board_side: Iterable[Path] = (),
        handover_names: Iterable[str] = HANDOVER_NAMES,
        handover_c_functions: Iterable[object] = HANDOVER_C_FUNCTIONS,
    ) -> None:
        self._package = str(package.resolve()) + os.sep
        self._board_side = tuple(str(path.resolve()) + os.sep for path in board_side)
        self._handover_names = frozenset(handover_names)
        self._handover_c = tuple(handover_c_functions)
        self._kinds: dict[CodeType, str] = {}  # "count", "board", "other"
        self._inside: dict[int, FrameType] = {}  # thread -> the hand-over frame it runs
        self._recording = False
        self._segments: list[Segment] = []
        self._seen: set[CodeType] = set()
        self._left = 0
        self._done = threading.Event()
        self._lock = threading.Lock()

    # -- installing ----------------------------------------------------------------------

    @contextmanager
    def installed(self) -> Iterator[CallPathCounter]:
        """Profile this thread and every thread started from now on, until the end."""
        sys.setprofile(self._profile)
        threading.setprofile(self._profile)
        try:
            yield self
        finally:
            threading.setprofile(None)
            sys.setprofile(None)

    # -- recording -----------------------------------------------------------------------

    def record(self, segments: int | None = 1) -> None:
        """Start recording: ``segments`` segments (``None``: one, until :meth:`stop`)."""
        with self._lock:
            self._segments = [Segment()]
            self._seen = set()
            self._left = -1 if segments is None else segments
            # A hand-over that ended an earlier recording returned unseen.
            self._inside.clear()
            self._done.clear()
            self._recording = True

    def stop(self) -> list[Segment]:
        """Stop recording (if it has not stopped) and return the segments recorded."""
        with self._lock:
            if self._recording:
                self._recording = False
                self._done.set()
            return self._segments

    def wait(self, timeout: float) -> bool:
        """Wait until the recording has stopped by itself; ``False`` if it did not."""
        return self._done.wait(timeout)

    @property
    def segments(self) -> list[Segment]:
        """The segments of the last recording (the last one may still grow)."""
        return self._segments

    # -- the profile function ------------------------------------------------------------

    def _kind(self, code: CodeType) -> str:
        kind = self._kinds.get(code)
        if kind is None:
            filename = os.path.abspath(code.co_filename)
            if filename.startswith(self._board_side):
                kind = "board"
            elif filename.startswith(self._package):
                kind = "count"
            else:
                kind = "other"
            self._kinds[code] = kind
        return kind

    def _name(self, code: CodeType) -> str:
        relative = os.path.relpath(os.path.abspath(code.co_filename), Path(self._package).parent)
        module = relative.removesuffix(".py").removesuffix(f"{os.sep}__init__")
        module = module.replace(os.sep, ".")
        return f"{module}:{code.co_qualname}"

    def _profile(self, frame: FrameType, event: str, arg: Any) -> None:
        if not self._recording:
            return
        thread = threading.get_ident()
        inside = self._inside.get(thread)
        if inside is not None:
            if event == "return" and frame is inside:
                del self._inside[thread]
            return
        if event == "call":
            code = frame.f_code
            kind = self._kind(code)
            if kind == "count":
                if code not in self._seen:
                    self._seen.add(code)
                    self._segments[-1].functions.append(self._name(code))
                return
            if code.co_name in self._handover_names and self._called_from_host(frame):
                self._inside[thread] = frame
                self._handover(self._name(code) if kind != "other" else code.co_qualname)
        elif event == "c_call" and any(arg is function for function in self._handover_c):
            self._handover(getattr(arg, "__qualname__", repr(arg)))

    def _called_from_host(self, frame: FrameType) -> bool:
        caller = frame.f_back
        return caller is not None and self._kind(caller.f_code) == "count"

    def _handover(self, name: str) -> None:
        with self._lock:
            if not self._recording:
                return
            if self._left < 0:
                return  # one segment, until stopped
            self._segments[-1].ended_by = name
            self._left -= 1
            if self._left == 0:
                self._recording = False
                self._done.set()
                return
            self._segments.append(Segment())
            self._seen = set()


def j5aio_counter() -> CallPathCounter:
    """The counter of j5aio's functions (this checkout's), the simulators excluded."""
    import j5aio

    package = Path(j5aio.__file__).resolve().parent
    return CallPathCounter(package, board_side=[package / "simulator"])


# -- the cases (each run in a child interpreter) ------------------------------------------

KITS = {"fw3": "sr2019", "fw4": "sr2023"}
CASES = tuple(
    f"{face} {what} {fw}"
    for what in ("motor.power", "wait_until_pressed")
    for fw in ("fw3", "fw4")
    for face in ("sync", "async")
)
#: How long a case waits for a hand-over before it says none came.
PATIENCE = 10.0


def _use_kit(firmware: str) -> Any:
    from j5aio.simulator.kit import use_kit

    kit = use_kit(KITS[firmware])
    kit.camera = None  # its simulated world's ticks would run beside every call
    return kit


def _measure_motor(
    counter: CallPathCounter, set_power: Callable[[], None], read_power: Callable[[], object]
) -> list[Segment]:
    """Two segments: the command with nothing owed, then with the last command's ACK owed."""
    segments = []
    set_power()  # warm up
    for settle in (read_power, None):
        if settle is not None:
            settle()  # a query: the warm-up's ACK is read, nothing is owed
        counter.record(1)
        set_power()
        if not counter.wait(PATIENCE):
            raise RuntimeError("setting the power sent no bytes")
        segments += counter.stop()
    return segments


def _power_board(kit: Any) -> Any:
    """The kit's simulated power board (firmware 3 or 4)."""
    return (*kit.simulators("sr-power"), *kit.simulators("sr-power-fw4"))[0]


def _press_when_polled(counter: CallPathCounter, kit: Any, polls: int) -> threading.Thread:
    """Press once ``polls`` polls have run (recorded); record from the press on."""
    simulator = _power_board(kit)

    def press() -> None:
        counter.wait(PATIENCE)
        counter.record(None)
        simulator.press_start()

    thread = threading.Thread(target=press, daemon=True)
    thread.start()
    return thread


def _release(kit: Any) -> None:
    _power_board(kit).release_start()


def _wait_case(counter: CallPathCounter, kit: Any, wait: Callable[[], None]) -> list[Segment]:
    # Warm up: a wait pressed at once, and one pressed after two polls.
    for polls in (1, 3):
        counter.record(polls)
        presser = _press_when_polled(counter, kit, polls)
        wait()
        presser.join()
        counter.stop()
        _release(kit)
    counter.record(3)  # the call; two polls
    presser = _press_when_polled(counter, kit, 3)
    first = counter.segments  # the recording's list (a new one starts at the press)
    wait()
    presser.join()
    press = counter.stop()
    _release(kit)
    return [*first[:3], *press]


def child(case: str) -> dict[str, Any]:
    """Run one case (in a fresh interpreter) and return its segments."""
    face, what, firmware = case.split()
    counter = j5aio_counter()
    kit = _use_kit(firmware)
    with counter.installed():
        if face == "sync":
            segments = _sync_case(counter, kit, what)
        else:
            segments = _async_case(counter, kit, what)
    return {"case": case, "segments": [
        {"functions": s.functions, "ended_by": s.ended_by} for s in segments
    ]}


def _sync_case(counter: CallPathCounter, kit: Any, what: str) -> list[Segment]:
    from j5aio.sync import KitRobot, shutdown, simulated_environment

    robot = KitRobot(environment=simulated_environment())
    try:
        if what == "motor.power":
            motor = robot.motor_boards[0].motors[0]

            def set_power() -> None:
                motor.power = 0.5

            return _measure_motor(counter, set_power, lambda: motor.power)
        button = robot.power_board.start_button
        return _wait_case(counter, kit, button.wait_until_pressed)
    finally:
        shutdown()


def _async_case(counter: CallPathCounter, kit: Any, what: str) -> list[Segment]:
    import anyio
    import anyio.to_thread

    from j5aio.kit import KitRobot
    from j5aio.simulator.environment import SIMULATED_ENVIRONMENT

    async def main() -> list[Segment]:
        result: list[Segment] = []
        async with KitRobot(environment=SIMULATED_ENVIRONMENT) as robot:
            if what == "motor.power":
                motor = robot.motor_boards[0].motors[0]
                await motor.set_power(0.5)  # warm up
                for settle in (True, False):  # as _measure_motor does
                    if settle:
                        await motor.get_power()
                    counter.record(1)
                    await motor.set_power(0.5)
                    await anyio.to_thread.run_sync(counter.wait, PATIENCE)
                    result += counter.stop()
                return result
            button = robot.power_board.start_button
            for polls in (1, 3, 3):  # two to warm up, the last measured
                counter.record(polls)
                presser = _press_when_polled(counter, kit, polls)
                first = counter.segments
                await button.wait_until_pressed()  # the presser presses in time
                await anyio.to_thread.run_sync(presser.join)
                result = [*first[:3], *counter.stop()]
                _release(kit)
        return result

    segments: list[Segment] = anyio.run(main)
    return segments


# -- the parent ---------------------------------------------------------------------------


def run_case(case: str) -> dict[str, Any]:
    """Run ``case`` in a child interpreter of this checkout; return its segments."""
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(
        filter(None, [str(ROOT), os.environ.get("PYTHONPATH")])
    ))
    command = [sys.executable, str(Path(__file__).resolve()), "--child", case]
    result = subprocess.run(command, capture_output=True, text=True, env=env, timeout=300)
    lines = result.stdout.strip().splitlines()
    if result.returncode != 0 or not lines:
        raise RuntimeError(f"{case} failed ({result.returncode}): {result.stderr[-2000:]}")
    figures: dict[str, Any] = json.loads(lines[-1])
    return figures


def describe(result: dict[str, Any], *, quiet: bool = False) -> list[str]:
    """The lines printed for one case's result."""
    segments = result["segments"]
    names = ["to the bytes (nothing owed)", "to the bytes (the last ACK owed)"] if len(
        segments
    ) == 2 else [
        "call to the first poll's bytes", "one poll (its bytes to the next's)",
        "another poll", "press to the call returning",
    ]
    lines = []
    for name, segment in zip(names, segments, strict=False):
        if name == "another poll":
            continue  # the first poll's figure stands for both (printed if they differ)
        count = len(segment["functions"])
        verdict = ""
        if name in ("to the bytes (nothing owed)", "call to the first poll's bytes"):
            verdict = "  MET" if count <= GOAL else "  NOT MET"
        end = f" (stopped at {segment['ended_by']})" if segment["ended_by"] else ""
        lines.append(f"  {result['case']}: {name}: {count} functions{verdict}{end}")
        if not quiet:
            lines += [f"      {function}" for function in segment["functions"]]
    if len(segments) == 4 and len(segments[1]["functions"]) != len(segments[2]["functions"]):
        lines.append(f"  {result['case']}: the next poll: {len(segments[2]['functions'])}")
    return lines


def main(argv: list[str] | None = None) -> None:
    """Run the bench (or, with ``--child``, one case of it)."""
    parser = argparse.ArgumentParser(description=(__doc__ or "").splitlines()[0])
    parser.add_argument("--cases", default=",".join(CASES),
                        help=f"comma-separated, of: {', '.join(CASES)}")
    parser.add_argument("--quiet", action="store_true", help="counts only, no lists")
    parser.add_argument("--child", help=argparse.SUPPRESS)
    args = parser.parse_args(argv)
    if args.child:
        print(json.dumps(child(args.child)))
        return
    cases = [case.strip() for case in args.cases.split(",") if case.strip()]
    unknown = [case for case in cases if case not in CASES]
    if unknown:
        parser.error(f"unknown cases {unknown}; there are: {', '.join(CASES)}")
    print(f"j5aio functions on each call's path to the bytes (goal <= {GOAL})")
    for case in cases:
        for line in describe(run_case(case), quiet=args.quiet):
            print(line)


if __name__ == "__main__":
    main()
