"""Make the picture of the "Where am I" tutorial (docs/_static/where-am-i-drive.png).

Run ``J5AIO_ENV=sim python tools/make_where_am_i_picture.py`` (needs the vision extra): it
runs the tutorial's program (``examples/drive_to_token.py``) on the simulated kit, notes
the robot's true pose and the program's estimate 20 times a second, and draws both paths
on the arena from above (the arena is drawn as the vision tutorial's picture is).
"""

from __future__ import annotations

import importlib.util
import math
from pathlib import Path
from types import ModuleType
from typing import Any

import anyio
import cv2
import numpy as np

from j5aio.simulator.kit import use_kit
from j5aio.vision.track import latest_estimate

ROOT = Path(__file__).resolve().parent.parent
OUTPUT = ROOT / "docs" / "_static" / "where-am-i-drive.png"


def load(path: Path) -> ModuleType:
    """Import a script by its path."""
    spec = importlib.util.spec_from_file_location(path.stem, path)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


async def main() -> None:
    """Run the tutorial's program, then draw the paths."""
    pictures = load(ROOT / "tools" / "make_vision_pictures.py")
    example = load(ROOT / "examples" / "drive_to_token.py")
    kit = use_kit()
    assert kit.camera is not None
    truth: list[tuple[float, float]] = []
    believed: list[tuple[float, float]] = []
    target: list[tuple[float, float]] = []

    async def run() -> None:
        target.append(await example.main())

    async with anyio.create_task_group() as group:
        group.start_soon(run)
        while not target:
            pose = kit.world.pose
            truth.append((pose.x, pose.y))
            estimate = latest_estimate()
            if estimate is not None:
                believed.append((estimate.x, estimate.y))
            await anyio.sleep(0.05)
    length = kit.world.arena.length
    image: Any = pictures.draw_map(kit.world, kit.camera)

    def at(point: tuple[float, float]) -> tuple[int, int]:
        mapped: tuple[int, int] = pictures.to_map(point[0], point[1], length)
        return mapped

    cv2.polylines(image, [np.array([at(p) for p in truth], dtype=np.int32)], False,
                  (255, 200, 80), 2, cv2.LINE_AA)
    for point in believed[::2]:
        cv2.circle(image, at(point), 2, (160, 80, 255), -1, cv2.LINE_AA)
    cv2.drawMarker(image, at(target[0]), (0, 0, 255), cv2.MARKER_TILTED_CROSS, 14, 2)
    legend = (("true path", (255, 200, 80)), ("estimate", (160, 80, 255)),
              ("token, as the robot saw it", (0, 0, 255)))
    left, top = at((3900.0, 1500.0))  # on the floor, south-east of the tokens
    for k, (text, colour) in enumerate(legend):
        y = top + 18 * k
        cv2.line(image, (left, y - 4), (left + 16, y - 4), colour, 3)
        cv2.putText(image, text, (left + 22, y), cv2.FONT_HERSHEY_SIMPLEX, 0.42,
                    (255, 255, 255), 1, cv2.LINE_AA)
    cv2.imwrite(str(OUTPUT), image)
    error = max(math.dist(a, b) for a, b in zip(truth[-len(believed):], believed, strict=True))
    print(f"wrote {OUTPUT}; {len(truth)} poses noted, largest gap {error:.0f} mm")


if __name__ == "__main__":
    anyio.run(main)
