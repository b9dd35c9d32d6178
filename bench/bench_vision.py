"""Vision benchmark: detection speed against april_vision, see() latency, loop blocking,
and accuracy on rendered markers.

Run:  PYTHONPATH=. python bench/bench_vision.py [--quick]

Needs the vision extra (``pip install 'j5aio[vision]'``); the april_vision comparison
needs ``pip install april_vision`` (it is skipped, saying so, when it is not installed).
Every figure is a median (or a percentile) of repeated runs in this one process, so that
j5aio and the peer meet the same machine load.
"""

from __future__ import annotations

import argparse
import asyncio
import gc
import math
import statistics
import threading
import time
from collections.abc import Callable
from typing import Any

import anyio

from j5aio.backends.camera import FileCameraBackend
from j5aio.kit import KitRobot
from j5aio.simulator.arena import Pose
from j5aio.simulator.camera import DEFAULT_CALIBRATION, SimulatedCamera, render_view
from j5aio.simulator.environment import SIMULATED_ENVIRONMENT
from j5aio.simulator.kit import use_kit
from j5aio.vision import KNOWN_CALIBRATIONS, CameraCalibration, MarkerDetector, Orientation
from j5aio.vision.geometry import position_from_translation, rotation_from_orientation
from j5aio.vision.render import MarkerItem, render

POSES = (
    Pose(2875.0, 1000.0, math.pi / 2),
    Pose(1000.0, 1500.0, 0.3),
    Pose(4500.0, 4200.0, -2.5),
    Pose(2875.0, 2875.0, math.pi),
    Pose(1200.0, 4800.0, -1.2),
)


def arena_images(calibration: CameraCalibration, resolution: tuple[int, int]) -> list[Any]:
    """Rendered views of the standard arena from a few poses."""
    kit = use_kit()
    camera = SimulatedCamera(calibration=calibration, resolution=resolution)
    images = []
    for pose in POSES:
        kit.world.place_robot(pose)
        images.append(render_view(kit.world, camera))
    return images


def rates(
    functions: dict[str, Callable[[Any], object]], images: list[Any], seconds: float
) -> dict[str, float]:
    """Frames per second of each function over ``images``: the median of 5 rounds.

    The functions take turns within each round, so that a change in the machine's load
    falls on all of them alike.
    """
    for function in functions.values():
        for image in images:
            function(image)  # warm up
    measured: dict[str, list[float]] = {name: [] for name in functions}
    for _ in range(5):
        for name, function in functions.items():
            count = 0
            start = time.perf_counter()
            while time.perf_counter() - start < seconds / 5 / len(functions):
                function(images[count % len(images)])
                count += 1
            measured[name].append(count / (time.perf_counter() - start))
    return {name: statistics.median(values) for name, values in measured.items()}


def april_vision_processor(calibration: CameraCalibration, sizes_m: dict[int, float]) -> Any:
    """april_vision's Processor fed with our frames, or None when it is not installed."""
    try:
        from april_vision import FrameSource, Processor
    except ImportError:
        return None

    class Frames(FrameSource):  # type: ignore[misc,unused-ignore]
        def __init__(self) -> None:
            pass

    return Processor(
        Frames(),
        calibration=(calibration.fx, calibration.fy, calibration.cx, calibration.cy),
        tag_sizes=sizes_m,
    )


def detection_speed(seconds: float) -> None:
    print("== detection speed (rendered arena views, every marker with its pose)")
    cases = (
        ((640, 480), KNOWN_CALIBRATIONS["Logitech C270"].scaled_to(640, 480)),
        ((1280, 720), DEFAULT_CALIBRATION),
    )
    sizes = use_kit().world.arena.marker_sizes()
    sizes_m = {k: v / 1000 for k, v in sizes.items()}
    for resolution, calibration in cases:
        images = arena_images(calibration, resolution)
        count = sum(len(MarkerDetector().detect(i, calibration, sizes)) for i in images)
        ours = MarkerDetector()
        functions: dict[str, Callable[[Any], object]] = {
            "ours": lambda i: ours.detect(i, calibration, sizes),  # noqa: B023
            "ids": ours.detect_ids,
        }
        processor = april_vision_processor(calibration, sizes_m)
        if processor is not None:
            functions["theirs"] = lambda i: processor.see(frame=i)  # noqa: B023
        fps = rates(functions, images, seconds)
        line = (
            f"{resolution[0]}x{resolution[1]}: {count} markers in {len(images)} views; "
            f"j5aio detect_markers {fps['ours']:6.1f} fps, see_ids path {fps['ids']:6.1f} fps"
        )
        if processor is None:
            line += "; april_vision not installed (pip install april_vision) - no comparison"
        else:
            found = sum(len(processor.see(frame=i)) for i in images)
            line += (
                f"; april_vision Processor.see {fps['theirs']:6.1f} fps ({found} markers) "
                f"-> ratio j5aio/april_vision {fps['ours'] / fps['theirs']:4.2f}"
            )
        print(line)


