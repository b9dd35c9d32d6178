"""Every public name of sbot 2026.1.0 is in ``j5aio.compat.sbot``, with a compatible signature.

The peer's surface is read from the installed ``sbot`` (the ``compat-sbot`` tox env
installs it from PyPI; ``SBOT_PEER_PYTHON`` may instead name a Python that has it): every
public class, function and constant its modules define, each class's public methods and
properties with their parameters (names, kinds, defaults), its enum members and
named-tuple fields, and its builtin base classes. The same description of the compat
package must contain all of it: a rename, a missing parameter, another default or a lost
base class fails the test.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
from importlib.util import find_spec
from pathlib import Path
from typing import Any

import pytest

ROOT = Path(__file__).resolve().parents[2]
#: The version whose API the compat package gives.
PEER_VERSION = "2026.1.0"

#: Names of sbot that are not part of what a program uses: the Raspberry Pi HAT's GPIO
#: map, the USB ids sbot probes, its flags of what it runs on (the Webots simulator, the
#: HAT, an MQTT broker), and the constructor from april_vision's own marker.
NOT_API = frozenset({
    "sbot._leds.RobotLEDs",
    "sbot._leds.RGBled",
    "sbot._leds.HAS_HAT",
    "sbot._leds.IN_SIMULATOR",
    "sbot._utils.IN_SIMULATOR",
    "sbot._utils.MQTT_VALID",
    "sbot._arduinos.SUPPORTED_VID_PIDS",
    "sbot.marker.Marker.from_april_vision_marker",
})

# The modules sbot's programs reach: the package, the modules behind ``motors``,
# ``servos``... (their classes), and what those return or raise.
MODULES = (
    "", "._arduinos", "._comp", "._leds", "._motors", "._power", "._servos", "._utils",
    "._vision", ".marker", ".game_specific", ".internal.exceptions",
)

DESCRIBE = r'''
import enum, importlib, inspect, json, os, sys
os.environ["SBOT_PYTEST"] = "1"  # the names only: no robot

LITERALS = (int, float, str, bool, tuple, list, dict, range, type(None))

def params(function):
    try:
        signature = inspect.signature(function)
    except (TypeError, ValueError):
        return None
    return [
        [p.name, p.kind.name, None if p.default is p.empty else repr(p.default)]
        for p in signature.parameters.values()
    ]

def describe_class(cls):
    out = {"kind": "class", "bases": sorted(
        base.__name__ for base in cls.__mro__
        if base.__module__ in ("builtins", "enum") and base is not object
    )}
    if issubclass(cls, enum.Enum):
        out["members"] = {m.name: repr(m.value) for m in cls}
        return out
    if issubclass(cls, tuple) and hasattr(cls, "_fields"):
        out["fields"] = list(cls._fields)
    methods = {}
    for name, raw in vars(cls).items():
        if name.startswith("_") and name != "__init__":
            continue
        if name in getattr(cls, "_fields", ()):
            continue
        if isinstance(raw, property):
            methods[name] = "property"
        elif callable(raw) or isinstance(raw, (classmethod, staticmethod)):
            methods[name] = params(getattr(cls, name))
    out["methods"] = methods
    return out

def literal(value):
    if isinstance(value, range):
        return repr(value)
    if isinstance(value, dict):
        return repr(sorted((repr(k), repr(v)) for k, v in value.items()))
    return repr(value)

def describe(prefix, modules):
    surface = {}
    for suffix in modules:
        module = importlib.import_module(prefix + suffix)
        names = getattr(module, "__all__", None) if suffix == "" else None
        for name, value in vars(module).items():
            if name.startswith("_") or (names is not None and name not in names):
                continue
            key = "sbot" + suffix + "." + name
            if inspect.isclass(value) or inspect.isfunction(value):
                if suffix != "" and getattr(value, "__module__", "") != module.__name__:
                    continue  # imported into the module, described where it is defined
                surface[key] = (
                    describe_class(value) if inspect.isclass(value)
                    else {"kind": "function", "params": params(value)}
                )
            elif isinstance(value, enum.Enum):
                surface[key] = {"kind": "value", "value": repr(value.value)}
            elif isinstance(value, LITERALS):
                surface[key] = {"kind": "value", "value": literal(value)}
    return surface

print("SURFACE " + json.dumps(describe(sys.argv[1], json.loads(sys.argv[2]))))
'''


def _peer_python() -> str | None:
    """A Python with the peer installed: this one, or ``SBOT_PEER_PYTHON``."""
    if find_spec("sbot") is not None:
        return sys.executable
    return os.environ.get("SBOT_PEER_PYTHON") or None


def _surface(python: str, package: str) -> dict[str, Any]:
    environment = {**os.environ, "PYTHONPATH": str(ROOT), "SBOT_PYTEST": "1"}
    result = subprocess.run(
        [python, "-c", DESCRIBE, package, json.dumps(MODULES)],
        capture_output=True, text=True, timeout=120, env=environment, cwd=ROOT, check=False,
    )
    assert result.returncode == 0, result.stderr[-3000:]
    line = next(line for line in result.stdout.splitlines() if line.startswith("SURFACE "))
    found: dict[str, Any] = json.loads(line.removeprefix("SURFACE "))
    return found


@pytest.fixture(scope="module")
def peer_surface() -> dict[str, Any]:
    python = _peer_python()
    if python is None:
        pytest.skip(
            f"sbot is not installed: run `tox -e compat-sbot` (it installs sbot=={PEER_VERSION} "
            "from PyPI), or set SBOT_PEER_PYTHON to a Python that has it",
        )
    version = subprocess.run(
        [python, "-c", "from importlib.metadata import version; print(version('sbot'))"],
        capture_output=True, text=True, timeout=60, check=False,
    ).stdout.strip()
    if version != PEER_VERSION:
        pytest.skip(f"sbot {version} is installed; this test compares with {PEER_VERSION}")
    return _surface(python, "sbot")


@pytest.fixture(scope="module")
def compat_surface() -> dict[str, Any]:
    return _surface(sys.executable, "j5aio.compat.sbot")


def _differences(peer: dict[str, Any], compat: dict[str, Any]) -> list[str]:
    problems: list[str] = []
    for name, described in sorted(peer.items()):
        if name in NOT_API:
            continue
        ours = compat.get(name)
        if ours is None:
            problems.append(f"{name}: missing")
            continue
        if described["kind"] != ours["kind"]:
            problems.append(f"{name}: a {described['kind']} in sbot, a {ours['kind']} here")
            continue
        if described["kind"] in ("value", "function"):
            if described != ours:
                problems.append(f"{name}: sbot has {described}, here {ours}")
            continue
        missing_bases = set(described["bases"]) - set(ours["bases"])
        if missing_bases:
            problems.append(f"{name}: lacks base classes {sorted(missing_bases)}")
        for key in ("members", "fields"):
            if described.get(key) != ours.get(key) and key in described:
                problems.append(f"{name}: {key} {described[key]} here {ours.get(key)}")
        for method, signature in described.get("methods", {}).items():
            if f"{name}.{method}" in NOT_API:
                continue
            mine = ours.get("methods", {}).get(method, "missing")
            if method == "__init__":
                continue  # built by the package, not by programs
            if mine != signature:
                problems.append(f"{name}.{method}: sbot {signature}, here {mine}")
    return problems


def test_every_public_name_of_sbot_is_here_with_its_signature(
    peer_surface: dict[str, Any], compat_surface: dict[str, Any],
) -> None:
    assert len(peer_surface) > 40  # the description found sbot's API
    assert _differences(peer_surface, compat_surface) == []


def test_the_comparison_catches_a_rename_and_a_lost_parameter(
    peer_surface: dict[str, Any], compat_surface: dict[str, Any],
) -> None:
    broken = json.loads(json.dumps(compat_surface))
    motor = broken["sbot._motors.Motor"]["methods"]
    motor["set_speed"] = motor.pop("set_power")
    broken["sbot._utils.Utils"]["methods"]["sound_buzzer"].pop()
    del broken["sbot.marker.Position"]
    problems = _differences(peer_surface, broken)
    assert any(p.startswith("sbot._motors.Motor.set_power: ") for p in problems)
    assert any(p.startswith("sbot._utils.Utils.sound_buzzer: ") for p in problems)
    assert "sbot.marker.Position: missing" in problems
