"""Draw the docs' layer diagrams as SVG: one per reader, each marking the layers they use.

Run ``python tools/draw_layers.py`` after changing the layers; it writes
``docs/_static/layers-<reader>.svg`` for the student, the team and the volunteer, and
``layers-overview.svg`` for the concepts page.
``--check`` only reports whether the committed pictures are up to date.
"""

from __future__ import annotations

import argparse
import sys
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from tools import svg  # noqa: E402 - the helper beside this script, found from the root

OUT = ROOT / "docs" / "_static"


@dataclass(frozen=True)
class Layer:
    """One row of the diagram."""

    key: str
    name: str
    detail: str


LAYERS = (
    Layer("code", "Your program", "plain code, or coroutines and tasks"),
    Layer("face", "j5aio.sync  |  j5aio", "the blocking face, generated  |  the async core"),
    Layer("robot", "KitRobot / BaseRobot", "finds the boards; makes them safe however it ends"),
    Layer("group", "BoardGroup -> Board", "boards by position or serial number"),
    Layer("component", "Component", "Motor, LED, GPIOPin ...: checks what it is asked"),
    Layer("interface", "Interface", "the coroutines a component needs from a backend"),
    Layer("backend", "Backend", "console | hardware | simulated"),
    Layer("transport", "Transport", "serial link | USB link | in-memory stream"),
    Layer("far", "Board or simulator", "the same bytes on the wire either way"),
)

#: Per reader: the title, and the layers they write (strong) or meet (light).
READERS: dict[str, tuple[str, set[str], set[str]]] = {
    "overview": ("The layers of j5aio: requests flow down, results flow back up", set(), set()),
    "student": ("A first-time student's view", {"code"}, {"face", "robot", "component"}),
    "team": (
        "A team's view: several behaviours at once",
        {"code"},
        {"face", "robot", "group", "component"},
    ),
    "volunteer": (
        "A volunteer's view: a backend for their own board",
        {"backend", "interface"},
        {"component", "transport", "far"},
    ),
}

STRONG, LIGHT, PLAIN = "#f6c85f", "#fbe8b5", "#eef1f5"


def draw(reader: str) -> str:
    """The SVG of ``reader``'s diagram."""
    title, writes, meets = READERS[reader]
    width, row, gap, left = 640, 44, 14, 40
    body = [svg.arrow_marker(), svg.text(width / 2, 30, title, size=17, anchor="middle",
                                         weight="bold")]
    top = 50
    for index, layer in enumerate(LAYERS):
        y = top + index * (row + gap)
        fill = STRONG if layer.key in writes else LIGHT if layer.key in meets else PLAIN
        body.append(svg.box(left, y, width - 2 * left - 120, row, fill=fill))
        body.append(svg.text(left + 14, y + 19, layer.name, size=14, weight="bold"))
        body.append(svg.text(left + 14, y + 36, layer.detail, size=12, fill="#444"))
        if index:
            body.append(svg.line(width / 2 - 60, y - gap, width / 2 - 60, y, arrow=True))
    legend_x = width - 150
    legend = () if not (writes or meets) else ((STRONG, "you write this"),
                                               (LIGHT, "you use this"),
                                               (PLAIN, "works for you"))
    for offset, (fill, words) in enumerate(legend):
        y = top + offset * 26
        body.append(svg.box(legend_x, y, 18, 18, fill=fill, radius=3))
        body.append(svg.text(legend_x + 26, y + 14, words, size=12))
    height = top + len(LAYERS) * (row + gap) + 10
    return svg.document(width, height, body, title)


def main(argv: Sequence[str] | None = None) -> int:
    """Write (or with ``--check``, compare) every reader's diagram."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--check", action="store_true", help="fail if a picture is stale")
    parser.add_argument("--output", type=Path, default=OUT, help="the folder to write to")
    options = parser.parse_args(argv)
    stale = []
    for reader in READERS:
        path = options.output / f"layers-{reader}.svg"
        picture = draw(reader)
        if options.check:
            if not path.is_file() or path.read_text(encoding="utf-8") != picture:
                stale.append(path)
            continue
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(picture, encoding="utf-8")
        print(f"wrote {path}")
    for path in stale:
        print(f"{path} is stale: run python tools/draw_layers.py", file=sys.stderr)
    return 1 if stale else 0


if __name__ == "__main__":
    raise SystemExit(main())
