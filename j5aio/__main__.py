"""The command line: ``python -m j5aio`` (or ``j5aio``) with one subcommand per job.

- ``list``: the boards plugged into this computer, and every kind of board looked for;
- ``demo [--kit NAME]``: an example robot on the simulated kit, showing what the boards do;
- ``run [--sim [--kit NAME]] [--api sr-robot3|sbot] program.py``: a robot program, on the
  hardware or the simulated kit (``--api``: a program written for a competition's own
  API, :mod:`j5aio.compat`);
- ``simulate NAME --pty``: a simulated board on a pseudo-terminal, for any program to open;
- ``sync-gen MODULE -o FILE [--check]``: the typed sync facade of a kit's own boards.

Boards, simulators and kits come from the registry of board kinds
(:mod:`j5aio.board_kinds`), so those of installed plugins appear here too.
"""

from __future__ import annotations

import argparse
import contextlib
import json
import os
import signal
import sys
import tempfile
import threading
from collections.abc import Callable, Iterator, Sequence
from pathlib import Path
from types import FrameType
from typing import TYPE_CHECKING, Any, Final

from j5aio import syncgen
from j5aio.board_kinds import get_kit, kits, simulator_entries
from j5aio.compat.imports import API_NAMES
from j5aio.environments import ENVIRONMENT_NAMES, ENVIRONMENT_VARIABLE
from j5aio.simulator.kit import KIT_VARIABLE
from j5aio.simulator.kit_file import KIT_FILE_VARIABLE
from j5aio.simulator.pin_options import apply_pin_options, parse_analog, parse_digital

if TYPE_CHECKING:
    from j5aio.view import LiveView

__all__ = ["API_CHOICES", "SIMULATOR_NAMES", "build_parser", "invoked_as", "main"]

#: The competitions' APIs ``run --api`` offers (see :mod:`j5aio.compat.imports`).
API_CHOICES: Final = tuple(API_NAMES)

_EPILOG: Final = """\
examples:
  python -m j5aio demo                        watch a robot run on the simulated kit
  python -m j5aio run --sim robot.py          run your program on the simulated kit
  python -m j5aio run --sim --kit sr2019 robot.py   ... on a named simulated kit
  python -m j5aio run robot.py                run it on the boards plugged in
  python -m j5aio run --sim --view robot.py   ... and watch its boards in the browser
  python -m j5aio run --api sr-robot3 --sim --kit sr2023 robot.py
                                              run an sr-robot3 program unchanged
  python -m j5aio run --sim --zone 2 --mode comp --duration 20 --start-after 1 robot.py
                                              simulate a 20 s match starting from zone 2
  python -m j5aio list                        which boards are plugged in?
  python -m j5aio simulate sb-arduino --pty   serve a simulated board on a serial port

Run 'python -m j5aio COMMAND --help' for a command's options.
"""

#: The boards ``simulate`` can serve (the registry's serial simulators), with what each is.
SIMULATOR_NAMES: Final = {
    name: entry.description
    for name, (kind, entry) in simulator_entries().items()
    if entry.is_serial
}


def invoked_as(argv0: str | None = None) -> str:
    """How the command line was started: ``j5aio`` (the installed command) or ``python -m j5aio``.

    :param argv0: the program's name as started (``sys.argv[0]`` by default).
    """
    if argv0 is None:
        argv0 = sys.argv[0] if sys.argv else ""
    name = argv0.replace("\\", "/").rsplit("/", 1)[-1]  # a Windows path too
    if name.endswith(".py") or name in ("", "-c", "-m"):
        return "python -m j5aio"
    return name.removesuffix(".exe")


