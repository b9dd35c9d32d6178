"""Finding the code blocks of README.md and docs/*.rst, for the tests that run them."""

from __future__ import annotations

import re
import textwrap
from dataclasses import dataclass
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
README = ROOT / "README.md"
DOCS = ROOT / "docs"

#: The Markdown line that marks the next fenced block as a fragment, on purpose.
MARKDOWN_FRAGMENT = "<!-- fragment -->"
#: The reStructuredText option that marks a ``code-block`` as a fragment, on purpose.
RST_FRAGMENT = ":class: fragment"


@dataclass(frozen=True)
class Snippet:
    """One code block: where it is, its language, its text, and whether it is a fragment."""

    path: Path
    line: int
    language: str
    code: str
    fragment: bool

    @property
    def name(self) -> str:
        """A test id: file and line."""
        return f"{self.path.relative_to(ROOT)}:{self.line}"


_FENCE = re.compile(r"^```(\w*)\s*$")


def markdown_snippets(path: Path) -> list[Snippet]:
    """The fenced blocks of a Markdown file."""
    lines = path.read_text(encoding="utf-8").splitlines()
    found: list[Snippet] = []
    index = 0
    while index < len(lines):
        match = _FENCE.match(lines[index])
        if match is None:
            index += 1
            continue
        start = index
        index += 1
        body: list[str] = []
        while index < len(lines) and not lines[index].startswith("```"):
            body.append(lines[index])
            index += 1
        index += 1
        previous = next((x.strip() for x in reversed(lines[:start]) if x.strip()), "")
        found.append(Snippet(
            path, start + 1, match.group(1) or "text", "\n".join(body) + "\n",
            previous == MARKDOWN_FRAGMENT,
        ))
    return found


_DIRECTIVE = re.compile(r"^(\s*)\.\. code-block::\s*(\w+)\s*$")


def _indented_body(lines: list[str], index: int, indent: int) -> tuple[list[str], int]:
    """The block indented deeper than ``indent`` from ``index`` (leading blanks skipped)."""
    body: list[str] = []
    while index < len(lines):
        line = lines[index]
        if line.strip() and len(line) - len(line.lstrip()) <= indent:
            break
        body.append(line)
        index += 1
    while body and not body[-1].strip():
        body.pop()
    while body and not body[0].strip():
        body.pop(0)
    return body, index


def rst_snippets(path: Path) -> list[Snippet]:
    """The ``code-block`` directives and ``::`` literal blocks of a reStructuredText file."""
    lines = path.read_text(encoding="utf-8").splitlines()
    found: list[Snippet] = []
    index = 0
    while index < len(lines):
        line = lines[index]
        directive = _DIRECTIVE.match(line)
        if directive is not None:
            indent = len(directive.group(1))
            start = index
            index += 1
            options: list[str] = []
            while index < len(lines) and lines[index].strip().startswith(":"):
                options.append(lines[index].strip())
                index += 1
            body, index = _indented_body(lines, index, indent)
            found.append(Snippet(
                path, start + 1, directive.group(2),
                textwrap.dedent("\n".join(body)) + "\n", RST_FRAGMENT in options,
            ))
            continue
        if line.rstrip().endswith("::") and not line.lstrip().startswith(".."):
            indent = len(line) - len(line.lstrip())
            start = index
            body, index = _indented_body(lines, index + 1, indent)
            found.append(Snippet(
                path, start + 1, "literal", textwrap.dedent("\n".join(body)) + "\n", False,
            ))
            continue
        index += 1
    return found


def all_snippets() -> list[Snippet]:
    """Every code block of README.md and of the pages under docs/."""
    found = markdown_snippets(README)
    for page in sorted(DOCS.rglob("*.rst")):
        found += rst_snippets(page)
    return found
