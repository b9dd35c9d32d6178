"""A few helpers for writing SVG by hand: the docs' pictures need nothing to be installed."""

from __future__ import annotations

from html import escape

FONT = "font-family='DejaVu Sans, Helvetica, Arial, sans-serif'"


def document(width: float, height: float, body: list[str], title: str) -> str:
    """A whole SVG document of ``width`` x ``height`` holding the ``body`` elements."""
    return "\n".join([
        "<?xml version='1.0' encoding='utf-8'?>",
        f"<svg xmlns='http://www.w3.org/2000/svg' width='{width:g}' height='{height:g}' "
        f"viewBox='0 0 {width:g} {height:g}' role='img'>",
        f"<title>{escape(title)}</title>",
        f"<rect width='{width:g}' height='{height:g}' fill='white'/>",
        *body,
        "</svg>",
        "",
    ])


def text(x: float, y: float, words: str, *, size: float = 13, anchor: str = "start",
         weight: str = "normal", fill: str = "#222") -> str:
    """A line of text whose baseline starts (or is centred, or ends) at ``x``, ``y``."""
    return (
        f"<text x='{x:.1f}' y='{y:.1f}' {FONT} font-size='{size:g}' text-anchor='{anchor}' "
        f"font-weight='{weight}' fill='{fill}'>{escape(words)}</text>"
    )


def box(x: float, y: float, width: float, height: float, *, fill: str, stroke: str = "#444",
        radius: float = 6) -> str:
    """A rounded rectangle."""
    return (
        f"<rect x='{x:.1f}' y='{y:.1f}' width='{width:.1f}' height='{height:.1f}' "
        f"rx='{radius:g}' fill='{fill}' stroke='{stroke}' stroke-width='1.5'/>"
    )


def line(x1: float, y1: float, x2: float, y2: float, *, stroke: str = "#444",
         width: float = 1.5, dash: str | None = None, arrow: bool = False) -> str:
    """A straight line, optionally dashed and ending in the arrowhead of :func:`arrow_marker`."""
    extra = f" stroke-dasharray='{dash}'" if dash else ""
    extra += " marker-end='url(#arrow)'" if arrow else ""
    return (
        f"<line x1='{x1:.1f}' y1='{y1:.1f}' x2='{x2:.1f}' y2='{y2:.1f}' stroke='{stroke}' "
        f"stroke-width='{width:g}'{extra}/>"
    )


def polyline(points: list[tuple[float, float]], *, stroke: str, width: float = 2) -> str:
    """A line through ``points``."""
    coordinates = " ".join(f"{x:.1f},{y:.1f}" for x, y in points)
    return (
        f"<polyline points='{coordinates}' fill='none' stroke='{stroke}' "
        f"stroke-width='{width:g}' stroke-linejoin='round'/>"
    )


def arrow_marker() -> str:
    """The arrowhead that :func:`line` draws with ``arrow=True``."""
    return (
        "<defs><marker id='arrow' viewBox='0 0 10 10' refX='9' refY='5' markerWidth='7' "
        "markerHeight='7' orient='auto-start-reverse'><path d='M 0 0 L 10 5 L 0 10 z' "
        "fill='#444'/></marker></defs>"
    )