class LoopSteps:
    """Times every callback the event loop runs (wall clock and the loop thread's CPU time).

    CPU time is what the loop itself spends in one step, whatever the machine's load; the
    wall clock adds the time the thread waited for a core or for the GIL. The interpreter's
    garbage collections on the loop thread are timed apart (``gc``): a collection runs in
    whatever step happens to allocate when it is due, and lasts as long as the process has
    objects, whoever made them. ``cpu`` holds each step's CPU time less its collections.
    """

    def __init__(self) -> None:
        self.wall: list[float] = []
        self.cpu: list[float] = []
        self.gc: list[float] = []
        self.longest: tuple[float, str] = (0.0, "")
        self._original = asyncio.events.Handle._run
        self._loop_thread = threading.get_ident()
        self._gc_started = 0.0
        self._gc_in_step = 0.0

    def _on_gc(self, phase: str, info: dict[str, Any]) -> None:
        if threading.get_ident() != self._loop_thread:
            return
        if phase == "start":
            self._gc_started = time.thread_time()
        else:
            spent = time.thread_time() - self._gc_started
            self.gc.append(spent)
            self._gc_in_step += spent

    def __enter__(self) -> LoopSteps:
        original, wall, cpu = self._original, self.wall, self.cpu

        def timed(handle: asyncio.events.Handle) -> None:
            self._gc_in_step = 0.0
            w, c = time.perf_counter(), time.thread_time()
            original(handle)
            cpu.append(time.thread_time() - c - self._gc_in_step)
            wall.append(time.perf_counter() - w)
            if cpu[-1] > self.longest[0]:
                self.longest = (cpu[-1], repr(handle)[:150])

        gc.callbacks.append(self._on_gc)
        asyncio.events.Handle._run = timed  # type: ignore[method-assign,assignment]
        return self

    def __exit__(self, *exc: object) -> None:
        asyncio.events.Handle._run = self._original  # type: ignore[method-assign]
        gc.callbacks.remove(self._on_gc)


async def ticker(lateness: list[float]) -> None:
    """Sleep 1 ms at a time, noting how late each wake-up is."""
    while True:
        before = time.perf_counter()
        await asyncio.sleep(0.001)
        lateness.append(time.perf_counter() - before - 0.001)


