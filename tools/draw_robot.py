"""Draw the "Running on the robot" picture as SVG.

It shows the service, the broker, the sticks, the program and the boards, and what
passes between them.

Run ``python tools/draw_robot.py`` after changing it; it writes
``docs/_static/on-the-robot.svg``. ``--check`` only reports whether the committed picture
is up to date.
"""

from __future__ import annotations

import argparse
import sys
from collections.abc import Sequence
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from tools import svg  # noqa: E402 - the helper beside this script, found from the root

OUT = ROOT / "docs" / "_static"
NAME = "on-the-robot.svg"
TITLE = "On the robot: astoria, its broker, the sticks, your program and the boards"

SERVICE, BROKER, PROGRAM, HARDWARE, STICK = "#eef1f5", "#fbe8b5", "#f6c85f", "#d9ead3", "#dde7f7"


def labelled_box(x: float, y: float, w: float, h: float, fill: str, name: str,
                 *details: str) -> list[str]:
    """A box with a bold name and lines of detail below it."""
    parts = [svg.box(x, y, w, h, fill=fill), svg.text(x + 10, y + 19, name, size=13,
                                                      weight="bold")]
    parts += [svg.text(x + 10, y + 35 + 14 * i, d, size=11, fill="#444")
              for i, d in enumerate(details)]
    return parts


def note(x: float, y: float, words: str, anchor: str = "start") -> str:
    """A small label beside an arrow."""
    return svg.text(x, y, words, size=10.5, anchor=anchor, fill="#333")


def draw() -> str:
    """The SVG of the picture."""
    width, height = 900, 540
    body = [svg.arrow_marker(),
            svg.text(width / 2, 28, TITLE, size=16, anchor="middle", weight="bold")]
    # the sticks
    body += labelled_box(40, 70, 200, 62, STICK, "Team's USB stick",
                         "robot.py (the program)", "logs/, saved pictures")
    body += labelled_box(40, 170, 200, 62, STICK, "Competition's stick",
                         "astoria.json: arena, zone,", "mode, game_timeout ...")
    # astoria
    body.append(svg.box(290, 50, 250, 250, fill=SERVICE, stroke="#888"))
    body.append(svg.text(302, 70, "astoria (the robot's service)", size=13, weight="bold"))
    body += labelled_box(305, 85, 220, 44, "white", "astdiskd", "finds the sticks")
    body += labelled_box(305, 150, 220, 44, "white", "astmetad", "the match's metadata")
    body += labelled_box(305, 215, 220, 60, "white", "astprocd",
                         "runs robot.py from the team's", "stick; says where it is")
    # the broker and the web page
    body += labelled_box(620, 70, 220, 62, SERVICE, "Robot's web page",
                         "remote start, camera frames,", "the program's log")
    body += labelled_box(620, 190, 220, 62, BROKER, "Mosquitto (MQTT broker)",
                         "astoria.toml: host, port,", "topic_prefix (\"astoria\")")
    # the program and the boards
    body += labelled_box(290, 350, 550, 70, PROGRAM, "Your program, with j5aio",
                         "j5aio.service (j5aio[robot]): metadata, stick, remote start -> ",
                         "wait_start(); publish_frame() -> the web page")
    body += labelled_box(290, 460, 550, 56, HARDWARE, "The boards (USB)",
                         "power, motor and servo boards, Arduino, camera")
    # what passes between them
    body += [
        svg.line(240, 101, 305, 104, arrow=True),
        svg.line(240, 201, 305, 112, arrow=True),
        note(246, 92, "plugged in"),
        svg.line(525, 180, 620, 212, arrow=True),
        note(545, 172, "astmetad"),
        svg.line(525, 245, 620, 232, arrow=True),
        note(545, 256, "astprocd"),
        svg.line(700, 132, 700, 190, arrow=True),
        note(694, 158, "broadcast/", anchor="end"),
        note(694, 171, "start_button", anchor="end"),
        svg.line(780, 190, 780, 132, arrow=True),
        note(786, 165, "camera/annotated"),
        svg.line(760, 252, 760, 350, arrow=True),
        svg.line(680, 350, 680, 252, arrow=True),
        note(766, 300, "metadata, stick,"),
        note(766, 313, "remote start"),
        note(674, 300, "frames", anchor="end"),
        svg.line(415, 275, 415, 350, arrow=True),
        note(421, 318, "starts robot.py"),
        svg.line(560, 420, 560, 460, arrow=True),
        note(566, 444, "serial and USB requests"),
        svg.line(290, 385, 22, 385, dash="5 4"),
        svg.line(22, 385, 22, 101, dash="5 4"),
        svg.line(22, 101, 40, 101, dash="5 4", arrow=True),
        note(30, 404, "run logs and pictures"),
    ]
    return svg.document(width, height, body, TITLE)


def main(argv: Sequence[str] | None = None) -> int:
    """Write (or with ``--check``, compare) the picture."""
    parser = argparse.ArgumentParser(description=(__doc__ or "").splitlines()[0])
    parser.add_argument("--check", action="store_true", help="fail if the picture is stale")
    parser.add_argument("--output", type=Path, default=OUT, help="the folder to write to")
    options = parser.parse_args(argv)
    path = options.output / NAME
    picture = draw()
    if options.check:
        if not path.is_file() or path.read_text(encoding="utf-8") != picture:
            print(f"{path} is stale: run python tools/draw_robot.py", file=sys.stderr)
            return 1
        return 0
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(picture, encoding="utf-8")
    print(f"wrote {path}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
