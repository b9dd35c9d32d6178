"""The simulated kit's camera backend, and the clock that moves the kit's world on.

Every robot on the simulated kit finds this camera, but few look through it; so finding
it imports neither the arena nor the camera's model nor the vision modules: the kit's
world and camera, the camera's calibration and the arena's marker sizes are read the
first time the camera is looked through (or asked for its calibration, or its table of
marker sizes is read). Its names are documented, and imported, as
:mod:`j5aio.simulator.camera`'s.
"""

from __future__ import annotations

import asyncio
import copy
import functools
from collections.abc import Sequence
from typing import TYPE_CHECKING, ClassVar

from j5aio.backends.camera.frames import FrameCameraBackend
from j5aio.boards.camera import CameraBoard
from j5aio.components._marker_sizes import MarkerSizes

from .kit import SimulatedKit, current_kit

if TYPE_CHECKING:
    from collections.abc import Callable

    from j5aio.backends.hardware.options import DiscoveryOptions
    from j5aio.boards.board import Board
    from j5aio.vision.calibration import CameraCalibration
    from j5aio.vision.image import Image

    from ._camera_model import SimulatedCamera

__all__ = ["TICK", "SimulatedCameraBackend", "update_world"]

#: How often the world is moved on while a simulated camera exists, seconds.
TICK = 0.01


class _ArenaMarkerSizes(MarkerSizes):
    """The table of the sizes of the markers in a kit's arena, read when first looked at."""

    def __init__(self, kit: SimulatedKit) -> None:  # (the base's checks run on the arena's)
        self._kit = kit
        self._default = None
        self._table: dict[int, float] | None = None

    @property
    def _sizes(self) -> dict[int, float]:
        if self._table is None:
            self._table = dict(self._kit.world.arena.marker_sizes())
        return self._table

    @_sizes.setter
    def _sizes(self, sizes: dict[int, float]) -> None:
        self._table = sizes


class SimulatedCameraBackend(FrameCameraBackend):
    """The camera of the simulated kit: pictures rendered from the robot's pose.

    The kit's camera (:attr:`~j5aio.simulator.kit.SimulatedKit.camera`) is the one it
    was made with: a camera set on the kit afterwards is another camera's.

    :param kit: the kit whose world (arena, pose, motors) the camera looks at.
    :raises ValueError: the kit has no camera.
    """

    board: ClassVar[type[Board]] = CameraBoard

    def __init__(self, kit: SimulatedKit) -> None:
        if not kit.has_camera:
            raise ValueError(f"{kit.name} has no camera")
        # (the kit's default camera, not made yet, is made when first needed)
        self._world_camera = kit._camera_if_made()
        self._model: CameraCalibration | None = None
        super().__init__(f"SIMCAM-{kit.name}", None)
        self._kit = kit
        #: The table of the arena's marker sizes, which the camera starts with.
        self.marker_sizes: MarkerSizes = _ArenaMarkerSizes(kit)
        self._ticking = False

    @property
    def _camera(self) -> SimulatedCamera:
        if self._world_camera is None:
            self._world_camera = self._kit.default_camera()
        return self._world_camera

    @property
    def _calibration(self) -> CameraCalibration | None:  # (the base's, from the camera's model)
        if self._model is None:
            self._model, _ = self._camera.model()
        return self._model

    @_calibration.setter
    def _calibration(self, calibration: CameraCalibration | None) -> None:
        if calibration is not None:
            self._model = calibration

    @classmethod
    async def discover(cls, *, options: DiscoveryOptions | None = None) -> Sequence[Board]:
        """Find the current kit's camera (none if its world has no camera).

        ``options`` (for serial and USB discovery) is accepted and ignored.
        """
        kit = current_kit()
        if not kit.has_camera:
            return []
        backend = cls(kit)
        backend._start_ticking()
        return [CameraBoard(backend.name, backend)]

    @property
    def kit(self) -> SimulatedKit:
        """The kit the camera belongs to."""
        return self._kit

    def _start_ticking(self) -> None:
        _WorldClock.join(self._kit, asyncio.get_running_loop())
        self._ticking = True

    def grab(self) -> Image:
        """Render the view from the pose the robot has now (call on the event loop)."""
        from ._camera_view import render_view

        return render_view(self._kit.world, self._camera)

    async def frame_source(self) -> Callable[[], Image]:
        """Move the world to now, note it, and return the call that renders its view.

        Only a shallow copy of the world (a few microseconds) is made here, on the event
        loop; the scene is laid out and drawn by the returned call, on the worker thread.
        The copy holds the robot's pose of this moment: the arena, its markers and tokens
        are immutable, so the worker never reads what the loop changes.
        """
        from ._camera_view import render_view

        update_world(self._kit)
        return functools.partial(render_view, copy.copy(self._kit.world), self._camera)

    async def close(self) -> None:
        """Stop moving the world on, and stop the worker thread."""
        if self._ticking:
            self._ticking = False
            _WorldClock.leave(self._kit)
        await super().close()