def spread(values: list[float]) -> str:
    """p50/p95/max of durations in seconds, as milliseconds."""
    ordered = sorted(values)
    if not ordered:
        return "  none"
    p50 = ordered[len(ordered) // 2]
    p95 = ordered[min(len(ordered) - 1, int(len(ordered) * 0.95))]
    return f"{p50 * 1000:5.2f}/{p95 * 1000:5.2f}/{ordered[-1] * 1000:5.2f}"


#: The longest the event loop may be kept busy by see() (the goal), seconds.
STALL_GOAL = 0.002


async def blocking_while(see: Callable[[], Any], rounds: int) -> tuple[list[float], LoopSteps,
                                                                     list[float]]:
    """Call ``see()`` ``rounds`` times beside a 1 ms ticker, timing every loop step.

    Returns the latencies of see(), the loop's steps, and the ticker's lateness.
    """
    await see()  # warm up: a camera's detector is made on its worker thread
    latencies: list[float] = []
    lateness: list[float] = []
    with LoopSteps() as steps:
        async with anyio.create_task_group() as group:
            group.start_soon(ticker, lateness)
            await anyio.sleep(0.01)
            for _ in range(rounds):
                start = time.perf_counter()
                await see()
                latencies.append(time.perf_counter() - start)
            group.cancel_scope.cancel()
    return latencies, steps, lateness


def report(name: str, latencies: list[float] | None, steps: LoopSteps,
           lateness: list[float]) -> tuple[float, str]:
    """Print one line of figures (ms, p50/p95/max); return the longest loop step (CPU)."""
    see = f"see() {spread(latencies)}" if latencies is not None else " " * 24
    print(
        f"  {name:<34} {see}  loop step wall {spread(steps.wall)} "
        f"CPU {spread(steps.cpu)}  1 ms ticker late {spread(lateness)}  "
        f"{len(steps.gc)} GCs, longest {max(steps.gc, default=0.0) * 1000:.2f}"
    )
    return steps.longest


async def latency_and_blocking(rounds: int) -> None:
    print(
        "== see() latency and event-loop blocking: ms as p50/p95/max; a 1 ms ticker runs beside\n"
        "   see(), and every step the event loop runs is timed (wall clock; and CPU time of\n"
        "   the loop thread, which the machine's load does not inflate). On this shared\n"
        "   2-core machine the idle line shows what load alone does to the same measures.\n"
        "   The loop thread's garbage collections are timed apart (count, longest ms) and\n"
        "   left out of its steps' CPU time: they last as long as the process has objects."
    )
    cases = (
        ((640, 480), KNOWN_CALIBRATIONS["Logitech C270"].scaled_to(640, 480)),
        ((1280, 720), DEFAULT_CALIBRATION),
    )
    longest: dict[str, tuple[float, str]] = {}
    for resolution, calibration in cases:
        label = f"{resolution[0]}x{resolution[1]}"
        print(f"{label}:")
        images = arena_images(calibration, resolution)
        kit = use_kit()  # a fresh kit, whose camera takes the pictures of this size
        kit.camera = SimulatedCamera(calibration=calibration, resolution=resolution)
        sizes = kit.world.arena.marker_sizes()
        kit.world.place_robot(POSES[0])
        board = FileCameraBackend.make_board(images, calibration, loop=True, marker_sizes=sizes)
        async with KitRobot(environment=SIMULATED_ENVIRONMENT) as robot:
            assert robot.camera is not None
            for name, camera in (("j5aio file camera (detect)", board.camera),
                                 ("j5aio simulated camera (render+detect)", robot.camera)):
                figures = await blocking_while(camera.see, rounds)
                longest[f"{label} {name}"] = report(name, *figures)
        await board.close()
        processor = april_vision_processor(calibration, {k: v / 1000 for k, v in sizes.items()})
        if processor is None:
            print("  april_vision not installed (pip install april_vision) - no comparison")
        else:
            frames = iter(images * (rounds + 1))

            async def theirs() -> object:
                # april_vision's see() is synchronous: called from a coroutine, as a
                # program of sr-robot3's API running on asyncio would call it (after a
                # yield, so that each loop step holds one see()).
                await asyncio.sleep(0)
                return processor.see(frame=next(frames))  # noqa: B023

            report("april_vision Processor.see (sync)", *await blocking_while(theirs, rounds))
        idle: list[float] = []
        with LoopSteps() as steps:
            async with anyio.create_task_group() as group:
                group.start_soon(ticker, idle)
                await anyio.sleep(1.0)
                group.cancel_scope.cancel()
        report("idle loop (ticker only)", None, steps, idle)
    worst = max(longest, key=lambda k: longest[k][0])
    seconds, step = longest[worst]
    verdict = "met" if seconds <= STALL_GOAL else "NOT met"
    print(
        f"longest loop step (CPU) while j5aio's see() ran: {seconds * 1000:.2f} ms "
        f"({worst}); goal <= {STALL_GOAL * 1000:.0f} ms: {verdict}\n    that step: {step}"
    )


def accuracy() -> None:
    print("== accuracy: 150 mm markers at 1280x720, default simulated calibration "
          "(fx = 1387.5), 8 poses a distance")
    sizes = {1: 150.0}
    ours = MarkerDetector()
    processor = april_vision_processor(DEFAULT_CALIBRATION, {1: 0.15})
    poses = [(b, y, p, r) for b, y, p, r in (
        (0, 0, 0, 0), (12, 30, 0, 0), (-10, -35, 15, 0), (5, 0, -20, 20),
        (-15, 20, 10, -90), (8, -25, 0, 180), (3, 45, 0, 0), (-5, 0, 30, 0))]
    for distance in (500, 1000, 2000, 3000, 4000, 4500, 5000):
        worst: dict[str, list[float]] = {"ours": [0.0] * 4, "theirs": [0.0] * 4}
        for bearing, yaw, pitch, roll in poses:
            a = math.radians(bearing)
            centre = (distance * math.sin(a), 0.0, distance * math.cos(a))
            truth_o = Orientation(math.radians(yaw), math.radians(pitch), math.radians(roll))
            item = MarkerItem(1, 150.0, centre, rotation_from_orientation(truth_o))
            image = render(DEFAULT_CALIBRATION, (1280, 720), [item])
            truth, _ = position_from_translation(centre)
            results: dict[str, list[Any]] = {
                "ours": ours.detect(image, DEFAULT_CALIBRATION, sizes)
            }
            if processor is not None:
                results["theirs"] = processor.see(frame=image)
            for who, markers in results.items():
                if len(markers) != 1:
                    worst[who][3] += 1
                    continue
                m = markers[0]
                w = worst[who]
                if who == "ours":
                    seen = (float(m.position.distance), float(m.position.horizontal_angle))
                else:  # april_vision: whole mm, and bearing in degrees, clockwise
                    seen = (float(m.distance), math.radians(m.bearing))
                w[0] = max(w[0], abs(seen[0] - truth.distance) / truth.distance * 100)
                w[1] = max(w[1], math.degrees(abs(seen[1] - truth.horizontal_angle)))
                o = (m.orientation.yaw, m.orientation.pitch, m.orientation.roll)
                w[2] = max(w[2], *(math.degrees(abs(math.remainder(g - t, math.tau)))
                                   for g, t in zip(o, truth_o, strict=True)))
        line = f"{distance / 1000:3.1f} m ({150 * 1387.5 / distance:3.0f} px): "
        for who, w in worst.items():
            if who == "theirs" and processor is None:
                continue
            label = "j5aio" if who == "ours" else "april_vision"
            line += (f"{label}: distance {w[0]:4.2f} %, bearing {w[1]:4.2f} deg, "
                     f"orientation {w[2]:5.1f} deg, missed {w[3]:.0f}   ")
        print(line)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--quick", action="store_true", help="shorter runs")
    args = parser.parse_args()
    detection_speed(2.0 if args.quick else 6.0)
    anyio.run(latency_and_blocking, 20 if args.quick else 60)
    accuracy()


if __name__ == "__main__":
    main()
