"""What the live view shows of the simulated arena: its walls, markers and tokens, and the robot.

On the simulated kit the robot drives in an arena (:mod:`j5aio.simulator.arena`): the
page draws it from above, with the robot's pose and its camera's field of view, and
moves the robot as the kit's motors drive it. Beside the true pose it draws where the
program believes the robot is, when the program keeps an estimate
(:class:`~j5aio.vision.track.PositionTracker`). The arena is sent to a page once; the pose
each time it changes. Both are plain JSON-ready dictionaries, in the world frame of the
arena (mm, x east, y north; headings in radians anticlockwise from east).

Everything here reads the simulated kit, so it runs in the program's event-loop thread.
"""

from __future__ import annotations

import math
from collections.abc import Iterable
from typing import TYPE_CHECKING, Any

from j5aio.boards.board import Board
from j5aio.simulator.kit import SimulatedKit, current_kit
from j5aio.vision.track import latest_estimate

from .controls import simulator_of

if TYPE_CHECKING:
    from j5aio.simulator.camera import SimulatedCamera

__all__ = ["describe_arena", "describe_pose", "field_of_view", "kit_of"]


def kit_of(boards: Iterable[Board]) -> SimulatedKit | None:
    """The simulated kit the boards belong to, or ``None`` when none is simulated.

    A simulated camera knows its kit; any other board of the simulated kit belongs to
    the current kit.
    """
    simulated = False
    for board in boards:
        kit = getattr(board.backend, "kit", None)
        if isinstance(kit, SimulatedKit):
            return kit
        simulated = simulated or simulator_of(board) is not None
    return current_kit() if simulated else None


def field_of_view(camera: SimulatedCamera) -> tuple[float, float]:
    """The bearings of the left and right edges of the camera's picture, radians.

    Left is positive (anticlockwise), from the camera's pinhole model: the principal
    point splits the picture's width.
    """
    calibration, (width, _) = camera.model()
    return (
        math.atan2(calibration.cx + 0.5, calibration.fx),
        -math.atan2(width - calibration.cx - 0.5, calibration.fx),
    )


def describe_arena(kit: SimulatedKit) -> dict[str, Any]:
    """The arena of ``kit``'s world as the page draws it: size, wall markers, tokens, robot size."""
    world = kit.world
    arena = world.arena
    return {
        "key": kit.name,
        "width": arena.width,
        "length": arena.length,
        "markers": [
            {"id": m.marker_id, "x": m.x, "y": m.y, "size": m.size, "facing": m.facing}
            for m in arena.markers
        ],
        "tokens": [
            {"id": t.marker_id, "x": t.x, "y": t.y, "side": t.side, "heading": t.heading}
            for t in arena.tokens
        ],
        "robot": {"radius": world.drive.radius, "track_width": world.drive.track_width},
    }


def describe_pose(kit: SimulatedKit) -> dict[str, Any]:
    """Where ``kit``'s robot is now, and what its camera can see (``None`` without one).

    ``estimate`` is where the program believes the robot is: ``None`` until a
    :class:`~j5aio.vision.track.PositionTracker` has an estimate.
    """
    world = kit.world
    pose = world.pose
    shown: dict[str, Any] = {
        "x": pose.x, "y": pose.y, "heading": pose.heading, "camera": None, "estimate": None,
    }
    estimate = latest_estimate()
    if estimate is not None:
        shown["estimate"] = {
            "x": estimate.x, "y": estimate.y, "heading": estimate.heading,
            "error": estimate.position_error, "age": estimate.age,
        }
    if kit.camera is not None:
        x, y, _ = world.camera_position()
        left, right = field_of_view(kit.camera)
        shown["camera"] = {
            "x": x, "y": y,
            "left": world.camera_heading() + left, "right": world.camera_heading() + right,
        }
    return shown