def build_parser() -> argparse.ArgumentParser:
    """Make the argument parser of ``python -m j5aio`` (or of the ``j5aio`` command)."""
    parser = argparse.ArgumentParser(
        prog=invoked_as(),
        description="j5aio: run robot programs on real boards or on a simulated kit.",
        epilog=_EPILOG,
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    commands = parser.add_subparsers(dest="command", metavar="COMMAND")

    listing = commands.add_parser(
        "list",
        help="list the boards plugged into this computer",
        description="Find every supported board plugged in and print its type, serial "
        "number, firmware version and port.",
    )
    listing.set_defaults(handler=_list)

    demo = commands.add_parser(
        "demo",
        help="run an example robot on the simulated kit",
        description="Run an example robot (drive, sense and signal tasks at once) on the "
        "simulated kit, printing what the simulated boards do. No hardware is needed.",
    )
    _add_kit_option(demo)
    demo.add_argument(
        "--seconds",
        type=_seconds,
        default=None,
        metavar="S",
        help="how long the robot runs, in seconds (default 6)",
    )
    _add_view_options(demo)
    demo.set_defaults(handler=_demo)

    run = commands.add_parser(
        "run",
        help="run a robot program",
        description="Run a Python robot program. Its boards are the ones plugged in, "
        f"unless --sim or --env chooses otherwise (this sets {ENVIRONMENT_VARIABLE} for it).",
    )
    where = run.add_mutually_exclusive_group()
    where.add_argument(
        "--sim",
        action="store_const",
        const="sim",
        dest="environment",
        help="use the simulated kit instead of hardware",
    )
    where.add_argument(
        "--env",
        choices=ENVIRONMENT_NAMES,
        dest="environment",
        help="choose the environment by name",
    )
    _add_kit_option(run, " (implies --sim)")
    run.add_argument(
        "--api",
        choices=API_CHOICES,
        default=None,
        help="run a program written for a competition's own API: with sr-robot3, "
        "'import sr.robot3' gives j5aio's sr-robot3 (j5aio.compat.sr_robot3); with sbot, "
        "'import sbot' gives j5aio's sbot (j5aio.compat.sbot)",
    )
    _add_match_arguments(run)
    run.add_argument("program", help="the program to run, e.g. robot.py")
    run.add_argument(
        "arguments", nargs=argparse.REMAINDER, help="arguments passed on to the program"
    )
    _add_view_options(run)
    run.set_defaults(handler=_run)

    simulate = commands.add_parser(
        "simulate",
        help="serve a simulated board on a serial port (a pseudo-terminal)",
        description="Serve a simulated serial board on a pseudo-terminal until interrupted "
        "(Ctrl-C). The first line printed is the port's path; open it with pyserial, j5 or "
        "any other program as you would a real board's port.",
        epilog="boards:\n"
        + "\n".join(f"  {name:<17}{what}" for name, what in SIMULATOR_NAMES.items()),
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    simulate.add_argument("board", choices=SIMULATOR_NAMES, metavar="BOARD", help="the board")
    simulate.add_argument(
        "--pty",
        action="store_true",
        help="serve on a pseudo-terminal (the default, and the only transport so far)",
    )
    simulate.add_argument(
        "--serial",
        "--serial-number",
        dest="serial_number",
        default="SIM0",
        metavar="TEXT",
        help="the serial number (asset tag) the simulated board reports (default SIM0)",
    )
    simulate.add_argument(
        "--analog",
        type=_pin_option(parse_analog),
        action="append",
        default=[],
        metavar="A0=2.5",
        help="Arduinos: hold this many volts (0 to 5) on an analogue pin; repeatable",
    )
    simulate.add_argument(
        "--digital",
        type=_pin_option(parse_digital),
        action="append",
        default=[],
        metavar="3=0|1",
        help="Arduinos: hold an input pin (2 to 13, A0 to A5) low (0) or high (1); repeatable",
    )
    simulate.add_argument(
        "--time-scale",
        type=_time_scale,
        default=1.0,
        metavar="F",
        help="multiply the board's boot delay by F (default 1: as slow as the real board)",
    )
    simulate.add_argument(
        "--link",
        metavar="PATH",
        help="keep PATH a symbolic link to the pseudo-terminal while serving (removed at "
        "exit), so that programs can open one stable path, also after a restart",
    )
    simulate.add_argument(
        "--uart-timing",
        action="store_true",
        help="delay every reply by the time the board's serial line would take to carry it",
    )
    simulate.set_defaults(handler=_simulate)

    sync_gen = commands.add_parser(
        "sync-gen",
        help="generate the typed sync facade of a kit's own boards",
        description="Write a module of typed sync wrappers (like j5aio.sync's) for the "
        "boards and components defined in MODULE; with --check, only say whether the "
        "file is up to date (exit status 1 if not).",
    )
    syncgen.add_arguments(sync_gen)
    sync_gen.set_defaults(handler=syncgen.run)
    return parser


def _add_kit_option(parser: argparse.ArgumentParser, implies: str = "") -> None:
    names = ", ".join(kits())
    chosen = parser.add_mutually_exclusive_group()
    chosen.add_argument(
        "--kit",
        type=_kit_name,
        default=None,
        metavar="NAME",
        help=f"the simulated kit: one of {names} (default: ${KIT_VARIABLE}, else "
        f"'default'){implies}",
    )
    chosen.add_argument(
        "--kit-file",
        type=_kit_file,
        default=None,
        metavar="FILE",
        help="the simulated kit described as your robot in a TOML file: its boards, "
        f"their serial numbers and power wiring (sets ${KIT_FILE_VARIABLE}){implies}",
    )


def _kit_file(text: str) -> str:
    from j5aio.simulator.kit_file import load_kit_file

    path = Path(text).expanduser()
    try:
        load_kit_file(path)
    except (OSError, ValueError) as error:
        raise argparse.ArgumentTypeError(str(error)) from None
    return str(path.resolve())


def _kit_name(text: str) -> str:
    try:
        return get_kit(text).name
    except ValueError as error:
        raise argparse.ArgumentTypeError(str(error)) from None


def _pin_option(parse: Callable[[str], tuple[int, Any]]) -> Callable[[str], tuple[int, Any]]:
    def parse_option(text: str) -> tuple[int, Any]:
        try:
            return parse(text)
        except ValueError as error:
            raise argparse.ArgumentTypeError(str(error)) from None

    return parse_option


def _number(text: str, what: str) -> float:
    try:
        return float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is not {what}") from None


def _seconds(text: str) -> float:
    value = _number(text, "a number of seconds")
    if not 0 < value <= 600:
        raise argparse.ArgumentTypeError(f"{text} s is out of range: give 0 < S <= 600")
    return value


def _time_scale(text: str) -> float:
    value = _number(text, "a number")
    if not value >= 0:
        raise argparse.ArgumentTypeError(f"{text} is negative: give 0 or more")
    return value


# --- the live view (j5aio.view): --view, --view-port, --view-host on run and demo ---

#: How long the demo runs with --view unless --seconds says otherwise: time to look.
VIEW_DEMO_SECONDS: Final = 120.0


def _add_view_options(parser: argparse.ArgumentParser) -> None:
    view = parser.add_argument_group("live view")
    view.add_argument(
        "--view",
        action="store_true",
        help="serve a live view of the boards in the browser (needs j5aio[view]); "
        "prints its address",
    )
    view.add_argument(
        "--view-port",
        type=_port,
        default=None,
        metavar="N",
        help="the view's port (default: a free one)",
    )
    view.add_argument(
        "--view-host",
        default=None,
        metavar="ADDR",
        help="the address the view listens on (default 127.0.0.1: this computer only)",
    )


def _port(text: str) -> int:
    value = int(_number(text, "a port number"))
    if str(value) != text.strip() or not 0 <= value <= 65535:
        raise argparse.ArgumentTypeError(f"{text} is not a port number: give 0 to 65535")
    return value


def _start_view_option(args: argparse.Namespace) -> tuple[bool, LiveView | None]:
    """Start the live view if ``--view`` asks for it: (whether to go on, the view)."""
    if not args.view:
        if args.view_port is not None or args.view_host is not None:
            print("j5aio: --view-port and --view-host need --view", file=sys.stderr)
            return False, None
        return True, None
    from j5aio.view import INSTALL_HINT, start_view, web_stack_installed

    if not web_stack_installed():
        print(f"j5aio: the live view needs the 'view' extra: {INSTALL_HINT}", file=sys.stderr)
        return False, None
    try:
        # Started before the program's event loop: the view learns it from the first board
        # call, so it shows any robot (KitRobot, sync BaseRobot, ...) the program makes.
        return True, start_view(host=args.view_host, port=args.view_port or 0)
    except OSError as error:
        print(f"j5aio: could not start the live view: {error}", file=sys.stderr)
        return False, None


def _list(args: argparse.Namespace) -> int:
    import functools

    import anyio

    from j5aio.backends.hardware.listing import find_boards, format_boards
    from j5aio.board_kinds import board_kinds
    from j5aio.errors import CommunicationError

    problems: list[str] = []
    try:
        boards = anyio.run(functools.partial(find_boards, problems=problems))
    except CommunicationError as error:
        print(f"j5aio: could not look for boards: {error}", file=sys.stderr)
        return 1
    print(format_boards(boards))
    print("\nKinds of board looked for:")
    for kind in board_kinds():
        if kind.hardware is not None:
            source = "" if kind.package == "j5aio" else f"  [{kind.package}]"
            print(f"  {kind.name:<22}{kind.description}{source}")
    for problem in problems:
        print(f"j5aio: could not look for every board: {problem}", file=sys.stderr)
    return 1 if problems and not boards else 0


def _demo(args: argparse.Namespace) -> int:
    from j5aio.demo import DEFAULT_SECONDS, run_demo

    go_on, view = _start_view_option(args)
    if not go_on:
        return 2
    default = VIEW_DEMO_SECONDS if args.view else DEFAULT_SECONDS
    try:
        seconds = args.seconds if args.seconds is not None else default
        if args.kit_file is not None:
            os.environ[KIT_FILE_VARIABLE] = args.kit_file
        braked = run_demo(seconds, kit=args.kit)
    except KeyboardInterrupt:
        print("Interrupted.", file=sys.stderr)
        return 130
    finally:
        if view is not None:
            view.close()
    return 0 if braked else 1


def _run(args: argparse.Namespace) -> int:
    program = Path(args.program)
    if not program.is_file():
        print(f"j5aio: cannot run {args.program}: no such file", file=sys.stderr)
        return 2
    if args.kit is not None:
        if args.environment not in (None, "sim"):
            print(
                f"j5aio: --kit chooses a simulated kit, so it cannot be used with "
                f"--env {args.environment}",
                file=sys.stderr,
            )
            return 2
        args.environment = "sim"
        os.environ[KIT_VARIABLE] = args.kit
    if args.kit_file is not None:
        # The simulated kit, unless another environment is asked for: on the robot the
        # file's wiring still names the output to switch on for a board without power.
        args.environment = args.environment or "sim"
        os.environ[KIT_FILE_VARIABLE] = args.kit_file
    if _is_supervised_match(args):
        from j5aio.competition.supervisor import supervise

        # A timed match: the program runs in a child, its game over watched from here.
        return supervise(
            [sys.executable, "-m", "j5aio", *args.command_line],
            environment=args.environment or os.environ.get(ENVIRONMENT_VARIABLE),
        )
    go_on, view = _start_view_option(args)
    if not go_on:
        return 2
    if args.environment is not None:
        os.environ[ENVIRONMENT_VARIABLE] = args.environment
    sys.argv = [str(program), *args.arguments]
    sys.path.insert(0, str(program.resolve().parent))
    from j5aio.compat import imports
    from j5aio.safety import install
    from j5aio.tracebacks import run_program

    install()  # the exit hook, excepthook and signal handlers, before the program runs
    finder = imports.install(args.api) if args.api else None
    if finder is None:
        imports.install_hint()
    try:
        with _match(args, program) as ready:
            if not ready:
                return 2
            return run_program(program)
    finally:
        if finder is not None:
            imports.uninstall(finder)
        if view is not None:
            view.close()


# -- run: match settings, the start and the run log -----------------------------------------


def _add_match_arguments(run: argparse.ArgumentParser) -> None:
    match = run.add_argument_group(
        "match",
        "Simulate a match (these write a metadata file for the program, as a competition's "
        "USB stick would), start it, and keep a log of the run.",
    )
    match.add_argument("--arena", help="the arena's name (default A)")
    match.add_argument("--zone", type=int, help="the starting zone (default 0)")
    match.add_argument(
        "--mode", type=str.upper, choices=["COMP", "DEV"], help="COMP (a match) or DEV"
    )
    match.add_argument(
        "--duration", type=_seconds_long, metavar="S", help="the match's length in seconds"
    )
    match.add_argument(
        "--start-after",
        type=_start_after,
        metavar="S",
        help="press start automatically after S seconds (with --sim, Enter in the console "
        "starts the robot otherwise)",
    )
    match.add_argument(
        "--time-scale",
        type=_positive_scale,
        metavar="F",
        help="real seconds per robot second: robot.time(), robot.sleep(), the match and the "
        "simulated boards' delays (default 1)",
    )
    match.add_argument("--log-dir", type=Path, metavar="DIR", help="write the run log here")
    match.add_argument("--no-log", action="store_true", help="keep no run log")


def _in_range(
    what: str, unit: str, low: float, high: float, *, low_included: bool
) -> Callable[[str], float]:
    """An argparse type: a number from ``low`` (included or not) to ``high``."""
    sign = "<=" if low_included else "<"

    def parse(text: str) -> float:
        value = _number(text, what)
        if not ((low <= value) if low_included else (low < value)) or not value <= high:
            raise argparse.ArgumentTypeError(
                f"{text}{unit} is out of range: give {low:g} {sign} {unit.strip() or 'F'} "
                f"<= {high:g}"
            )
        return value

    return parse


_seconds_long = _in_range("a number of seconds", " s", 0, 3600, low_included=False)
_start_after = _in_range("a number of seconds", " s", 0, 3600, low_included=True)
_positive_scale = _in_range("a number", "", 0, 1000, low_included=False)


def _is_supervised_match(args: argparse.Namespace) -> bool:
    """Whether to run the program under the match supervisor (a timed match, on POSIX).

    Not in the supervised program itself, nor where the metadata is unusable (the program
    reports that), nor on Windows (no process groups to end), nor where
    :data:`~j5aio.competition.supervisor.NO_SUPERVISOR_VARIABLE` asks for none.
    """
    from j5aio.competition import supervisor
    from j5aio.competition.metadata import MetadataError, load_metadata, parse_metadata

    if supervisor.adopt() or sys.platform == "win32":
        return False
    if os.environ.get(supervisor.NO_SUPERVISOR_VARIABLE, "").strip() == "1":
        return False  # a test harness that looks into the simulated kit in its process
    try:
        if any(x is not None for x in (args.arena, args.zone, args.mode, args.duration)):
            metadata = parse_metadata(_metadata_fields(args))
        else:
            metadata = load_metadata()
    except MetadataError:
        return False
    return metadata.is_competition and metadata.duration is not None


@contextlib.contextmanager
def _match(args: argparse.Namespace, program: Path) -> Iterator[bool]:
    """Set up the match's metadata, time scale, start and run log around the program."""
    from j5aio.competition import start
    from j5aio.competition.clock import TIME_SCALE_VARIABLE
    from j5aio.competition.metadata import METADATA_VARIABLE, MetadataError, load_metadata
    from j5aio.competition.runlog import RunLog, choose_log_folder, teeing

    with contextlib.ExitStack() as stack:
        saved = {name: os.environ.get(name) for name in (METADATA_VARIABLE, TIME_SCALE_VARIABLE)}
        stack.callback(_restore_environment, saved)
        if any(x is not None for x in (args.arena, args.zone, args.mode, args.duration)):
            folder = Path(stack.enter_context(tempfile.TemporaryDirectory(prefix="j5aio-")))
            path = folder / "metadata.json"
            path.write_text(json.dumps(_metadata_fields(args)))
            os.environ[METADATA_VARIABLE] = str(path)
        if args.time_scale is not None:
            os.environ[TIME_SCALE_VARIABLE] = repr(args.time_scale)
            if args.environment == "sim":
                from j5aio.simulator.kit import kit_from_environment, use_kit
                from j5aio.simulator.kit_file import kit_file_from_environment

                use_kit(
                    kit_file_from_environment() or kit_from_environment(),
                    time_scale=args.time_scale,
                    wired=True,
                )
        try:
            metadata = load_metadata()
        except MetadataError as error:
            print(f"j5aio: {error}", file=sys.stderr)
            yield False
            return
        if args.start_after is not None:
            timer = threading.Timer(args.start_after, start.trigger_start)
            timer.daemon = True
            timer.start()
            stack.callback(timer.cancel)
        elif args.environment == "sim" and sys.stdin is not None and sys.stdin.isatty():
            threading.Thread(target=_start_on_enter, daemon=True).start()
        if not args.no_log:
            folder = args.log_dir or choose_log_folder(program, metadata)
            try:
                log = RunLog(folder)
            except OSError as error:
                print(f"j5aio: no run log ({folder}: {error})", file=sys.stderr)
            else:
                stack.callback(log.close)
                log.write_header(program.resolve(), metadata)
                print(f"j5aio: logging this run to {log.path}", file=sys.stderr)
                from j5aio.competition.supervisor import report_log

                report_log(log.path)  # the supervisor's game over goes in the log too
                stack.enter_context(teeing(log))
        yield True


def _restore_environment(saved: dict[str, str | None]) -> None:
    for name, value in saved.items():
        if value is None:
            os.environ.pop(name, None)
        else:
            os.environ[name] = value


def _metadata_fields(args: argparse.Namespace) -> dict[str, object]:
    return {
        "arena": args.arena if args.arena is not None else "A",
        "zone": args.zone if args.zone is not None else 0,
        "mode": args.mode or "DEV",
        "duration": args.duration,
        "marker_offset": 0,
    }


def _start_on_enter() -> None:
    from j5aio.competition.start import trigger_start

    print("j5aio: press Enter to start the robot (the simulated start button).", file=sys.stderr)
    with contextlib.suppress(OSError, ValueError, EOFError):
        sys.stdin.readline()
        trigger_start()


def _simulate(args: argparse.Namespace) -> int:
    if sys.platform == "win32":  # pragma: no cover - tested on POSIX only
        print("j5aio: simulate needs pseudo-terminals, which Windows lacks", file=sys.stderr)
        return 2
    from j5aio.simulator.base import SerialBoardSimulator
    from j5aio.simulator.serve import serve_on_pty

    _kind, entry = simulator_entries()[args.board]
    simulator = entry.factory(args.serial_number)
    assert isinstance(simulator, SerialBoardSimulator)  # only serial ones are choices
    try:
        apply_pin_options(simulator, args.analog, args.digital)
    except TypeError as error:
        print(f"j5aio: {error}", file=sys.stderr)
        return 2
    stop = threading.Event()

    def on_signal(signum: int, frame: FrameType | None) -> None:
        stop.set()

    previous = {sig: signal.signal(sig, on_signal) for sig in (signal.SIGINT, signal.SIGTERM)}
    try:
        with serve_on_pty(
            simulator, time_scale=args.time_scale, uart_timing=args.uart_timing, link=args.link,
        ) as server:
            print(server.port, flush=True)
            print(
                f"Serving a simulated {SIMULATOR_NAMES[args.board]} (serial number "
                f"{args.serial_number}) on {server.port}. Press Ctrl-C to stop.",
                file=sys.stderr,
                flush=True,
            )
            while not stop.wait(0.2) and server.is_serving:
                pass
    finally:
        for sig, handler in previous.items():
            signal.signal(sig, handler)
    print("Stopped.", file=sys.stderr, flush=True)
    return 0


def main(argv: Sequence[str] | None = None) -> int:
    """Run the command line with ``argv`` (the program's arguments by default).

    :returns: the exit status.
    """
    parser = build_parser()
    args = parser.parse_args(argv)
    args.command_line = list(sys.argv[1:] if argv is None else argv)  # for a supervised run
    handler: Callable[[argparse.Namespace], int] | None = getattr(args, "handler", None)
    if handler is None:
        parser.print_help()
        return 2
    try:
        return handler(args)
    except (BrokenPipeError, BaseExceptionGroup) as error:
        if not _only_broken_pipes(error):
            raise
        # The reader of our output went away (``j5aio demo | head``): stop quietly. Python
        # flushes stdout once more at exit, so it is pointed at nowhere first.
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        return 1


def _only_broken_pipes(error: BaseException) -> bool:
    """Whether ``error`` is a broken pipe, or a group of nothing but broken pipes."""
    if isinstance(error, BaseExceptionGroup):
        return all(_only_broken_pipes(inner) for inner in error.exceptions)
    return isinstance(error, BrokenPipeError)


if __name__ == "__main__":
    sys.exit(main())
