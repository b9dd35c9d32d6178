"""Record a program running on the simulated kit, and draw what the boards did as an SVG.

    python tools/plot_kit_run.py examples/sync_blink_and_drive.py -o docs/_static/run-student.svg

The program runs here, on a fresh simulated kit (as under ``python -m j5aio run --sim``),
while a thread samples the simulators themselves every few milliseconds: the power of
motor board 0's two motors, the power board's run LED and piezo, and one Arduino pin's
level. The picture is drawn by hand as SVG, so nothing needs to be installed; the
docs' pictures of the kit in action are made with it.
"""

from __future__ import annotations

import argparse
import os
import runpy
import sys
import threading
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from tools import svg  # noqa: E402 - the helper beside this script, found from the root


@dataclass
class Trace:
    """One recorded signal: a name, its range, and (time, value) samples."""

    name: str
    low: float
    high: float
    colour: str
    samples: list[tuple[float, float]] = field(default_factory=list)


@dataclass
class Recording:
    """Every trace of one run."""

    traces: list[Trace]
    seconds: float = 0.0


def record(program: Path, *, pin: int, interval: float, title: str) -> Recording:
    """Run ``program`` on a fresh simulated kit and sample the simulators while it runs."""
    os.environ["J5AIO_ENV"] = "sim"
    sys.path.insert(0, str(ROOT))
    from j5aio.simulator.kit import KitConfig, use_kit

    kit = use_kit(KitConfig())
    motors = kit.motor_boards[0]
    power = kit.power_boards[0]
    arduino = kit.sb_arduinos[0]
    probes: list[tuple[Trace, Callable[[], float]]] = [
        (Trace("motor 0 power", -1, 1, "#1f77b4"), lambda: motors.motors[0].power),
        (Trace("motor 1 power", -1, 1, "#ff7f0e"), lambda: motors.motors[1].power),
        (Trace("run LED", 0, 1, "#2ca02c"), lambda: float(power.run_led)),
        (Trace("piezo sounding", 0, 1, "#9467bd"), lambda: float(bool(power.note_queue))),
        (Trace(f"Arduino pin {pin}", 0, 1, "#d62728"), lambda: float(arduino.pins.level(pin))),
    ]
    stop = threading.Event()
    start = time.monotonic()

    def sample() -> None:
        while not stop.is_set():
            now = time.monotonic() - start
            for trace, probe in probes:
                trace.samples.append((now, probe()))
            stop.wait(interval)

    sampler = threading.Thread(target=sample, name="kit sampler", daemon=True)
    sampler.start()
    saved_argv = sys.argv
    sys.argv = [str(program)]
    try:
        runpy.run_path(str(program), run_name="__main__")
    finally:
        time.sleep(3 * interval)
        stop.set()
        sampler.join()
        sys.argv = saved_argv
    return Recording([trace for trace, _ in probes], time.monotonic() - start)


def changes(samples: list[tuple[float, float]]) -> list[tuple[float, float]]:
    """The samples where the value changed, with the first and the last."""
    kept = [sample for index, sample in enumerate(samples)
            if index == 0 or sample[1] != samples[index - 1][1]]
    if samples and kept[-1] is not samples[-1]:
        kept.append(samples[-1])
    return kept


def draw(recording: Recording, title: str) -> str:
    """The SVG of a recording: one band per trace, time along the bottom."""
    width, left, right, band, gap, top = 760, 150, 20, 56, 18, 50
    plot_width = width - left - right
    seconds = max(recording.seconds, 0.1)
    body = [svg.text(width / 2, 28, title, size=16, anchor="middle", weight="bold")]

    def x_of(t: float) -> float:
        return left + plot_width * t / seconds

    for index, trace in enumerate(recording.traces):
        y0 = top + index * (band + gap)
        body.append(svg.box(left, y0, plot_width, band, fill="#f7f8fa", stroke="#bbb", radius=2))
        body.append(svg.text(left - 10, y0 + band / 2 + 4, trace.name, anchor="end", size=12))
        span = trace.high - trace.low

        def y_of(value: float, y0: float = y0, trace: Trace = trace, span: float = span) -> float:
            return y0 + band - 4 - (band - 8) * (value - trace.low) / span

        if trace.low < 0 < trace.high:
            body.append(svg.line(left, y_of(0), left + plot_width, y_of(0), stroke="#ccc",
                                 width=1, dash="4 3"))
        labels = ((trace.high, f"{trace.high:+g}" if trace.low < 0 else "on"),
                  (trace.low, f"{trace.low:+g}" if trace.low < 0 else "off"))
        for value, words in labels:
            body.append(svg.text(left + 4, y_of(value) + (10 if value == trace.high else -2),
                                 words, size=9, fill="#888"))
        points: list[tuple[float, float]] = []
        for t, value in changes(trace.samples):  # a step plot: hold each value until the next
            if points:
                points.append((x_of(t), points[-1][1]))
            points.append((x_of(t), y_of(value)))
        if points:
            body.append(svg.polyline(points, stroke=trace.colour))
    axis_y = top + len(recording.traces) * (band + gap)
    body.append(svg.line(left, axis_y - gap + 6, left + plot_width, axis_y - gap + 6))
    step = 0.5 if seconds > 1.5 else 0.25
    tick = 0.0
    while tick <= seconds + 1e-9:
        x = x_of(tick)
        body.append(svg.line(x, axis_y - gap + 6, x, axis_y - gap + 11))
        body.append(svg.text(x, axis_y + 8, f"{tick:g} s", size=11, anchor="middle"))
        tick += step
    return svg.document(width, axis_y + 20, body, title)


def main(argv: Sequence[str] | None = None) -> int:
    """Run, record and draw."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("program", type=Path, help="the robot program to run")
    parser.add_argument("-o", "--output", type=Path, required=True, help="the SVG to write")
    parser.add_argument("--title", default=None, help="the picture's title")
    parser.add_argument("--pin", type=int, default=13, help="the Arduino pin to record")
    parser.add_argument("--interval", type=float, default=0.005, help="seconds between samples")
    options = parser.parse_args(argv)
    title = options.title or f"{options.program.name} on the simulated kit"
    recording = record(options.program, pin=options.pin, interval=options.interval, title=title)
    options.output.parent.mkdir(parents=True, exist_ok=True)
    options.output.write_text(draw(recording, title), encoding="utf-8")
    print(f"wrote {options.output} ({recording.seconds:.2f} s recorded)")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
