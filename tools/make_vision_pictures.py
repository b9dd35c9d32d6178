"""Make the pictures of the vision tutorial (docs/_static/vision-*.png).

Run ``python tools/make_vision_pictures.py`` (needs the vision extra): it draws the
standard simulated arena from above, with the robot and what its camera can see, and
renders the robot's view with the markers that ``see()`` finds outlined.
"""

from __future__ import annotations

import math
from pathlib import Path

import anyio
import cv2
import numpy as np

from j5aio.kit import KitRobot
from j5aio.simulator.arena import Pose, SimulatedWorld
from j5aio.simulator.camera import SimulatedCamera
from j5aio.simulator.environment import SIMULATED_ENVIRONMENT
from j5aio.simulator.kit import use_kit

STATIC = Path(__file__).resolve().parent.parent / "docs" / "_static"
POSE = Pose(1500.0, 1300.0, 0.9)
SCALE = 0.12  # pixels a mm on the map
MARGIN = 40


def to_map(x: float, y: float, length: float) -> tuple[int, int]:
    """World mm to map pixels (north up)."""
    return (round(MARGIN + x * SCALE), round(MARGIN + (length - y) * SCALE))


def draw_map(world: SimulatedWorld, camera: SimulatedCamera) -> np.ndarray:
    """The arena from above: walls, markers with their ids, tokens, robot, field of view."""
    arena = world.arena
    size = (round(arena.width * SCALE) + 2 * MARGIN, round(arena.length * SCALE) + 2 * MARGIN)
    image = np.full((size[1], size[0], 3), 255, dtype=np.uint8)
    cv2.rectangle(image, to_map(0, 0, arena.length), to_map(arena.width, arena.length,
                  arena.length), (90, 110, 120), -1)
    cv2.rectangle(image, to_map(0, 0, arena.length), to_map(arena.width, arena.length,
                  arena.length), (40, 40, 40), 3)
    for marker in arena.markers:
        dx, dy = -math.sin(marker.facing), math.cos(marker.facing)
        half = marker.size / 2
        a = to_map(marker.x - dx * half, marker.y - dy * half, arena.length)
        b = to_map(marker.x + dx * half, marker.y + dy * half, arena.length)
        cv2.line(image, a, b, (255, 255, 255), 5)
        label = to_map(marker.x + 220 * math.cos(marker.facing),
                       marker.y + 220 * math.sin(marker.facing), arena.length)
        cv2.putText(image, str(marker.marker_id), (label[0] - 8, label[1] + 5),
                    cv2.FONT_HERSHEY_SIMPLEX, 0.4, (255, 255, 255), 1, cv2.LINE_AA)
    for token in arena.tokens:
        half = token.side / 2
        c, s = math.cos(token.heading), math.sin(token.heading)
        corners = [
            to_map(token.x + half * (sx * c - sy * s), token.y + half * (sx * s + sy * c),
                   arena.length)
            for sx, sy in ((-1, -1), (1, -1), (1, 1), (-1, 1))
        ]
        cv2.fillConvexPoly(image, np.array(corners, dtype=np.int32), (60, 160, 230), cv2.LINE_AA)
        cv2.putText(image, str(token.marker_id), (corners[2][0] + 4, corners[2][1]),
                    cv2.FONT_HERSHEY_SIMPLEX, 0.4, (255, 255, 255), 1, cv2.LINE_AA)
    calibration, (width, _) = camera.model()
    half_fov = math.atan2(width / 2, calibration.fx)
    cx, cy, _ = world.camera_position()
    reach = 3500.0
    fov = [to_map(cx, cy, arena.length)] + [
        to_map(cx + reach * math.cos(world.pose.heading + s * half_fov),
               cy + reach * math.sin(world.pose.heading + s * half_fov), arena.length)
        for s in (-1, 1)
    ]
    overlay = image.copy()
    cv2.fillConvexPoly(overlay, np.array(fov, dtype=np.int32), (0, 220, 255), cv2.LINE_AA)
    image = cv2.addWeighted(overlay, 0.35, image, 0.65, 0).astype(np.uint8)
    centre = to_map(world.pose.x, world.pose.y, arena.length)
    cv2.circle(image, centre, round(world.drive.radius * SCALE), (40, 40, 200), -1, cv2.LINE_AA)
    nose = to_map(world.pose.x + world.drive.radius * math.cos(world.pose.heading),
                  world.pose.y + world.drive.radius * math.sin(world.pose.heading), arena.length)
    cv2.line(image, centre, nose, (255, 255, 255), 2, cv2.LINE_AA)
    return image


async def main() -> None:
    """Write both pictures, and print the markers the robot sees."""
    STATIC.mkdir(parents=True, exist_ok=True)
    kit = use_kit()
    kit.world.place_robot(POSE)
    assert kit.camera is not None
    cv2.imwrite(str(STATIC / "vision-arena.png"), draw_map(kit.world, kit.camera))
    async with KitRobot(environment=SIMULATED_ENVIRONMENT) as robot:
        assert robot.camera is not None
        await robot.camera.save(STATIC / "vision-detection.png")
        for marker in await robot.camera.see():
            print(marker)
    print(f"wrote {STATIC / 'vision-arena.png'} and {STATIC / 'vision-detection.png'}")


if __name__ == "__main__":
    anyio.run(main)