class _WorldClock:
    """Moves a kit's world on while any of its cameras is open.

    One clock a kit, on the event loop of the camera that started it, however many camera
    backends have been made for the kit. While the robot drives it ticks every
    :data:`TICK` (so that the walls stop it where they are); while every drive motor is
    still it sleeps, and a motor board's next command wakes it: an idle robot costs
    nothing, and the world is moved on at the very moment the powers change.
    """

    _clocks: ClassVar[dict[int, _WorldClock]] = {}

    def __init__(self, kit: SimulatedKit, loop: asyncio.AbstractEventLoop) -> None:
        self.kit = kit
        self.loop = loop
        self.users = 0
        self.timer: asyncio.TimerHandle | None = None
        self._stop_listening = [board.listen(self._changed) for board in kit.drive_motor_boards]

    @classmethod
    def join(cls, kit: SimulatedKit, loop: asyncio.AbstractEventLoop) -> None:
        clock = cls._clocks.get(id(kit))
        if clock is None or clock.kit is not kit or clock.loop is not loop or loop.is_closed():
            if clock is not None:
                clock.stop()
            clock = cls._clocks[id(kit)] = cls(kit, loop)
            clock.tick()
        clock.users += 1

    @classmethod
    def leave(cls, kit: SimulatedKit) -> None:
        clock = cls._clocks.get(id(kit))
        if clock is None or clock.kit is not kit:
            return
        clock.users -= 1
        if clock.users <= 0:
            clock.stop()
            del cls._clocks[id(kit)]

    def stop(self) -> None:
        """Stop ticking and listening to the motor boards."""
        if self.timer is not None:
            self.timer.cancel()
            self.timer = None
        for stop in self._stop_listening:
            stop()
        self._stop_listening = []

    def tick(self) -> None:
        """Move the world on now; tick again soon while the robot drives."""
        self.timer = None
        if not update_world(self.kit) or self.loop.is_closed():
            return
        self.timer = self.loop.call_later(TICK, self.tick)

    def _changed(self) -> None:
        # A motor board took a command (in whatever thread fed it): move the world on to
        # now with the powers held until now, and tick if the robot now drives.
        if self.loop.is_closed():
            return
        try:
            running = asyncio.get_running_loop()
        except RuntimeError:
            running = None
        if running is self.loop:
            self._wake()
        else:
            self.loop.call_soon_threadsafe(self._wake)

    def _wake(self) -> None:
        if self.timer is not None:
            update_world(self.kit)  # ticking already: only take the new powers now
            return
        self.tick()


def update_world(kit: SimulatedKit, now: float | None = None) -> bool:
    """Move ``kit``'s robot on to ``now`` from its motors.

    ``now`` is a time of the kit's clock (``kit.clock``, :mod:`j5aio.simulator.clock`),
    its present by default: the robot drives in the kit's time, as its boards' timers
    run, so under a time scale of 2 a robot second of driving lasts two real seconds.

    :returns: whether the robot drives on from ``now`` (a drive motor's power is not 0).
    """
    if not kit.has_world and not any(
        motor.power for board in kit.drive_motor_boards for motor in board.motors
    ):
        # Every motor is still and the world not made yet: a world made later, at the
        # first power, starts from there, where this one would have held the robot still.
        return False
    drive = kit.world.drive
    powers = []
    for board_index, motor_index in (drive.left, drive.right):
        try:
            powers.append(kit.drive_motor_boards[board_index].motors[motor_index].power)
        except IndexError:
            powers.append(0.0)
    kit.world.update(kit.clock.now() if now is None else now, powers[0], powers[1])
    return powers[0] != 0 or powers[1] != 0


# Documented, and imported, as j5aio.simulator.camera's.
for _name in ("SimulatedCameraBackend", "update_world"):
    globals()[_name].__module__ = "j5aio.simulator.camera"
del _name
