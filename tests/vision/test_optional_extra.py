"""Without the vision extra, j5aio imports and a camera says what to install."""

from __future__ import annotations

import subprocess
import sys
import textwrap

import pytest

from j5aio.vision._optional import INSTALL_HINT, VisionNotInstalledError, require

# Runs in a fresh interpreter where numpy, cv2 and pyapriltags cannot be imported.
BLOCKED = textwrap.dedent(
    """
    import sys

    class Block:
        def find_spec(self, name, path=None, target=None):
            if name.split(".")[0] in ("numpy", "cv2", "pyapriltags"):
                raise ImportError(f"{name} is blocked for this test")
            return None

    sys.meta_path.insert(0, Block())
    """
)


def run_blocked(code: str) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [sys.executable, "-c", BLOCKED + textwrap.dedent(code)],
        capture_output=True,
        text=True,
        timeout=120,
        check=False,
    )


def test_j5aio_imports_and_the_simulated_robot_runs_without_the_extra() -> None:
    result = run_blocked(
        """
        import anyio
        import j5aio, j5aio.vision, j5aio.sync, j5aio.kit
        import j5aio.components.marker_camera
        from j5aio.kit import KitRobot
        from j5aio.simulator.environment import SIMULATED_ENVIRONMENT
        from j5aio.vision import VisionNotInstalledError

        async def main():
            async with KitRobot(environment=SIMULATED_ENVIRONMENT) as robot:
                await robot.motor_boards[0].motors[0].set_power(0.5)
                try:
                    await robot.camera.see()
                except VisionNotInstalledError as exc:
                    print("CAMERA:", exc)

        anyio.run(main)
        assert "numpy" not in sys.modules and "cv2" not in sys.modules
        print("OK")
        """
    )
    assert result.returncode == 0, result.stderr
    assert "OK" in result.stdout
    assert "CAMERA: Cameras need the optional vision libraries" in result.stdout
    assert INSTALL_HINT in result.stdout


def discover_blocked(devices: list[str]) -> subprocess.CompletedProcess[str]:
    return run_blocked(
        f"""
        import anyio, glob, logging
        logging.basicConfig(level=logging.WARNING, format="%(message)s")
        sys.platform = "linux"
        glob.glob = lambda pattern: {devices!r}
        from j5aio.backends.camera import OpenCVCameraBackend
        print("FOUND", anyio.run(OpenCVCameraBackend.discover))
        try:
            OpenCVCameraBackend(0)
        except ImportError as exc:
            print("DIRECT:", exc)
        """
    )


def test_webcam_discovery_finds_none_and_says_what_to_install() -> None:
    result = discover_blocked(["/dev/video0"])
    assert result.returncode == 0, result.stderr
    assert "FOUND []" in result.stdout
    assert "DIRECT: Cameras need" in result.stdout
    assert INSTALL_HINT in result.stderr


def test_with_no_camera_plugged_in_nothing_is_said_about_the_extra() -> None:
    result = discover_blocked([])
    assert result.returncode == 0, result.stderr
    assert "FOUND []" in result.stdout
    assert INSTALL_HINT not in result.stderr


def test_require_names_the_package_to_install() -> None:
    with pytest.raises(VisionNotInstalledError, match="opencv-python-headless") as caught:
        # a module that does not exist stands in for a missing OpenCV
        import j5aio.vision._optional as optional

        optional._PACKAGES["j5aio_no_such_module"] = "opencv-python-headless"
        try:
            require("j5aio_no_such_module")
        finally:
            del optional._PACKAGES["j5aio_no_such_module"]
    assert isinstance(caught.value, ImportError)
