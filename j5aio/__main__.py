"""The command line: ``python -m j5aio`` (or ``j5aio``) with one subcommand per job.

- ``list``: the boards plugged into this computer;
- ``demo``: an example robot on the simulated kit, showing what the boards do;
- ``run [--sim] program.py``: a robot program, on the hardware or the simulated kit;
- ``simulate NAME --pty``: a simulated board on a pseudo-terminal, for any program to open;
- ``sync-gen MODULE -o FILE [--check]``: the typed sync facade of a kit's own boards.
"""

from __future__ import annotations

import argparse
import os
import signal
import sys
import threading
from collections.abc import Callable, Sequence
from pathlib import Path
from types import FrameType
from typing import Final

from j5aio import syncgen
from j5aio.environments import ENVIRONMENT_NAMES, ENVIRONMENT_VARIABLE
from j5aio.simulator import SERIAL_SIMULATORS

__all__ = ["SIMULATOR_NAMES", "build_parser", "invoked_as", "main"]

_EPILOG: Final = """\
examples:
  python -m j5aio demo                        watch a robot run on the simulated kit
  python -m j5aio run --sim robot.py          run your program on the simulated kit
  python -m j5aio run robot.py                run it on the boards plugged in
  python -m j5aio list                        which boards are plugged in?
  python -m j5aio simulate sb-arduino --pty   serve a simulated board on a serial port

Run 'python -m j5aio COMMAND --help' for a command's options.
"""

_DESCRIPTIONS: Final = {
    "sr-motor": "SR v4 motor board, firmware 3 (1 Mbaud)",
    "sr-ruggeduino": "SR Ruggeduino, firmware 1 (115200 baud)",
    "sb-arduino": "SourceBots Arduino, 2019 firmware (115200 baud)",
    "sr-arduino-fw2": "SR Arduino, firmware 2 (115200 baud)",
    "sb-arduino-2024": "SourceBots Arduino, sb2024 firmware 2.0 (115200 baud)",
}

#: The boards ``simulate`` can serve, with what each is.
SIMULATOR_NAMES: Final = {
    name: _DESCRIPTIONS.get(name, getattr(factory, "__name__", name))
    for name, factory in SERIAL_SIMULATORS.items()
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
    demo.add_argument(
        "--seconds",
        type=_seconds,
        default=None,
        metavar="S",
        help="how long the robot runs, in seconds (default 6)",
    )
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
    run.add_argument("program", help="the program to run, e.g. robot.py")
    run.add_argument(
        "arguments", nargs=argparse.REMAINDER, help="arguments passed on to the program"
    )
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
        "--serial-number",
        default="SIM0",
        help="the serial number the simulated board reports (default SIM0)",
    )
    simulate.add_argument(
        "--time-scale",
        type=_time_scale,
        default=1.0,
        metavar="F",
        help="multiply the board's boot delay by F (default 1: as slow as the real board)",
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


def _list(args: argparse.Namespace) -> int:
    import functools

    import anyio

    from j5aio.backends.hardware.listing import find_boards, format_boards
    from j5aio.errors import CommunicationError

    problems: list[str] = []
    try:
        boards = anyio.run(functools.partial(find_boards, problems=problems))
    except CommunicationError as error:
        print(f"j5aio: could not look for boards: {error}", file=sys.stderr)
        return 1
    print(format_boards(boards))
    for problem in problems:
        print(f"j5aio: could not look for every board: {problem}", file=sys.stderr)
    return 1 if problems and not boards else 0


def _demo(args: argparse.Namespace) -> int:
    from j5aio.demo import DEFAULT_SECONDS, run_demo

    try:
        braked = run_demo(args.seconds if args.seconds is not None else DEFAULT_SECONDS)
    except KeyboardInterrupt:
        print("Interrupted.", file=sys.stderr)
        return 130
    return 0 if braked else 1


def _run(args: argparse.Namespace) -> int:
    program = Path(args.program)
    if not program.is_file():
        print(f"j5aio: cannot run {args.program}: no such file", file=sys.stderr)
        return 2
    if args.environment is not None:
        os.environ[ENVIRONMENT_VARIABLE] = args.environment
    sys.argv = [str(program), *args.arguments]
    sys.path.insert(0, str(program.resolve().parent))
    from j5aio.tracebacks import run_program

    return run_program(program)


def _simulate(args: argparse.Namespace) -> int:
    if sys.platform == "win32":  # pragma: no cover - tested on POSIX only
        print("j5aio: simulate needs pseudo-terminals, which Windows lacks", file=sys.stderr)
        return 2
    from j5aio.simulator.serve import serve_on_pty

    simulator = SERIAL_SIMULATORS[args.board](args.serial_number)
    stop = threading.Event()

    def on_signal(signum: int, frame: FrameType | None) -> None:
        stop.set()

    previous = {sig: signal.signal(sig, on_signal) for sig in (signal.SIGINT, signal.SIGTERM)}
    try:
        with serve_on_pty(
            simulator, time_scale=args.time_scale, uart_timing=args.uart_timing,
        ) as server:
            print(server.path, flush=True)
            print(
                f"Serving a simulated {SIMULATOR_NAMES[args.board]} (serial number "
                f"{args.serial_number}) on {server.path}. Press Ctrl-C to stop.",
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
    handler: Callable[[argparse.Namespace], int] | None = getattr(args, "handler", None)
    if handler is None:
        parser.print_help()
        return 2
    return handler(args)


if __name__ == "__main__":
    sys.exit(main())
